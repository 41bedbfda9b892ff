#pragma once
// The raw leaves of an OctoMap map, looked up voxel by voxel: the independent judges
// (voxel_quality, the scan walks of mfp-terrain-bench) read the map through this and
// nothing of mfp's extraction. Voxel (i, j, k) spans [i r, (i + 1) r) on x, and so on.
#include <cstdint>
#include <map>
#include <unordered_set>
#include <vector>

#include "terrain/extraction/occupancy_map.h"

namespace mfp {

// A key of voxel column (i, j), |i|, |j| < 2^20.
int64_t VoxelColumnKey(int64_t i, int64_t j);

// Leaves of one kind (occupied, or known free), each at its octree level.
class LeafSet {
 public:
  LeafSet(const std::vector<OccupiedLeaf>& leaves, double resolution_m);
  // Whether voxel (i, j, k) lies in one of the leaves.
  bool Contains(int64_t i, int64_t j, int64_t k) const;
  // The octree level of a leaf of this edge [m] (0: one voxel).
  int LevelOf(double size_m) const;

 private:
  double r_;
  std::map<int, std::unordered_set<int64_t>> by_level_;
};

}  // namespace mfp
