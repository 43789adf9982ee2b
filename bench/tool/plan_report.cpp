#include "tool/plan_report.hpp"

#include <cstdio>
#include <string>

#include "softstep/softstep.hpp"

namespace softstep::tool {

namespace {

// "rigid", "soft + min + max", "any (general)", "point + hinge lock + limits", ...
std::string kernel_features(const PlanKernel& k) {
  if (k.type != JointType::Ball && k.type != JointType::Distance) return k.parts;
  if (k.row == SpringRow::Any) return "general (per-lane switches)";
  std::string text = spring_row_name(k.row);
  if (k.lower_limit) text += " + min";
  if (k.upper_limit) text += " + max";
  return text;
}

}  // namespace

void print_plan(const StepPlan& plan) {
  std::printf("plan             %s, built %llu time(s)\n",
              plan.specialized ? "specialized" : "general (--general)",
              static_cast<unsigned long long>(plan.builds));
  std::string effects;
  const auto effect = [&](bool on, const char* name) {
    if (on) effects += (effects.empty() ? "" : ", ") + std::string(name);
  };
  effect(plan.gravity, "gravity");
  effect(plan.damping, "damping");
  effect(plan.forces, "forces");
  effect(plan.springs, "springs");
  effect(plan.limits, "limits");
  effect(plan.motors, "motors");
  effect(plan.warm_start, "warm start");
  effect(plan.kinematic_bodies, "kinematic bodies");
  effect(plan.unconstrained_bodies, "bodies without joints");
  std::printf("  effects        %s\n", effects.empty() ? "none" : effects.c_str());
  std::string stages;
  for (PlanStage st : plan.stages)
    stages += (stages.empty() ? "" : " ") + std::string(plan_stage_name(st));
  std::printf("  stages         %s\n", stages.empty() ? "none" : stages.c_str());
  std::printf("  awake bodies   %zu, sleeping islands %zu, rows per pass %llu\n", plan.awake_bodies,
              plan.sleeping_islands, static_cast<unsigned long long>(plan.rows_per_pass));
  std::printf(
      "  solver         %s: %zu tree island(s) exact (%zu joints, %zu split at their centre)%s, "
      "iterative: %zu with a loop, %zu with other joints\n",
      solver_mode_name(plan.solver), plan.tree_islands, plan.tree_joints, plan.tree_islands_split,
      plan.tree_islands_whole ? " stepped whole (each its sub-steps in turn)" : "",
      plan.loop_islands, plan.other_islands);
  if (plan.contact_manifolds > 0) {
    std::printf("  contacts       %zu manifolds, %zu points, %zu colours, %zu in overflow; rows: "
                "normal%s%s; %s\n",
                plan.contact_manifolds, plan.contact_points, plan.contact_colors,
                plan.contact_overflow, plan.contact_friction ? ", friction" : "",
                plan.contact_rolling ? ", rolling" : "",
                plan.contact_restitution ? "restitution pass" : "no restitution pass");
  }
  std::printf("  kernel variants (type, features: batches, joints)\n");
  for (const PlanKernel& k : plan.kernels) {
    std::printf("    %-9s %-40s %8u batches %9u joints\n", joint_type_name(k.type),
                kernel_features(k).c_str(), k.batches, k.joints);
  }
}

nlohmann::json plan_json(const StepPlan& plan) {
  nlohmann::json j;
  j["specialized"] = plan.specialized ? 1 : 0;
  j["solver"] = {{"mode", solver_mode_name(plan.solver)},
                 {"tree_islands", plan.tree_islands},
                 {"tree_joints", plan.tree_joints},
                 {"tree_islands_split", plan.tree_islands_split},
                 {"loop_islands", plan.loop_islands},
                 {"other_islands", plan.other_islands},
                 {"tree_islands_whole", plan.tree_islands_whole}};
  j["stages"] = nlohmann::json::array();
  for (PlanStage st : plan.stages) j["stages"].push_back(plan_stage_name(st));
  j["effects"] = {{"gravity", plan.gravity},
                  {"damping", plan.damping},
                  {"forces", plan.forces},
                  {"springs", plan.springs},
                  {"limits", plan.limits},
                  {"warm_start", plan.warm_start},
                  {"kinematic_bodies", plan.kinematic_bodies},
                  {"unconstrained_bodies", plan.unconstrained_bodies}};
  j["kernels"] = nlohmann::json::array();
  for (const PlanKernel& k : plan.kernels) {
    j["kernels"].push_back({{"type", joint_type_name(k.type)},
                            {"spring_row", spring_row_name(k.row)},
                            {"lower_limit", k.lower_limit},
                            {"upper_limit", k.upper_limit},
                            {"parts", k.parts},
                            {"rows_per_joint", k.rows_per_joint},
                            {"batches", k.batches},
                            {"joints", k.joints},
                            {"lane_bytes", k.lane_bytes},
                            {"impulse_bytes", k.impulse_bytes}});
  }
  j["rows_per_pass"] = plan.rows_per_pass;
  j["contacts"] = {{"manifolds", plan.contact_manifolds},
                   {"points", plan.contact_points},
                   {"colors", plan.contact_colors},
                   {"overflow", plan.contact_overflow},
                   {"friction", plan.contact_friction},
                   {"rolling", plan.contact_rolling},
                   {"restitution", plan.contact_restitution}};
  return j;
}

}  // namespace softstep::tool
