#include "planner/robot/body_clearance.h"

#include <algorithm>
#include <cmath>

namespace mfp {
namespace {

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Sutherland-Hodgman: the part of `subject` on the left of the directed edge a -> b.
std::vector<Eigen::Vector2d> ClipLeftOf(const std::vector<Eigen::Vector2d>& subject, const Eigen::Vector2d& a,
                                        const Eigen::Vector2d& b) {
  std::vector<Eigen::Vector2d> out;
  const size_t n = subject.size();
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& p = subject[i];
    const Eigen::Vector2d& q = subject[(i + 1) % n];
    const double sp = Cross(b - a, p - a), sq = Cross(b - a, q - a);
    if (sp >= 0) out.push_back(p);
    if ((sp >= 0) != (sq >= 0)) out.push_back(p + (sp / (sp - sq)) * (q - p));
  }
  return out;
}

}  // namespace

double PolygonArea(const std::vector<Eigen::Vector2d>& polygon) {
  double twice = 0.0;
  for (size_t i = 0; i < polygon.size(); ++i) twice += Cross(polygon[i], polygon[(i + 1) % polygon.size()]);
  return 0.5 * twice;
}

double ConvexOverlapArea(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b) {
  std::vector<Eigen::Vector2d> clipped = a;
  for (size_t i = 0; i < b.size() && clipped.size() >= 3; ++i) clipped = ClipLeftOf(clipped, b[i], b[(i + 1) % b.size()]);
  return clipped.size() >= 3 ? std::max(0.0, PolygonArea(clipped)) : 0.0;
}

bool InBodyBand(const BodyExtent& body, const BodyObstacle& obstacle, double ground_z_m) {
  return obstacle.top_z_m > ground_z_m + body.bottom_m && obstacle.bottom_z_m < ground_z_m + body.top_m;
}

namespace {

// The largest share over obstacle(0) .. obstacle(count - 1).
template <typename ObstacleAt>
double WorstOverlapShare(const BodyExtent& body, size_t count, const ObstacleAt& obstacle_at, double x_m, double y_m,
                         double yaw_rad, double ground_z_m) {
  if (!body.known()) return 0.0;
  const std::vector<Eigen::Vector2d> footprint = BodyFootprint(body, x_m, y_m, yaw_rad);
  const double area = body.length_m() * body.width_m();
  double worst = 0.0;
  for (size_t k = 0; k < count; ++k) {
    const BodyObstacle& obstacle = obstacle_at(k);
    if (!InBodyBand(body, obstacle, ground_z_m)) continue;
    worst = std::max(worst, ConvexOverlapArea(footprint, obstacle.polygon_world_m) / area);
  }
  return worst;
}

}  // namespace

double BodyOverlapShare(const BodyExtent& body, const std::vector<BodyObstacle>& obstacles, double x_m, double y_m,
                        double yaw_rad, double ground_z_m) {
  const auto at = [&obstacles](size_t k) -> const BodyObstacle& { return obstacles[k]; };
  return WorstOverlapShare(body, obstacles.size(), at, x_m, y_m, yaw_rad, ground_z_m);
}

double BodyOverlapShare(const BodyExtent& body, const std::vector<BodyObstacle>& obstacles,
                        const std::vector<int>& which, double x_m, double y_m, double yaw_rad, double ground_z_m) {
  const auto at = [&obstacles, &which](size_t k) -> const BodyObstacle& {
    return obstacles[static_cast<size_t>(which[k])];
  };
  return WorstOverlapShare(body, which.size(), at, x_m, y_m, yaw_rad, ground_z_m);
}

}  // namespace mfp
