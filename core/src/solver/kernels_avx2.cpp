// 8 lanes.
#include "solver/kernel_table.hpp"

namespace softstep::solver {
using Avx2Lane = xsimd::batch<float, xsimd::avx2>;
KernelTable<8> avx2_kernels() {
  return make_kernel_table<Avx2Lane>();
}
}  // namespace softstep::solver
