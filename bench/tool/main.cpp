// softstep: the command-line tool. Subcommands: profile, sweep, hardcases.
#include <cstdio>
#include <cstring>
#include <exception>
#include <span>

#include "softstep/errors.hpp"
#include "tool/arguments.hpp"
#include "tool/hardcases_command.hpp"
#include "tool/profile_command.hpp"
#include "tool/sweep_command.hpp"

int main(int argc, char** argv) {
  using namespace softstep::tool;
  const char* usage =
      "usage: softstep profile|sweep|hardcases [options]   (softstep COMMAND --help for the "
      "options)";
  if (argc < 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0) {
    std::puts(usage);
    return argc < 2 ? 2 : 0;
  }
  const std::string command = argv[1];
  Arguments args(std::span<char* const>(argv + 2, static_cast<std::size_t>(argc - 2)));
  try {
    if (command == "profile") {
      if (args.take_switch("--help")) {
        std::puts(kProfileUsage.c_str());
        return 0;
      }
      return profile_command(args);
    }
    if (command == "sweep") {
      if (args.take_switch("--help")) {
        std::puts(kSweepUsage.c_str());
        return 0;
      }
      return sweep_command(args);
    }
    if (command == "hardcases") {
      if (args.take_switch("--help")) {
        std::puts(kHardcasesUsage);
        return 0;
      }
      return hardcases_command(args);
    }
    throw UsageError("unknown command '" + command + "'");
  } catch (const UsageError& e) {
    std::fprintf(stderr, "softstep: %s\n%s\n", e.what(),
                 command == "profile" ? kProfileUsage.c_str()
                 : command == "sweep" ? kSweepUsage.c_str()
                                      : usage);
    return 2;
  } catch (const softstep::InvalidArgument& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "softstep: error: %s\n", e.what());
    return 1;
  }
}
