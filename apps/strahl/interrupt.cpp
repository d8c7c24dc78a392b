#include "interrupt.h"

#include <signal.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>

#include "console.h"
#include "strahl/image/output_file.h"
#include "strahl/util/cancel.h"

namespace strahl::cli {

namespace {
std::atomic<bool> g_interrupted{false};
std::atomic<int> g_signal{0};
static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free,
              "only lock-free atomics may be touched in a signal handler");

// The first signal sets the flag. A second one ends the process at once, as its default action
// would, after removing the temporary files of images being written (async-signal-safe: unlink
// on a fixed table), so no stray file is left beside the outputs.
extern "C" void on_signal(int sig) {
  if (g_interrupted.load(std::memory_order_relaxed)) {
    remove_unfinished_outputs();
    ::signal(sig, SIG_DFL);
    ::raise(sig);
    return;
  }
  g_signal.store(sig, std::memory_order_relaxed);
  g_interrupted.store(true, std::memory_order_relaxed);
}

std::atomic<bool> g_held{false};
}  // namespace

const std::atomic<bool>* install_interrupt_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  sigaction(SIGHUP, &sa, nullptr);  // the terminal went away: like SIGTERM
  // Past a file-size limit (ulimit -f) a write fails with EFBIG, reported like any failed write,
  // instead of SIGXFSZ ending the process with a temporary file left behind.
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  sigaction(SIGXFSZ, &ignore, nullptr);
  set_cancel_flag(&g_interrupted);
  if (std::getenv("STRAHL_TEST_HOLD")) set_cancel_hook(hold_for_test);
  return &g_interrupted;
}

int interrupt_signal() { return g_signal.load(std::memory_order_relaxed); }

const char* interrupt_signal_name() {
  switch (interrupt_signal()) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    default: return "signal";
  }
}

void hold_for_test(const char* stage) {
  const char* env = std::getenv("STRAHL_TEST_HOLD");
  if (!env) return;
  const std::string spec = env;
  const std::size_t colon = spec.find(':');
  if (spec.substr(0, colon) != stage || g_held.exchange(true)) return;
  const double seconds = colon == std::string::npos ? 10.0 : std::atof(spec.c_str() + colon + 1);
  console::err("strahl: holding at {}\n", stage);
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (!g_interrupted.load(std::memory_order_relaxed) && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

}  // namespace strahl::cli
