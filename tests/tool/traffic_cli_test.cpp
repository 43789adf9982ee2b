// `softstep profile --bandwidth`: the memory section's fraction of the bound is the model's
// bytes over the step's time over the bandwidth given, in the table and in the JSON alike.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "run_tool.hpp"

namespace softstep::tool_test {
namespace {

TEST(ToolTraffic, TheBoundFractionIsTheModelsBytesOverTheStepTimeAndTheBandwidth) {
  const std::string dir = scratch_dir("traffic");
  const ToolRun run = run_tool(
      "profile chain --links 50 --chains 4 --steps 5 --threads 1 --bandwidth 25 --json " + dir +
      "/p.json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.out.find("of bound"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("(of 25.0 GB/s"), std::string::npos) << run.out;
  const nlohmann::json j = nlohmann::json::parse(read_text(dir + "/p.json"));
  const nlohmann::json& memory = j.at("memory");
  const double bytes = memory.at("model_bytes_per_step").get<double>();
  const double ms = j.at("ms_per_step").get<double>();
  ASSERT_GT(bytes, 0.0);
  EXPECT_DOUBLE_EQ(memory.at("bandwidth_gb_per_s").get<double>(), 25.0);
  EXPECT_NEAR(memory.at("bound_fraction").get<double>(), bytes / (ms * 1e6) / 25.0,
              1e-12 * bytes);
  for (const char* stage : {"prepare", "solve", "relax", "store"})
    EXPECT_TRUE(memory.at("stages").contains(stage)) << stage;
  EXPECT_TRUE(memory.at("stages").at("solve").contains("bytes_per_row"));
  EXPECT_TRUE(memory.at("stages").at("store").contains("bytes_per_body"));
}

TEST(ToolTraffic, WithoutABandwidthThereIsNoFraction) {
  const std::string dir = scratch_dir("traffic_plain");
  const ToolRun run =
      run_tool("profile chain --links 20 --steps 3 --threads 1 --json " + dir + "/p.json");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out.find("of bound"), std::string::npos);
  const nlohmann::json j = nlohmann::json::parse(read_text(dir + "/p.json"));
  EXPECT_FALSE(j.at("memory").contains("bound_fraction"));
}

TEST(ToolTraffic, ANonPositiveBandwidthIsRefusedByName) {
  const ToolRun run = run_tool("profile chain --links 20 --steps 1 --bandwidth 0");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--bandwidth"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace softstep::tool_test
