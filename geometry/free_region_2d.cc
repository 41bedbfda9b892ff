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

// The outward unit normal of a counter-clockwise polygon's edge k; false for an edge too
// short to have one.
bool EdgeNormal(const Polygon& polygon, size_t k, Eigen::Vector2d* normal) {
  const Eigen::Vector2d e = polygon[(k + 1) % polygon.size()] - polygon[k];
  if (e.norm() <= 1e-12) return false;
  *normal = Eigen::Vector2d(e.y(), -e.x()).normalized();
  return true;
}

struct Separation {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();  // unit normal: the seed lies in a . x <= b, the obstacle in a . x >= b
  double b = 0.0;
  double gap = -std::numeric_limits<double>::infinity();  // between the two along a [m]
};

struct Bounds {
  Eigen::Vector2d lo, hi;
  // Strictly apart along x or y: the two sets share no point.
  bool Apart(const Bounds& o) const {
    return hi.x() < o.lo.x() || o.hi.x() < lo.x() || hi.y() < o.lo.y() || o.hi.y() < lo.y();
  }
};

Bounds BoundsOf(const Polygon& polygon) {
  Bounds b{Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()),
           Eigen::Vector2d::Constant(-std::numeric_limits<double>::infinity())};
  for (const Eigen::Vector2d& v : polygon) {
    b.lo = b.lo.cwiseMin(v);
    b.hi = b.hi.cwiseMax(v);
  }
  return b;
}

// What Separate needs of the seed, the same for every obstacle: its edge normals, how far
// it reaches along each, and its centroid.
struct SeedShape {
  explicit SeedShape(const Polygon& seed) : polygon(seed), centroid(Centroid(seed)) {
    for (size_t k = 0; k < seed.size(); ++k) {
      Eigen::Vector2d n;
      if (!EdgeNormal(seed, k, &n)) continue;
      normals.push_back(n);
      reach.push_back(MaxAlong(seed, n));
      axis_normals = axis_normals && ((n.x() == 0.0 && std::abs(n.y()) == 1.0) || (n.y() == 0.0 && std::abs(n.x()) == 1.0));
    }
  }
  const Polygon& polygon;
  Eigen::Vector2d centroid;
  std::vector<Eigen::Vector2d> normals;
  std::vector<double> reach;
  // Every normal exactly (+-1, 0) or (0, +-1) (a lattice rectangle's): a . v is v's
  // coordinate or its negative, so an obstacle's least a . v is a side of its bounds.
  bool axis_normals = true;
};

// The candidate lines in this order (the first of equal gaps wins): the seed's edge
// normals, the obstacle's reversed, the direction between their centroids.
Separation Separate(const SeedShape& seed, const Polygon& obstacle) {
  Separation best;
  auto consider = [&](const Eigen::Vector2d& a, double seed_reach) {
    const double b = MinAlong(obstacle, a);
    const double gap = b - seed_reach;
    if (gap > best.gap) best = {a, b, gap};
  };
  for (size_t k = 0; k < seed.normals.size(); ++k) consider(seed.normals[k], seed.reach[k]);
  for (size_t k = 0; k < obstacle.size(); ++k) {
    Eigen::Vector2d n;
    if (!EdgeNormal(obstacle, k, &n)) continue;
    consider(-n, MaxAlong(seed.polygon, -n));
  }
  const Eigen::Vector2d between = Centroid(obstacle) - seed.centroid;
  if (between.norm() > 1e-12) {
    const Eigen::Vector2d a = between.normalized();
    consider(a, MaxAlong(seed.polygon, a));
  }
  return best;
}

// The best gap along the seed's edge normals alone: Separate's first candidates.
double SeedNormalsGap(const SeedShape& seed, const Polygon& obstacle) {
  double best = -std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < seed.normals.size(); ++k) best = std::max(best, MinAlong(obstacle, seed.normals[k]) - seed.reach[k]);
  return best;
}

// SeedNormalsGap from the obstacle's bounds, when the seed's normals lie along the axes:
// MinAlong along (+-1, 0) or (0, +-1) is the bounds' side (negated), the same value.
double SeedNormalsGap(const SeedShape& seed, const Bounds& obstacle) {
  double best = -std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < seed.normals.size(); ++k) {
    const Eigen::Vector2d& n = seed.normals[k];
    const double least = n.x() > 0.0 ? obstacle.lo.x() : n.x() < 0.0 ? -obstacle.hi.x()
                       : n.y() > 0.0 ? obstacle.lo.y() : -obstacle.hi.y();
    best = std::max(best, least - seed.reach[k]);
  }
  return best;
}

// An obstacle waiting for its turn, keyed by its gap or a lower bound of it.
struct Pending {
  double key;
  int index;
};

// An obstacle whose exact gap is known, waiting for its turn with its separating line.
struct PendingCut {
  double key;  // the gap
  int index;
  Separation separation;
};

// The order of turns (a max-heap of this): the smaller key first, then the smaller index.
struct ComesLater {
  template <typename X, typename Y>
  bool operator()(const X& x, const Y& y) const {
    return x.key > y.key || (x.key == y.key && x.index > y.index);
  }
};

// The obstacles in the order of their bounds (SeedNormalsGap), sorted a few at a time:
// before each few, those apart from the region are dropped (they would be on their turn).
class BoundOrder {
 public:
  BoundOrder(const SeedShape& seed, const Polygon* obstacles, size_t count) : bounds_(count) {
    pending_.reserve(count);
    for (size_t k = 0; k < count; ++k) {
      if (obstacles[k].size() < 3) continue;
      bounds_[k] = BoundsOf(obstacles[k]);
      const double key = seed.axis_normals ? SeedNormalsGap(seed, bounds_[k]) : SeedNormalsGap(seed, obstacles[k]);
      pending_.push_back({key, static_cast<int>(k)});
    }
  }

  const Bounds& bounds(int k) const { return bounds_[static_cast<size_t>(k)]; }

  // The next obstacle in order, nullptr when none is left.
  const Pending* Next(const Bounds& region) {
    if (head_ == sorted_end_) SortMore(region);
    return head_ < sorted_end_ ? &pending_[head_] : nullptr;
  }
  void Pop() { ++head_; }

 private:
  static constexpr size_t kFew = 32;

  void SortMore(const Bounds& region) {
    const auto rest = pending_.begin() + static_cast<std::ptrdiff_t>(head_);
    pending_.erase(std::remove_if(rest, pending_.end(), [&](const Pending& p) { return bounds(p.index).Apart(region); }),
                   pending_.end());
    const auto before = [](const Pending& x, const Pending& y) { return ComesLater()(y, x); };
    const auto end = rest + static_cast<std::ptrdiff_t>(std::min(kFew, pending_.size() - head_));
    std::nth_element(rest, end, pending_.end(), before);
    std::sort(rest, end, before);
    sorted_end_ = static_cast<size_t>(end - pending_.begin());
  }

  std::vector<Pending> pending_;
  std::vector<Bounds> bounds_;
  size_t head_ = 0, sorted_end_ = 0;
};

// Whether the obstacle meets the region { normals . x <= offsets } in more than touching:
// the obstacle clipped by every line in turn keeps an area. An obstacle whose bounds are
// apart from the region polygon's meets it in nothing (the clip would leave rounding only).
bool MeetsRegion(const Polygon& obstacle, const Bounds& obstacle_bounds, const Bounds& region_bounds,
                 const std::vector<Eigen::Vector2d>& normals, const std::vector<double>& offsets, Polygon* inside,
                 Polygon* scratch) {
  if (obstacle_bounds.Apart(region_bounds)) return false;
  // Wholly on or beyond one line: the clip by that line keeps no area (the common case for
  // an obstacle a cut already passed), so no copy is clipped. Any such line answers, so
  // the cuts are tried latest first (an obstacle is passed by the cuts near it, which come
  // late for the obstacles whose turn comes late) and the box's four sides, which hold
  // every obstacle grown among, last.
  for (size_t r = normals.size(); r-- > 0;) {
    if (MinAlong(obstacle, normals[r]) >= offsets[r]) return false;
  }
  *inside = obstacle;
  for (size_t r = 0; r < normals.size() && inside->size() >= 3; ++r) {
    KeepBelowLineInto(*inside, normals[r], offsets[r], scratch);
    std::swap(*inside, *scratch);
  }
  return inside->size() >= 3 && std::abs(PolygonArea2d(*inside)) >= kTouchArea;
}

}  // namespace

std::optional<FreeRegion2d> GrowFreeRegion(const std::vector<Eigen::Vector2d>& seed,
                                           const std::vector<std::vector<Eigen::Vector2d>>& obstacles,
                                           const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  Eigen::Vector2d near_lo, near_hi;
  return GrowFreeRegionNear(seed, obstacles, lo, hi, std::numeric_limits<double>::infinity(), &near_lo, &near_hi);
}

std::optional<FreeRegion2d> GrowFreeRegionNear(const std::vector<Eigen::Vector2d>& seed,
                                               const std::vector<std::vector<Eigen::Vector2d>>& obstacles,
                                               const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double near_gap,
                                               Eigen::Vector2d* near_lo, Eigen::Vector2d* near_hi) {
  return GrowFreeRegionNear(seed, obstacles.data(), obstacles.size(), lo, hi, near_gap, near_lo, near_hi);
}

std::optional<FreeRegion2d> GrowFreeRegionNear(const std::vector<Eigen::Vector2d>& seed,
                                               const std::vector<Eigen::Vector2d>* obstacles, size_t count,
                                               const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double near_gap,
                                               Eigen::Vector2d* near_lo, Eigen::Vector2d* near_hi) {
  if (seed.size() < 3) return std::nullopt;
  for (const Eigen::Vector2d& v : seed) {
    if ((v - lo).minCoeff() < 0.0 || (hi - v).minCoeff() < 0.0) return std::nullopt;
  }
  const SeedShape seed_shape(seed);
  // Obstacles in the order of their gaps, equal gaps by index (a stable sort's order), each
  // exact gap computed only when the obstacle comes up still near the region: first in the
  // order of the best gap along the seed's own normals (Separate's first candidates, so
  // never above the exact gap), then, when that bound comes up, by the exact gap (a heap of
  // the few that get one).
  BoundOrder by_bound(seed_shape, obstacles, count);
  std::vector<PendingCut> by_gap;  // a heap
  std::vector<Eigen::Vector2d> normals = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  std::vector<double> offsets = {hi.x(), hi.y(), -lo.x(), -lo.y()};
  Polygon region = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
  Bounds region_bounds = BoundsOf(region);
  Polygon inside, scratch;
  bool near_taken = false;
  auto take_near = [&] {
    *near_lo = region_bounds.lo;
    *near_hi = region_bounds.hi;
    near_taken = true;
  };
  for (;;) {
    const Pending* bound = by_bound.Next(region_bounds);
    if (bound == nullptr && by_gap.empty()) break;
    const bool bound_first = by_gap.empty() || (bound != nullptr && ComesLater()(by_gap.front(), *bound));
    if (!near_taken && (bound_first ? bound->key : by_gap.front().key) >= near_gap) take_near();
    if (bound_first) {
      const int k = bound->index;
      by_bound.Pop();
      const Polygon& obstacle = obstacles[k];
      // The region only shrinks: an obstacle apart from it now is cut off when its turn comes.
      // One that overlaps the seed is never apart (the seed stays in the region).
      if (by_bound.bounds(k).Apart(region_bounds)) continue;
      const Separation separation = Separate(seed_shape, obstacle);
      // Edge normals decide whether two convex polygons overlap (separating axes); a seed
      // that an obstacle overlaps has no free region.
      if (separation.gap < -1e-9) return std::nullopt;
      by_gap.push_back({separation.gap, k, separation});
      std::push_heap(by_gap.begin(), by_gap.end(), ComesLater());
      continue;
    }
    std::pop_heap(by_gap.begin(), by_gap.end(), ComesLater());
    const int k = by_gap.back().index;
    const Separation separation = by_gap.back().separation;
    by_gap.pop_back();
    if (!MeetsRegion(obstacles[k], by_bound.bounds(k), region_bounds, normals, offsets, &inside,
                     &scratch)) {
      continue;  // already cut off
    }
    normals.push_back(separation.a);
    offsets.push_back(separation.b);
    KeepBelowLineInto(region, separation.a, separation.b, &scratch);
    std::swap(region, scratch);
    region_bounds = BoundsOf(region);
  }
  if (!near_taken) take_near();
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
