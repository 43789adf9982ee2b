// 4 lanes, SSE4.2 (fused like every width when SOFTSTEP_USE_FMA: see lanes.hpp).
#include "solver/kernel_table.hpp"

namespace softstep::solver {
using SseLane = xsimd::batch<float, xsimd::sse4_2>;
KernelTable<4> sse_kernels() {
  return make_kernel_table<SseLane>();
}
}  // namespace softstep::solver
