#include "bench/course_checker.h"

#include <Eigen/Geometry>
#include <cmath>
#include <sstream>

#include "planner/footstep_planner.h"

namespace mfp {

namespace {

bool InsideBox(const TerrainBox& box, const Eigen::Vector3d& p) {
  const Eigen::Vector3d q = BoxRotation(box).transpose() * (p - box.center_world_m);
  return std::abs(q.x()) < box.size_m.x() / 2 && std::abs(q.y()) < box.size_m.y() / 2 &&
         std::abs(q.z()) < box.size_m.z() / 2;
}

std::string Fmt(const Eigen::Vector3d& p) {
  std::ostringstream s;
  s.precision(3);
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

}  // namespace

bool FootOnTrueSurface(const TerrainDescription& terrain, const Eigen::Vector3d& p, double margin_m,
                       double max_slope_rad, double height_tol_m) {
  bool on_face = false;
  for (const TerrainBox& box : terrain.boxes) {
    const Eigen::Matrix3d r = BoxRotation(box);
    if (r(2, 2) < std::cos(max_slope_rad)) continue;  // local +z is the top face only when it points up enough
    const Eigen::Vector3d q = r.transpose() * (p - box.center_world_m);
    if (std::abs(q.z() - box.size_m.z() / 2) > height_tol_m) continue;
    if (std::abs(q.x()) > box.size_m.x() / 2 - margin_m || std::abs(q.y()) > box.size_m.y() / 2 - margin_m) continue;
    on_face = true;
    break;
  }
  if (!on_face) return false;
  const Eigen::Vector3d above = p + Eigen::Vector3d(0, 0, height_tol_m + 1e-3);
  for (const TerrainBox& box : terrain.boxes) {
    if (InsideBox(box, above)) return false;
  }
  return true;
}

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
  for (size_t k = n; k < footsteps.size(); ++k) {
    const Footstep& f = footsteps[k];
    const Eigen::Vector3d& p = f.position_world_m;
    if (!FootOnTrueSurface(terrain, p, edge_margin_m, robot.max_slope_rad, tol.height_m)) {
      fail("off_surface", "step " + std::to_string(k) + " leg " + robot.legs[f.leg].name + " at " + Fmt(p));
    }
    if (std::abs(p.z() - feet[f.leg].z()) > robot.dz_max_m + tol.height_m) {
      fail("height_change", "step " + std::to_string(k) + " changes height by " +
                                std::to_string(p.z() - feet[f.leg].z()) + " m");
    }
    feet[f.leg] = p;
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (const auto& q : feet) centre += q.head<2>();
    centre /= n;
    const Eigen::Rotation2Dd rot(f.yaw_rad);
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d off = rot.inverse() * (feet[i].head<2>() - centre) - robot.legs[i].nominal_offset_body_m;
      if (off.cwiseAbs().maxCoeff() > robot.d_lim_m + tol.reach_m) {
        fail("reach", "after step " + std::to_string(k) + " leg " + robot.legs[i].name + " is " +
                          std::to_string(off.cwiseAbs().maxCoeff()) + " m from its nominal spot (d_lim " +
                          std::to_string(robot.d_lim_m) + ")");
      }
    }
  }
  // Goal: every final foot near its goal spot, final yaw near the goal yaw.
  std::vector<Footstep> final_stance;
  for (int i = 0; i < n; ++i) final_stance.push_back(Footstep{0, i, feet[i], 0.0, -1});
  const double yaw = FinalStanceYaw(robot, final_stance);
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
