// The contact kernels, 8-wide, compiled with AVX2 (and FMA when the build fuses).
#include "contacts/contact_kernels_build.hpp"
#include "solver/lane_types.hpp"

namespace softstep::solver {
ContactKernels<8> avx2_contact_kernels() {
  return make_contact_kernels<Avx2Lane>();
}
}  // namespace softstep::solver
