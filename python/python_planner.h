#pragma once
// The Python module's work in plain C++ (no pybind11 here): terrain from a height map or
// a map file, regions for a robot, one plan as mfp-plan makes it (the same regions,
// request, options and JSON), so `mfp.plan(...).to_json()` equals `mfp-plan --json`.
#include <optional>
#include <string>
#include <vector>

#include "geometry/convex_region.h"
#include "io/scenario_yaml.h"
#include "planner/formulation/plan.h"
#include "planner/robot/robot_model.h"
#include "terrain/extraction/height_grid.h"
#include "terrain/extraction/occupancy_map.h"

namespace mfp {

// Where a Python Terrain's surfaces come from: a height grid or an occupancy map.
struct PythonTerrain {
  std::optional<HeightGrid> grid;
  std::optional<OccupancyMap> map;
  std::string source;  // for messages: the file, or "height map"
};

// Reads an OctoMap (.bt, .ot) or height-map file (.npy with its YAML, or the YAML).
// Throws InputError as LoadMapFile and LoadHeightGridFile do.
PythonTerrain TerrainFromFile(const std::string& path);

// Extracts regions with the given options (throws InputError on a bad map); `note`
// receives the extractor's message.
std::vector<ConvexRegion> TerrainRegions(const PythonTerrain& terrain, const RegionExtractorOptions& options,
                                         std::string* note = nullptr);

// What mfp.plan takes besides the robot and the terrain (mfp-plan's flags).
struct PythonPlanInputs {
  Pose2D start, goal;
  double time_limit_s = 0.0;  // 0: the planner's default, as mfp-plan without --time-limit
  int window = 0;             // --window (0: default)
  int max_steps = 0;          // --max-steps (0: default)
  int threads = 0;            // --threads (0: default)
  bool polish = true;         // false: --no-polish
  std::string relaxation_solver;  // --relaxation-solver ("" = default)
};

struct PythonPlanResult {
  Plan plan;
  std::vector<ConvexRegion> regions;
  std::string json;  // exactly the text mfp-plan --json writes
};

// Plans as mfp-plan does with --robot/--terrain/--start/--goal. Throws InputError with
// mfp-plan's message on bad input, including a request the planner rejects (invalid start
// or goal: mfp-plan's exit 2); any other outcome is a result with its status.
PythonPlanResult PlanOnTerrain(const RobotModel& robot, const PythonTerrain& terrain,
                               const PythonPlanInputs& inputs);

}  // namespace mfp
