#include "softstep/step_traffic.hpp"

#include <numeric>

#include "softstep/world.hpp"
#include "world_impl.hpp"

namespace softstep {
namespace {

constexpr double kRecord = 32.0;  // every solver body record (body_records.hpp)
static_assert(sizeof(simd::VelocityRecord) == kRecord && sizeof(simd::ForceRecord) == kRecord);

// The BodySlot fields the step reads when it prepares a body (velocities, orientation, mass,
// inverse inertia, gravity scale, damping) and writes back when it stores one (position,
// orientation, velocities; the rest test's two floats).
constexpr double kSlotPrepareRead =
    2 * sizeof(Eigen::Vector3d) + sizeof(Quaternion) + sizeof(double) + sizeof(Eigen::Matrix3d) +
    3 * sizeof(double);
constexpr double kSlotStoreWritten =
    3 * sizeof(Eigen::Vector3d) + sizeof(Quaternion) + 2 * sizeof(float);

}  // namespace

double StepTraffic::total() const { return std::accumulate(bytes.begin(), bytes.end(), 0.0); }

StepTraffic step_traffic(const World& world) {
  const StepPlan& plan = world.step_plan();
  const WorldSettings& s = world.settings();
  const auto runs = [&](PlanStage p) { return plan.runs(p); };
  double lanes = 0.0, impulses = 0.0;
  for (const PlanKernel& k : plan.kernels) {
    lanes += double(k.lane_bytes);
    impulses += double(k.impulse_bytes);
  }
  const double bodies = double(plan.awake_bodies);
  const double substeps = s.substeps;
  const double rows = double(plan.rows_per_pass);
  // A joint pass reads its lanes and, of every body it touches, the velocity (written back),
  // the delta since the step start and the mass record. Contact lanes are not modelled: with
  // no joint in the lanes the joint passes count nothing.
  const bool joint_passes = rows > 0.0;
  const double joint_pass_bodies = bodies * (2 * kRecord + kRecord + kRecord);
  StepTraffic t;
  const auto set = [&](Stage stage, double bytes, double units, bool per_row) {
    const auto i = static_cast<std::size_t>(stage);
    t.bytes[i] = bytes;
    t.units[i] = units;
    t.per_row[i] = per_row;
  };
  if (runs(PlanStage::PrepareBodies) || runs(PlanStage::PrepareJoints)) {
    // Bodies: the slot fields in, four records out. Joints: their lanes in and out, the
    // bodies' orientations (slots) and mass records in.
    const double body_part = bodies * (kSlotPrepareRead + 4 * kRecord);
    const double joint_part =
        runs(PlanStage::PrepareJoints) ? 2 * lanes + bodies * (sizeof(Quaternion) + kRecord) : 0.0;
    set(Stage::Prepare, body_part + joint_part, bodies, false);
  }
  // Velocity in and out, force record in; per sub-step.
  set(Stage::IntegrateVelocities, substeps * bodies * 3 * kRecord, substeps * bodies, false);
  if (runs(PlanStage::WarmStart) && joint_passes) {
    set(Stage::WarmStart, substeps * (lanes + joint_pass_bodies), substeps * rows, true);
  }
  if (runs(PlanStage::Solve) && joint_passes) {
    const double passes = substeps * s.solve_iterations;
    set(Stage::Solve, passes * (lanes + impulses + joint_pass_bodies), passes * rows, true);
  }
  // Velocity in, delta in and out; per sub-step.
  set(Stage::IntegratePositions, substeps * bodies * 3 * kRecord, substeps * bodies, false);
  if (runs(PlanStage::Relax) && s.relax_iterations > 0 && joint_passes) {
    const double passes = substeps * s.relax_iterations;
    set(Stage::Relax, passes * (lanes + impulses + joint_pass_bodies), passes * rows, true);
  }
  // Velocity and delta records in; the slot's pose and velocities in and out.
  set(Stage::Store, bodies * (2 * kRecord + 2 * kSlotStoreWritten), bodies, false);
  if (plan.awake_bodies == 0) t = StepTraffic{};
  return t;
}

}  // namespace softstep
