#include "scenes/suspension_bridge.hpp"

#include <algorithm>
#include <cmath>

namespace softstep::scenes {

namespace {

constexpr double kG = 9.81;

// The rods' shape for horizontal tension h: node heights relative to the left tower, and
// the horizontal span they cover.
struct CableShape {
  std::vector<double> x, y;  // nodes 0 .. n+1 (towers at both ends)
};
CableShape cable_shape(const std::vector<double>& weights, double segment, double h) {
  double total = 0.0;
  for (double w : weights) total += w;
  double v = total / 2.0;  // the vertical tension in the first rod, pulling the tower down
  CableShape s{{0.0}, {0.0}};
  for (std::size_t k = 0; k <= weights.size(); ++k) {
    const double length = std::hypot(h, v);
    s.x.push_back(s.x.back() + segment * h / length);
    s.y.push_back(s.y.back() - segment * v / length);
    if (k < weights.size()) v -= weights[k];
  }
  return s;
}

// H such that the cable spans `span`: the span grows with H, bisected in log space.
CableShape static_cable(const std::vector<double>& weights, double segment, double span) {
  double lo = 1e-6, hi = 1e12;
  for (int i = 0; i < 200; ++i) {
    const double mid = std::sqrt(lo * hi);
    (cable_shape(weights, segment, mid).x.back() < span ? lo : hi) = mid;
  }
  return cable_shape(weights, segment, std::sqrt(lo * hi));
}

BodyId body(World& world, const Eigen::Vector3d& p, double mass, const Eigen::Vector3d& size,
            double damping) {
  BodyDef d;
  d.position = p;
  d.mass = mass;
  d.inertia = solid_box_inertia(mass, size);
  d.linear_damping = damping;
  d.angular_damping = damping;
  return world.create_body(d);
}

}  // namespace

SuspensionBridgeScene build_suspension_bridge(World& world, const SuspensionBridgeOptions& o) {
  SuspensionBridgeScene s;
  const int n = o.stations;
  const double span = o.slack_ratio * o.segment * (n + 1);
  std::vector<double> weights(static_cast<std::size_t>(n), (o.plank_mass / 2.0 + o.node_mass) * kG);
  weights[static_cast<std::size_t>(n / 2)] += o.load_mass / 2.0 * kG;  // half on each cable
  // Built in its static shape, so it starts near rest.
  const CableShape shape = static_cable(weights, o.segment, span);
  s.tower_height = 20.0;
  s.static_sag = -*std::min_element(shape.y.begin(), shape.y.end());
  BodyDef tower;
  tower.type = BodyType::Static;
  constexpr double kHang = 0.3;  // m, plank centre below its nodes
  for (int b = 0; b < o.bridges; ++b) {
    const double z0 = 10.0 * b;
    tower.position = {0.0, s.tower_height, z0};
    const BodyId left_tower = world.create_body(tower);
    tower.position = {span, s.tower_height, z0};
    const BodyId right_tower = world.create_body(tower);
    std::vector<BodyId> cable[2];
    for (int side = 0; side < 2; ++side) {
      const double z = z0 + (side == 0 ? -0.5 : 0.5) * o.width;
      BodyId previous = left_tower;
      Eigen::Vector3d previous_point(0.0, s.tower_height, z);
      for (int k = 0; k <= n; ++k) {
        const bool last = k == n;
        const Eigen::Vector3d point(shape.x[k + 1], s.tower_height + shape.y[k + 1], z);
        const BodyId next =
            last ? right_tower : body(world, point, o.node_mass, {0.1, 0.1, 0.1}, o.damping);
        DistanceJointDef rod;
        rod.body_a = previous;
        rod.body_b = next;
        rod.local_anchor_a = world.local_point(previous, previous_point);
        rod.local_anchor_b = world.local_point(next, point);
        rod.rest_length = o.segment;
        s.joints.push_back(world.create_joint(rod));
        if (!last) cable[side].push_back(next);
        previous = next;
        previous_point = point;
      }
    }
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d centre(shape.x[k + 1], s.tower_height + shape.y[k + 1] - kHang, z0);
      const BodyId plank = body(world, centre, o.plank_mass, {0.9, 0.1, o.width}, o.damping);
      for (int side = 0; side < 2; ++side) {
        const BodyId node = cable[side][static_cast<std::size_t>(k)];
        const JointFrames f =
            frames_at(world, node, plank, world.body(node).position, Eigen::Vector3d::UnitZ());
        RevoluteJointDef hinge;
        hinge.body_a = node;
        hinge.body_b = plank;
        hinge.frame_a = f.a;
        hinge.frame_b = f.b;
        s.joints.push_back(world.create_joint(hinge));
      }
      s.planks.push_back(plank);
      if (k == n / 2) {
        const BodyId load = body(world, centre - Eigen::Vector3d(0.0, 0.5, 0.0), o.load_mass,
                                 {1.0, 0.6, 1.0}, o.damping);
        BallJointDef hook;
        hook.body_a = plank;
        hook.body_b = load;
        hook.local_anchor_b = Eigen::Vector3d(0.0, 0.5, 0.0);
        s.joints.push_back(world.create_joint(hook));
        if (b == 0) s.load = load;
      }
    }
    for (int side = 0; side < 2; ++side)
      s.nodes.insert(s.nodes.end(), cable[side].begin(), cable[side].end());
  }
  return s;
}

double measured_sag(const World& world, const SuspensionBridgeScene& s,
                    const SuspensionBridgeOptions& o) {
  double lowest = s.tower_height;
  for (int k = 0; k < o.stations; ++k)
    lowest = std::min(lowest, world.body(s.nodes[static_cast<std::size_t>(k)]).position.y());
  return s.tower_height - lowest;
}

}  // namespace softstep::scenes
