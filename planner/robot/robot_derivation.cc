#include "planner/robot/robot_derivation.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <numeric>
#include <sstream>

#include "base/check.h"
#include "base/format.h"
#include "planner/robot/internal/inscribed_square.h"
#include "planner/robot/internal/reach_choice.h"

namespace mfp {
namespace {

// Joint-space grid samples of one leg: joint positions and foot points, column-wise.
struct LegSamples {
  Eigen::MatrixXd q;  // num_dof x N
  Eigen::MatrixXd p;  // 3 x N, body frame
};

// Throws TimeLimitError naming the stage once the derivation's deadline has expired.
void CheckDerivationTime(const RobotDescription& robot, const DerivationOptions& options, const char* stage) {
  if (!options.deadline.Expired()) return;
  throw TimeLimitError(robot.source + ": " + (options.deadline.Stopped() ? "stopped" : "time limit reached") +
                       " while deriving the robot from its URDF (" + stage + ")");
}

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
                             double cell_m, double z_m, double ik_tolerance_m, const Deadline& deadline) {
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
  // The deadline is read every 64 cells (each up to 60 IK iterations); an expired one
  // leaves the footprint partial, and the caller throws.
  for (size_t popped = 0; !queue.empty(); ++popped) {
    if (popped % 64 == 0 && deadline.Expired()) break;
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

namespace {

void RejectPlanarLegs(const RobotDescription& robot) {
  for (const LegChain& leg : robot.legs) {
    const std::string axis = PlanarLegAxis(leg);
    if (axis.empty()) continue;
    std::string joints;
    for (const JointModel& j : leg.joints) {
      if (j.movable()) joints += (joints.empty() ? "'" : ", '") + j.name + "'";
    }
    throw InputError(robot.source + ": leg '" + leg.name + "' is planar: its joints " + joints +
                     " all turn about the axis " + axis +
                     ", so its foot has no sideways freedom; mfp's reachability square needs a foot that "
                     "moves both along and across the body (planar-legged robots are not supported)");
  }
}

// The legs' joint-space samples and what they say about the robot's size.
struct LegSampling {
  std::vector<LegSamples> samples;
  std::vector<Eigen::Vector3d> hips;
  std::vector<double> lowest;   // lowest foot point per leg, body z [m]
  double widest_reach = 0.0;    // widest x-y extent of a leg's samples [m]
  double hip_z = 0.0;           // mean hip height, body z [m]
  double common_reach = 0.0;    // smallest downward reach below hip_z [m]

  // The x-y box of leg k's samples, grown by one cell.
  std::pair<Eigen::Vector2d, Eigen::Vector2d> Bounds(size_t k, double cell) const {
    const Eigen::Vector2d lo = samples[k].p.topRows<2>().rowwise().minCoeff();
    const Eigen::Vector2d hi = samples[k].p.topRows<2>().rowwise().maxCoeff();
    return std::make_pair(Eigen::Vector2d(lo.array() - cell), Eigen::Vector2d(hi.array() + cell));
  }
};

LegSampling SampleLegs(const RobotDescription& robot, const DerivationOptions& options) {
  const size_t n = robot.legs.size();
  LegSampling s;
  s.samples.resize(n);
  s.hips.resize(n);
  s.lowest.resize(n);
  for (size_t k = 0; k < n; ++k) {
    CheckDerivationTime(robot, options, "joint-space samples");
    s.samples[k] = SampleJointSpace(robot.legs[k], options.samples_per_leg);
    s.hips[k] = HipPosition(robot.legs[k]);
    s.hip_z += s.hips[k].z() / n;
    const Eigen::Vector2d lo = s.samples[k].p.topRows<2>().rowwise().minCoeff();
    const Eigen::Vector2d hi = s.samples[k].p.topRows<2>().rowwise().maxCoeff();
    s.widest_reach = std::max(s.widest_reach, (hi - lo).maxCoeff());
  }
  // The downward reach of each leg below the mean hip height bounds the stance height.
  s.common_reach = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < n; ++k) {
    s.lowest[k] = s.samples[k].p.row(2).minCoeff();
    const double reach = s.hip_z - s.lowest[k];
    if (!(reach > 1e-6)) {
      std::ostringstream msg;
      msg << robot.source << ": leg '" << robot.legs[k].name
          << "' cannot reach the ground at any stance height: its lowest foot point is at z = "
          << Fixed(s.lowest[k]) << " m, not below the hips (z = " << Fixed(s.hip_z) << " m)";
      throw InputError(msg.str());
    }
    s.common_reach = std::min(s.common_reach, reach);
  }
  MFP_CHECK(s.widest_reach > 0.0);
  return s;
}

// Smallest leg's inscribed square at height z with a coarse grid (cell-centre search).
double SmallestSquareAt(const RobotDescription& robot, const LegSampling& s, double z, double cell,
                        const DerivationOptions& options) {
  double worst = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < robot.legs.size() && worst > 0.0; ++k) {
    const auto [lo, hi] = s.Bounds(k, cell);
    const Footprint fp = ReachableFootprint(robot.legs[k], s.samples[k], lo, hi, cell, z,
                                            options.ik_tolerance_m, options.deadline);
    CheckDerivationTime(robot, options, "footprints of the stance candidates");
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
}

// Legged robots stand with the knee bent, the hips at 60-80 % of the legs' full
// extension, so that a foot can both rise and drop: the nearest height to stance_fraction
// of the reach where every leg still has a useful footprint (its inscribed square at
// least half the best over the candidates). Never the crouched height where the
// footprint alone is largest. Returns the stance height [m] and notes it in provenance.
double DeriveStanceHeight(const RobotDescription& robot, const LegSampling& s,
                          const DerivationOptions& options, std::vector<std::string>* provenance) {
  const double scan_cell = s.widest_reach / options.scan_cells;
  std::vector<double> fractions, scores;
  double best_score = 0.0;
  for (int i = 0; i < options.stance_candidates; ++i) {
    const double frac = 0.25 + 0.70 * i / std::max(1, options.stance_candidates - 1);
    fractions.push_back(frac);
    scores.push_back(SmallestSquareAt(robot, s, s.hip_z - frac * s.common_reach, scan_cell, options));
    best_score = std::max(best_score, scores.back());
  }
  if (best_score <= 0.0) {
    throw InputError(robot.source + ": the legs have no common stance height: at no height between " +
                     Fixed(0.25 * s.common_reach) + " and " + Fixed(0.95 * s.common_reach) +
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
  const double stance = chosen * s.common_reach;
  provenance->push_back(
      "stance_height = " + Fixed(stance) + " m: derived, " + Fixed(100 * chosen, 0) +
      "% of the smallest downward reach below the hips (" + Fixed(s.common_reach) + " m): of " +
      std::to_string(options.stance_candidates) + " heights between 25% and 95%, the nearest to " +
      Fixed(100 * options.stance_fraction, 0) + "% (knee bent, as legged robots stand) where every "
      "leg's inscribed square is at least half the best");
  return stance;
}

// Leg k at the stance height: its footprint, largest square, nominal foot and vertical
// travel. foot_xy is the square's centre.
LegDerivation DeriveLeg(const RobotDescription& robot, const LegSampling& s, size_t k, double stance,
                        double z_plane, double cell, const DerivationOptions& options,
                        Eigen::Vector2d* foot_xy) {
  const LegChain& chain = robot.legs[k];
  const auto [lo, hi] = s.Bounds(k, cell);
  Footprint fp =
      ReachableFootprint(chain, s.samples[k], lo, hi, cell, z_plane, options.ik_tolerance_m, options.deadline);
  CheckDerivationTime(robot, options, "footprints at the stance height");
  if (fp.grid.CountOccupied() == 0) {
    std::ostringstream msg;
    msg << robot.source << ": leg '" << chain.name << "' cannot reach the stance height "
        << Fixed(stance) << " m below the hips (its foot reaches down to "
        << Fixed(s.hip_z - s.lowest[k]) << " m below them)";
    throw InputError(msg.str());
  }
  const InscribedSquare square =
      LargestInscribedSquare(fp.grid, s.hips[k].head<2>(), options.centre_weight_per_m);
  LegDerivation leg;
  leg.hip_body_m = s.hips[k];
  leg.square_half_side_m = square.half_side_m;
  leg.disk_radius_m = fp.grid.DiskClearance(square.centre_m);
  leg.lowest_foot_z_m = s.lowest[k];
  leg.nominal_foot_body_m = Eigen::Vector3d(square.centre_m.x(), square.centre_m.y(), z_plane);
  int ix = 0, iy = 0;
  MFP_CHECK(fp.grid.CellOf(square.centre_m, &ix, &iy));
  const Eigen::VectorXd q_cell = fp.q[static_cast<size_t>(iy) * fp.grid.nx() + ix];
  MFP_CHECK(q_cell.size() == chain.num_dof());
  const IkResult ik = SolveFootIk(chain, leg.nominal_foot_body_m, q_cell, options.ik_tolerance_m);
  leg.nominal_q = ik.converged ? ik.q : q_cell;
  const double step = 0.5 * cell;
  leg.dz_up_m = VerticalTravel(chain, leg.nominal_foot_body_m, leg.nominal_q, +1.0, step, stance,
                               options.ik_tolerance_m);
  leg.dz_down_m = VerticalTravel(chain, leg.nominal_foot_body_m, leg.nominal_q, -1.0, step,
                                 s.hip_z - s.lowest[k], options.ik_tolerance_m);
  leg.footprint = std::move(fp.grid);
  *foot_xy = square.centre_m;
  return leg;
}

// The smallest square and vertical travel over the legs, and the legs that set them.
struct LegLimits {
  double d_lim_raw = std::numeric_limits<double>::infinity();  // smallest half-side [m]
  double disk_raw = std::numeric_limits<double>::infinity();   // smallest disk radius [m]
  double dz_max = std::numeric_limits<double>::infinity();     // smallest travel [m]
  std::string d_leg, disk_leg, dz_leg;
};

LegLimits SmallestLimits(const RobotDescription& robot, const std::vector<LegDerivation>& legs) {
  LegLimits limits;
  for (size_t k = 0; k < legs.size(); ++k) {
    if (legs[k].square_half_side_m < limits.d_lim_raw) {
      limits.d_lim_raw = legs[k].square_half_side_m;
      limits.d_leg = robot.legs[k].name;
    }
    if (legs[k].disk_radius_m < limits.disk_raw) {
      limits.disk_raw = legs[k].disk_radius_m;
      limits.disk_leg = robot.legs[k].name;
    }
    const double dz = std::min(legs[k].dz_up_m, legs[k].dz_down_m);
    if (dz < limits.dz_max) {
      limits.dz_max = dz;
      limits.dz_leg = robot.legs[k].name;
    }
  }
  return limits;
}

// A stance where a leg has no reach left is not a model to plan with: say which leg and
// which heights would do, instead of handing on a zero limit.
void RejectExhaustedLegs(const RobotDescription& robot, const LegSampling& s, const LegLimits& limits,
                         double stance, double cell) {
  const std::string& src = robot.source;
  const std::string heights = Fixed(0.25 * s.common_reach) + " and " + Fixed(0.95 * s.common_reach) + " m";
  if (!(limits.d_lim_raw - 0.5 * cell > 0.0)) {
    int dof = 0;
    for (const LegChain& leg : robot.legs) {
      if (leg.name == limits.d_leg) dof = leg.num_dof();
    }
    throw InputError(src + ": at the stance height " + Fixed(stance) + " m leg '" + limits.d_leg +
                     "' reaches no square wider than a footprint cell (" + Fixed(cell) + " m)" +
                     (dof < 3 ? " (with " + std::to_string(dof) +
                                    " movable joints its foot reaches a curve, not an area, at one height; "
                                    "mfp needs legs of at least 3)"
                              : "; choose stance_height between " + heights + " in a robot YAML"));
  }
  if (!(limits.dz_max > 0.0)) {
    throw InputError(src + ": at the stance height " + Fixed(stance) + " m leg '" + limits.dz_leg +
                     "' cannot move its foot up or down from its nominal point (the edge of its vertical "
                     "reach); choose stance_height between " + heights + " in a robot YAML");
  }
}

// The model's legs: nominal offsets about the mean of the feet.
void AddModelLegs(const RobotDescription& robot, const std::vector<Eigen::Vector2d>& feet_xy,
                  const std::vector<Eigen::Vector3d>& hips, RobotModel* model) {
  const size_t n = feet_xy.size();
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& f : feet_xy) mean += f / static_cast<double>(n);
  for (size_t k = 0; k < n; ++k) {
    LegModel leg;
    leg.name = robot.legs[k].name;
    leg.nominal_offset_body_m = feet_xy[k] - mean;
    leg.hip_body_m = hips[k];
    model->legs.push_back(leg);
    const Eigen::Vector2d o = leg.nominal_offset_body_m;
    std::ostringstream line;
    line << "legs[" << k << "] '" << leg.name << "' nominal offset (" << Fixed(o.x()) << ", "
         << Fixed(o.y()) << ") m, L_leg " << Fixed(o.norm()) << " m, phi "
         << Fixed(std::atan2(o.y(), o.x())) << " rad: derived, centre of the largest square in "
         << "the foot's reachable footprint at the stance height (foot link '"
         << robot.legs[k].foot_link << "'), minus the mean of the feet";
    model->provenance.push_back(line.str());
  }
}

// d_lim for the chosen reach polygon, with the provenance of both polygons: the disk the
// footprint holds about the nominal foot says whether the box holds at every body yaw.
void AddReachLimit(const LegLimits& limits, double cell, const ReachChoice& choice, RobotModel* model) {
  const ReachShape shape = choice.shape;
  const double half_cell = 0.5 * cell;
  const double box = std::max(0.0, limits.d_lim_raw - half_cell);
  const double disk = std::max(0.0, limits.disk_raw - half_cell);
  // A regular polygon's corners lie apothem / cos(pi / sides) from its centre: the apothem
  // of the one inscribed in the disk, so that it lies in the footprint at every body yaw.
  const auto inscribed_apothem = [disk](ReachShape polygon) { return std::cos(M_PI / ReachShapeSides(polygon)) * disk; };
  const double octagon = inscribed_apothem(ReachShape::kOctagon);
  const std::string square_line = "half-side of the largest square in the reachable footprint at the stance height, "
                                  "smallest over legs (leg '" + limits.d_leg + "', " + Fixed(limits.d_lim_raw) +
                                  " m) less half a footprint cell (" + Fixed(half_cell) + " m)";
  const std::string disk_line = "the largest disk about the nominal foot in the footprint, smallest over legs (leg '" +
                                limits.disk_leg + "', " + Fixed(limits.disk_raw) + " m) less half a cell, " +
                                Fixed(disk) + " m";
  model->reach_shape = shape;
  if (shape != ReachShape::kBox) {
    const double apothem = inscribed_apothem(shape);
    model->d_lim_m = apothem;
    model->provenance.push_back("d_lim = " + Fixed(apothem) + " m: derived, apothem of the reach " +
                                ReachShapeName(shape) + ", cos(pi/" + std::to_string(ReachShapeSides(shape)) + ") * " +
                                disk_line +
                                " (the box would be " + Fixed(box) + " m: " + square_line + ")");
  } else {
    model->d_lim_m = box;
    model->provenance.push_back("d_lim = " + Fixed(box) + " m: derived, " + square_line);
  }
  const double corner = std::sqrt(2.0) * box;
  model->provenance.push_back(
      std::string("reach_shape = ") + ReachShapeName(shape) + ": " + choice.why + "; " + disk_line +
      (corner <= disk + 1e-9 ? ", holds the box's corners (" + Fixed(corner) + " m) at every body yaw"
                             : ", does not hold the box's corners (" + Fixed(corner) +
                                   " m from it) when the body is turned from the world axes") +
      "; the octagon inscribed in it has apothem " + Fixed(octagon) + " m, the 16-gon " +
      Fixed(inscribed_apothem(ReachShape::kHexadecagon)) + " m");
}

// The model's limits, foot radius, gait and weights, each with its provenance.
void AddModelLimits(const RobotDescription& robot, const LegLimits& limits, double cell,
                    const DerivationOptions& options, const ReachChoice& reach, RobotModel* model) {
  double foot_radius = 0.0;
  for (const LegChain& leg : robot.legs) foot_radius = std::max(foot_radius, leg.foot_sphere_radius_m);
  AddReachLimit(limits, cell, reach, model);
  model->l_bnd_m = options.l_bnd_fraction * model->d_lim_m;
  model->provenance.push_back("l_bnd = " + Fixed(model->l_bnd_m) + " m: derived, " +
                              Fixed(options.l_bnd_fraction, 2) + " * d_lim");
  model->dz_max_m = limits.dz_max;
  model->provenance.push_back(
      "dz_max = " + Fixed(limits.dz_max) + " m: derived, the smallest vertical travel (up or down) of a "
      "foot from its nominal point that stays reachable, in steps of " + Fixed(0.5 * cell) +
      " m (leg '" + limits.dz_leg + "')");
  const double max_leg = LegReach(*model);
  model->max_yaw_change_rad = MaxYawChangeFor(model->d_lim_m, max_leg);
  model->provenance.push_back(
      "max_yaw_change = " + Fixed(model->max_yaw_change_rad) + " rad: derived, 2 asin(d_lim / (2 * " +
      Fixed(max_leg) + " m)), the yaw that moves the farthest nominal foot by d_lim");
  model->foot_radius_m = foot_radius;
  model->provenance.push_back(
      "foot_radius = " + Fixed(foot_radius) + " m: derived, " +
      (foot_radius > 0 ? "largest foot collision sphere" : "no foot collision sphere"));
  model->provenance.push_back("max_slope = " + Fixed(model->max_slope_rad) +
                              " rad: default (a URDF cannot say)");
  model->gait = WaveGait(model->legs);
  std::string gait_text;
  for (int g : model->gait) gait_text += (gait_text.empty() ? "" : ", ") + model->legs[g].name;
  model->provenance.push_back("gait = [" + gait_text +
                              "]: derived, a wave around the body in decreasing angle of o_k");
  model->provenance.push_back("weights: defaults (a URDF cannot say)");
}

// For the footprint shape: each leg's polygon, with a provenance line giving the shortest
// reach forward and back along x over the legs.
void AddFootprintFaces(const ReachChoice& reach, int faces_per_leg, RobotModel* model) {
  if (reach.shape != ReachShape::kFootprint) return;
  double forward = std::numeric_limits<double>::infinity(), back = forward;
  for (size_t k = 0; k < reach.faces.size(); ++k) {
    for (const ReachFace& f : reach.faces[k]) {
      if (f.normal.x() > 1.0 - 1e-9) forward = std::min(forward, f.offset_m);
      if (f.normal.x() < -1.0 + 1e-9) back = std::min(back, f.offset_m);
    }
    model->legs[k].footprint_faces = reach.faces[k];
  }
  model->provenance.push_back("footprint polygon: derived per leg, " + std::to_string(faces_per_leg) +
                              " faces about the nominal foot inside the reachable footprint at the stance height, "
                              "less half a cell; its shortest reach over the legs along x is " + Fixed(forward) +
                              " m forward and " + Fixed(back) + " m back");
}

}  // namespace

RobotDerivation DeriveRobot(const RobotDescription& robot, const DerivationOptions& options) {
  MFP_CHECK(!robot.legs.empty());
  RejectPlanarLegs(robot);
  const LegSampling sampling = SampleLegs(robot, options);
  RobotDerivation out;
  RobotModel& model = out.model;
  model.name = robot.name;
  for (const std::string& note : robot.notes) model.provenance.push_back("urdf: " + note);
  const double stance = options.stance_height_m
                            ? *options.stance_height_m
                            : DeriveStanceHeight(robot, sampling, options, &model.provenance);
  model.stance_height_m = stance;
  out.feet_plane_z_body_m = sampling.hip_z - stance;
  const double cell = sampling.widest_reach / options.final_cells;
  std::vector<Eigen::Vector2d> feet_xy(robot.legs.size());
  for (size_t k = 0; k < robot.legs.size(); ++k) {
    out.legs.push_back(
        DeriveLeg(robot, sampling, k, stance, out.feet_plane_z_body_m, cell, options, &feet_xy[k]));
  }
  const LegLimits limits = SmallestLimits(robot, out.legs);
  RejectExhaustedLegs(robot, sampling, limits, stance, cell);
  AddModelLegs(robot, feet_xy, sampling.hips, &model);
  std::vector<std::string> leg_names;
  for (const LegChain& leg : robot.legs) leg_names.push_back(leg.name);
  const ReachChoice reach = ChooseReach(out.legs, leg_names, cell, options);
  AddModelLimits(robot, limits, cell, options, reach, &model);
  AddFootprintFaces(reach, options.footprint_faces, &model);
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& f : feet_xy) mean += f / static_cast<double>(feet_xy.size());
  std::string body_line;
  model.body = DeriveBodyExtent(robot, out.legs, mean, out.feet_plane_z_body_m, &body_line);
  model.provenance.push_back(body_line);
  return out;
}

}  // namespace mfp
