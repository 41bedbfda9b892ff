#pragma once
// A terrain made of solid boxes (ground slabs, stepping stones, tilted blocks). Used to
// write scenario courses once and get both exact top-face regions and OctoMap maps
// (mfp-terrain) from them.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "geometry/convex_region.h"

namespace mfp {

struct TerrainBox {
  std::string name;
  Eigen::Vector3d center_world_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d size_m = Eigen::Vector3d::Ones();       // full extents along the box axes
  Eigen::Vector3d rpy_rad = Eigen::Vector3d::Zero();      // roll, pitch, yaw (extrinsic X, Y, Z)
};

// How a map is made from the boxes as a real one is: rays cast from sensor positions
// mark the voxel they first hit occupied and the voxels they pass through free. With no
// sensors the map is the plain voxelisation (every voxel whose centre is inside a box
// occupied, no free space known).
struct SensorScan {
  std::vector<Eigen::Vector3d> sensors_world_m;  // ray origins [m, world]
  double max_range_m = 6.0;                      // rays end here when they hit nothing [m]
};

// Scan noise, applied to the map's top surfaces after it is made (seeded, repeatable).
struct MapNoise {
  unsigned seed = 1;
  double jitter_fraction = 0.0;  // top voxels moved up or down by one voxel
  double hole_fraction = 0.0;    // top voxels missing (neither occupied nor free)
  int outliers = 0;              // isolated occupied voxels in open space
  bool Any() const { return jitter_fraction > 0.0 || hole_fraction > 0.0 || outliers > 0; }
};

struct TerrainDescription {
  std::vector<TerrainBox> boxes;
  double resolution_m = 0.02;  // voxel size when the description is turned into a map
  SensorScan scan;             // no sensors: plain voxelisation
  MapNoise noise;              // none by default
};

// Rotation of a box: R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Matrix3d BoxRotation(const TerrainBox& box);

// The eight corners of a box in the world frame.
std::vector<Eigen::Vector3d> BoxCorners(const TerrainBox& box);

// Where the ray o + t d (world frame) passes through the box of rotation R (BoxRotation):
// the ray parameters [*t_in, *t_out] where it enters and leaves the box's slabs (t may be
// negative: the line, not only the ray). False when it misses the box; a direction
// component below parallel_tol (box frame) counts as parallel to those faces.
bool RayBoxInterval(const TerrainBox& box, const Eigen::Matrix3d& R, const Eigen::Vector3d& o,
                    const Eigen::Vector3d& d, double parallel_tol, double* t_in, double* t_out);

// Exact top-face regions: for each box, the face whose outward normal points most
// upward, inset by inset_m, minus the parts other boxes cover (where another box rises
// above the face, grown by inset_m), as ConvexRegions with ids 0, 1, ... in box order.
// An uncovered face is one region; a partly covered face is cut into several convex
// pieces, a fully covered face gives none. Faces on one plane that touch or overlap
// (a walkway of rotated boxes, a floor of tiles, a landing beside a floor of its height)
// are one surface: their union is inset once (no strip lost along a seam) and cut into
// few convex pieces (InsetUnionOfConvexPolygons), placed at their first box. Boxes whose
// top face is steeper than max_slope_rad or (alone) vanishes after the inset are skipped.
// Throws InputError on non-finite or non-positive sizes.
std::vector<ConvexRegion> TopFaceRegions(const TerrainDescription& terrain, double inset_m,
                                         double max_slope_rad);

}  // namespace mfp
