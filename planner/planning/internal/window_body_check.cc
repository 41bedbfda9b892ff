#include "planner/planning/internal/window_body_check.h"

#include <algorithm>
#include <sstream>

#include "planner/robot/body_clearance.h"
#include "planner/robot/body_obstacle_index.h"

namespace mfp {

std::optional<std::string> WindowBodyClash(const PlanContext& context, const std::vector<Footstep>& steps, int kept) {
  const RobotModel& robot = context.robot;
  const std::vector<BodyObstacle>& obstacles = context.request.body_obstacles;
  const size_t n = static_cast<size_t>(robot.num_legs());
  if (obstacles.empty() || !robot.body.known() || steps.size() <= n) return std::nullopt;
  // The configuration after step i stands on the n footsteps ending at i.
  const size_t end = std::min(steps.size(), n + static_cast<size_t>(std::max(0, kept)));
  const double radius_m = BodyRadius(robot.body);
  for (size_t i = n; i < end; ++i) {
    std::vector<Eigen::Vector3d> stance;
    double ground_z = 0.0;
    for (size_t k = i + 1 - n; k <= i; ++k) {
      stance.push_back(steps[k].position_world_m);
      ground_z += steps[k].position_world_m.z() / static_cast<double>(n);
    }
    const Eigen::Vector2d centre = StanceCentreXY(stance);
    // Only obstacles within the body's radius of its centre can meet its plan box.
    const std::vector<int> near = context.body_index.Near(centre, radius_m);
    const double share = BodyOverlapShare(robot.body, obstacles, near, centre.x(), centre.y(), steps[i].yaw_rad, ground_z);
    if (share > 0.0) {
      std::ostringstream why;
      why.precision(3);
      why << "the body at step " << i - n + 1 << " of the window (" << centre.x() << ", " << centre.y() << ") m, yaw "
          << steps[i].yaw_rad << " rad overlaps an obstacle (" << 100.0 * share << " % of its footprint)";
      return why.str();
    }
  }
  return std::nullopt;
}

}  // namespace mfp
