#include "recorder.hpp"

#include <stdexcept>

#include "contact_records.hpp"
#include "scene/body_format.hpp"
#include "scene/joint_formats.hpp"
#include "scene/settings_format.hpp"
#include "softstep/scene_file.hpp"
#include "world_impl.hpp"

namespace softstep {

namespace recording {

namespace {
// Written to the file in blocks: a step's record is 17 bytes, too small to write alone.
constexpr std::size_t kFlushBytes = 1 << 20;
}  // namespace

Recorder::Recorder(const std::string& path, const World& world)
    : path_(path), out_(path, std::ios::binary | std::ios::trunc) {
  if (!out_) throw std::runtime_error("cannot write the recording " + path);
  buffer_.bytes().append(kMagic, sizeof kMagic);
  buffer_.put(kVersion);
  const std::string scene = save_scene_text(world);
  buffer_.put(static_cast<std::uint64_t>(scene.size()));
  buffer_.bytes() += scene;
  buffer_.put(world.state_hash());
  flush_if_full();
}

Recorder::~Recorder() {
  if (out_.is_open()) out_.write(buffer_.bytes().data(), std::streamsize(buffer_.bytes().size()));
}

void Recorder::flush_if_full() {
  if (buffer_.bytes().size() < kFlushBytes) return;
  out_.write(buffer_.bytes().data(), std::streamsize(buffer_.bytes().size()));
  buffer_.bytes().clear();
}

void Recorder::id_record(Tag tag, std::uint32_t index, std::uint32_t generation) {
  buffer_.put(tag);
  buffer_.put(index);
  buffer_.put(generation);
  flush_if_full();
}

void Recorder::step(double dt, std::span<const ContactManifold> contacts,
                    std::uint64_t motion_hash) {
  buffer_.put(contacts.empty() ? Tag::Step : Tag::ContactStep);
  buffer_.put(dt);
  if (!contacts.empty()) write_contacts(buffer_, contacts);
  buffer_.put(motion_hash);
  flush_if_full();
}

void Recorder::create_body(const BodyDef& def, BodyId id) {
  buffer_.put(Tag::CreateBody);
  buffer_.put_text(scene::body_json(def).dump());
  buffer_.put(id.index);
  buffer_.put(id.generation);
  flush_if_full();
}

void Recorder::set_vector(Tag tag, BodyId id, const Eigen::Vector3d& v) {
  id_record(tag, id.index, id.generation);
  for (int k = 0; k < 3; ++k) buffer_.put(v[k]);
}

void Recorder::set_orientation(BodyId id, const Quaternion& q) {
  id_record(Tag::SetOrientation, id.index, id.generation);
  for (double c : {q.w(), q.x(), q.y(), q.z()}) buffer_.put(c);
}

void Recorder::set_mass_properties(BodyId id, double mass, const Eigen::Matrix3d& inertia) {
  id_record(Tag::SetMassProperties, id.index, id.generation);
  buffer_.put(mass);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) buffer_.put(inertia(r, c));
}

void Recorder::apply_impulse(BodyId id, const Eigen::Vector3d& impulse,
                             const Eigen::Vector3d& point) {
  id_record(Tag::ApplyImpulse, id.index, id.generation);
  for (int k = 0; k < 3; ++k) buffer_.put(impulse[k]);
  for (int k = 0; k < 3; ++k) buffer_.put(point[k]);
}

void Recorder::apply_force(BodyId id, const Eigen::Vector3d& force,
                           const Eigen::Vector3d& point) {
  id_record(Tag::ApplyForce, id.index, id.generation);
  for (int k = 0; k < 3; ++k) buffer_.put(force[k]);
  for (int k = 0; k < 3; ++k) buffer_.put(point[k]);
}

void Recorder::create_joint(const World& world, JointId id) {
  // Bodies by slot: the replay names them by the ids the same calls gave it.
  const scene::JointFormat& format = scene::joint_format(world.joint_type(id));
  nlohmann::json j = {{"type", format.name}};
  format.write(world, id, scene::BodyIndex::by_slot(), j);
  buffer_.put(Tag::CreateJoint);
  buffer_.put_text(j.dump());
  buffer_.put(id.index);
  buffer_.put(id.generation);
  flush_if_full();
}

void Recorder::set_joint(const World& world, JointId id) {
  const scene::JointFormat& format = scene::joint_format(world.joint_type(id));
  nlohmann::json j = {{"type", format.name}};
  format.write(world, id, scene::BodyIndex::by_slot(), j);
  id_record(Tag::SetJoint, id.index, id.generation);
  buffer_.put_text(j.dump());
  flush_if_full();
}

void Recorder::set_settings(const WorldSettings& settings) {
  buffer_.put(Tag::SetSettings);
  buffer_.put_text(scene::settings_json(settings).dump());
  flush_if_full();
}

void Recorder::finish(std::uint64_t state_hash) {
  buffer_.put(Tag::End);
  buffer_.put(state_hash);
  out_.write(buffer_.bytes().data(), std::streamsize(buffer_.bytes().size()));
  buffer_.bytes().clear();
  out_.close();
  if (out_.fail()) throw std::runtime_error("could not finish the recording " + path_);
}

}  // namespace recording

void World::start_recording(const std::string& path) {
  stop_recording();
  impl_->recorder = std::make_unique<recording::Recorder>(path, *this);
}

void World::stop_recording() {
  if (!impl_->recorder) return;
  std::unique_ptr<recording::Recorder> recorder = std::move(impl_->recorder);
  recorder->finish(state_hash());
}

}  // namespace softstep
