// mfp-plan as a user runs it: exit codes (0 reached, 2 bad input, 3 not reached), error
// messages that name the problem, and the plan JSON contract of DESIGN.md.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <sys/wait.h>

#include "tests/test_temp_path.h"

namespace {

const std::string kPlan = std::string(MFP_BINARY_DIR) + "/tools/mfp-plan";
const std::string kScenarios = std::string(MFP_SOURCE_DIR) + "/config/scenarios/";

struct Outcome {
  int code;
  std::string err;
};

Outcome Execute(const std::string& args) {
  const std::string err_file = mfp::TestTempPath("stderr.txt");
  const int status = std::system((kPlan + " " + args + " --quiet 2> " + err_file + " > /dev/null").c_str());
  std::ifstream in(err_file);
  std::stringstream text;
  text << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

TEST(MfpPlanCli, MissingScenarioIsBadInputNamingTheFile) {
  const Outcome r = Execute("--scenario /nonexistent/scenario.yaml");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("/nonexistent/scenario.yaml"), std::string::npos) << r.err;
}

TEST(MfpPlanCli, MalformedPoseIsBadInput) {
  const Outcome r = Execute("--scenario " + kScenarios + "littledog_flat.yaml --goal 1,2");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--goal"), std::string::npos) << r.err;
  EXPECT_EQ(Execute("--scenario " + kScenarios + "littledog_flat.yaml --goal 1,nan,0").code, 2);
}

TEST(MfpPlanCli, GoalOrStartOffTheMapIsBadInput) {
  Outcome r = Execute("--scenario " + kScenarios + "littledog_flat.yaml --goal 9,9,0");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("goal"), std::string::npos) << r.err;
  r = Execute("--scenario " + kScenarios + "littledog_flat.yaml --start -5,0,0");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("start foot"), std::string::npos) << r.err;
}

TEST(MfpPlanCli, OutOfRangeFlagIsBadInput) {
  EXPECT_EQ(Execute("--scenario " + kScenarios + "littledog_flat.yaml --max-steps 0").code, 2);
  EXPECT_EQ(Execute("--scenario " + kScenarios + "littledog_flat.yaml --relaxation-solver gurobi").code, 2);
}

TEST(MfpPlanCli, TooFewStepsExitsThree) {
  EXPECT_EQ(Execute("--scenario " + kScenarios + "littledog_flat.yaml --max-steps 4").code, 3);
}

TEST(MfpPlanCli, PlanJsonFollowsTheContract) {
  const std::string json_path = mfp::TestTempPath("plan.json");
  const std::string mps_path = mfp::TestTempPath("plan.mps");
  const Outcome r = Execute("--scenario " + kScenarios + "littledog_flat.yaml --json " + json_path + " --write-mps " +
                        mps_path + " --validate");
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(json_path);
  const nlohmann::json plan = nlohmann::json::parse(in);
  for (const char* key : {"status", "reaches_goal", "objective", "bound", "gap", "solve_time_s", "nodes",
                          "integer_variables", "objective_offset", "robot", "regions", "footsteps"}) {
    EXPECT_TRUE(plan.contains(key)) << key;
  }
  EXPECT_TRUE(plan["reaches_goal"].get<bool>());
  EXPECT_EQ(plan["robot"]["legs"].size(), 4u);
  EXPECT_EQ(plan["robot"]["gait"].size(), 4u);
  ASSERT_GT(plan["footsteps"].size(), 4u);
  for (size_t i = 0; i < plan["footsteps"].size(); ++i) {
    const auto& f = plan["footsteps"][i];
    EXPECT_EQ(f["index"].get<int>(), static_cast<int>(i));
    for (const char* key : {"leg", "x", "y", "z", "yaw", "region"}) EXPECT_TRUE(f.contains(key)) << key;
  }
  ASSERT_GE(plan["regions"].size(), 1u);
  const auto& region = plan["regions"][0];
  EXPECT_EQ(region["A"].size(), region["b"].size());
  EXPECT_EQ(region["A"][0].size(), 3u);
  std::ifstream mps(mps_path);
  std::stringstream text;
  text << mps.rdbuf();
  EXPECT_NE(text.str().find("QUADOBJ"), std::string::npos);
  EXPECT_NE(text.str().find("ENDATA"), std::string::npos);
}

// DESIGN.md: `--window N --max-steps N` is one MIQP of N steps. On this scenario the
// 24-step window trims steps short of the goal: no second window may take the steps left
// (before stop 39 one did: `windows` 2).
TEST(MfpPlanCli, WindowEqualToMaxStepsIsOneMiqp) {
  const std::string json_path = mfp::TestTempPath("one_window.json");
  const Outcome r = Execute("--scenario " + kScenarios + "hexapod_stepping_stones_45.yaml --window 24 --max-steps 24 " +
                            "--time-limit 5 --json " + json_path);
  ASSERT_EQ(r.code, 3) << r.err;  // 24 steps do not reach this goal
  std::ifstream in(json_path);
  const nlohmann::json plan = nlohmann::json::parse(in);
  EXPECT_EQ(plan["windows"].get<int>(), 1);
  EXPECT_GT(plan["steps"].get<int>(), 0);
}

}  // namespace

namespace {

// Issue 19: a YAML key that is a list aborted mfp-plan (SIGABRT, an uncaught yaml-cpp
// exception); a map far finer than the foot took tens of seconds. Both are exit 2 now.
TEST(MfpPlanCli, HostileScenarioAndMapAreBadInputNotASignal) {
  const std::string scenario = mfp::TestTempPath("key.yaml");
  std::ofstream(scenario) << "robot: " << MFP_SOURCE_DIR << "/config/robots/hexapod.yaml\n? [a, b]\n: 1\n";
  Outcome r = Execute("--scenario " + scenario);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("a key is a list"), std::string::npos) << r.err;

  // The flat course as a map, its resolution line rewritten to 0.1 mm.
  const std::string coarse = mfp::TestTempPath("flat.bt"), fine = mfp::TestTempPath("fine.bt");
  ASSERT_EQ(std::system((std::string(MFP_BINARY_DIR) + "/tools/mfp-terrain " + kScenarios +
                         "hexapod_flat.yaml --out " + coarse + " > /dev/null 2>&1").c_str()), 0);
  std::ifstream in(coarse, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), {});
  const size_t at = bytes.find("res 0.02\n");
  ASSERT_NE(at, std::string::npos);
  bytes.replace(at, 9, "res 0.0001\n");
  std::ofstream(fine, std::ios::binary) << bytes;
  r = Execute("--robot " + std::string(MFP_SOURCE_DIR) + "/config/robots/hexapod.yaml --terrain " + fine +
              " --start 0,0,0 --goal 1,0,0 --time-limit 10");
  // 10 s: the robot's derivation comes first and must not run out of time on a loaded
  // machine; the map is refused by its header, long before any limit.
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("resolution 0.0001 m is too fine"), std::string::npos) << r.err;
}

}  // namespace
