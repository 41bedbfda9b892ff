#include "geometry/free_region_2d.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/internal/convex_polygon_difference.h"

namespace mfp {
namespace {

using Polygon = std::vector<Eigen::Vector2d>;

// An overlap of less than this area is touching, not meeting [m^2].
constexpr double kTouchArea = 1e-10;

double MinAlong(const Polygon& polygon, const Eigen::Vector2d& a) {
  double m = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& v : polygon) m = std::min(m, a.dot(v));
  return m;
}

double MaxAlong(const Polygon& polygon, const Eigen::Vector2d& a) { return -MinAlong(polygon, -a); }

Eigen::Vector2d Centroid(const Polygon& polygon) {
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& v : polygon) c += v;
  return c / static_cast<double>(polygon.size());
}

// Outward unit normals of a counter-clockwise polygon's edges.
void AddEdgeNormals(const Polygon& polygon, std::vector<Eigen::Vector2d>* normals) {
  for (size_t k = 0; k < polygon.size(); ++k) {
    const Eigen::Vector2d e = polygon[(k + 1) % polygon.size()] - polygon[k];
    if (e.norm() > 1e-12) normals->push_back(Eigen::Vector2d(e.y(), -e.x()).normalized());
  }
}

struct Separation {
  Eigen::Vector2d a;  // unit normal: the seed lies in a . x <= b, the obstacle in a . x >= b
  double b = 0.0;
  double gap = -std::numeric_limits<double>::infinity();  // between the two along a [m]
};

Separation Separate(const Polygon& seed, const Polygon& obstacle) {
  std::vector<Eigen::Vector2d> candidates;
  AddEdgeNormals(seed, &candidates);
  std::vector<Eigen::Vector2d> obstacle_normals;
  AddEdgeNormals(obstacle, &obstacle_normals);
  for (const Eigen::Vector2d& n : obstacle_normals) candidates.push_back(-n);
  const Eigen::Vector2d between = Centroid(obstacle) - Centroid(seed);
  if (between.norm() > 1e-12) candidates.push_back(between.normalized());
  Separation best;
  for (const Eigen::Vector2d& a : candidates) {
    const double b = MinAlong(obstacle, a);
    const double gap = b - MaxAlong(seed, a);
    if (gap > best.gap) best = {a, b, gap};
  }
  return best;
}

}  // namespace

std::optional<FreeRegion2d> GrowFreeRegion(const std::vector<Eigen::Vector2d>& seed,
                                           const std::vector<std::vector<Eigen::Vector2d>>& obstacles,
                                           const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  if (seed.size() < 3) return std::nullopt;
  for (const Eigen::Vector2d& v : seed) {
    if ((v - lo).minCoeff() < 0.0 || (hi - v).minCoeff() < 0.0) return std::nullopt;
  }
  std::vector<std::pair<Separation, int>> order;
  for (size_t k = 0; k < obstacles.size(); ++k) {
    if (obstacles[k].size() < 3) continue;
    const Separation s = Separate(seed, obstacles[k]);
    // Edge normals decide whether two convex polygons overlap (separating axes); a seed
    // that an obstacle overlaps has no free region.
    if (s.gap < -1e-9) return std::nullopt;
    order.emplace_back(s, static_cast<int>(k));
  }
  std::stable_sort(order.begin(), order.end(), [](const auto& x, const auto& y) { return x.first.gap < y.first.gap; });
  std::vector<Eigen::Vector2d> normals = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  std::vector<double> offsets = {hi.x(), hi.y(), -lo.x(), -lo.y()};
  Polygon region = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
  for (const auto& [separation, k] : order) {
    Polygon inside = obstacles[k];
    for (size_t r = 0; r < normals.size() && inside.size() >= 3; ++r) inside = KeepBelowLine(inside, normals[r], offsets[r]);
    if (inside.size() < 3 || std::abs(PolygonArea2d(inside)) < kTouchArea) continue;  // already cut off
    normals.push_back(separation.a);
    offsets.push_back(separation.b);
    region = KeepBelowLine(region, separation.a, separation.b);
  }
  FreeRegion2d out;
  out.A.resize(static_cast<Eigen::Index>(normals.size()), 2);
  out.b.resize(static_cast<Eigen::Index>(normals.size()));
  for (size_t r = 0; r < normals.size(); ++r) {
    out.A.row(static_cast<Eigen::Index>(r)) = normals[r].transpose();
    out.b(static_cast<Eigen::Index>(r)) = offsets[r];
  }
  out.polygon = std::move(region);
  return out;
}

double RegionExcess(const FreeRegion2d& region, const std::vector<Eigen::Vector2d>& points) {
  double worst = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& p : points) worst = std::max(worst, (region.A * p - region.b).maxCoeff());
  return worst;
}

}  // namespace mfp
