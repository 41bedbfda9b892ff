#include "io/robot_json.h"

namespace mfp {

nlohmann::json RobotToJson(const RobotModel& robot) {
  nlohmann::json legs = nlohmann::json::array();
  for (const LegModel& leg : robot.legs) {
    const Eigen::Vector2d& o = leg.nominal_offset_body_m;
    legs.push_back({{"name", leg.name},
                    {"nominal_offset", {o.x(), o.y()}},
                    {"hip", {leg.hip_body_m.x(), leg.hip_body_m.y(), leg.hip_body_m.z()}}});
  }
  const PlannerWeights& w = robot.weights;
  return {{"name", robot.name},
          {"legs", legs},
          {"gait", robot.gait},
          {"d_lim", robot.d_lim_m},
          {"reach_shape", ReachShapeName(robot.reach_shape)},
          {"l_bnd", robot.l_bnd_m},
          {"dz_max", robot.dz_max_m},
          {"stance_height", robot.stance_height_m},
          {"foot_radius", robot.foot_radius_m},
          {"max_yaw_change", robot.max_yaw_change_rad},
          {"max_slope", robot.max_slope_rad},
          {"weights",
           {{"goal_position", w.goal_position},
            {"goal_yaw", w.goal_yaw},
            {"trim_step", w.trim_step},
            {"displacement", w.displacement}}},
          {"body_box",
           {{"known", robot.body.known()},
            {"min", {robot.body.min_m.x(), robot.body.min_m.y()}},
            {"max", {robot.body.max_m.x(), robot.body.max_m.y()}},
            {"bottom", robot.body.bottom_m},
            {"top", robot.body.top_m},
            {"length", robot.body.length_m()},
            {"width", robot.body.width_m()}}},
          {"provenance", robot.provenance}};
}

}  // namespace mfp
