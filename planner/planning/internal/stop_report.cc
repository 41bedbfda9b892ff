#include "planner/planning/internal/stop_report.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

#include "geometry/plan_bounds.h"
#include "planner/planning/internal/route_guide.h"
#include "planner/robot/reach_polygon.h"

namespace mfp {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// The way ahead's samples lie at least this far apart, whatever l_bnd: a robot model with
// a tiny or zero l_bnd must not ask for millions of samples [m].
constexpr double kMinSampleStepM = 1e-3;

// Chebyshev (L-infinity) distance from p to segment [a, b]: max(|ex(t)|, |ey(t)|) with
// e(t) = a + t (b - a) - p is convex and piecewise linear in t, so its least value over
// [0, 1] lies at an end or where a piece changes (ex = 0, ey = 0, ex = ey, ex = -ey).
double ChebyshevToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d e = a - p, d = b - a;
  auto at = [&](double t) { return (e + t * d).cwiseAbs().maxCoeff(); };
  double best = std::min(at(0.0), at(1.0));
  for (const auto& [num, den] : {std::pair{-e.x(), d.x()}, std::pair{-e.y(), d.y()},
                                 std::pair{e.y() - e.x(), d.x() - d.y()}, std::pair{-(e.x() + e.y()), d.x() + d.y()}}) {
    if (std::abs(den) < 1e-15) continue;
    const double t = num / den;
    if (t > 0.0 && t < 1.0) best = std::min(best, at(t));
  }
  return best;
}

std::vector<Eigen::Vector2d> Polygon(const ConvexRegion& r) {
  std::vector<Eigen::Vector2d> polygon;
  for (const Eigen::Vector3d& v : r.vertices_world_m) polygon.push_back(v.head<2>());
  return polygon;
}

bool SegmentsCross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d) {
  auto side = [](const Eigen::Vector2d& o, const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
    const double z = (p - o).x() * (q - o).y() - (p - o).y() * (q - o).x();
    return (z > 0.0) - (z < 0.0);
  };
  return side(a, b, c) * side(a, b, d) < 0 && side(c, d, a) * side(c, d, b) < 0;
}

// The least Chebyshev distance between two regions' polygons in plan view (0 where they
// meet): for disjoint convex polygons it lies between a vertex of one and an edge of the other.
double ChebyshevBetween(const ConvexRegion& a, const ConvexRegion& b) {
  const std::vector<Eigen::Vector2d> pa = Polygon(a), pb = Polygon(b);
  if (pa.empty() || pb.empty()) return kInf;
  for (const Eigen::Vector2d& v : pa) {
    if (PlanDistanceToRegion(b, v) <= 0.0) return 0.0;
  }
  for (const Eigen::Vector2d& v : pb) {
    if (PlanDistanceToRegion(a, v) <= 0.0) return 0.0;
  }
  double best = kInf;
  for (size_t i = 0; i < pa.size(); ++i) {
    const Eigen::Vector2d &a0 = pa[i], &a1 = pa[(i + 1) % pa.size()];
    for (size_t j = 0; j < pb.size(); ++j) {
      const Eigen::Vector2d &b0 = pb[j], &b1 = pb[(j + 1) % pb.size()];
      if (SegmentsCross(a0, a1, b0, b1)) return 0.0;
      best = std::min({best, ChebyshevToSegment(a0, b0, b1), ChebyshevToSegment(b0, a0, a1)});
    }
  }
  return best;
}

// The regions near the path (their plan-view boxes meet the path's box grown by `margin_m`),
// so that each sample looks at a few.
std::vector<int> RegionsNearPath(const std::vector<ConvexRegion>& regions, const StopPath& path, double margin_m) {
  Eigen::AlignedBox2d box;  // empty: an empty path has no region near it
  for (const Eigen::Vector2d& c : path.centres_m) box.extend(c);
  box.min().array() -= margin_m;
  box.max().array() += margin_m;
  std::vector<int> near;
  for (size_t i = 0; i < regions.size(); ++i) {
    if (PlanBounds(regions[i]).intersects(box)) near.push_back(static_cast<int>(i));
  }
  return near;
}

// The region (index) holding p whose height there is nearest z_m; -1: none holds p. (A
// region more than dz_max above or below is still named: the path meets it there.)
int SupportAt(const std::vector<ConvexRegion>& regions, const std::vector<int>& near, const Eigen::Vector2d& p,
              double z_m) {
  int best = -1;
  double best_dz = kInf;
  for (int i : near) {
    if (PlanDistanceToRegion(regions[static_cast<size_t>(i)], p) > 0.0) continue;
    const double dz = std::abs(regions[static_cast<size_t>(i)].HeightAt(p.x(), p.y()) - z_m);
    if (dz < best_dz) {
      best = i;
      best_dz = dz;
    }
  }
  return best;
}

// The region (index) with this id; -1 when none has it.
int IndexOfId(const std::vector<ConvexRegion>& regions, int id) {
  for (size_t i = 0; i < regions.size(); ++i) {
    if (regions[i].id == id) return static_cast<int>(i);
  }
  return -1;
}

// Heights of a region's vertices: lowest and highest [m].
std::pair<double, double> HeightSpan(const ConvexRegion& r) {
  double lo = kInf, hi = -kInf;
  for (const Eigen::Vector3d& v : r.vertices_world_m) lo = std::min(lo, v.z()), hi = std::max(hi, v.z());
  return {lo, hi};
}

// The first region (index) of a chain of steps from regions[from] to regions[to], each hop
// within step_span_m on both axes (ChebyshevBetween) and dz_max_m in height, through the
// regions of `near` whose boxes come within margin_m of the gap's ends; -1 when none joins them.
int DetourRegion(const std::vector<ConvexRegion>& regions, const std::vector<int>& near, int from, int to,
                 const Eigen::Vector2d& a, const Eigen::Vector2d& b, double step_span_m, double dz_max_m,
                 double margin_m) {
  Eigen::AlignedBox2d gap(a.cwiseMin(b), a.cwiseMax(b));
  gap.min().array() -= margin_m;
  gap.max().array() += margin_m;
  std::vector<int> local;
  for (int i : near) {
    if (PlanBounds(regions[static_cast<size_t>(i)]).intersects(gap)) local.push_back(i);
  }
  auto hop = [&](int u, int v) {
    const auto [ulo, uhi] = HeightSpan(regions[static_cast<size_t>(u)]);
    const auto [vlo, vhi] = HeightSpan(regions[static_cast<size_t>(v)]);
    if (std::max({0.0, ulo - vhi, vlo - uhi}) > dz_max_m) return false;
    return ChebyshevBetween(regions[static_cast<size_t>(u)], regions[static_cast<size_t>(v)]) <= step_span_m;
  };
  // Breadth first from `from`; first_hop[i]: the region after `from` on the chain to i.
  std::vector<int> first_hop(regions.size(), -2);
  std::vector<int> queue{from};
  first_hop[static_cast<size_t>(from)] = -1;
  for (size_t k = 0; k < queue.size(); ++k) {
    const int u = queue[k];
    for (int v : local) {
      if (first_hop[static_cast<size_t>(v)] != -2 || !hop(u, v)) continue;
      if (u == from && v == to) continue;  // the blocked crossing itself is no way round it
      first_hop[static_cast<size_t>(v)] = u == from ? v : first_hop[static_cast<size_t>(u)];
      if (v == to) return first_hop[static_cast<size_t>(v)];
      queue.push_back(v);
    }
  }
  return -1;
}

// 2: a gap no step crosses and no chain of steps goes round; 1: one a foot could go round;
// 0: within a step.
int Severity(const PlanStopGap& g) { return g.blocks ? (g.detour_region < 0 ? 2 : 1) : 0; }

// One leg's gaps along the path: the first that blocks (with the path index where it
// starts), else the widest.
struct LegGap {
  PlanStopGap gap;
  size_t starts_at = 0;
};

std::optional<LegGap> LegGapAhead(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                                  const std::vector<int>& near, const Footstep& foot, const StopPath& path,
                                  double step_span_m, double detour_margin_m, const Deadline& deadline,
                                  bool* cut_short) {
  int last = IndexOfId(regions, foot.region_id);
  Eigen::Vector2d last_xy = foot.position_world_m.head<2>();
  double z = foot.position_world_m.z();
  if (last < 0) last = SupportAt(regions, near, last_xy, z);
  std::optional<LegGap> chosen;
  constexpr size_t kNoGap = std::numeric_limits<size_t>::max();
  size_t gap_start = kNoGap;  // the path index where the current gap started
  auto offer = [&](const LegGap& g) {
    if (!chosen || Severity(g.gap) > Severity(chosen->gap) ||
        (Severity(g.gap) == 0 && Severity(chosen->gap) == 0 && g.gap.width_m > chosen->gap.width_m)) {
      chosen = g;
    }
  };
  for (size_t j = 0; j < path.centres_m.size(); ++j) {
    if (j % 64 == 0 && deadline.Expired()) {  // the rest of the way is not examined
      *cut_short = true;
      return chosen;
    }
    const Eigen::Vector2d p = NominalFootXY(robot, foot.leg, path.centres_m[j].x(), path.centres_m[j].y(), path.yaws_rad[j]);
    const int r = SupportAt(regions, near, p, z);
    if (r < 0) {
      if (gap_start == kNoGap) gap_start = j;
      continue;
    }
    const double rise_m = regions[static_cast<size_t>(r)].HeightAt(p.x(), p.y()) - z;
    if (last >= 0 && r != last && (gap_start != kNoGap || std::abs(rise_m) > robot.dz_max_m)) {
      LegGap g;
      g.starts_at = gap_start != kNoGap ? gap_start : j;
      g.gap.found = true;
      g.gap.leg = foot.leg;
      g.gap.from_region = regions[static_cast<size_t>(last)].id;
      g.gap.to_region = regions[static_cast<size_t>(r)].id;
      g.gap.from_m = last_xy;
      g.gap.to_m = p;
      g.gap.width_m = ChebyshevBetween(regions[static_cast<size_t>(last)], regions[static_cast<size_t>(r)]);
      g.gap.rise_m = rise_m;
      g.gap.step_span_m = step_span_m;
      g.gap.blocks = g.gap.width_m > step_span_m || std::abs(g.gap.rise_m) > robot.dz_max_m;
      if (g.gap.blocks) {
        const int detour = DetourRegion(regions, near, last, r, last_xy, p, step_span_m, robot.dz_max_m,
                                        detour_margin_m);
        if (detour >= 0) {
          g.gap.detour_region = regions[static_cast<size_t>(detour)].id;
          const std::vector<Eigen::Vector2d> polygon = Polygon(regions[static_cast<size_t>(detour)]);
          g.gap.detour_m = ClosestBoundaryPoint(polygon, 0.5 * (last_xy + p));
        }
      }
      if (g.gap.blocks || g.gap.width_m > 0.0) offer(g);  // regions that meet leave no gap
      if (chosen && chosen->gap.blocks && chosen->gap.detour_region < 0) return chosen;
    }
    gap_start = kNoGap;
    last = r;
    last_xy = p;
    z = regions[static_cast<size_t>(r)].HeightAt(p.x(), p.y());
  }
  if (gap_start != kNoGap && last >= 0) {  // the path leaves the regions for good
    LegGap g;
    g.starts_at = gap_start;
    g.gap.found = true;
    g.gap.leg = foot.leg;
    g.gap.from_region = regions[static_cast<size_t>(last)].id;
    g.gap.from_m = last_xy;
    g.gap.to_m = NominalFootXY(robot, foot.leg, path.centres_m.back().x(), path.centres_m.back().y(), path.yaws_rad.back());
    g.gap.width_m = (g.gap.to_m - g.gap.from_m).cwiseAbs().maxCoeff();
    g.gap.step_span_m = step_span_m;
    // A path's end a step or less past the last region (a goal spot within the goal
    // tolerance of one, or a goal foothold's edge) is no blocker.
    g.gap.blocks = g.gap.width_m > step_span_m;
    offer(g);
  }
  return chosen;
}

std::string Xy(const Eigen::Vector2d& p) {
  std::ostringstream s;
  s.precision(3);
  s << "(" << p.x() << ", " << p.y() << ")";
  return s.str();
}

}  // namespace

StopPath PathAhead(const PlanContext& context, const Eigen::Vector2d& centre_m, double yaw_rad, double sample_m,
                   int max_points) {
  StopPath path;
  std::vector<Eigen::Vector2d> corners{centre_m};
  std::vector<double> corner_yaws{yaw_rad};
  const RouteGuide& guide = context.guide;
  const bool route_yaws = context.guided && guide.route.size() >= 2 && guide.yaws_rad.size() == guide.route.size();
  if (context.guided && guide.route.size() >= 2) {
    const double s0 = RouteProgress(guide, centre_m);
    double s = 0.0;
    corners.push_back(RoutePoint(guide, s0));
    corner_yaws.push_back(RouteYaw(guide, s0).value_or(yaw_rad));
    for (size_t k = 1; k < guide.route.size(); ++k) {
      s += (guide.route[k] - guide.route[k - 1]).norm();
      if (s <= s0) continue;
      corners.push_back(guide.route[k]);
      corner_yaws.push_back(route_yaws ? guide.yaws_rad[k] : yaw_rad);
    }
  } else {
    corners.push_back(context.GoalXY());
    corner_yaws.push_back(yaw_rad);
  }
  // Without the route's yaws the body turns from the stance's yaw to the goal's along the
  // way; with them it holds each and turns to the goal's at the end (the goal stance).
  double total_m = 0.0;
  for (size_t k = 0; k + 1 < corners.size(); ++k) total_m += (corners[k + 1] - corners[k]).norm();
  const double turn = std::remainder(context.request.goal_yaw_rad - yaw_rad, 2.0 * M_PI);
  double along_m = 0.0;
  for (size_t k = 0; k + 1 < corners.size() && static_cast<int>(path.centres_m.size()) < max_points; ++k) {
    const double len = (corners[k + 1] - corners[k]).norm();
    // In double before the cast: a leg of the way may be longer than INT_MAX samples.
    const double room = static_cast<double>(max_points - static_cast<int>(path.centres_m.size()));
    const int pieces = std::max(1, static_cast<int>(std::min(std::ceil(len / sample_m), room)));
    for (int j = 0; j < pieces && static_cast<int>(path.centres_m.size()) < max_points; ++j) {
      const double t = static_cast<double>(j) / pieces;
      path.centres_m.push_back(corners[k] + t * (corners[k + 1] - corners[k]));
      const double share = total_m > 0.0 ? (along_m + t * len) / total_m : 1.0;
      path.yaws_rad.push_back(route_yaws ? corner_yaws[k] : yaw_rad + share * turn);
    }
    along_m += len;
  }
  if (static_cast<int>(path.centres_m.size()) < max_points) {
    path.centres_m.push_back(corners.back());
    path.yaws_rad.push_back(context.request.goal_yaw_rad);
  }
  return path;
}

PlanStopGap FirstGapAhead(const RobotModel& robot, const std::vector<ConvexRegion>& regions,
                          const std::vector<Footstep>& feet, const StopPath& path, double step_span_m,
                          const Deadline& deadline) {
  double reach = 0.0;  // how far a nominal foot lies from the body centre
  for (const LegModel& leg : robot.legs) reach = std::max(reach, leg.nominal_offset_body_m.norm());
  const std::vector<int> near = RegionsNearPath(regions, path, reach + step_span_m);
  std::optional<LegGap> best;
  for (const Footstep& foot : feet) {
    // A way round within two steps and the stance's reach of the gap's ends, for every leg alike.
    bool cut_short = false;
    const std::optional<LegGap> g =
        LegGapAhead(robot, regions, near, foot, path, step_span_m, reach + 2.0 * step_span_m, deadline, &cut_short);
    if (cut_short) {  // a part of the way unexamined: no claim about the gap ahead
      PlanStopGap unexamined;
      unexamined.examined = false;
      return unexamined;
    }
    if (!g) continue;
    const int sg = Severity(g->gap), sb = best ? Severity(best->gap) : -1;
    const bool better = !best || sg > sb || (sg == sb && sg > 0 && g->starts_at < best->starts_at) ||
                        (sg == 0 && sb == 0 && g->gap.width_m > best->gap.width_m);
    if (better) best = g;
  }
  return best ? best->gap : PlanStopGap{};
}

PlanStop DescribeStop(const PlanContext& context, const Plan& plan, const std::string& reason,
                      const Deadline& deadline) {
  PlanStop stop;
  const RobotModel& robot = context.robot;
  const size_t n = static_cast<size_t>(robot.num_legs());
  if (plan.footsteps.size() < n) return stop;
  stop.stopped = true;
  stop.reason = reason;
  const std::vector<Footstep> feet(plan.footsteps.end() - static_cast<std::ptrdiff_t>(n), plan.footsteps.end());
  std::set<int> ids;
  for (const Footstep& f : feet) {
    stop.centre_world_m += f.position_world_m / static_cast<double>(n);
    if (f.region_id >= 0) ids.insert(f.region_id);
  }
  stop.regions.assign(ids.begin(), ids.end());
  stop.yaw_rad = feet.back().yaw_rad;
  const PlannerOptions& options = context.options;
  const double sample_m = std::max(kMinSampleStepM, options.stop_report_step_l_bnd * robot.l_bnd_m);
  const StopPath path =
      PathAhead(context, stop.centre_world_m.head<2>(), stop.yaw_rad, sample_m, options.stop_report_max_samples);
  stop.gap = FirstGapAhead(robot, context.usable, feet, path, AxisStepSpan(robot), deadline);
  return stop;
}

std::string StopText(const RobotModel& robot, const PlanStop& stop) {
  std::ostringstream text;
  text.precision(3);
  text << "it stands at " << Xy(stop.centre_world_m.head<2>()) << ", yaw " << stop.yaw_rad << ", on region"
       << (stop.regions.size() == 1 ? "" : "s");
  for (size_t k = 0; k < stop.regions.size(); ++k) text << (k == 0 ? " " : ", ") << stop.regions[k];
  const PlanStopGap& g = stop.gap;
  if (!g.examined) {
    text << "; the way ahead was not examined (out of time)";
    return text.str();
  }
  if (!g.found) {
    text << "; every leg's nominal path ahead stays on regions";
    return text.str();
  }
  const std::string leg = "leg " + std::to_string(g.leg) + " ('" + robot.legs[static_cast<size_t>(g.leg)].name + "')";
  if (g.to_region < 0 && g.blocks) {
    text << "; ahead, " << leg << " leaves region " << g.from_region << " near " << Xy(g.from_m)
         << " and its nominal path meets no region on the rest of the way (to " << Xy(g.to_m) << ")";
  } else if (g.blocks) {
    text << "; ahead, " << leg << " must cross a gap in the regions from region " << g.from_region << " near "
         << Xy(g.from_m) << " to region " << g.to_region << " near " << Xy(g.to_m) << ": " << g.width_m
         << " m on an axis";
    if (g.width_m > g.step_span_m) {
      text << ", more than one step spans (" << AxisStepSpanName(robot) << " = " << g.step_span_m << " m)";
    } else {
      text << ", within a step (" << g.step_span_m << " m), but a " << g.rise_m << " m rise, more than dz_max ("
           << robot.dz_max_m << " m)";
    }
    if (g.detour_region >= 0) {
      text << "; one foot could go round it only through region " << g.detour_region << " near " << Xy(g.detour_m);
    } else {
      text << ", and no chain of steps through the regions near it goes round";
    }
  } else {
    text << "; the widest gap ahead, on " << leg << "'s path from region " << g.from_region << " near "
         << Xy(g.from_m) << " to " << (g.to_region < 0 ? "its end" : "region " + std::to_string(g.to_region))
         << " near " << Xy(g.to_m) << ", is " << g.width_m << " m on an axis, within one step (" << g.step_span_m
         << " m)";
  }
  return text.str();
}

}  // namespace mfp
