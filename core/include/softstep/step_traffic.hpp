// What a step must move through memory at least, stage by stage: the model behind "how close
// does a step come to the memory bandwidth" (softstep profile --bandwidth). A model, not a
// measurement: the hosts this project runs on have no hardware counters.
//
// Each run of a stage reads the data it needs once and writes what it changes once, as if
// every byte it touches twice within the run stayed in cache and nothing stayed in cache
// between runs. Real traffic is higher where a body record is evicted between the joints that
// share it (another colour, another thread) and where a cache line is written back whole;
// lower where the whole working set fits in the last-level cache. Over a stage's measured
// time these bytes give the rate it reached; over a triad bandwidth, the fraction of the
// memory bound it reached. Joints and bodies only: contact lanes are not counted yet.
#pragma once

#include <array>
#include <cstdint>

#include "softstep/profile.hpp"

namespace softstep {

class World;

struct StepTraffic {
  // Bytes per step (all sub-steps and passes of a stage summed, as StepProfile::stage_ms is).
  std::array<double, kStageCount> bytes{};
  // What a stage's bytes are counted per: constraint rows times the passes over them for the
  // joint passes, bodies times the sub-steps for the body stages (0 where a stage does not run).
  std::array<double, kStageCount> units{};
  std::array<bool, kStageCount> per_row{};  // units are rows (else bodies)
  double total() const;
};

// The model for the world's last plan (its content and settings as of the last step).
StepTraffic step_traffic(const World& world);

}  // namespace softstep
