#include "terrain/extraction/internal/noise_patches.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

namespace mfp {
namespace {

// Union-find over patches; a group holds at most one large patch.
struct PatchGroups {
  std::vector<int> parent;
  std::vector<int> large;  // per root: its group's large patch, or -1
  int Find(int p) {
    while (parent[static_cast<size_t>(p)] != p) {
      parent[static_cast<size_t>(p)] = parent[static_cast<size_t>(parent[static_cast<size_t>(p)])];
      p = parent[static_cast<size_t>(p)];
    }
    return p;
  }
  void Join(int p, int q) {
    p = Find(p);
    q = Find(q);
    if (p == q || (large[static_cast<size_t>(p)] >= 0 && large[static_cast<size_t>(q)] >= 0)) return;
    if (q < p) std::swap(p, q);
    parent[static_cast<size_t>(q)] = p;
    large[static_cast<size_t>(p)] = std::max(large[static_cast<size_t>(p)], large[static_cast<size_t>(q)]);
  }
};

// Whether some cell of patch p holds the disk: every cell whose square comes closer than
// radius_cells to its centre is p's.
bool HoldsDisk(const HeightMap& hm, const std::vector<int>& owner, const PlanarPatch& patch, int p,
               double radius_cells) {
  const int reach = static_cast<int>(std::ceil(radius_cells + 0.5));
  std::vector<std::pair<int, int>> offsets;
  for (int dr = -reach; dr <= reach; ++dr) {
    for (int dc = -reach; dc <= reach; ++dc) {
      const double ex = std::max(std::abs(dc) - 0.5, 0.0), ey = std::max(std::abs(dr) - 0.5, 0.0);
      if (ex * ex + ey * ey < radius_cells * radius_cells - 1e-9) offsets.emplace_back(dr, dc);
    }
  }
  for (int cell : patch.cells) {
    const int row = cell / hm.cols, col = cell % hm.cols;
    const bool holds = std::all_of(offsets.begin(), offsets.end(), [&](const std::pair<int, int>& o) {
      return hm.Inside(row + o.first, col + o.second) &&
             owner[static_cast<size_t>(hm.Index(row + o.first, col + o.second))] == p;
    });
    if (holds) return true;
  }
  return false;
}

// Patches joined across 4-adjacent seen cells at most two voxels apart, one side small;
// the seen cells (surface_cells, ascending) in order.
PatchGroups GroupPatches(const HeightMap& hm, const std::vector<int>& surface_cells,
                         const std::vector<PlanarPatch>& patches, double foot_radius_m) {
  const int n = static_cast<int>(patches.size());
  PatchGroups groups;
  groups.parent.resize(static_cast<size_t>(n));
  std::iota(groups.parent.begin(), groups.parent.end(), 0);
  groups.large.assign(static_cast<size_t>(n), -1);
  std::vector<int> owner(hm.height_m.size(), -1);
  for (int p = 0; p < n; ++p) {
    for (int cell : patches[static_cast<size_t>(p)].cells) owner[static_cast<size_t>(cell)] = p;
  }
  for (int p = 0; p < n; ++p) {
    if (HoldsDisk(hm, owner, patches[static_cast<size_t>(p)], p, foot_radius_m / hm.resolution_m)) {
      groups.large[static_cast<size_t>(p)] = p;
    }
  }
  const double max_step_m = 2.0 * hm.resolution_m * (1.0 + 1e-3);
  for (const int cell : surface_cells) {
    const int p = owner[static_cast<size_t>(cell)];
    if (p < 0) continue;
    const int row = cell / hm.cols, col = cell % hm.cols;
    for (const auto& [dr, dc] : {std::pair{0, 1}, std::pair{1, 0}}) {
      if (!hm.Inside(row + dr, col + dc)) continue;
      const int nb = hm.Index(row + dr, col + dc);
      const int q = owner[static_cast<size_t>(nb)];
      if (q < 0 || q == p || std::isnan(hm.height_m[static_cast<size_t>(nb)])) continue;
      if (groups.large[static_cast<size_t>(p)] == p && groups.large[static_cast<size_t>(q)] == q) continue;
      if (std::abs(hm.height_m[static_cast<size_t>(cell)] - hm.height_m[static_cast<size_t>(nb)]) > max_step_m) continue;
      groups.Join(p, q);
    }
  }
  return groups;
}

// Height of a seen cell above the patch's plane [m]; 0 for an unseen cell kept as noise.
double Residual(const HeightMap& hm, const PlanarPatch& plane, int cell) {
  const float h = hm.height_m[static_cast<size_t>(cell)];
  if (std::isnan(h)) return 0.0;
  return h - plane.HeightAt(hm.CellCenter(cell / hm.cols, cell % hm.cols));
}

bool WithinPlane(const HeightMap& hm, const PlanarPatch& plane, const std::vector<int>& cells, double tolerance_m) {
  return std::all_of(cells.begin(), cells.end(),
                     [&](int cell) { return std::abs(Residual(hm, plane, cell)) <= tolerance_m; });
}

}  // namespace

bool FitPlaneToSeenCells(const HeightMap& hm, const std::vector<int>& cells, PlanarPatch* plane) {
  std::vector<Eigen::Vector3d> points;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int cell : cells) {
    const float h = hm.height_m[static_cast<size_t>(cell)];
    if (std::isnan(h)) continue;
    const Eigen::Vector2d xy = hm.CellCenter(cell / hm.cols, cell % hm.cols);
    points.emplace_back(xy.x(), xy.y(), h);
    mean += points.back();
  }
  if (points.size() < 3) return false;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d AtA = Eigen::Matrix3d::Zero();
  Eigen::Vector3d Atz = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d v(p.x() - mean.x(), p.y() - mean.y(), 1.0);
    AtA += v * v.transpose();
    Atz += v * (p.z() - mean.z());
  }
  Eigen::FullPivLU<Eigen::Matrix3d> lu(AtA);
  if (lu.rank() < 3) return false;
  const Eigen::Vector3d abc = lu.solve(Atz);
  plane->a = abc.x();
  plane->b = abc.y();
  plane->c = mean.z() + abc.z() - abc.x() * mean.x() - abc.y() * mean.y();
  plane->normal_world = Eigen::Vector3d(-plane->a, -plane->b, 1.0).normalized();
  return true;
}

namespace {

// The joined patch's residual and noise figures: cells beyond max_residual_m are noise.
void CountNoise(const HeightMap& hm, double max_residual_m, PlanarPatch* patch) {
  patch->max_residual_m = 0.0;
  patch->noise_cells = 0;
  for (int cell : patch->cells) {
    const double r = std::abs(Residual(hm, *patch, cell));
    const bool unseen = std::isnan(hm.height_m[static_cast<size_t>(cell)]);
    if (r <= max_residual_m && !unseen) {
      patch->max_residual_m = std::max(patch->max_residual_m, r);
    } else {
      ++patch->noise_cells;
    }
  }
}

// A group of small patches only: one plane for them all when every cell lies within the
// noise tolerance of it (members off it left out, once); otherwise the patches as they were.
void JoinSmallGroup(const HeightMap& hm, const SegmentationOptions& options, std::vector<PlanarPatch*> members,
                    std::vector<PlanarPatch>* out) {
  for (int attempt = 0; attempt < 2 && members.size() > 1; ++attempt) {
    PlanarPatch joined;
    for (const PlanarPatch* m : members) joined.cells.insert(joined.cells.end(), m->cells.begin(), m->cells.end());
    if (!FitPlaneToSeenCells(hm, joined.cells, &joined)) break;
    std::vector<PlanarPatch*> off, on;
    for (PlanarPatch* m : members) (WithinPlane(hm, joined, m->cells, options.noise_tolerance_m) ? on : off).push_back(m);
    if (off.empty()) {
      CountNoise(hm, options.max_residual_m, &joined);
      out->push_back(std::move(joined));
      return;
    }
    for (PlanarPatch* m : off) out->push_back(std::move(*m));
    members = std::move(on);
  }
  for (PlanarPatch* m : members) out->push_back(std::move(*m));
}

// A group with a large patch: small members within the noise tolerance of its plane join it.
void JoinIntoLarge(const HeightMap& hm, const SegmentationOptions& options, PlanarPatch* large,
                   const std::vector<PlanarPatch*>& members, std::vector<PlanarPatch>* out) {
  for (PlanarPatch* m : members) {
    if (m == large) continue;
    if (!WithinPlane(hm, *large, m->cells, options.noise_tolerance_m)) {
      out->push_back(std::move(*m));
      continue;
    }
    large->cells.insert(large->cells.end(), m->cells.begin(), m->cells.end());
    large->noise_cells += static_cast<int>(m->cells.size());
  }
  out->push_back(std::move(*large));
}

}  // namespace

void JoinNoisePatches(const HeightMap& hm, const std::vector<int>& surface_cells, const SegmentationOptions& options,
                      std::vector<PlanarPatch>* patches) {
  if (!(options.noise_patch_foot_radius_m > 0.0) || patches->size() < 2) return;
  PatchGroups groups = GroupPatches(hm, surface_cells, *patches, options.noise_patch_foot_radius_m);
  const int n = static_cast<int>(patches->size());
  std::vector<std::vector<PlanarPatch*>> members(static_cast<size_t>(n));
  for (int p = 0; p < n; ++p) members[static_cast<size_t>(groups.Find(p))].push_back(&(*patches)[static_cast<size_t>(p)]);
  std::vector<PlanarPatch> out;
  out.reserve(patches->size());
  for (int root = 0; root < n; ++root) {
    const std::vector<PlanarPatch*>& group = members[static_cast<size_t>(root)];
    if (group.empty()) continue;
    const int large = groups.large[static_cast<size_t>(root)];
    if (group.size() == 1) {
      out.push_back(std::move(*group.front()));
    } else if (large >= 0) {
      JoinIntoLarge(hm, options, &(*patches)[static_cast<size_t>(large)], group, &out);
    } else {
      JoinSmallGroup(hm, options, group, &out);
    }
  }
  *patches = std::move(out);
}

}  // namespace mfp
