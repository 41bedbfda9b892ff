#include "geometry/region_reachability.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <optional>

#include "geometry/plan_bounds.h"

namespace mfp {
namespace {

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

void HeightRange(const ConvexRegion& r, double* lo, double* hi) {
  *lo = std::numeric_limits<double>::infinity();
  *hi = -*lo;
  for (const Eigen::Vector3d& v : r.vertices_world_m) {
    *lo = std::min(*lo, v.z() - r.plane_tolerance_m);
    *hi = std::max(*hi, v.z() + r.plane_tolerance_m);
  }
}

}  // namespace

double RegionPlanarDistance(const ConvexRegion& a, const ConvexRegion& b) {
  const auto& va = a.vertices_world_m;
  const auto& vb = b.vertices_world_m;
  double d = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : va) d = std::min(d, PlanDistanceToRegion(b, p.head<2>()));
  for (const Eigen::Vector3d& p : vb) d = std::min(d, PlanDistanceToRegion(a, p.head<2>()));
  if (d == 0.0) return 0.0;
  // Edges crossing without a vertex inside (two overlapping rectangles in a cross).
  for (size_t i = 0; i < va.size(); ++i) {
    const Eigen::Vector2d p = va[i].head<2>(), q = va[(i + 1) % va.size()].head<2>();
    for (size_t j = 0; j < vb.size(); ++j) {
      const Eigen::Vector2d r = vb[j].head<2>(), s = vb[(j + 1) % vb.size()].head<2>();
      const double d1 = Cross(q - p, r - p), d2 = Cross(q - p, s - p);
      const double d3 = Cross(s - r, p - r), d4 = Cross(s - r, q - r);
      if (((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0))) return 0.0;
    }
  }
  return d;
}

std::vector<int> StartRegionIndices(const std::vector<ConvexRegion>& regions,
                                    const std::vector<Eigen::Vector3d>& start_feet_world_m, double step_xy_m,
                                    double dz_max_m, double tolerance_m) {
  const int n = static_cast<int>(regions.size());
  std::vector<uint8_t> start(n, 0);
  for (const Eigen::Vector3d& f : start_feet_world_m) {
    bool on_region = false;
    for (int i = 0; i < n; ++i) {
      if (RegionContains(regions[i], f, tolerance_m)) start[i] = 1, on_region = true;
    }
    if (on_region) continue;
    // A foot on seen surface that no region holds: its first step lands within one step.
    for (int i = 0; i < n; ++i) {
      double lo = 0.0, hi = 0.0;
      HeightRange(regions[i], &lo, &hi);
      if (f.z() > hi + dz_max_m || f.z() < lo - dz_max_m) continue;
      if (PlanDistanceToRegion(regions[i], f.head<2>()) <= step_xy_m) start[i] = 1;
    }
  }
  std::vector<int> out;
  for (int i = 0; i < n; ++i) {
    if (start[i]) out.push_back(i);
  }
  return out;
}

std::optional<std::vector<int>> ReachableRegionIndices(const std::vector<ConvexRegion>& regions,
                                                       const std::vector<Eigen::Vector3d>& start_feet_world_m,
                                                       double step_xy_m, double dz_max_m, double tolerance_m,
                                                       const Deadline& deadline) {
  const int n = static_cast<int>(regions.size());
  std::vector<double> lo(n), hi(n);
  std::vector<Eigen::Vector2d> box_lo(n), box_hi(n);
  for (int i = 0; i < n; ++i) {
    HeightRange(regions[i], &lo[i], &hi[i]);
    const Eigen::AlignedBox2d bounds = PlanBounds(regions[i]);
    box_lo[i] = bounds.min();
    box_hi[i] = bounds.max();
  }
  std::vector<uint8_t> seen(n, 0);
  std::deque<int> queue;
  for (int i : StartRegionIndices(regions, start_feet_world_m, step_xy_m, dz_max_m, tolerance_m)) {
    seen[i] = 1;
    queue.push_back(i);
  }
  while (!queue.empty()) {
    if (deadline.Expired()) return std::nullopt;
    const int i = queue.front();
    queue.pop_front();
    for (int j = 0; j < n; ++j) {
      if (seen[j]) continue;
      // Cheap rejections first: height ranges, then bounding boxes.
      if (lo[j] > hi[i] + dz_max_m || lo[i] > hi[j] + dz_max_m) continue;
      const Eigen::Vector2d gap = (box_lo[j] - box_hi[i]).cwiseMax(box_lo[i] - box_hi[j]).cwiseMax(0.0);
      if (gap.norm() > step_xy_m) continue;
      if (RegionPlanarDistance(regions[i], regions[j]) > step_xy_m) continue;
      seen[j] = 1;
      queue.push_back(j);
    }
  }
  std::vector<int> out;
  for (int i = 0; i < n; ++i) {
    if (seen[i]) out.push_back(i);
  }
  return out;
}

std::vector<int> WindowRegionIndices(const std::vector<ConvexRegion>& regions,
                                     const std::vector<Eigen::Vector3d>& start_feet_world_m,
                                     int steps_per_leg, double step_xy_m, double dz_max_m) {
  const double reach_xy = steps_per_leg * step_xy_m, reach_z = steps_per_leg * dz_max_m;
  std::vector<int> out;
  for (size_t i = 0; i < regions.size(); ++i) {
    double lo, hi;
    HeightRange(regions[i], &lo, &hi);
    for (const Eigen::Vector3d& f : start_feet_world_m) {
      if (lo <= f.z() + reach_z && hi >= f.z() - reach_z &&
          PlanDistanceToRegion(regions[i], f.head<2>()) <= reach_xy) {
        out.push_back(static_cast<int>(i));
        break;
      }
    }
  }
  return out;
}

}  // namespace mfp
