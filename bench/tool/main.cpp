// softstep: the command-line tool. Subcommands: profile, sweep, hardcases, view, replay. The
// options are declared with CLI11 (each command's file declares its own), which writes `--help` and
// names the option and the value in its errors.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "softstep/errors.hpp"
#include "tool/arguments.hpp"
#include "tool/hardcases_command.hpp"
#include "tool/profile_command.hpp"
#include "tool/replay_command.hpp"
#include "tool/sweep_command.hpp"
#include "tool/view_command.hpp"

namespace {

// "usage: softstep profile [OPTIONS] [scene] (softstep profile --help for the options)" for
// the command being parsed, or the tool's own usage before a command was named.
std::string usage_line(const CLI::App& app) {
  const CLI::App* shown = &app;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App* s) { return s->parsed(); }))
    shown = sub;
  const std::string name = shown == &app ? "softstep" : "softstep " + shown->get_name();
  std::string usage = CLI::Formatter().make_usage(shown, name);
  while (!usage.empty() && (usage.back() == '\n' || usage.back() == ' ')) usage.pop_back();
  return usage + "   (" + (shown == &app ? std::string("softstep COMMAND") : name) +
         " --help for the options)";
}

}  // namespace

int main(int argc, char** argv) {
  using namespace softstep::tool;
  CLI::App app("softstep: profile, sweep, check and view soft-constraint scenes", "softstep");
  app.require_subcommand(1);
  app.fallthrough(false);
  ProfileOptions profile;
  SweepOptions sweep;
  HardcasesOptions hardcases;
  ViewOptions view;
  ReplayOptions replay;
  CLI::App* profile_cmd = add_profile_command(app, profile);
  CLI::App* sweep_cmd = add_sweep_command(app, sweep);
  CLI::App* hardcases_cmd = add_hardcases_command(app, hardcases);
  CLI::App* view_cmd = add_view_command(app, view);
  CLI::App* replay_cmd = add_replay_command(app, replay);
  try {
    app.parse(argc, argv);
    if (*profile_cmd) return profile_command(profile);
    if (*sweep_cmd) return sweep_command(sweep);
    if (*hardcases_cmd) return hardcases_command(hardcases);
    if (*view_cmd) return view_command(view);
    if (*replay_cmd) return replay_command(replay);
    return 2;
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "softstep: %s\n%s\n", e.what(), usage_line(app).c_str());
    return 2;
  } catch (const UsageError& e) {
    std::fprintf(stderr, "softstep: %s\n%s\n", e.what(), usage_line(app).c_str());
    return 2;
  } catch (const softstep::InvalidArgument& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "softstep: error: %s\n", e.what());
    return 1;
  }
}
