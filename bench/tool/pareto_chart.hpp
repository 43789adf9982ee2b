// A log-log scatter chart of error against time per step as a self-contained SVG, with the
// Pareto front drawn through its points and labelled.
#pragma once

#include <string>
#include <vector>

#include "tool/pareto.hpp"

namespace softstep::tool {

struct ChartText {
  std::string title;
  std::string x_axis;  // with its unit
  std::string y_axis;  // with its unit
};

// labels[i] names point i (written next to it when it is on the front).
std::string pareto_svg(const std::vector<CostPoint>& points, const std::vector<bool>& front,
                       const std::vector<std::string>& labels, const ChartText& text);

}  // namespace softstep::tool
