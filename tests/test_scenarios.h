#pragma once
// Scenarios of config/scenarios/ for tests, loaded the way mfp-plan loads them.
#include <string>
#include <vector>

#include "io/robot_loader.h"
#include "io/scenario_yaml.h"
#include "planner/planning/footstep_planner.h"

namespace mfp {

// A scenario of config/scenarios/ loaded with its robot, regions and request.
struct Course {
  Scenario scenario;
  RobotModel robot;
  std::vector<ConvexRegion> regions;
  PlanRequest request;
};

inline Course LoadCourse(const std::string& file_name) {
  Course c;
  c.scenario = LoadScenario(std::string(MFP_SOURCE_DIR) + "/config/scenarios/" + file_name);
  c.robot = LoadRobot(c.scenario.robot_path);
  c.regions = ScenarioRegions(c.scenario, c.robot);
  c.request = ScenarioRequest(c.scenario, c.robot, c.regions);
  return c;
}

// A scenario's first window alone, `steps` long: one MIQP, as in the seed paper's Table I.
inline Course LoadTableICourse(const std::string& file_name, int steps) {
  Course c = LoadCourse(file_name);
  c.request.max_steps = steps;
  c.request.window_steps = steps;
  c.request.max_windows = 1;
  return c;
}

}  // namespace mfp
