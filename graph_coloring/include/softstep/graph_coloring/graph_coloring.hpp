// Colours constraints so that no two constraints of one colour share a blocking body; the
// kernels then solve a colour's constraints in parallel lanes without write conflicts.
//
// Bodies that are never written by the solver (static and kinematic ones) are passed as
// kNonBlocking and never block a colour. The number of colours is bounded (kColorCount); a
// constraint no colour can take goes to the overflow set, which the solver runs last, in
// order, one constraint at a time.
//
// Incremental and deterministic: add() takes the first colour free for both bodies, remove()
// frees the bodies in that colour and swaps the colour's last member into the hole. The
// result depends only on the sequence of add/remove calls.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace softstep::graph_coloring {

// Why 24: a colour is worth a pass only when it fills SIMD lanes on both threads. A body
// joined to more than ~24 others is a hub whose constraints cannot run in parallel anyway;
// they are cheaper in the overflow set than as two dozen nearly empty colours. Chains need
// 2 colours and grids 4, so ordinary scenes never reach the bound.
inline constexpr int kColorCount = 24;
inline constexpr int kOverflow = -1;
inline constexpr std::uint32_t kNonBlocking = 0xFFFFFFFFu;

struct ColoringStats {
  int colors_used = 0;                                 // colours holding at least one constraint
  std::array<std::uint32_t, kColorCount> per_color{};  // constraints in each colour
  std::uint32_t overflow = 0;                          // constraints in the overflow set
  std::uint32_t lane_groups = 0;                       // groups of `width` lanes over all colours
  double lane_fill = 0.0;  // coloured constraints / (lane_groups * width)
};

class GraphColoring {
 public:
  // Colours `constraint` (any id, used as an index: keep ids dense). Returns its colour or
  // kOverflow. The constraint must not be present.
  int add(std::uint32_t constraint, std::uint32_t body_a, std::uint32_t body_b);
  // Removes a present constraint.
  void remove(std::uint32_t constraint);
  void clear();

  bool contains(std::uint32_t constraint) const;
  int color_of(std::uint32_t constraint) const;  // precondition: contains()
  std::span<const std::uint32_t> members(int color) const { return members_[color]; }
  std::span<const std::uint32_t> overflow() const { return overflow_; }
  std::size_t size() const { return count_; }

  ColoringStats stats(int lane_width) const;

 private:
  static constexpr int kAbsent = -2;
  struct Entry {
    int color = kAbsent;
    std::uint32_t position = 0;  // index in members_[color] or overflow_
    std::uint32_t body_a = kNonBlocking;
    std::uint32_t body_b = kNonBlocking;
  };
  bool body_free(int color, std::uint32_t body) const;
  void set_body(int color, std::uint32_t body, bool used);

  std::vector<Entry> entries_;
  std::array<std::vector<std::uint64_t>, kColorCount> used_bodies_;  // bitset per colour
  std::array<std::vector<std::uint32_t>, kColorCount> members_;
  std::vector<std::uint32_t> overflow_;
  std::size_t count_ = 0;
};

// Lays out one colour's members in groups of `width` lanes; the last group is filled with
// `padding` (the solver's static dummy constraint slot). Returns a multiple of width.
std::vector<std::uint32_t> pack_lanes(std::span<const std::uint32_t> members, int width,
                                      std::uint32_t padding);

}  // namespace softstep::graph_coloring
