#include "tool/progress_bar.hpp"

#include <unistd.h>

#include <cstdio>

namespace softstep::tool {

ProgressBar::ProgressBar(std::string label, long total)
    : label_(std::move(label)),
      total_(total),
      enabled_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() {
  if (enabled_) std::fprintf(stderr, "\r\033[K");
}

void ProgressBar::update(long done) {
  if (!enabled_ || total_ <= 0) return;
  const int percent = static_cast<int>(100 * done / total_);
  if (percent == last_percent_) return;
  last_percent_ = percent;
  constexpr int kWidth = 40;
  const int filled = percent * kWidth / 100;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double eta =
      done > 0 ? elapsed * static_cast<double>(total_ - done) / static_cast<double>(done) : 0.0;
  std::fprintf(stderr, "\r%s [%.*s%*s] %3d%% %ld/%ld eta %.0fs", label_.c_str(), filled,
               "########################################", kWidth - filled, "", percent, done,
               total_, eta);
  std::fflush(stderr);
}

}  // namespace softstep::tool
