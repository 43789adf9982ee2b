#include "tool/hardcases_command.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "scenes/hard_cases.hpp"
#include "tool/progress_bar.hpp"

namespace softstep::tool {

namespace {
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
  cmd->add_flag("--quick", o.quick, "skip the 10,000-link chains");
  cmd->footer(
      "tests/hard_cases_test.cpp asserts the same bounds. Exit code 1 if any case fails, other\n"
      "than the known failures it lists.");
  return cmd;
}

int hardcases_command(const HardcasesOptions& options) {
  WorldSettings settings;
  settings.simd = parse_simd(options.simd);
  const bool quick = options.quick;

  const auto cases = scenes::hard_cases();
  std::printf(
      "| case | parameters | max joint error, m | max speed, m/s | energy gain | result |\n");
  std::printf("|---|---|---|---|---|---|\n");
  int failed = 0;
  std::vector<std::string> known;
  ProgressBar bar("hardcases", static_cast<long>(cases.size()));
  long done = 0;
  for (const auto& c : cases) {
    bar.update(done++);
    if (quick && c.heavy) continue;
    const scenes::HardCaseOutcome o = c.run(settings);
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
  return failed == 0 ? 0 : 1;
}

}  // namespace softstep::tool
