// The contact kernels alone (solve and relax passes of simd/contact_kernel.hpp) over the lane
// groups of a pyramid: the manifolds the tool's `pyramid` scene gets from Bullet, built here
// from its geometry (1 m boxes of 100 kg, base N, each row offset by half a box, a static
// ground): N on the ground, N(N-1)/2 side by side, N(N-1) on the two boxes below, every one a
// 4-point face contact with friction 0.6. Coloured with graph_coloring (the ground binds
// nothing) and packed kWidth<L> to a group, the solver's layout. Included by
// contact_kernel_benchmark.cpp (scalar, SSE, AVX2) and contact_kernel_benchmark_avx512.cpp:
// internal linkage, so neither file's copy, compiled for its instruction set, stands in for
// the other's. The figures: ns_per_row (normal + 2 friction rows per point, one pass) and
// x_scalar, the speed-up over the scalar kernel on the same scene measured earlier in the
// same run.
#pragma once

#include <benchmark/benchmark.h>

#include <array>
#include <ctime>
#include <string>
#include <vector>

#include "kernel_bench_support.hpp"
#include "softstep/simd/contact_kernel.hpp"

namespace softstep::simd {

// Outside the anonymous namespace: the two functions below take it across files.
enum class ContactPass { Solve, Relax };

// The scalar kernel's ns per row on the pyramid of `base`, for x_scalar: the scalar
// benchmark's own figure when it ran earlier in this run, else measured now (about 0.2 s).
// Defined in contact_kernel_benchmark.cpp, whose scalar code is compiled without AVX-512.
void remember_scalar_ns_per_row(ContactPass pass, int base, double ns);
double scalar_ns_per_row(ContactPass pass, int base);

namespace {

struct PyramidManifold {
  std::int32_t body_a, body_b;  // kDummyBody for the ground
  std::array<float, 3> normal;  // from A to B
  std::array<std::array<float, 3>, 2> tangent;
  std::array<std::array<float, 3>, kContactPoints> r_a, r_b;
  float base_separation;
};

struct PyramidContacts {
  std::vector<PyramidManifold> manifolds;
  int boxes = 0;
};

// Box k of row r sits at x = k - (count - 1) / 2, y = r + 0.5 (as bench/contacts/ builds it);
// body 1 + its index in row order. The corners of each touching patch are the points.
PyramidContacts pyramid_contacts(int base) {
  PyramidContacts p;
  std::vector<std::array<float, 3>> centre{{0.0f, -1.0f, 0.0f}};  // the ground, under the dummy
  std::vector<std::vector<std::int32_t>> rows;
  for (int r = 0; r < base; ++r) {
    const int count = base - r;
    auto& row = rows.emplace_back();
    for (int k = 0; k < count; ++k) {
      row.push_back(static_cast<std::int32_t>(centre.size()));
      centre.push_back({float(k) - 0.5f * float(count - 1), float(r) + 0.5f, 0.0f});
    }
  }
  p.boxes = static_cast<int>(centre.size()) - 1;
  const auto add = [&](std::int32_t a, std::int32_t b, std::array<float, 3> n,
                       const std::array<std::array<float, 3>, kContactPoints>& points,
                       float separation) {
    PyramidManifold m;
    m.body_a = a == 0 ? kDummyBody : a;
    m.body_b = b;
    m.normal = n;
    // Right-handed tangents of the two normals the pyramid has (up, +x).
    m.tangent = n[1] != 0.0f ? std::array<std::array<float, 3>, 2>{{{0, 0, 1}, {1, 0, 0}}}
                             : std::array<std::array<float, 3>, 2>{{{0, 1, 0}, {0, 0, 1}}};
    float centre_gap = 0.0f;  // n . (c_b - c_a)
    for (int k = 0; k < 3; ++k) centre_gap += n[k] * (centre[b][k] - centre[a][k]);
    for (int i = 0; i < kContactPoints; ++i) {
      for (int k = 0; k < 3; ++k) {
        m.r_a[i][k] = points[i][k] - centre[a][k];
        m.r_b[i][k] = points[i][k] - centre[b][k];
      }
    }
    // separation - n . (r_b - r_a), and r_b - r_a = c_a - c_b at every point.
    m.base_separation = separation + centre_gap;
    p.manifolds.push_back(m);
  };
  // Resting: a few millimetres of penetration on the supports, touching at the sides.
  constexpr float kPenetration = -0.005f;
  const auto flat = [](float x0, float x1, float y) {
    return std::array<std::array<float, 3>, kContactPoints>{
        {{x0, y, -0.5f}, {x1, y, -0.5f}, {x1, y, 0.5f}, {x0, y, 0.5f}}};
  };
  for (int r = 0; r < base; ++r) {
    const auto& row = rows[static_cast<std::size_t>(r)];
    for (std::size_t k = 0; k < row.size(); ++k) {
      const std::int32_t box = row[k];
      const float x = centre[static_cast<std::size_t>(box)][0];
      const float bottom = float(r);
      if (r == 0) {
        add(0, box, {0, 1, 0}, flat(x - 0.5f, x + 0.5f, bottom), kPenetration);
      } else {
        const auto& below = rows[static_cast<std::size_t>(r - 1)];
        add(below[k], box, {0, 1, 0}, flat(x - 0.5f, x, bottom), kPenetration);
        add(below[k + 1], box, {0, 1, 0}, flat(x, x + 0.5f, bottom), kPenetration);
      }
      if (k + 1 < row.size()) {
        const float face = x + 0.5f;
        add(box, row[k + 1], {1, 0, 0},
            {{{face, bottom, -0.5f}, {face, bottom + 1, -0.5f}, {face, bottom + 1, 0.5f},
              {face, bottom, 0.5f}}},
            0.0f);
      }
    }
  }
  return p;
}

template <int W>
struct PackedContacts {
  std::vector<std::vector<ContactLanes<W>>> colors;
  std::vector<VelocityRecord> velocity;
  std::vector<DeltaRecord> delta;
  std::vector<MassRecord> mass;
  double rows = 0.0;  // per pass: 3 per point
  BodyArrays arrays() { return {velocity.data(), delta.data(), mass.data()}; }
};

template <int W>
PackedContacts<W> pack_pyramid(int base) {
  const PyramidContacts p = pyramid_contacts(base);
  PackedContacts<W> out;
  const std::size_t bodies = static_cast<std::size_t>(p.boxes) + 1;
  // Settling boxes: a little speed down and a little spin, so no row is trivially idle.
  out.velocity.assign(bodies, VelocityRecord{{0.0f, -0.05f, 0.0f}, {0.0f, 0.0f, 0.01f}, {}});
  out.delta.assign(bodies, DeltaRecord{{0, 0, 0}, {0, 0, 0, 1}, 0});
  const float inv_inertia = 6.0f / 100.0f;  // a 1 m cube of 100 kg: I = m (1 + 1) / 12
  out.mass.assign(bodies, MassRecord{0.01f, {inv_inertia, inv_inertia, inv_inertia, 0, 0, 0}, 0});
  out.velocity[kDummyBody] = VelocityRecord{};
  out.mass[kDummyBody] = MassRecord{};
  graph_coloring::GraphColoring coloring;
  for (std::size_t i = 0; i < p.manifolds.size(); ++i) {
    const PyramidManifold& m = p.manifolds[i];
    coloring.add(static_cast<std::uint32_t>(i),
                 m.body_a == kDummyBody ? graph_coloring::kNonBlocking
                                        : static_cast<std::uint32_t>(m.body_a),
                 static_cast<std::uint32_t>(m.body_b));
  }
  constexpr std::uint32_t kPad = 0xFFFFFFFFu;
  for (int c = 0; c < graph_coloring::kColorCount; ++c) {
    if (coloring.members(c).empty()) continue;
    const auto lanes = graph_coloring::pack_lanes(coloring.members(c), W, kPad);
    auto& groups = out.colors.emplace_back(lanes.size() / W);
    for (auto& g : groups) {  // padding lanes: the dummy body, no points
      std::fill(std::begin(g.id), std::end(g.id), kPaddingLane);
      std::fill(std::begin(g.body_a), std::end(g.body_a), kDummyBody);
      std::fill(std::begin(g.body_b), std::end(g.body_b), kDummyBody);
      g.points = 0;
    }
    for (std::size_t i = 0; i < lanes.size(); ++i) {
      if (lanes[i] == kPad) continue;
      ContactLanes<W>& g = groups[i / W];
      const int lane = static_cast<int>(i % W);
      const PyramidManifold& m = p.manifolds[lanes[i]];
      g.id[lane] = lanes[i];
      g.body_a[lane] = m.body_a;
      g.body_b[lane] = m.body_b;
      g.point_count[lane] = float(kContactPoints);
      g.points = kContactPoints;
      for (int k = 0; k < 3; ++k) {
        g.normal[k][lane] = m.normal[k];
        g.tangent[0][k][lane] = m.tangent[0][k];
        g.tangent[1][k][lane] = m.tangent[1][k];
      }
      g.friction[lane] = 0.6f;
      for (int q = 0; q < kContactPoints; ++q) {
        ContactPointLanes<W>& lanes_q = g.point[q];
        // The arms in the manifold's frame (t1, t2, n), as the kernels take them.
        const auto vec = [](const std::array<float, 3>& a) {
          return Vec3<float>{a[0], a[1], a[2]};
        };
        const ContactFrame<float> frame{vec(m.normal), vec(m.tangent[0]), vec(m.tangent[1])};
        const Vec3<float> r_a = to_frame(frame, vec(m.r_a[q]));
        const Vec3<float> r_b = to_frame(frame, vec(m.r_b[q]));
        const float* along_a[3] = {&r_a.x, &r_a.y, &r_a.z};
        const float* along_b[3] = {&r_b.x, &r_b.y, &r_b.z};
        for (int k = 0; k < 3; ++k) {
          lanes_q.r_a[k][lane] = *along_a[k];
          lanes_q.r_b[k][lane] = *along_b[k];
        }
        lanes_q.base_separation[lane] = m.base_separation;
        lanes_q.normal_impulse[lane] = 0.5f;  // warm: about a quarter of a box's weight share
      }
      out.rows += 3.0 * kContactPoints;
    }
  }
  return out;
}

// The contact spring of ContactSettings' defaults (30 Hz, damping ratio 10, push-out at most
// 3 m/s, restitution above 1 m/s) for the sub-step of kContext (kernel_bench_support.hpp).
ContactContext contact_context() {
  const Softness<float> spring = make_softness(30.0f, 10.0f, kContext.h);
  return {spring.bias_rate, spring.mass_scale, spring.impulse_scale, 3.0f, 1.0f};
}

// The pyramid of `base` packed and prepared, friction on (its signature), ready for passes.
template <class L>
struct ContactBench {
  PackedContacts<kWidth<L>> packed;
  ContactContext cc = contact_context();
  explicit ContactBench(int base) : packed(pack_pyramid<kWidth<L>>(base)) {
    const BodyArrays arrays = packed.arrays();
    for (auto& color : packed.colors) {
      for (auto& g : color) prepare_contacts<L, kContactFriction>(g, arrays);
    }
  }
  // One pass over every colour's groups.
  template <ContactPass P>
  void pass() {
    const BodyArrays arrays = packed.arrays();
    for (auto& color : packed.colors) {
      for (auto& g : color)
        solve_contacts<L, kContactFriction, P == ContactPass::Solve>(g, arrays, kContext, cc);
    }
    benchmark::ClobberMemory();
  }
};

// The process's CPU time, ns: what Google Benchmark's CPU time (and so ns_per_row) counts. On
// a shared machine wall time also counts the time other processes held the core.
double cpu_time_ns() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e9 + static_cast<double>(t.tv_nsec);
}

template <class L, ContactPass P>
void run_contacts(benchmark::State& state) {
  const int base = static_cast<int>(state.range(0));
  ContactBench<L> bench(base);
  const double start = cpu_time_ns();
  for (auto _ : state) bench.template pass<P>();
  const double rows = bench.packed.rows;
  const double ns = (cpu_time_ns() - start) / (static_cast<double>(state.iterations()) * rows);
  state.counters["ns_per_row"] = benchmark::Counter(
      rows * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["rows"] = rows;
  if constexpr (kWidth<L> == 1) remember_scalar_ns_per_row(P, base, ns);
  state.counters["x_scalar"] = scalar_ns_per_row(P, base) / ns;
}

// Bases: 20 (590 manifolds, a few hundred kB of lanes: in L2) and 100 (14,950, the issue's
// pyramid: several MB, out of L2).
void pyramid_bases(benchmark::internal::Benchmark* b) {
  b->Arg(20)->Arg(100)->Unit(benchmark::kMicrosecond);
}

}  // namespace
}  // namespace softstep::simd
