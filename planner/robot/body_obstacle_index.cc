#include "planner/robot/body_obstacle_index.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/check.h"

namespace mfp {
namespace {

int64_t Key(int x, int y) { return (static_cast<int64_t>(x) << 32) ^ static_cast<uint32_t>(y); }

// An obstacle spanning more buckets than this is listed once, in everywhere_.
constexpr double kMaxBucketsPerObstacle = 1e5;

}  // namespace

BodyObstacleIndex::BodyObstacleIndex(const std::vector<BodyObstacle>& obstacles, double bucket_m)
    : bucket_m_(bucket_m) {
  MFP_CHECK(bucket_m > 0.0 && std::isfinite(bucket_m));
  constexpr double kInf = std::numeric_limits<double>::infinity();
  bounds_.reserve(obstacles.size());
  for (const BodyObstacle& o : obstacles) {
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(kInf), hi = -lo;
    for (const Eigen::Vector2d& v : o.polygon_world_m) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
    bounds_.emplace_back(lo, hi);
  }
  for (size_t k = 0; k < bounds_.size(); ++k) {
    const Eigen::Vector2d span = (bounds_[k].second - bounds_[k].first) / bucket_m_;
    if (!span.allFinite() || span.prod() > kMaxBucketsPerObstacle) {
      everywhere_.push_back(static_cast<int>(k));
      continue;
    }
    const Eigen::Vector2i lo = CellOf(bounds_[k].first), hi = CellOf(bounds_[k].second);
    for (int x = lo.x(); x <= hi.x(); ++x) {
      for (int y = lo.y(); y <= hi.y(); ++y) buckets_[Key(x, y)].push_back(static_cast<int>(k));
    }
  }
}

Eigen::Vector2i BodyObstacleIndex::CellOf(const Eigen::Vector2d& p) const {
  return Eigen::Vector2i(static_cast<int>(std::floor(p.x() / bucket_m_)), static_cast<int>(std::floor(p.y() / bucket_m_)));
}

std::vector<int> BodyObstacleIndex::Near(const Eigen::Vector2d& centre, double radius_m) const {
  std::vector<int> near = everywhere_;
  const Eigen::Vector2i lo = CellOf(centre - Eigen::Vector2d::Constant(radius_m));
  const Eigen::Vector2i hi = CellOf(centre + Eigen::Vector2d::Constant(radius_m));
  for (int x = lo.x(); x <= hi.x(); ++x) {
    for (int y = lo.y(); y <= hi.y(); ++y) {
      const auto bucket = buckets_.find(Key(x, y));
      if (bucket == buckets_.end()) continue;
      for (int k : bucket->second) {
        const Eigen::Vector2d gap = (bounds_[k].first - centre).cwiseMax(centre - bounds_[k].second).cwiseMax(
            Eigen::Vector2d::Zero());
        if (gap.norm() < radius_m) near.push_back(k);
      }
    }
  }
  std::sort(near.begin(), near.end());
  near.erase(std::unique(near.begin(), near.end()), near.end());
  return near;
}

double BodyRadius(const BodyExtent& body) {
  return std::max({body.min_m.norm(), body.max_m.norm(), Eigen::Vector2d(body.min_m.x(), body.max_m.y()).norm(),
                   Eigen::Vector2d(body.max_m.x(), body.min_m.y()).norm()});
}

}  // namespace mfp
