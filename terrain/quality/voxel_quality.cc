#include "terrain/quality/voxel_quality.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "base/check.h"
#include "geometry/plan_bounds.h"
#include "terrain/quality/leaf_set.h"

namespace mfp {
namespace {

struct SurfaceVoxel {
  int64_t i, j, k;  // the occupied voxel; its top is (k + 1) r
};

// Every seen surface voxel: the top layer of each occupied leaf, known free above, no
// occupied voxel within the clearance.
std::vector<SurfaceVoxel> SeenSurfaces(const OccupancyMap& map, const LeafSet& occupied, const LeafSet& free,
                                       double clearance_m) {
  const double r = map.resolution_m;
  const int room = std::max(1, static_cast<int>(std::ceil(clearance_m / r - 1e-9)));
  std::vector<SurfaceVoxel> out;
  for (const OccupiedLeaf& leaf : map.leaves) {
    const int64_t n = int64_t{1} << occupied.LevelOf(leaf.size_m);
    const Eigen::Vector3d corner = leaf.center_world_m.array() - 0.5 * leaf.size_m;
    const auto i0 = static_cast<int64_t>(std::llround(corner.x() / r));
    const auto j0 = static_cast<int64_t>(std::llround(corner.y() / r));
    const int64_t k = static_cast<int64_t>(std::llround(corner.z() / r)) + n - 1;
    for (int64_t i = i0; i < i0 + n; ++i) {
      for (int64_t j = j0; j < j0 + n; ++j) {
        if (!free.Contains(i, j, k + 1)) continue;
        bool clear = true;
        for (int d = 1; d <= room && clear; ++d) clear = !occupied.Contains(i, j, k + d);
        if (clear) out.push_back({i, j, k});
      }
    }
  }
  return out;
}

int64_t DominantLevel(const std::vector<SurfaceVoxel>& surfaces) {
  std::unordered_map<int64_t, int> count;
  int64_t best = 0;
  int best_count = -1;
  for (const SurfaceVoxel& s : surfaces) {
    const int c = ++count[s.k];
    if (c > best_count) best_count = c, best = s.k;
  }
  return best;
}

// The column offsets the erosion checks, for the floor as a set (every column whose
// square comes closer than erosion_m to the centre) or centre to centre (every column
// whose centre lies within erosion_m).
std::vector<std::pair<int, int>> ErosionOffsets(double erosion_m, double r, bool as_set) {
  const int reach = static_cast<int>(std::floor(erosion_m / r + (as_set ? 0.5 : 0.0) + 1e-9)) + 1;
  std::vector<std::pair<int, int>> offsets;
  for (int di = -reach; di <= reach; ++di) {
    for (int dj = -reach; dj <= reach; ++dj) {
      if (as_set) {
        const double ex = std::max(std::abs(di) - 0.5, 0.0) * r, ey = std::max(std::abs(dj) - 0.5, 0.0) * r;
        if (ex * ex + ey * ey < erosion_m * erosion_m - 1e-12) offsets.emplace_back(di, dj);
      } else if ((di * di + dj * dj) * r * r <= erosion_m * erosion_m + 1e-12) {
        offsets.emplace_back(di, dj);
      }
    }
  }
  return offsets;
}

bool CoveredAt(const std::vector<ConvexRegion>& regions, const std::vector<Eigen::AlignedBox2d>& boxes,
               const Eigen::Vector2d& xy, double top_m, double height_tolerance_m) {
  for (size_t n = 0; n < regions.size(); ++n) {
    // The box with the containment test's own 1e-9 m: a point on a region's side (a
    // cell centre on an edge of a convex piece) counts whichever way its vertices round.
    if ((xy.array() < boxes[n].min().array() - 1e-9).any() || (xy.array() > boxes[n].max().array() + 1e-9).any()) continue;
    if (std::abs(regions[n].HeightAt(xy.x(), xy.y()) - top_m) > height_tolerance_m) continue;
    if (PlanDistanceToRegion(regions[n], xy) <= 1e-9) return true;
  }
  return false;
}

}  // namespace

VoxelQuality JudgeRegionsAgainstVoxels(const std::vector<ConvexRegion>& regions, const OccupancyMap& map,
                                       const VoxelQualityOptions& options) {
  const double r = map.resolution_m;
  if (!(r > 0.0) || !std::isfinite(r)) throw InputError("voxel quality: the map's resolution must be positive");
  if (!(options.clearance_m > 0.0) || !(options.erosion_m >= 0.0) || !(options.floor_band_m >= 0.0)) {
    throw InputError("voxel quality: clearance must be > 0, erosion and floor band >= 0");
  }
  const LeafSet occupied(map.leaves, r), free(map.free_leaves, r);
  const std::vector<SurfaceVoxel> surfaces = SeenSurfaces(map, occupied, free, options.clearance_m);
  VoxelQuality q;
  q.seen_surface_voxels = static_cast<int>(surfaces.size());
  std::unordered_map<int64_t, std::vector<int64_t>> columns;  // plan cell -> surface voxel k
  for (const SurfaceVoxel& s : surfaces) columns[VoxelColumnKey(s.i, s.j)].push_back(s.k);
  auto surface_near = [&](int64_t i, int64_t j, double top_m, double tolerance_m) {
    const auto it = columns.find(VoxelColumnKey(i, j));
    if (it == columns.end()) return false;
    for (int64_t k : it->second) {
      if (std::abs((static_cast<double>(k) + 1.0) * r - top_m) <= tolerance_m + 1e-9) return true;
    }
    return false;
  };

  std::vector<Eigen::AlignedBox2d> boxes;
  for (const ConvexRegion& region : regions) boxes.push_back(PlanBounds(region));

  // The floor, its certifiable part and their coverage.
  if (!surfaces.empty()) {
    const int64_t floor_k = DominantLevel(surfaces);
    q.floor_height_m = (static_cast<double>(floor_k) + 1.0) * r;
    const std::vector<std::pair<int, int>> as_set = ErosionOffsets(options.erosion_m, r, true);
    const std::vector<std::pair<int, int>> centres = ErosionOffsets(options.erosion_m, r, false);
    auto eroded_in = [&](const SurfaceVoxel& s, double top, const std::vector<std::pair<int, int>>& offsets) {
      for (const auto& [di, dj] : offsets) {
        if (!surface_near(s.i + di, s.j + dj, top, r)) return false;
      }
      return true;
    };
    int seen_covered = 0;
    for (const SurfaceVoxel& s : surfaces) {
      const double top = (static_cast<double>(s.k) + 1.0) * r;
      if (std::abs(top - q.floor_height_m) > options.floor_band_m + 1e-9) continue;
      ++q.seen_floor_cells;
      const Eigen::Vector2d xy((static_cast<double>(s.i) + 0.5) * r, (static_cast<double>(s.j) + 0.5) * r);
      const bool covered = CoveredAt(regions, boxes, xy, top, r);
      seen_covered += covered ? 1 : 0;
      if (!eroded_in(s, top, centres)) continue;  // the set erosion checks these columns too
      ++q.certifiable_centre_floor_cells;
      q.certifiable_centre_covered_cells += covered ? 1 : 0;
      if (!eroded_in(s, top, as_set)) continue;
      ++q.certifiable_floor_cells;
      q.certifiable_covered_cells += covered ? 1 : 0;
      if (!covered && options.list_missed) q.missed_certifiable.emplace_back(xy.x(), xy.y(), top);
    }
    q.seen_floor_m2 = q.seen_floor_cells * r * r;
    q.seen_floor_coverage = q.seen_floor_cells > 0 ? static_cast<double>(seen_covered) / q.seen_floor_cells : 0.0;
    q.certifiable_centre_coverage =
        q.certifiable_centre_floor_cells > 0
            ? static_cast<double>(q.certifiable_centre_covered_cells) / q.certifiable_centre_floor_cells
            : 0.0;
    q.certifiable_coverage = q.certifiable_floor_cells > 0
                                 ? static_cast<double>(q.certifiable_covered_cells) / q.certifiable_floor_cells
                                 : 0.0;
  }

  // Soundness: region points sampled on a grid, each on a seen surface voxel.
  const double step = options.sample_step_m > 0.0 ? options.sample_step_m : r;
  for (size_t n = 0; n < regions.size(); ++n) {
    const Eigen::Vector2d lo = boxes[n].min(), hi = boxes[n].max();
    for (double x = lo.x() + 0.5 * step; x < hi.x(); x += step) {
      for (double y = lo.y() + 0.5 * step; y < hi.y(); y += step) {
        if (PlanDistanceToRegion(regions[n], {x, y}) > 0.0) continue;
        const double z = regions[n].HeightAt(x, y);
        ++q.region_samples;
        const auto i = static_cast<int64_t>(std::floor(x / r));
        const auto j = static_cast<int64_t>(std::floor(y / r));
        if (surface_near(i, j, z, r + regions[n].plane_tolerance_m)) {
          ++q.sound_samples;
        } else {
          q.worst_point = {x, y, z};
        }
      }
    }
  }
  q.soundness = q.region_samples > 0 ? static_cast<double>(q.sound_samples) / q.region_samples : 1.0;
  return q;
}

}  // namespace mfp
