#pragma once

#include <Eigen/Core>

namespace softstep {

// Lane width of the solver kernels. All widths give bit-identical results.
enum class SimdWidth {
  Best,    // the widest this CPU and build support
  Scalar,  // 1 lane
  Sse,     // 4 lanes, SSE4.2
  Avx2,    // 8 lanes, AVX2
};

// "best", "scalar", "sse" or "avx2".
const char* simd_width_name(SimdWidth width);

struct WorldSettings {
  Eigen::Vector3d gravity{0.0, -9.81, 0.0};  // m/s^2
  int substeps = 4;                          // >= 1: sub-steps per step(dt), each a full solve
  int relax_iterations = 1;  // >= 0: rigid, unbiased passes per sub-step after positions move
  int threads = 1;           // >= 1
  bool warm_start = true;    // start each sub-step from the previous sub-step's impulses
  // Rigid rows are solved as a stiff spring (and relaxed with none). Its frequency is capped
  // at a quarter of the sub-step rate, so it cannot overshoot: Hz, > 0.
  double rigid_hertz = 60.0;
  double rigid_damping_ratio = 2.0;  // >= 0
  // How fast a rigid row may correct position error, m/s, > 0: joints created apart close
  // at this speed instead of launching bodies.
  double max_correction_speed = 3.0;
  SimdWidth simd = SimdWidth::Best;
};

}  // namespace softstep
