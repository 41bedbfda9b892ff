#include "terrain/quality/leaf_set.h"

#include <algorithm>
#include <cmath>

namespace mfp {
namespace {

// i >> level rounded towards minus infinity: the index of the level's voxel holding i.
int64_t FloorShift(int64_t i, int level) { return i >= 0 ? i >> level : -((-i - 1) >> level) - 1; }

int64_t Key3(int64_t i, int64_t j, int64_t k) {
  return ((i + (1 << 20)) << 42) | ((j + (1 << 20)) << 21) | (k + (1 << 20));
}

}  // namespace

int64_t VoxelColumnKey(int64_t i, int64_t j) { return ((i + (1 << 20)) << 21) | (j + (1 << 20)); }

LeafSet::LeafSet(const std::vector<OccupiedLeaf>& leaves, double resolution_m) : r_(resolution_m) {
  for (const OccupiedLeaf& leaf : leaves) {
    const int level = LevelOf(leaf.size_m);
    const Eigen::Vector3d corner = leaf.center_world_m.array() - 0.5 * leaf.size_m;
    const auto i = static_cast<int64_t>(std::llround(corner.x() / r_));
    const auto j = static_cast<int64_t>(std::llround(corner.y() / r_));
    const auto k = static_cast<int64_t>(std::llround(corner.z() / r_));
    by_level_[level].insert(Key3(FloorShift(i, level), FloorShift(j, level), FloorShift(k, level)));
  }
}

bool LeafSet::Contains(int64_t i, int64_t j, int64_t k) const {
  for (const auto& [level, keys] : by_level_) {
    if (keys.count(Key3(FloorShift(i, level), FloorShift(j, level), FloorShift(k, level))) != 0) return true;
  }
  return false;
}

int LeafSet::LevelOf(double size_m) const {
  return std::max(0, static_cast<int>(std::lround(std::log2(size_m / r_))));
}

}  // namespace mfp
