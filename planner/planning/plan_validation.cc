#include "planner/planning/plan_validation.h"

#include <cmath>
#include <sstream>

#include "planner/base/check.h"
#include "planner/formulation/centre_of_contacts.h"
#include "planner/planning/footstep_planner.h"

namespace mfp {
double RotationTolerance(const RobotModel& robot, double yaw_segment_rad) {
  const double reach = LegReach(robot);
  // Distance between a point of the chord (linear in yaw) and the arc point of the same
  // yaw is below w^2/4 for segments up to pi/2; scaled by the offset length.
  return reach * yaw_segment_rad * yaw_segment_rad / 4.0;
}

std::vector<std::string> ValidatePlan(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                      const Plan& plan, const GoalSpec& goal,
                                      const ValidationTolerances& tol) {
  std::vector<std::string> errors;
  const int n = robot.num_legs();
  const auto& steps = plan.footsteps;
  const int N = static_cast<int>(steps.size());
  auto report = [&](int i, const std::string& what, double excess) {
    std::ostringstream msg;
    msg << "step " << i << " (leg " << (i < N ? steps[i].leg : -1) << "): " << what;
    if (excess > 0) msg << " off by " << excess;
    errors.push_back(msg.str());
  };
  if (N < n) {
    errors.push_back("plan has " + std::to_string(N) + " footsteps, fewer than the " + std::to_string(n) + " of a stance");
    return errors;
  }
  auto pos = [&](int j) -> Eigen::Vector3d {
    while (j < 0) j += n;  // before the plan: the start stance
    return steps[j].position_world_m;
  };
  auto yaw_of = [&](int j) { return steps[std::max(j, 0)].yaw_rad; };
  // The formulation's step expressions with exact sin/cos: centre of contacts (eq. 2) and
  // nominal foot (eq. 3).
  auto nominal = [&](int i) -> Eigen::Vector2d {
    const Eigen::Vector2d p =
        CentreOfContacts<Eigen::Vector2d>(i, n, [&](int j) { return Eigen::Vector2d(pos(j).head<2>()); });
    return NominalFootXY(robot, steps[std::max(i, 0)].leg, p.x(), p.y(), yaw_of(i));
  };
  for (int i = 0; i < N; ++i) {
    if (steps[i].leg != robot.gait[i % n]) report(i, "leg out of gait order (expected " + std::to_string(robot.gait[i % n]) + ")", 0);
    if (steps[i].index != i) report(i, "index field is " + std::to_string(steps[i].index), 0);
    if (!steps[i].position_world_m.allFinite() || !std::isfinite(steps[i].yaw_rad)) report(i, "non-finite value", 0);
  }
  if (!errors.empty()) return errors;
  for (int i = n; i < N; ++i) {
    const Eigen::Vector3d f = steps[i].position_world_m;
    // Safe region.
    const ConvexRegion* region = nullptr;
    for (const ConvexRegion& r : regions) {
      if (r.id == steps[i].region_id) region = &r;
    }
    if (region == nullptr) {
      report(i, "region id " + std::to_string(steps[i].region_id) + " does not exist", 0);
    } else if (RegionViolation(*region, f) > tol.position_m) {
      report(i, "outside region " + std::to_string(region->id), RegionViolation(*region, f));
    }
    // Reference box about r_nom,i and reachability box about r_nom,i-n.
    const Eigen::Vector2d ref = (f.head<2>() - nominal(i)).cwiseAbs();
    const Eigen::Vector2d reach = (f.head<2>() - nominal(i - n)).cwiseAbs();
    const double box_tol = tol.position_m + tol.rotation_m;
    if (ref.maxCoeff() > robot.l_bnd_m + box_tol) report(i, "reference box l_bnd", ref.maxCoeff() - robot.l_bnd_m);
    if (reach.maxCoeff() > robot.d_lim_m + box_tol) report(i, "reachability box d_lim", reach.maxCoeff() - robot.d_lim_m);
    const double dz = std::abs(f.z() - pos(i - n).z());
    if (dz > robot.dz_max_m + tol.position_m) report(i, "height change dz_max", dz - robot.dz_max_m);
    const double dyaw = std::abs(steps[i].yaw_rad - steps[i - 1].yaw_rad);
    if (dyaw > robot.max_yaw_change_rad + tol.yaw_rad) report(i, "yaw change", dyaw - robot.max_yaw_change_rad);
  }
  if (plan.reaches_goal) {
    const GoalDistances d = DistancesToGoal(robot, steps, goal);
    for (int k = 0; k < n; ++k) {
      const double foot = d.foot_m[k];
      if (foot > goal.tolerance_m + tol.position_m) report(N - n + k, "final foot far from its goal spot", foot - goal.tolerance_m);
    }
    if (d.yaw_rad > goal.yaw_tolerance_rad + tol.yaw_rad) report(N - 1, "final yaw far from the goal yaw", d.yaw_rad - goal.yaw_tolerance_rad);
  }
  return errors;
}

}  // namespace mfp
