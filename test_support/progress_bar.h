#ifndef FCL_SUPERELLIPSOID_SUPPORT_PROGRESS_BAR_H
#define FCL_SUPERELLIPSOID_SUPPORT_PROGRESS_BAR_H

// A one-line progress bar on stderr for the benchmark and the scene runner, drawn only when
// stderr is a terminal (logs and CI stay clean). Debian packages no C++ progress-bar library; this
// is the 30 lines it takes.

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

namespace fcl_superellipsoid {
namespace support {

class ProgressBar {
 public:
  ProgressBar(long total, bool enabled)
      : total_(total > 0 ? total : 1), enabled_(enabled && isatty(STDERR_FILENO)) {}
  ~ProgressBar() { finish(); }

  /// Advances by `steps` and redraws with `what` (the current task).
  void advance(long steps, const std::string& what) {
    done_ += steps;
    if (!enabled_) return;
    const double fraction = std::min(1.0, double(done_) / double(total_));
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const int width = 30, filled = static_cast<int>(fraction * width);
    std::fprintf(stderr, "\r[%s%s] %3.0f%%  %5.0f s left  %-50.50s",
                 std::string(filled, '#').c_str(), std::string(width - filled, '.').c_str(),
                 100 * fraction, fraction > 0 ? elapsed * (1 - fraction) / fraction : 0.0,
                 what.c_str());
    std::fflush(stderr);
  }
  void finish() {
    if (enabled_ && !finished_) std::fprintf(stderr, "\r%*s\r", 100, "");
    finished_ = true;
  }

 private:
  long total_, done_ = 0;
  bool enabled_, finished_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace support
}  // namespace fcl_superellipsoid

#endif  // FCL_SUPERELLIPSOID_SUPPORT_PROGRESS_BAR_H
