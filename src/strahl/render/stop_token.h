#pragma once
// What a back end asks between camera samples: should rendering stop? Two relaxed atomic loads —
// cheap enough for every sample, so a cancel (a signal, the viewer moving on, Ctrl-C in Python)
// or the time limit takes effect within one sample's time, even inside one pixel. The integrator's
// ray budget (TraceSettings) bounds that time.

#include <atomic>

namespace strahl {

class StopToken {
 public:
  explicit StopToken(const std::atomic<bool>* external = nullptr) : external_(external) {}
  StopToken(const StopToken&) = delete;
  StopToken& operator=(const StopToken&) = delete;

  bool requested() const {
    return stop_.load(std::memory_order_relaxed) || (external_ && external_->load(std::memory_order_relaxed));
  }
  void request() { stop_.store(true, std::memory_order_relaxed); }
  // The flag set from outside (a signal handler), if any, was set.
  bool external_requested() const { return external_ && external_->load(std::memory_order_relaxed); }

 private:
  std::atomic<bool> stop_{false};
  const std::atomic<bool>* external_;
};

}  // namespace strahl
