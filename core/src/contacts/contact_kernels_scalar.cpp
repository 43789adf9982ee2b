// The contact kernels, 1-lane, compiled without instruction-set flags.
#include "contacts/contact_kernels_build.hpp"
#include "solver/lane_types.hpp"

namespace softstep::solver {
ContactKernels<1> scalar_contact_kernels() {
  return make_contact_kernels<ScalarLane>();
}
}  // namespace softstep::solver
