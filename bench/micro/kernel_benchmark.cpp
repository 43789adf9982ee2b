// Each joint kernel alone (prepare, warm start, solve, relax), at scalar, SSE (4) and AVX2
// (8) width (AVX-512, 16 lanes: kernel_benchmark_avx512.cpp), on chains of 10,000 and 100,000 links and on 1,000 chains of 100 links. The
// angular types run twice: with their locks only, and with every part of their free axis
// (limit, motor, spring), so that the difference is what those parts cost. The swing-twist
// joint runs with a ragdoll's parts (cone, twist limits, friction) and with all of them. Uses only
// simd/ and graph_coloring/: the layers the issue asks to benchmark alone. The figure to
// read is ns_per_row: time per constraint row for one pass of the kernel over all joints.
//
// Compiled with -mavx2 (and -mfma with SOFTSTEP_USE_FMA): it runs only on AVX2 machines.
#include "kernel_bench_support.hpp"

namespace softstep::simd {
namespace {

using Sse = xsimd::batch<float, xsimd::sse4_2>;
using Avx2 = xsimd::batch<float, xsimd::avx2>;

#define SOFTSTEP_KERNEL_BENCH(GROUP, STAGE)                                                     \
  BENCHMARK(run<float, GROUP, Stage::STAGE>)->Name(#GROUP "/" #STAGE "/scalar")->Apply(scenes); \
  BENCHMARK(run<Sse, GROUP, Stage::STAGE>)->Name(#GROUP "/" #STAGE "/sse")->Apply(scenes);      \
  BENCHMARK(run<Avx2, GROUP, Stage::STAGE>)->Name(#GROUP "/" #STAGE "/avx2")->Apply(scenes)

SOFTSTEP_KERNEL_BENCH(BallJointGroup, Prepare);
SOFTSTEP_KERNEL_BENCH(BallJointGroup, WarmStart);
SOFTSTEP_KERNEL_BENCH(BallJointGroup, Solve);
SOFTSTEP_KERNEL_BENCH(BallJointGroup, Relax);
SOFTSTEP_KERNEL_BENCH(DistanceJointGroup, Prepare);
SOFTSTEP_KERNEL_BENCH(DistanceJointGroup, Solve);
SOFTSTEP_KERNEL_BENCH(DistanceJointGroup, Relax);
SOFTSTEP_KERNEL_BENCH(RevoluteJointGroup, Solve);
SOFTSTEP_KERNEL_BENCH(RevoluteJointGroup, Relax);
SOFTSTEP_KERNEL_BENCH(PrismaticJointGroup, Solve);
SOFTSTEP_KERNEL_BENCH(PrismaticJointGroup, Relax);
SOFTSTEP_KERNEL_BENCH(WeldJointGroup, Solve);
SOFTSTEP_KERNEL_BENCH(WeldJointGroup, Relax);
SOFTSTEP_KERNEL_BENCH(WheelJointGroup, Solve);
SOFTSTEP_KERNEL_BENCH(WheelJointGroup, Relax);
SOFTSTEP_KERNEL_BENCH(MotorJointGroup, Solve);  // rigid halves; never relaxed

// The angular types with every part of their free axis (limit, motor, spring).
#define SOFTSTEP_ALL_PARTS_BENCH(GROUP, STAGE)                              \
  BENCHMARK(run<float, GROUP, Stage::STAGE, kGeneralKernel, kAllAxisParts>) \
      ->Name(#GROUP "/" #STAGE "/scalar/all_parts")                         \
      ->Apply(scenes);                                                      \
  BENCHMARK(run<Avx2, GROUP, Stage::STAGE, kGeneralKernel, kAllAxisParts>)  \
      ->Name(#GROUP "/" #STAGE "/avx2/all_parts")                           \
      ->Apply(scenes)
SOFTSTEP_ALL_PARTS_BENCH(RevoluteJointGroup, Solve);
SOFTSTEP_ALL_PARTS_BENCH(PrismaticJointGroup, Solve);
SOFTSTEP_ALL_PARTS_BENCH(WheelJointGroup, Solve);
// The motor joint with both halves soft.
constexpr std::uint32_t kMotorSoft = kMotorLinearSoft | kMotorAngularSoft;
BENCHMARK(run<float, MotorJointGroup, Stage::Solve, kGeneralKernel, kMotorSoft>)
    ->Name("MotorJointGroup/Solve/scalar/soft")
    ->Apply(scenes);
BENCHMARK(run<Avx2, MotorJointGroup, Stage::Solve, kGeneralKernel, kMotorSoft>)
    ->Name("MotorJointGroup/Solve/avx2/soft")
    ->Apply(scenes);

#define SOFTSTEP_SWING_TWIST_BENCH(STAGE, PARTS, SUFFIX)                                       \
  BENCHMARK(run<float, SwingTwistJointGroup, Stage::STAGE, kGeneralKernel, PARTS>)            \
      ->Name("SwingTwistJointGroup/" #STAGE "/scalar" SUFFIX)                                  \
      ->Apply(scenes);                                                                         \
  BENCHMARK(run<Sse, SwingTwistJointGroup, Stage::STAGE, kGeneralKernel, PARTS>)              \
      ->Name("SwingTwistJointGroup/" #STAGE "/sse" SUFFIX)                                     \
      ->Apply(scenes);                                                                         \
  BENCHMARK(run<Avx2, SwingTwistJointGroup, Stage::STAGE, kGeneralKernel, PARTS>)             \
      ->Name("SwingTwistJointGroup/" #STAGE "/avx2" SUFFIX)                                    \
      ->Apply(scenes)
SOFTSTEP_SWING_TWIST_BENCH(Solve, kRagdollParts, "");
SOFTSTEP_SWING_TWIST_BENCH(Relax, kRagdollParts, "");
SOFTSTEP_SWING_TWIST_BENCH(Solve, kAllSwingTwistParts, "/all_parts");

// The rigid variant of the same kernels (no per-lane spring switch, no limit rows).
#define SOFTSTEP_RIGID_BENCH(GROUP, STAGE)           \
  BENCHMARK(run<float, GROUP, Stage::STAGE, kRigid>) \
      ->Name(#GROUP "/" #STAGE "/scalar/rigid")      \
      ->Apply(scenes);                               \
  BENCHMARK(run<Avx2, GROUP, Stage::STAGE, kRigid>)  \
      ->Name(#GROUP "/" #STAGE "/avx2/rigid")        \
      ->Apply(scenes)
SOFTSTEP_RIGID_BENCH(BallJointGroup, Solve);
SOFTSTEP_RIGID_BENCH(BallJointGroup, Relax);
SOFTSTEP_RIGID_BENCH(DistanceJointGroup, Solve);
SOFTSTEP_RIGID_BENCH(DistanceJointGroup, Relax);

}  // namespace
}  // namespace softstep::simd

BENCHMARK_MAIN();
