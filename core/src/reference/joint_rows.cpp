#include "reference/joint_rows.hpp"

namespace softstep::reference {

namespace {
Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& r) {
  Eigen::Matrix3d s;
  s << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  return s;
}
}  // namespace

JointRows joint_rows_between(const BodyFrame& a, const BodyFrame& b,
                             const Eigen::Vector3d& local_anchor_a,
                             const Eigen::Vector3d& local_anchor_b, bool ball, double rest_length) {
  JointRows rows;
  const Eigen::Vector3d r_a = a.orientation * local_anchor_a;
  const Eigen::Vector3d r_b = b.orientation * local_anchor_b;
  const Eigen::Vector3d separation = (b.position + r_b) - (a.position + r_a);
  // Point rows: C_dot = v_b + w_b x r_b - v_a - w_a x r_a, and w x r = -[r]x w.
  Eigen::Matrix<double, 3, 12> point;
  point << -Eigen::Matrix3d::Identity(), cross_matrix(r_a), Eigen::Matrix3d::Identity(),
      -cross_matrix(r_b);
  if (ball) {
    rows.count = 3;
    rows.jacobian = point;
    rows.error = separation;
  } else {
    const double length = separation.norm();
    const Eigen::Vector3d n =
        length > 1e-12 ? Eigen::Vector3d(separation / length) : Eigen::Vector3d::Zero();
    rows.count = 1;
    rows.jacobian.row(0) = n.transpose() * point;
    rows.error.x() = length - rest_length;
  }
  Eigen::Matrix<double, 12, 12> inverse_mass = Eigen::Matrix<double, 12, 12>::Zero();
  inverse_mass.block<3, 3>(0, 0) = a.inverse_mass * Eigen::Matrix3d::Identity();
  inverse_mass.block<3, 3>(3, 3) = a.inverse_inertia;
  inverse_mass.block<3, 3>(6, 6) = b.inverse_mass * Eigen::Matrix3d::Identity();
  inverse_mass.block<3, 3>(9, 9) = b.inverse_inertia;
  rows.k = rows.jacobian * inverse_mass * rows.jacobian.transpose();
  return rows;
}

}  // namespace softstep::reference
