#include "strahl/image/output_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <system_error>

#include "strahl/util/error.h"
#include "strahl/util/system_error.h"

namespace strahl {
namespace fs = std::filesystem;

namespace {

constexpr std::size_t kBufferSize = 1 << 16;

// The names of the temporary files being written, for remove_unfinished_outputs(). A slot is
// claimed (free → writing the name), published (→ in use) and released (→ free) with atomics;
// a signal handler reads only published names. Eight slots: the CLI writes one file at a time
// (the image, a checkpoint, an AOV); files beyond eight are simply not in the table.
constexpr int kSlots = 8;
constexpr std::size_t kNameSize = 4096;
enum SlotState : int { kFree, kFilling, kInUse };
std::atomic<int> g_state[kSlots];
char g_names[kSlots][kNameSize];

int claim_slot(const std::string& name) noexcept {
  if (name.size() >= kNameSize) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (!g_state[i].compare_exchange_strong(expected, kFilling)) continue;
    std::memcpy(g_names[i], name.c_str(), name.size() + 1);
    g_state[i].store(kInUse, std::memory_order_release);
    return i;
  }
  return -1;
}

void release_slot(int slot) noexcept {
  if (slot >= 0) g_state[slot].store(kFree, std::memory_order_release);
}

}  // namespace

void remove_unfinished_outputs() noexcept {
  for (int i = 0; i < kSlots; ++i)
    if (g_state[i].load(std::memory_order_acquire) == kInUse) ::unlink(g_names[i]);
}

fs::path OutputFile::temporary_name(const fs::path& target, std::uint32_t serial) {
  char suffix[32];
  std::snprintf(suffix, sizeof suffix, ".tmp-%ld-%08x", long(::getpid()), unsigned(serial));
  fs::path name = target;
  name += suffix;
  return name;
}

fs::path OutputFile::output_destination(const fs::path& target) {
  fs::path path = target;
  for (int links = 0; links <= 40; ++links) {
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(path, ec)) || ec) return path;
    const fs::path link = fs::read_symlink(path, ec);
    if (ec) return path;  // (the write itself then names the reason)
    path = link.is_absolute() ? link : path.parent_path() / link;
  }
  throw Error(target.string() + ": cannot write the image: " + system_reason(ELOOP));
}

OutputFile::OutputFile(const fs::path& target) : target_(target), destination_(output_destination(target)) {
  static std::atomic<std::uint32_t> serial{0};
  for (int attempt = 0; fd_ < 0; ++attempt) {
    temporary_ = temporary_name(destination_, serial++);
    slot_ = claim_slot(temporary_.string());
    fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd_ >= 0) {
      temporary_exists_ = true;
      break;
    }
    const int error = errno;
    release_slot(slot_);
    slot_ = -1;
    if (error != EEXIST || attempt > 100) throw_error(error);  // EEXIST: a stale file of an earlier process
  }
  buffer_.reserve(kBufferSize);
}

OutputFile::~OutputFile() { discard(); }

void OutputFile::fail(int error) noexcept {
  if (error_ == 0) error_ = error != 0 ? error : EIO;
}

void OutputFile::flush() noexcept {
  const char* p = buffer_.data();
  std::size_t left = buffer_.size();
  while (left > 0 && error_ == 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      fail(n < 0 ? errno : ENOSPC);
      break;
    }
    p += n;
    left -= std::size_t(n);
  }
  buffer_.clear();
}

void OutputFile::write(const void* data, std::size_t size) noexcept {
  if (error_ != 0) return;
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const std::size_t room = kBufferSize - buffer_.size();
    const std::size_t take = std::min(room, size);
    buffer_.insert(buffer_.end(), p, p + take);
    p += take;
    size -= take;
    position_ += take;
    if (buffer_.size() == kBufferSize) flush();
    if (error_ != 0) return;
  }
}

void OutputFile::seek(std::uint64_t position) noexcept {
  flush();
  if (error_ != 0) return;
  if (::lseek(fd_, off_t(position), SEEK_SET) < 0) return fail(errno);
  position_ = position;
}

void OutputFile::commit() {
  flush();
  if (error_ != 0) throw_error(error_);
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) throw_error(errno);  // NFS and quotas report failed writes here
  if (::rename(temporary_.c_str(), destination_.c_str()) != 0) throw_error(errno);
  temporary_exists_ = false;
  release_slot(slot_);
  slot_ = -1;
}

void OutputFile::discard() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (temporary_exists_) ::unlink(temporary_.c_str());
  temporary_exists_ = false;
  release_slot(slot_);
  slot_ = -1;
}

void OutputFile::throw_error(int error) const {
  throw Error(target_.string() + ": cannot write the image: " + system_reason(error));
}

}  // namespace strahl
