// The 4-wide body kernels, compiled with SSE4.2 (and FMA when the build fuses).
#include "solver/kernel_table.hpp"
#include "solver/lane_types.hpp"

namespace softstep::solver {
BodyKernels sse_body_kernels() {
  return make_body_kernels<SseLane>();
}
}  // namespace softstep::solver
