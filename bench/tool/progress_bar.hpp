// A progress bar on stderr, drawn only when stderr is a terminal (quiet in pipes and CI).
#pragma once

#include <chrono>
#include <string>

namespace softstep::tool {

class ProgressBar {
 public:
  ProgressBar(std::string label, long total);
  ~ProgressBar();
  void update(long done);

 private:
  std::string label_;
  long total_;
  bool enabled_;
  int last_percent_ = -1;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace softstep::tool
