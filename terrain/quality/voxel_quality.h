#pragma once
// Region quality judged against a map's raw voxels (for scans with no box description:
// real sensor maps). Independent of the extractor: it reads only the occupancy map's
// leaves, never the height map or the segmentation, so it can judge them.
//
// Definitions (resolution r, every leaf split into voxels of edge r):
// - a *seen surface voxel* is occupied, its voxel above is known free (a ray passed
//   above it: seen from above) and no voxel within the clearance above it is occupied;
// - the *seen floor* is the seen surface voxels of the map's dominant level (the most
//   common surface height, within floor_band_m);
// - the *certifiable floor* is the seen floor eroded by erosion_m in plan view, the floor
//   taken as a set (the union of its columns' squares): a floor column's centre is
//   certifiable when every column whose square comes closer than erosion_m to it holds a
//   seen surface voxel within one voxel of its height. No sound extractor can certify
//   more (a foot plus margin plus a voxel of edge uncertainty must fit on seen surface).
//   The figure of the older, half a voxel more lenient judge (only columns whose
//   *centre* lies within erosion_m) is kept beside it (certifiable_centre_*);
// - a region point is *sound* when its column holds a seen surface voxel whose top lies
//   within one voxel plus the region's plane tolerance of the point.
#include <Eigen/Core>

#include <vector>

#include "geometry/convex_region.h"
#include "terrain/extraction/occupancy_map.h"

namespace mfp {

struct VoxelQualityOptions {
  double clearance_m = 0.4;     // free of occupied voxels above a seen surface [m]
  double erosion_m = 0.07;      // foot radius + 1 cm + one voxel, typically [m]
  double floor_band_m = 0.1;    // floor voxels lie within this of the dominant height [m]
  double sample_step_m = 0.0;   // region sampling step; 0: the map's resolution [m]
  bool list_missed = false;     // fill VoxelQuality::missed_certifiable
};

struct VoxelQuality {
  double floor_height_m = 0.0;      // top of the dominant level's voxels [m]
  int seen_surface_voxels = 0;      // anywhere in the map
  int seen_floor_cells = 0;         // of the dominant level
  double seen_floor_m2 = 0.0;
  int certifiable_floor_cells = 0;
  int certifiable_covered_cells = 0;  // certifiable floor cells inside a region at their height
  double certifiable_coverage = 0.0;  // covered / certifiable (0 when nothing is certifiable)
  // The same by the centre-to-centre erosion (a column is certifiable when every column
  // whose centre lies within erosion_m of its centre holds floor): a superset.
  int certifiable_centre_floor_cells = 0;
  int certifiable_centre_covered_cells = 0;
  double certifiable_centre_coverage = 0.0;
  double seen_floor_coverage = 0.0;   // seen floor cells inside a region / seen floor cells
  int region_samples = 0;
  int sound_samples = 0;
  double soundness = 1.0;             // sound / samples (1 without regions)
  Eigen::Vector3d worst_point = Eigen::Vector3d::Zero();  // an unsound sample, if any
  // With list_missed: the certifiable floor cells no region covers, as (x, y) of the
  // voxel column's centre and the top of its surface voxel [m].
  std::vector<Eigen::Vector3d> missed_certifiable;
};

// Throws InputError when the map's resolution is not positive or options are out of range.
VoxelQuality JudgeRegionsAgainstVoxels(const std::vector<ConvexRegion>& regions, const OccupancyMap& map,
                                       const VoxelQualityOptions& options);

}  // namespace mfp
