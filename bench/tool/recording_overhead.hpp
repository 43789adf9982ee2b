// softstep profile --recording-overhead FILE: what World::start_recording costs a step. A twin
// of the world, loaded from its scene, records to FILE while the world does not; both take
// the same contacts each step (the twin stays bit-identical: the design's determinism), they
// are stepped alternately (which goes first alternates, so neither always finds the other's
// data in the cache) and their step() calls compared. The twins must end with equal state
// hashes.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "softstep/softstep.hpp"

namespace softstep::tool {

class RecordingTwin {
 public:
  // Call after the scene is built, before its first step.
  RecordingTwin(const World& world, const std::string& path);
  // Steps the twin as the world steps (with `contacts` when the scene has any); goes_first:
  // whether step `step_index`'s twin goes before the world's.
  void step(double dt, std::span<const ContactManifold> contacts, bool with_contacts);
  static bool goes_first(long step_index) { return step_index % 2 == 1; }
  // Stops recording; throws std::runtime_error when the twin diverged from `world`, else
  // prints the comparison with the world's step() calls (`plain_ms`, one per step).
  void finish(const World& world, const std::vector<double>& plain_ms);

 private:
  World twin_;
  std::vector<double> recording_ms_;
};

}  // namespace softstep::tool
