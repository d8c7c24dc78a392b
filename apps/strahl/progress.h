#pragma once
// Progress of a render on stderr: a redrawn bar with elapsed time and ETA on a terminal,
// a plain line every 10% otherwise (logs, CI). Thread-safe; called once per finished tile.

#include <chrono>
#include <mutex>

namespace strahl::cli {

class Progress {
 public:
  explicit Progress(bool enabled);
  void update(long done, long total);
  void finish();

 private:
  bool enabled_;
  bool terminal_;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_, last_draw_;
  int last_decile_ = 0;  // the first line comes at 10%
};

}  // namespace strahl::cli
