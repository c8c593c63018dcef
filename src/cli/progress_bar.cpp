#include "cli/progress_bar.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace periflex {

bool stderr_is_terminal() { return isatty(STDERR_FILENO) == 1; }

ProgressBar::ProgressBar(double end_time, bool enabled)
    : end_time_(end_time), enabled_(enabled), start_(Clock::now()), last_draw_(start_) {}

void ProgressBar::update(double time, long steps, const std::string& extra) {
  if (!enabled_) return;
  const auto now = Clock::now();
  if (drawn_ && now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  drawn_ = true;

  const double fraction = end_time_ > 0 ? std::clamp(time / end_time_, 0.0, 1.0) : 1.0;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double eta = fraction > 1e-9 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  constexpr int kWidth = 30;
  const int filled = static_cast<int>(fraction * kWidth);
  std::string bar(filled, '#');
  bar.append(kWidth - filled, '.');
  std::fprintf(stderr, "\r[%s] %5.1f%%  t = %.4g / %.4g s  %.0f steps/s  ETA %.0f s %s\033[K", bar.c_str(),
               100.0 * fraction, time, end_time_, elapsed > 0 ? steps / elapsed : 0.0, eta, extra.c_str());
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (enabled_ && drawn_) std::fprintf(stderr, "\r\033[K");
}

}  // namespace periflex
