// The tool's command line: help generated from the options, errors that name the option and
// the value (exit code 2), the option names the README uses, and the JSON report's keys.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>
#include <nlohmann/json.hpp>

#include "run_tool.hpp"

namespace softstep::tool_test {
namespace {

TEST(ToolCli, HelpListsEveryCommandsOptions) {
  const ToolRun top = run_tool("--help");
  EXPECT_EQ(top.exit_code, 0);
  for (const char* command : {"profile", "sweep", "hardcases"})
    EXPECT_NE(top.out.find(command), std::string::npos) << command;

  const ToolRun profile = run_tool("profile --help");
  EXPECT_EQ(profile.exit_code, 0);
  for (const char* option :
       {"--links",   "--chains", "--joint",         "--layout",     "--end-mass",
        "--size",    "--span",   "--loads",         "--load-mass",  "--hertz",
        "--zeta",    "--steps",  "--substeps",      "--iterations", "--relax",
        "--threads", "--simd",   "--no-warm-start", "--no-sleep",   "--general",
        "--plan",    "--json",   "--csv",           "--trace",      "--no-friction-while-solving"})
    EXPECT_NE(profile.out.find(option), std::string::npos) << option;

  const ToolRun sweep = run_tool("sweep --help");
  EXPECT_EQ(sweep.exit_code, 0);
  for (const char* option : {"--out", "--warm-start", "--rigid-hertz", "--runs", "--error",
                             "--reference-substeps", "--reference-iterations", "--probes"})
    EXPECT_NE(sweep.out.find(option), std::string::npos) << option;

  const ToolRun hard = run_tool("hardcases --help");
  EXPECT_EQ(hard.exit_code, 0);
  EXPECT_NE(hard.out.find("--quick"), std::string::npos);
}

struct BadLine {
  const char* arguments;
  const char* option;  // the message must name it...
  const char* value;   // ...and the value
};

TEST(ToolCli, BadValuesNameTheOptionAndTheValue) {
  const BadLine lines[] = {
      {"profile chain --links 0", "--links", "0"},
      {"profile chain --links ten", "--links", "ten"},
      {"profile --hertz nan", "--hertz", "nan"},
      {"profile --hertz -3", "--hertz", "-3"},
      {"profile --simd avx1024", "--simd", "avx1024"},
      {"profile --joint hinge", "--joint", "hinge"},
      {"profile grid --links 3", "--links", "grid"},
      {"profile bridge --span 4 --loads 5", "--loads", "5"},
      {"profile --zeta 0.5", "--zeta", "--hertz"},
      {"profile --frobnicate", "--frobnicate", "--frobnicate"},
      {"sweep --out d --substeps 1,0", "--substeps", "0"},
      {"sweep --out d --warm-start maybe", "--warm-start", "maybe"},
      {"sweep --steps 10", "--out", "--out"},
      {"hardcases --simd wide", "--simd", "wide"},
  };
  for (const BadLine& line : lines) {
    const ToolRun run = run_tool(line.arguments);
    EXPECT_EQ(run.exit_code, 2) << line.arguments;
    EXPECT_NE(run.err.find(line.option), std::string::npos) << line.arguments << ": " << run.err;
    EXPECT_NE(run.err.find(line.value), std::string::npos) << line.arguments << ": " << run.err;
    EXPECT_NE(run.err.find("--help"), std::string::npos) << "no pointer to the help: " << run.err;
  }
}

TEST(ToolCli, ProfileWritesItsFiguresAsJson) {
  const std::string dir = scratch_dir("profile_json");
  const ToolRun run = run_tool(
      "profile chain --links 20 --chains 2 --hertz 5 --zeta 0.7 --steps 10 "
      "--threads 1 --json " +
      dir + "/p.json --csv " + dir + "/p.csv --trace " + dir + "/t.json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(read_text(dir + "/p.json"));
  for (const char* key : {"scene",
                          "bodies",
                          "joints",
                          "steps",
                          "substeps",
                          "solve_iterations",
                          "relax_iterations",
                          "threads",
                          "simd",
                          "ms_per_step",
                          "stage_ms",
                          "rows_per_second",
                          "barrier_wait_share",
                          "colors",
                          "max_joint_error_m",
                          "rms_joint_error_m",
                          "max_joint_error_run_m",
                          "stretch_ratio",
                          "state_hash",
                          "awake_bodies",
                          "sleeping_islands",
                          "plan"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["bodies"], 42);
  EXPECT_EQ(j["joints"], 40);
  EXPECT_EQ(j["steps"], 10);
  // The hash the table printed is the hash the file holds.
  EXPECT_NE(run.out.find(j["state_hash"].get<std::string>()), std::string::npos);
  for (const char* key : {"stages", "effects", "kernels", "rows_per_pass"})
    EXPECT_TRUE(j["plan"].contains(key)) << key;
  const nlohmann::json trace = nlohmann::json::parse(read_text(dir + "/t.json"));
  ASSERT_FALSE(trace["traceEvents"].empty());
  EXPECT_EQ(trace["traceEvents"][0]["ph"], "X");
}


std::string state_hash_line(const std::string& out) {
  const std::size_t at = out.find("state hash");
  return at == std::string::npos ? "" : out.substr(at, out.find('\n', at) - at);
}

TEST(ToolCli, SavedSceneProfilesToTheSameState) {
  const std::string dir = scratch_dir("saved_scene");
  const std::string common = " --steps 20 --threads 1";
  for (const std::string scene : {"chain --links 30 --chains 2 --joint distance --hertz 4",
                                  "grid --size 6", "bridge --span 30 --loads 3"}) {
    SCOPED_TRACE(scene);
    const ToolRun built = run_tool("profile " + scene + common + " --save " + dir + "/s.json");
    ASSERT_EQ(built.exit_code, 0) << built.err;
    const ToolRun loaded = run_tool("profile " + dir + "/s.json" + common);
    ASSERT_EQ(loaded.exit_code, 0) << loaded.err;
    EXPECT_FALSE(state_hash_line(built.out).empty());
    EXPECT_EQ(state_hash_line(loaded.out), state_hash_line(built.out));
  }
  // The other command that takes a scene takes a file too.
  const ToolRun sweep = run_tool("sweep " + dir + "/s.json --out " + dir +
                                 "/sweep --steps 4 --substeps 1 --relax 0 --runs 1 --probes 1");
  EXPECT_EQ(sweep.exit_code, 0) << sweep.err;
  EXPECT_NE(read_text(dir + "/sweep/results.csv").find("substeps"), std::string::npos);
}

// results.csv's first data row as column name -> text.
std::map<std::string, std::string> first_csv_row(const std::string& text) {
  std::istringstream in(text);
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  std::map<std::string, std::string> cells;
  std::istringstream names(header), values(row);
  for (std::string name, value; std::getline(names, name, ',') && std::getline(values, value, ',');)
    cells[name] = value;
  return cells;
}

// softstep sweep writes each talk scene's own reading beside the timing (null where the scene
// has none): the ragdoll's limit violation, the car's bounce (2 Hz springs: within 3 %) and
// ride height error (the wheels' contacts are round, so driving at 2 m/s rides as at rest,
// nanometres off once the bounce has decayed: README "Cars, bridges, dragging"),
// the bridge's sag error and crossing time (null: 60 steps leave the cart on its pier).
TEST(ToolCli, SweepWritesTheTalkScenesReadings) {
  const std::string dir = scratch_dir("sweep_readings");
  const std::string common =
      " --count 1 --substeps 4 --relax 1 --iterations 1 --runs 1 --probes 0 --threads 1"
      " --reference-substeps 4 --reference-iterations 1 --simd scalar";
  const ToolRun car = run_tool("sweep vehicle --speed 2 --steps 240 --out " + dir + "/car" + common);
  ASSERT_EQ(car.exit_code, 0) << car.err;
  std::map<std::string, std::string> row = first_csv_row(read_text(dir + "/car/results.csv"));
  ASSERT_TRUE(row.count("bounce_hz")) << "no bounce_hz column";
  EXPECT_NEAR(std::stod(row["bounce_hz"]), 2.0, 0.06);
  EXPECT_NEAR(std::stod(row["bounce_error"]), 0.0, 0.03);
  EXPECT_LT(std::abs(std::stod(row["ride_height_error_m"])), 1e-5);
  EXPECT_EQ(row["sag_error"], "null");
  EXPECT_EQ(row["limit_violation_deg"], "null");

  const ToolRun bridge =
      run_tool("sweep suspension-bridge --steps 60 --out " + dir + "/bridge" + common);
  ASSERT_EQ(bridge.exit_code, 0) << bridge.err;
  row = first_csv_row(read_text(dir + "/bridge/results.csv"));
  ASSERT_TRUE(row.count("sag_error") && row.count("crossing_s"));
  EXPECT_EQ(row["sag_error"], "null");
  EXPECT_EQ(row["bounce_hz"], "null");

  const ToolRun ragdoll = run_tool("sweep ragdoll --steps 30 --out " + dir + "/ragdoll" + common);
  ASSERT_EQ(ragdoll.exit_code, 0) << ragdoll.err;
  row = first_csv_row(read_text(dir + "/ragdoll/results.csv"));
  ASSERT_TRUE(row.count("limit_violation_deg"));
  EXPECT_GE(std::stod(row["limit_violation_deg"]), 0.0);
  EXPECT_EQ(row["ride_height_error_m"], "null");
}

TEST(ToolCli, ABadSceneFileIsNamedWithTheFieldAndValue) {
  const std::string dir = scratch_dir("bad_scene");
  ASSERT_EQ(run_tool("profile chain --links 3 --steps 1 --save " + dir + "/s.json").exit_code, 0);
  std::string text = read_text(dir + "/s.json");
  text.replace(text.find("\"mass\":1.0"), 10, "\"mass\":-3");
  { std::ofstream(dir + "/bad.json") << text; }
  const ToolRun run = run_tool("profile " + dir + "/bad.json");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find(dir + "/bad.json: /bodies/1/mass = -3"), std::string::npos) << run.err;
  const ToolRun options = run_tool("profile " + dir + "/s.json --links 4");
  EXPECT_EQ(options.exit_code, 2);
  EXPECT_NE(options.err.find("--links"), std::string::npos) << options.err;
}


TEST(ToolCli, ViewSubsamplesBodiesJointsAndFrames) {
  const std::string dir = scratch_dir("view_subsample");
  ASSERT_EQ(run_tool("profile chain --links 200 --steps 1 --save " + dir + "/s.json").exit_code, 0);
  const ToolRun run = run_tool("view " + dir +
                               "/s.json --steps 100 --max-bodies 10 --max-joints 20 "
                               "--frames 10 --out " +
                               dir + "/page");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // Every 20th body (10) plus both ends of every 10th joint (40), some shared; at most 10
  // frames before the last step's.
  EXPECT_NE(run.out.find("of 201 bodies, 20 of 200 joints"), std::string::npos) << run.out;
  const std::size_t frames_at = run.out.find(" frames of 100 steps");
  ASSERT_NE(frames_at, std::string::npos) << run.out;
  const int frames = std::stoi(run.out.substr(run.out.rfind(' ', frames_at - 1) + 1));
  EXPECT_LE(frames, 11);
  EXPECT_GE(frames, 5);
  const std::string page = read_text(dir + "/page/index.html");
  // Self-contained: no resource is fetched from anywhere.
  for (const char* fetch : {"src=", "href=", "http://", "https://", "import(", "fetch("})
    EXPECT_EQ(page.find(fetch), std::string::npos) << fetch;
}

TEST(ToolCli, HardcasesWriteAViewerPagePerCase) {
  const std::string dir = scratch_dir("hardcases_view");
  const ToolRun run = run_tool("hardcases --quick --view " + dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string index = read_text(dir + "/index.html");
  int pages = 0;
  for (std::size_t at = index.find("href=\""); at != std::string::npos;
       at = index.find("href=\"", at + 1), ++pages) {
    const std::string file = index.substr(at + 6, index.find('"', at + 6) - at - 6);
    const std::string page = read_text(dir + "/" + file);
    EXPECT_NE(page.find("data-state=\"loading\""), std::string::npos) << file;
    EXPECT_EQ(page.find("/*SOFTSTEP_DATA*/"), std::string::npos) << file << ": no data";
  }
  EXPECT_GE(pages, 15);  // every case but the 10,000-link chains
  EXPECT_NE(index.find("kinematic driver"), std::string::npos);
}

// --substeps reaches every case's world and its bounds: at one sub-step a rigid row's
// stiffness is capped at a quarter of 60 Hz, so the hanging chain stretches more than at the
// default 4 and its bound (the static stretch of the capped springs) grows with it.
TEST(ToolCli, HardcasesTakeTheSubStepsAndTheirBounds) {
  const auto error_and_bound = [](const std::string& extra) {
    const ToolRun run = run_tool("hardcases --case \"mass ratio 10:1\"" + extra);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    // "| mass ratio 10:1 | <parameters> | <error> (<= <bound>) | ..."
    const std::size_t row = run.out.find("| mass ratio 10:1 |");
    const std::size_t cell = run.out.find(" | ", run.out.find(" | ", row + 2) + 3) + 3;
    const double error = std::stod(run.out.substr(cell));
    const double bound = std::stod(run.out.substr(run.out.find("(<= ", cell) + 4));
    return std::pair{error, bound};
  };
  const auto [error_4, bound_4] = error_and_bound("");
  const auto [error_1, bound_1] = error_and_bound(" --substeps 1");
  EXPECT_GT(error_1, 2.0 * error_4);
  EXPECT_GT(bound_1, 2.0 * bound_4);
  const ToolRun zero = run_tool("hardcases --substeps 0");
  EXPECT_EQ(zero.exit_code, 2);
  EXPECT_NE(zero.err.find("--substeps"), std::string::npos) << zero.err;
}

TEST(ToolCli, ProfileRecordsAndReplayChecksIt) {
  const std::string dir = scratch_dir("record");
  const ToolRun profile =
      run_tool("profile chain --links 20 --hertz 4 --steps 30 --record " + dir + "/run.rec");
  ASSERT_EQ(profile.exit_code, 0) << profile.err;
  const ToolRun replay = run_tool("replay " + dir + "/run.rec");
  EXPECT_EQ(replay.exit_code, 0) << replay.err;
  EXPECT_NE(replay.out.find("30 steps"), std::string::npos) << replay.out;
  // The same final state as the profiled run.
  const std::string hash = profile.out.substr(profile.out.find("state hash") + 17, 16);
  EXPECT_NE(replay.out.find(hash), std::string::npos) << replay.out;

  std::string bytes = read_text(dir + "/run.rec");
  { std::ofstream(dir + "/cut.rec", std::ios::binary) << bytes.substr(0, bytes.size() - 30); }
  const ToolRun cut = run_tool("replay " + dir + "/cut.rec");
  EXPECT_EQ(cut.exit_code, 1);
  EXPECT_NE(cut.err.find("cut.rec"), std::string::npos) << cut.err;

  // profile FILE.rec replays it with profiling on: every step checked, the stage table, the
  // same final state; options that would change a step are refused by name.
  const ToolRun profiled = run_tool("profile " + dir + "/run.rec --json " + dir + "/rec.json");
  EXPECT_EQ(profiled.exit_code, 0) << profiled.err;
  EXPECT_NE(profiled.out.find("30 steps and 0 other calls replayed, every step matched"),
            std::string::npos)
      << profiled.out;
  EXPECT_NE(profiled.out.find("solve"), std::string::npos) << profiled.out;
  EXPECT_NE(profiled.out.find(hash), std::string::npos) << profiled.out;
  const nlohmann::json report = nlohmann::json::parse(read_text(dir + "/rec.json"));
  EXPECT_EQ(report["steps"], 30);
  EXPECT_GT(report["ms_per_step"].get<double>(), 0.0);
  const ToolRun changed = run_tool("profile " + dir + "/run.rec --substeps 8");
  EXPECT_NE(changed.exit_code, 0);
  EXPECT_NE(changed.err.find("--substeps cannot be used with a recording"), std::string::npos)
      << changed.err;
  const ToolRun cut_profile = run_tool("profile " + dir + "/cut.rec");
  EXPECT_EQ(cut_profile.exit_code, 1);
  EXPECT_NE(cut_profile.err.find("cut.rec"), std::string::npos) << cut_profile.err;
}

// results.csv's rows without the columns that depend on time (ms_per_step, and pareto, which
// is ranked by it).
std::vector<std::string> error_rows(const std::string& csv) {
  std::vector<std::string> rows;
  std::istringstream lines(csv);
  std::string line;
  std::vector<std::string> header;
  while (std::getline(lines, line)) {
    std::vector<std::string> cells;
    std::istringstream cell_stream(line);
    std::string cell;
    while (std::getline(cell_stream, cell, ',')) cells.push_back(cell);
    if (header.empty()) header = cells;
    std::string kept;
    for (std::size_t k = 0; k < cells.size() && k < header.size(); ++k) {
      if (header[k] != "ms_per_step" && header[k] != "pareto") kept += cells[k] + ",";
    }
    rows.push_back(kept);
  }
  return rows;
}

// softstep sweep FILE.rec replays the recording's calls at every setting and its reference
// at the reference settings. A recording of steps of 1/60 s alone sweeps to the rows of the
// scene file of its initial state, every error column to the printed digit (the same
// calls in the same order at the same settings: bit for bit). --steps is refused (a recording
// runs its own), and so is a corrupted recording, with the reader's error.
TEST(ToolCli, SweepTakesARecording) {
  const std::string dir = scratch_dir("sweep_recording");
  const ToolRun made = run_tool("profile chain --links 20 --hertz 4 --steps 30 --save " + dir +
                                "/s.json --record " + dir + "/run.rec");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const std::string grid =
      " --substeps 1,4 --relax 0,1 --runs 1 --probes 2 --reference-substeps 16";
  const ToolRun scene = run_tool("sweep " + dir + "/s.json --steps 30 --out " + dir + "/scene" + grid);
  ASSERT_EQ(scene.exit_code, 0) << scene.err;
  const ToolRun swept = run_tool("sweep " + dir + "/run.rec --out " + dir + "/rec" + grid);
  ASSERT_EQ(swept.exit_code, 0) << swept.err;
  const std::vector<std::string> from_scene = error_rows(read_text(dir + "/scene/results.csv"));
  const std::vector<std::string> from_recording = error_rows(read_text(dir + "/rec/results.csv"));
  ASSERT_EQ(from_scene.size(), 5u);  // the header and 4 settings
  EXPECT_EQ(from_recording, from_scene);
  EXPECT_NE(swept.out.find("30 recorded steps"), std::string::npos) << swept.out;

  const ToolRun steps = run_tool("sweep " + dir + "/run.rec --steps 10 --out " + dir + "/x");
  EXPECT_EQ(steps.exit_code, 2);
  EXPECT_NE(steps.err.find("--steps cannot be used with a recording"), std::string::npos)
      << steps.err;
  const std::string bytes = read_text(dir + "/run.rec");
  { std::ofstream(dir + "/cut.rec", std::ios::binary) << bytes.substr(0, bytes.size() - 30); }
  const ToolRun cut = run_tool("sweep " + dir + "/cut.rec --out " + dir + "/cut" + grid);
  EXPECT_EQ(cut.exit_code, 1);
  EXPECT_NE(cut.err.find(dir + "/cut.rec: truncated"), std::string::npos) << cut.err;
}

// A recording with contacts (the fuzzer's seed: the pyramid of base 2 over 3 steps, as
// softstep profile pyramid --base 2 --steps 3 --record FILE writes it): replay counts its contacts, profile shows the contacts line and the contact load.
TEST(ToolCli, ContactRecordingsReplayAndProfileWithTheirContacts) {
  const std::string rec =
      std::string(SOFTSTEP_SOURCE_DIR) + "/tests/fuzz/recording_corpus/seed_v3_contacts";
  const std::string dir = scratch_dir("contact_record");
  const ToolRun replay = run_tool("replay " + rec);
  EXPECT_EQ(replay.exit_code, 0) << replay.err;
  EXPECT_NE(replay.out.find("contacts: 3 of the steps were given contacts, 15 manifolds in all"),
            std::string::npos)
      << replay.out;
  const ToolRun profiled = run_tool("profile " + rec + " --plan --json " + dir + "/rec.json");
  EXPECT_EQ(profiled.exit_code, 0) << profiled.err;
  EXPECT_NE(profiled.out.find("contacts         3 of the steps: median 5 manifolds"),
            std::string::npos)
      << profiled.out;
  EXPECT_NE(profiled.out.find("contact load"), std::string::npos) << profiled.out;
  EXPECT_NE(profiled.out.find("prepare_contacts"), std::string::npos) << profiled.out;
  const nlohmann::json report = nlohmann::json::parse(read_text(dir + "/rec.json"));
  EXPECT_EQ(report["contacts"]["steps"], 3);
  EXPECT_EQ(report["contacts"]["manifolds"], 15);
}

}  // namespace
}  // namespace softstep::tool_test
