#include "bench/course_checker.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "io/body_obstacles.h"
#include "planner/planning/footstep_planner.h"
#include "planner/robot/body_clearance.h"

namespace mfp {

namespace {

// How far the world offset w from a nominal foot lies beyond the leg's footprint polygon
// turned by yaw_rad: the largest face excess (<= 0 inside) [m].
double FootprintExcess(const LegModel& leg, double yaw_rad, const Eigen::Vector2d& w) {
  const Eigen::Vector2d body = Eigen::Rotation2Dd(-yaw_rad) * w;
  double excess = -1e300;
  for (const ReachFace& face : leg.footprint_faces) excess = std::max(excess, face.normal.dot(body) - face.offset_m);
  return excess;
}

std::string Fmt(const Eigen::Vector3d& p) {
  std::ostringstream s;
  s.precision(3);
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

// The body at each configuration: centre of contacts and yaw of the stance after each
// footstep, its band above the mean height of those feet, against the true boxes.
void CheckBody(const TerrainDescription& terrain, const RobotModel& robot, const std::vector<Footstep>& footsteps,
               const CourseCheckTolerances& tol, CourseVerdict* v) {
  if (!robot.body.known()) return;
  const int n = robot.num_legs();
  const std::vector<BodyObstacle> boxes = BoxBodyObstacles(terrain.boxes);
  std::vector<Eigen::Vector3d> feet(n, Eigen::Vector3d::Zero());
  size_t worst_step = 0;
  for (size_t k = 0; k < footsteps.size(); ++k) {
    feet[footsteps[k].leg] = footsteps[k].position_world_m;
    if (static_cast<int>(k) + 1 < n) continue;
    const Eigen::Vector2d c = StanceCentreXY(feet);
    double ground = 0.0;
    for (const Eigen::Vector3d& f : feet) ground += f.z() / n;
    const double share = BodyOverlapShare(robot.body, boxes, c.x(), c.y(), footsteps[k].yaw_rad, ground);
    if (share > v->body_overlap_share) {
      v->body_overlap_share = share;
      worst_step = k;
    }
  }
  if (v->body_overlap_share <= tol.body_share) return;
  v->body_clear = false;
  if (v->valid) v->cause = "body_collision";
  v->valid = false;
  v->violations.push_back("body_collision: " + std::to_string(100.0 * v->body_overlap_share) +
                          " % of the body's plan box inside a box after step " + std::to_string(worst_step));
}

}  // namespace

CourseVerdict CheckPlanOnCourse(const TerrainDescription& terrain, const RobotModel& robot,
                                const std::vector<Footstep>& footsteps, const Pose2D& goal,
                                double edge_margin_m, const CourseCheckTolerances& tol) {
  CourseVerdict v;
  const int n = robot.num_legs();
  auto fail = [&](const std::string& cause, const std::string& what) {
    if (v.valid) v.cause = cause;
    v.valid = false;
    v.violations.push_back(cause + ": " + what);
  };
  if (static_cast<int>(footsteps.size()) < n) {
    fail("no_plan", "fewer footsteps than legs");
    return v;
  }
  std::vector<Eigen::Vector3d> feet(n, Eigen::Vector3d::Zero());
  std::vector<bool> seen(n, false);
  for (int k = 0; k < n; ++k) {
    feet[footsteps[k].leg] = footsteps[k].position_world_m;
    seen[footsteps[k].leg] = true;
  }
  for (int i = 0; i < n; ++i) {
    if (!seen[i]) fail("no_plan", "start stance lacks a leg");
  }
  if (!v.valid) return v;
  // Configuration after each footstep; the start stance's for the first n.
  std::vector<Pose2D> configs;
  {
    const Eigen::Vector2d c = StanceCentreXY(feet);
    for (int k = 0; k < n; ++k) configs.push_back({c.x(), c.y(), footsteps[k].yaw_rad});
  }
  for (size_t k = n; k < footsteps.size(); ++k) {
    const Footstep& f = footsteps[k];
    const Eigen::Vector3d& p = f.position_world_m;
    if (!FootOnTrueSurface(terrain, p, edge_margin_m - tol.numeric_m, robot.max_slope_rad, tol.height_m)) {
      fail("off_surface", "step " + std::to_string(k) + " leg " + robot.legs[f.leg].name + " at " + Fmt(p));
    }
    if (std::abs(p.z() - feet[f.leg].z()) > robot.dz_max_m + tol.height_m) {
      fail("height_change", "step " + std::to_string(k) + " changes height by " +
                                std::to_string(p.z() - feet[f.leg].z()) + " m");
    }
    // Reach as the robot model states it (the paper's eq. 3-4): the new foot within the
    // d_lim square about its nominal spot in the configuration n steps back, and within the l_bnd square about its nominal spot
    // in the configuration it makes. Squares on world axes, centres the mean of the feet.
    const Pose2D before = configs[k - n];
    feet[f.leg] = p;
    const Eigen::Vector2d centre = StanceCentreXY(feet);
    configs.push_back({centre.x(), centre.y(), f.yaw_rad});
    const Eigen::Vector2d o = robot.legs[f.leg].nominal_offset_body_m;
    const Eigen::Vector2d from_before = p.head<2>() - NominalFootXY(robot, f.leg, before.x_m, before.y_m, before.yaw_rad);
    const Eigen::Vector2d from_own = p.head<2>() - (centre + Eigen::Rotation2Dd(f.yaw_rad) * o);
    if (robot.reach_shape == ReachShape::kFootprint) {
      // The leg's footprint polygon, turned by each configuration's yaw (robot_model.h).
      const double reach = FootprintExcess(robot.legs[f.leg], before.yaw_rad, from_before);
      const double ref = FootprintExcess(robot.legs[f.leg], f.yaw_rad, from_own);
      if (reach > tol.reach_m || ref > tol.reach_m) {
        fail("reach", "step " + std::to_string(k) + " leg " + robot.legs[f.leg].name + " is " + std::to_string(reach) +
                          " m beyond its footprint polygon about its nominal spot n steps back, " +
                          std::to_string(ref) + " m beyond it about its own");
      }
      continue;
    }
    const double reach = from_before.cwiseAbs().maxCoeff();
    const double ref = from_own.cwiseAbs().maxCoeff();
    if (reach > robot.d_lim_m + tol.reach_m || ref > robot.l_bnd_m + tol.reach_m) {
      fail("reach", "step " + std::to_string(k) + " leg " + robot.legs[f.leg].name + " is " + std::to_string(reach) +
                        " m from its nominal spot n steps back (d_lim " + std::to_string(robot.d_lim_m) + "), " +
                        std::to_string(ref) + " m from its own (l_bnd " + std::to_string(robot.l_bnd_m) + ")");
    }
  }
  CheckBody(terrain, robot, footsteps, tol, &v);
  // Goal: every final foot near its goal spot, final yaw near the goal yaw. The yaw is
  // the one the final feet show (best fit of the nominal offsets), not the plan's own
  // claim: FinalStanceYaw reads the last footstep's yaw, and a stance rebuilt here with
  // yaw 0 made every goal facing elsewhere (the 90 degree turns) look missed.
  const double yaw = EstimateStanceYaw(robot, feet);
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d spot = NominalFootXY(robot, i, goal.x_m, goal.y_m, goal.yaw_rad);
    worst = std::max(worst, (feet[i].head<2>() - spot).norm());
  }
  const double yaw_error = std::abs(std::remainder(yaw - goal.yaw_rad, 2 * M_PI));
  v.reaches_goal = worst <= tol.goal_m && yaw_error <= tol.goal_yaw_rad;
  return v;
}

}  // namespace mfp
