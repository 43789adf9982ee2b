// The Pareto front of (time, error) points: the settings no other setting beats on both.
#pragma once

#include <span>
#include <vector>

namespace softstep::tool {

struct CostPoint {
  double ms;     // time per step
  double error;  // any error measure, smaller is better; NaN or inf for a run that blew up
};

// For each point, whether it is on the front: no other point is at least as fast and at least
// as accurate while strictly better in one. Equal points are both on it; a point whose error
// is not finite never is.
std::vector<bool> pareto_front(std::span<const CostPoint> points);

// The most accurate point that takes at most budget_ms (the faster on a tie), or -1 if none.
int most_accurate_within(std::span<const CostPoint> points, double budget_ms);

}  // namespace softstep::tool
