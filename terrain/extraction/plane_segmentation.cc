#include "terrain/extraction/internal/plane_segmentation.h"

#include <Eigen/Dense>
#include <cmath>
#include <deque>

#include "base/check.h"

namespace mfp {
namespace {

constexpr int kUnvisited = -1;
constexpr int kDropped = -2;  // left out of a patch: may join a later one, never seeds one

// Running least-squares sums for z = a x + b y + c, in coordinates relative to the seed.
struct PlaneSums {
  Eigen::Matrix3d AtA = Eigen::Matrix3d::Zero();
  Eigen::Vector3d Atz = Eigen::Vector3d::Zero();
  int count = 0;
  void Add(double x, double y, double z) {
    const Eigen::Vector3d v(x, y, 1.0);
    AtA += v * v.transpose();
    Atz += v * z;
    ++count;
  }
  // Returns false when the cells do not fix a plane yet (fewer than 3 or collinear).
  bool Fit(Eigen::Vector3d* abc) const {
    if (count < 3) return false;
    Eigen::FullPivLU<Eigen::Matrix3d> lu(AtA);
    if (lu.rank() < 3) return false;
    *abc = lu.solve(Atz);
    return true;
  }
};

}  // namespace

double PlanarPatch::SlopeRad() const { return std::acos(std::min(1.0, normal_world.z())); }

std::vector<PlanarPatch> SegmentPlanarPatches(const HeightMap& hm, const SurfaceAnalysis& surface,
                                              const SegmentationOptions& options) {
  MFP_CHECK(surface.roughness_m.size() == hm.height_m.size());
  std::vector<int> label(hm.height_m.size(), kUnvisited);
  std::vector<PlanarPatch> patches;
  const double res = hm.resolution_m;
  const int drow[4] = {1, -1, 0, 0};
  const int dcol[4] = {0, 0, 1, -1};
  std::deque<int> queue;
  std::vector<int> members;
  for (int seed = 0; seed < static_cast<int>(label.size()); ++seed) {
    if (label[seed] != kUnvisited || !(surface.roughness_m[seed] <= options.max_seed_roughness_m)) {
      continue;
    }
    const int patch_id = static_cast<int>(patches.size());
    const int seed_row = seed / hm.cols, seed_col = seed % hm.cols;
    const double z0 = hm.height_m[seed];
    // Start from the cell's local plane, in cells relative to the seed.
    const Eigen::Vector3f& n0 = surface.normal_world[seed];
    Eigen::Vector3d abc(-n0.x() / n0.z() * res, -n0.y() / n0.z() * res, 0.0);
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
    PlanarPatch patch;
    for (int cell : members) {
      const int row = cell / hm.cols, col = cell % hm.cols;
      const double residual =
          hm.height_m[cell] - z0 - (abc.x() * (col - seed_col) + abc.y() * (row - seed_row) + abc.z());
      if (std::abs(residual) > options.max_residual_m) {
        label[cell] = kDropped;
        continue;
      }
      patch.max_residual_m = std::max(patch.max_residual_m, std::abs(residual));
      patch.cells.push_back(cell);
    }
    // Back to world coordinates: z = z0 + a' (x - x0)/res + b' (y - y0)/res + c'.
    const Eigen::Vector2d xy0 = hm.CellCenter(seed_row, seed_col);
    patch.a = abc.x() / res;
    patch.b = abc.y() / res;
    patch.c = z0 + abc.z() - patch.a * xy0.x() - patch.b * xy0.y();
    patch.normal_world = Eigen::Vector3d(-patch.a, -patch.b, 1.0).normalized();
    patches.push_back(std::move(patch));
  }
  return patches;
}

}  // namespace mfp
