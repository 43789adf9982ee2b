#include "tool/view_recorder.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>

#include "tool/viewer_page.hpp"

namespace softstep::tool {

namespace {

// The two bodies of a joint of any type (the page draws a line between them).
std::pair<BodyId, BodyId> joint_bodies(const World& world, JointId j) {
  const auto ends = [&](auto def) { return std::pair{def.body_a, def.body_b}; };
  switch (world.joint_type(j)) {
    case JointType::Ball: return ends(world.joint_def<BallJointDef>(j));
    case JointType::Distance: return ends(world.joint_def<DistanceJointDef>(j));
    case JointType::Revolute: return ends(world.joint_def<RevoluteJointDef>(j));
    case JointType::Prismatic: return ends(world.joint_def<PrismaticJointDef>(j));
    case JointType::Weld: return ends(world.joint_def<WeldJointDef>(j));
    case JointType::SwingTwist: return ends(world.joint_def<SwingTwistJointDef>(j));
    case JointType::Wheel: return ends(world.joint_def<WheelJointDef>(j));
    case JointType::Motor: return ends(world.joint_def<MotorJointDef>(j));
  }
  return {};
}

std::size_t stride(std::size_t count, std::size_t cap) {
  return cap == 0 ? count + 1 : std::max<std::size_t>(1, (count + cap - 1) / cap);
}

char type_letter(BodyType t) {
  return t == BodyType::Static ? 's' : t == BodyType::Kinematic ? 'k' : 'd';
}

template <class T>
void append_bytes(std::vector<std::uint8_t>& out, const std::vector<T>& values) {
  const std::size_t at = out.size();
  out.resize(at + values.size() * sizeof(T));
  if (!values.empty()) std::memcpy(out.data() + at, values.data(), values.size() * sizeof(T));
}

}  // namespace

ViewRecorder::ViewRecorder(const World& world, std::string title, const ViewLimits& limits)
    : title_(std::move(title)), limits_(limits) {
  const std::vector<BodyId> all_bodies = world.body_ids();
  const std::vector<JointId> all_joints = world.joint_ids();
  world_bodies_ = all_bodies.size();
  world_joints_ = all_joints.size();
  gravity_ = world.settings().gravity;
  // Drawn index per body slot (-1: not drawn).
  std::vector<std::int64_t> drawn;
  const auto draw = [&](BodyId id) {
    if (id.index >= drawn.size()) drawn.resize(id.index + 1, -1);
    if (drawn[id.index] < 0) {
      drawn[id.index] = static_cast<std::int64_t>(bodies_.size());
      bodies_.push_back(id);
      types_ += type_letter(world.body(id).type);
    }
    return static_cast<std::uint32_t>(drawn[id.index]);
  };
  const std::size_t body_stride = stride(all_bodies.size(), limits.max_bodies);
  for (std::size_t i = 0; i < all_bodies.size(); i += body_stride) draw(all_bodies[i]);
  const std::size_t joint_stride = stride(all_joints.size(), limits.max_joints);
  for (std::size_t i = 0; i < all_joints.size(); i += joint_stride) {
    const JointId j = all_joints[i];
    const auto [a, b] = joint_bodies(world, j);
    joints_.push_back(j);
    joint_ends_.push_back(draw(a));
    joint_ends_.push_back(draw(b));
  }
  record_frame(world);
}

void ViewRecorder::record_frame(const World& world) {
  frame_steps_.push_back(steps_);
  for (BodyId b : bodies_) {
    const Eigen::Vector3d p = world.body(b).position;
    for (int k = 0; k < 3; ++k) positions_.push_back(static_cast<float>(p[k]));
  }
  for (JointId j : joints_) {
    const JointReading r = world.joint_reading(j);
    error_.push_back(static_cast<float>(r.error));
    force_.push_back(static_cast<float>(r.force.norm()));
  }
}

void ViewRecorder::decimate() {
  // Keeps frames 0, 2, 4, ...: frame k is then step k * (2 every_).
  const std::size_t frames = frame_steps_.size();
  const std::size_t nb = bodies_.size() * 3, nj = joints_.size();
  std::size_t kept = 0;
  for (std::size_t f = 0; f < frames; f += 2, ++kept) {
    frame_steps_[kept] = frame_steps_[f];
    std::copy_n(positions_.begin() + f * nb, nb, positions_.begin() + kept * nb);
    std::copy_n(error_.begin() + f * nj, nj, error_.begin() + kept * nj);
    std::copy_n(force_.begin() + f * nj, nj, force_.begin() + kept * nj);
  }
  frame_steps_.resize(kept);
  positions_.resize(kept * nb);
  error_.resize(kept * nj);
  force_.resize(kept * nj);
  every_ *= 2;
}

void ViewRecorder::after_step(const World& world, double dt) {
  ++steps_;
  const StepProfile& p = world.last_step_profile();
  for (double ms : p.stage_ms) stage_ms_.push_back(static_cast<float>(ms));
  step_ms_.push_back(static_cast<float>(p.step_ms));
  dt_.push_back(dt);
  if (steps_ % every_ != 0) return;
  record_frame(world);
  if (frame_steps_.size() > std::max<std::size_t>(limits_.max_frames, 2)) decimate();
}

std::string ViewRecorder::page(const World* world) {
  if (world != nullptr && frame_steps_.back() != steps_) record_frame(*world);
  const std::size_t frames = frame_steps_.size();

  // Positions as 16-bit fractions of the run's bounding box: a third of the bytes of floats,
  // and finer than a pixel. A non-finite position (a run that blew up) is stored as 65535 in
  // every coordinate and not drawn.
  Eigen::Vector3f lo = Eigen::Vector3f::Constant(std::numeric_limits<float>::max());
  Eigen::Vector3f hi = -lo;
  for (std::size_t i = 0; i + 2 < positions_.size(); i += 3) {
    const Eigen::Vector3f p(positions_[i], positions_[i + 1], positions_[i + 2]);
    if (!p.allFinite()) continue;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  if (lo.x() > hi.x()) lo = hi = Eigen::Vector3f::Zero();
  const Eigen::Vector3f extent = (hi - lo).cwiseMax(1e-6f);
  std::vector<std::uint16_t> quantized(positions_.size());
  for (std::size_t i = 0; i + 2 < positions_.size(); i += 3) {
    const Eigen::Vector3f p(positions_[i], positions_[i + 1], positions_[i + 2]);
    for (int k = 0; k < 3; ++k) {
      const float t = (p[k] - lo[k]) / extent[k];
      quantized[i + k] =
          p.allFinite()
              ? static_cast<std::uint16_t>(std::lround(std::clamp(t, 0.0f, 1.0f) * 65534.0f))
              : 65535;
    }
  }

  // Float arrays first, so each starts on a 4-byte boundary for the page's typed arrays.
  std::vector<std::uint8_t> blob;
  nlohmann::json offsets;
  offsets["stage_ms"] = blob.size();
  append_bytes(blob, stage_ms_);
  offsets["step_ms"] = blob.size();
  append_bytes(blob, step_ms_);
  offsets["error"] = blob.size();
  append_bytes(blob, error_);
  offsets["force"] = blob.size();
  append_bytes(blob, force_);
  offsets["positions"] = blob.size();
  append_bytes(blob, quantized);

  nlohmann::json stages = nlohmann::json::array();
  for (int k = 0; k < kStageCount; ++k) stages.push_back(stage_name(static_cast<Stage>(k)));
  double time = 0.0;
  std::vector<double> step_end_time;
  for (double dt : dt_) step_end_time.push_back(time += dt);
  nlohmann::json frame_time = nlohmann::json::array();
  for (long s : frame_steps_)
    frame_time.push_back(s == 0 ? 0.0 : step_end_time[static_cast<std::size_t>(s - 1)]);
  const nlohmann::json meta = {{"title", title_},
                               {"world_bodies", world_bodies_},
                               {"world_joints", world_joints_},
                               {"bodies", bodies_.size()},
                               {"types", types_},
                               {"joints", joint_ends_},
                               {"steps", steps_},
                               {"frames", frames},
                               {"frame_steps", frame_steps_},
                               {"frame_time", frame_time},
                               {"stages", stages},
                               {"box_min", {lo.x(), lo.y(), lo.z()}},
                               {"box_extent", {extent.x(), extent.y(), extent.z()}},
                               {"gravity", {gravity_.x(), gravity_.y(), gravity_.z()}},
                               {"offsets", offsets}};
  return viewer_page(meta.dump(), base64(blob));
}

std::string base64(const std::vector<std::uint8_t>& bytes) {
  static const char* const kDigits =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t n = (std::uint32_t{bytes[i]} << 16) |
                            (i + 1 < bytes.size() ? std::uint32_t{bytes[i + 1]} << 8 : 0) |
                            (i + 2 < bytes.size() ? std::uint32_t{bytes[i + 2]} : 0);
    out += kDigits[(n >> 18) & 63];
    out += kDigits[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[n & 63] : '=';
  }
  return out;
}

}  // namespace softstep::tool
