#include "outputs.h"

#include "strahl/image/image_io.h"

namespace strahl::cli {

std::filesystem::path aov_path(const std::string& output, const std::string& name) {
  std::filesystem::path path(output);
  path.replace_extension("." + name + ".exr");
  return path;
}

void check_outputs(const Options& options, const std::string& output) {
  check_output_path(output);
  for (const std::string& name : options.aov) check_output_path(aov_path(output, name));
}

}  // namespace strahl::cli
