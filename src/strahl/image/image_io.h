#pragma once
// Image files, format chosen by extension: .png .jpg/.jpeg .ppm (8-bit; sRGB unless linear),
// .pfm .exr (linear float HDR). Writing goes to a temporary file beside the target that is
// renamed over it only when complete (image/output_file.h), so an existing image is never left
// half-written.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "strahl/image/image.h"

namespace strahl {

struct WriteOptions {
  bool linear = false;  // 8-bit formats store linear values instead of sRGB (POV-Ray's File_Gamma=1.0)
};

// True for the extensions write_image understands (case-insensitive).
bool is_supported_image_extension(const std::filesystem::path& path);

// Checks, before any work is done, that write_image could write `path`: a known extension, an
// existing directory in which a file can be created (tried with the very temporary name the
// image will be written under, removed at once), and no directory or non-regular file (a FIFO,
// a device such as /dev/null) at `path` itself, which the final rename would replace. Where `path`
// is a symbolic link, all this holds for the file it leads to, which is what is written. Throws
// strahl::Error naming the problem and, for a failed system call, its reason (errno).
void check_output_path(const std::filesystem::path& path);

// Checks that the format of `path` can hold a width × height image that reads back with the
// same size (docs/cli.md, "Output formats"): JPEG at most 65535 pixels per side; PNG, PPM and
// PFM at most 2^24 (what the readers accept), PNG at most 2^30 bytes of rows, PPM less than 2^31
// bytes of pixels; EXR any. Throws strahl::Error naming the limit.
void check_image_size(const std::filesystem::path& path, int width, int height);

// Throws strahl::Error on an unknown extension, a size the format cannot hold
// (check_image_size) or a failed write, naming the reason (errno).
void write_image(const Image& image, const std::filesystem::path& path, const WriteOptions& options = {});

// Reads .png (8 or 16 bit), .jpg, .ppm, .pfm and .exr; 8/16-bit values are taken as they are
// stored (no sRGB decoding), divided by 255 or 65535. Throws strahl::Error.
Image read_image(const std::filesystem::path& path);

// A PNG or JPEG (or another format stb_image reads) from its bytes in memory, as read_image reads
// it; `name` stands for it in messages. At most kMaxDecodedPixels pixels (checked before
// decoding). Throws strahl::Error.
inline constexpr std::int64_t kMaxDecodedPixels = std::int64_t(1) << 26;  // 8192 x 8192
Image decode_image(std::string_view bytes, const std::string& name);

// 8-bit encodings.
float linear_to_srgb(float linear);
unsigned char to_byte(float value);

}  // namespace strahl
