#include "scenes/suspension_bridge.hpp"

#include <algorithm>
#include <cmath>

#include "scenes/sphere_contacts.hpp"

namespace softstep::scenes {

namespace {

constexpr double kG = 9.81;
constexpr double kPlankThickness = 0.1;  // m
constexpr double kPierLength = 6.0;      // m, room for the cart to start and to stop
constexpr double kCartStart = 3.0;       // m, the cart's centre before the left tower

// The rods' shape for horizontal tension h: node heights relative to the left tower, and
// the horizontal span they cover.
struct CableShape {
  std::vector<double> x, y;  // nodes 0 .. n+1 (towers at both ends)
};
CableShape cable_shape(const std::vector<double>& weights, double segment, double h) {
  double total = 0.0;
  for (double w : weights) total += w;
  double v = total / 2.0;  // the vertical tension in the first rod, if the loads were symmetric
  CableShape s{{0.0}, {0.0}};
  for (std::size_t k = 0; k <= weights.size(); ++k) {
    const double length = std::hypot(h, v);
    s.x.push_back(s.x.back() + segment * h / length);
    s.y.push_back(s.y.back() - segment * v / length);
    if (k < weights.size()) v -= weights[k];
  }
  return s;
}

// H such that the cable spans `span`: the span grows with H, bisected in log space. The
// loads this scene solves for are symmetric about mid-span, so the first rod carries half.
CableShape static_cable(const std::vector<double>& weights, double segment, double span) {
  double lo = 1e-6, hi = 1e12;
  for (int i = 0; i < 200; ++i) {
    const double mid = std::sqrt(lo * hi);
    (cable_shape(weights, segment, mid).x.back() < span ? lo : hi) = mid;
  }
  return cable_shape(weights, segment, std::sqrt(lo * hi));
}

double sag_of(const CableShape& shape) {
  return -*std::min_element(shape.y.begin(), shape.y.end());
}

// The cable under the cart at mid-span: each axle's quarter of the cart's weight split
// between the stations of the rod under it by the lever rule at the shape's own x.
CableShape loaded_cable(const std::vector<double>& weights, double segment, double span,
                        double axle_load, double wheelbase) {
  CableShape shape = static_cable(weights, segment, span);
  for (int iteration = 0; iteration < 20; ++iteration) {
    std::vector<double> loaded = weights;
    for (double axle_x : {0.5 * span - 0.5 * wheelbase, 0.5 * span + 0.5 * wheelbase}) {
      for (std::size_t k = 0; k + 1 < shape.x.size(); ++k) {
        if (axle_x < shape.x[k] || axle_x > shape.x[k + 1]) continue;
        const double t = (axle_x - shape.x[k]) / (shape.x[k + 1] - shape.x[k]);
        // Nodes 1..n are stations 0..n-1; the towers (0, n+1) take their share themselves.
        if (k >= 1) loaded[k - 1] += (1.0 - t) * axle_load;
        if (k + 1 <= weights.size()) loaded[k] += t * axle_load;
        break;
      }
    }
    shape = static_cable(loaded, segment, span);
  }
  return shape;
}

BodyId body(World& world, const Eigen::Vector3d& p, const Quaternion& q, double mass,
            const Eigen::Vector3d& size, double damping) {
  BodyDef d;
  d.position = p;
  d.orientation = q;
  d.mass = mass;
  d.inertia = solid_box_inertia(mass, size);
  d.linear_damping = damping;
  d.angular_damping = damping;
  return world.create_body(d);
}

BodyId static_box(World& world, const Eigen::Vector3d& p) {
  BodyDef d;
  d.type = BodyType::Static;
  d.position = p;
  return world.create_body(d);
}

}  // namespace

SuspensionBridgeScene build_suspension_bridge(World& world, const SuspensionBridgeOptions& o) {
  SuspensionBridgeScene s;
  const int n = o.stations;
  s.span = o.slack_ratio * o.segment * (n + 1);
  const std::vector<double> weights(static_cast<std::size_t>(n),
                                    (o.plank_mass / 2.0 + o.node_mass) * kG);
  // Built in its unloaded static shape, so it starts near rest.
  const CableShape shape = static_cable(weights, o.segment, s.span);
  s.tower_height = 20.0;
  s.static_sag = sag_of(shape);
  s.cart.chassis_mass = o.load_mass - 4.0 * s.cart.wheel_mass;
  s.cart.wheelbase = 2.0;
  s.cart.speed = o.cart_speed;
  s.cart.start_rolling = false;
  s.cart.motor_torque = o.cart_motor_torque;
  s.loaded_static_sag = sag_of(loaded_cable(weights, o.segment, s.span,
                                            o.load_mass * kG / 4.0, s.cart.wheelbase));
  s.plank_half = {0.5 * o.segment, 0.5 * kPlankThickness, 0.5 * o.width};
  s.pier_half = {0.5 * kPierLength, 0.5, 0.5 * o.width};
  for (int b = 0; b < o.bridges; ++b) {
    const double z0 = 10.0 * b;
    const BodyId left_tower = static_box(world, {0.0, s.tower_height, z0});
    const BodyId right_tower = static_box(world, {s.span, s.tower_height, z0});
    s.piers.push_back(static_box(world, {-s.pier_half.x(), s.tower_height - 0.5, z0}));
    s.piers.push_back(static_box(world, {s.span + s.pier_half.x(), s.tower_height - 0.5, z0}));
    // Every station's node on both cables, towers included: [side][0 .. n+1].
    std::vector<BodyId> cable[2];
    for (int side = 0; side < 2; ++side) {
      const double z = z0 + (side == 0 ? -0.5 : 0.5) * o.width;
      cable[side].push_back(left_tower);
      for (int k = 0; k <= n; ++k) {
        const Eigen::Vector3d previous_point(shape.x[k], s.tower_height + shape.y[k], z);
        const Eigen::Vector3d point(shape.x[k + 1], s.tower_height + shape.y[k + 1], z);
        const BodyId next = k == n ? right_tower
                                   : body(world, point, Quaternion::Identity(), o.node_mass,
                                          {0.1, 0.1, 0.1}, o.damping);
        DistanceJointDef rod;
        rod.body_a = cable[side].back();
        rod.body_b = next;
        rod.local_anchor_a = world.local_point(rod.body_a, previous_point);
        rod.local_anchor_b = world.local_point(next, point);
        rod.rest_length = o.segment;
        s.joints.push_back(world.create_joint(rod));
        cable[side].push_back(next);
      }
    }
    for (int k = 0; k <= n; ++k) {
      // The plank's top face spans the rod from station k to k + 1.
      const Eigen::Vector3d from(shape.x[k], s.tower_height + shape.y[k], z0);
      const Eigen::Vector3d to(shape.x[k + 1], s.tower_height + shape.y[k + 1], z0);
      const Eigen::Vector3d along = (to - from).normalized();
      const Eigen::Vector3d up(-along.y(), along.x(), 0.0);
      const Quaternion q(Eigen::AngleAxisd(std::atan2(along.y(), along.x()),
                                           Eigen::Vector3d::UnitZ()));
      const BodyId plank = body(world, 0.5 * (from + to) - s.plank_half.y() * up, q,
                                o.plank_mass, 2.0 * s.plank_half, o.damping);
      for (int side = 0; side < 2; ++side) {
        const Eigen::Vector3d across(0.0, 0.0, (side == 0 ? -0.5 : 0.5) * o.width);
        const BodyId near = cable[side][static_cast<std::size_t>(k)];
        const JointFrames f =
            frames_at(world, near, plank, from + across, Eigen::Vector3d::UnitZ());
        RevoluteJointDef hinge;
        hinge.body_a = near;
        hinge.body_b = plank;
        hinge.frame_a = f.a;
        hinge.frame_b = f.b;
        s.joints.push_back(world.create_joint(hinge));
        BallJointDef pin;
        pin.body_a = cable[side][static_cast<std::size_t>(k + 1)];
        pin.body_b = plank;
        pin.local_anchor_a = world.local_point(pin.body_a, to + across);
        pin.local_anchor_b = world.local_point(plank, to + across);
        s.joints.push_back(world.create_joint(pin));
      }
      s.planks.push_back(plank);
    }
    for (int side = 0; side < 2; ++side)
      s.nodes.insert(s.nodes.end(), cable[side].begin() + 1, cable[side].end() - 1);
    s.carts.push_back(build_car(world, s.cart, {-kCartStart, s.tower_height, z0}, s.joints));
    s.crossings.emplace_back();
  }
  return s;
}

void bridge_contacts(const World& world, const SuspensionBridgeScene& s,
                     std::vector<ContactManifold>& out) {
  out.clear();
  const std::size_t planks_per_bridge = s.planks.size() / s.carts.size();
  constexpr double kMargin = 0.05;  // m: speculative points a little ahead of the wheels
  for (std::size_t b = 0; b < s.carts.size(); ++b) {
    for (BodyId wheel : s.carts[b].wheels) {
      const SphereShape sphere{wheel, s.cart.wheel_radius};
      for (std::size_t k = 0; k < 2; ++k) {
        if (auto m = sphere_on_box(world, s.piers[2 * b + k], s.pier_half, sphere, kMargin,
                                   s.cart.tyre_friction))
          out.push_back(*m);
      }
      for (std::size_t k = 0; k < planks_per_bridge; ++k) {
        if (auto m = sphere_on_box(world, s.planks[b * planks_per_bridge + k], s.plank_half,
                                   sphere, kMargin, s.cart.tyre_friction))
          out.push_back(*m);
      }
    }
  }
}

void track_carts(World& world, SuspensionBridgeScene& s, double time) {
  for (std::size_t b = 0; b < s.carts.size(); ++b) {
    Crossing& c = s.crossings[b];
    const double x = world.body(s.carts[b].chassis).position.x();
    if (std::isnan(c.entered_s) && x > 0.0) c.entered_s = time;
    if (std::isnan(c.sag_at_mid) && x > 0.5 * s.span) {
      double lowest = s.tower_height;
      const std::size_t per_bridge = s.nodes.size() / s.carts.size();
      for (std::size_t k = 0; k < per_bridge / 2; ++k)
        lowest = std::min(lowest, world.body(s.nodes[b * per_bridge + k]).position.y());
      c.sag_at_mid = s.tower_height - lowest;
    }
    if (std::isnan(c.left_s) && x > s.span) c.left_s = time;
    if (!c.braked && x > s.span + kCartStart) {
      for (JointId j : s.carts[b].wheel_joints) {
        WheelJointDef w = world.joint_def<WheelJointDef>(j);
        w.motor.speed = 0.0;
        world.set_joint(j, w);
      }
      c.braked = true;
    }
  }
}

double measured_sag(const World& world, const SuspensionBridgeScene& s,
                    const SuspensionBridgeOptions& o, int bridge) {
  double lowest = s.tower_height;
  const std::size_t first = static_cast<std::size_t>(bridge) * 2 * o.stations;
  for (int k = 0; k < o.stations; ++k)
    lowest = std::min(lowest, world.body(s.nodes[first + static_cast<std::size_t>(k)]).position.y());
  return s.tower_height - lowest;
}

}  // namespace softstep::scenes
