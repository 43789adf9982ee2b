#include "solver/kernel_table.hpp"

namespace softstep::solver {
KernelTable<1> scalar_kernels() {
  return make_kernel_table<float>();
}
}  // namespace softstep::solver
