#pragma once
// Walks on real scans (issue 25): for each scan and robot, walks of a few metres between
// points of the scan's seen floor where the robot's nominal stance fits (every foot spot
// on seen floor, room above it), planned as mfp-plan plans them (regions and seen surface
// of the map, the robot's options), and each plan judged independently against the raw
// voxels: every footstep on a voxel seen from above with room above it.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/scenario_yaml.h"
#include "planner/robot/robot_model.h"
#include "terrain/extraction/occupancy_map.h"

namespace mfp {

struct ScanWalkOptions {
  int walks = 4;              // per scan and robot
  double min_length_m = 2.0;  // start to goal, straight line
  double max_length_m = 10.0;
  double time_limit_s = 20.0; // per plan
  // Endpoints are drawn from this seed (mixed per scan and robot by WalkDrawSeed); 25 is
  // the draw of the walks recorded in docs/measurements.md unless they name another.
  unsigned seed = 25;
  bool verbose = false;       // a line per walk
  // Every nominal foot of both ends on certifiable floor (seen floor for the foot radius +
  // 1 cm + one voxel around it), not merely on a seen floor cell: walks whose ends any
  // sound extractor could cover.
  bool certifiable_ends = false;
  // Both ends with room for the body: no occupied voxel in the body's height band (above
  // the mean height of the stance's feet) over its plan box (robots with a known body).
  bool body_room_ends = false;
  // Keep only walks whose ends certifiable floor joins by steps (the judge's
  // CertifiableFloorJoins on the raw voxels, independent of mfp's regions): walks a robot
  // could walk. The unjoined walks drawn on the way (up to `walks` of them) are run as a
  // second population, where the right answer is a status naming where and why.
  bool joined_ends = false;
  // With joined_ends, also every leg's own way (LegNotJoinedAtItsHeight): certifiable floor
  // joins its start spot to its goal spot from its own start height, by hops that change
  // height by at most dz_max, as the robot's steps do. Where a voxel is taller than dz_max
  // (new_college's 20 cm), a foot cannot change level, and ends whose feet would have to
  // are walks no sound planner can plan; off by default, so the recorded draws stay.
  bool legs_joined_ends = false;
  // Plan only the walk of this index (0-based) of each scan and robot's draw (-1: all):
  // to re-run one walk alone, with the same draw.
  int only_walk = -1;
  // The extractor's enclosed_unseen_radius_cells for the walks' regions (-1: its default).
  int enclosed_unseen_radius_cells = -1;
  // The extractor's convex_cover for the walks' regions (-1: its default, 0 off, 1 on).
  int convex_cover = -1;
  // The extractor's cover target and regions per m^2 (negative: its defaults).
  double target_coverage = -1.0;
  double regions_per_m2 = -1.0;
  // The extractor's max_regions for the walks' regions (-1: its default).
  int max_regions = -1;
  // The planner's reach polygon (robot_model.h), replacing the robot file's; unset: the
  // file's. The draw and the judge never depend on it: they use the robot derived with
  // the paper's box, so both shapes are judged on the same walks.
  std::optional<ReachShape> reach_shape;
  // With verbose, a failed walk's feet on no region print a map of this many cells each
  // way around them (CellMapText: the extractor's fates and the raw voxels' kinds; 0: none).
  int cell_map_cells = 0;
};

// The seed of one scan and robot's draw: the walks' seed mixed with the scan's file name
// (not its directory, so a draw does not change with where the scan is stored) and the
// robot's name, so that each scan and robot draws its own walks.
unsigned WalkDrawSeed(unsigned seed, const std::string& scan_path, const std::string& robot_name);

// The first leg (0-based; -1: none) whose way certifiable floor does not join: from the
// floor at its nominal spot in the start pose to the floor at its nominal spot in the goal
// pose, by hops of the robot's step span that change height by at most its dz_max, judged
// on the map's voxels as the walks' judge does (legs whose spots have no seen floor pass).
int LegNotJoinedAtItsHeight(const OccupancyMap& map, const std::string& robot_path, const Pose2D& start,
                            const Pose2D& goal);

// The ends (start, goal) of the walks BenchScanWalks draws for one scan and robot, in its
// order: the judged walks, then, with o.joined_ends, the unjoined ones met on the way.
std::vector<std::pair<Pose2D, Pose2D>> DrawWalkEnds(const OccupancyMap& map, const std::string& scan_path,
                                                    const std::string& robot_path, const ScanWalkOptions& o);

// Prints a table: scan, robot, walks, valid to the goal, walks whose start had a foot on
// no region (accepted on the seen surface), goals moved, footsteps off the seen voxels,
// walks with an end whose body band holds occupied voxels (body_ends), statuses. Returns the number of
// walks that ended valid at their goal (or at the goal moved within its tolerance).
int BenchScanWalks(const std::vector<std::string>& scans, const std::vector<std::string>& robots,
                   const ScanWalkOptions& options);

}  // namespace mfp
