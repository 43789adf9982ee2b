// replay_recording: reads a recording with every length and count checked against what is
// left of the file, re-makes each call on a world loaded from its initial scene, and compares
// the motion hash after every step. Anything unexpected is a RecordingError naming the file
// and the byte or step; nothing in a file can make it read out of bounds.
#include <fstream>
#include <sstream>

#include "byte_reader.hpp"
#include "contact_records.hpp"
#include "format.hpp"
#include "scene/body_format.hpp"
#include "scene/joint_formats.hpp"
#include "scene/json_reader.hpp"
#include "scene/settings_format.hpp"
#include "softstep/recording.hpp"
#include "softstep/scene_file.hpp"

namespace softstep {

namespace {

using recording::ByteReader;
using recording::Tag;

std::string hex(std::uint64_t v) {
  char b[20];
  std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(v));
  return b;
}

class Replayer {
 public:
  Replayer(const std::string& bytes, const std::string& name, const ReplayHooks& hooks)
      : in_(bytes, name), name_(name), hooks_(hooks) {}

  ReplayReport run() {
    header();
    while (true) {
      if (in_.at_end())
        throw RecordingError(name_ + ": ends after step " + std::to_string(report_.steps) +
                             " without its end record (cut short, or stop_recording was not "
                             "called); every step up to there matched");
      record_at_ = in_.offset();
      const auto tag = static_cast<Tag>(in_.get<std::uint8_t>("a record's tag"));
      if (tag == Tag::End) break;
      if (tag != Tag::End && version_of(tag) > version_)
        fail("record tag " + std::to_string(static_cast<int>(tag)) +
             " does not exist in a recording of version " + std::to_string(version_));
      try {
        record(tag);
      } catch (const SceneFileError& e) {
        fail(e.what());
      } catch (const InvalidArgument& e) {
        fail(std::string("the call is refused: ") + e.what());
      }
    }
    const std::uint64_t recorded = in_.get<std::uint64_t>("the final state hash");
    if (!in_.at_end()) fail("bytes after the end record");
    report_.state_hash = world_.state_hash();
    if (hooks_.check && report_.state_hash != recorded)
      fail("the state hash at the end is " + hex(report_.state_hash) + ", the recording has " +
           hex(recorded));
    return report_;
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw RecordingError(name_ + ": record at byte " + std::to_string(record_at_) +
                         " (after step " + std::to_string(report_.steps) + "): " + why);
  }

  // The version a record tag came with.
  static std::uint32_t version_of(Tag tag) {
    const auto t = static_cast<std::uint8_t>(tag);
    return t >= recording::kFirstVersion3Tag   ? 3
           : t >= recording::kFirstVersion2Tag ? 2
                                               : 1;
  }

  // Replays one step and, when checking, compares its motion hash with the recorded one.
  void step(double dt, std::span<const ContactManifold> contacts) {
    const auto recorded = in_.get<std::uint64_t>("a step's motion hash");
    if (hooks_.before_step) hooks_.before_step(world_, report_.steps + 1, dt);
    world_.step(dt, contacts);
    ++report_.steps;
    if (!hooks_.check) {
      if (hooks_.after_step) hooks_.after_step(world_, report_.steps, dt);
      return;
    }
    const std::uint64_t now = world_.motion_hash();
    if (now != recorded)
      throw RecordingError(name_ + ": step " + std::to_string(report_.steps) +
                           " diverged: motion hash " + hex(now) + ", the recording has " +
                           hex(recorded) + " (record at byte " + std::to_string(record_at_) +
                           (contacts.empty() ? ""
                                             : ", a step with " + std::to_string(contacts.size()) +
                                                   " contact manifolds") +
                           ")");
    if (hooks_.after_step) hooks_.after_step(world_, report_.steps, dt);
  }

  void header() {
    const std::string magic = in_.text(sizeof recording::kMagic, "the file's signature");
    if (magic != std::string(recording::kMagic, sizeof recording::kMagic))
      throw RecordingError(name_ + ": not a softstep recording (no SSTEPREC signature)");
    const auto version = in_.get<std::uint32_t>("the version");
    if (version < recording::kOldestVersion || version > recording::kVersion)
      throw RecordingError(name_ + ": a recording of version " + std::to_string(version) +
                           "; this softstep reads versions " +
                           std::to_string(recording::kOldestVersion) + " to " +
                           std::to_string(recording::kVersion));
    version_ = version;
    const auto scene_size = in_.get<std::uint64_t>("the initial scene's length");
    const std::string scene = in_.text(scene_size, "the initial scene");
    try {
      world_ = load_scene_text(scene, name_ + " (its initial scene)");
    } catch (const SceneFileError& e) {
      throw RecordingError(e.what());
    }
    const auto start_hash = in_.get<std::uint64_t>("the initial state hash");
    if (world_.state_hash() != start_hash)
      throw RecordingError(
          name_ +
          ": its initial scene does not load into the world that was recorded (state hash " +
          hex(world_.state_hash()) + " against " + hex(start_hash) +
          "): the recording was started on a world with destroyed bodies or joints, whose ids (and "
          "the joints' colouring) a scene does not hold; start recording before the first "
          "destroy_body or destroy_joint");
    for (BodyId id : world_.body_ids()) remember(id);
    if (hooks_.adjust_settings) world_.set_settings(adjusted(world_.settings()));
    if (hooks_.on_start) hooks_.on_start(world_);
  }

  WorldSettings adjusted(WorldSettings settings) const {
    if (hooks_.adjust_settings) hooks_.adjust_settings(settings);
    return settings;
  }

  void remember(BodyId id) {
    if (id.index >= by_slot_.size()) by_slot_.resize(id.index + 1);
    by_slot_[id.index] = id;
  }

  template <class Id>
  Id read_id() {
    Id id;
    id.index = in_.get<std::uint32_t>("an id");
    id.generation = in_.get<std::uint32_t>("an id");
    return id;
  }
  Eigen::Vector3d read_vector() {
    Eigen::Vector3d v;
    for (int k = 0; k < 3; ++k) v[k] = in_.get<double>("a vector");
    return v;
  }
  template <class Id>
  void expect_id(Id got) {
    const Id recorded = read_id<Id>();
    if (got != recorded)
      fail("the call gave id " + std::to_string(got.index) + "/" + std::to_string(got.generation) +
           ", the recording has " + std::to_string(recorded.index) + "/" +
           std::to_string(recorded.generation));
  }
  // A JSON record, read with the scene file's readers.
  template <class Read>
  auto from_json(const char* what, Read&& read) {
    const std::string text = in_.text(what);
    scene::json j;
    try {
      j = scene::json::parse(text);
    } catch (const scene::json::exception& e) {
      fail(std::string(what) + " is not valid JSON: " + e.what());
    }
    const scene::Source source{name_ + " (" + what + " at byte " + std::to_string(record_at_) + ")",
                               &j};
    scene::ObjectReader fields(source, j, "");
    return read(fields);
  }

  void record(Tag tag) {
    switch (tag) {
      case Tag::Step:
        step(in_.get<double>("a step's dt"), {});
        return;
      case Tag::ContactStep: {
        const auto dt = in_.get<double>("a step's dt");
        recording::read_contacts(in_, contacts_, [&](const std::string& why) {
          fail("step " + std::to_string(report_.steps + 1) + ": " + why);
        });
        step(dt, contacts_);
        ++report_.contact_steps;
        report_.contact_manifolds += static_cast<long>(contacts_.size());
        return;
      }
      case Tag::CreateBody: {
        const BodyDef def =
            from_json("a body", [](scene::ObjectReader& f) { return scene::read_body(f); });
        const BodyId id = world_.create_body(def);
        expect_id(id);
        remember(id);
        break;
      }
      case Tag::DestroyBody: {
        const auto id = read_id<BodyId>();
        world_.destroy_body(id);
        by_slot_[id.index] = BodyId{};
        break;
      }
      case Tag::SetPosition: {
        const auto id = read_id<BodyId>();
        world_.set_position(id, read_vector());
        break;
      }
      case Tag::SetOrientation: {
        const auto id = read_id<BodyId>();
        double c[4];
        for (double& x : c) x = in_.get<double>("a quaternion");
        world_.set_orientation(id, Quaternion(c[0], c[1], c[2], c[3]));
        break;
      }
      case Tag::SetLinearVelocity: {
        const auto id = read_id<BodyId>();
        world_.set_linear_velocity(id, read_vector());
        break;
      }
      case Tag::SetAngularVelocity: {
        const auto id = read_id<BodyId>();
        world_.set_angular_velocity(id, read_vector());
        break;
      }
      case Tag::SetMassProperties: {
        const auto id = read_id<BodyId>();
        const auto mass = in_.get<double>("a mass");
        Eigen::Matrix3d inertia;
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) inertia(r, c) = in_.get<double>("an inertia");
        world_.set_mass_properties(id, mass, inertia);
        break;
      }
      case Tag::ApplyImpulse: {
        const auto id = read_id<BodyId>();
        const Eigen::Vector3d impulse = read_vector();
        world_.apply_impulse(id, impulse, read_vector());
        break;
      }
      case Tag::ApplyForce: {
        const auto id = read_id<BodyId>();
        const Eigen::Vector3d force = read_vector();
        world_.apply_force(id, force, read_vector());
        break;
      }
      case Tag::ApplyTorque: {
        const auto id = read_id<BodyId>();
        world_.apply_torque(id, read_vector());
        break;
      }
      case Tag::CreateJoint: {
        const JointId id = from_json("a joint", [&](scene::ObjectReader& f) {
          const scene::JointFormat* format = scene::joint_format(f.text("type"));
          if (format == nullptr) scene::fail(f.source(), "/type", "unknown joint type");
          return format->read(world_, f, by_slot_);
        });
        expect_id(id);
        break;
      }
      case Tag::SetJoint: {
        const auto id = read_id<JointId>();
        from_json("a joint", [&](scene::ObjectReader& f) {
          const scene::JointFormat* format = scene::joint_format(f.text("type"));
          if (format == nullptr) scene::fail(f.source(), "/type", "unknown joint type");
          format->set(world_, id, f, by_slot_);
          return 0;
        });
        break;
      }
      case Tag::DestroyJoint:
        world_.destroy_joint(read_id<JointId>());
        break;
      case Tag::SetSettings: {
        const WorldSettings s =
            from_json("settings", [](scene::ObjectReader& f) { return scene::read_settings(f); });
        world_.set_settings(adjusted(s));
        break;
      }
      default:
        fail("unknown record tag " + std::to_string(static_cast<int>(tag)));
    }
    ++report_.calls;
  }

  ByteReader in_;
  const std::string& name_;
  const ReplayHooks& hooks_;
  std::uint32_t version_ = 0;
  World world_;
  std::vector<BodyId> by_slot_;
  std::vector<ContactManifold> contacts_;  // of the step being replayed (storage kept)
  ReplayReport report_;
  std::size_t record_at_ = 0;
};

}  // namespace

ReplayReport replay_recording_bytes(const std::string& bytes, const std::string& name,
                                    const ReplayHooks& hooks) {
  return Replayer(bytes, name, hooks).run();
}

ReplayReport replay_recording(const std::string& path, const ReplayHooks& hooks) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw RecordingError(path + ": cannot open the file");
  std::stringstream bytes;
  bytes << in.rdbuf();
  return replay_recording_bytes(bytes.str(), path, hooks);
}

ReplayReport replay_recording_bytes(const std::string& bytes, const std::string& name,
                                    const std::function<void(World&, long, double)>& after_step) {
  ReplayHooks hooks;
  hooks.after_step = after_step;
  return replay_recording_bytes(bytes, name, hooks);
}

ReplayReport replay_recording(const std::string& path,
                              const std::function<void(World&, long, double)>& after_step) {
  ReplayHooks hooks;
  hooks.after_step = after_step;
  return replay_recording(path, hooks);
}

}  // namespace softstep
