// `softstep profile pyramid|pile`: the Bullet contact scenes profiled like any scene. The
// counts the tool prints are checked against the pyramid's geometry, not against the output.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "run_tool.hpp"

namespace softstep::tool_test {
namespace {

// The pyramid of base N (bench/contacts/contact_scenes.cpp): N(N+1)/2 one-metre boxes, row r
// holding N - r of them side by side, each box above the bottom row centred over the gap of
// the two below it. Touching faces, one manifold each:
//   the bottom row on the ground                 N
//   side by side within row r                    N - r - 1, summed: N(N-1)/2
//   on the two boxes below, rows 1 .. N-1        2 (N - r),  summed: N(N-1)
// Every contact is face on face, its patch a rectangle (the full face, or half of it where a
// box straddles two): Bullet's box-box test gives its 4 corners. Friction 0.6 and no rolling
// resistance: 3 rows per point (normal + 2 tangents).
struct PyramidCounts {
  long boxes, manifolds, points, rows;
};
PyramidCounts pyramid_counts(long n) {
  const long manifolds = n + n * (n - 1) / 2 + n * (n - 1);
  return {n * (n + 1) / 2, manifolds, 4 * manifolds, 12 * manifolds};
}

nlohmann::json profile_json(const std::string& arguments, const std::string& name,
                            std::string* out = nullptr) {
  const std::string path = scratch_dir(name) + "/profile.json";
  const ToolRun run = run_tool("profile " + arguments + " --json " + path);
  EXPECT_EQ(run.exit_code, 0) << arguments << ": " << run.err;
  if (out != nullptr) *out = run.out;
  return nlohmann::json::parse(read_text(path));
}

TEST(ContactProfile, PyramidPrintsItsContactsCollisionAndStages) {
  const PyramidCounts expected = pyramid_counts(10);
  ASSERT_EQ(expected.boxes, 55);
  ASSERT_EQ(expected.manifolds, 145);
  const std::string dir = scratch_dir("pyramid_profile");
  const ToolRun run = run_tool("profile pyramid --base 10 --steps 5 --substeps 4 --relax 1 --json " +
                               dir + "/p.json --csv " + dir + "/p.csv --trace " + dir + "/p.trace");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string& out = run.out;
  std::ostringstream contacts;
  contacts << "contacts         5 of the steps: median " << expected.manifolds << " manifolds, "
           << expected.points << " points, " << expected.rows << " rows per pass";
  EXPECT_NE(out.find(contacts.str()), std::string::npos) << out;
  EXPECT_NE(out.find("contact stages   prepare_contacts warm_start solve relax"),
            std::string::npos)
      << out;
  for (const char* line : {"\n  solve ", "\n  relax ", "\n  contact load ", "\n  contact checks ",
                           "\n  collision (user's) ", "\n  step() call ", "serial share"})
    EXPECT_NE(out.find(line), std::string::npos) << line << " missing in\n" << out;
  // The collision line comes after the stages and is no share of the step: it is not in it.
  EXPECT_LT(out.find("\n  relax "), out.find("\n  collision (user's) "));
  // No joints: the joints' colour line says so instead of "0 used (joints per color: )".
  EXPECT_NE(out.find("colors           no joints in lanes"), std::string::npos) << out;
  EXPECT_EQ(out.find("joints per color"), std::string::npos) << out;

  const nlohmann::json j = nlohmann::json::parse(read_text(dir + "/p.json"));
  EXPECT_EQ(j["bodies"], expected.boxes + 1);  // and the ground
  EXPECT_EQ(j["contacts"]["steps"], 5);
  EXPECT_EQ(j["contacts"]["median_manifolds"], expected.manifolds);
  EXPECT_EQ(j["contacts"]["median_points"], expected.points);
  EXPECT_EQ(j["contacts"]["median_rows"], expected.rows);
  EXPECT_EQ(j["contact_rows"], expected.rows);
  EXPECT_EQ(j["joint_rows"], 0);
  EXPECT_EQ(j["plan"]["contacts"]["manifolds"], expected.manifolds);
  EXPECT_EQ(j["plan"]["contacts"]["points"], expected.points);
  EXPECT_GE(j["contacts"]["colors"].get<int>(), 1);
  EXPECT_GT(j["contacts"]["median_collision_ms"].get<double>(), 0.0);
  EXPECT_GT(j["contacts"]["median_load_ms"].get<double>(), 0.0);
  EXPECT_GT(j["contacts"]["median_check_ms"].get<double>(), 0.0);
  const std::vector<std::string> stages = j["contacts"]["stages"];
  EXPECT_EQ(stages, (std::vector<std::string>{"prepare_contacts", "warm_start", "solve", "relax"}));
  // ns per row counts the contact rows: the step over (rows x 4 sub-steps x (1 solve + 1 relax)).
  EXPECT_NEAR(j["ns_per_row_solve"].get<double>(),
              j["ms_per_step"].get<double>() * 1e6 / (double(expected.rows) * 4 * 2),
              1e-9 * j["ns_per_row_solve"].get<double>());

  // --trace: the user's collision, softstep's contact load and the stages that run the contacts.
  const nlohmann::json trace = nlohmann::json::parse(read_text(dir + "/p.trace"));
  std::map<std::string, int> slices;
  for (const auto& e : trace["traceEvents"]) ++slices[e["name"].get<std::string>()];
  EXPECT_EQ(slices["collision"], 5);
  EXPECT_EQ(slices["contact_load"], 5);
  EXPECT_EQ(slices["prepare"], 5);
  EXPECT_EQ(slices["solve"], 5 * 4);
  EXPECT_EQ(slices["relax"], 5 * 4);

  // --csv: one row per step, with the contact load and the collision beside the stages.
  std::istringstream csv(read_text(dir + "/p.csv"));
  std::string header, row;
  std::getline(csv, header);
  EXPECT_NE(header.find(",contact_load_ms,collision_ms,threads"), std::string::npos) << header;
  int rows = 0;
  while (std::getline(csv, row)) ++rows;
  EXPECT_EQ(rows, 5);
}

// The pyramid is solved bit for bit alike at every width and on 1 or 2 threads (the design's
// promise), seen through the tool: the same state hash.
TEST(ContactProfile, PyramidStateIsTheSameAtEveryWidthAndThreadCount) {
  const std::string common = "pyramid --base 6 --steps 20 --threads-fixed";
  const nlohmann::json scalar = profile_json(common + " --simd scalar --threads 1", "pw_scalar");
  for (const char* variant : {"--simd sse --threads 1", "--simd avx2 --threads 2",
                              "--simd best --threads 2"}) {
    const nlohmann::json other = profile_json(common + " " + variant, "pw_other");
    EXPECT_EQ(other["state_hash"], scalar["state_hash"]) << variant;
  }
}

TEST(ContactProfile, PileCountsItsBodiesAndContacts) {
  // 64 bodies fill one 8 x 8 layer 2 m up: they land within 1 s (free fall of 2 m: 0.64 s).
  std::string out;
  const nlohmann::json j = profile_json("pile --count 64 --steps 60", "pile", &out);
  EXPECT_EQ(j["bodies"], 64 + 5);  // the floor and four walls
  EXPECT_NE(out.find("pile: 64 boxes and spheres"), std::string::npos) << out;
  const long steps = j["contacts"]["steps"];
  EXPECT_GT(steps, 0);
  EXPECT_LT(steps, 60);  // not before they land
  const double manifolds = j["contacts"]["median_manifolds"];
  const double points = j["contacts"]["median_points"];
  EXPECT_GE(manifolds, 1.0);
  EXPECT_GE(points, manifolds);
  EXPECT_LE(points, 4.0 * manifolds);
  EXPECT_EQ(j["contacts"]["median_rows"].get<double>(), 3.0 * points);  // friction, no rolling
}

// --recording-overhead: the twin that recorded stayed the world's twin (equal state hashes, or
// the tool fails), and its file replays to that same state.
TEST(ContactProfile, RecordingOverheadTwinRecordsTheSameRun) {
  const std::string dir = scratch_dir("recording_overhead");
  std::string out;
  const nlohmann::json j = profile_json(
      "pyramid --base 4 --steps 10 --recording-overhead " + dir + "/twin.rec", "ro_json", &out);
  EXPECT_NE(out.find("ms/step recording vs"), std::string::npos) << out;
  const ToolRun replay = run_tool("replay " + dir + "/twin.rec");
  EXPECT_EQ(replay.exit_code, 0) << replay.err;
  EXPECT_NE(replay.out.find("10 steps and 0 other calls replayed, every step matched; state hash " +
                            j["state_hash"].get<std::string>()),
            std::string::npos)
      << replay.out;
}

TEST(ContactProfile, HelpNamesTheContactScenesAndTheirOptions) {
  const ToolRun help = run_tool("profile --help");
  EXPECT_EQ(help.exit_code, 0);
  for (const char* word : {"pyramid", "pile", "--base", "--count", "--recording-overhead"})
    EXPECT_NE(help.out.find(word), std::string::npos) << word;
}

TEST(ContactProfile, BadContactSceneOptionsAreNamed) {
  const struct {
    const char* arguments;
    const char* message;
  } lines[] = {
      {"profile pyramid --base 0", "--base: value 0: expected a whole number in [1, 1000]"},
      {"profile pyramid --base 2000", "--base: value 2000"},
      {"profile chain --base 5", "--base: a pyramid option, not for scene chain"},
      {"profile pyramid --count 5",
       "--count: a ragdoll, vehicle, suspension-bridge or pile option, not for scene pyramid"},
      {"profile pile --count 0", "--count: value 0"},
      {"profile pile --base 3", "--base: a pyramid option, not for scene pile"},
      {"profile pyramid --record a.rec --recording-overhead b.rec",
       "--record excludes --recording-overhead"},
  };
  for (const auto& line : lines) {
    const ToolRun run = run_tool(line.arguments);
    EXPECT_EQ(run.exit_code, 2) << line.arguments;
    EXPECT_NE(run.err.find(line.message), std::string::npos) << line.arguments << ": " << run.err;
  }
}

}  // namespace
}  // namespace softstep::tool_test
