// The contact kernels, 4-wide, compiled with SSE4.2 (and FMA when the build fuses).
#include "contacts/contact_kernels_build.hpp"
#include "solver/lane_types.hpp"

namespace softstep::solver {
ContactKernels<4> sse_contact_kernels() {
  return make_contact_kernels<SseLane>();
}
}  // namespace softstep::solver
