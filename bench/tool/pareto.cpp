#include "tool/pareto.hpp"

#include <cmath>

namespace softstep::tool {

std::vector<bool> pareto_front(std::span<const CostPoint> points) {
  std::vector<bool> front(points.size(), false);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const CostPoint& p = points[i];
    if (!std::isfinite(p.error) || !std::isfinite(p.ms)) continue;
    bool dominated = false;
    for (const CostPoint& q : points) {
      if (!std::isfinite(q.error)) continue;
      if (q.ms <= p.ms && q.error <= p.error && (q.ms < p.ms || q.error < p.error)) {
        dominated = true;
        break;
      }
    }
    front[i] = !dominated;
  }
  return front;
}

int most_accurate_within(std::span<const CostPoint> points, double budget_ms) {
  int best = -1;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const CostPoint& p = points[i];
    if (!std::isfinite(p.error) || p.ms > budget_ms) continue;
    const auto b = static_cast<std::size_t>(best);
    if (best < 0 || p.error < points[b].error ||
        (p.error == points[b].error && p.ms < points[b].ms)) {
      best = static_cast<int>(i);
    }
  }
  return best;
}

}  // namespace softstep::tool
