// The contact kernels alone, scalar vs SSE (4) vs AVX2 (8) (AVX-512, 16 lanes:
// contact_kernel_benchmark_avx512.cpp), over a pyramid's 4-point box manifolds with friction
// (contact_kernel_bench_support.hpp). Read ns_per_row, and x_scalar: the speed-up over the
// scalar kernel on the same pyramid, measured first in the same run (absent when the scalar
// benchmark did not run before, e.g. with --benchmark_enable_random_interleaving).
// Compiled with -mavx2 (and -mfma with SOFTSTEP_USE_FMA) into softstep_kernel_bench.
#include <map>

#include "contact_kernel_bench_support.hpp"

namespace softstep::simd {

namespace {
std::map<std::pair<ContactPass, int>, double>& scalar_figures() {
  static std::map<std::pair<ContactPass, int>, double> figures;
  return figures;
}
}  // namespace

void remember_scalar_ns_per_row(ContactPass pass, int base, double ns) {
  scalar_figures()[{pass, base}] = ns;
}

double scalar_ns_per_row(ContactPass pass, int base) {
  const auto known = scalar_figures().find({pass, base});
  if (known != scalar_figures().end()) return known->second;
  ContactBench<float> bench(base);
  const auto run = [&] {
    if (pass == ContactPass::Solve) bench.pass<ContactPass::Solve>();
    else bench.pass<ContactPass::Relax>();
  };
  run();  // warm the caches
  long passes = 0;
  const double start = cpu_time_ns();
  while (passes < 3 || cpu_time_ns() - start < 2e8) {
    run();
    ++passes;
  }
  const double ns = (cpu_time_ns() - start) / (static_cast<double>(passes) * bench.packed.rows);
  remember_scalar_ns_per_row(pass, base, ns);
  return ns;
}

namespace {

using Sse = xsimd::batch<float, xsimd::sse4_2>;
using Avx2 = xsimd::batch<float, xsimd::avx2>;

#define SOFTSTEP_CONTACT_BENCH(PASS, LANES, NAME)        \
  BENCHMARK(run_contacts<LANES, ContactPass::PASS>)      \
      ->Name("ContactLanes/" #PASS "/" #NAME)            \
      ->Apply(pyramid_bases)

SOFTSTEP_CONTACT_BENCH(Solve, float, scalar);
SOFTSTEP_CONTACT_BENCH(Relax, float, scalar);
SOFTSTEP_CONTACT_BENCH(Solve, Sse, sse);
SOFTSTEP_CONTACT_BENCH(Relax, Sse, sse);
SOFTSTEP_CONTACT_BENCH(Solve, Avx2, avx2);
SOFTSTEP_CONTACT_BENCH(Relax, Avx2, avx2);

}  // namespace
}  // namespace softstep::simd
