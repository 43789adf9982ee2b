// The kernels of kernel_benchmark.cpp at 16 lanes (AVX-512), registered in the same binary so
// that one run lists every width side by side. This file alone is compiled with the AVX-512
// flags the library's 16-lane kernel files use; on a CPU without AVX-512 its benchmarks are
// skipped with a message and never execute an AVX-512 instruction.
#include "contact_kernel_bench_support.hpp"
#include "kernel_bench_support.hpp"

namespace softstep::simd {
namespace {

using Avx512 = xsimd::batch<float, xsimd::avx512bw>;

bool cpu_has_avx512() {
  __builtin_cpu_init();
  return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
         __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw") &&
         __builtin_cpu_supports("avx512vl");
}

template <template <int> class Group, Stage S, JointFeatures F = kGeneralKernel,
          std::uint32_t Sig = 0>
void run_avx512(benchmark::State& state) {
  if (!cpu_has_avx512()) {
    state.SkipWithError("skipped: this CPU lacks AVX-512 (F, CD, DQ, BW and VL)");
    return;
  }
  run<Avx512, Group, S, F, Sig>(state);
}

#define SOFTSTEP_AVX512_BENCH(GROUP, STAGE, ...)                     \
  BENCHMARK(run_avx512<GROUP, Stage::STAGE __VA_OPT__(, ) __VA_ARGS__>)

SOFTSTEP_AVX512_BENCH(BallJointGroup, Prepare)->Name("BallJointGroup/Prepare/avx512")->Apply(scenes);
SOFTSTEP_AVX512_BENCH(BallJointGroup, WarmStart)
    ->Name("BallJointGroup/WarmStart/avx512")
    ->Apply(scenes);
SOFTSTEP_AVX512_BENCH(BallJointGroup, Solve)->Name("BallJointGroup/Solve/avx512")->Apply(scenes);
SOFTSTEP_AVX512_BENCH(BallJointGroup, Relax)->Name("BallJointGroup/Relax/avx512")->Apply(scenes);
SOFTSTEP_AVX512_BENCH(DistanceJointGroup, Prepare)
    ->Name("DistanceJointGroup/Prepare/avx512")
    ->Apply(scenes);
SOFTSTEP_AVX512_BENCH(DistanceJointGroup, Solve)
    ->Name("DistanceJointGroup/Solve/avx512")
    ->Apply(scenes);
SOFTSTEP_AVX512_BENCH(DistanceJointGroup, Relax)
    ->Name("DistanceJointGroup/Relax/avx512")
    ->Apply(scenes);
SOFTSTEP_AVX512_BENCH(RevoluteJointGroup, Solve)
    ->Name("RevoluteJointGroup/Solve/avx512")
    ->Apply(scenes);
SOFTSTEP_AVX512_BENCH(RevoluteJointGroup, Relax)
    ->Name("RevoluteJointGroup/Relax/avx512")
    ->Apply(scenes);
SOFTSTEP_AVX512_BENCH(PrismaticJointGroup, Solve)
    ->Name("PrismaticJointGroup/Solve/avx512")
    ->Apply(scenes);
SOFTSTEP_AVX512_BENCH(PrismaticJointGroup, Relax)
    ->Name("PrismaticJointGroup/Relax/avx512")
    ->Apply(scenes);
SOFTSTEP_AVX512_BENCH(WeldJointGroup, Solve)->Name("WeldJointGroup/Solve/avx512")->Apply(scenes);
SOFTSTEP_AVX512_BENCH(WeldJointGroup, Relax)->Name("WeldJointGroup/Relax/avx512")->Apply(scenes);
SOFTSTEP_AVX512_BENCH(RevoluteJointGroup, Solve, kGeneralKernel, kAllAxisParts)
    ->Name("RevoluteJointGroup/Solve/avx512/all_parts")
    ->Apply(scenes);
SOFTSTEP_AVX512_BENCH(PrismaticJointGroup, Solve, kGeneralKernel, kAllAxisParts)
    ->Name("PrismaticJointGroup/Solve/avx512/all_parts")
    ->Apply(scenes);
SOFTSTEP_AVX512_BENCH(BallJointGroup, Solve, kRigid)
    ->Name("BallJointGroup/Solve/avx512/rigid")
    ->Apply(scenes);
SOFTSTEP_AVX512_BENCH(BallJointGroup, Relax, kRigid)
    ->Name("BallJointGroup/Relax/avx512/rigid")
    ->Apply(scenes);
SOFTSTEP_AVX512_BENCH(DistanceJointGroup, Solve, kRigid)
    ->Name("DistanceJointGroup/Solve/avx512/rigid")
    ->Apply(scenes);
SOFTSTEP_AVX512_BENCH(DistanceJointGroup, Relax, kRigid)
    ->Name("DistanceJointGroup/Relax/avx512/rigid")
    ->Apply(scenes);

// The contact kernels (contact_kernel_benchmark.cpp) at 16 lanes.
template <ContactPass P>
void run_contacts_avx512(benchmark::State& state) {
  if (!cpu_has_avx512()) {
    state.SkipWithError("skipped: this CPU lacks AVX-512 (F, CD, DQ, BW and VL)");
    return;
  }
  run_contacts<Avx512, P>(state);
}
BENCHMARK(run_contacts_avx512<ContactPass::Solve>)
    ->Name("ContactLanes/Solve/avx512")
    ->Apply(pyramid_bases);
BENCHMARK(run_contacts_avx512<ContactPass::Relax>)
    ->Name("ContactLanes/Relax/avx512")
    ->Apply(pyramid_bases);

}  // namespace
}  // namespace softstep::simd
