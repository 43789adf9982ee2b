// The threads of one step. A step with one thread never touches OpenMP; with more, all of
// them run the same stages and meet at team_barrier (libgomp's barrier inside the step's one
// parallel region).
#pragma once

#include <chrono>

#include "solver/joint_batches.hpp"

namespace softstep::solver {

inline void team_barrier(const Share& share) {
  if (share.threads <= 1) return;
  if (share.barrier_wait_us == nullptr) {
#pragma omp barrier
    return;
  }
  const auto start = std::chrono::steady_clock::now();
#pragma omp barrier
  *share.barrier_wait_us +=
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace softstep::solver
