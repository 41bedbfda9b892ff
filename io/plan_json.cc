#include "io/plan_json.h"

#include <cmath>

#include "io/region_json.h"
#include "io/robot_json.h"

namespace mfp {
namespace {

// JSON has no infinity; an unknown bound or gap is written as null.
nlohmann::json Number(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

// A partial plan's stop (PlanStop): where its last stance stands and the gap ahead.
nlohmann::json StopToJson(const PlanStop& stop) {
  nlohmann::json json = {{"x", stop.centre_world_m.x()},
                         {"y", stop.centre_world_m.y()},
                         {"z", stop.centre_world_m.z()},
                         {"yaw", stop.yaw_rad},
                         {"regions", stop.regions},
                         {"reason", stop.reason}};
  const PlanStopGap& g = stop.gap;
  if (g.found) {
    json["gap"] = {{"leg", g.leg},
                   {"from_region", g.from_region},
                   {"to_region", g.to_region},
                   {"from", {g.from_m.x(), g.from_m.y()}},
                   {"to", {g.to_m.x(), g.to_m.y()}},
                   {"width", g.width_m},
                   {"rise", g.rise_m},
                   {"step_span", g.step_span_m},
                   {"blocks", g.blocks}};
    if (g.detour_region >= 0) {
      json["gap"]["detour_region"] = g.detour_region;
      json["gap"]["detour"] = {g.detour_m.x(), g.detour_m.y()};
    }
  }
  json["examined"] = g.examined;
  return json;
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
  // The plan's footholds on seen floor (ids above the caller's regions) join the list, so
  // every footstep's region names an entry; "footholds" lists their ids.
  std::vector<ConvexRegion> all_regions = regions;
  all_regions.insert(all_regions.end(), plan.footholds.begin(), plan.footholds.end());
  const nlohmann::json region_list = RegionsToJson(all_regions)["regions"];
  nlohmann::json foothold_ids = nlohmann::json::array();
  for (const ConvexRegion& r : plan.footholds) foothold_ids.push_back(r.id);
  const int new_steps = std::max(0, static_cast<int>(plan.footsteps.size()) - robot.num_legs());
  nlohmann::json json = {{"status", ToString(plan.status)},
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
          {"robot", RobotToJson(robot)},
          {"regions", region_list},
          {"footholds", foothold_ids},
          {"footsteps", steps},
          {"goal", {{"x", plan.goal_x_m}, {"y", plan.goal_y_m}, {"yaw", plan.goal_yaw_rad}, {"moved", plan.goal_moved}}}};
  if (plan.stop.stopped) json["stop"] = StopToJson(plan.stop);
  return json;
}

}  // namespace mfp
