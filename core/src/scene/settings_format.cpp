#include "settings_format.hpp"

#include <string>

#include "joint_formats.hpp"

namespace softstep::scene {

namespace {

template <class T>
struct Field {
  const char* key;
  T WorldSettings::*member;
};

constexpr Field<int> kInts[] = {
    {"substeps", &WorldSettings::substeps},
    {"solve_iterations", &WorldSettings::solve_iterations},
    {"relax_iterations", &WorldSettings::relax_iterations},
    {"threads", &WorldSettings::threads},
};

constexpr Field<double> kNumbers[] = {
    {"rigid_hertz", &WorldSettings::rigid_hertz},
    {"rigid_damping_ratio", &WorldSettings::rigid_damping_ratio},
    {"max_correction_speed", &WorldSettings::max_correction_speed},
    {"max_linear_speed", &WorldSettings::max_linear_speed},
    {"sleep_linear_speed", &WorldSettings::sleep_linear_speed},
    {"sleep_angular_speed", &WorldSettings::sleep_angular_speed},
    {"time_to_sleep", &WorldSettings::time_to_sleep},
    {"max_rotation_per_substep", &WorldSettings::max_rotation_per_substep},
};

// The "contact" object: how the contacts given to step() are solved.
constexpr struct {
  const char* key;
  double ContactSettings::*member;
} kContactNumbers[] = {
    {"hertz", &ContactSettings::hertz},
    {"damping_ratio", &ContactSettings::damping_ratio},
    {"max_push_out_speed", &ContactSettings::max_push_out_speed},
    {"restitution_threshold", &ContactSettings::restitution_threshold},
};

constexpr struct {
  const char* key;
  bool ContactSettings::*member;
} kContactSwitches[] = {
    {"friction_while_solving", &ContactSettings::friction_while_solving},
};

constexpr Field<bool> kSwitches[] = {
    {"warm_start", &WorldSettings::warm_start},
    {"geometric_stiffness", &WorldSettings::geometric_stiffness},
    {"sleeping", &WorldSettings::sleeping},
    {"specialize", &WorldSettings::specialize},
    {"fixed_threads", &WorldSettings::fixed_threads},
};

constexpr SimdWidth kWidths[] = {SimdWidth::Best, SimdWidth::Scalar, SimdWidth::Sse,
                                 SimdWidth::Avx2, SimdWidth::Avx512};

}  // namespace

WorldSettings read_settings(ObjectReader& fields) {
  WorldSettings s;
  s.gravity = fields.vec3("gravity", s.gravity);
  for (const auto& f : kInts) s.*f.member = fields.integer(f.key, s.*f.member);
  for (const auto& f : kNumbers) s.*f.member = fields.number(f.key, s.*f.member);
  for (const auto& f : kSwitches) s.*f.member = fields.boolean(f.key, s.*f.member);
  ObjectReader contact(fields.source(), fields.object("contact"), fields.path_of("contact"));
  for (const auto& f : kContactNumbers)
    s.contact.*f.member = contact.number(f.key, s.contact.*f.member);
  for (const auto& f : kContactSwitches)
    s.contact.*f.member = contact.boolean(f.key, s.contact.*f.member);
  contact.no_other_keys();
  const std::string simd = fields.text("simd", simd_width_name(s.simd));
  bool known = false;
  for (SimdWidth w : kWidths) {
    if (simd == simd_width_name(w)) {
      s.simd = w;
      known = true;
    }
  }
  if (!known)
    fail(fields.source(), fields.path_of("simd"),
         "expected \"best\", \"scalar\", \"sse\", \"avx2\" or \"avx512\"");
  const std::string solver = fields.text("solver", solver_mode_name(s.solver));
  known = false;
  for (SolverMode m : {SolverMode::Iterative, SolverMode::DirectForTrees, SolverMode::Auto}) {
    if (solver == solver_mode_name(m)) {
      s.solver = m;
      known = true;
    }
  }
  if (!known)
    fail(fields.source(), fields.path_of("solver"),
         "expected \"iterative\", \"direct-for-trees\" or \"auto\"");
  fields.no_other_keys();
  return s;
}

nlohmann::json settings_json(const WorldSettings& s) {
  nlohmann::json j;
  j["gravity"] = vector_json(s.gravity);
  for (const auto& f : kInts) j[f.key] = s.*f.member;
  for (const auto& f : kNumbers) j[f.key] = s.*f.member;
  for (const auto& f : kSwitches) j[f.key] = s.*f.member;
  for (const auto& f : kContactNumbers) j["contact"][f.key] = s.contact.*f.member;
  for (const auto& f : kContactSwitches) j["contact"][f.key] = s.contact.*f.member;
  j["simd"] = simd_width_name(s.simd);
  j["solver"] = solver_mode_name(s.solver);
  return j;
}

}  // namespace softstep::scene
