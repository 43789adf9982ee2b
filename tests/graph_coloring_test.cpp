// Colouring invariants on thousands of random graphs, the colour counts of chains and grids,
// and incremental updates equal to a replay of the same history.
#include "softstep/graph_coloring/graph_coloring.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>

namespace softstep::graph_coloring {
namespace {

struct Edge {
  std::uint32_t a, b;  // kNonBlocking for a static body
};

// Every present constraint is in exactly one colour or in the overflow, and no colour holds
// two constraints sharing a blocking body.
void check_invariants(const GraphColoring& g, const std::vector<Edge>& edges,
                      const std::vector<bool>& present) {
  std::vector<int> seen(edges.size(), 0);
  for (int c = 0; c < kColorCount; ++c) {
    std::set<std::uint32_t> bodies;
    for (std::uint32_t id : g.members(c)) {
      ++seen[id];
      ASSERT_EQ(g.color_of(id), c);
      for (std::uint32_t body : {edges[id].a, edges[id].b}) {
        if (body == kNonBlocking) continue;
        ASSERT_TRUE(bodies.insert(body).second) << "colour " << c << " shares body " << body;
      }
    }
  }
  for (std::uint32_t id : g.overflow()) {
    ++seen[id];
    ASSERT_EQ(g.color_of(id), kOverflow);
  }
  for (std::size_t i = 0; i < edges.size(); ++i)
    ASSERT_EQ(seen[i], present[i] ? 1 : 0) << "constraint " << i;
}

std::vector<Edge> random_graph(std::mt19937& rng, int kind) {
  std::uniform_int_distribution<int> size(1, 300);
  const int bodies = size(rng) + 1;
  const int count = size(rng);
  std::uniform_int_distribution<std::uint32_t> body(0, static_cast<std::uint32_t>(bodies - 1));
  std::bernoulli_distribution is_static(0.15);
  std::vector<Edge> edges;
  for (int i = 0; i < count; ++i) {
    Edge e{body(rng), body(rng)};
    if (kind == 1) e.a = static_cast<std::uint32_t>(i % 3);  // hubs: three bodies touch everything
    if (e.a == e.b) e.b = (e.b + 1) % static_cast<std::uint32_t>(bodies + 1);
    if (is_static(rng)) e.a = kNonBlocking;
    if (is_static(rng)) e.b = kNonBlocking;
    edges.push_back(e);
  }
  return edges;
}

TEST(GraphColoring, RandomGraphsKeepTheInvariants) {
  std::mt19937 rng(12345);
  int hubs_seen = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const std::vector<Edge> edges = random_graph(rng, trial % 2);
    GraphColoring g;
    std::vector<bool> present(edges.size(), false);
    for (std::uint32_t i = 0; i < edges.size(); ++i) {
      g.add(i, edges[i].a, edges[i].b);
      present[i] = true;
    }
    check_invariants(g, edges, present);
    // A body in more constraints than there are colours forces an overflow.
    std::map<std::uint32_t, int> degree;
    for (const Edge& e : edges) {
      if (e.a != kNonBlocking) ++degree[e.a];
      if (e.b != kNonBlocking) ++degree[e.b];
    }
    const bool hub =
        std::ranges::any_of(degree, [](const auto& d) { return d.second > kColorCount; });
    if (hub) {
      EXPECT_GT(g.overflow().size(), 0u);
    }
    hubs_seen += hub ? 1 : 0;
  }
  EXPECT_GT(hubs_seen, 100);  // the generator really makes hubs
}

TEST(GraphColoring, StaticBodiesNeverBlock) {
  GraphColoring g;
  for (std::uint32_t i = 0; i < 100; ++i) EXPECT_EQ(g.add(i, kNonBlocking, i), 0);
  EXPECT_EQ(g.stats(8).colors_used, 1);
}

TEST(GraphColoring, ChainUsesTwoColors) {
  GraphColoring g;
  g.add(0, kNonBlocking, 0);
  for (std::uint32_t i = 1; i < 1000; ++i) g.add(i, i - 1, i);
  const ColoringStats s = g.stats(8);
  EXPECT_EQ(s.colors_used, 2);
  EXPECT_EQ(s.overflow, 0u);
  EXPECT_EQ(s.per_color[0], 500u);
  EXPECT_EQ(s.per_color[1], 500u);
}

TEST(GraphColoring, GridUsesAtMostFourColors) {
  const std::uint32_t n = 50;
  GraphColoring g;
  std::uint32_t id = 0;
  std::vector<Edge> edges;
  for (std::uint32_t r = 0; r < n; ++r) {
    for (std::uint32_t c = 0; c < n; ++c) {
      const std::uint32_t body = r * n + c;
      if (c + 1 < n) {
        edges.push_back({body, body + 1});
        g.add(id++, body, body + 1);
      }
      if (r + 1 < n) {
        edges.push_back({body, body + n});
        g.add(id++, body, body + n);
      }
    }
  }
  const ColoringStats s = g.stats(8);
  EXPECT_LE(s.colors_used, 4);
  EXPECT_EQ(s.overflow, 0u);
  check_invariants(g, edges, std::vector<bool>(edges.size(), true));
}

TEST(GraphColoring, IncrementalEqualsReplayOfTheSameHistory) {
  std::mt19937 rng(99);
  for (int trial = 0; trial < 200; ++trial) {
    const std::vector<Edge> edges = random_graph(rng, trial % 2);
    std::vector<bool> present(edges.size(), false);
    GraphColoring live;
    struct Op {
      bool add;
      std::uint32_t id;
    };
    std::vector<Op> history;
    std::bernoulli_distribution remove(0.3);
    for (std::uint32_t i = 0; i < edges.size(); ++i) {
      live.add(i, edges[i].a, edges[i].b);
      present[i] = true;
      history.push_back({true, i});
      if (remove(rng)) {
        std::uniform_int_distribution<std::uint32_t> pick(0, i);
        const std::uint32_t victim = pick(rng);
        if (present[victim]) {
          live.remove(victim);
          present[victim] = false;
          history.push_back({false, victim});
        }
      }
    }
    check_invariants(live, edges, present);
    GraphColoring replay;
    for (const Op& op : history) {
      if (op.add) {
        replay.add(op.id, edges[op.id].a, edges[op.id].b);
      } else {
        replay.remove(op.id);
      }
    }
    for (int c = 0; c < kColorCount; ++c) {
      ASSERT_TRUE(std::ranges::equal(live.members(c), replay.members(c)));
    }
    ASSERT_TRUE(std::ranges::equal(live.overflow(), replay.overflow()));
  }
}

TEST(GraphColoring, RemovalFreesTheBodies) {
  GraphColoring g;
  for (std::uint32_t i = 0; i < kColorCount; ++i)
    g.add(i, 0, i + 1);  // hub body 0 fills every colour
  EXPECT_EQ(g.add(kColorCount, 0, 100), kOverflow);
  g.remove(5);
  const int color = g.add(5, 0, 200);
  EXPECT_EQ(color, 5);  // the only colour where the hub is free again
  EXPECT_EQ(g.color_of(5), 5);
}

TEST(LanePacking, PadsTheLastGroup) {
  const std::vector<std::uint32_t> members{1, 2, 3, 4, 5};
  const auto lanes = pack_lanes(members, 4, 99);
  EXPECT_EQ(lanes, (std::vector<std::uint32_t>{1, 2, 3, 4, 5, 99, 99, 99}));
  EXPECT_TRUE(pack_lanes({}, 8, 0).empty());
  const ColoringStats s = [] {
    GraphColoring g;
    for (std::uint32_t i = 0; i < 5; ++i) g.add(i, kNonBlocking, i);
    return g.stats(4);
  }();
  EXPECT_EQ(s.lane_groups, 2u);
  EXPECT_DOUBLE_EQ(s.lane_fill, 5.0 / 8.0);
}

}  // namespace
}  // namespace softstep::graph_coloring
