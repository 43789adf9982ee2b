#include "tool/recording_overhead.hpp"

#include <chrono>
#include <cstdio>
#include <stdexcept>

#include "softstep/scene_file.hpp"
#include "tool/elapsed_ms.hpp"
#include "tool/report_files.hpp"

namespace softstep::tool {

RecordingTwin::RecordingTwin(const World& world, const std::string& path)
    : twin_(load_scene_text(save_scene_text(world), "recording twin")) {
  twin_.set_profiling(true);  // as the world: the two differ by the recording alone
  twin_.start_recording(path);
}

void RecordingTwin::step(double dt, std::span<const ContactManifold> contacts,
                         bool with_contacts) {
  const auto start = std::chrono::steady_clock::now();
  if (with_contacts) twin_.step(dt, contacts);
  else twin_.step(dt);
  recording_ms_.push_back(elapsed_ms(start));
}

void RecordingTwin::finish(const World& world, const std::vector<double>& plain_ms) {
  twin_.stop_recording();
  if (twin_.state_hash() != world.state_hash())
    throw std::runtime_error("--recording-overhead: the recording twin diverged from the world");
  std::vector<double> ratio;
  for (std::size_t k = 0; k < plain_ms.size() && k < recording_ms_.size(); ++k)
    ratio.push_back(recording_ms_[k] / plain_ms[k]);
  std::printf("recording        %.3f ms/step recording vs %.3f plain (step() calls, alternated); "
              "median per-step ratio %.3f\n",
              median(recording_ms_), median(plain_ms), median(ratio));
}

}  // namespace softstep::tool
