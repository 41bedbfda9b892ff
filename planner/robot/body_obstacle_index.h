#pragma once
// Body obstacles looked up by plan position: buckets of a square plan grid, each listing
// the obstacles whose plan bounding box meets it, so that a body pose looks only at the
// obstacles near it (a scanned map has thousands of prisms). Shared by the stance route's
// body check and the windows' after-the-fact check. Plain Eigen; no I/O.
#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "planner/robot/body_clearance.h"

namespace mfp {

class BodyObstacleIndex {
 public:
  BodyObstacleIndex() = default;
  // bucket_m: the grid's side [m] (a query's radius or more keeps each query to a few
  // buckets); must be > 0. The obstacles are not copied: they must outlive the index.
  BodyObstacleIndex(const std::vector<BodyObstacle>& obstacles, double bucket_m);

  // Indices (ascending, each once) of the obstacles whose plan bounding box lies less than
  // radius_m from centre: every obstacle a shape within radius_m of centre can overlap
  // with positive area, and perhaps some that it cannot.
  std::vector<int> Near(const Eigen::Vector2d& centre, double radius_m) const;
  size_t size() const { return bounds_.size(); }

 private:
  Eigen::Vector2i CellOf(const Eigen::Vector2d& p) const;

  double bucket_m_ = 1.0;
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> bounds_;  // plan bounding boxes [m]
  std::unordered_map<int64_t, std::vector<int>> buckets_;            // cell key -> obstacles meeting it
  std::vector<int> everywhere_;  // obstacles too large (or unbounded) for buckets: looked at from everywhere
};

// The radius of the body's plan box about its reference point [m]: its farthest corner.
double BodyRadius(const BodyExtent& body);

// Smallest bucket side for a body's index [m]: buckets of the body's radius, but not so
// small that one obstacle spans many of them.
constexpr double kBodyBucketMinM = 0.25;

}  // namespace mfp
