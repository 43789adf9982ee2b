// Talk 3:1: the effective mass is the mass *seen* by the constraint impulse. Apply equal and
// opposite unit impulses at the anchors along an axis, measure the relative anchor velocity
// along that axis: 1/v_rel must equal 1/(J M^-1 J^T) as the kernels compute it.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "softstep/simd/distance_joint_kernel.hpp"

namespace softstep::simd {
namespace {

struct RandomBody {
  double inv_mass;
  Eigen::Matrix3d inv_inertia;  // world frame
  Eigen::Vector3d r;            // anchor offset from the centre, world frame
};

RandomBody random_body(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_real_distribution<double> mass(0.1, 20.0);
  const double m = mass(rng);
  const Eigen::Vector3d principal(mass(rng) * 0.05, mass(rng) * 0.05, mass(rng) * 0.05);
  const Eigen::Matrix3d rot =
      Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
  const Eigen::Matrix3d inertia = rot * principal.asDiagonal() * rot.transpose();
  return {1.0 / m, inertia.inverse(), Eigen::Vector3d(u(rng), u(rng), u(rng))};
}

MassRecord record(const RandomBody& b) {
  const Eigen::Matrix3d& i = b.inv_inertia;
  return {static_cast<float>(b.inv_mass),
          {float(i(0, 0)), float(i(1, 1)), float(i(2, 2)), float(i(0, 1)), float(i(0, 2)), float(i(1, 2))},
          0.0f};
}

// The unit-impulse experiment, in double, with no Jacobian in sight.
double measured_effective_mass(const RandomBody& a, const RandomBody& b, const Eigen::Vector3d& n) {
  const Eigen::Vector3d dv_a = -a.inv_mass * n;
  const Eigen::Vector3d dw_a = a.inv_inertia * a.r.cross(-n);
  const Eigen::Vector3d dv_b = b.inv_mass * n;
  const Eigen::Vector3d dw_b = b.inv_inertia * b.r.cross(n);
  const double v_rel = ((dv_b + dw_b.cross(b.r)) - (dv_a + dw_a.cross(a.r))).dot(n);
  return 1.0 / v_rel;
}

TEST(EffectiveMass, UnitImpulseExperimentMatchesKernels) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const RandomBody a = random_body(rng), b = random_body(rng);
    const MassRecord masses[3] = {MassRecord{}, record(a), record(b)};
    const BodyArrays arrays{nullptr, nullptr, masses};
    const SubstepContext ctx{0.01f, 100.0f, {0, 1, 0}, 1.0f};

    BallJointGroup<1> ball{};
    ball.body_a[0] = 1;
    ball.body_b[0] = 2;
    for (int k = 0; k < 3; ++k) {
      ball.r_a[k][0] = float(a.r[k]);
      ball.r_b[k][0] = float(b.r[k]);
    }
    ball.hertz[0] = kRigidHertz;
    prepare_ball_joints<float>(ball, arrays, ctx);
    Eigen::Matrix3d k_inv;
    k_inv << ball.k_inv[0][0], ball.k_inv[3][0], ball.k_inv[4][0], ball.k_inv[3][0], ball.k_inv[1][0],
        ball.k_inv[5][0], ball.k_inv[4][0], ball.k_inv[5][0], ball.k_inv[2][0];
    const Eigen::Matrix3d k = k_inv.inverse();

    const Eigen::Vector3d n = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    const double expected = measured_effective_mass(a, b, n);
    // Ball joint: the mass seen along n is 1 / (n^T K n).
    EXPECT_NEAR(1.0 / n.dot(k * n), expected, 2e-4 * expected) << "trial " << trial;

    // Distance joint along n: its axial mass is the same quantity. Place B's centre so that
    // the anchors lie 1 m apart along n.
    DistanceJointGroup<1> dist{};
    dist.body_a[0] = 1;
    dist.body_b[0] = 2;
    const Eigen::Vector3d center_delta = a.r + n - b.r;
    for (int kk = 0; kk < 3; ++kk) {
      dist.r_a[kk][0] = float(a.r[kk]);
      dist.r_b[kk][0] = float(b.r[kk]);
      dist.center_delta[kk][0] = float(center_delta[kk]);
    }
    dist.hertz[0] = kRigidHertz;
    prepare_distance_joints<float>(dist, arrays, ctx);
    EXPECT_NEAR(dist.axial_mass[0], expected, 2e-4 * expected) << "trial " << trial;
  }
}

TEST(EffectiveMass, ImmovableBodiesGiveZeroNotNan) {
  const MassRecord masses[1] = {MassRecord{}};
  const BodyArrays arrays{nullptr, nullptr, masses};
  const SubstepContext ctx{0.01f, 100.0f, {0, 1, 0}, 1.0f};
  BallJointGroup<1> ball{};
  ball.hertz[0] = kRigidHertz;
  prepare_ball_joints<float>(ball, arrays, ctx);
  for (auto& row : ball.k_inv) EXPECT_EQ(row[0], 0.0f);
}

}  // namespace
}  // namespace softstep::simd
