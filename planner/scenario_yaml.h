#pragma once
// Scenario files (config/scenarios/*.yaml): a robot, a terrain, a start and a goal, and
// optional planner settings. The terrain is one of: boxes (a course description whose
// top faces are the regions, also turned into maps by mfp-terrain), explicit convex
// regions (polygons on planes, for users with regions from elsewhere), or a map file.
#include <string>
#include <vector>

#include "planner/footstep_planner.h"
#include "planner/robot_model.h"
#include "terrain/convex_region.h"
#include "terrain/terrain_description.h"

namespace mfp {

struct Pose2D {
  double x_m = 0.0, y_m = 0.0, yaw_rad = 0.0;
};

struct Scenario {
  std::string name;
  std::string path;        // the YAML file
  std::string robot_path;  // resolved relative to the scenario file
  TerrainDescription terrain;                // boxes, when given
  std::vector<ConvexRegion> listed_regions;  // explicit regions, when given
  std::string map_path;                      // map file, when given
  Pose2D start, goal;
  int max_steps = 0;        // 0: planner default
  int window_steps = 0;     // 0: planner default
  double time_limit_s = 0;  // 0: planner default
  PlannerOptions options;
};

// Throws InputError naming the file, key and allowed range.
Scenario LoadScenario(const std::string& path);

// The scenario's regions: listed regions as given, box top faces inset by the robot's
// foot radius and filtered by its slope limit. Map files are handled by the terrain
// pipeline (tools pass them through RegionsFromMapFile).
std::vector<ConvexRegion> RegionsFromDescription(const Scenario& scenario, const RobotModel& robot);

}  // namespace mfp
