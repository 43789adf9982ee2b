// World::set_solve_capture: the first sub-step of a step as the solver saw it, for the
// accuracy references. Copies only; the solver itself is untouched, so a captured step is
// bit-identical to an uncaptured one.
#include "world_impl.hpp"

namespace softstep {

namespace {
using Velocity6 = Vector6;

void copy_velocities(const SolverBodies& sb, std::vector<Velocity6>& into) {
  for (const std::uint32_t s : sb.movable) {
    const simd::VelocityRecord& r = sb.velocity[s + 1];
    into[s] << r.v[0], r.v[1], r.v[2], r.w[0], r.w[1], r.w[2];
  }
}
}  // namespace

void World::Impl::capture_step_start(float h, double rigid_hertz) {
  SolveCapture& c = capture;
  c.h = h;
  c.rigid_hertz = rigid_hertz;
  const std::size_t n = bodies.size();
  c.position.assign(n, Eigen::Vector3d::Zero());
  c.orientation.assign(n, Quaternion::Identity());
  c.velocity_before_solve.assign(n, Velocity6::Zero());
  c.velocity_after_solve.assign(n, Velocity6::Zero());
  c.inverse_mass.assign(n, 0.0);
  c.inverse_inertia.assign(n, Eigen::Matrix3d::Zero());
  for (std::size_t s = 0; s < n; ++s) {
    if (!bodies[s].alive) continue;
    c.position[s] = bodies[s].position;
    c.orientation[s] = bodies[s].orientation;
  }
  c.joints.clear();
  for (std::uint32_t s = 0; s < joints.size(); ++s) {
    if (joints[s].alive) c.joints.push_back({s, joints[s].generation});
  }
  c.impulse.assign(c.joints.size(), Eigen::Vector3d::Zero());
}

void World::Impl::capture_before_solve() {
  copy_velocities(solver_bodies, capture.velocity_before_solve);
  for (const std::uint32_t s : solver_bodies.movable) {
    const simd::MassRecord& m = solver_bodies.mass[s + 1];
    capture.inverse_mass[s] = m.inv_mass;
    const float* i = m.inv_inertia;  // xx yy zz xy xz yz
    capture.inverse_inertia[s] << i[0], i[3], i[4], i[3], i[1], i[5], i[4], i[5], i[2];
  }
}

void World::Impl::capture_solved() {
  copy_velocities(solver_bodies, capture.velocity_after_solve);
  for (std::size_t k = 0; k < capture.joints.size(); ++k) {
    const std::array<float, kMaxJointImpulses> p = lane_solver->impulses(capture.joints[k].index);
    capture.impulse[k] = Eigen::Vector3d(p[0], p[1], p[2]);
  }
}

void World::set_solve_capture(bool on) {
  impl_->capturing = on;
}

const SolveCapture& World::solve_capture() const {
  return impl_->capture;
}

}  // namespace softstep
