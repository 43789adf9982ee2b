#include <cmath>
#include <numbers>

#include "reference/joint_rows.hpp"
#include "softstep/metrics.hpp"

namespace softstep::metrics {

namespace {
reference::BodyFrame frame_now(const World& world, BodyId id) {
  const BodyState s = world.body(id);
  const bool dynamic = s.type == BodyType::Dynamic;
  const Eigen::Matrix3d r = s.orientation.toRotationMatrix();
  return {
      s.position, s.orientation, dynamic ? 1.0 / s.mass : 0.0,
      dynamic ? Eigen::Matrix3d(r * s.inertia.inverse() * r.transpose()) : Eigen::Matrix3d::Zero()};
}
}  // namespace

double mechanical_energy(const World& world, std::span<const BodyId> bodies,
                         std::span<const JointId> joints) {
  double energy = 0.0;
  const Eigen::Vector3d g = world.settings().gravity;
  for (const BodyId id : bodies) {
    const BodyState s = world.body(id);
    if (s.type != BodyType::Dynamic) continue;
    const Eigen::Matrix3d r = s.orientation.toRotationMatrix();
    const Eigen::Matrix3d inertia = r * s.inertia * r.transpose();
    energy += 0.5 * s.mass * s.linear_velocity.squaredNorm() +
              0.5 * s.angular_velocity.dot(inertia * s.angular_velocity) -
              s.mass * s.gravity_scale * g.dot(s.position);
  }
  for (const JointId id : joints) {
    const reference::JointRows rows =
        reference::joint_rows(world, id, [&world](BodyId b) { return frame_now(world, b); });
    if (rows.count == 0 || rows.spring.is_rigid()) continue;
    const int n = rows.count;
    const Eigen::VectorXd c = rows.error.head(n);
    if (rows.spring.is_absolute()) {  // k itself, N/m (a distance joint's one row)
      energy += 0.5 * rows.spring.absolute_stiffness * c.squaredNorm();
      continue;
    }
    const double omega = 2.0 * std::numbers::pi * rows.spring.hertz;
    const Eigen::MatrixXd k = rows.k.topLeftCorner(n, n);
    energy += 0.5 * omega * omega * c.dot(k.ldlt().solve(c));
  }
  return energy;
}

double position_drift(const World& world, std::span<const BodyId> bodies,
                      std::span<const Eigen::Vector3d> reference) {
  if (bodies.empty()) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < bodies.size(); ++i)
    sum += (world.body(bodies[i]).position - reference[i]).squaredNorm();
  return std::sqrt(sum / static_cast<double>(bodies.size()));
}

double stretch_ratio(std::span<const Eigen::Vector3d> path, double rest_length) {
  double length = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) length += (path[i] - path[i - 1]).norm();
  return length / rest_length;
}

}  // namespace softstep::metrics
