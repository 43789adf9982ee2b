// What `softstep profile` reports of the contacts a run's steps were given: how many
// (manifolds, points, and the constraint rows they bring to a pass), how they coloured, what
// taking them cost softstep (the contact load: colouring and ordering, serial) and, when the
// scene finds them itself, what finding them cost (the user's collision detection, outside
// the step). One place for the built-in scenes and the recordings.
#pragma once

#include <nlohmann/json.hpp>
#include <span>
#include <vector>

#include "softstep/softstep.hpp"

namespace softstep::tool {

// The rows the manifolds bring to one pass: per point the normal row and, with friction > 0,
// two tangent rows; per manifold with rolling resistance > 0 three angular rows. Only the
// manifolds softstep solves count: those with an awake dynamic body (a manifold whose bodies
// are all static or asleep is left out of the lanes). Counted before the step that takes them;
// `friction` is how many of `all` are tangent rows (a solve pass without friction leaves them
// out: contact_friction_while_solving).
struct ContactRows {
  double all = 0.0, friction = 0.0;
};
ContactRows contact_rows(const World& world, std::span<const ContactManifold> contacts);

struct ContactSamples {
  long steps = 0;  // steps that had contacts in lanes
  // Per such step: from its plan and profile, and the rows (NaN when the contacts were not
  // seen, as in a replayed recording: then no rows figure is printed).
  std::vector<double> manifolds, points, rows, friction_rows, load_ms, check_ms;
  int check_threads = 1;            // the last step's (StepProfile::check_threads)
  bool load_beside_checks = false;  // the last step's (StepProfile::contact_load_beside_checks)
  long layout_kept = 0;             // steps that kept the last layout (contact_layout_kept)
  // Per step: the scene's own narrow phase before it (empty when the scene has none).
  std::vector<double> collision_ms;
  // Per such step: World::contact_readings() asked right after it (the step leaves the
  // readings to be read out of its warm-start cache when a caller asks: a user who reads them
  // pays this beside the step).
  std::vector<double> readings_ms;
  std::size_t colors = 0, overflow = 0;  // the last step's
  // After a step; `rows` from contact_rows before it, or NaN. Asks for the step's readings
  // (timed into readings_ms).
  void add_step(const World& world, ContactRows rows);
  double median_rows() const;           // 0 with no rows known
  double median_friction_rows() const;  // of those, friction rows
};

// The plan's stages that run the contacts (their time is in the stage table's rows of the same
// names, beside the joints'): prepare_contacts, solve, then warm_start and relax when the
// settings have them, restitution when a contact asks for it, as World::step_plan adds them.
std::vector<PlanStage> contact_stages(const StepPlan& plan, const WorldSettings& settings);

// "contacts  ... manifolds, points, rows per pass; colours, overflow" and the contact stages of
// the last step's plan (nothing without contacts).
void print_contacts_line(const ContactSamples& samples, const StepPlan& plan,
                         const WorldSettings& settings);
// The per-stage table's lines for the contacts: softstep's contact load (a share of the step)
// and the collision detection before the step (not in it).
void print_contact_stage_lines(const ContactSamples& samples, double step_ms);
nlohmann::json contacts_json(const ContactSamples& samples, const StepPlan& plan,
                             const WorldSettings& settings);

}  // namespace softstep::tool
