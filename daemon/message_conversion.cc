#include "daemon/message_conversion.h"

#include "base/format.h"

namespace mfp {

plan_t StatusReply(SolveStatus status, const std::string& message, int64_t request_id,
                   const std::string& robot_name, int64_t utime, int64_t map_utime) {
  plan_t reply{};  // value-initialised: no steps, every number zero, reaches_goal false
  reply.utime = utime;
  reply.request_id = request_id;
  reply.status = static_cast<int8_t>(status);
  // Names and messages quoting them are published escaped (EscapedText): no control
  // byte reaches a client's log, and a NUL cannot cut the LCM string.
  reply.message = EscapedText(message);
  reply.robot = EscapedText(robot_name);
  reply.map_utime = map_utime;
  return reply;
}

plan_t ToPlanMessage(const Plan& plan, int64_t request_id, const std::string& robot_name,
                     int64_t utime, int64_t map_utime) {
  plan_t reply = StatusReply(plan.status, plan.message, request_id, robot_name, utime, map_utime);
  reply.reaches_goal = plan.reaches_goal;
  reply.objective = plan.objective;
  reply.bound = plan.bound;
  reply.gap = plan.gap;
  reply.solve_time_s = plan.solve_time_s;
  reply.nodes = plan.nodes;
  for (const Footstep& f : plan.footsteps) {
    footstep_t step;
    step.index = f.index;
    step.leg = f.leg;
    for (int k = 0; k < 3; ++k) step.position[k] = f.position_world_m[k];
    step.yaw = f.yaw_rad;
    step.region_id = f.region_id;
    reply.steps.push_back(step);
  }
  reply.num_steps = static_cast<int32_t>(reply.steps.size());
  return reply;
}

region_set_t ToRegionSetMessage(const std::vector<ConvexRegion>& regions, const std::string& frame,
                                int64_t utime, int64_t map_utime) {
  region_set_t set;
  set.utime = utime;
  set.map_utime = map_utime;
  set.frame = EscapedText(frame);
  for (const ConvexRegion& r : regions) {
    region_t out;
    out.id = r.id;
    out.num_faces = static_cast<int32_t>(r.A.rows());
    for (Eigen::Index j = 0; j < r.A.rows(); ++j) {
      out.A.push_back({r.A(j, 0), r.A(j, 1), r.A(j, 2)});
      out.b.push_back(r.b(j));
    }
    out.num_vertices = static_cast<int32_t>(r.vertices_world_m.size());
    for (const Eigen::Vector3d& v : r.vertices_world_m) out.vertices.push_back({v.x(), v.y(), v.z()});
    for (int k = 0; k < 3; ++k) out.normal[k] = r.normal_world[k];
    out.plane_tolerance_m = r.plane_tolerance_m;
    out.area_m2 = r.area_m2;
    set.regions.push_back(std::move(out));
  }
  set.num_regions = static_cast<int32_t>(set.regions.size());
  return set;
}

std::vector<ConvexRegion> FromRegionSetMessage(const region_set_t& message) {
  std::vector<ConvexRegion> regions;
  for (const region_t& in : message.regions) {
    ConvexRegion r;
    r.id = in.id;
    r.A.resize(in.num_faces, 3);
    r.b.resize(in.num_faces);
    for (int j = 0; j < in.num_faces; ++j) {
      for (int k = 0; k < 3; ++k) r.A(j, k) = in.A[static_cast<size_t>(j)][static_cast<size_t>(k)];
      r.b(j) = in.b[static_cast<size_t>(j)];
    }
    for (const auto& v : in.vertices) r.vertices_world_m.emplace_back(v[0], v[1], v[2]);
    r.normal_world = Eigen::Vector3d(in.normal[0], in.normal[1], in.normal[2]);
    r.plane_tolerance_m = in.plane_tolerance_m;
    r.area_m2 = in.area_m2;
    regions.push_back(std::move(r));
  }
  return regions;
}

std::vector<Footstep> FootstepsFromPlanMessage(const plan_t& message) {
  std::vector<Footstep> steps;
  for (const footstep_t& s : message.steps) {
    steps.push_back(Footstep{s.index, s.leg, Eigen::Vector3d(s.position[0], s.position[1], s.position[2]), s.yaw,
                             s.region_id});
  }
  return steps;
}

}  // namespace mfp
