#pragma once
// Every file a run writes: the image (rewritten by checkpoints too) and one EXR per AOV,
// `<output without extension>.<name>.exr`. All are checked before the scene is loaded, so that a
// run which could not save its work fails at once (docs/cli.md, "The output paths are checked first").

#include <filesystem>
#include <string>
#include <vector>

#include "options.h"

namespace strahl::cli {

// The AOV image `name` beside `output`.
std::filesystem::path aov_path(const std::string& output, const std::string& name);

// Throws strahl::Error for the first of the run's output paths that cannot be written.
void check_outputs(const Options& options, const std::string& output);

}  // namespace strahl::cli
