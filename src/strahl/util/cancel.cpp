#include "strahl/util/cancel.h"

namespace strahl {

namespace {
std::atomic<const std::atomic<bool>*> g_flag{nullptr};
std::atomic<CancelHook> g_hook{nullptr};
}  // namespace

void set_cancel_flag(const std::atomic<bool>* flag) { g_flag.store(flag, std::memory_order_relaxed); }

void set_cancel_hook(CancelHook hook) { g_hook.store(hook, std::memory_order_relaxed); }

void check_cancelled(const char* stage) {
  if (const CancelHook hook = g_hook.load(std::memory_order_relaxed)) hook(stage);
  const std::atomic<bool>* flag = g_flag.load(std::memory_order_relaxed);
  if (flag && flag->load(std::memory_order_relaxed)) throw Cancelled();
}

}  // namespace strahl
