#include "progress.h"

#include <unistd.h>

#include "console.h"

namespace strahl::cli {

Progress::Progress(bool enabled)
    : enabled_(enabled), terminal_(::isatty(STDERR_FILENO) == 1), start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

void Progress::update(long done, long total) {
  if (!enabled_ || total <= 0) return;
  std::unique_lock lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;  // another thread is reporting; skip rather than wait
  const auto now = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double fraction = double(done) / double(total);
  const double eta = fraction > 0 ? elapsed * (1 - fraction) / fraction : 0;
  if (terminal_) {
    if (done < total && now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    constexpr int kWidth = 40;
    const int filled = int(fraction * kWidth);
    std::string bar(std::size_t(filled), '=');
    bar.resize(kWidth, ' ');
    strahl::console::err("\r[{}] {:5.1f}%  {:.1f} s elapsed, ETA {:.1f} s ", bar, 100 * fraction, elapsed, eta);
  } else {
    const int decile = int(fraction * 10);
    if (decile <= last_decile_) return;
    last_decile_ = decile;
    strahl::console::err("rendering: {:3d}%  {:.1f} s elapsed, ETA {:.1f} s\n", decile * 10, elapsed, eta);
  }
}

void Progress::finish() {
  std::lock_guard lock(mutex_);
  if (!enabled_) return;
  // Updates skipped while another thread held the lock may include the last one: end at 100%.
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (terminal_) {
    strahl::console::err("\r[{}] 100.0%  {:.1f} s elapsed, ETA 0.0 s \n", std::string(40, '='), elapsed);
  } else if (last_decile_ < 10) {
    strahl::console::err("rendering: 100%  {:.1f} s elapsed, ETA 0.0 s\n", elapsed);
  }
}

}  // namespace strahl::cli
