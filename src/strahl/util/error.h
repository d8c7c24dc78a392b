#pragma once
// Errors of orchestration code (loading, compiling, writing). Kernel code never throws.
// Every scene error names where it is: "file:line:column: message".

#include <stdexcept>
#include <string>

namespace strahl {

struct FileLoc {
  std::string file;
  int line = 0;    // 1-based; 0 = unknown
  int column = 0;  // 1-based; 0 = unknown

  std::string str() const {
    if (file.empty()) return {};
    if (line <= 0) return file;
    return file + ":" + std::to_string(line) + (column > 0 ? ":" + std::to_string(column) : "");
  }
};

// A bad scene (file or API) or a failed read/write: the user's input, not a bug. Exit code 2.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
  Error(const FileLoc& loc, const std::string& message)
      : std::runtime_error(loc.file.empty() ? message : loc.str() + ": " + message), loc_(loc) {}
  const FileLoc& loc() const { return loc_; }

 private:
  FileLoc loc_;
};

}  // namespace strahl
