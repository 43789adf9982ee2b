#include "tool/replay_command.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>

#include "softstep/recording.hpp"

namespace softstep::tool {

CLI::App* add_replay_command(CLI::App& app, ReplayOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "replay",
      "re-run a recording (World::start_recording, or profile --record FILE) and check "
      "it bit for bit");
  cmd->add_option("file", o.path, "the recording")->required()->check(CLI::ExistingFile);
  cmd->footer(
      "After every step the world's motion hash must equal the recorded one, and at the end its\n"
      "state hash; the first step that differs is named. Exit code 1 on a mismatch or an\n"
      "unreadable file.");
  return cmd;
}

int replay_command(const ReplayOptions& o) {
  try {
    const ReplayReport r = replay_recording(o.path);
    std::printf(
        "%s: %ld steps and %ld other calls replayed, every step matched; state hash %016llx\n",
        o.path.c_str(), r.steps, r.calls, static_cast<unsigned long long>(r.state_hash));
    if (r.contact_steps > 0)
      std::printf("contacts: %ld of the steps were given contacts, %ld manifolds in all\n",
                  r.contact_steps, r.contact_manifolds);
    return 0;
  } catch (const RecordingError& e) {
    std::fprintf(stderr, "softstep replay: %s\n", e.what());
    return 1;
  }
}

}  // namespace softstep::tool
