#include "planner/planning/internal/goal_footholds.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mfp {

namespace {

// The square of half side h about the spot when the seen surface certifies it (a flat disk
// of the foot radius, the margin and the square's half diagonal about the spot).
std::optional<ConvexRegion> CertifiedSquare(const SeenSurface& seen, const Eigen::Vector2d& spot, double foot_radius_m,
                                            double margin_m, double h, int id, bool refuse_runs = true) {
  const std::optional<SeenDisk> disk =
      FlatSeenDisk(seen, spot, foot_radius_m + margin_m + std::sqrt(2.0) * h, refuse_runs);
  if (!disk) return std::nullopt;
  const double z = 0.5 * (disk->low_m + disk->high_m);
  std::vector<Eigen::Vector3d> square;
  for (const auto& [dx, dy] : {std::pair{-1, -1}, std::pair{1, -1}, std::pair{1, 1}, std::pair{-1, 1}}) {
    square.emplace_back(spot.x() + dx * h, spot.y() + dy * h, z);
  }
  return MakeRegionFromPolygon(id, square, 0.5 * disk->cell_m);
}

}  // namespace

int NextRegionId(const std::vector<ConvexRegion>& regions, int at_least) {
  int next_id = at_least;
  for (const ConvexRegion& r : regions) next_id = std::max(next_id, r.id + 1);
  return next_id;
}

double FootholdHalfSide(const PlannerOptions& options) {
  return options.goal_foothold_half_side_m > 0.0 ? options.goal_foothold_half_side_m : 0.5 * options.goal_tolerance_m;
}

double FootholdMaxHalfSide(const RobotModel& robot, const PlannerOptions& options) {
  return options.goal_foothold_max_half_side_m > 0.0 ? options.goal_foothold_max_half_side_m : robot.d_lim_m;
}

std::optional<ConvexRegion> SeenFoothold(const SeenSurface& seen, const Eigen::Vector2d& spot, double foot_radius_m,
                                         double margin_m, double half_side_m, double max_half_side_m, int id,
                                         bool refuse_runs) {
  if (!(half_side_m > 0.0)) return std::nullopt;  // a square must have a side (and the doubling below must grow)
  std::optional<ConvexRegion> best = CertifiedSquare(seen, spot, foot_radius_m, margin_m, half_side_m, id, refuse_runs);
  // The larger squares keep the two-level test: refusing runs there too shrank a real scan's
  // goal footholds until the plan could not finish on them (docs/measurements.md).
  for (double h = 2.0 * half_side_m; best && h <= max_half_side_m + 1e-9; h *= 2.0) {
    std::optional<ConvexRegion> larger =
        CertifiedSquare(seen, spot, foot_radius_m, margin_m, h, id, /*refuse_runs=*/false);
    if (!larger) break;
    best = std::move(larger);
  }
  return best;
}

std::optional<FootholdGoal> SeenFootholdGoal(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                             const SeenSurface& seen, const GoalPose& goal,
                                             const PlannerOptions& options, const Deadline& deadline) {
  if (!options.goal_seen_footholds || seen.grids.empty()) return std::nullopt;
  const double half_side = FootholdHalfSide(options);
  auto stands = [&](const Eigen::Vector2d& spot) {
    return CertifiedSquare(seen, spot, robot.foot_radius_m, options.goal_foothold_margin_m, half_side, 0).has_value();
  };
  const std::optional<GoalPose> pose =
      NearestGoalWith(robot, regions, goal, options.goal_position_tolerance_m, options.goal_heading_tolerance_rad,
                      options.goal_search_step_m, options.goal_search_yaw_step_rad, stands, deadline);
  if (!pose) return std::nullopt;
  int next_id = NextRegionId(regions);
  FootholdGoal chosen{*pose, {}, {}, {}};
  for (int leg = 0; leg < robot.num_legs(); ++leg) {
    const Eigen::Vector2d spot = NominalFootXY(robot, leg, pose->x_m, pose->y_m, pose->yaw_rad);
    if (DistanceToNearestRegion(regions, spot) <= 0.0) continue;
    chosen.legs.push_back(leg);
    chosen.spots_m.push_back(spot);
    chosen.footholds.push_back(*SeenFoothold(seen, spot, robot.foot_radius_m, options.goal_foothold_margin_m, half_side,
                                             FootholdMaxHalfSide(robot, options), next_id++));
  }
  return chosen;
}

std::vector<ConvexRegion> StartFootholds(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                         const PlanRequest& request, const PlannerOptions& options, int first_id) {
  std::vector<ConvexRegion> footholds;
  if (!options.start_seen_footholds || request.seen_surface == nullptr || request.seen_surface->grids.empty()) {
    return footholds;
  }
  for (const Eigen::Vector3d& foot : request.start_feet_world_m) {
    bool on = false;
    for (const ConvexRegion& r : regions) on = on || RegionContains(r, foot, options.start_tolerance_m);
    if (on) continue;
    std::optional<ConvexRegion> hold = SeenFoothold(*request.seen_surface, foot.head<2>(), robot.foot_radius_m,
                                                    options.goal_foothold_margin_m, FootholdHalfSide(options),
                                                    FootholdMaxHalfSide(robot, options),
                                                    first_id + static_cast<int>(footholds.size()),
                                                    /*refuse_runs=*/false);
    if (hold) footholds.push_back(std::move(*hold));
  }
  return footholds;
}

}  // namespace mfp
