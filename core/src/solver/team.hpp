// The threads of one step. A step with one thread never touches OpenMP; with more, all of
// them run the same stages inside one parallel region and meet at team_barrier.
//
// Why not `#pragma omp barrier`: libgomp's barrier spins for a long time before it sleeps.
// When another process holds one of the two cores, the thread that arrived first spins away
// the time slice the late thread needs, and a step with a barrier per colour became 30-60x
// slower (TOOLCHAIN.md). This barrier spins for a few microseconds (enough when both threads
// run: an idle-machine barrier takes 0.4-1 us) and then sleeps on a futex.
#pragma once

#include <immintrin.h>

#include <atomic>
#include <chrono>

#include "solver/joint_batches.hpp"

namespace softstep::solver {

class StepBarrier {
 public:
  explicit StepBarrier(int threads) : threads_(threads) {}

  void wait() {
    const unsigned generation = generation_.load(std::memory_order_acquire);
    if (arrived_.fetch_add(1, std::memory_order_acq_rel) + 1 == threads_) {
      arrived_.store(0, std::memory_order_relaxed);
      generation_.fetch_add(1, std::memory_order_release);
      generation_.notify_all();
      return;
    }
    for (int i = 0; i < kSpins; ++i) {
      if (generation_.load(std::memory_order_acquire) != generation) return;
      _mm_pause();
    }
    generation_.wait(generation, std::memory_order_acquire);  // returns once it has changed
  }

 private:
  static constexpr int kSpins = 256;  // a few microseconds of pause instructions
  const int threads_;
  std::atomic<int> arrived_{0};
  std::atomic<unsigned> generation_{0};
};

inline void team_barrier(const Share& share) {
  if (share.threads <= 1) return;
  if (share.barrier_wait_us == nullptr) {
    share.barrier->wait();
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  share.barrier->wait();
  *share.barrier_wait_us +=
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace softstep::solver
