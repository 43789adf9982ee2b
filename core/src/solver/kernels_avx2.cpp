// The 8-wide body kernels, compiled with AVX2 (and FMA when the build fuses).
#include "solver/kernel_table.hpp"
#include "solver/lane_types.hpp"

namespace softstep::solver {
BodyKernels avx2_body_kernels() {
  return make_body_kernels<Avx2Lane>();
}
}  // namespace softstep::solver
