#include "planner/planning/internal/window_body_regions.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "planner/planning/internal/route_guide.h"
#include "planner/robot/body_clearance.h"

namespace mfp {
namespace {

struct BodyPose {
  Eigen::Vector2d centre_m;
  double yaw_rad = 0.0;
};

// The body's plan box at the start stance, then along the stance route from the point
// nearest the start to reach_m ahead, every spacing_m.
std::vector<BodyPose> SeedPoses(const PlanContext& context, const FootstepProblem& problem, double reach_m,
                                double spacing_m) {
  const BodyPose start{StanceCentreXY(problem.start_feet_world_m), problem.start_yaw_rad};
  std::vector<BodyPose> seeds = {start};
  const RouteGuide& guide = context.guide;
  if (!context.guided || guide.route.size() < 2) return seeds;
  const double progress = RouteProgress(guide, start.centre_m);
  const double end = std::min(guide.length_m, progress + reach_m);
  for (double s = progress + spacing_m; s < end + 0.5 * spacing_m; s += spacing_m) {
    const double at = std::min(s, end);
    const std::optional<double> yaw = RouteYaw(guide, at);
    seeds.push_back({RoutePoint(guide, at), yaw ? *yaw : start.yaw_rad});
  }
  return seeds;
}

}  // namespace

std::vector<FreeRegion2d> WindowBodyRegions(const PlanContext& context, const FootstepProblem& problem,
                                           bool clear_of_body) {
  const RobotModel& robot = context.robot;
  const BodyExtent& body = robot.body;
  const FormulationOptions& options = context.options.formulation;
  if (!(options.body_regions || clear_of_body) || options.max_body_regions <= 0 || !body.known() ||
      context.request.body_obstacles.empty()) {
    return {};
  }
  // Where the body can be: over the window's regions (the centre of contacts is a mean
  // of feet on them), grown by the box's farthest corner.
  double radius = 0.0;
  for (const Eigen::Vector2d& c : {body.min_m, body.max_m, Eigen::Vector2d(body.min_m.x(), body.max_m.y()),
                                   Eigen::Vector2d(body.max_m.x(), body.min_m.y())}) {
    radius = std::max(radius, c.norm());
  }
  const int n = robot.num_legs();
  const int configurations = (problem.num_new_steps + n - 1) / n;
  // The highest ground the window can stand on: its start feet, and its regions within
  // the height its configurations can climb.
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(INFINITY), hi = Eigen::Vector2d::Constant(-INFINITY);
  double ground_hi = -INFINITY;
  for (const Eigen::Vector3d& f : problem.start_feet_world_m) {
    lo = lo.cwiseMin(f.head<2>());
    hi = hi.cwiseMax(f.head<2>());
    ground_hi = std::max(ground_hi, f.z());
  }
  const double climb_limit = ground_hi + configurations * robot.dz_max_m;
  for (const ConvexRegion& region : problem.regions) {
    for (const Eigen::Vector3d& v : region.vertices_world_m) {
      lo = lo.cwiseMin(v.head<2>());
      hi = hi.cwiseMax(v.head<2>());
      if (v.z() <= climb_limit) ground_hi = std::max(ground_hi, v.z());
    }
  }
  lo -= Eigen::Vector2d::Constant(radius);
  hi += Eigen::Vector2d::Constant(radius);
  std::vector<std::vector<Eigen::Vector2d>> near;
  for (const BodyObstacle& obstacle : context.request.body_obstacles) {
    // In the band over every ground the window can stand on: walls, not the stones and
    // steps it walks on (those are left to the after-the-fact check, window_body_check.h).
    if (!InBodyBand(body, obstacle, ground_hi)) continue;
    Eigen::Vector2d olo = Eigen::Vector2d::Constant(INFINITY), ohi = Eigen::Vector2d::Constant(-INFINITY);
    for (const Eigen::Vector2d& v : obstacle.polygon_world_m) {
      olo = olo.cwiseMin(v);
      ohi = ohi.cwiseMax(v);
    }
    if ((olo - hi).maxCoeff() < 0.0 && (lo - ohi).maxCoeff() < 0.0) near.push_back(obstacle.polygon_world_m);
  }
  if (near.empty()) return {};
  const double reach = configurations * 2.0 * robot.d_lim_m;
  const double spacing = 0.5 * std::min(body.length_m(), body.width_m());
  std::vector<FreeRegion2d> regions;
  for (const BodyPose& seed : SeedPoses(context, problem, reach, spacing)) {
    if (static_cast<int>(regions.size()) >= options.max_body_regions || context.request.deadline.Expired()) break;
    const std::vector<Eigen::Vector2d> box = BodyFootprint(body, seed.centre_m.x(), seed.centre_m.y(), seed.yaw_rad);
    bool held = false;  // a region grown before holds this pose with room to spare
    for (const FreeRegion2d& r : regions) held = held || RegionExcess(r, box) <= -options.body_margin_m;
    if (held) continue;
    if (std::optional<FreeRegion2d> region = GrowFreeRegion(box, near, lo, hi)) regions.push_back(std::move(*region));
  }
  return regions;
}

}  // namespace mfp
