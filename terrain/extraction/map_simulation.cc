#include "terrain/extraction/map_simulation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <unordered_set>

#include "base/check.h"
#include "terrain/extraction/voxelize.h"

namespace mfp {
namespace {

// Ray parameter where the ray o + t d enters the box, or infinity when it misses.
// Returns -1 when o lies inside the box.
double RayEntersBox(const TerrainBox& box, const Eigen::Matrix3d& R, const Eigen::Vector3d& o,
                    const Eigen::Vector3d& d) {
  double t_in = 0.0, t_out = 0.0;
  if (!RayBoxInterval(box, R, o, d, 1e-15, &t_in, &t_out) || t_out < 0.0) {
    return std::numeric_limits<double>::infinity();
  }
  return t_in < 0.0 ? -1.0 : t_in;
}

struct Grid {
  Eigen::Vector3i lo;  // voxel index of cell (0, 0, 0)
  Eigen::Vector3i n;
  std::vector<uint8_t> state;  // 0 unknown, 1 free, 2 occupied
  bool Inside(const Eigen::Vector3i& k) const {
    const Eigen::Vector3i r = k - lo;
    return (r.array() >= 0).all() && (r.array() < n.array()).all();
  }
  size_t Index(const Eigen::Vector3i& k) const {
    const Eigen::Vector3i r = k - lo;
    return (static_cast<size_t>(r.z()) * n.y() + r.y()) * n.x() + r.x();
  }
};

using Key = int64_t;
constexpr int64_t kKeyBias = int64_t{1} << 20;
Key MakeKey(const Eigen::Vector3i& k) {
  return ((k.x() + kKeyBias) << 42) | ((k.y() + kKeyBias) << 21) | (k.z() + kKeyBias);
}
Eigen::Vector3i FromKey(Key key) {
  const int64_t mask = (int64_t{1} << 21) - 1;
  return Eigen::Vector3i(static_cast<int>(((key >> 42) & mask) - kKeyBias),
                         static_cast<int>(((key >> 21) & mask) - kKeyBias),
                         static_cast<int>((key & mask) - kKeyBias));
}
Eigen::Vector3i VoxelOf(const Eigen::Vector3d& p, double res) {
  return Eigen::Vector3i(static_cast<int>(std::floor(p.x() / res)), static_cast<int>(std::floor(p.y() / res)),
                         static_cast<int>(std::floor(p.z() / res)));
}
Eigen::Vector3d CentreOf(const Eigen::Vector3i& k, double res) {
  return res * (k.cast<double>() + Eigen::Vector3d::Constant(0.5));
}

}  // namespace

OccupancyMap ScanTerrain(const TerrainDescription& terrain, size_t max_voxels) {
  // Validates the description (sizes, resolution, range) the same way.
  VoxelizeTerrain(TerrainDescription{{}, terrain.resolution_m, {}, {}});
  const double res = terrain.resolution_m;
  const SensorScan& scan = terrain.scan;
  if (scan.sensors_world_m.empty()) throw InputError("terrain scan: no sensor positions");
  if (!std::isfinite(scan.max_range_m) || scan.max_range_m <= 0.0 || scan.max_range_m > 100.0) {
    throw InputError("terrain scan: max_range must be in (0, 100] m");
  }
  std::vector<Eigen::Matrix3d> rotations;
  for (size_t i = 0; i < terrain.boxes.size(); ++i) {
    const TerrainBox& box = terrain.boxes[i];
    if (!box.center_world_m.allFinite() || !box.size_m.allFinite() || !box.rpy_rad.allFinite() ||
        (box.size_m.array() <= 0.0).any()) {
      throw InputError("terrain box " + std::to_string(i) + ": centre, size and rpy must be finite, sizes > 0 m");
    }
    rotations.push_back(BoxRotation(box));
  }
  for (size_t s = 0; s < scan.sensors_world_m.size(); ++s) {
    const Eigen::Vector3d& o = scan.sensors_world_m[s];
    if (!o.allFinite()) throw InputError("terrain scan: sensor " + std::to_string(s) + " is not finite");
    for (size_t i = 0; i < terrain.boxes.size(); ++i) {
      if (RayEntersBox(terrain.boxes[i], rotations[i], o, Eigen::Vector3d::UnitZ()) < 0.0) {
        throw InputError("terrain scan: sensor " + std::to_string(s) + " is inside terrain box " +
                         std::to_string(i));
      }
    }
  }
  // The grid: the boxes' bounds, where rays can end (a ray past them only frees space).
  Eigen::Vector3d box_lo = Eigen::Vector3d::Constant(INFINITY), box_hi = -box_lo;
  for (const TerrainBox& box : terrain.boxes) {
    for (const Eigen::Vector3d& c : BoxCorners(box)) {
      box_lo = box_lo.cwiseMin(c);
      box_hi = box_hi.cwiseMax(c);
    }
  }
  for (const Eigen::Vector3d& o : scan.sensors_world_m) {
    box_lo = box_lo.cwiseMin(o);
    box_hi = box_hi.cwiseMax(o);
  }
  Grid grid;
  grid.lo = VoxelOf(box_lo, res) - Eigen::Vector3i::Ones();
  grid.n = VoxelOf(box_hi, res) + Eigen::Vector3i::Constant(2) - grid.lo;
  const double voxels = grid.n.cast<double>().prod();
  const double limit_m = OctreeHalfExtentM(res) - res;
  if (box_lo.minCoeff() < -limit_m || box_hi.maxCoeff() > limit_m) {
    throw InputError("terrain scan: the boxes and sensors reach beyond the octree's range");
  }
  if (voxels > static_cast<double>(max_voxels)) {
    std::ostringstream msg;
    msg << "terrain scan: the grid holds " << voxels << " voxels at " << res << " m, more than the limit of "
        << max_voxels;
    throw InputError(msg.str());
  }
  grid.state.assign(static_cast<size_t>(voxels), 0);

  const double step = res / (2.0 * scan.max_range_m);
  const int n_el = static_cast<int>(std::ceil(M_PI / step));
  for (const Eigen::Vector3d& o : scan.sensors_world_m) {
    for (int ie = 0; ie <= n_el; ++ie) {
      const double el = -M_PI / 2 + M_PI * ie / n_el;
      const int n_az = std::max(1, static_cast<int>(std::ceil(2 * M_PI * std::cos(el) / step)));
      for (int ia = 0; ia < n_az; ++ia) {
        const double az = 2 * M_PI * ia / n_az;
        const Eigen::Vector3d d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
        double t_hit = std::numeric_limits<double>::infinity();
        for (size_t i = 0; i < terrain.boxes.size(); ++i) {
          t_hit = std::min(t_hit, RayEntersBox(terrain.boxes[i], rotations[i], o, d));
        }
        const bool hit = t_hit <= scan.max_range_m;
        const double t_end = hit ? t_hit : scan.max_range_m;
        // Voxel walk (Amanatides & Woo) from the sensor to the end point.
        Eigen::Vector3i k = VoxelOf(o, res);
        const Eigen::Vector3i k_end = VoxelOf(o + d * (hit ? t_hit + 1e-7 : t_end), res);
        Eigen::Vector3i dir;
        Eigen::Vector3d t_max, t_delta;
        for (int a = 0; a < 3; ++a) {
          dir(a) = d(a) > 0 ? 1 : (d(a) < 0 ? -1 : 0);
          if (dir(a) == 0) {
            t_max(a) = t_delta(a) = std::numeric_limits<double>::infinity();
          } else {
            const double boundary = (k(a) + (dir(a) > 0 ? 1 : 0)) * res;
            t_max(a) = (boundary - o(a)) / d(a);
            t_delta(a) = res / std::abs(d(a));
          }
        }
        while (k != k_end) {
          if (!grid.Inside(k)) break;
          uint8_t& s = grid.state[grid.Index(k)];
          if (s == 0) s = 1;
          int a = 0;
          if (t_max(1) < t_max(a)) a = 1;
          if (t_max(2) < t_max(a)) a = 2;
          if (t_max(a) > t_end) break;
          k(a) += dir(a);
          t_max(a) += t_delta(a);
        }
        if (hit && grid.Inside(k_end)) grid.state[grid.Index(k_end)] = 2;
      }
    }
  }
  OccupancyMap map;
  map.resolution_m = res;
  for (int z = 0; z < grid.n.z(); ++z) {
    for (int y = 0; y < grid.n.y(); ++y) {
      for (int x = 0; x < grid.n.x(); ++x) {
        const Eigen::Vector3i k = grid.lo + Eigen::Vector3i(x, y, z);
        const uint8_t s = grid.state[grid.Index(k)];
        if (s == 2) map.leaves.push_back({CentreOf(k, res), res});
        if (s == 1) map.free_leaves.push_back({CentreOf(k, res), res});
      }
    }
  }
  return map;
}

void AddMapNoise(const MapNoise& noise, OccupancyMap* map) {
  if (!(noise.jitter_fraction >= 0.0 && noise.jitter_fraction <= 1.0 && noise.hole_fraction >= 0.0 &&
        noise.hole_fraction <= 1.0 && noise.outliers >= 0 && noise.outliers <= 1000000)) {
    throw InputError("terrain noise: jitter and holes must be fractions in [0, 1], outliers in [0, 1000000]");
  }
  if (!noise.Any() || map->leaves.empty()) return;
  const double res = map->resolution_m;
  std::unordered_set<Key> occupied, free;
  for (const OccupiedLeaf& leaf : map->leaves) {
    MFP_CHECK_MSG(std::abs(leaf.size_m - res) < 1e-9 * res, "AddMapNoise needs single-voxel leaves");
    occupied.insert(MakeKey(VoxelOf(leaf.center_world_m, res)));
  }
  for (const OccupiedLeaf& leaf : map->free_leaves) {
    MFP_CHECK_MSG(std::abs(leaf.size_m - res) < 1e-9 * res, "AddMapNoise needs single-voxel leaves");
    free.insert(MakeKey(VoxelOf(leaf.center_world_m, res)));
  }
  const bool has_free = !free.empty();
  std::mt19937 rng(noise.seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  // Top voxels in a fixed order (sorted keys), so the noise depends only on the seed.
  std::vector<Key> tops;
  Eigen::Vector3i lo = Eigen::Vector3i::Constant(std::numeric_limits<int>::max()), hi = -lo;
  for (Key key : occupied) {
    const Eigen::Vector3i k = FromKey(key);
    lo = lo.cwiseMin(k);
    hi = hi.cwiseMax(k);
    if (!occupied.count(MakeKey(k + Eigen::Vector3i::UnitZ()))) tops.push_back(key);
  }
  std::sort(tops.begin(), tops.end());
  for (Key key : tops) {
    const Eigen::Vector3i k = FromKey(key);
    const Key above = MakeKey(k + Eigen::Vector3i::UnitZ());
    const double u = uniform(rng);
    if (u < noise.hole_fraction) {
      occupied.erase(key);  // unseen: neither occupied nor free
      free.erase(key);
    } else if (u < noise.hole_fraction + noise.jitter_fraction) {
      if (uniform(rng) < 0.5) {
        occupied.insert(above);
        free.erase(above);
      } else {
        occupied.erase(key);
        if (has_free) free.insert(key);
      }
    }
  }
  // Outliers: voxels with no occupied neighbour, anywhere in the map's bounds.
  for (int placed = 0, tries = 0; placed < noise.outliers && tries < 100 * noise.outliers + 100; ++tries) {
    Eigen::Vector3i k;
    for (int a = 0; a < 3; ++a) {
      std::uniform_int_distribution<int> pick(lo(a), std::max(lo(a), hi(a) + (a == 2 ? 8 : 0)));
      k(a) = pick(rng);
    }
    bool alone = true;
    for (int dx = -1; dx <= 1 && alone; ++dx)
      for (int dy = -1; dy <= 1 && alone; ++dy)
        for (int dz = -1; dz <= 1 && alone; ++dz) alone = !occupied.count(MakeKey(k + Eigen::Vector3i(dx, dy, dz)));
    if (!alone) continue;
    occupied.insert(MakeKey(k));
    free.erase(MakeKey(k));
    ++placed;
  }
  std::vector<Key> sorted(occupied.begin(), occupied.end());
  std::sort(sorted.begin(), sorted.end());
  map->leaves.clear();
  for (Key key : sorted) map->leaves.push_back({CentreOf(FromKey(key), res), res});
  sorted.assign(free.begin(), free.end());
  std::sort(sorted.begin(), sorted.end());
  map->free_leaves.clear();
  for (Key key : sorted) map->free_leaves.push_back({CentreOf(FromKey(key), res), res});
}

OccupancyMap MakeTerrainMap(const TerrainDescription& terrain) {
  OccupancyMap map = terrain.scan.sensors_world_m.empty() ? VoxelizeTerrain(terrain) : ScanTerrain(terrain);
  AddMapNoise(terrain.noise, &map);
  return map;
}

}  // namespace mfp
