#include "softstep/graph_coloring/graph_coloring.hpp"

#include <cassert>

namespace softstep::graph_coloring {

bool GraphColoring::body_free(int color, std::uint32_t body) const {
  if (body == kNonBlocking) return true;
  const auto& bits = used_bodies_[color];
  const std::size_t word = body >> 6;
  return word >= bits.size() || ((bits[word] >> (body & 63u)) & 1u) == 0;
}

void GraphColoring::set_body(int color, std::uint32_t body, bool used) {
  if (body == kNonBlocking) return;
  auto& bits = used_bodies_[color];
  const std::size_t word = body >> 6;
  if (word >= bits.size()) bits.resize(word + 1, 0);
  const std::uint64_t mask = std::uint64_t{1} << (body & 63u);
  bits[word] = used ? (bits[word] | mask) : (bits[word] & ~mask);
}

int GraphColoring::add(std::uint32_t constraint, std::uint32_t body_a, std::uint32_t body_b) {
  if (constraint >= entries_.size()) entries_.resize(std::size_t{constraint} + 1);
  Entry& e = entries_[constraint];
  assert(e.color == kAbsent);
  e.body_a = body_a;
  e.body_b = body_b;
  ++count_;
  // A constraint whose bodies are both non-blocking could go anywhere; colour 0 keeps it
  // with the bulk. Otherwise the first colour free for both bodies.
  for (int c = 0; c < kColorCount; ++c) {
    if (body_free(c, body_a) && body_free(c, body_b)) {
      set_body(c, body_a, true);
      set_body(c, body_b, true);
      e.color = c;
      e.position = static_cast<std::uint32_t>(members_[c].size());
      members_[c].push_back(constraint);
      return c;
    }
  }
  e.color = kOverflow;
  e.position = static_cast<std::uint32_t>(overflow_.size());
  overflow_.push_back(constraint);
  return kOverflow;
}

void GraphColoring::remove(std::uint32_t constraint) {
  assert(contains(constraint));
  Entry& e = entries_[constraint];
  std::vector<std::uint32_t>& list = e.color == kOverflow ? overflow_ : members_[e.color];
  if (e.color != kOverflow) {
    set_body(e.color, e.body_a, false);
    set_body(e.color, e.body_b, false);
  }
  const std::uint32_t last = list.back();
  list[e.position] = last;
  entries_[last].position = e.position;
  list.pop_back();
  e = Entry{};
  --count_;
}

void GraphColoring::clear() {
  *this = GraphColoring{};
}

bool GraphColoring::contains(std::uint32_t constraint) const {
  return constraint < entries_.size() && entries_[constraint].color != kAbsent;
}

int GraphColoring::color_of(std::uint32_t constraint) const {
  return entries_[constraint].color;
}

ColoringStats GraphColoring::stats(int lane_width) const {
  ColoringStats s;
  std::size_t colored = 0;
  for (int c = 0; c < kColorCount; ++c) {
    const auto n = static_cast<std::uint32_t>(members_[c].size());
    s.per_color[c] = n;
    if (n == 0) continue;
    ++s.colors_used;
    colored += n;
    s.lane_groups +=
        (n + static_cast<std::uint32_t>(lane_width) - 1) / static_cast<std::uint32_t>(lane_width);
  }
  s.overflow = static_cast<std::uint32_t>(overflow_.size());
  s.lane_fill = s.lane_groups == 0 ? 1.0
                                   : static_cast<double>(colored) /
                                         (static_cast<double>(s.lane_groups) * lane_width);
  return s;
}

}  // namespace softstep::graph_coloring
