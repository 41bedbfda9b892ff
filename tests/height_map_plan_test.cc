// One scenario given three ways - as boxes, as an OctoMap file and as a height-map file
// (.npy with its YAML) - plans to the goal each time, with every footstep on the true
// surface of the boxes (a foot disk on a real top face, within the height the map can
// tell: half a cell for the height map, a voxel for the voxel maps).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "io/internal/npy_array.h"
#include "io/robot_loader.h"
#include "io/scenario_yaml.h"
#include "planner/planning/footstep_planner.h"
#include "planner/planning/plan_validation.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "terrain/octomap/octomap_io.h"
#include "terrain/quality/height_grid_sampling.h"
#include "terrain/quality/terrain_quality.h"
#include "tests/test_temp_path.h"

namespace mfp {
namespace {

// Writes BASE.npy and BASE.yaml; returns BASE.npy.
std::string WriteHeightMapFiles(const HeightGrid& grid, const std::string& base) {
  NpyArray a;
  a.rows = static_cast<size_t>(grid.nx);
  a.cols = static_cast<size_t>(grid.ny);
  a.values = grid.heights_m;
  const std::vector<uint8_t> bytes = NpyBytes(a);
  std::ofstream(base + ".npy", std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                                         static_cast<std::streamsize>(bytes.size()));
  std::ostringstream yaml;
  yaml.precision(17);
  yaml << "resolution: " << grid.resolution_m << "\norigin: [" << grid.origin_m.x() << ", " << grid.origin_m.y()
       << "]\nunknown: nan\n";
  std::ofstream(base + ".yaml") << yaml.str();
  return base + ".npy";
}

enum class Source { kBoxes, kOctomap, kHeightMap };

class ThreeSources : public ::testing::TestWithParam<Source> {};

TEST_P(ThreeSources, PlansToTheGoalWithEveryFootOnTheTrueSurface) {
  Scenario scenario = LoadScenario(std::string(MFP_SOURCE_DIR) + "/config/scenarios/hexapod_stepping_stones_45.yaml");
  const TerrainDescription truth = scenario.terrain;
  const double res = truth.resolution_m;
  if (GetParam() == Source::kOctomap) {
    scenario.map_path = TestTempPath("stones.bt");
    WriteTerrainMap(truth, scenario.map_path);
  } else if (GetParam() == Source::kHeightMap) {
    scenario.map_path = WriteHeightMapFiles(SampleHeightGrid(truth, res), TestTempPath("stones"));
  }
  const RobotModel robot = LoadRobot(scenario.robot_path);
  const std::vector<ConvexRegion> regions = ScenarioRegions(scenario, robot);
  ASSERT_FALSE(regions.empty());
  PlanRequest request = ScenarioRequest(scenario, robot, regions);
  request.time_limit_s = 300.0;  // generous: a slow machine changes the time, not the outcome
  const auto solver = MakeRelaxationSolver(scenario.options.solvers.backend);
  const Plan plan = PlanFootsteps(robot, regions, request, scenario.options, *solver);
  ASSERT_TRUE(plan.reaches_goal) << ToString(plan.status) << ": " << plan.message;
  const GoalSpec goal{scenario.goal.x_m, scenario.goal.y_m, scenario.goal.yaw_rad,
                      scenario.options.goal_tolerance_m, scenario.options.goal_yaw_tolerance_rad};
  for (const std::string& v : ValidatePlan(robot, regions, plan, goal, ValidationTolerances())) ADD_FAILURE() << v;
  // Heights: a region's plane slab is half a voxel thick either way; a voxel map also puts
  // a top face between voxel levels up to half a voxel off, a height map keeps it exact.
  const double height_tol_m = GetParam() == Source::kHeightMap ? 0.5 * res + 1e-6 : res + 1e-6;
  for (const Footstep& f : plan.footsteps) {
    EXPECT_TRUE(FootOnTrueSurface(truth, f.position_world_m, robot.foot_radius_m, robot.max_slope_rad, height_tol_m))
        << "footstep " << f.index << " at " << f.position_world_m.transpose() << " is off the true surface";
  }
}

INSTANTIATE_TEST_SUITE_P(HeightMapPlan, ThreeSources,
                         ::testing::Values(Source::kBoxes, Source::kOctomap, Source::kHeightMap),
                         [](const ::testing::TestParamInfo<Source>& info) {
                           return info.param == Source::kBoxes     ? std::string("Boxes")
                                  : info.param == Source::kOctomap ? std::string("Octomap")
                                                                   : std::string("HeightMap");
                         });

}  // namespace
}  // namespace mfp
