// The scalar body kernels (the overflow set and SimdWidth::Scalar).
#include "solver/kernel_table.hpp"
#include "solver/lane_types.hpp"

namespace softstep::solver {
BodyKernels scalar_body_kernels() {
  return make_body_kernels<ScalarLane>();
}
}  // namespace softstep::solver
