#include "python/python_planner.h"

#include <chrono>
#include <memory>

#include "base/check.h"
#include "io/height_map_file.h"
#include "io/plan_json.h"
#include "planner/planning/footstep_planner.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "terrain/extraction/region_extractor.h"
#include "terrain/octomap/octomap_io.h"

namespace mfp {
namespace {

bool RejectsInput(SolveStatus status) {
  return status == SolveStatus::kInvalidRequest || status == SolveStatus::kInvalidStart ||
         status == SolveStatus::kInvalidGoal || status == SolveStatus::kNoMap;
}

}  // namespace

PythonTerrain TerrainFromFile(const std::string& path) {
  PythonTerrain terrain;
  terrain.source = path;
  if (IsHeightMapPath(path)) {
    terrain.grid = LoadHeightGridFile(path);
  } else {
    terrain.map = LoadMapFile(path);
  }
  return terrain;
}

std::vector<ConvexRegion> TerrainRegions(const PythonTerrain& terrain, const RegionExtractorOptions& options,
                                         std::string* note) {
  MFP_CHECK(terrain.grid.has_value() != terrain.map.has_value());
  RegionExtractionResult result =
      terrain.grid ? ExtractRegionsFromHeightGrid(*terrain.grid, options) : ExtractRegions(*terrain.map, options);
  if (note != nullptr) *note = result.message;
  return std::move(result.regions);
}

PythonPlanResult PlanOnTerrain(const RobotModel& robot, const PythonTerrain& terrain,
                               const PythonPlanInputs& inputs) {
  // The steps of mfp-plan's main, in its order, with a scenario made from the flags.
  const auto run_start = std::chrono::steady_clock::now();
  Scenario scenario;
  scenario.name = terrain.source;
  scenario.start = inputs.start;
  scenario.goal = inputs.goal;
  const double run_limit = inputs.time_limit_s > 0 ? inputs.time_limit_s : scenario.options.default_time_limit_s;
  const Deadline run_deadline = Deadline::After(
      run_limit - std::chrono::duration<double>(std::chrono::steady_clock::now() - run_start).count());
  PythonPlanResult out;
  const RegionExtractorOptions extraction = ScenarioRegionOptions(scenario, robot, run_deadline);
  RegionExtractionResult extracted =
      terrain.grid ? ExtractRegionsFromHeightGrid(*terrain.grid, extraction) : ExtractRegions(*terrain.map, extraction);
  ScenarioTerrain scenario_terrain{std::move(extracted.regions),
                                   std::make_shared<const SeenSurface>(SeenSurfaceOfLayers(extracted.layers, extracted.moved_as_seen, extracted.filled)),
                                   extracted.message, std::nullopt, ""};
  TakeBodyObstacles(extracted, &scenario_terrain);
  out.regions = scenario_terrain.regions;
  PlannerOptions& options = scenario.options;
  if (!inputs.relaxation_solver.empty()) options.solvers.backend = ParseRelaxationBackend(inputs.relaxation_solver);
  PlanRequest request = ScenarioRequest(scenario, robot, scenario_terrain);
  if (inputs.max_steps > 0) request.max_steps = inputs.max_steps;
  if (inputs.window > 0) request.window_steps = inputs.window;
  if (inputs.time_limit_s > 0) request.time_limit_s = inputs.time_limit_s;
  request.deadline = run_deadline;
  if (inputs.threads > 0) options.solvers.threads = inputs.threads;
  if (!inputs.polish) options.polish.enabled = false;
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(options.solvers);
  out.plan = PlanFootsteps(robot, out.regions, request, options, solvers.workers());
  if (RejectsInput(out.plan.status)) throw InputError(out.plan.message);
  out.json = PlanToJson(out.plan, robot, out.regions)
                 .dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
  return out;
}

}  // namespace mfp
