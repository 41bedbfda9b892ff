#include "planner/miqp_formulation.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

#include "planner/check.h"
#include "planner/miqp_builder.h"
#include "planner/region_union_hull.h"

namespace mfp {
namespace {

double WrapToPi(double a) { return std::remainder(a, 2.0 * M_PI); }

std::string StepName(const char* what, int i) { return std::string(what) + "_" + std::to_string(i); }

// The chord of sin (sine = true) or cos over [a, e]: v(theta) = slope theta + intercept.
// One definition for both yaw encodings and for SnapYawToOneSegment's check.
struct Chord {
  double slope, intercept;
  double At(double theta) const { return slope * theta + intercept; }
};
Chord ChordOf(bool sine, double a, double e) {
  const double va = sine ? std::sin(a) : std::cos(a), ve = sine ? std::sin(e) : std::cos(e);
  const double slope = (ve - va) / (e - a);
  return {slope, va - slope * a};
}

// Bounding box of the regions' vertices, grown by a margin, used as variable bounds of
// the footstep positions and as the box from which big-M constants are computed.
struct Box3 {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(kInfinity);
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(-kInfinity);
  void Add(const Eigen::Vector3d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
};

// Largest value of a . f - b over the box (corners suffice: it is linear).
double MaxOverBox(const Eigen::Vector3d& a, double b, const Box3& box) {
  double value = -b;
  for (int k = 0; k < 3; ++k) value += std::max(a(k) * box.lo(k), a(k) * box.hi(k));
  return value;
}

}  // namespace

MiqpFormulation::MiqpFormulation(const FootstepProblem& problem, const FormulationOptions& options)
    : problem_(problem), options_(options) {
  MFP_CHECK(problem_.robot != nullptr);
  const RobotModel& robot = *problem_.robot;
  n_ = robot.num_legs();
  if (static_cast<int>(problem_.start_feet_world_m.size()) != n_) {
    throw InputError("start stance has " + std::to_string(problem_.start_feet_world_m.size()) +
                     " feet, robot '" + robot.name + "' has " + std::to_string(n_) + " legs");
  }
  for (const Eigen::Vector3d& f : problem_.start_feet_world_m) {
    if (!f.allFinite()) throw InputError("start stance has a non-finite foot position");
  }
  if (!std::isfinite(problem_.start_yaw_rad) || !std::isfinite(problem_.goal_x_m) ||
      !std::isfinite(problem_.goal_y_m) || !std::isfinite(problem_.goal_yaw_rad)) {
    throw InputError("start yaw and goal pose must be finite numbers");
  }
  if (!problem_.history_feet_world_m.empty() &&
      static_cast<int>(problem_.history_feet_world_m.size()) != n_) {
    throw InputError("history must hold one foot per leg");
  }
  if (!problem_.start_step_yaw_rad.empty() &&
      static_cast<int>(problem_.start_step_yaw_rad.size()) != n_) {
    throw InputError("start step yaws must hold one yaw per leg");
  }
  if (problem_.num_new_steps < 1) {
    throw InputError("number of new steps must be >= 1, got " +
                     std::to_string(problem_.num_new_steps));
  }
  if (problem_.regions.empty()) throw InputError("no terrain regions to step on");
  if (!(options_.yaw_segment_rad > 0.01 && options_.yaw_segment_rad <= M_PI) ||
      !(options_.yaw_margin_rad >= 0.0 && options_.yaw_margin_rad <= M_PI)) {
    throw InputError("yaw_segment must be in (0.01, pi] rad and yaw_margin in [0, pi] rad");
  }
  num_steps_ = n_ + problem_.num_new_steps;
  num_blocks_ = (num_steps_ + n_ - 1) / n_;
  // Goal yaw unwrapped to within pi of the start so the yaw range is the short way round.
  problem_.goal_yaw_rad =
      problem_.start_yaw_rad + WrapToPi(problem_.goal_yaw_rad - problem_.start_yaw_rad);
  const double lo = std::min(problem_.start_yaw_rad, problem_.goal_yaw_rad) - options_.yaw_margin_rad;
  const double hi = std::max(problem_.start_yaw_rad, problem_.goal_yaw_rad) + options_.yaw_margin_rad;
  const int segments = std::max(1, static_cast<int>(std::ceil((hi - lo) / options_.yaw_segment_rad - 1e-9)));
  for (int k = 0; k <= segments; ++k) breakpoints_.push_back(lo + (hi - lo) * k / segments);
  // Configuration b turns at most b max_yaw_change from the start, so only the segments
  // that meet that range can hold its yaw: the others are left out. The chords stay
  // those of the grid, so the plans are exactly those of the full grid.
  block_breakpoints_.assign(num_blocks_, {});
  yaw_reach_.assign(num_blocks_, {lo, hi});
  for (int blk = 1; blk < num_blocks_; ++blk) {
    double lo_b = lo, hi_b = hi;
    if (options_.clip_yaw_to_reach) {
      const double turn = blk * problem_.robot->max_yaw_change_rad;
      lo_b = problem_.start_yaw_rad - turn;
      hi_b = problem_.start_yaw_rad + turn;
    }
    std::vector<double>& bp = block_breakpoints_[blk];
    for (int k = 0; k < segments; ++k) {
      if (breakpoints_[k + 1] < lo_b || breakpoints_[k] > hi_b) continue;
      if (bp.empty()) bp.push_back(breakpoints_[k]);
      bp.push_back(breakpoints_[k + 1]);
    }
    yaw_reach_[blk] = {std::max(lo, lo_b), std::min(hi, hi_b)};
  }

  Build();
}

int MiqpFormulation::LegOfStep(int step) const {
  const int phase = ((problem_.gait_phase + step) % n_ + n_) % n_;
  return problem_.robot->gait[phase];
}

Eigen::Vector2d MiqpFormulation::GoalFoot(int leg) const {
  return NominalFootXY(*problem_.robot, leg, problem_.goal_x_m, problem_.goal_y_m, problem_.goal_yaw_rad);
}

void MiqpFormulation::Build() {
  const RobotModel& robot = *problem_.robot;
  const int N = num_steps_;
  const int n = n_;
  MiqpBuilder b;

  // Workspace box: every footstep lies in some region, so in the regions' bounding box.
  Box3 box;
  for (const ConvexRegion& r : problem_.regions) {
    for (const Eigen::Vector3d& v : r.vertices_world_m) {
      box.Add(v + Eigen::Vector3d(0, 0, r.plane_tolerance_m));
      box.Add(v - Eigen::Vector3d(0, 0, r.plane_tolerance_m));
    }
  }
  for (const Eigen::Vector3d& f : problem_.start_feet_world_m) box.Add(f);
  box.lo -= Eigen::Vector3d::Constant(1e-3);
  box.hi += Eigen::Vector3d::Constant(1e-3);

  // ---- footstep positions: constants for the start stance, variables afterwards ----
  vars_.x.assign(N, -1);
  vars_.y.assign(N, -1);
  vars_.z.assign(N, -1);
  for (int i = n; i < N; ++i) {
    vars_.x[i] = b.AddVariable(StepName("x", i), box.lo.x(), box.hi.x(), false);
    vars_.y[i] = b.AddVariable(StepName("y", i), box.lo.y(), box.hi.y(), false);
    vars_.z[i] = b.AddVariable(StepName("z", i), box.lo.z(), box.hi.z(), false);
  }
  // Position of step j on one axis. Steps before the plan (j < 0) are the start stance of
  // the same leg: a cyclic gait moves leg(j) = leg(j + n).
  const bool has_history = !problem_.history_feet_world_m.empty();
  auto pos = [&](int j, int axis) -> LinExpr {
    if (j < 0 && has_history) return LinExpr::Constant(problem_.history_feet_world_m[j + n](axis));
    while (j < 0) j += n;
    if (j < n) return LinExpr::Constant(problem_.start_feet_world_m[j](axis));
    const int index = axis == 0 ? vars_.x[j] : axis == 1 ? vars_.y[j] : vars_.z[j];
    return LinExpr::Var(index);
  };
  // Centre of contacts p_i: mean of the n latest footsteps ending at step i (eq. 2).
  auto coc_sum = [&](int i, int axis) -> LinExpr {
    LinExpr sum;
    for (int j = i - n + 1; j <= i; ++j) sum += pos(j, axis);
    return (1.0 / n) * sum;
  };
  // For new steps p_i is a variable defined by an equality row: every constraint and
  // cost that uses p_i then touches 1 column instead of n, which keeps the KKT systems
  // of the relaxations sparse.
  vars_.px.assign(N, -1);
  vars_.py.assign(N, -1);
  for (int i = n; i < N; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      const std::string name = std::string(axis == 0 ? "px_" : "py_") + std::to_string(i);
      const int p = b.AddVariable(name, box.lo(axis), box.hi(axis), false);
      (axis == 0 ? vars_.px : vars_.py)[i] = p;
      b.AddRow("def_" + name, coc_sum(i, axis) - LinExpr::Var(p), 0.0, 0.0);
    }
  }
  auto coc = [&](int i, int axis) -> LinExpr {
    return i >= n ? LinExpr::Var(axis == 0 ? vars_.px[i] : vars_.py[i]) : coc_sum(i, axis);
  };

  // ---- yaw per configuration, with piecewise-linear sin/cos ----
  const int B = num_blocks_;
  // Range of theta, sin and cos over a configuration's segments: the chords' values lie
  // between those at the breakpoints.
  struct YawRange {
    double theta_lo, theta_hi, s_lo = 1, s_hi = -1, c_lo = 1, c_hi = -1;
  };
  std::vector<YawRange> range(B);
  for (int blk = 1; blk < B; ++blk) {
    const std::vector<double>& bp = block_breakpoints_[blk];
    YawRange& r = range[blk];
    r.theta_lo = bp.front();
    r.theta_hi = bp.back();
    for (double psi : bp) {
      r.s_lo = std::min(r.s_lo, std::sin(psi));
      r.s_hi = std::max(r.s_hi, std::sin(psi));
      r.c_lo = std::min(r.c_lo, std::cos(psi));
      r.c_hi = std::max(r.c_hi, std::cos(psi));
    }
  }
  vars_.theta.assign(B, -1);
  vars_.s.assign(B, -1);
  vars_.c.assign(B, -1);
  vars_.segment.assign(B, {});
  vars_.segment_theta.assign(B, {});
  for (int blk = 1; blk < B; ++blk) {
    const YawRange& r = range[blk];
    // theta itself is bounded by the yaw it can reach; the big-M rows use the segments'
    // span, which contains that range.
    vars_.theta[blk] = b.AddVariable(StepName("theta", blk), yaw_reach_[blk].first, yaw_reach_[blk].second, false);
    vars_.s[blk] = b.AddVariable(StepName("sin", blk), r.s_lo, r.s_hi, false);
    vars_.c[blk] = b.AddVariable(StepName("cos", blk), r.c_lo, r.c_hi, false);
  }
  auto theta = [&](int blk) {
    return blk == 0 ? LinExpr::Constant(problem_.start_yaw_rad) : LinExpr::Var(vars_.theta[blk]);
  };
  auto sin_of = [&](int blk) {
    return blk == 0 ? LinExpr::Constant(std::sin(problem_.start_yaw_rad)) : LinExpr::Var(vars_.s[blk]);
  };
  auto cos_of = [&](int blk) {
    return blk == 0 ? LinExpr::Constant(std::cos(problem_.start_yaw_rad)) : LinExpr::Var(vars_.c[blk]);
  };
  for (int blk = 1; blk < B; ++blk) {
    const std::vector<double>& bp = block_breakpoints_[blk];
    const int K = static_cast<int>(bp.size()) - 1;
    const double yaw_lo = range[blk].theta_lo, yaw_hi = range[blk].theta_hi;
    const double s_lo = range[blk].s_lo, s_hi = range[blk].s_hi, c_lo = range[blk].c_lo, c_hi = range[blk].c_hi;
    LinExpr one_segment;
    for (int k = 0; k < K; ++k) {
      const int sk = b.AddBinary("seg_" + std::to_string(blk) + "_" + std::to_string(k));
      vars_.segment[blk].push_back(sk);
      one_segment += LinExpr::Var(sk);
    }
    b.AddRow(StepName("one_segment", blk), one_segment, 1.0, 1.0);
    if (options_.yaw_encoding == YawEncoding::kConvexHull) {
      // Disaggregated: theta = sum_k theta_k with psi_k S_k <= theta_k <= psi_{k+1} S_k,
      // s = sum_k (m_k theta_k + q_k S_k) and likewise c. Exact for integer S, and the
      // relaxation is the convex hull of the piecewise-linear curves: (s, c) cannot shrink
      // towards the origin the way the big-M rows allow.
      LinExpr theta_sum = LinExpr::Var(vars_.theta[blk], -1.0);
      LinExpr sin_sum = LinExpr::Var(vars_.s[blk], -1.0);
      LinExpr cos_sum = LinExpr::Var(vars_.c[blk], -1.0);
      for (int k = 0; k < K; ++k) {
        const int sk = vars_.segment[blk][k];
        const double a = bp[k], e = bp[k + 1];
        const std::string tag = std::to_string(blk) + "_" + std::to_string(k);
        const int tk = b.AddVariable("theta_" + tag, std::min(0.0, a), std::max(0.0, e), false);
        vars_.segment_theta[blk].push_back(tk);
        b.AddRow("seg_lo_" + tag, LinExpr::Var(tk) - LinExpr::Var(sk, a), 0.0, kInfinity);
        b.AddRow("seg_hi_" + tag, LinExpr::Var(tk) - LinExpr::Var(sk, e), -kInfinity, 0.0);
        theta_sum += LinExpr::Var(tk);
        const Chord cs = ChordOf(true, a, e), cc = ChordOf(false, a, e);
        sin_sum += LinExpr::Var(tk, cs.slope) + LinExpr::Var(sk, cs.intercept);
        cos_sum += LinExpr::Var(tk, cc.slope) + LinExpr::Var(sk, cc.intercept);
      }
      b.AddRow(StepName("theta_sum", blk), theta_sum, 0.0, 0.0);
      b.AddRow(StepName("sin_def", blk), sin_sum, 0.0, 0.0);
      b.AddRow(StepName("cos_def", blk), cos_sum, 0.0, 0.0);
    } else {
      for (int k = 0; k < K; ++k) {
        const int sk = vars_.segment[blk][k];
        const double a = bp[k], e = bp[k + 1];
        const std::string tag = std::to_string(blk) + "_" + std::to_string(k);
        // S_bk => psi_k <= theta_b <= psi_{k+1}, written with the tightest constants:
        // theta >= lo + (psi_k - lo) S and theta <= hi - (hi - psi_{k+1}) S.
        b.AddRow("seg_lo_" + tag, theta(blk) - LinExpr::Var(sk, a - yaw_lo), yaw_lo, kInfinity);
        b.AddRow("seg_hi_" + tag, theta(blk) + LinExpr::Var(sk, yaw_hi - e), -kInfinity, yaw_hi);
        // S_bk => s = m theta + q (chord of sin over [a, e]); likewise for cos.
        for (int fn = 0; fn < 2; ++fn) {
          const Chord chord = ChordOf(fn == 0, a, e);
          const double m = chord.slope, q = chord.intercept;
          const double lo_v = fn == 0 ? s_lo : c_lo, hi_v = fn == 0 ? s_hi : c_hi;
          // Largest |v - m theta - q| over the variable box: the big-M of this row.
          double M = 0.0;
          for (double t : {yaw_lo, yaw_hi}) {
            for (double v : {lo_v, hi_v}) M = std::max(M, std::abs(v - m * t - q));
          }
          const LinExpr resid = (fn == 0 ? sin_of(blk) : cos_of(blk)) - LinExpr::Var(vars_.theta[blk], m) -
                                LinExpr::Constant(q);
          const char* fname = fn == 0 ? "sin" : "cos";
          // resid <= M (1 - S)  and  resid >= -M (1 - S)
          b.AddRow(std::string(fname) + "_chord_up_" + tag, resid + LinExpr::Var(sk, M), -kInfinity, M);
          b.AddRow(std::string(fname) + "_chord_dn_" + tag, resid - LinExpr::Var(sk, M), -M, kInfinity);
        }
      }
    }
    // Bounded yaw change between consecutive configurations.
    b.AddRow(StepName("yaw_change", blk), theta(blk) - theta(blk - 1), -robot.max_yaw_change_rad,
             robot.max_yaw_change_rad);
  }

  // Nominal foot position of step i: p_i + R(theta_b(i)) o_leg(i), linear in (s, c).
  auto nominal = [&](int i, int axis) -> LinExpr {
    int blk = i < 0 ? 0 : i / n;
    const Eigen::Vector2d o = robot.legs[LegOfStep(i)].nominal_offset_body_m;
    LinExpr r = coc(i, axis);
    if (blk == 0 && !problem_.start_step_yaw_rad.empty()) {
      const double yaw = problem_.start_step_yaw_rad[i];
      const double c = std::cos(yaw), s = std::sin(yaw);
      r += LinExpr::Constant(axis == 0 ? c * o.x() - s * o.y() : s * o.x() + c * o.y());
      return r;
    }
    if (axis == 0) {
      r += o.x() * cos_of(blk);
      r -= o.y() * sin_of(blk);
    } else {
      r += o.x() * sin_of(blk);
      r += o.y() * cos_of(blk);
    }
    return r;
  };
  auto eval_const = [](const LinExpr& e) {
    MFP_CHECK(e.terms.empty());
    return e.constant;
  };
  // How far each start foot is from its own nominal position (infinity norm): bounds the
  // first move of each leg, for big-M and region pruning.
  std::vector<double> start_offset(n, 0.0);
  for (int i = 0; i < n; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      start_offset[i] = std::max(start_offset[i],
                                 std::abs(problem_.start_feet_world_m[i](axis) - eval_const(nominal(i, axis))));
    }
  }

  for (int i = n; i < N; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      const char* ax = axis == 0 ? "x" : "y";
      // Reference box: |f_i - r_nom,i| <= l_bnd.
      b.AddRow(std::string("ref_") + ax + "_" + std::to_string(i), pos(i, axis) - nominal(i, axis),
               -robot.l_bnd_m, robot.l_bnd_m);
      // Reachability from the previous configuration: |f_i - r_nom,i-n| <= d_lim.
      b.AddRow(std::string("reach_") + ax + "_" + std::to_string(i), pos(i, axis) - nominal(i - n, axis),
               -robot.d_lim_m, robot.d_lim_m);
    }
    // Height change of one step.
    b.AddRow(StepName("dz", i), pos(i, 2) - pos(i - n, 2), -robot.dz_max_m, robot.dz_max_m);
  }

  // ---- trimming: t_i => the foot stays where it was (f_i = f_{i-n}) ----
  // Largest move of step i on each axis, valid for every feasible plan: the reachability
  // box about r_nom,i-n plus how far the previous foot can be from r_nom,i-n.
  auto max_move_xy = [&](int i) {
    return robot.d_lim_m + (i - n < n ? start_offset[i - n] : robot.l_bnd_m);
  };
  vars_.trim.assign(N, -1);
  for (int i = n; i < N; ++i) {
    const int t = b.AddBinary(StepName("trim", i));
    vars_.trim[i] = t;
    for (int axis = 0; axis < 3; ++axis) {
      const double M = axis < 2 ? max_move_xy(i) : robot.dz_max_m;
      const LinExpr move = pos(i, axis) - pos(i - n, axis);
      const std::string tag = std::string(axis == 0 ? "x" : axis == 1 ? "y" : "z") + "_" + std::to_string(i);
      b.AddRow("trim_up_" + tag, move + LinExpr::Var(t, M), -kInfinity, M);
      b.AddRow("trim_dn_" + tag, move - LinExpr::Var(t, M), -M, kInfinity);
    }
    // Trimmed steps form a suffix of the plan: once stopped, the robot stays stopped.
    if (options_.monotone_trimming && i > n) {
      b.AddRow(StepName("trim_suffix", i), LinExpr::Var(vars_.trim[i - 1]) - LinExpr::Var(t), -kInfinity, 0.0);
    }
  }

  // ---- a configuration whose first step is trimmed does not turn: t_bn => theta_b = theta_b-1 ----
  // With trimming as a suffix, the yaw of the last configuration is then the yaw of the
  // last step taken, which is the body yaw the plan reports, the goal test checks and the
  // goal cost weighs. Without it a trimmed last configuration could turn to the goal yaw
  // on paper while the steps the robot takes end at another yaw.
  if (options_.trimmed_configurations_hold_yaw) {
    for (int blk = 1; blk < B; ++blk) {
      const int t = vars_.trim[blk * n];
      if (t < 0) continue;
      const double M = robot.max_yaw_change_rad;
      const LinExpr turn = theta(blk) - theta(blk - 1);
      b.AddRow(StepName("hold_yaw_up", blk), turn + LinExpr::Var(t, M), -kInfinity, M);
      b.AddRow(StepName("hold_yaw_dn", blk), turn - LinExpr::Var(t, M), -M, kInfinity);
    }
  }

  // ---- safe regions: sum_r H_ir = 1, H_ir => A_r f_i <= b_r ----
  const int R = static_cast<int>(problem_.regions.size());
  vars_.region.assign(N, std::vector<int>(R, -1));
  vars_.region_copy.assign(N, std::vector<int>(R, -1));
  // Moves of each leg so far bound how far step i can be from that leg's start foot.
  std::vector<double> reach_xy(N, 0.0), reach_z(N, 0.0);
  for (int i = n; i < N; ++i) {
    reach_xy[i] = (i - n < n ? 0.0 : reach_xy[i - n]) + max_move_xy(i);
    reach_z[i] = (i - n < n ? 0.0 : reach_z[i - n]) + robot.dz_max_m;
  }
  region_rows_.assign(N, {-1, -1});
  for (int i = n; i < N; ++i) {
    const Eigen::Vector3d& start_foot = problem_.start_feet_world_m[(i - n) % n];
    const int first_region_row = b.num_rows();
    LinExpr one_region;
    std::vector<int> members;
    for (int r = 0; r < R; ++r) {
      const ConvexRegion& region = problem_.regions[r];
      if (options_.prune_unreachable_regions) {
        Box3 rb;
        for (const Eigen::Vector3d& v : region.vertices_world_m) rb.Add(v);
        const double tol = region.plane_tolerance_m + 1e-6;
        const bool reachable =
            rb.lo.x() <= start_foot.x() + reach_xy[i] && rb.hi.x() >= start_foot.x() - reach_xy[i] &&
            rb.lo.y() <= start_foot.y() + reach_xy[i] && rb.hi.y() >= start_foot.y() - reach_xy[i] &&
            rb.lo.z() - tol <= start_foot.z() + reach_z[i] && rb.hi.z() + tol >= start_foot.z() - reach_z[i];
        if (!reachable) continue;
      }
      const int h = b.AddBinary("H_" + std::to_string(i) + "_" + std::to_string(region.id));
      vars_.region[i][r] = h;
      members.push_back(h);
      one_region += LinExpr::Var(h);
      const std::string tag = std::to_string(i) + "_" + std::to_string(region.id);
      if (options_.region_encoding == RegionEncoding::kBigM) {
        for (int row = 0; row < region.A.rows(); ++row) {
          const Eigen::Vector3d a = region.A.row(row).transpose();
          const double M = MaxOverBox(a, region.b(row), box);
          if (M <= 0.0) continue;  // the box already implies this face
          LinExpr af;
          for (int axis = 0; axis < 3; ++axis) af += a(axis) * pos(i, axis);
          // a.f <= b + M (1 - H)
          b.AddRow("region_" + tag + "_" + std::to_string(row), af + LinExpr::Var(h, M), -kInfinity,
                   region.b(row) + M);
        }
      } else {
        // Disaggregated copies f_ir with A_r f_ir <= b_r H_ir and box bounds scaled by H.
        const int first = b.num_variables();
        vars_.region_copy[i][r] = first;
        for (int axis = 0; axis < 3; ++axis) {
          const double lo_a = std::min(0.0, box.lo(axis)), hi_a = std::max(0.0, box.hi(axis));
          const int v = b.AddVariable("F_" + tag + "_" + "xyz"[axis], lo_a, hi_a, false);
          b.AddRow("F_lo_" + tag + "_" + "xyz"[axis], LinExpr::Var(v) - LinExpr::Var(h, box.lo(axis)), 0.0, kInfinity);
          b.AddRow("F_hi_" + tag + "_" + "xyz"[axis], LinExpr::Var(v) - LinExpr::Var(h, box.hi(axis)), -kInfinity, 0.0);
        }
        for (int row = 0; row < region.A.rows(); ++row) {
          LinExpr af;
          for (int axis = 0; axis < 3; ++axis) af += LinExpr::Var(first + axis, region.A(row, axis));
          b.AddRow("hull_" + tag + "_" + std::to_string(row), af - LinExpr::Var(h, region.b(row)), -kInfinity, 0.0);
        }
      }
    }
    if (members.empty()) {
      std::ostringstream msg;
      msg << "step " << i << " (leg " << LegOfStep(i) << ") cannot reach any region";
      infeasible_reason_ = msg.str();
      // Keep the model well formed: the empty choice row is left out; the planner
      // reports the reason instead of solving.
      continue;
    }
    b.AddRow(StepName("one_region", i), one_region, 1.0, 1.0);
    if (options_.region_encoding == RegionEncoding::kConvexHull) {
      for (int axis = 0; axis < 3; ++axis) {
        LinExpr sum = pos(i, axis);
        for (int r = 0; r < R; ++r) {
          if (vars_.region_copy[i][r] >= 0) sum -= LinExpr::Var(vars_.region_copy[i][r] + axis);
        }
        b.AddRow(std::string("hull_sum_") + "xyz"[axis] + "_" + std::to_string(i), sum, 0.0, 0.0);
      }
    }
    region_rows_[i] = {first_region_row, b.num_rows()};
  }

  // ---- objective ----
  const PlannerWeights& w = robot.weights;
  // Goal: the final stance (last step of each leg) against the goal stance.
  for (int i = N - n; i < N; ++i) {
    const Eigen::Vector2d g = GoalFoot(LegOfStep(i));
    for (int axis = 0; axis < 2; ++axis) {
      b.AddSquaredCost(pos(i, axis) - LinExpr::Constant(g(axis)), w.goal_position);
    }
  }
  if (B > 1) b.AddSquaredCost(theta(B - 1) - LinExpr::Constant(problem_.goal_yaw_rad), w.goal_yaw);
  // Fewer steps: a negative weight on every trimmed step.
  for (int i = n; i < N; ++i) b.AddLinearCost(LinExpr::Var(vars_.trim[i], w.trim_step));
  // Smooth progress: displacement of the centre of contacts between configurations.
  for (int i = n; i < N; ++i) {
    for (int axis = 0; axis < 2; ++axis) {
      b.AddSquaredCost(coc(i, axis) - coc(i - n, axis), w.displacement);
    }
  }
  miqp_ = b.Build();
  // One-of groups in plan order (a configuration's yaw segments, then its steps'
  // regions), so that branching rules that follow the group order decide the plan from
  // its start outwards.
  miqp_.sos1_groups.clear();
  for (int blk = 0; blk < B; ++blk) {
    if (!vars_.segment[blk].empty()) miqp_.sos1_groups.push_back(vars_.segment[blk]);
    for (int i = std::max(n, blk * n); i < std::min(N, (blk + 1) * n); ++i) {
      std::vector<int> members;
      for (int h : vars_.region[i]) {
        if (h >= 0) members.push_back(h);
      }
      if (!members.empty()) miqp_.sos1_groups.push_back(members);
    }
  }
}

Miqp MiqpFormulation::WithRegionsRelaxedFrom(int first_step) const {
  first_step = std::max(first_step, n_);
  if (first_step >= num_steps_) return miqp_;
  Miqp out = miqp_;
  std::vector<bool> dropped(miqp_.num_rows(), false);
  for (int i = first_step; i < num_steps_; ++i) {
    for (int row = region_rows_[i].first; row < region_rows_[i].second; ++row) dropped[row] = true;
  }
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<double> row_lo, row_hi;
  out.row_names.clear();
  for (int row = 0; row < miqp_.num_rows(); ++row) {
    if (dropped[row]) continue;
    const int out_row = static_cast<int>(row_lo.size());
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(miqp_.A, row); it; ++it) {
      triplets.emplace_back(out_row, static_cast<int>(it.col()), it.value());
    }
    row_lo.push_back(miqp_.row_lower(row));
    row_hi.push_back(miqp_.row_upper(row));
    out.row_names.push_back(miqp_.row_names[row]);
  }
  for (int i = first_step; i < num_steps_; ++i) {
    if (region_rows_[i].first < 0) continue;  // reaches no region: the model is infeasible anyway
    std::vector<const ConvexRegion*> reachable;
    for (size_t r = 0; r < problem_.regions.size(); ++r) {
      const int h = vars_.region[i][r];
      if (h < 0) continue;
      reachable.push_back(&problem_.regions[r]);
      out.var_lower(h) = out.var_upper(h) = 0.0;
      const int copy = vars_.region_copy[i][r];  // convex-hull encoding only
      for (int axis = 0; copy >= 0 && axis < 3; ++axis) out.var_lower(copy + axis) = out.var_upper(copy + axis) = 0.0;
    }
    const RegionUnionHull hull = HullOfRegions(reachable);
    for (int k = 0; k < hull.A.rows(); ++k) {
      const int out_row = static_cast<int>(row_lo.size());
      if (hull.A(k, 0) != 0.0) triplets.emplace_back(out_row, vars_.x[i], hull.A(k, 0));
      if (hull.A(k, 1) != 0.0) triplets.emplace_back(out_row, vars_.y[i], hull.A(k, 1));
      row_lo.push_back(-kInfinity);
      row_hi.push_back(hull.b(k));
      out.row_names.push_back("union_hull_" + std::to_string(i) + "_" + std::to_string(k));
    }
    out.var_lower(vars_.z[i]) = std::max(out.var_lower(vars_.z[i]), hull.z_lower_m);
    out.var_upper(vars_.z[i]) = std::min(out.var_upper(vars_.z[i]), hull.z_upper_m);
  }
  out.A.resize(static_cast<Eigen::Index>(row_lo.size()), miqp_.num_variables());
  out.A.setFromTriplets(triplets.begin(), triplets.end());
  out.row_lower = Eigen::Map<const Eigen::VectorXd>(row_lo.data(), static_cast<Eigen::Index>(row_lo.size()));
  out.row_upper = Eigen::Map<const Eigen::VectorXd>(row_hi.data(), static_cast<Eigen::Index>(row_hi.size()));
  return out;
}

bool MiqpFormulation::SnapYawToOneSegment(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                          Eigen::VectorXd* x_ptr) const {
  Eigen::VectorXd& x = *x_ptr;
  MFP_CHECK(x.size() == miqp_.num_variables());
  // Accuracy of a relaxation point: chords and breakpoints are met to about this.
  constexpr double kTolerance = 1e-6;
  bool changed = false;
  for (int blk = 1; blk < num_blocks_; ++blk) {
    const std::vector<int>& seg = vars_.segment[blk];
    const int K = static_cast<int>(seg.size());
    bool integral = true;
    for (int k = 0; k < K; ++k) integral = integral && std::min(x(seg[k]), 1.0 - x(seg[k])) <= 1e-9;
    if (integral) continue;
    const std::vector<double>& bp = block_breakpoints_[blk];
    const double theta = x(vars_.theta[blk]), s = x(vars_.s[blk]), c = x(vars_.c[blk]);
    int chosen = -1;
    for (int k = 0; k < K; ++k) {
      if (upper(seg[k]) < 0.5 || theta < bp[k] - kTolerance || theta > bp[k + 1] + kTolerance) continue;
      const double t = std::clamp(theta, bp[k], bp[k + 1]);
      if (std::abs(s - ChordOf(true, bp[k], bp[k + 1]).At(t)) > kTolerance ||
          std::abs(c - ChordOf(false, bp[k], bp[k + 1]).At(t)) > kTolerance) {
        continue;
      }
      if (chosen < 0 || x(seg[k]) > x(seg[chosen])) chosen = k;
    }
    if (chosen < 0) continue;
    bool allowed = true;  // the other segments must be allowed to be 0
    for (int k = 0; k < K; ++k) allowed = allowed && (k == chosen || lower(seg[k]) < 0.5);
    if (!allowed) continue;
    for (int k = 0; k < K; ++k) {
      x(seg[k]) = k == chosen ? 1.0 : 0.0;
      if (!vars_.segment_theta[blk].empty()) x(vars_.segment_theta[blk][k]) = k == chosen ? theta : 0.0;
    }
    changed = true;
  }
  return changed;
}

std::vector<Footstep> MiqpFormulation::ExtractFootsteps(const Eigen::VectorXd& x) const {
  MFP_CHECK(x.size() == miqp_.num_variables());
  std::vector<Footstep> steps;
  for (int i = 0; i < num_steps_; ++i) {
    Footstep f;
    f.index = i;
    f.leg = LegOfStep(i);
    if (i < n_) {
      f.position_world_m = problem_.start_feet_world_m[i];
      f.yaw_rad = problem_.start_yaw_rad;
      const int r = FindRegionBelow(problem_.regions, f.position_world_m.x(), f.position_world_m.y(), 1e-3);
      f.region_id = r >= 0 ? problem_.regions[r].id : -1;
    } else {
      f.position_world_m = Eigen::Vector3d(x(vars_.x[i]), x(vars_.y[i]), x(vars_.z[i]));
      f.yaw_rad = x(vars_.theta[i / n_]);
      double best = -1.0;
      for (size_t r = 0; r < problem_.regions.size(); ++r) {
        const int h = vars_.region[i][r];
        if (h >= 0 && x(h) > best) {
          best = x(h);
          f.region_id = problem_.regions[r].id;
        }
      }
    }
    steps.push_back(f);
  }
  return steps;
}

int MiqpFormulation::CountUntrimmedSteps(const Eigen::VectorXd& x) const {
  int count = 0;
  for (int i = n_; i < num_steps_; ++i) count += x(vars_.trim[i]) < 0.5 ? 1 : 0;
  return count;
}

std::vector<Eigen::VectorXd> MiqpFormulation::RoundAlongPlan(const Eigen::VectorXd& relaxed) const {
  MFP_CHECK(relaxed.size() == miqp_.num_variables());
  int first_trimmed = num_steps_;
  for (int i = num_steps_ - 1; i >= n_; --i) {
    if (relaxed(vars_.trim[i]) >= 0.5) first_trimmed = i;
  }
  std::vector<Eigen::VectorXd> proposals;
  for (int trim_from : {first_trimmed, num_steps_}) {
    Eigen::VectorXd rounded;
    if (RoundWithTrimming(relaxed, trim_from, &rounded)) proposals.push_back(rounded);
    if (first_trimmed == num_steps_) break;  // both proposals would be the same
  }
  return proposals;
}

bool MiqpFormulation::RoundWithTrimming(const Eigen::VectorXd& relaxed, int first_trimmed,
                                        Eigen::VectorXd* rounded) const {
  *rounded = relaxed;
  // Yaw: the segment that contains the relaxed yaw.
  for (int blk = 1; blk < num_blocks_; ++blk) {
    const double th = relaxed(vars_.theta[blk]);
    const int K = static_cast<int>(vars_.segment[blk].size());
    int chosen = K - 1;
    for (int k = 0; k < K; ++k) {
      if (th <= block_breakpoints_[blk][k + 1]) {
        chosen = k;
        break;
      }
    }
    for (int k = 0; k < K; ++k) (*rounded)(vars_.segment[blk][k]) = k == chosen ? 1.0 : 0.0;
  }
  for (int i = n_; i < num_steps_; ++i) (*rounded)(vars_.trim[i]) = i >= first_trimmed ? 1.0 : 0.0;
  // Regions: a trimmed step keeps the region of the foot it stays on. Otherwise, among
  // the regions whose polygon holds the relaxed foot, the one with the largest weight;
  // when none holds it, the largest weight overall.
  std::vector<int> chosen_region(num_steps_, -1);
  for (int i = 0; i < n_; ++i) {
    const Eigen::Vector3d& f = problem_.start_feet_world_m[i];
    chosen_region[i] = FindRegionBelow(problem_.regions, f.x(), f.y(), 1e-3);
  }
  for (int i = n_; i < num_steps_; ++i) {
    const Eigen::Vector3d f(relaxed(vars_.x[i]), relaxed(vars_.y[i]), relaxed(vars_.z[i]));
    int best = -1;
    const int kept = chosen_region[i - n_];
    if ((*rounded)(vars_.trim[i]) > 0.5 && kept >= 0 && vars_.region[i][kept] >= 0) {
      best = kept;
    } else {
      // Regions that hold the foot first, then by weight, then (where weights tie, as
      // they do for steps whose region choice was relaxed to a hull, all of weight 0)
      // the nearer first.
      std::tuple<bool, double, double> best_key(false, -kInfinity, -kInfinity);
      for (size_t r = 0; r < problem_.regions.size(); ++r) {
        const int h = vars_.region[i][r];
        if (h < 0) continue;
        const double violation = RegionViolation(problem_.regions[r], f);
        const std::tuple<bool, double, double> key(violation <= 1e-6, relaxed(h), -violation);
        if (best < 0 || key > best_key) {
          best_key = key;
          best = static_cast<int>(r);
        }
      }
    }
    if (best < 0) return false;
    chosen_region[i] = best;
    for (size_t r = 0; r < problem_.regions.size(); ++r) {
      const int h = vars_.region[i][r];
      if (h >= 0) (*rounded)(h) = static_cast<int>(r) == best ? 1.0 : 0.0;
    }
  }
  return true;
}

}  // namespace mfp
