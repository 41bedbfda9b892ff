#include "planner/robot/robot_derivation.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <numeric>
#include <sstream>

#include "planner/base/check.h"
#include "planner/base/format.h"
#include "planner/robot/inscribed_square.h"

namespace mfp {
namespace {

// Joint-space grid samples of one leg: joint positions and foot points, column-wise.
struct LegSamples {
  Eigen::MatrixXd q;  // num_dof x N
  Eigen::MatrixXd p;  // 3 x N, body frame
};

LegSamples SampleJointSpace(const LegChain& leg, int budget) {
  const int dof = leg.num_dof();
  MFP_CHECK(dof > 0);
  const int per_joint = std::max(2, static_cast<int>(std::floor(std::pow(budget, 1.0 / dof))));
  long total = 1;
  for (int i = 0; i < dof; ++i) total *= per_joint;
  const Eigen::VectorXd lower = leg.LowerLimits();
  const Eigen::VectorXd upper = leg.UpperLimits();
  LegSamples samples;
  samples.q.resize(dof, total);
  samples.p.resize(3, total);
  std::vector<int> index(dof, 0);
  for (long n = 0; n < total; ++n) {
    Eigen::VectorXd q(dof);
    for (int i = 0; i < dof; ++i) {
      q[i] = lower[i] + (upper[i] - lower[i]) * index[i] / (per_joint - 1);
    }
    samples.q.col(n) = q;
    samples.p.col(n) = FootPosition(leg, q);
    for (int i = 0; i < dof && ++index[i] == per_joint; ++i) index[i] = 0;
  }
  return samples;
}

// Reachable footprint at height z: seeds from samples near that height, each seed cell
// confirmed by IK at its centre, then flood fill to neighbouring cells by IK from the
// neighbour's solution. Returns the grid and the joint positions of each occupied cell.
struct Footprint {
  FootprintGrid grid;
  std::vector<Eigen::VectorXd> q;  // per cell (row-major), empty when unoccupied
};

Footprint ReachableFootprint(const LegChain& leg, const LegSamples& samples,
                             const Eigen::Vector2d& xy_min, const Eigen::Vector2d& xy_max,
                             double cell_m, double z_m, double ik_tolerance_m) {
  Footprint fp;
  fp.grid = FootprintGrid(xy_min, xy_max, cell_m);
  const int nx = fp.grid.nx();
  fp.q.assign(static_cast<size_t>(nx) * fp.grid.ny(), Eigen::VectorXd());
  std::vector<std::uint8_t> tried(fp.q.size(), 0);
  std::deque<std::pair<int, int>> queue;
  auto try_cell = [&](int ix, int iy, const Eigen::VectorXd& q_start) {
    const size_t k = static_cast<size_t>(iy) * nx + ix;
    if (fp.q[k].size() != 0) return;
    const Eigen::Vector2d c = fp.grid.CellCentre(ix, iy);
    const IkResult ik = SolveFootIk(leg, Eigen::Vector3d(c.x(), c.y(), z_m), q_start,
                                    ik_tolerance_m, 60);
    if (!ik.converged) return;
    fp.q[k] = ik.q;
    fp.grid.Set(ix, iy, true);
    queue.emplace_back(ix, iy);
  };
  // Seeds: one sample per cell, the one nearest the height.
  const double band = cell_m;
  std::vector<double> best_dz(fp.q.size(), std::numeric_limits<double>::infinity());
  std::vector<long> best_sample(fp.q.size(), -1);
  for (long n = 0; n < samples.p.cols(); ++n) {
    const double dz = std::abs(samples.p(2, n) - z_m);
    if (dz > band) continue;
    int ix = 0, iy = 0;
    if (!fp.grid.CellOf(samples.p.col(n).head<2>(), &ix, &iy)) continue;
    const size_t k = static_cast<size_t>(iy) * nx + ix;
    if (dz < best_dz[k]) {
      best_dz[k] = dz;
      best_sample[k] = n;
    }
  }
  for (int iy = 0; iy < fp.grid.ny(); ++iy) {
    for (int ix = 0; ix < nx; ++ix) {
      const long n = best_sample[static_cast<size_t>(iy) * nx + ix];
      if (n >= 0) try_cell(ix, iy, samples.q.col(n));
    }
  }
  const int kSteps[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  while (!queue.empty()) {
    const auto [ix, iy] = queue.front();
    queue.pop_front();
    const Eigen::VectorXd q_here = fp.q[static_cast<size_t>(iy) * nx + ix];
    for (const auto& step : kSteps) {
      const int jx = ix + step[0], jy = iy + step[1];
      // The outer ring stays empty so that every square is bounded by the grid.
      if (jx < 1 || jy < 1 || jx >= nx - 1 || jy >= fp.grid.ny() - 1) continue;
      const size_t k = static_cast<size_t>(jy) * nx + jx;
      if (fp.q[k].size() != 0 || tried[k] >= 4) continue;
      ++tried[k];
      try_cell(jx, jy, q_here);
    }
  }
  fp.grid.UpdateBoundary();
  return fp;
}

// Largest vertical travel from the nominal foot, one direction (+1 up, -1 down), by
// continuation IK in steps of step_m, up to limit_m.
double VerticalTravel(const LegChain& leg, const Eigen::Vector3d& start,
                      const Eigen::VectorXd& q_start, double direction, double step_m,
                      double limit_m, double tolerance_m) {
  Eigen::VectorXd q = q_start;
  double reached = 0.0;
  for (double t = step_m; t <= limit_m + 1e-12; t += step_m) {
    const Eigen::Vector3d target = start + Eigen::Vector3d(0, 0, direction * t);
    const IkResult ik = SolveFootIk(leg, target, q, tolerance_m, 80);
    if (!ik.converged) break;
    q = ik.q;
    reached = t;
  }
  return reached;
}

// The body's extent (robot_model.h): the base link's box from the URDF, widened in plan
// view to the legs' movable joint origins (hips, knees) at the nominal stance; heights
// above the feet's plane from the base box. Unknown when the URDF gives no base box.
BodyExtent DeriveBodyExtent(const RobotDescription& robot, const std::vector<LegDerivation>& legs,
                            const Eigen::Vector2d& centre_body_m, double feet_plane_z_body_m,
                            std::string* provenance) {
  BodyExtent body;
  const Eigen::AlignedBox3d& base = robot.body_box_m;
  if (base.isEmpty()) {
    *provenance = "body box: unknown (the body link '" + robot.root_link + "' has no collision, visual or "
                  "inertial box); give body_box in the robot YAML for body clearance";
    return body;
  }
  Eigen::AlignedBox2d plan(base.min().head<2>(), base.max().head<2>());
  for (size_t k = 0; k < legs.size(); ++k) {
    for (const Eigen::Vector3d& joint : MovableJointOrigins(robot.legs[k], legs[k].nominal_q)) {
      plan.extend(joint.head<2>());
    }
  }
  body.min_m = plan.min() - centre_body_m;
  body.max_m = plan.max() - centre_body_m;
  body.bottom_m = std::max(0.0, base.min().z() - feet_plane_z_body_m);
  body.top_m = std::max(body.bottom_m, base.max().z() - feet_plane_z_body_m);
  *provenance = "body box = x [" + Fixed(body.min_m.x()) + ", " + Fixed(body.max_m.x()) + "] m, y [" +
                Fixed(body.min_m.y()) + ", " + Fixed(body.max_m.y()) + "] m about the centre of contacts, " +
                Fixed(body.bottom_m) + " to " + Fixed(body.top_m) + " m above the feet: derived, " +
                robot.body_box_source + ", widened in plan view to the legs' hips and knees at the nominal stance";
  return body;
}

}  // namespace

std::vector<int> WaveGait(const std::vector<LegModel>& legs) {
  std::vector<double> angle(legs.size());
  for (size_t k = 0; k < legs.size(); ++k) {
    const Eigen::Vector2d o = legs[k].nominal_offset_body_m;
    double a = std::atan2(o.y(), o.x());
    if (a < -M_PI + 1e-6) a = M_PI;  // a leg straight behind is at +pi, not -pi
    angle[k] = a;
  }
  std::vector<int> gait(legs.size());
  std::iota(gait.begin(), gait.end(), 0);
  std::stable_sort(gait.begin(), gait.end(),
                   [&](int a, int b) { return angle[a] > angle[b] + 1e-9; });
  return gait;
}

RobotDerivation DeriveRobot(const RobotDescription& robot, const DerivationOptions& options) {
  MFP_CHECK(!robot.legs.empty());
  const size_t n = robot.legs.size();
  const std::string& src = robot.source;
  for (const LegChain& leg : robot.legs) {
    const std::string axis = PlanarLegAxis(leg);
    if (!axis.empty()) {
      std::string joints;
      for (const JointModel& j : leg.joints) {
        if (j.movable()) joints += (joints.empty() ? "'" : ", '") + j.name + "'";
      }
      throw InputError(src + ": leg '" + leg.name + "' is planar: its joints " + joints +
                       " all turn about the axis " + axis +
                       ", so its foot has no sideways freedom; mfp's reachability square needs a foot that "
                       "moves both along and across the body (planar-legged robots are not supported)");
    }
  }
  std::vector<LegSamples> samples(n);
  std::vector<Eigen::Vector3d> hips(n);
  double widest_reach = 0.0;
  double hip_z = 0.0;
  for (size_t k = 0; k < n; ++k) {
    samples[k] = SampleJointSpace(robot.legs[k], options.samples_per_leg);
    hips[k] = HipPosition(robot.legs[k]);
    hip_z += hips[k].z() / n;
    const Eigen::Vector2d lo = samples[k].p.topRows<2>().rowwise().minCoeff();
    const Eigen::Vector2d hi = samples[k].p.topRows<2>().rowwise().maxCoeff();
    widest_reach = std::max(widest_reach, (hi - lo).maxCoeff());
  }
  // The downward reach of each leg below the mean hip height bounds the stance height.
  double common_reach = std::numeric_limits<double>::infinity();
  std::vector<double> lowest(n);
  for (size_t k = 0; k < n; ++k) {
    lowest[k] = samples[k].p.row(2).minCoeff();
    const double reach = hip_z - lowest[k];
    if (!(reach > 1e-6)) {
      std::ostringstream msg;
      msg << src << ": leg '" << robot.legs[k].name
          << "' cannot reach the ground at any stance height: its lowest foot point is at z = "
          << Fixed(lowest[k]) << " m, not below the hips (z = " << Fixed(hip_z) << " m)";
      throw InputError(msg.str());
    }
    common_reach = std::min(common_reach, reach);
  }
  MFP_CHECK(widest_reach > 0.0);

  auto leg_bounds = [&](size_t k, double cell) {
    const Eigen::Vector2d lo = samples[k].p.topRows<2>().rowwise().minCoeff();
    const Eigen::Vector2d hi = samples[k].p.topRows<2>().rowwise().maxCoeff();
    return std::make_pair(Eigen::Vector2d(lo.array() - cell), Eigen::Vector2d(hi.array() + cell));
  };
  // Smallest leg's inscribed square at height z with a coarse grid (cell-centre search).
  auto score = [&](double z, double cell) {
    double worst = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < n && worst > 0.0; ++k) {
      const auto [lo, hi] = leg_bounds(k, cell);
      const Footprint fp = ReachableFootprint(robot.legs[k], samples[k], lo, hi, cell, z,
                                              options.ik_tolerance_m);
      double best = 0.0;
      for (int iy = 0; iy < fp.grid.ny(); ++iy) {
        for (int ix = 0; ix < fp.grid.nx(); ++ix) {
          if (fp.grid.Occupied(ix, iy)) {
            best = std::max(best, fp.grid.Clearance(fp.grid.CellCentre(ix, iy)));
          }
        }
      }
      worst = std::min(worst, best);
    }
    return worst;
  };

  RobotDerivation out;
  RobotModel& model = out.model;
  model.name = robot.name;
  for (const std::string& note : robot.notes) model.provenance.push_back("urdf: " + note);
  double stance = 0.0;
  if (options.stance_height_m) {
    stance = *options.stance_height_m;
  } else {
    // Legged robots stand with the knee bent, the hips at 60-80 % of the legs' full
    // extension, so that a foot can both rise and drop: the nearest height to
    // stance_fraction of the reach where every leg still has a useful footprint (its
    // inscribed square at least half the best over the candidates). Never the crouched
    // height where the footprint alone is largest.
    const double scan_cell = widest_reach / options.scan_cells;
    std::vector<double> fractions, scores;
    double best_score = 0.0;
    for (int i = 0; i < options.stance_candidates; ++i) {
      const double frac = 0.25 + 0.70 * i / std::max(1, options.stance_candidates - 1);
      fractions.push_back(frac);
      scores.push_back(score(hip_z - frac * common_reach, scan_cell));
      best_score = std::max(best_score, scores.back());
    }
    if (best_score <= 0.0) {
      throw InputError(src + ": the legs have no common stance height: at no height between " +
                       Fixed(0.25 * common_reach) + " and " + Fixed(0.95 * common_reach) +
                       " m below the hips can every foot stand");
    }
    double chosen = -1.0;
    for (size_t i = 0; i < fractions.size(); ++i) {
      if (scores[i] < 0.5 * best_score) continue;
      if (chosen < 0 || std::abs(fractions[i] - options.stance_fraction) <
                            std::abs(chosen - options.stance_fraction) - 1e-9) {
        chosen = fractions[i];
      }
    }
    stance = chosen * common_reach;
    model.provenance.push_back(
        "stance_height = " + Fixed(stance) + " m: derived, " + Fixed(100 * chosen, 0) +
        "% of the smallest downward reach below the hips (" + Fixed(common_reach) + " m): of " +
        std::to_string(options.stance_candidates) + " heights between 25% and 95%, the nearest to " +
        Fixed(100 * options.stance_fraction, 0) + "% (knee bent, as legged robots stand) where every "
        "leg's inscribed square is at least half the best");
  }
  model.stance_height_m = stance;
  out.feet_plane_z_body_m = hip_z - stance;
  const double z_plane = out.feet_plane_z_body_m;

  const double cell = widest_reach / options.final_cells;
  std::vector<Eigen::Vector2d> feet_xy(n);
  double d_lim_raw = std::numeric_limits<double>::infinity();
  double dz_max = std::numeric_limits<double>::infinity();
  std::string dz_leg, d_leg;
  for (size_t k = 0; k < n; ++k) {
    const LegChain& chain = robot.legs[k];
    const auto [lo, hi] = leg_bounds(k, cell);
    Footprint fp =
        ReachableFootprint(chain, samples[k], lo, hi, cell, z_plane, options.ik_tolerance_m);
    if (fp.grid.CountOccupied() == 0) {
      std::ostringstream msg;
      msg << src << ": leg '" << chain.name << "' cannot reach the stance height "
          << Fixed(stance) << " m below the hips (its foot reaches down to "
          << Fixed(hip_z - lowest[k]) << " m below them)";
      throw InputError(msg.str());
    }
    const InscribedSquare square = LargestInscribedSquare(
        fp.grid, hips[k].head<2>(), options.centre_weight_per_m);
    LegDerivation leg;
    leg.hip_body_m = hips[k];
    leg.square_half_side_m = square.half_side_m;
    leg.lowest_foot_z_m = lowest[k];
    leg.nominal_foot_body_m = Eigen::Vector3d(square.centre_m.x(), square.centre_m.y(), z_plane);
    int ix = 0, iy = 0;
    MFP_CHECK(fp.grid.CellOf(square.centre_m, &ix, &iy));
    const Eigen::VectorXd q_cell = fp.q[static_cast<size_t>(iy) * fp.grid.nx() + ix];
    MFP_CHECK(q_cell.size() == chain.num_dof());
    const IkResult ik = SolveFootIk(chain, leg.nominal_foot_body_m, q_cell, options.ik_tolerance_m);
    leg.nominal_q = ik.converged ? ik.q : q_cell;
    const double step = 0.5 * cell;
    leg.dz_up_m = VerticalTravel(chain, leg.nominal_foot_body_m, leg.nominal_q, +1.0, step,
                                 stance, options.ik_tolerance_m);
    leg.dz_down_m = VerticalTravel(chain, leg.nominal_foot_body_m, leg.nominal_q, -1.0, step,
                                   hip_z - lowest[k], options.ik_tolerance_m);
    leg.footprint = std::move(fp.grid);
    feet_xy[k] = square.centre_m;
    if (square.half_side_m < d_lim_raw) {
      d_lim_raw = square.half_side_m;
      d_leg = chain.name;
    }
    const double dz = std::min(leg.dz_up_m, leg.dz_down_m);
    if (dz < dz_max) {
      dz_max = dz;
      dz_leg = chain.name;
    }
    out.legs.push_back(std::move(leg));
  }

  // A stance where a leg has no reach left is not a model to plan with: say which leg
  // and which heights would do, instead of handing on a zero limit.
  const std::string heights = Fixed(0.25 * common_reach) + " and " + Fixed(0.95 * common_reach) + " m";
  if (!(d_lim_raw - 0.5 * cell > 0.0)) {
    int dof = 0;
    for (const LegChain& leg : robot.legs) {
      if (leg.name == d_leg) dof = leg.num_dof();
    }
    throw InputError(src + ": at the stance height " + Fixed(stance) + " m leg '" + d_leg +
                     "' reaches no square wider than a footprint cell (" + Fixed(cell) + " m)" +
                     (dof < 3 ? " (with " + std::to_string(dof) +
                                    " movable joints its foot reaches a curve, not an area, at one height; "
                                    "mfp needs legs of at least 3)"
                              : "; choose stance_height between " + heights + " in a robot YAML"));
  }
  if (!(dz_max > 0.0)) {
    throw InputError(src + ": at the stance height " + Fixed(stance) + " m leg '" + dz_leg +
                     "' cannot move its foot up or down from its nominal point (the edge of its vertical "
                     "reach); choose stance_height between " + heights + " in a robot YAML");
  }
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& f : feet_xy) mean += f / static_cast<double>(n);
  double foot_radius = 0.0;
  for (size_t k = 0; k < n; ++k) {
    LegModel leg;
    leg.name = robot.legs[k].name;
    leg.nominal_offset_body_m = feet_xy[k] - mean;
    leg.hip_body_m = hips[k];
    foot_radius = std::max(foot_radius, robot.legs[k].foot_sphere_radius_m);
    model.legs.push_back(leg);
    const Eigen::Vector2d o = leg.nominal_offset_body_m;
    std::ostringstream line;
    line << "legs[" << k << "] '" << leg.name << "' nominal offset (" << Fixed(o.x()) << ", "
         << Fixed(o.y()) << ") m, L_leg " << Fixed(o.norm()) << " m, phi "
         << Fixed(std::atan2(o.y(), o.x())) << " rad: derived, centre of the largest square in "
         << "the foot's reachable footprint at the stance height (foot link '"
         << robot.legs[k].foot_link << "'), minus the mean of the feet";
    model.provenance.push_back(line.str());
  }
  model.d_lim_m = std::max(0.0, d_lim_raw - 0.5 * cell);
  model.provenance.push_back(
      "d_lim = " + Fixed(model.d_lim_m) + " m: derived, half-side of the largest square in the "
      "reachable footprint at the stance height, smallest over legs (leg '" + d_leg + "', " +
      Fixed(d_lim_raw) + " m) less half a footprint cell (" + Fixed(0.5 * cell) + " m)");
  model.l_bnd_m = options.l_bnd_fraction * model.d_lim_m;
  model.provenance.push_back("l_bnd = " + Fixed(model.l_bnd_m) + " m: derived, " +
                             Fixed(options.l_bnd_fraction, 2) + " * d_lim");
  model.dz_max_m = dz_max;
  model.provenance.push_back(
      "dz_max = " + Fixed(dz_max) + " m: derived, the smallest vertical travel (up or down) of a "
      "foot from its nominal point that stays reachable, in steps of " + Fixed(0.5 * cell) +
      " m (leg '" + dz_leg + "')");
  const double max_leg = LegReach(model);
  model.max_yaw_change_rad = MaxYawChangeFor(model.d_lim_m, max_leg);
  model.provenance.push_back(
      "max_yaw_change = " + Fixed(model.max_yaw_change_rad) + " rad: derived, 2 asin(d_lim / (2 * " +
      Fixed(max_leg) + " m)), the yaw that moves the farthest nominal foot by d_lim");
  model.foot_radius_m = foot_radius;
  model.provenance.push_back(
      "foot_radius = " + Fixed(foot_radius) + " m: derived, " +
      (foot_radius > 0 ? "largest foot collision sphere" : "no foot collision sphere"));
  model.provenance.push_back("max_slope = " + Fixed(model.max_slope_rad) +
                             " rad: default (a URDF cannot say)");
  model.gait = WaveGait(model.legs);
  std::string gait_text;
  for (int g : model.gait) gait_text += (gait_text.empty() ? "" : ", ") + model.legs[g].name;
  model.provenance.push_back("gait = [" + gait_text +
                             "]: derived, a wave around the body in decreasing angle of o_k");
  model.provenance.push_back("weights: defaults (a URDF cannot say)");
  std::string body_line;
  model.body = DeriveBodyExtent(robot, out.legs, mean, z_plane, &body_line);
  model.provenance.push_back(body_line);
  return out;
}

}  // namespace mfp
