#include "terrain/extraction/internal/plane_segmentation.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <deque>

#include "base/check.h"
#include "terrain/extraction/internal/noise_levels.h"
#include "terrain/extraction/internal/noise_patches.h"
#include "terrain/extraction/internal/surface_layers.h"

namespace mfp {
namespace {

constexpr int kUnvisited = -1;
constexpr int kDropped = -2;  // left out of a patch: may join or seed a later one

// Running least-squares sums for z = a x + b y + c, in coordinates relative to the seed.
// x and y are whole cells, so A^T A is summed in integers (exact, and equal to the double
// sums while they stay below 2^53: a patch of 10^6 cells 10^4 cells wide stays below 2^47).
struct PlaneSums {
  long long sxx = 0, sxy = 0, syy = 0, sx = 0, sy = 0;
  Eigen::Vector3d Atz = Eigen::Vector3d::Zero();
  int count = 0;
  void Add(int x, int y, double z) {
    sxx += static_cast<long long>(x) * x;
    sxy += static_cast<long long>(x) * y;
    syy += static_cast<long long>(y) * y;
    sx += x;
    sy += y;
    Atz += Eigen::Vector3d(x, y, 1.0) * z;
    ++count;
  }
  // Returns false when the cells do not fix a plane yet (fewer than 3 or collinear).
  bool Fit(Eigen::Vector3d* abc) const {
    if (count < 3) return false;
    Eigen::Matrix3d AtA;
    AtA << static_cast<double>(sxx), static_cast<double>(sxy), static_cast<double>(sx), static_cast<double>(sxy),
        static_cast<double>(syy), static_cast<double>(sy), static_cast<double>(sx), static_cast<double>(sy), count;
    Eigen::FullPivLU<Eigen::Matrix3d> lu(AtA);
    if (lu.rank() < 3) return false;
    *abc = lu.solve(Atz);
    return true;
  }
};

// The plane z = z0 + a (col - seed_col) + b (row - seed_row) + c of a growing patch, in
// cells relative to its seed (z in metres).
struct SeedPlane {
  int seed_row = 0, seed_col = 0;
  double z0 = 0.0;
  Eigen::Vector3d abc = Eigen::Vector3d::Zero();
  double Residual(const HeightMap& hm, int cell) const {
    const int row = cell / hm.cols, col = cell % hm.cols;
    return hm.height_m[cell] - z0 - (abc.x() * (col - seed_col) + abc.y() * (row - seed_row) + abc.z());
  }
};

// Per-patch scratch over the height map: all kFree between patches.
enum CellKind : uint8_t { kFree = 0, kCore = 1, kVisited = 2, kNoise = 3 };

// Whether `cell` may be kept as noise of the patch `patch_id` (SegmentationOptions).
bool NoiseCandidate(const HeightMap& hm, const std::vector<int>& label, int cell, int patch_id,
                    const SeedPlane& plane, const SegmentationOptions& options) {
  if (label[cell] != kUnvisited && label[cell] != kDropped && label[cell] != patch_id) return false;
  if (std::isnan(hm.height_m[cell])) {
    return options.unseen != nullptr && (*options.unseen)[cell] == (kEmptyColumn | kNotErased);
  }
  return std::abs(plane.Residual(hm, cell)) <= options.noise_tolerance_m;
}

// The group of non-core cells 4-connected to `start`, if it is noise: at most
// noise_max_cells cells, every one a candidate, every 8-neighbour outside it a core
// cell. Returns the group, or nothing; marks what it visited kVisited in kind and lists
// it in touched.
std::vector<int> NoiseGroup(const HeightMap& hm, const std::vector<int>& label, int start, int patch_id,
                            const SeedPlane& plane, const SegmentationOptions& options, std::vector<uint8_t>* kind,
                            std::vector<int>* touched) {
  std::vector<int> group{start};
  (*kind)[start] = kVisited;
  touched->push_back(start);
  const int drow[4] = {1, -1, 0, 0};
  const int dcol[4] = {0, 0, 1, -1};
  for (size_t next = 0; next < group.size(); ++next) {
    const int cell = group[next];
    if (!NoiseCandidate(hm, label, cell, patch_id, plane, options)) return {};
    for (int k = 0; k < 4; ++k) {
      const int r = cell / hm.cols + drow[k], c = cell % hm.cols + dcol[k];
      if (!hm.Inside(r, c)) return {};
      const int nb = hm.Index(r, c);
      if ((*kind)[nb] != kFree) continue;  // core, or in this group
      if (static_cast<int>(group.size()) >= options.noise_max_cells) return {};
      (*kind)[nb] = kVisited;
      touched->push_back(nb);
      group.push_back(nb);
    }
  }
  // Enclosed: every diagonal neighbour is core or in the group too.
  for (int cell : group) {
    for (int dr : {-1, 1}) {
      for (int dc : {-1, 1}) {
        const int r = cell / hm.cols + dr, c = cell % hm.cols + dc;
        if (!hm.Inside(r, c)) return {};
        const int nb = hm.Index(r, c);
        if ((*kind)[nb] != kCore && std::find(group.begin(), group.end(), nb) == group.end()) return {};
      }
    }
  }
  return group;
}

// The patch of one grown region: members within max_residual_m of the plane (refitted
// to them when others were left out), plus the noise groups they enclose; members left
// out are labelled kDropped, noise cells patch_id. kind is all kFree on entry and return.
PlanarPatch FinishPatch(const HeightMap& hm, const std::vector<int>& members, int patch_id, SeedPlane plane,
                        const SegmentationOptions& options, std::vector<int>* label, std::vector<uint8_t>* kind) {
  PlaneSums core_sums;
  bool any_left_out = false;
  for (int cell : members) {
    if (std::abs(plane.Residual(hm, cell)) <= options.max_residual_m) {
      (*kind)[cell] = kCore;
      core_sums.Add(cell % hm.cols - plane.seed_col, cell / hm.cols - plane.seed_row, hm.height_m[cell] - plane.z0);
    } else {
      any_left_out = true;
    }
  }
  if (any_left_out) core_sums.Fit(&plane.abc);  // unchanged when the core does not fix a plane
  PlanarPatch patch;
  std::vector<int> noise, touched;
  if (options.noise_max_cells > 0) {
    const int drow[4] = {1, -1, 0, 0};
    const int dcol[4] = {0, 0, 1, -1};
    for (int cell : members) {
      if ((*kind)[cell] != kCore) continue;
      for (int k = 0; k < 4; ++k) {
        const int r = cell / hm.cols + drow[k], c = cell % hm.cols + dcol[k];
        if (!hm.Inside(r, c) || (*kind)[hm.Index(r, c)] != kFree) continue;
        const size_t before = noise.size();
        for (int g : NoiseGroup(hm, *label, hm.Index(r, c), patch_id, plane, options, kind, &touched)) {
          noise.push_back(g);
        }
        for (size_t i = before; i < noise.size(); ++i) (*kind)[noise[i]] = kNoise;
      }
    }
  }
  for (int cell : members) {
    if ((*kind)[cell] == kCore) {
      patch.max_residual_m = std::max(patch.max_residual_m, std::abs(plane.Residual(hm, cell)));
      patch.cells.push_back(cell);
    } else if ((*kind)[cell] != kNoise) {
      (*label)[cell] = kDropped;
    }
  }
  for (int cell : noise) {
    (*label)[cell] = patch_id;
    patch.cells.push_back(cell);
  }
  patch.noise_cells = static_cast<int>(noise.size());
  // Back to kFree: members and whatever the noise searches visited.
  for (int cell : members) (*kind)[cell] = kFree;
  for (int cell : touched) (*kind)[cell] = kFree;
  // Back to world coordinates: z = z0 + a' (x - x0)/res + b' (y - y0)/res + c'.
  const double res = hm.resolution_m;
  const Eigen::Vector2d xy0 = hm.CellCenter(plane.seed_row, plane.seed_col);
  patch.a = plane.abc.x() / res;
  patch.b = plane.abc.y() / res;
  patch.c = plane.z0 + plane.abc.z() - patch.a * xy0.x() - patch.b * xy0.y();
  patch.normal_world = Eigen::Vector3d(-patch.a, -patch.b, 1.0).normalized();
  return patch;
}

}  // namespace

double PlanarPatch::SlopeRad() const { return std::acos(std::min(1.0, normal_world.z())); }

namespace {

// A patch grown on noise-free levels takes the plane of its cells' own heights (the
// surface's height: the noise averages out), with the residual of its cells within
// max_residual_m of it. Patches without a denoised cell are left as they are.
void RefitOnHeights(const HeightMap& raw, const NoiseLevels& noise, double max_residual_m,
                    std::vector<PlanarPatch>* patches) {
  for (PlanarPatch& patch : *patches) {
    const bool any = std::any_of(patch.cells.begin(), patch.cells.end(),
                                 [&](int cell) { return noise.denoised[static_cast<size_t>(cell)] != 0; });
    if (!any || !FitPlaneToSeenCells(raw, patch.cells, &patch)) continue;
    patch.max_residual_m = 0.0;
    for (int cell : patch.cells) {
      const float h = raw.height_m[static_cast<size_t>(cell)];
      if (std::isnan(h)) continue;
      const double r = std::abs(h - patch.HeightAt(raw.CellCenter(cell / raw.cols, cell % raw.cols)));
      if (r <= max_residual_m) patch.max_residual_m = std::max(patch.max_residual_m, r);
    }
  }
}

}  // namespace

std::vector<PlanarPatch> SegmentPlanarPatches(const HeightMap& raw, const SurfaceAnalysis& surface,
                                              const SegmentationOptions& options) {
  MFP_CHECK(surface.roughness_m.size() == surface.cells.size() && surface.normal_world.size() == surface.cells.size());
  // Grown on noise-free levels where the surface is noisy (noise_levels.h).
  const bool noise_levels = options.noise_patch_foot_radius_m > 0.0 && options.noise_max_cells > 0;
  NoiseLevels own_levels;
  if (noise_levels && options.noise_levels == nullptr) {
    own_levels = NoiseFreeLevels(raw, surface.cells, options.noise_tolerance_m, options.noise_max_cells);
  }
  const NoiseLevels& noise = noise_levels && options.noise_levels != nullptr ? *options.noise_levels : own_levels;
  const HeightMap& hm = noise.denoised_cells > 0 ? noise.levels : raw;
  std::vector<int> label(hm.height_m.size(), kUnvisited);
  std::vector<PlanarPatch> patches;
  const double res = hm.resolution_m;
  const int drow[4] = {1, -1, 0, 0};
  const int dcol[4] = {0, 0, 1, -1};
  std::deque<int> queue;
  std::vector<int> members;
  std::vector<uint8_t> kind(hm.height_m.size(), kFree);
  // Seeds in ascending order among the surface cells (a cell without one is neither smooth
  // nor a flat level): the fit's cells, the raw map's surface cells in ascending order,
  // which the noise levels keep.
  for (size_t entry = 0; entry < surface.cells.size(); ++entry) {
    const int seed = surface.cells[entry];
    MFP_CHECK(!std::isnan(hm.height_m[seed]) && (entry == 0 || surface.cells[entry - 1] < seed));
    // A cell a patch's fit left out (a stone one voxel above the floor the patch grew
    // over) starts a patch of its own when smooth.
    if (label[seed] != kUnvisited && label[seed] != kDropped) continue;
    const bool smooth = surface.roughness_m[entry] <= options.max_seed_roughness_m;
    if (!smooth && !(noise.denoised_cells > 0 && FlatLevel(hm, seed))) continue;
    const int patch_id = static_cast<int>(patches.size());
    const int seed_row = seed / hm.cols, seed_col = seed % hm.cols;
    const double z0 = hm.height_m[seed];
    // Start from the cell's local plane, in cells relative to the seed.
    const Eigen::Vector3f& n0 = surface.normal_world[entry];
    Eigen::Vector3d abc(-n0.x() / n0.z() * res, -n0.y() / n0.z() * res, 0.0);
    if (!smooth) abc.setZero();  // a flat level: the local fit saw the noise
    PlaneSums sums;
    int next_refit = 8;
    members.clear();
    queue.clear();
    queue.push_back(seed);
    label[seed] = patch_id;
    while (!queue.empty()) {
      const int cell = queue.front();
      queue.pop_front();
      members.push_back(cell);
      const int row = cell / hm.cols, col = cell % hm.cols;
      sums.Add(col - seed_col, row - seed_row, hm.height_m[cell] - z0);
      if (sums.count >= next_refit) {
        sums.Fit(&abc);
        next_refit = sums.count + std::max(8, sums.count / 8);
      }
      for (int k = 0; k < 4; ++k) {
        const int r = row + drow[k], c = col + dcol[k];
        if (!hm.Inside(r, c)) continue;
        const int nb = hm.Index(r, c);
        if (label[nb] != kUnvisited && label[nb] != kDropped) continue;
        const float h = hm.height_m[nb];
        if (std::isnan(h)) continue;
        const double predicted = abc.x() * (c - seed_col) + abc.y() * (r - seed_row) + abc.z();
        if (std::abs(h - z0 - predicted) > options.grow_tolerance_m) continue;
        label[nb] = patch_id;
        queue.push_back(nb);
      }
    }
    sums.Fit(&abc);
    SeedPlane plane{seed_row, seed_col, z0, abc};
    PlanarPatch patch = FinishPatch(hm, members, patch_id, plane, options, &label, &kind);
    patches.push_back(std::move(patch));
  }
  if (noise.denoised_cells > 0) RefitOnHeights(raw, noise, options.max_residual_m, &patches);
  JoinNoisePatches(raw, surface.cells, options, &patches);
  return patches;
}

}  // namespace mfp
