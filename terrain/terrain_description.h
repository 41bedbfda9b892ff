#pragma once
// A terrain made of solid boxes (ground slabs, stepping stones, tilted blocks). Used to
// write scenario courses once and get both exact top-face regions and OctoMap maps
// (mfp-terrain) from them.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "terrain/convex_region.h"

namespace mfp {

struct TerrainBox {
  std::string name;
  Eigen::Vector3d center_world_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d size_m = Eigen::Vector3d::Ones();       // full extents along the box axes
  Eigen::Vector3d rpy_rad = Eigen::Vector3d::Zero();      // roll, pitch, yaw (extrinsic X, Y, Z)
};

struct TerrainDescription {
  std::vector<TerrainBox> boxes;
  double resolution_m = 0.02;  // voxel size when the description is turned into a map
};

// Rotation of a box: R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Matrix3d BoxRotation(const TerrainBox& box);

// The eight corners of a box in the world frame.
std::vector<Eigen::Vector3d> BoxCorners(const TerrainBox& box);

// Exact top-face regions: for each box, the face whose outward normal points most
// upward, inset by inset_m, as a ConvexRegion with ids 0, 1, ... in box order. Boxes
// whose top face is steeper than max_slope_rad or vanishes after the inset are skipped.
// Throws InputError on non-finite or non-positive sizes.
std::vector<ConvexRegion> TopFaceRegions(const TerrainDescription& terrain, double inset_m,
                                         double max_slope_rad);

}  // namespace mfp
