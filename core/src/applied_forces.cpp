// Forces and torques the caller applies for the next step (issue 17, hook 9). They are kept
// per body, folded into the body's force record when the step prepares its bodies (force /
// mass onto the gravity term, inverse inertia x torque as an angular acceleration), applied
// in every sub-step, and cleared after the step.
#include <algorithm>

#include "recording/recorder.hpp"
#include "validation.hpp"
#include "world_impl.hpp"

namespace softstep {

namespace {

// Checks a force or torque given for a dynamic body (`field`, `given`), and the sum it would
// make with what the body already carries for the next step (`what`: "force" or "torque"),
// which must stay inside the float envelope.
void check_load(const World::Impl& w, std::string_view call, std::uint32_t slot,
                std::string_view field, const Eigen::Vector3d& given, const char* what,
                const Eigen::Vector3d& sum) {
  const BodySlot& b = w.bodies[slot];
  if (b.type != BodyType::Dynamic) {
    validation::reject(call, "body", b.type == BodyType::Static ? "static" : "kinematic",
                       "only a dynamic body responds to a force or torque");
  }
  validation::finite(call, field, given);
  if (!(sum.cwiseAbs().maxCoeff() <= validation::kMaxMagnitude)) {
    validation::reject(call, field, validation::format(given),
                       std::string("would make the body's ") + what + " for the next step " +
                           validation::format(sum) + ", beyond +-" +
                           validation::format(validation::kMaxMagnitude));
  }
}

bool loaded(const BodySlot& b) {
  return !b.force.isZero(0.0) || !b.torque.isZero(0.0);
}

// Adds a checked load to the body and lists it for clearing after the step.
void add_load(World::Impl& w, std::uint32_t slot, const Eigen::Vector3d& force,
              const Eigen::Vector3d& torque) {
  BodySlot& b = w.bodies[slot];
  w.touch(slot);
  const bool listed = loaded(b);
  b.force += force;
  b.torque += torque;
  if (!loaded(b)) return;
  if (!listed) w.forced_bodies.push_back(slot);
  w.plan_forces(true);
}

}  // namespace

void World::Impl::plan_forces(bool on) {
  if (!plan_built || plan.forces == on) return;
  plan.forces = on;
  if (!plan.specialized || plan.awake_bodies == 0) return;  // general plans run every stage
  std::vector<PlanStage>& stages = plan.stages;
  if (on) {
    // Stages are listed in enum order: Forces goes before the first stage that follows it.
    stages.insert(std::find_if(stages.begin(), stages.end(),
                               [](PlanStage s) { return s > PlanStage::Forces; }),
                  PlanStage::Forces);
  } else {
    stages.erase(std::remove(stages.begin(), stages.end(), PlanStage::Forces), stages.end());
  }
}

void World::Impl::clear_forces() {
  if (forced_bodies.empty()) return;
  for (std::uint32_t s : forced_bodies) {
    bodies[s].force.setZero();
    bodies[s].torque.setZero();
  }
  forced_bodies.clear();
  plan_forces(false);
}

void World::apply_force(BodyId id, const Eigen::Vector3d& force,
                        const Eigen::Vector3d& world_point) {
  Impl& w = *impl_;
  const char* call = "apply_force";
  const std::uint32_t slot = body_slot(w, call, "body", id);
  validation::finite(call, "world_point", world_point);
  const BodySlot& b = w.bodies[slot];
  check_load(w, call, slot, "force", force, "force", b.force + force);
  const Eigen::Vector3d torque = (world_point - b.position).cross(force);
  check_load(w, call, slot, "force", force, "torque", b.torque + torque);
  add_load(w, slot, force, torque);
  if (w.recorder) w.recorder->apply_force(id, force, world_point);
}

void World::apply_torque(BodyId id, const Eigen::Vector3d& torque) {
  Impl& w = *impl_;
  const char* call = "apply_torque";
  const std::uint32_t slot = body_slot(w, call, "body", id);
  check_load(w, call, slot, "torque", torque, "torque", w.bodies[slot].torque + torque);
  add_load(w, slot, Eigen::Vector3d::Zero(), torque);
  if (w.recorder) w.recorder->apply_torque(id, torque);
}

}  // namespace softstep
