#pragma once
// The progress bar of the commands that take a while (`rigid run`, `rigid sweep`): one line on
// standard error, redrawn at most ten times a second, shown only when standard error is a
// terminal and the work has taken more than half a second, with the elapsed time and an
// estimate of the time left (elapsed · (1 − f) / f, the rate so far held constant).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

namespace rigid::cli {

class ProgressBar {
 public:
  explicit ProgressBar(bool enabled) : enabled_(enabled && isatty(STDERR_FILENO) != 0) {}
  ~ProgressBar() { clear(); }
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// Redraws with the fraction `f` done; `detail()` (a string) is called only when a redraw is due.
  template <class Detail>
  void update(double f, Detail&& detail) {
    if (!enabled_) return;
    const auto now = Clock::now();  // ~20 ns: small next to a step or a right-hand side
    if (now - start_ < std::chrono::milliseconds(500) || now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    f = std::clamp(f, 0.0, 1.0);
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(f * kWidth);
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const std::string eta = f > 0 ? std::to_string(static_cast<long long>(elapsed * (1 - f) / f + 0.5)) + " s left" : "";
    std::fprintf(stderr, "\r[%s%s] %3.0f%%  %s  %.1f s elapsed  %s ",
                 std::string(static_cast<std::size_t>(filled), '#').c_str(),
                 std::string(static_cast<std::size_t>(kWidth - filled), ' ').c_str(), 100 * f,
                 std::string(detail()).c_str(), elapsed, eta.c_str());
    drawn_ = true;
  }
  void clear() {
    if (drawn_) std::fputs("\r\033[K", stderr);
    drawn_ = false;
  }

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_;
  bool drawn_ = false;
  Clock::time_point start_ = Clock::now(), last_ = start_;
};

}  // namespace rigid::cli
