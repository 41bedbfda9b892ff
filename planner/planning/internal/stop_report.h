#pragma once
// Where a plan that ends short of the goal stopped, and the place ahead that blocks it: the
// first gap in the regions along the way left (the route, or the straight line to the goal
// unguided) that a leg's nominal path must cross and one step cannot span. A step moves a
// foot at most d_lim + l_bnd on each world axis (the reach box about the previous nominal
// spot plus the reference box the previous foot stood in), so a gap wider than that on
// both axes is one no window can cross, whatever the search's time. Private to
// planner/planning.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "base/deadline.h"
#include "planner/formulation/plan.h"
#include "planner/planning/internal/plan_context.h"

namespace mfp {

// The way ahead of a stance, sampled along its path for each leg's nominal foot.
struct StopPath {
  std::vector<Eigen::Vector2d> centres_m;  // body centre, from the stance on [m, world]
  std::vector<double> yaws_rad;            // body yaw at each centre [rad]
};

// The way left from the last stance (centre, yaw): the route from the stance's nearest
// route point to its end (the route's yaws where it carries them, else the stance's yaw),
// or the straight line to the goal; points about sample_m apart, at most max_points.
StopPath PathAhead(const PlanContext& context, const Eigen::Vector2d& centre_m, double yaw_rad, double sample_m,
                   int max_points);

// The first gap along the path ahead, over every leg, that one step cannot span (or, when
// none, the widest gap ahead). feet: the last stance, one per leg in leg order, with the
// ids of the regions they stand on. regions: the plan's regions (ids as in the footsteps).
// step_span_m: the most a step moves a foot on one axis (d_lim + l_bnd). A search that
// reaches the deadline before it has examined the whole way returns no gap (found false).
PlanStopGap FirstGapAhead(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                          const std::vector<Footstep>& feet, const StopPath& path, double step_span_m,
                          const Deadline& deadline);

// The stop of a plan ending short of the goal: its last stance (the plan's last n
// footsteps) and the gap ahead; reason says why the windows ended (a short phrase). The
// gap search ends at `deadline` (then no gap is named).
PlanStop DescribeStop(const PlanContext& context, const Plan& plan, const std::string& reason,
                      const Deadline& deadline);

// "stopped at (x, y, yaw) on regions ...; ahead, leg k ('name') must cross ...": the
// stop's place and the gap ahead, for the plan's message.
std::string StopText(const RobotModel& robot, const PlanStop& stop);

}  // namespace mfp
