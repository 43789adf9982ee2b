// Conversions between the ways a spring is given: frequency and damping ratio, stiffness
// and damping, ODE's ERP and CFM, and the solver coefficients (talk 2:3:2, 3:3).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "expect_invalid_argument.hpp"
#include "softstep/simd/softness.hpp"
#include "softstep/softstep.hpp"

namespace softstep {
namespace {

TEST(Spring, HertzZetaToStiffnessAndBackRoundTrips) {
  for (double hertz : {0.1, 1.0, 30.0, 1000.0}) {
    for (double zeta : {0.0, 0.3, 1.0, 7.0}) {
      for (double m : {1e-3, 1.0, 1e3}) {
        const Spring s = Spring::soft(hertz, zeta);
        const double k = s.stiffness(m);
        const double c = s.damping(m);
        EXPECT_NEAR(k, m * std::pow(2.0 * std::numbers::pi * hertz, 2), 1e-12 * k);
        const Spring back = Spring::from_stiffness(k, c, m);
        EXPECT_NEAR(back.hertz, hertz, 1e-12 * hertz);
        EXPECT_NEAR(back.damping_ratio, zeta, 1e-12 * (1.0 + zeta));
      }
    }
  }
}

TEST(Spring, CoefficientsAreTheTalksGammaAndBeta) {
  const double m = 2.0, h = 1.0 / 120.0;
  const Spring s = Spring::soft(5.0, 0.4);
  const double k = s.stiffness(m), c = s.damping(m);
  const SoftCoefficients co = s.coefficients(m, h);
  EXPECT_DOUBLE_EQ(co.gamma, 1.0 / (c + h * k));
  EXPECT_DOUBLE_EQ(co.beta, h * k / (c + h * k));
  EXPECT_NEAR(co.bias_rate, co.beta / h, 1e-12 * co.bias_rate);
  // Sequential-impulse form: mass_scale * m_eff is the soft effective mass 1/(1/m + gamma/h),
  // and impulse_scale = 1 - mass_scale (DESIGN.md "The math in one place").
  EXPECT_NEAR(co.mass_scale * m, 1.0 / (1.0 / m + co.gamma / h), 1e-12);
  EXPECT_NEAR(co.impulse_scale, 1.0 - co.mass_scale, 1e-15);
}

TEST(Spring, ErpCfmRoundTrip) {
  const double m = 0.7, h = 1.0 / 60.0;
  for (double hertz : {0.5, 4.0, 25.0}) {
    for (double zeta : {0.0, 0.5, 2.0}) {
      const Spring s = Spring::soft(hertz, zeta);
      const SoftCoefficients co = s.coefficients(m, h);
      const Spring back = Spring::from_erp_cfm(co.beta, co.gamma, m, h);  // ERP = beta, CFM = gamma
      EXPECT_NEAR(back.hertz, hertz, 1e-9 * hertz);
      EXPECT_NEAR(back.damping_ratio, zeta, 1e-9 * (1.0 + zeta));
    }
  }
}

TEST(Spring, StiffnessToInfinityGivesRigid) {
  const double m = 1.0, h = 1.0 / 60.0, c = 1.0;
  double previous_gamma = std::numeric_limits<double>::infinity();
  for (double k = 1e2; k <= 1e16; k *= 100.0) {
    const SoftCoefficients co = Spring::from_stiffness(k, c, m).coefficients(m, h);
    EXPECT_LT(co.gamma, previous_gamma);
    previous_gamma = co.gamma;
    if (k >= 1e16) {
      EXPECT_LT(co.gamma, 1e-14);
      EXPECT_NEAR(co.beta, 1.0, 1e-12);
    }
  }
  const SoftCoefficients rigid = Spring::rigid().coefficients(m, h);
  EXPECT_EQ(rigid.gamma, 0.0);
  EXPECT_EQ(rigid.beta, 1.0);
}

TEST(Spring, DesignerFormIsFramesAndOscillation) {
  const Spring none = Spring::designer(6.0, Oscillation::None);
  EXPECT_DOUBLE_EQ(none.hertz, 10.0);
  EXPECT_DOUBLE_EQ(none.damping_ratio, 1.0);
  EXPECT_DOUBLE_EQ(Spring::designer(3.0, Oscillation::Free, 30.0).hertz, 10.0);
  EXPECT_DOUBLE_EQ(Spring::designer(3.0, Oscillation::Free).damping_ratio, 0.0);
  const double some = Spring::designer(3.0, Oscillation::Some).damping_ratio;
  EXPECT_GT(some, 0.0);
  EXPECT_LT(some, 1.0);
}

// The kernels' float softness is the same formula as the API's double one.
TEST(Spring, KernelSoftnessMatchesApiCoefficients) {
  for (double hertz : {0.2, 3.0, 60.0, 5000.0}) {
    for (double zeta : {0.0, 0.7, 10.0}) {
      const float h = 1.0f / 240.0f;
      const auto k = simd::make_softness(static_cast<float>(hertz), static_cast<float>(zeta), h);
      const SoftCoefficients co = Spring::soft(hertz, zeta).coefficients(1.0, h);
      EXPECT_NEAR(k.bias_rate, co.bias_rate, 1e-5 * co.bias_rate);
      EXPECT_NEAR(k.mass_scale, co.mass_scale, 1e-6);
      EXPECT_NEAR(k.impulse_scale, co.impulse_scale, 1e-6);
    }
  }
  const auto free = simd::make_softness(0.0f, 0.0f, 0.01f);
  EXPECT_EQ(free.mass_scale, 0.0f);
  EXPECT_EQ(free.bias_rate, 0.0f);
}

// The softness must give back, per solve, the accumulated impulse the spring lets through:
// mass_scale * feedback = impulse_scale = 1 / (1 + a) (softness.hpp), and so below 1. For the
// slowest rows (a = h omega (2 zeta + h omega) down to 1e-15: rigid_hertz 1e-6, undamped
// springs of mHz, nanosecond sub-steps) mass_scale was 1 - 1/(1 + a) in float, which cancels:
// at rigid_hertz 1e-6 the product was 1.14, and a rigid ball joint's impulse grew 14 % per
// solve iteration until NaN.
TEST(Spring, KernelSoftnessGivesBackLessThanItHoldsAtEveryFrequency) {
  for (double hertz : {1e-6, 1e-3, 0.2, 60.0, 1e4, 1e9}) {
    for (double zeta : {0.0, 0.7, 2.0, 1e3}) {
      for (float h : {1e-9f, 1.0f / 240.0f, 1.0f, 1e3f}) {
        const auto k = simd::make_softness(static_cast<float>(hertz), static_cast<float>(zeta), h);
        const double omega = 2.0 * std::numbers::pi * hertz;
        const double a = double(h) * omega * (2.0 * zeta + double(h) * omega);
        if (!(a > 1e-30 && a < 1e30)) continue;  // beyond float: the context caps these
        const double given_back = double(k.mass_scale) * double(k.feedback);
        // Float rounding may leave it a few 1e-8 above 1 / (1 + a); 1.14 grew a joint to NaN.
        EXPECT_LT(given_back, 1.0 + 1e-6)
            << hertz << " Hz, zeta " << zeta << ", h " << h << " s, a " << a;
        EXPECT_NEAR(given_back, 1.0 / (1.0 + a), 1e-4 / (1.0 + a))
            << hertz << " Hz, zeta " << zeta << ", h " << h << " s, a " << a;
        EXPECT_NEAR(k.mass_scale, a / (1.0 + a), 1e-4 * a / (1.0 + a))
            << hertz << " Hz, zeta " << zeta << ", h " << h << " s";
      }
    }
  }
}

// Issue 17, bug 5: the helpers returned NaN or a rigid spring for input no spring has; they
// reject it like every other call, naming the argument and the value.
TEST(Spring, HelpersRejectInputNoSpringHas) {
  const auto rejects = expect_invalid_argument;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  rejects([] { Spring::from_stiffness(-5.0, 0.0, 1.0); }, "k", "-5");
  rejects([] { Spring::from_stiffness(5.0, -1.0, 1.0); }, "c", "-1");
  rejects([] { Spring::from_stiffness(5.0, 0.0, 0.0); }, "effective_mass", "0");
  rejects([nan] { Spring::from_stiffness(nan, 0.0, 1.0); }, "k", "nan");
  rejects([] { Spring::from_erp_cfm(0.2, 0.0, 1.0, 1.0 / 60.0); }, "cfm", "0");
  rejects([] { Spring::from_erp_cfm(1.5, 0.01, 1.0, 1.0 / 60.0); }, "erp", "1.5");
  rejects([] { Spring::from_erp_cfm(0.2, 0.01, 1.0, 0.0); }, "h", "0");
  rejects([] { Spring::from_erp_cfm(0.2, 0.01, -1.0, 1.0 / 60.0); }, "effective_mass", "-1");
  rejects([] { Spring::designer(0.0, Oscillation::Some); }, "frames", "0");
  rejects([] { Spring::designer(3.0, Oscillation::Some, -60.0); }, "frame_rate", "-60");
  rejects([] { Spring::designer(3.0, static_cast<Oscillation>(7)); }, "oscillation", "7");
  // What they accept stays a finite, soft spring.
  const Spring s = Spring::from_erp_cfm(0.2, 1e-3, 1.0, 1.0 / 60.0);
  EXPECT_TRUE(std::isfinite(s.hertz) && s.hertz > 0.0);
  EXPECT_TRUE(std::isfinite(s.damping_ratio) && s.damping_ratio >= 0.0);
}

}  // namespace
}  // namespace softstep
