#pragma once
// Scenario files (config/scenarios/*.yaml): a robot, a terrain, a start and a goal, and
// optional planner settings. The terrain is one of: boxes (a course description whose
// top faces are the regions, also turned into maps by mfp-terrain), explicit convex
// regions (polygons on planes, for users with regions from elsewhere), or a map file.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geometry/convex_region.h"
#include "geometry/seen_surface.h"
#include "geometry/terrain_description.h"
#include "io/option_table.h"
#include "planner/planning/footstep_planner.h"
#include "planner/robot/robot_model.h"
#include "terrain/extraction/region_extractor.h"

namespace mfp {

struct Pose2D {
  double x_m = 0.0, y_m = 0.0, yaw_rad = 0.0;
};

// Where the regions of a box terrain come from: the map pipeline (voxelise the boxes,
// extract regions as from any OctoMap; the default, as on the robot) or the boxes' exact
// top faces (no perception error; for comparisons and debugging).
enum class BoxRegionSource { kExtracted, kTopFaces };

struct Scenario {
  std::string name;
  std::string path;        // the YAML file
  std::string robot_path;  // resolved relative to the scenario file
  TerrainDescription terrain;                // boxes, when given
  BoxRegionSource boxes_source = BoxRegionSource::kExtracted;
  std::vector<ConvexRegion> listed_regions;  // explicit regions, when given
  std::string map_path;                      // map file, when given
  // Real surface kept around each foot beyond its radius (terrain: edge_margin) [m];
  // unset: the extractor's default (RegionExtractorOptions::edge_margin_m).
  std::optional<double> edge_margin_m;
  // Smallest region of foot centres kept (terrain: min_region_area) [m^2], exactly; unset:
  // the extractor's default (RegionExtractorOptions::min_region_area_m2, or on fine maps
  // min_region_area_voxels voxels). Stones barely wider than a foot plus its edge
  // margins need less than the default.
  std::optional<double> min_region_area_m2;
  // Whether one patch's regions may overlap (terrain: overlapping_regions); unset: the
  // extractor's default (RegionExtractorOptions::overlapping_regions).
  std::optional<bool> overlapping_regions;
  Pose2D start, goal;
  int max_steps = 0;        // 0: planner default
  int window_steps = 0;     // 0: planner default
  double time_limit_s = 0;  // 0: planner default
  PlannerOptions options;
  // What the file should change (flat planner keys, read as aliases); the tools print them.
  std::vector<std::string> warnings;
};

// Throws InputError naming the file, key and allowed range.
Scenario LoadScenario(const std::string& path);

// The keys of a scenario file (those of its planner: block are PlannerOptionDocs()).
const OptionTable<Scenario>& ScenarioOptionTable();
std::vector<OptionDoc> ScenarioOptionDocs();

// The scenario's regions for this robot (foot radius, slope limit): listed regions as
// given; a map file or the boxes through the terrain pipeline; or the boxes' top faces.
// `note` (optional) receives the extractor's message when it finds no region or the
// deadline ended it (then the regions of the patches done so far are returned).
std::vector<ConvexRegion> ScenarioRegions(const Scenario& scenario, const RobotModel& robot,
                                          std::string* note = nullptr,
                                          const Deadline& deadline = Deadline());

// A map's surface layers (RegionExtractionResult::layers: every surface seen from above
// with room above it) as the seen surface the planner accepts start feet on, with the
// cells the noise repair moved at the height they were seen (RegionExtractionResult::
// moved_as_seen): a robot stands on the voxel's top it is on. The layers' erased fills
// (RegionExtractionResult::filled: kFilledErased) are not seen surface: NaN.
SeenSurface SeenSurfaceOfLayers(const std::vector<HeightMap>& layers,
                                const std::vector<HeightMap>& moved_as_seen = {},
                                const std::vector<std::vector<uint8_t>>& filled = {});

// A scenario's terrain for one robot: its regions and the surface seen from above that they
// came from (PlanRequest::seen_surface): a map's surface layers, a box terrain's uninset
// top faces; empty for listed regions (a start foot must then be on a region).
struct ScenarioTerrain {
  std::vector<ConvexRegion> regions;
  std::shared_ptr<const SeenSurface> seen_surface = std::make_shared<const SeenSurface>();  // never null
  std::string note;  // the extractor's message when it found no region or ran out of time
  // From an occupancy map (a map file or a voxelised `terrain:`), with the planner key
  // map_body_obstacles and a known body: the map's obstacles to the body
  // (map_body_obstacles.h); ScenarioRequest passes them instead of the boxes' own.
  std::optional<std::vector<BodyObstacle>> map_body_obstacles;
  std::string body_note;  // why the map gave no body obstacles (a budget or the time ran out)
};
ScenarioTerrain LoadScenarioTerrain(const Scenario& scenario, const RobotModel& robot,
                                    const Deadline& deadline = Deadline());
// An extraction's body obstacles into terrain (map_body_obstacles), or why there are none
// (body_note); nothing when the extraction made none (the key off, or no body).
void TakeBodyObstacles(const RegionExtractionResult& result, ScenarioTerrain* terrain);

// The extractor options ScenarioRegions uses for a map or boxes: the robot's foot radius,
// slope limit and clearance, the scenario's terrain settings, the deadline.
RegionExtractorOptions ScenarioRegionOptions(const Scenario& scenario, const RobotModel& robot,
                                             const Deadline& deadline = Deadline());

// The request a scenario describes: the robot's nominal stance at the start pose (feet on
// the regions below them), the goal, and the scenario's step and time settings.
PlanRequest ScenarioRequest(const Scenario& scenario, const RobotModel& robot,
                            const std::vector<ConvexRegion>& regions);

// The same with the terrain's seen surface: the request carries it, and a start foot with
// no region below it stands on the highest seen surface there.
PlanRequest ScenarioRequest(const Scenario& scenario, const RobotModel& robot, const ScenarioTerrain& terrain);

}  // namespace mfp
