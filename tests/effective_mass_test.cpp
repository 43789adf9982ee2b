// Talk 3:1: the effective mass is the mass *seen* by the constraint impulse. Apply equal and
// opposite unit impulses at the anchors along an axis, measure the relative anchor velocity
// along that axis: 1/v_rel must equal 1/(J M^-1 J^T) as the kernels compute it.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "softstep/simd/ball_joint_kernel.hpp"
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
      Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized())
          .toRotationMatrix();
  const Eigen::Matrix3d inertia = rot * principal.asDiagonal() * rot.transpose();
  return {1.0 / m, inertia.inverse(), Eigen::Vector3d(u(rng), u(rng), u(rng))};
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

Mat3Sym<float> lanes(const Eigen::Matrix3d& m) {
  return {float(m(0, 0)), float(m(1, 1)), float(m(2, 2)),
          float(m(0, 1)), float(m(0, 2)), float(m(1, 2))};
}
Vec3<float> lanes(const Eigen::Vector3d& v) {
  return {float(v.x()), float(v.y()), float(v.z())};
}

Eigen::Matrix3d matrix(const Mat3Sym<float>& m) {
  Eigen::Matrix3d r;
  r << m.xx, m.xy, m.xz, m.xy, m.yy, m.yz, m.xz, m.yz, m.zz;
  return r;
}

// K^-1 as the ball-joint kernel computes it for these bodies, as an Eigen matrix.
Eigen::Matrix3d kernel_k_inv(const RandomBody& a, const RandomBody& b) {
  return matrix(inverse_effective_mass(float(a.inv_mass), lanes(a.inv_inertia), lanes(a.r),
                                       float(b.inv_mass), lanes(b.inv_inertia), lanes(b.r)));
}

TEST(EffectiveMass, UnitImpulseExperimentMatchesKernels) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const RandomBody a = random_body(rng), b = random_body(rng);
    const Eigen::Vector3d n = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    const double expected = measured_effective_mass(a, b, n);

    // Ball joint: the mass seen along n is 1 / (n^T K n).
    const Eigen::Matrix3d k_inv_m = kernel_k_inv(a, b);
    EXPECT_NEAR(1.0 / n.dot(k_inv_m.inverse() * n), expected, 2e-4 * expected) << "trial " << trial;

    // Distance joint along n: its axial mass is the same quantity.
    const float axial = axial_mass(float(a.inv_mass), lanes(a.inv_inertia), lanes(a.r),
                                   float(b.inv_mass), lanes(b.inv_inertia), lanes(b.r), lanes(n));
    EXPECT_NEAR(axial, expected, 2e-4 * expected) << "trial " << trial;
  }
}

// The 3x3 inverse is scaled before its determinant is formed, so masses far from 1 kg keep
// their effective mass (an unscaled determinant left the float range at ~1e13 kg and gave
// inf/NaN).
TEST(EffectiveMass, ExtremeMassesStayAccurate) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double scale : {1e-12, 1e-6, 1e6, 1e13, 1e16}) {
    RandomBody a = random_body(rng), b = random_body(rng);
    for (RandomBody* body : {&a, &b}) {
      body->inv_mass /= scale;
      body->inv_inertia /= scale;
    }
    const Eigen::Vector3d n = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    const double expected = measured_effective_mass(a, b, n);
    const Eigen::Matrix3d k_inv_m = kernel_k_inv(a, b);
    ASSERT_TRUE(k_inv_m.allFinite()) << "scale " << scale;
    EXPECT_NEAR(1.0 / n.dot(k_inv_m.inverse() * n), expected, 2e-4 * expected) << "scale " << scale;
  }
}

TEST(EffectiveMass, ImmovableBodiesGiveZeroNotNan) {
  const Mat3Sym<float> zero{0, 0, 0, 0, 0, 0};
  const Vec3<float> r{0.1f, 0.2f, 0.3f};
  const Mat3Sym<float> k_inv = inverse_effective_mass(0.0f, zero, r, 0.0f, zero, r);
  for (float v : {k_inv.xx, k_inv.yy, k_inv.zz, k_inv.xy, k_inv.xz, k_inv.yz}) EXPECT_EQ(v, 0.0f);
  EXPECT_EQ(axial_mass(0.0f, zero, r, 0.0f, zero, r, Vec3<float>{1, 0, 0}), 0.0f);
}

}  // namespace
}  // namespace softstep::simd
