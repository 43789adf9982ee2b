// The contact kernels, 16-wide, compiled with AVX-512 (F, CD, DQ, BW, VL; FMA when the build
// fuses): chosen at run time like the joints' 16-lane kernels.
#include "contacts/contact_kernels_build.hpp"
#include "solver/lane_types.hpp"

namespace softstep::solver {
ContactKernels<16> avx512_contact_kernels() {
  return make_contact_kernels<Avx512Lane>();
}
}  // namespace softstep::solver
