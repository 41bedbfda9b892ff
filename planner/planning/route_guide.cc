#include "planner/planning/internal/route_guide.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <sstream>
#include <utility>

#include "geometry/convex_region.h"
#include "geometry/region_reachability.h"
#include "planner/planning/internal/stance_route.h"
#include "planner/robot/reach_polygon.h"

namespace mfp {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

bool InsidePolygon(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
  if (poly.size() < 3) return false;
  for (size_t k = 0; k < poly.size(); ++k) {
    const Eigen::Vector2d& a = poly[k];
    const Eigen::Vector2d& b = poly[(k + 1) % poly.size()];
    if ((b - a).x() * (p - a).y() - (b - a).y() * (p - a).x() < -1e-12) return false;
  }
  return true;
}

double PolygonPointDistance(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
  if (InsidePolygon(poly, p)) return 0.0;
  double d = kInf;
  for (size_t k = 0; k < poly.size(); ++k) d = std::min(d, PointSegmentDistance(p, poly[k], poly[(k + 1) % poly.size()]));
  return d;
}

Eigen::Vector2d ClosestPoint(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
  if (InsidePolygon(poly, p)) return p;
  return ClosestBoundaryPoint(poly, p);
}

double PolygonDistance(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b) {
  double d = kInf;
  for (const auto& p : a) d = std::min(d, PolygonPointDistance(b, p));
  for (const auto& p : b) d = std::min(d, PolygonPointDistance(a, p));
  return d;
}

struct Node {
  std::vector<Eigen::Vector2d> poly;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double zmin = kInf, zmax = -kInf;
};

// "" or, for the first start foot that no region holds and no region lies one step from,
// why that leg cannot take its first step.
std::string StartFootWithoutFirstStep(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                      const std::vector<Eigen::Vector3d>& start_feet, double span_m,
                                      double start_tolerance_m) {
  for (int i = 0; i < robot.num_legs(); ++i) {
    if (!StartRegionIndices(regions, {start_feet[i]}, span_m, robot.dz_max_m, start_tolerance_m).empty()) continue;
    std::ostringstream msg;
    msg.precision(3);
    msg << "no route: the start foot of leg '" << robot.legs[i].name << "' at (" << start_feet[i].x() << ", "
        << start_feet[i].y() << ", " << start_feet[i].z() << ") stands on no region and no region lies within one step ("
        << span_m << " m, dz_max " << robot.dz_max_m << " m) of it";
    return msg.str();
  }
  return "";
}

// The closest points of two convex polygons in plan view, a's first.
std::pair<Eigen::Vector2d, Eigen::Vector2d> ClosestPoints(const std::vector<Eigen::Vector2d>& a,
                                                          const std::vector<Eigen::Vector2d>& b) {
  std::pair<Eigen::Vector2d, Eigen::Vector2d> best(a.front(), b.front());
  double best_d = kInf;
  for (const Eigen::Vector2d& p : a) {
    const Eigen::Vector2d q = ClosestPoint(b, p);
    if ((q - p).norm() < best_d) best_d = (q - p).norm(), best = {p, q};
  }
  for (const Eigen::Vector2d& q : b) {
    const Eigen::Vector2d p = ClosestPoint(a, q);
    if ((q - p).norm() < best_d) best_d = (q - p).norm(), best = {p, q};
  }
  return best;
}

// The gap where the route breaks beyond reachable region `near`: of the regions no foot
// reaches that lie nearer the goal spot than `near` does and within dz_max of its height,
// the one closest to it; its width and what one step spans across it. "" when there is none.
std::string GapBeyond(const RobotModel& robot, const std::vector<ConvexRegion>& regions, const std::vector<Node>& nodes,
                      const std::vector<double>& dist, int near, const Eigen::Vector2d& spot) {
  const double near_to_spot = PolygonPointDistance(nodes[near].poly, spot);
  int beyond = -1;
  double width = kInf;
  for (int r = 0; r < static_cast<int>(nodes.size()); ++r) {
    if (dist[r] < kInf || nodes[r].poly.empty()) continue;
    if (std::max(nodes[r].zmin - nodes[near].zmax, nodes[near].zmin - nodes[r].zmax) > robot.dz_max_m) continue;
    if (PolygonPointDistance(nodes[r].poly, spot) >= near_to_spot) continue;
    const double d = PolygonDistance(nodes[near].poly, nodes[r].poly);
    if (d < width) width = d, beyond = r;
  }
  if (beyond < 0 || !(width > 0.0)) return "";
  const auto [p, q] = ClosestPoints(nodes[near].poly, nodes[beyond].poly);
  std::ostringstream msg;
  msg.precision(3);
  msg << "; the nearest region beyond it toward that spot, region " << regions[beyond].id << ", lies across a gap "
      << width << " m wide from (" << p.x() << ", " << p.y() << ") to (" << q.x() << ", " << q.y()
      << "), and one step (reach " << ReachShapeName(robot.reach_shape);
  if (robot.reach_shape == ReachShape::kFootprint) {
    msg << ", " << AxisStepSpanName(robot) << " " << AxisStepSpan(robot) << " m";
  } else {
    msg << " d_lim " << robot.d_lim_m << " m, l_bnd " << robot.l_bnd_m << " m";
  }
  msg << ") spans " << StepReachAlong(StepPolygon(robot), q - p) << " m in that direction";
  return msg.str();
}

}  // namespace

std::string FirstStepWithoutRegion(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                   const std::vector<Eigen::Vector3d>& start_feet, double start_yaw_rad,
                                   double start_tolerance_m) {
  const Eigen::Vector2d centre = StanceCentreXY(start_feet);
  const std::vector<Eigen::Vector2d> shape_reach = ReachPolygon(robot.reach_shape, robot.d_lim_m);
  for (int k = 0; k < robot.num_legs(); ++k) {
    // A footprint robot's first step stays in its leg's own polygon about the nominal foot,
    // turned to the start yaw (the start configuration's reach rows).
    std::vector<Eigen::Vector2d> reach = shape_reach;
    if (robot.reach_shape == ReachShape::kFootprint) {
      reach = ReachFaceCorners(robot.legs[k].footprint_faces);
      for (Eigen::Vector2d& v : reach) v = Eigen::Rotation2Dd(start_yaw_rad) * v;
    }
    bool held = false;
    for (const ConvexRegion& r : regions) held = held || RegionContains(r, start_feet[k], start_tolerance_m);
    if (held) continue;
    const Eigen::Vector2d nominal = NominalFootXY(robot, k, centre.x(), centre.y(), start_yaw_rad);
    bool landing = false;
    for (const ConvexRegion& r : regions) {
      if (r.vertices_world_m.empty()) continue;
      double zlo = kInf, zhi = -kInf;
      std::vector<Eigen::Vector2d> poly;
      for (const Eigen::Vector3d& v : r.vertices_world_m) {
        poly.push_back(v.head<2>());
        zlo = std::min(zlo, v.z());
        zhi = std::max(zhi, v.z());
      }
      const double tol = r.plane_tolerance_m + 1e-6;
      if (zlo - tol > start_feet[k].z() + robot.dz_max_m || zhi + tol < start_feet[k].z() - robot.dz_max_m) continue;
      if (!poly.empty() && StepsToBridge(poly, {nominal}, reach) <= 1.0 + 1e-9) {
        landing = true;
        break;
      }
    }
    if (landing) continue;
    std::ostringstream msg;
    msg.precision(3);
    msg << "no route: the start foot of leg '" << robot.legs[k].name << "' at (" << start_feet[k].x() << ", "
        << start_feet[k].y() << ", " << start_feet[k].z() << ") stands on no region, and its first step, within d_lim "
        << robot.d_lim_m << " m of its nominal spot (" << nominal.x() << ", " << nominal.y()
        << ") in the start stance and dz_max " << robot.dz_max_m << " m of the foot, meets no region";
    return msg.str();
  }
  return "";
}

double MaxStepSpan(const RobotModel& robot) {
  double span = 0.0;
  for (const Eigen::Vector2d& v : StepPolygon(robot)) span = std::max(span, v.norm());
  return span;
}

RouteGuide PlanRoute(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                     const std::vector<Eigen::Vector3d>& start_feet, const Eigen::Vector2d& goal_xy, double goal_yaw_rad,
                     double goal_tolerance_m, double start_tolerance_m, const Deadline& deadline) {
  RouteGuide guide;
  const int m = static_cast<int>(regions.size());
  const int n = robot.num_legs();
  std::vector<Node> nodes(m);
  for (int r = 0; r < m; ++r) {
    for (const Eigen::Vector3d& v : regions[r].vertices_world_m) {
      nodes[r].poly.push_back(v.head<2>());
      nodes[r].centre += v.head<2>();
      nodes[r].zmin = std::min(nodes[r].zmin, v.z());
      nodes[r].zmax = std::max(nodes[r].zmax, v.z());
    }
    if (!nodes[r].poly.empty()) nodes[r].centre /= static_cast<double>(nodes[r].poly.size());
  }
  const double span = MaxStepSpan(robot);
  const std::vector<Eigen::Vector2d> step = StepPolygon(robot);
  // The step polygon's half-width on x and y.
  const double axis_span = AxisStepSpan(robot);
  std::vector<Eigen::AlignedBox2d> bounds(m);
  for (int r = 0; r < m; ++r) {
    for (const Eigen::Vector2d& p : nodes[r].poly) bounds[r].extend(p);
  }
  std::vector<std::vector<std::pair<int, double>>> edges(m);
  for (int a = 0; a < m; ++a) {
    if (deadline.Expired()) {
      guide.out_of_time = true;
      return guide;
    }
    for (int b = a + 1; b < m; ++b) {
      const double dz = std::max({0.0, nodes[a].zmin - nodes[b].zmax, nodes[b].zmin - nodes[a].zmax});
      if (dz > robot.dz_max_m) continue;
      // Joined only where one step's move bridges the gap (a window can cross it); plan
      // boxes farther apart than a step on x or y cannot be.
      const Eigen::Vector2d box_gap =
          (bounds[b].min() - bounds[a].max()).cwiseMax(bounds[a].min() - bounds[b].max());
      if (box_gap.maxCoeff() > axis_span) continue;
      if (nodes[a].poly.empty() || nodes[b].poly.empty()) continue;
      if (StepsToBridge(nodes[a].poly, nodes[b].poly, step) > 1.0 + 1e-9) continue;
      const double w = (nodes[a].centre - nodes[b].centre).norm();
      edges[a].push_back({b, w});
      edges[b].push_back({a, w});
    }
  }
  // Multi-source Dijkstra from every region under a start foot.
  std::vector<double> dist(m, kInf);
  std::vector<int> parent(m, -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  // (A start foot that no region holds starts from every region one step away; with none
  // there, that leg cannot take its first step.)
  guide.broken = StartFootWithoutFirstStep(robot, regions, start_feet, span, start_tolerance_m);
  if (!guide.broken.empty()) return guide;
  for (int r : StartRegionIndices(regions, start_feet, span, robot.dz_max_m, start_tolerance_m)) {
    dist[r] = 0;
    queue.push({0.0, r});
  }
  while (!queue.empty()) {
    const auto [d, r] = queue.top();
    queue.pop();
    if (d > dist[r]) continue;
    if (deadline.Expired()) {
      guide.out_of_time = true;
      return guide;
    }
    for (const auto& [s, w] : edges[r]) {
      if (d + w < dist[s]) {
        dist[s] = d + w;
        parent[s] = r;
        queue.push({d + w, s});
      }
    }
  }
  // Every leg needs a reachable region at its goal spot.
  int goal_region = -1;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d spot = goal_xy + Eigen::Rotation2Dd(goal_yaw_rad) * robot.legs[i].nominal_offset_body_m;
    int best = -1;
    bool any = false;
    for (int r = 0; r < m; ++r) {
      if (PolygonPointDistance(nodes[r].poly, spot) > goal_tolerance_m) continue;
      any = true;
      if (dist[r] < kInf && (best < 0 || dist[r] < dist[best])) best = r;
    }
    if (best < 0) {
      // Where it breaks: the reachable region nearest to this leg's goal spot.
      int near = -1;
      double near_d = kInf;
      for (int r = 0; r < m; ++r) {
        if (dist[r] == kInf) continue;
        const double dd = PolygonPointDistance(nodes[r].poly, spot);
        if (dd < near_d) {
          near_d = dd;
          near = r;
        }
      }
      std::ostringstream msg;
      msg.precision(3);
      msg << "no route: leg '" << robot.legs[i].name << "' cannot reach its goal spot (" << spot.x() << ", "
          << spot.y() << ")";
      if (!any) msg << ", which lies on no region";
      if (near >= 0) {
        msg << "; the regions reachable from the start end at region " << regions[near].id << " near ("
            << nodes[near].centre.x() << ", " << nodes[near].centre.y() << "), " << near_d
            << " m from that spot; beyond it every region is more than one step away (" << AxisStepSpanName(robot) << " "
            << AxisStepSpan(robot) << " m on x or y, " << span << " m at most) or more than " << robot.dz_max_m
            << " m (dz_max) higher or lower" << GapBeyond(robot, regions, nodes, dist, near, spot);
      }
      guide.broken = msg.str();
      return guide;
    }
    if (goal_region < 0 || dist[best] > dist[goal_region]) goal_region = best;
  }
  guide.connected = true;
  // Body route: start centre, the region centres of the longest legs' path, goal.
  const Eigen::Vector2d start = StanceCentreXY(start_feet);
  std::vector<int> path;
  for (int r = goal_region; r >= 0; r = parent[r]) path.push_back(r);
  std::reverse(path.begin(), path.end());
  guide.route.push_back(start);
  for (size_t k = 1; k < path.size(); ++k) {
    // Where the route crosses from one region to the next, then the next one's centre.
    const Node& a = nodes[path[k - 1]];
    const Node& b = nodes[path[k]];
    guide.route.push_back(0.5 * (ClosestPoint(a.poly, b.centre) + ClosestPoint(b.poly, a.centre)));
    guide.route.push_back(b.centre);
  }
  guide.route.push_back(goal_xy);
  for (size_t k = 1; k < guide.route.size(); ++k) guide.length_m += (guide.route[k] - guide.route[k - 1]).norm();
  return guide;
}

namespace {

// Where no body-clear stance route was found but the body check refused poses: when the
// same search without the body obstacles finds a route, the body (not the feet) is what
// blocks it, and the guide is no longer connected (the plan answers 'no route' rather than
// walking the region graph's route through the obstacle).
void RefuseBodyBlockedRoute(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                            const Eigen::Vector2d& start, double start_yaw_rad, const Eigen::Vector2d& goal_xy,
                            double goal_yaw_rad, const StanceRouteOptions& options, const StanceRoute& body_clear,
                            RouteGuide* guide, const Deadline& deadline) {
  StanceRouteOptions loose = options;
  loose.support_radius_l_bnd = std::max(options.support_radius_l_bnd, std::sqrt(2.0));
  const StanceRoute feet_only =
      PlanStanceRoute(robot, regions, {}, 0.0, start, start_yaw_rad, goal_xy, goal_yaw_rad, loose, deadline);
  guide->out_of_time = feet_only.out_of_time;
  if (!feet_only.found) return;
  std::ostringstream why;
  why.precision(3);
  why << "no route for the body: the feet could pass, but every stance route from the start to the goal meets an "
         "obstacle with the body's plan box ("
      << robot.body.length_m() << " x " << robot.body.width_m() << " m, " << body_clear.body_blocked_poses
      << " poses refused, at up to " << std::max(options.headings, options.fine_headings) << " headings";
  const Eigen::Vector2d& at = body_clear.body_blocked_nearest_goal_m;
  if (!std::isnan(at.x())) why << "; the refused pose nearest the goal at (" << at.x() << ", " << at.y() << ")";
  why << "); widen the passage, or check the robot's body_box";
  guide->connected = false;
  guide->broken = why.str();
}

}  // namespace

void FollowStanceRoute(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                       const std::vector<BodyObstacle>& body_obstacles,
                       const std::vector<Eigen::Vector3d>& start_feet, double start_yaw_rad,
                       const Eigen::Vector2d& goal_xy, double goal_yaw_rad, const StanceRouteOptions& options,
                       RouteGuide* guide, const Deadline& deadline) {
  if (!guide->connected || start_feet.empty()) return;
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  double ground_z = 0.0;
  for (const auto& f : start_feet) {
    start += f.head<2>();
    ground_z += f.z();
  }
  start /= static_cast<double>(start_feet.size());
  ground_z /= static_cast<double>(start_feet.size());
  StanceRoute stances = PlanStanceRouteWithFallbacks(robot, regions, body_obstacles, ground_z, start, start_yaw_rad,
                                                     goal_xy, goal_yaw_rad, options, deadline);
  guide->out_of_time = stances.out_of_time;
  if (!stances.found && !stances.out_of_time && stances.body_blocked_poses > 0) {
    RefuseBodyBlockedRoute(robot, regions, start, start_yaw_rad, goal_xy, goal_yaw_rad, options, stances, guide,
                           deadline);
  }
  if (!stances.found) return;
  guide->route = stances.route;
  // The route's yaws where the yaw matters: the body check refused poses, or enough route
  // poses are usable only turned away from the goal's heading that windows aiming at it
  // would leave the route (one or two such poses on a long route: the goal's pull guides
  // better than the search's coarse headings).
  const double unusable_share =
      stances.route.empty() ? 0.0 : static_cast<double>(stances.goal_yaw_unusable_poses) / stances.route.size();
  if (stances.body_blocked_poses > 0 ||
      (stances.goal_yaw_unusable_poses > 0 && unusable_share >= options.route_yaw_unusable_share)) {
    guide->yaws_rad = stances.yaws_rad;
  }
  guide->length_m = stances.length_m;
  guide->from_stances = true;
}

Eigen::Vector2d RoutePoint(const RouteGuide& guide, double s_m) {
  if (guide.route.empty()) return Eigen::Vector2d::Zero();
  double s = std::max(0.0, s_m);
  for (size_t k = 1; k < guide.route.size(); ++k) {
    const double len = (guide.route[k] - guide.route[k - 1]).norm();
    if (s <= len && len > 0) return guide.route[k - 1] + (s / len) * (guide.route[k] - guide.route[k - 1]);
    s -= len;
  }
  return guide.route.back();
}

std::optional<double> RouteYaw(const RouteGuide& guide, double s_m) {
  if (guide.yaws_rad.size() != guide.route.size() || guide.route.empty()) return std::nullopt;
  double s = std::max(0.0, s_m);
  for (size_t k = 1; k < guide.route.size(); ++k) {
    const double len = (guide.route[k] - guide.route[k - 1]).norm();
    if (s < len) return guide.yaws_rad[k - 1];
    s -= len;
  }
  return guide.yaws_rad.back();
}

double RouteProgress(const RouteGuide& guide, const Eigen::Vector2d& p) {
  double best = kInf, best_s = 0.0, s = 0.0;
  for (size_t k = 1; k < guide.route.size(); ++k) {
    const Eigen::Vector2d a = guide.route[k - 1], b = guide.route[k];
    const Eigen::Vector2d d = b - a;
    const double len = d.norm();
    const double t = len > 0 ? std::clamp((p - a).dot(d) / (len * len), 0.0, 1.0) : 0.0;
    const double e = (a + t * d - p).norm();
    if (e < best) {
      best = e;
      best_s = s + t * len;
    }
    s += len;
  }
  return best_s;
}

}  // namespace mfp
