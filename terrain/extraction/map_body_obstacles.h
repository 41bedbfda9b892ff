#pragma once
// The body's obstacles in an occupancy map: occupied voxels that may reach into a robot
// body's height band, merged into few axis-aligned vertical prisms (a plan rectangle over a
// z band), for the planner's body check (planner/robot/body_clearance.h: the caller turns
// each into a BodyObstacle). Whether a prism meets the body is judged per pose over that
// pose's ground; this only leaves out voxels that can never reach the band: a run of
// voxels whose top is at most floor_band_m above the lowest surface within
// ground_radius_m of it (the body's ground, the mean height of feet standing within that
// radius, is never lower). Floors and stones the feet stand on go; walls, tables, posts stay.
// Plain Eigen; no I/O.
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "base/deadline.h"
#include "terrain/extraction/occupancy_map.h"

namespace mfp {

struct MapObstacleOptions {
  // The body's band starts this far above its ground (BodyExtent::bottom_m) [m].
  double floor_band_m = 0.0;
  // How far from any point of the body's plan box a foot may stand [m] (the ground below
  // a body is the mean height of its feet).
  double ground_radius_m = 0.5;
  // Each prism's plan rectangle grown by this on every side [m]: 0 for a map whose voxel
  // is occupied when any point of it is (a sensor's), half a voxel for a voxelisation
  // that marks a voxel when its centre is inside (a true edge up to that far outside).
  double grow_m = 0.0;
  // Prism bands on multiples of this [m] (at least a voxel), so that the columns of a noisy
  // wall or of clutter share bands and merge into fewer prisms: a band's top rises by less
  // than a step; a bottom above the lowest level a body's band can reach over its column
  // (the lowest ground within ground_radius_m plus floor_band_m) sinks by less than a
  // step, a bottom below it starts at it rounded down (no body's band goes lower). 0: a
  // voxel, exact tops (a coarser step makes a stair's steps taller obstacles: a hexapod's
  // stairs course became no_route at 0.1 m, docs/measurements.md stop 28).
  double band_step_m = 0.0;
  // Budgets, checked before anything is expanded or allocated: column cells the leaves
  // cover (leaf_budget.h) and cells of the plan grid over the map's extent; and prisms made.
  uint64_t max_leaf_columns = uint64_t{1} << 25;
  uint64_t max_grid_cells = uint64_t{1} << 26;
  size_t max_prisms = 200000;
  Deadline deadline;  // checked every grid row
};

struct MapPrism {
  Eigen::Vector2d min_world_m = Eigen::Vector2d::Zero();  // plan rectangle [m, world]
  Eigen::Vector2d max_world_m = Eigen::Vector2d::Zero();
  double bottom_z_m = 0.0;  // lowest voxel's bottom [m, world]
  double top_z_m = 0.0;     // highest voxel's top [m, world]
};

struct MapObstacles {
  // Every occupied voxel that may reach a body's band lies inside one of them (when complete).
  std::vector<MapPrism> prisms;
  bool complete = true;  // false: a budget or the deadline ended it; prisms is then empty
  std::string message;   // why it is not complete
  int64_t voxel_runs = 0;        // column runs of occupied voxels in the map
  int64_t runs_above_floor = 0;  // of them, runs that may reach the band (in the prisms)
  double time_s = 0.0;
};

// Throws InputError when floor_band_m, ground_radius_m or grow_m is negative or not finite.
MapObstacles MapBodyObstacles(const OccupancyMap& map, const MapObstacleOptions& options);

}  // namespace mfp
