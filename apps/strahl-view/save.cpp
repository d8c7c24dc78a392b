#include "save.h"

#include <unistd.h>

#include <cerrno>
#include <fmt/format.h>

#include "strahl/util/error.h"
#include "strahl/util/system_error.h"

namespace strahl::view {

namespace fs = std::filesystem;

fs::path numbered_name(const fs::path& base, int n) {
  return base.parent_path() / fmt::format("{}-{:04}{}", base.stem().string(), n, base.extension().string());
}

fs::path save_numbered(const Image& image, const fs::path& base, const WriteOptions& options) {
  constexpr int kMaxNumber = 99999;
  const fs::path temporary =
      base.parent_path() / fmt::format(".{}.saving-{}{}", base.stem().string(), ::getpid(), base.extension().string());
  write_image(image, temporary, options);  // itself written safely (a temporary file and a rename)
  struct Remove {
    const fs::path& path;
    ~Remove() { ::unlink(path.c_str()); }
  } remove{temporary};
  for (int n = 1; n <= kMaxNumber; ++n) {
    const fs::path target = numbered_name(base, n);
    std::error_code ec;
    if (fs::exists(fs::symlink_status(target, ec))) continue;
    if (::link(temporary.c_str(), target.c_str()) == 0) return target;
    if (errno != EEXIST) throw Error(target.string() + ": cannot save the image: " + system_reason(errno));
  }
  throw Error(base.string() + ": cannot save the image: every name up to " + numbered_name(base, kMaxNumber).string() +
              " is taken");
}

}  // namespace strahl::view
