#pragma once
// Saving what the viewer shows without ever overwriting a file: <stem>-0001<ext>,
// <stem>-0002<ext>, … beside the base path (-o, or <scene>.png), the first free number.

#include <filesystem>

#include "strahl/image/image.h"
#include "strahl/image/image_io.h"

namespace strahl::view {

// Writes `image` with the usual writers (the format follows base's extension) under a temporary
// name, then links it to the first free numbered name: link(2) fails rather than replace a file
// that appeared meanwhile, so nothing is ever overwritten and no file is ever half-written.
// Returns the name. Throws strahl::Error (naming the reason) when it cannot.
std::filesystem::path save_numbered(const Image& image, const std::filesystem::path& base, const WriteOptions& options);

// The n-th numbered name for `base`.
std::filesystem::path numbered_name(const std::filesystem::path& base, int n);

}  // namespace strahl::view
