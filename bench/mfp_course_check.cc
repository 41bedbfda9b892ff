// mfp-course-check: judges a plan JSON (mfp-plan --json) against the true boxes of a
// scenario (a generated course or any scenario with boxes), not against mfp's regions.
// Exit codes: 0 every footstep valid and the goal reached, 3 otherwise, 2 bad input.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <fstream>
#include <iostream>

#include "base/check.h"
#include "bench/course_checker.h"
#include "bench/course_generator.h"
#include "io/cli_parse.h"
#include "io/robot_loader.h"
#include "io/scenario_yaml.h"

int main(int argc, char** argv) {
  CLI::App app{"mfp-course-check: a plan judged against the true geometry of its course"};
  std::string scenario_path, plan_path;
  app.add_option("--scenario", scenario_path, "scenario YAML with terrain boxes")->required();
  app.add_option("--plan", plan_path, "plan JSON written by mfp-plan --json")->required();
  MFP_CLI_PARSE(app, argc, argv);
  try {
    const mfp::Scenario scenario = mfp::LoadScenario(scenario_path);
    if (scenario.terrain.boxes.empty()) throw mfp::InputError(scenario_path + ": the checker needs terrain boxes");
    const mfp::RobotModel robot = mfp::LoadRobot(scenario.robot_path);
    std::ifstream in(plan_path);
    if (!in) throw mfp::InputError("cannot read " + plan_path);
    const nlohmann::json j = nlohmann::json::parse(in);
    std::vector<mfp::Footstep> steps;
    for (const auto& f : j.at("footsteps")) {
      mfp::Footstep s;
      s.leg = f.at("leg").get<int>();
      s.position_world_m = {f.at("x").get<double>(), f.at("y").get<double>(), f.at("z").get<double>()};
      s.yaw_rad = f.at("yaw").get<double>();
      steps.push_back(s);
    }
    const mfp::CourseVerdict v = mfp::CheckPlanOnCourse(scenario.terrain, robot, steps, scenario.goal,
                                                        robot.foot_radius_m + mfp::kCourseEdgeMargin);
    for (const auto& e : v.violations) std::cout << "violation: " << e << "\n";
    std::cout << (v.valid ? "valid" : "INVALID") << ", " << (v.reaches_goal ? "reaches the goal" : "does NOT reach the goal")
              << "\n";
    return v.valid && v.reaches_goal ? 0 : 3;
  } catch (const std::exception& e) {
    std::cerr << "mfp-course-check: " << e.what() << "\n";
    return 2;
  }
}
