#include "tool/contact_report.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "tool/elapsed_ms.hpp"
#include "tool/report_files.hpp"

namespace softstep::tool {

ContactRows contact_rows(const World& world, std::span<const ContactManifold> contacts) {
  const auto moving = [&](BodyId id) {
    return world.body(id).type == BodyType::Dynamic && world.is_awake(id);
  };
  ContactRows rows;
  for (const ContactManifold& m : contacts) {
    if (!moving(m.body_a) && !moving(m.body_b)) continue;
    const double friction = m.friction > 0.0 ? 2.0 * m.point_count : 0.0;
    rows.all += m.point_count + friction + (m.rolling_resistance > 0.0 ? 3.0 : 0.0);
    rows.friction += friction;
  }
  return rows;
}

void ContactSamples::add_step(const World& world, ContactRows step_rows) {
  const StepPlan& plan = world.step_plan();
  if (plan.contact_manifolds == 0) return;
  ++steps;
  manifolds.push_back(double(plan.contact_manifolds));
  points.push_back(double(plan.contact_points));
  if (!std::isnan(step_rows.all)) {
    rows.push_back(step_rows.all);
    friction_rows.push_back(step_rows.friction);
  }
  load_ms.push_back(world.last_step_profile().contact_load_ms);
  check_ms.push_back(world.last_step_profile().contact_check_ms);
  check_threads = world.last_step_profile().check_threads;
  load_beside_checks = world.last_step_profile().contact_load_beside_checks;
  layout_kept += world.last_step_profile().contact_layout_kept ? 1 : 0;
  const auto start = std::chrono::steady_clock::now();
  (void)world.contact_readings();
  readings_ms.push_back(elapsed_ms(start));
  colors = plan.contact_colors;
  overflow = plan.contact_overflow;
}

double ContactSamples::median_rows() const { return median(rows); }
double ContactSamples::median_friction_rows() const {
  return median(friction_rows);
}

std::vector<PlanStage> contact_stages(const StepPlan& plan, const WorldSettings& settings) {
  if (plan.contact_manifolds == 0) return {};
  std::vector<PlanStage> out;
  for (PlanStage st : plan.stages) {
    const bool runs_contacts =
        st == PlanStage::PrepareContacts || st == PlanStage::Solve ||
        (st == PlanStage::WarmStart && settings.warm_start) ||
        (st == PlanStage::Relax && settings.relax_iterations > 0) ||
        (st == PlanStage::Restitution && plan.contact_restitution);
    if (runs_contacts) out.push_back(st);
  }
  return out;
}

void print_contacts_line(const ContactSamples& s, const StepPlan& plan,
                         const WorldSettings& settings) {
  if (s.steps == 0) return;
  std::string rows;
  if (!s.rows.empty()) {
    char text[160];
    std::snprintf(text, sizeof text,
                  ", %.0f rows per pass (normal + 2 friction per point, + 3 rolling per manifold "
                  "that asks)",
                  s.median_rows());
    rows = text;
  }
  std::printf("contacts         %ld of the steps: median %.0f manifolds, %.0f points%s; last "
              "step %zu colours, %zu manifolds in overflow\n",
              s.steps, median(s.manifolds), median(s.points), rows.c_str(), s.colors, s.overflow);
  std::string stages;
  for (PlanStage st : contact_stages(plan, settings))
    stages += (stages.empty() ? "" : " ") + std::string(plan_stage_name(st));
  if (!stages.empty())
    std::printf("contact stages   %s (in the stage table with the joints' work of the same stage)\n",
                stages.c_str());
}

void print_contact_stage_lines(const ContactSamples& s, double step_ms) {
  // The contacts run inside the prepare, warm start, solve, relax and restitution stages;
  // their lanes are filled (matched with the last step's cache) in prepare by every thread,
  // and read back into the readings and the next cache in store. The load (the colouring and
  // the order) runs on one thread: beside the checks when they are shared, else after them;
  // a step whose contacts ask for what last step's did keeps last step's layout.
  if (s.steps > 0) {
    const double load = median(s.load_ms);
    std::printf(
        "  %-22s %8.3f  %5.1f %%  (softstep: colouring and ordering, one thread; %s; "
        "last step's kept in %ld of %ld steps; matching and packing are in prepare, reading "
        "back in store)\n",
        "contact load", load, step_ms > 0 ? 100.0 * load / step_ms : 0.0,
        s.load_beside_checks ? "beside the checks, within their time" : "serial, before the stages",
        s.layout_kept, s.steps);
  }
  if (s.steps > 0) {
    const double check = median(s.check_ms);
    const std::string where = s.check_threads > 1
                                  ? "on " + std::to_string(s.check_threads) + " threads"
                                  : std::string("serial");
    std::printf(
        "  %-22s %8.3f  %5.1f %%  (softstep: every field checked and the keys indexed "
        "before anything changes; %s)\n",
        "contact checks", check, step_ms > 0 ? 100.0 * check / step_ms : 0.0, where.c_str());
  }
  if (!s.collision_ms.empty()) {
    std::printf("  %-22s %8.3f  (the scene's narrow phase before each step, the user's part: "
                "not in the step)\n",
                "collision (user's)", median(s.collision_ms));
  }
  if (s.steps > 0) {
    std::printf("  %-22s %8.3f  (World::contact_readings() asked after the step: read out of "
                "the warm-start cache on demand, not in the step)\n",
                "contact readings", median(s.readings_ms));
  }
}

nlohmann::json contacts_json(const ContactSamples& s, const StepPlan& plan,
                             const WorldSettings& settings) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  nlohmann::json stages = nlohmann::json::array();
  for (PlanStage st : contact_stages(plan, settings)) stages.push_back(plan_stage_name(st));
  return {{"steps", s.steps},
          {"stages", stages},
          {"median_manifolds", median(s.manifolds)},
          {"median_points", median(s.points)},
          {"median_rows", s.rows.empty() ? kNaN : s.median_rows()},
          {"colors", s.colors},
          {"overflow", s.overflow},
          {"median_load_ms", median(s.load_ms)},
          {"check_threads", s.check_threads},
          {"load_beside_checks", s.load_beside_checks},
          {"layout_kept_steps", s.layout_kept},
          {"median_check_ms", median(s.check_ms)},
          {"median_readings_ms", median(s.readings_ms)},
          {"median_collision_ms", s.collision_ms.empty() ? kNaN : median(s.collision_ms)}};
}

}  // namespace softstep::tool
