#pragma once
// A file written safely, for the image writers: created exclusively under a temporary name beside
// the target (`<target>.tmp-<pid>-<8 hex digits>`, so that nothing else is ever overwritten),
// every write checked, and renamed over the target only once it is complete and closed without
// an error. On any failure, or when destroyed before commit(), the temporary file is removed, so
// the target is never left half-written. Errors name the target and the reason from errno.
// A target that is a symbolic link is followed (output_destination): the file it points to is
// written, and the link stays.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace strahl {

class OutputFile {
 public:
  // Creates the temporary file. Throws strahl::Error ("<target>: cannot write the image: <reason>").
  explicit OutputFile(const std::filesystem::path& target);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  // Buffered writes. They never throw (C callers such as stb cannot pass an exception on): the
  // first failure is kept, later writes are skipped, and commit() reports it.
  void write(const void* data, std::size_t size) noexcept;
  void seek(std::uint64_t position) noexcept;
  std::uint64_t tell() const noexcept { return position_; }
  const std::filesystem::path& temporary_path() const noexcept { return temporary_; }

  // Flushes, closes and renames over the target. Throws strahl::Error on any failure so far.
  void commit();

  // The temporary name for `target`; `serial` distinguishes the files of one process.
  static std::filesystem::path temporary_name(const std::filesystem::path& target, std::uint32_t serial);

  // The file that writing `target` replaces: `target` itself, or where its symbolic links lead
  // (each relative to the link's directory; a link to a name that does not exist yet leads to a
  // new file there). Throws strahl::Error after 40 links (a loop), as the system does.
  static std::filesystem::path output_destination(const std::filesystem::path& target);

 private:
  void flush() noexcept;
  void fail(int error) noexcept;
  [[noreturn]] void throw_error(int error) const;
  void discard() noexcept;

  std::filesystem::path target_, destination_, temporary_;
  int fd_ = -1;
  bool temporary_exists_ = false;
  int error_ = 0;  // the first errno, 0 while all is well
  int slot_ = -1;  // in the table remove_unfinished_outputs() reads
  std::uint64_t position_ = 0;
  std::vector<char> buffer_;
};

// Removes every temporary file that an OutputFile is writing at this moment. Async-signal-safe
// (unlink(2) on names kept in a fixed table): for a signal handler that ends the process at once.
void remove_unfinished_outputs() noexcept;

}  // namespace strahl
