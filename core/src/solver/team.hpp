// The threads of one step. A step with one thread never touches OpenMP; with more, all of
// them run the same stages and meet at team_barrier (libgomp's barrier inside the step's one
// parallel region).
#pragma once

#include "solver/joint_batches.hpp"

namespace softstep::solver {

inline void team_barrier(const Share& share) {
  if (share.threads > 1) {
#pragma omp barrier
  }
}

}  // namespace softstep::solver
