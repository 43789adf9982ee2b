#include "scenes/bridge_scene.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace softstep::scenes {

namespace {

// Points at equal arc-length steps along y = -k x (L - x), L = piers' distance, with k chosen
// so that the curve's length is `length`: the chain starts hanging slack, not stretched.
std::vector<Eigen::Vector3d> sagging_points(double piers, double length, int count) {
  const auto arc = [&](double k, std::vector<double>* xs, std::vector<double>* ss) {
    constexpr int kSamples = 4096;
    double s = 0.0, x0 = 0.0, y0 = 0.0;
    if (xs) xs->assign(1, 0.0), ss->assign(1, 0.0);
    for (int i = 1; i <= kSamples; ++i) {
      const double x = piers * i / kSamples, y = -k * x * (piers - x);
      s += std::hypot(x - x0, y - y0);
      x0 = x;
      y0 = y;
      if (xs) xs->push_back(x), ss->push_back(s);
    }
    return s;
  };
  double lo = 0.0, hi = 10.0 / piers;
  for (int i = 0; i < 60; ++i) {  // bisection on the curvature for the wanted length
    const double mid = 0.5 * (lo + hi);
    (arc(mid, nullptr, nullptr) < length ? lo : hi) = mid;
  }
  const double k = 0.5 * (lo + hi);
  std::vector<double> xs, ss;
  arc(k, &xs, &ss);
  std::vector<Eigen::Vector3d> points;
  std::size_t j = 1;
  for (int i = 1; i <= count; ++i) {
    const double target = length * i / (count + 1);
    while (j + 1 < ss.size() && ss[j] < target) ++j;
    const double t = (target - ss[j - 1]) / (ss[j] - ss[j - 1]);
    const double x = xs[j - 1] + t * (xs[j] - xs[j - 1]);
    points.emplace_back(x, -k * x * (piers - x), 0.0);
  }
  return points;
}

}  // namespace

BridgeScene build_bridge(World& world, const BridgeOptions& o) {
  if (o.span < 2 || o.loads < 0 || o.loads > o.span) {
    throw std::invalid_argument("build_bridge: need span >= 2 and 0 <= loads <= span (span " +
                                std::to_string(o.span) + ", loads " + std::to_string(o.loads) +
                                ")");
  }
  constexpr double kSpacing = 0.25;
  const double length = kSpacing * (o.span + 1);
  const double piers = o.slack_ratio * length;
  const std::vector<Eigen::Vector3d> points = sagging_points(piers, length, o.span);
  BridgeScene scene;
  BodyDef pier;
  pier.type = BodyType::Static;
  const BodyId left = world.create_body(pier);
  pier.position = {piers, 0.0, 0.0};
  const BodyId right = world.create_body(pier);
  // Joints at the midpoint between neighbouring centres, as laid out.
  const auto join = [&](BodyId a, BodyId b) {
    const Eigen::Vector3d mid = 0.5 * (world.body(a).position + world.body(b).position);
    BallJointDef j;
    j.body_a = a;
    j.body_b = b;
    j.local_anchor_a = world.local_point(a, mid);
    j.local_anchor_b = world.local_point(b, mid);
    j.spring = o.spring;
    scene.joints.push_back(world.create_ball_joint(j));
  };
  BodyId previous = left;
  for (int i = 1; i <= o.span; ++i) {
    BodyDef link;
    link.position = points[static_cast<std::size_t>(i - 1)];
    link.inertia = solid_sphere_inertia(1.0, 0.1);
    const BodyId body = world.create_body(link);
    scene.links.push_back(body);
    join(previous, body);
    previous = body;
  }
  join(previous, right);
  for (int k = 0; k < o.loads; ++k) {
    const BodyId link = scene.links[static_cast<std::size_t>((k + 1) * o.span / (o.loads + 1))];
    BodyDef load;
    load.position = world.body(link).position - Eigen::Vector3d(0.0, o.rod_length, 0.0);
    load.mass = o.load_mass;
    load.inertia = solid_sphere_inertia(o.load_mass, o.load_radius);
    const BodyId body = world.create_body(load);
    scene.loads.push_back(body);
    DistanceJointDef rod;
    rod.body_a = link;
    rod.body_b = body;
    rod.rest_length = o.rod_length;
    scene.joints.push_back(world.create_distance_joint(rod));
  }
  return scene;
}

}  // namespace softstep::scenes
