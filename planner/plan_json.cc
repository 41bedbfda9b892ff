#include "planner/plan_json.h"

#include <cmath>

namespace mfp {
namespace {

// JSON has no infinity; an unknown bound or gap is written as null.
nlohmann::json Number(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json RobotSummary(const RobotModel& robot) {
  nlohmann::json legs = nlohmann::json::array();
  for (const LegModel& leg : robot.legs) {
    legs.push_back({{"name", leg.name},
                    {"nominal_offset", {leg.nominal_offset_body_m.x(), leg.nominal_offset_body_m.y()}}});
  }
  return {{"name", robot.name}, {"legs", legs},         {"gait", robot.gait},
          {"d_lim", robot.d_lim_m}, {"l_bnd", robot.l_bnd_m}, {"dz_max", robot.dz_max_m}};
}

nlohmann::json RegionObject(const ConvexRegion& region) {
  nlohmann::json A = nlohmann::json::array(), b = nlohmann::json::array(), vertices = nlohmann::json::array();
  for (Eigen::Index row = 0; row < region.A.rows(); ++row) {
    A.push_back({region.A(row, 0), region.A(row, 1), region.A(row, 2)});
    b.push_back(region.b(row));
  }
  for (const Eigen::Vector3d& v : region.vertices_world_m) vertices.push_back({v.x(), v.y(), v.z()});
  return {{"id", region.id}, {"A", A}, {"b", b}, {"vertices", vertices}};
}

}  // namespace

nlohmann::json PlanToJson(const Plan& plan, const RobotModel& robot,
                          const std::vector<ConvexRegion>& regions) {
  nlohmann::json steps = nlohmann::json::array();
  for (const Footstep& f : plan.footsteps) {
    steps.push_back({{"index", f.index},
                     {"leg", f.leg},
                     {"x", f.position_world_m.x()},
                     {"y", f.position_world_m.y()},
                     {"z", f.position_world_m.z()},
                     {"yaw", f.yaw_rad},
                     {"region", f.region_id}});
  }
  nlohmann::json region_list = nlohmann::json::array();
  for (const ConvexRegion& r : regions) region_list.push_back(RegionObject(r));
  const int new_steps = std::max(0, static_cast<int>(plan.footsteps.size()) - robot.num_legs());
  return {{"status", ToString(plan.status)},
          {"message", plan.message},
          {"reaches_goal", plan.reaches_goal},
          {"objective", Number(plan.objective)},
          {"bound", Number(plan.bound)},
          {"gap", Number(plan.gap)},
          {"solve_time_s", plan.solve_time_s},
          {"nodes", plan.nodes},
          {"relaxations", plan.relaxations},
          {"windows", plan.windows},
          {"steps", new_steps},
          {"integer_variables", plan.integer_variables},
          {"objective_offset", plan.objective_offset},
          {"robot", RobotSummary(robot)},
          {"regions", region_list},
          {"footsteps", steps}};
}

}  // namespace mfp
