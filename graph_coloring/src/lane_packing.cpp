#include <cstddef>

#include "softstep/graph_coloring/graph_coloring.hpp"

namespace softstep::graph_coloring {

std::vector<std::uint32_t> pack_lanes(std::span<const std::uint32_t> members, int width,
                                      std::uint32_t padding) {
  const std::size_t w = static_cast<std::size_t>(width);
  std::vector<std::uint32_t> lanes(members.begin(), members.end());
  lanes.resize((members.size() + w - 1) / w * w, padding);
  return lanes;
}

}  // namespace softstep::graph_coloring
