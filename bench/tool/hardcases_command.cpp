#include "tool/hardcases_command.hpp"

#include <CLI/CLI.hpp>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "scenes/hard_cases.hpp"
#include "tool/progress_bar.hpp"
#include "tool/report_files.hpp"
#include "tool/view_command.hpp"

namespace softstep::tool {

namespace {

// "mass ratio 10:1" -> "mass_ratio_10_1.html".
std::string page_name(const std::string& case_name) {
  std::string name;
  for (char ch : case_name) {
    const bool keep = std::isalnum(static_cast<unsigned char>(ch)) != 0;
    if (keep)
      name += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    else if (!name.empty() && name.back() != '_')
      name += '_';
  }
  while (!name.empty() && name.back() == '_') name.pop_back();
  return name + ".html";
}

std::string cell(double value, double bound) {
  char b[64];
  std::snprintf(b, sizeof b, "%.3g (<= %.3g)", value, bound);
  return b;
}
}  // namespace

CLI::App* add_hardcases_command(CLI::App& app, HardcasesOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "hardcases", "run every hard case and print a Markdown table of figures and bounds");
  cmd->add_option("--simd", o.simd, "SIMD width")
      ->check(CLI::IsMember(simd_names()))
      ->capture_default_str();
  cmd->add_option("--solver", o.solver,
                  "WorldSettings::solver for every case (the direct-for-trees cases set theirs); "
                  "a rigid chain solved exactly is judged as one that does not stretch")
      ->check(CLI::IsMember(solver_names()))
      ->capture_default_str();
  cmd->add_option("--substeps", o.substeps,
                  "sub-steps per step for every case (the cases that set their own keep them); "
                  "the bounds follow, as a rigid row's stiffness is capped by the sub-step")
      ->check(whole_in(1, 1000))
      ->capture_default_str();
  cmd->add_option("--case", o.only, "only the cases whose name contains TEXT")->type_name("TEXT");
  cmd->add_flag("--quick", o.quick, "skip the 10,000-link chains");
  cmd->add_option("--view", o.view_dir,
                  "write a viewer page per case into DIR (index.html lists them)")
      ->type_name("DIR");
  add_view_limits(*cmd, o.limits);
  cmd->footer(
      "tests/hard_cases_test.cpp asserts the same bounds. Exit code 1 if any case fails, other\n"
      "than the known failures it lists.");
  return cmd;
}

int hardcases_command(const HardcasesOptions& options) {
  WorldSettings settings;
  settings.simd = parse_simd(options.simd);
  settings.solver = parse_solver(options.solver);
  settings.substeps = options.substeps;
  const bool quick = options.quick;

  const auto cases = scenes::hard_cases();
  std::printf(
      "| case | parameters | max joint error, m | max speed, m/s | energy gain | result |\n");
  std::printf("|---|---|---|---|---|---|\n");
  int failed = 0;
  std::vector<std::string> known;
  ProgressBar bar("hardcases", static_cast<long>(cases.size()));
  long done = 0;
  std::string index;  // the --view folder's list of pages
  for (const auto& c : cases) {
    bar.update(done++);
    if (quick && c.heavy) continue;
    if (c.name.find(options.only) == std::string::npos) continue;
    // With --view, the case's first world is recorded (a case that runs several worlds, one
    // per spring, shows its first).
    std::unique_ptr<ViewRecorder> recorder;
    bool later_world = false;
    if (!options.view_dir.empty()) {
      scenes::watch_hard_cases([&](World& world, long step, double dt) {
        if (step == 0) {
          later_world = recorder != nullptr;
          if (later_world) return;
          world.set_profiling(true);
          recorder =
              std::make_unique<ViewRecorder>(world, c.name + ": " + c.parameters, options.limits);
        } else if (!later_world) {
          recorder->after_step(world, dt);
        }
      });
    }
    const scenes::HardCaseOutcome o = c.run(settings);
    scenes::watch_hard_cases({});
    if (recorder) {
      std::filesystem::create_directories(options.view_dir);
      const std::string file = page_name(c.name);
      write_file(options.view_dir + "/" + file, recorder->page());
      index += "<li><a href=\"" + file + "\">" + markup_text(c.name) +
               "</a>: " + markup_text(c.parameters) + "</li>\n";
    }
    const bool ok = o.passed();
    const bool known_failure = !ok && !c.known_failure.empty();
    failed += ok || known_failure ? 0 : 1;
    if (known_failure) known.push_back(c.name + ": " + c.known_failure);
    std::printf("| %s | %s | %s | %s | %s | %s |\n", c.name.c_str(), c.parameters.c_str(),
                cell(o.figures.joint_error, o.bounds.joint_error).c_str(),
                cell(o.figures.max_speed, o.bounds.max_speed).c_str(),
                cell(o.figures.energy_gain, o.bounds.energy_gain).c_str(),
                ok                  ? "pass"
                : known_failure     ? "known failure (below)"
                : !o.figures.finite ? "FAIL (NaN)"
                                    : "FAIL");
    std::fflush(stdout);
  }
  for (const std::string& k : known) std::printf("\nKnown failure, %s\n", k.c_str());
  if (!options.view_dir.empty()) {
    write_file(options.view_dir + "/index.html",
               "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>softstep "
               "hard cases</title></head>\n<body><h1>softstep hard cases</h1>\n<ul>\n" +
                   index + "</ul></body></html>\n");
    std::printf("\nviewer pages: %s/index.html\n", options.view_dir.c_str());
  }
  return failed == 0 ? 0 : 1;
}

}  // namespace softstep::tool
