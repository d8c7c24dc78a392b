#pragma once
// Image files, format chosen by extension: .png .jpg/.jpeg .ppm (8-bit; sRGB unless linear),
// .pfm .exr (linear float HDR). Writing goes to a temporary file beside the target that is
// renamed over it only when complete, so an existing image is never left half-written.

#include <filesystem>
#include <string>

#include "strahl/image/image.h"

namespace strahl {

struct WriteOptions {
  bool linear = false;  // 8-bit formats store linear values instead of sRGB (POV-Ray's File_Gamma=1.0)
};

// True for the extensions write_image understands (case-insensitive).
bool is_supported_image_extension(const std::filesystem::path& path);

// Checks, before any work is done, that write_image could write `path`: a known extension, an
// existing directory in which a file can be created (tried with a temporary file, removed at
// once), and no directory or non-regular file (a device such as /dev/null) at `path` itself,
// which the final rename would replace. Throws strahl::Error naming the problem.
void check_output_path(const std::filesystem::path& path);

// Throws strahl::Error on an unknown extension or a failed write.
void write_image(const Image& image, const std::filesystem::path& path, const WriteOptions& options = {});

// Reads .png (8 or 16 bit), .jpg, .ppm, .pfm and .exr; 8/16-bit values are taken as they are
// stored (no sRGB decoding), divided by 255 or 65535. Throws strahl::Error.
Image read_image(const std::filesystem::path& path);

// 8-bit encodings.
float linear_to_srgb(float linear);
unsigned char to_byte(float value);

}  // namespace strahl
