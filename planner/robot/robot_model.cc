#include "planner/robot/robot_model.h"

#include <cmath>
#include <set>
#include <sstream>

#include "base/check.h"
#include "planner/robot/nominal_foot.h"

namespace mfp {
namespace {

void RequirePositive(const std::string& robot, const char* field, double value) {
  if (!std::isfinite(value) || value <= 0.0) {
    std::ostringstream msg;
    msg << "robot '" << robot << "': " << field << " must be a finite number > 0, got " << value;
    throw InputError(msg.str());
  }
}

}  // namespace

void ValidateRobotModel(const RobotModel& robot) {
  const std::string& name = robot.name;
  if (robot.legs.size() < 2) {
    throw InputError("robot '" + name + "': needs at least 2 legs, has " +
                     std::to_string(robot.legs.size()));
  }
  const BodyExtent& body = robot.body;
  if (!body.min_m.allFinite() || !body.max_m.allFinite() || !std::isfinite(body.bottom_m) ||
      !std::isfinite(body.top_m) || (body.min_m.array() > body.max_m.array()).any() || body.bottom_m > body.top_m) {
    throw InputError("robot '" + name + "': body box needs finite numbers with min <= max (x and y) and "
                     "bottom <= top");
  }
  for (size_t k = 0; k < robot.legs.size(); ++k) {
    const LegModel& leg = robot.legs[k];
    if (!leg.nominal_offset_body_m.allFinite() || !leg.hip_body_m.allFinite()) {
      throw InputError("robot '" + name + "': leg " + std::to_string(k) + " ('" + leg.name +
                       "') has a non-finite nominal offset or hip position");
    }
  }
  if (robot.gait.size() != robot.legs.size()) {
    throw InputError("robot '" + name + "': gait must list each of the " +
                     std::to_string(robot.legs.size()) + " legs once, lists " +
                     std::to_string(robot.gait.size()));
  }
  std::set<int> seen;
  for (int leg : robot.gait) {
    if (leg < 0 || leg >= robot.num_legs() || !seen.insert(leg).second) {
      throw InputError("robot '" + name + "': gait entry " + std::to_string(leg) +
                       " is out of range [0, " + std::to_string(robot.num_legs() - 1) +
                       "] or repeated");
    }
  }
  RequirePositive(name, "d_lim", robot.d_lim_m);
  for (const LegModel& leg : robot.legs) {
    if (robot.reach_shape != ReachShape::kFootprint) break;
    bool holds_nominal = leg.footprint_faces.size() >= 3;
    for (const ReachFace& f : leg.footprint_faces) {
      holds_nominal = holds_nominal && std::isfinite(f.offset_m) && f.offset_m > 0.0 && f.normal.allFinite();
    }
    if (!holds_nominal) {
      throw InputError("robot '" + name + "': reach_shape footprint needs leg '" + leg.name +
                       "''s footprint polygon (at least 3 faces, each with a positive offset): it is derived "
                       "from a URDF only");
    }
  }
  RequirePositive(name, "l_bnd", robot.l_bnd_m);
  RequirePositive(name, "dz_max", robot.dz_max_m);
  RequirePositive(name, "max_yaw_change", robot.max_yaw_change_rad);
  RequirePositive(name, "max_slope", robot.max_slope_rad);
  if (!std::isfinite(robot.foot_radius_m) || robot.foot_radius_m < 0.0) {
    throw InputError("robot '" + name + "': foot_radius must be a finite number >= 0");
  }
  if (!std::isfinite(robot.stance_height_m) || robot.stance_height_m < 0.0) {
    throw InputError("robot '" + name + "': stance_height must be a finite number >= 0");
  }
  const PlannerWeights& w = robot.weights;
  if (!std::isfinite(w.goal_position) || w.goal_position <= 0.0 || !std::isfinite(w.goal_yaw) ||
      w.goal_yaw < 0.0 || !std::isfinite(w.trim_step) || w.trim_step > 0.0 ||
      !std::isfinite(w.displacement) || w.displacement < 0.0) {
    throw InputError("robot '" + name +
                     "': weights need goal_position > 0, goal_yaw >= 0, trim_step <= 0, "
                     "displacement >= 0 (all finite)");
  }
}

const char* ReachShapeName(ReachShape shape) {
  switch (shape) {
    case ReachShape::kOctagon:
      return "octagon";
    case ReachShape::kHexadecagon:
      return "hexadecagon";
    case ReachShape::kFootprint:
      return "footprint";
    case ReachShape::kBox:
      break;
  }
  return "box";
}

int ReachShapeSides(ReachShape shape) {
  switch (shape) {
    case ReachShape::kOctagon:
      return 8;
    case ReachShape::kHexadecagon:
    case ReachShape::kFootprint:
      return 16;
    case ReachShape::kBox:
      break;
  }
  return 4;
}

Eigen::Vector2d StanceCentreXY(const std::vector<Eigen::Vector3d>& feet_world_m) {
  MFP_CHECK(!feet_world_m.empty());
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const Eigen::Vector3d& f : feet_world_m) centre += f.head<2>();
  return centre / static_cast<double>(feet_world_m.size());
}

Eigen::Vector2d NominalFootXY(const RobotModel& robot, int leg, double x_m, double y_m, double yaw_rad) {
  MFP_CHECK(leg >= 0 && leg < robot.num_legs());
  const Eigen::Vector2d o = robot.legs[leg].nominal_offset_body_m;
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  return Eigen::Vector2d(NominalFootX(x_m, s, c, o), NominalFootY(y_m, s, c, o));
}

double LegReach(const RobotModel& robot) {
  double reach = 0.0;
  for (const LegModel& leg : robot.legs) reach = std::max(reach, leg.nominal_offset_body_m.norm());
  return reach;
}

double MaxYawChangeFor(double d_lim_m, double leg_reach_m) {
  return leg_reach_m > 0.0 ? 2.0 * std::asin(std::min(1.0, d_lim_m / (2.0 * leg_reach_m))) : M_PI / 4;
}

Eigen::Vector2d MeanNominalOffset(const RobotModel& robot) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const LegModel& leg : robot.legs) sum += leg.nominal_offset_body_m;
  return robot.legs.empty() ? sum : Eigen::Vector2d(sum / robot.legs.size());
}

std::vector<Eigen::Vector2d> BodyFootprint(const BodyExtent& body, double x_m, double y_m, double yaw_rad) {
  const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
  const Eigen::Vector2d local[4] = {body.min_m, {body.max_m.x(), body.min_m.y()}, body.max_m,
                                    {body.min_m.x(), body.max_m.y()}};
  std::vector<Eigen::Vector2d> corners;
  for (const Eigen::Vector2d& p : local) corners.emplace_back(x_m + c * p.x() - s * p.y(), y_m + s * p.x() + c * p.y());
  return corners;
}

}  // namespace mfp
