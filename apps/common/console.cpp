#include "console.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>

namespace strahl::console {

namespace {
std::atomic<bool> g_lost[2] = {false, false};  // stdout, stderr
}

void write(Stream stream, std::string_view text) noexcept {
  const int fd = stream == Stream::out ? STDOUT_FILENO : STDERR_FILENO;
  const int saved_errno = errno;  // a caller may be about to report its own errno
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {  // closed, full or broken: the message is lost, the work goes on
      g_lost[stream == Stream::out ? 0 : 1].store(true, std::memory_order_relaxed);
      break;
    }
    text.remove_prefix(std::size_t(n));
  }
  errno = saved_errno;
}

bool lost(Stream stream) noexcept { return g_lost[stream == Stream::out ? 0 : 1].load(std::memory_order_relaxed); }

void protect_streams() noexcept {
  struct sigaction sa {};
  sa.sa_handler = SIG_IGN;
  sigemptyset(&sa.sa_mask);
  ::sigaction(SIGPIPE, &sa, nullptr);
  for (int fd = 0; fd <= 2; ++fd) {
    if (::fcntl(fd, F_GETFD) != -1 || errno != EBADF) continue;
    // open() returns the lowest free number, which is `fd` itself while the lower ones are open.
    const int null = ::open("/dev/null", fd == 0 ? O_RDONLY : O_WRONLY);
    if (null >= 0 && null != fd) ::close(null);
  }
}

}  // namespace strahl::console
