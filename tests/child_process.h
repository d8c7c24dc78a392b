#pragma once
// Runs a program as a child process for the CLI tests: fork/exec with a working directory, stdout
// and stderr captured through pipes (or closed, full or broken, see Streams), signals sent while
// it runs, a wall-clock limit after which it is killed, and the CPU time it used (from wait4).

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace strahl::test {

struct ChildResult {
  int exit_code = -1;      // the exit status; −1 when it did not exit normally
  int term_signal = 0;     // the signal that ended it, if one did
  bool timed_out = false;  // killed by us after the time limit
  double cpu_seconds = 0;  // user + system time
  long max_rss_kib = 0;    // peak resident memory (ru_maxrss)
  std::string out, err;
};

// What the child's stdout and stderr are: a pipe the test reads (captured), closed (2>&-),
// /dev/full (every write fails with ENOSPC) or a pipe whose reader is gone before the child
// starts (every write fails with EPIPE, or raises SIGPIPE).
enum class Stream { captured, closed, full, broken_pipe };
struct Streams {
  Stream out = Stream::captured, err = Stream::captured;
};

class ChildProcess {
 public:
  // argv[0] is the program's path. `cwd` empty: the test's own directory.
  explicit ChildProcess(const std::vector<std::string>& argv, const std::filesystem::path& cwd = {},
                        Streams streams = {}) {
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    const std::string dir = cwd.string();
    int out[2], err[2];
    if (::pipe2(out, O_CLOEXEC) != 0 || ::pipe2(err, O_CLOEXEC) != 0) throw std::runtime_error("pipe failed");
    const int full = ::open("/dev/full", O_WRONLY | O_CLOEXEC);
    if (full < 0) throw std::runtime_error("cannot open /dev/full");
    for (auto [mode, fds] : {std::pair{streams.out, out}, std::pair{streams.err, err}})
      if (mode == Stream::broken_pipe) {
        ::close(fds[0]);
        fds[0] = -1;
      }
    start_ = std::chrono::steady_clock::now();
    pid_ = ::fork();
    if (pid_ < 0) throw std::runtime_error("fork failed");
    if (pid_ == 0) {  // the child: only async-signal-safe calls until exec
      const int null = ::open("/dev/null", O_RDONLY);
      if (null >= 0) ::dup2(null, STDIN_FILENO);
      const auto set = [&](Stream mode, int pipe_end, int fd) {
        if (mode == Stream::closed) ::close(fd);
        else ::dup2(mode == Stream::full ? full : pipe_end, fd);
      };
      set(streams.out, out[1], STDOUT_FILENO);
      set(streams.err, err[1], STDERR_FILENO);
      if (!dir.empty() && ::chdir(dir.c_str()) != 0) ::_exit(126);
      ::execv(args[0], args.data());
      ::_exit(127);
    }
    ::close(full);
    ::close(out[1]);
    ::close(err[1]);
    out_fd_ = streams.out == Stream::captured ? out[0] : -1;
    err_fd_ = streams.err == Stream::captured ? err[0] : -1;
    if (streams.out != Stream::captured && out[0] >= 0) ::close(out[0]);
    if (streams.err != Stream::captured && err[0] >= 0) ::close(err[0]);
  }
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    close_fds();
  }

  // Reads output until stderr contains `text` (true) or the child closes it or time runs out.
  bool wait_for_stderr(const std::string& text, double timeout_s) {
    while (result_.err.find(text) == std::string::npos) {
      if (!pump(remaining(timeout_s))) return result_.err.find(text) != std::string::npos;
      if (remaining(timeout_s) <= 0) return result_.err.find(text) != std::string::npos;
    }
    return true;
  }

  void send(int sig) const {
    if (pid_ > 0) ::kill(pid_, sig);
  }

  // Collects all output until the child exits; kills it once `timeout_s` (from the start) is over.
  ChildResult wait(double timeout_s) {
    while (pump(remaining(timeout_s))) {
      if (remaining(timeout_s) <= 0) {
        ::kill(pid_, SIGKILL);
        result_.timed_out = true;
        break;
      }
    }
    int status = 0;
    rusage usage{};
    while (::wait4(pid_, &status, 0, &usage) < 0 && errno == EINTR) {
    }
    pid_ = -1;
    if (!result_.timed_out) {  // whatever is still buffered
      while (pump(0)) {
      }
    }
    close_fds();
    if (WIFEXITED(status)) result_.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) result_.term_signal = WTERMSIG(status);
    result_.max_rss_kib = usage.ru_maxrss;
    result_.cpu_seconds = double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                          1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
    return result_;
  }

 private:
  double remaining(double timeout_s) const {
    return timeout_s - std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

  // Waits up to `seconds` for output and reads what there is; false once both pipes are closed
  // (with neither captured: once the child has exited).
  bool pump(double seconds) {
    pollfd fds[2];
    int n = 0;
    if (out_fd_ >= 0) fds[n++] = {out_fd_, POLLIN, 0};
    if (err_fd_ >= 0) fds[n++] = {err_fd_, POLLIN, 0};
    const int ms = seconds > 0 ? int(seconds * 1000) + 1 : 0;
    if (n == 0) {  // nothing captured: wait for the child to exit (WNOWAIT leaves it to wait())
      if (pid_ <= 0) return false;
      siginfo_t info{};
      if (::waitid(P_PID, id_t(pid_), &info, WEXITED | WNOHANG | WNOWAIT) != 0 || info.si_pid != 0) return false;
      ::poll(nullptr, 0, std::min(ms, 10));
      return true;
    }
    if (::poll(fds, nfds_t(n), ms) <= 0) return true;
    for (int i = 0; i < n; ++i) {
      if (!(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      char buf[4096];
      const ssize_t got = ::read(fds[i].fd, buf, sizeof buf);
      const bool is_out = fds[i].fd == out_fd_;
      if (got > 0) {
        (is_out ? result_.out : result_.err).append(buf, std::size_t(got));
      } else if (got == 0 || errno != EINTR) {
        ::close(fds[i].fd);
        (is_out ? out_fd_ : err_fd_) = -1;
      }
    }
    return out_fd_ >= 0 || err_fd_ >= 0;
  }

  void close_fds() {
    if (out_fd_ >= 0) ::close(out_fd_);
    if (err_fd_ >= 0) ::close(err_fd_);
    out_fd_ = err_fd_ = -1;
  }

  pid_t pid_ = -1;
  int out_fd_ = -1, err_fd_ = -1;
  std::chrono::steady_clock::time_point start_;
  ChildResult result_;
};

// Runs `argv` to the end (or `timeout_s`) and returns what it did.
inline ChildResult run_child(const std::vector<std::string>& argv, const std::filesystem::path& cwd = {},
                             double timeout_s = 30, Streams streams = {}) {
  ChildProcess child(argv, cwd, streams);
  return child.wait(timeout_s);
}

}  // namespace strahl::test
