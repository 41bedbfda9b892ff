// mfp-robot FILE.urdf|FILE.yaml [--json FILE] [--svg FILE] [--step-extents]: prints the
// robot model the planner would use (legs, hips, nominal offsets, d_lim, l_bnd, dz_max,
// gait) with where each value came from; --json writes the plan JSON's robot object (`-` =
// stdout), --svg draws the body, hips, nominal stance and each foot's reachable footprint
// with its inscribed square; --step-extents prints how far each foot truly reaches forward
// and back of its nominal foot when the body may be turned, and the longest forward step
// the footprints allow. Exit 0 on success, 2 on bad input.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "base/check.h"
#include "base/format.h"
#include "io/cli_parse.h"
#include "io/robot_json.h"
#include "io/robot_loader.h"
#include "io/text_output.h"
#include "planner/robot/reach_polygon.h"

namespace {

using mfp::Fixed;

// Length of the footprint's chord through p along the unit direction u: how far the foot
// moves along u, body still, from one end of its reach to the other [m].
double FootprintChord(const mfp::FootprintGrid& grid, const Eigen::Vector2d& p, const Eigen::Vector2d& u) {
  const double step = 0.1 * grid.cell_m();
  double length = 0.0;
  for (const double sign : {1.0, -1.0}) {
    double t = 0.0;
    while (grid.OccupiedAt(p + sign * (t + step) * u)) t += step;
    length += t;
  }
  return length;
}

// How far the foot reaches from p along the body-frame unit direction u while the body may
// be turned by any yaw within +-half_spread_rad of u's heading: the largest t such that
// every point s u, 0 <= s <= t, turned back by each such yaw (1-degree samples and both
// ends) lies in the footprint [m]. half_spread_rad = 0: the plain ray.
double ReachAlongTurned(const mfp::FootprintGrid& grid, const Eigen::Vector2d& p, const Eigen::Vector2d& u,
                        double half_spread_rad) {
  const double step = 0.1 * grid.cell_m();
  const int samples = static_cast<int>(std::ceil(half_spread_rad / (M_PI / 180.0)));
  auto inside = [&](double t) {
    for (int k = -samples; k <= samples; ++k) {
      const double yaw = samples == 0 ? 0.0 : half_spread_rad * k / samples;
      const Eigen::Vector2d turned(std::cos(yaw) * u.x() + std::sin(yaw) * u.y(),
                                   -std::sin(yaw) * u.x() + std::cos(yaw) * u.y());
      if (!grid.OccupiedAt(p + t * turned)) return false;
    }
    return true;
  };
  double t = 0.0;
  while (inside(t + step)) t += step;
  return t;
}

// The footprint's longest run of occupied cells along body x, over its rows [m]: how far a
// foot moves forward, body still, from the back of its reach to the front on the best line.
double LongestRunAlongX(const mfp::FootprintGrid& grid) {
  int best = 0;
  for (int iy = 0; iy < grid.ny(); ++iy) {
    int run = 0;
    for (int ix = 0; ix < grid.nx(); ++ix) {
      run = grid.Occupied(ix, iy) ? run + 1 : 0;
      best = std::max(best, run);
    }
  }
  return best * grid.cell_m();
}

// How far a foot's footprint polygon (robot_model.h ReachFace) reaches from the nominal
// foot along the body-frame unit direction u at every yaw within +-half_spread_rad: the
// smallest over 1-degree samples of the ray's distance to the polygon's boundary [m].
double PolygonReachTurned(const std::vector<mfp::ReachFace>& faces, const Eigen::Vector2d& u, double half_spread_rad) {
  const int samples = static_cast<int>(std::ceil(half_spread_rad / (M_PI / 180.0)));
  double reach = 1e300;
  for (int k = -samples; k <= samples; ++k) {
    const double yaw = samples == 0 ? 0.0 : half_spread_rad * k / samples;
    const Eigen::Vector2d d(std::cos(yaw) * u.x() + std::sin(yaw) * u.y(), -std::sin(yaw) * u.x() + std::cos(yaw) * u.y());
    for (const mfp::ReachFace& f : faces) {
      const double along = f.normal.dot(d);
      if (along > 1e-12) reach = std::min(reach, f.offset_m / along);
    }
  }
  return reach;
}

// For the footprint shape: the polygons' forward step along x (the reach forward plus the
// reference behind), smallest over legs, with the body turned by up to +-0, +-pi/16, +-pi/8.
void PrintPolygonSteps(const mfp::RobotModel& robot, std::ostream& out) {
  if (robot.reach_shape != mfp::ReachShape::kFootprint) return;
  out << "  footprint polygons' step along x (fwd + back), body turned 0 / pi/16 / pi/8:";
  for (const double spread : {0.0, M_PI / 16, M_PI / 8}) {
    double step = 1e300;
    for (const mfp::LegModel& leg : robot.legs) {
      step = std::min(step, PolygonReachTurned(leg.footprint_faces, Eigen::Vector2d::UnitX(), spread) +
                                PolygonReachTurned(leg.footprint_faces, -Eigen::Vector2d::UnitX(), spread));
    }
    out << " " << Fixed(step);
  }
  out << "\n";
}

// Per leg, the footprint's reach forward (+x) and back (-x) of the nominal foot when the
// body may turn by +-0, +-pi/16 (one pi/8 yaw segment) and +-pi/8 (two), and its longest run
// along x; then the longest forward step of one foot (smallest over legs, every leg must
// cross) under each model.
void PrintStepExtents(const mfp::RobotModel& robot, const mfp::RobotDerivation& derivation, std::ostream& out) {
  if (derivation.legs.size() != robot.legs.size()) {
    out << "step extents: no footprints (the robot is not derived from a URDF)\n";
    return;
  }
  const double spreads[3] = {0.0, M_PI / 16, M_PI / 8};
  out << "step extents along body x [m] (fwd / back of the nominal foot, body turned by up to +-0, +-pi/16, "
         "+-pi/8; run: the longest run along x)\n";
  double fwd[3], sum[3], run = 1e9, second_run = 1e9;
  for (int s = 0; s < 3; ++s) fwd[s] = sum[s] = 1e9;
  for (int k = 0; k < robot.num_legs(); ++k) {
    const mfp::LegDerivation& d = derivation.legs[k];
    const Eigen::Vector2d nominal = d.nominal_foot_body_m.head<2>();
    out << "  " << k << " " << robot.legs[k].name << ":";
    for (int s = 0; s < 3; ++s) {
      const double f = ReachAlongTurned(d.footprint, nominal, Eigen::Vector2d::UnitX(), spreads[s]);
      const double b = ReachAlongTurned(d.footprint, nominal, -Eigen::Vector2d::UnitX(), spreads[s]);
      out << "  " << Fixed(f) << " / " << Fixed(b);
      fwd[s] = std::min(fwd[s], f);
      sum[s] = std::min(sum[s], f + b);
    }
    const double r = LongestRunAlongX(d.footprint);
    out << "  run " << Fixed(r) << "\n";
    if (r < run) {
      second_run = run;
      run = r;
    } else {
      second_run = std::min(second_run, r);
    }
  }
  const double l = robot.l_bnd_m;
  out << "longest forward step of every leg [m]:\n";
  out << "  this model (" << mfp::ReachShapeName(robot.reach_shape) << ", " << mfp::AxisStepSpanName(robot)
      << "): " << Fixed(mfp::AxisStepSpan(robot)) << "\n";
  out << "  footprint reach + l_bnd, body turned 0 / pi/16 / pi/8: " << Fixed(fwd[0] + l) << " / " << Fixed(fwd[1] + l)
      << " / " << Fixed(fwd[2] + l) << "\n";
  out << "  footprint reach and footprint reference (fwd + back):   " << Fixed(sum[0]) << " / " << Fixed(sum[1])
      << " / " << Fixed(sum[2]) << "\n";
  out << "  body still, the longest run along x:                    " << Fixed(run) << "\n";
  out << "  body moved by the other feet's longest run (no balance): " << Fixed(run + second_run) << "\n";
  PrintPolygonSteps(robot, out);
}

void PrintTable(const mfp::RobotModel& robot, const mfp::RobotDerivation& derivation,
                std::ostream& out) {
  out << "robot " << robot.name << ": " << robot.num_legs() << " legs\n";
  out << "  #  name              hip x     hip y     hip z     o_x       o_y       L_leg     "
         "phi[rad]";
  const bool derived = derivation.legs.size() == robot.legs.size();
  if (derived) out << "  square    dz_up     dz_down   disk      chord_x   chord_y";
  out << "\n";
  for (int k = 0; k < robot.num_legs(); ++k) {
    const mfp::LegModel& leg = robot.legs[k];
    const Eigen::Vector2d o = leg.nominal_offset_body_m;
    char line[256];
    std::snprintf(line, sizeof(line), "  %-2d %-16s %9.4f %9.4f %9.4f %9.4f %9.4f %9.4f %9.4f",
                  k, leg.name.c_str(), leg.hip_body_m.x(), leg.hip_body_m.y(),
                  leg.hip_body_m.z(), o.x(), o.y(), o.norm(), std::atan2(o.y(), o.x()));
    out << line;
    if (derived) {
      const mfp::LegDerivation& d = derivation.legs[k];
      const Eigen::Vector2d nominal = d.nominal_foot_body_m.head<2>();
      std::snprintf(line, sizeof(line), " %9.4f %9.4f %9.4f %9.4f %9.4f %9.4f", d.square_half_side_m, d.dz_up_m,
                    d.dz_down_m, d.disk_radius_m, FootprintChord(d.footprint, nominal, Eigen::Vector2d::UnitX()),
                    FootprintChord(d.footprint, nominal, Eigen::Vector2d::UnitY()));
      out << line;
    }
    out << "\n";
  }
  std::string gait;
  for (int g : robot.gait) gait += (gait.empty() ? "" : " -> ") + robot.legs[g].name;
  out << "  gait:           " << gait << "\n";
  out << "  stance height:  " << Fixed(robot.stance_height_m) << " m\n";
  out << "  d_lim:          " << Fixed(robot.d_lim_m) << " m (reach " << mfp::ReachShapeName(robot.reach_shape)
      << ")\n";
  out << "  l_bnd:          " << Fixed(robot.l_bnd_m) << " m\n";
  out << "  dz_max:         " << Fixed(robot.dz_max_m) << " m\n";
  out << "  max yaw change: " << Fixed(robot.max_yaw_change_rad) << " rad\n";
  out << "  foot radius:    " << Fixed(robot.foot_radius_m) << " m\n";
  out << "  max slope:      " << Fixed(robot.max_slope_rad) << " rad\n";
  const mfp::BodyExtent& body = robot.body;
  if (body.known()) {
    out << "  body box:       " << Fixed(body.length_m()) << " x " << Fixed(body.width_m()) << " m (x ["
        << Fixed(body.min_m.x()) << ", " << Fixed(body.max_m.x()) << "], y [" << Fixed(body.min_m.y()) << ", "
        << Fixed(body.max_m.y()) << "] about the centre of contacts), " << Fixed(body.bottom_m) << " to "
        << Fixed(body.top_m) << " m above the feet\n";
  } else {
    out << "  body box:       unknown (no body clearance)\n";
  }
  out << "where each value comes from:\n";
  for (const std::string& line : robot.provenance) out << "  " << line << "\n";
}

// SVG in body coordinates, x forward drawn to the right, y left drawn up.
std::string RobotSvg(const mfp::RobotModel& robot, const mfp::RobotDerivation& derivation) {
  Eigen::Vector2d lo(-0.05, -0.05), hi(0.05, 0.05);
  const bool derived = derivation.legs.size() == robot.legs.size();
  const Eigen::Vector2d mean_feet = [&] {
    Eigen::Vector2d m = Eigen::Vector2d::Zero();
    if (!derived) return m;
    for (const auto& d : derivation.legs) m += d.nominal_foot_body_m.head<2>() / robot.num_legs();
    return m;
  }();
  auto extend = [&](const Eigen::Vector2d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  };
  for (int k = 0; k < robot.num_legs(); ++k) {
    extend(robot.legs[k].hip_body_m.head<2>());
    extend(robot.legs[k].nominal_offset_body_m + mean_feet);
    if (!derived) continue;
    const mfp::FootprintGrid& g = derivation.legs[k].footprint;
    for (int iy = 0; iy < g.ny(); ++iy) {
      for (int ix = 0; ix < g.nx(); ++ix) {
        if (g.Occupied(ix, iy)) extend(g.CellCentre(ix, iy));
      }
    }
  }
  const double margin = 0.05 * (hi - lo).maxCoeff() + 0.01;
  lo -= Eigen::Vector2d::Constant(margin);
  hi += Eigen::Vector2d::Constant(margin);
  const double scale = 800.0 / (hi - lo).maxCoeff();  // pixels per metre
  auto X = [&](double x) { return Fixed((x - lo.x()) * scale, 1); };
  auto Y = [&](double y) { return Fixed((hi.y() - y) * scale, 1); };
  std::ostringstream svg;
  const double width = (hi.x() - lo.x()) * scale, height = (hi.y() - lo.y()) * scale;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << Fixed(width, 0) << "\" height=\""
      << Fixed(height, 0) << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg << "<text x=\"8\" y=\"16\">" << robot.name << ": d_lim " << Fixed(robot.d_lim_m, 3)
      << " m, l_bnd " << Fixed(robot.l_bnd_m, 3) << " m, dz_max " << Fixed(robot.dz_max_m, 3)
      << " m, stance " << Fixed(robot.stance_height_m, 3) << " m</text>\n";
  const char* colours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                           "#9467bd", "#8c564b", "#e377c2", "#17becf"};
  // Footprints: occupied cells merged into runs per row.
  for (int k = 0; derived && k < robot.num_legs(); ++k) {
    const mfp::FootprintGrid& g = derivation.legs[k].footprint;
    const double c = g.cell_m();
    svg << "<g fill=\"" << colours[k % 8] << "\" fill-opacity=\"0.18\">\n";
    for (int iy = 0; iy < g.ny(); ++iy) {
      for (int ix = 0; ix < g.nx();) {
        if (!g.Occupied(ix, iy)) {
          ++ix;
          continue;
        }
        int end = ix;
        while (end < g.nx() && g.Occupied(end, iy)) ++end;
        const Eigen::Vector2d a = g.CellCentre(ix, iy) - Eigen::Vector2d::Constant(0.5 * c);
        svg << "<rect x=\"" << X(a.x()) << "\" y=\"" << Y(a.y() + c) << "\" width=\""
            << Fixed((end - ix) * c * scale, 1) << "\" height=\"" << Fixed(c * scale, 1)
            << "\"/>\n";
        ix = end;
      }
    }
    svg << "</g>\n";
  }
  // Body outline: polygon through the hips in angular order.
  std::vector<Eigen::Vector2d> hips;
  for (const auto& leg : robot.legs) hips.push_back(leg.hip_body_m.head<2>());
  std::sort(hips.begin(), hips.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return std::atan2(a.y(), a.x()) < std::atan2(b.y(), b.x());
  });
  svg << "<polygon fill=\"#dddddd\" stroke=\"black\" points=\"";
  for (const auto& h : hips) svg << X(h.x()) << "," << Y(h.y()) << " ";
  svg << "\"/>\n";
  svg << "<line x1=\"" << X(0) << "\" y1=\"" << Y(0) << "\" x2=\"" << X(0.3 * (hi.x() - 0))
      << "\" y2=\"" << Y(0) << "\" stroke=\"black\" stroke-dasharray=\"4 3\"/>\n";
  for (int k = 0; k < robot.num_legs(); ++k) {
    const auto& leg = robot.legs[k];
    const Eigen::Vector2d foot = leg.nominal_offset_body_m + mean_feet;
    const Eigen::Vector2d hip = leg.hip_body_m.head<2>();
    const char* colour = colours[k % 8];
    svg << "<line x1=\"" << X(hip.x()) << "\" y1=\"" << Y(hip.y()) << "\" x2=\"" << X(foot.x())
        << "\" y2=\"" << Y(foot.y()) << "\" stroke=\"" << colour << "\"/>\n";
    svg << "<circle cx=\"" << X(hip.x()) << "\" cy=\"" << Y(hip.y())
        << "\" r=\"4\" fill=\"black\"/>\n";
    const double d = robot.d_lim_m, l = robot.l_bnd_m;
    svg << "<rect x=\"" << X(foot.x() - d) << "\" y=\"" << Y(foot.y() + d) << "\" width=\""
        << Fixed(2 * d * scale, 1) << "\" height=\"" << Fixed(2 * d * scale, 1)
        << "\" fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"2\"/>\n";
    svg << "<rect x=\"" << X(foot.x() - l) << "\" y=\"" << Y(foot.y() + l) << "\" width=\""
        << Fixed(2 * l * scale, 1) << "\" height=\"" << Fixed(2 * l * scale, 1)
        << "\" fill=\"none\" stroke=\"" << colour << "\" stroke-dasharray=\"5 3\"/>\n";
    svg << "<circle cx=\"" << X(foot.x()) << "\" cy=\"" << Y(foot.y()) << "\" r=\"5\" fill=\""
        << colour << "\"/>\n";
    svg << "<text x=\"" << X(foot.x()) << "\" y=\"" << Y(foot.y()) << "\" dx=\"7\" dy=\"-7\">"
        << k << " " << leg.name << "</text>\n";
  }
  svg << "<text x=\"8\" y=\"" << Fixed(height - 8, 0)
      << "\">shaded: reachable footprint at stance height; solid square: d_lim; dashed: "
         "l_bnd; dots: nominal feet; black: hips</text>\n";
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Prints the robot model mfp derives from a URDF or robot YAML."};
  std::string robot_file, json_file, svg_file;
  bool step_extents = false;
  app.add_option("FILE", robot_file, "robot URDF or YAML")->required();
  app.add_option("--json", json_file, "write the robot JSON here ('-' = stdout)");
  app.add_option("--svg", svg_file, "draw body, hips, nominal stance and footprints here");
  app.add_flag("--step-extents", step_extents,
               "print each foot's reach forward and back of its nominal foot and the longest forward step");
  MFP_CLI_PARSE(app, argc, argv);
  try {
    mfp::RobotDerivation derivation;
    const mfp::RobotModel robot = mfp::LoadRobot(robot_file, &derivation);
    if (json_file != "-") PrintTable(robot, derivation, std::cout);
    if (step_extents) PrintStepExtents(robot, derivation, std::cout);
    if (!json_file.empty()) mfp::WriteTextOutput(json_file, mfp::RobotToJson(robot).dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
    if (!svg_file.empty()) mfp::WriteTextOutput(svg_file, RobotSvg(robot, derivation));
  } catch (const mfp::InputError& e) {
    std::cerr << "mfp-robot: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
