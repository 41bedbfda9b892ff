#include "tools/plan_svg.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace mfp {
namespace {

const char* kLegColours[] = {"#e6194b", "#3cb44b", "#4363d8", "#f58231", "#911eb4",
                             "#42d4f4", "#f032e6", "#bfef45", "#469990", "#9a6324"};

std::string LegColour(int leg) { return kLegColours[leg % 10]; }

// Grey level for a height between lo and hi (higher is darker).
std::string HeightShade(double z, double lo, double hi) {
  const double t = hi > lo ? (z - lo) / (hi - lo) : 0.0;
  const int v = static_cast<int>(235 - 110 * t);
  std::ostringstream out;
  out << "rgb(" << v << "," << v << "," << std::min(255, v + 10) << ")";
  return out.str();
}

}  // namespace

std::string PlanToSvg(const Plan& plan, const RobotModel& robot,
                      const std::vector<ConvexRegion>& regions, const SvgGoal& goal,
                      const std::string& title) {
  // World bounds of everything drawn.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = Eigen::Vector3d::Constant(-1e9);
  for (const ConvexRegion& r : regions)
    for (const Eigen::Vector3d& v : r.vertices_world_m) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
  for (const Footstep& f : plan.footsteps) {
    lo = lo.cwiseMin(f.position_world_m);
    hi = hi.cwiseMax(f.position_world_m);
  }
  lo.x() = std::min(lo.x(), goal.x_m);
  lo.y() = std::min(lo.y(), goal.y_m);
  hi.x() = std::max(hi.x(), goal.x_m);
  hi.y() = std::max(hi.y(), goal.y_m);
  if (lo.x() > hi.x()) lo = hi = Eigen::Vector3d::Zero();
  const double margin = 0.1;
  lo.head<2>() -= Eigen::Vector2d::Constant(margin);
  hi.head<2>() += Eigen::Vector2d::Constant(margin);
  const double width_px = 900.0;
  const double scale = width_px / std::max(hi.x() - lo.x(), 1e-3);  // px per metre
  const double top_h = (hi.y() - lo.y()) * scale;
  const double profile_h = 180.0;
  const double header = 30.0;
  const double zlo = lo.z() - 0.05, zhi = hi.z() + 0.05;
  const double zscale = (profile_h - 30.0) / std::max(zhi - zlo, 1e-3);
  auto X = [&](double x) { return (x - lo.x()) * scale; };
  auto Y = [&](double y) { return header + (hi.y() - y) * scale; };  // y up
  auto Zp = [&](double z) { return header + top_h + profile_h - 10.0 - (z - zlo) * zscale; };

  std::ostringstream s;
  s << std::fixed << std::setprecision(1);
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width_px << "\" height=\""
    << header + top_h + profile_h << "\" font-family=\"sans-serif\">\n";
  s << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  s << "<text x=\"8\" y=\"20\" font-size=\"14\">" << title << " — " << ToString(plan.status)
    << (plan.reaches_goal ? ", reaches goal" : ", goal NOT reached") << ", "
    << std::max<int>(0, static_cast<int>(plan.footsteps.size()) - robot.num_legs()) << " steps, "
    << std::setprecision(3) << plan.solve_time_s << " s</text>\n" << std::setprecision(1);
  // Regions, shaded by height, with ids.
  for (const ConvexRegion& r : regions) {
    double zmean = 0.0;
    s << "<polygon points=\"";
    for (const Eigen::Vector3d& v : r.vertices_world_m) {
      s << X(v.x()) << "," << Y(v.y()) << " ";
      zmean += v.z() / r.vertices_world_m.size();
    }
    s << "\" fill=\"" << HeightShade(zmean, zlo, zhi) << "\" stroke=\"#555\" stroke-width=\"1\"/>\n";
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& v : r.vertices_world_m) c += v / r.vertices_world_m.size();
    s << "<text x=\"" << X(c.x()) << "\" y=\"" << Y(c.y()) << "\" font-size=\"9\" fill=\"#777\">r"
      << r.id << "</text>\n";
  }
  // Each leg's path, then the footsteps.
  const int n = robot.num_legs();
  for (int leg = 0; leg < n; ++leg) {
    s << "<polyline fill=\"none\" stroke=\"" << LegColour(leg) << "\" stroke-opacity=\"0.5\" points=\"";
    for (const Footstep& f : plan.footsteps)
      if (f.leg == leg) s << X(f.position_world_m.x()) << "," << Y(f.position_world_m.y()) << " ";
    s << "\"/>\n";
  }
  for (const Footstep& f : plan.footsteps) {
    const bool start = f.index < n;
    s << "<circle cx=\"" << X(f.position_world_m.x()) << "\" cy=\"" << Y(f.position_world_m.y())
      << "\" r=\"" << (start ? 6 : 4) << "\" fill=\"" << (start ? "white" : LegColour(f.leg))
      << "\" stroke=\"" << LegColour(f.leg) << "\" stroke-width=\"2\"/>\n";
    if (!start) {
      s << "<text x=\"" << X(f.position_world_m.x()) + 5 << "\" y=\"" << Y(f.position_world_m.y()) - 4
        << "\" font-size=\"8\">" << f.index << "</text>\n";
    }
  }
  // Goal: the goal stance as hollow squares and the body heading.
  for (int leg = 0; leg < n; ++leg) {
    const Eigen::Vector2d g = NominalFootXY(robot, leg, goal.x_m, goal.y_m, goal.yaw_rad);
    const double gx = g.x(), gy = g.y();
    s << "<rect x=\"" << X(gx) - 5 << "\" y=\"" << Y(gy) - 5 << "\" width=\"10\" height=\"10\" fill=\"none\" stroke=\""
      << LegColour(leg) << "\" stroke-dasharray=\"2,2\"/>\n";
  }
  s << "<line x1=\"" << X(goal.x_m) << "\" y1=\"" << Y(goal.y_m) << "\" x2=\""
    << X(goal.x_m + 0.15 * std::cos(goal.yaw_rad)) << "\" y2=\"" << Y(goal.y_m + 0.15 * std::sin(goal.yaw_rad))
    << "\" stroke=\"black\" stroke-width=\"2\"/>\n";
  s << "<text x=\"" << X(goal.x_m) + 6 << "\" y=\"" << Y(goal.y_m) + 14 << "\" font-size=\"11\">goal</text>\n";
  if (!plan.footsteps.empty()) {
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (int i = 0; i < std::min<int>(n, plan.footsteps.size()); ++i) c += plan.footsteps[i].position_world_m.head<2>() / n;
    s << "<text x=\"" << X(c.x()) + 6 << "\" y=\"" << Y(c.y()) + 14 << "\" font-size=\"11\">start</text>\n";
  }
  // Side profile: height against x.
  const double base = header + top_h;
  s << "<line x1=\"0\" y1=\"" << base + 5 << "\" x2=\"" << width_px << "\" y2=\"" << base + 5 << "\" stroke=\"#ccc\"/>\n";
  s << "<text x=\"8\" y=\"" << base + 20 << "\" font-size=\"11\">side profile (height vs x)</text>\n";
  for (const ConvexRegion& r : regions) {
    double xmin = 1e9, xmax = -1e9, zsum = 0;
    for (const Eigen::Vector3d& v : r.vertices_world_m) {
      xmin = std::min(xmin, v.x());
      xmax = std::max(xmax, v.x());
      zsum += v.z();
    }
    const double z = zsum / r.vertices_world_m.size();
    s << "<line x1=\"" << X(xmin) << "\" y1=\"" << Zp(z) << "\" x2=\"" << X(xmax) << "\" y2=\"" << Zp(z)
      << "\" stroke=\"#999\" stroke-width=\"3\"/>\n";
  }
  for (const Footstep& f : plan.footsteps) {
    s << "<circle cx=\"" << X(f.position_world_m.x()) << "\" cy=\"" << Zp(f.position_world_m.z())
      << "\" r=\"3\" fill=\"" << LegColour(f.leg) << "\"/>\n";
  }
  // Legend.
  for (int leg = 0; leg < n; ++leg) {
    s << "<circle cx=\"" << width_px - 150 << "\" cy=\"" << 40 + 14 * leg << "\" r=\"4\" fill=\"" << LegColour(leg)
      << "\"/><text x=\"" << width_px - 140 << "\" y=\"" << 44 + 14 * leg << "\" font-size=\"10\">"
      << robot.legs[leg].name << "</text>\n";
  }
  s << "</svg>\n";
  return s.str();
}

}  // namespace mfp
