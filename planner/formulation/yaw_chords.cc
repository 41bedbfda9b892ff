#include "planner/formulation/internal/yaw_chords.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace mfp {
namespace {

// Range of theta, sin and cos over a configuration's segments: the chords' values lie
// between those at the breakpoints.
struct YawRange {
  double theta_lo, theta_hi, s_lo = 1, s_hi = -1, c_lo = 1, c_hi = -1;
};

YawRange RangeOf(const std::vector<double>& bp) {
  YawRange r;
  r.theta_lo = bp.front();
  r.theta_hi = bp.back();
  for (double psi : bp) {
    r.s_lo = std::min(r.s_lo, std::sin(psi));
    r.s_hi = std::max(r.s_hi, std::sin(psi));
    r.c_lo = std::min(r.c_lo, std::cos(psi));
    r.c_hi = std::max(r.c_hi, std::cos(psi));
  }
  return r;
}

void AddConvexHullChords(const std::vector<double>& bp, int cfg, MiqpBuilder* b, FootstepVariables* vars) {
  const int K = static_cast<int>(bp.size()) - 1;
  LinExpr theta_sum = LinExpr::Var(vars->theta[cfg], -1.0);
  LinExpr sin_sum = LinExpr::Var(vars->s[cfg], -1.0);
  LinExpr cos_sum = LinExpr::Var(vars->c[cfg], -1.0);
  for (int k = 0; k < K; ++k) {
    const int sk = vars->segment[cfg][k];
    const double a = bp[k], e = bp[k + 1];
    const std::string tag = std::to_string(cfg) + "_" + std::to_string(k);
    const int tk = b->AddVariable("theta_" + tag, std::min(0.0, a), std::max(0.0, e), false);
    vars->segment_theta[cfg].push_back(tk);
    b->AddRow("seg_lo_" + tag, LinExpr::Var(tk) - LinExpr::Var(sk, a), 0.0, kInfinity);
    b->AddRow("seg_hi_" + tag, LinExpr::Var(tk) - LinExpr::Var(sk, e), -kInfinity, 0.0);
    theta_sum += LinExpr::Var(tk);
    const Chord cs = ChordOf(true, a, e), cc = ChordOf(false, a, e);
    sin_sum += LinExpr::Var(tk, cs.slope) + LinExpr::Var(sk, cs.intercept);
    cos_sum += LinExpr::Var(tk, cc.slope) + LinExpr::Var(sk, cc.intercept);
  }
  b->AddRow(StepName("theta_sum", cfg), theta_sum, 0.0, 0.0);
  b->AddRow(StepName("sin_def", cfg), sin_sum, 0.0, 0.0);
  b->AddRow(StepName("cos_def", cfg), cos_sum, 0.0, 0.0);
}

void AddBigMChords(const StepExpressions& ex, const std::vector<double>& bp, int cfg, MiqpBuilder* b,
                   const FootstepVariables& vars) {
  const int K = static_cast<int>(bp.size()) - 1;
  const YawRange range = RangeOf(bp);
  const double yaw_lo = range.theta_lo, yaw_hi = range.theta_hi;
  for (int k = 0; k < K; ++k) {
    const int sk = vars.segment[cfg][k];
    const double a = bp[k], e = bp[k + 1];
    const std::string tag = std::to_string(cfg) + "_" + std::to_string(k);
    // S_bk => psi_k <= theta_b <= psi_{k+1}, written with the tightest constants:
    // theta >= lo + (psi_k - lo) S and theta <= hi - (hi - psi_{k+1}) S.
    b->AddRow("seg_lo_" + tag, ex.Yaw(cfg) - LinExpr::Var(sk, a - yaw_lo), yaw_lo, kInfinity);
    b->AddRow("seg_hi_" + tag, ex.Yaw(cfg) + LinExpr::Var(sk, yaw_hi - e), -kInfinity, yaw_hi);
    // S_bk => s = m theta + q (chord of sin over [a, e]); likewise for cos.
    for (int fn = 0; fn < 2; ++fn) {
      const Chord chord = ChordOf(fn == 0, a, e);
      const double m = chord.slope, q = chord.intercept;
      const double lo_v = fn == 0 ? range.s_lo : range.c_lo, hi_v = fn == 0 ? range.s_hi : range.c_hi;
      // Largest |v - m theta - q| over the variable box: the big-M of this row.
      double M = 0.0;
      for (double t : {yaw_lo, yaw_hi}) {
        for (double v : {lo_v, hi_v}) M = std::max(M, std::abs(v - m * t - q));
      }
      const LinExpr resid =
          (fn == 0 ? ex.Sin(cfg) : ex.Cos(cfg)) - LinExpr::Var(vars.theta[cfg], m) - LinExpr::Constant(q);
      const char* fname = fn == 0 ? "sin" : "cos";
      // resid <= M (1 - S)  and  resid >= -M (1 - S)
      b->AddRow(std::string(fname) + "_chord_up_" + tag, resid + LinExpr::Var(sk, M), -kInfinity, M);
      b->AddRow(std::string(fname) + "_chord_dn_" + tag, resid - LinExpr::Var(sk, M), -M, kInfinity);
    }
  }
}

}  // namespace

Chord ChordOf(bool sine, double a, double e) {
  const double va = sine ? std::sin(a) : std::cos(a), ve = sine ? std::sin(e) : std::cos(e);
  const double slope = (ve - va) / (e - a);
  return {slope, va - slope * a};
}

double ChordPointError(double width_rad) {
  // The chord point at fraction t of a segment of width h, against the arc's point at
  // the same yaw (segment centred on 0): (cos(h/2) - cos(phi), (2t - 1) sin(h/2) - sin(phi)),
  // phi = (2t - 1) h / 2. Its largest length over a fine grid of t, plus the grid's
  // possible miss (the length's slope is below 1, the step below 1e-4 rad).
  double worst = 0.0;
  const int samples = 4096;
  for (int k = 0; k <= samples; ++k) {
    const double u = 2.0 * k / samples - 1.0, phi = 0.5 * u * width_rad;
    worst = std::max(worst, std::hypot(std::cos(0.5 * width_rad) - std::cos(phi), u * std::sin(0.5 * width_rad) - std::sin(phi)));
  }
  return worst + width_rad / samples;
}

double LargestSegment(const std::vector<double>& bp) {
  double width = 0.0;
  for (size_t k = 1; k < bp.size(); ++k) width = std::max(width, bp[k] - bp[k - 1]);
  return width;
}

YawGrid MakeYawGrid(double start_yaw_rad, double goal_yaw_rad, double max_yaw_change_rad, int num_configurations,
                    const FormulationOptions& options) {
  YawGrid grid;
  const double lo = std::min(start_yaw_rad, goal_yaw_rad) - options.yaw_margin_rad;
  const double hi = std::max(start_yaw_rad, goal_yaw_rad) + options.yaw_margin_rad;
  const int segments = std::max(1, static_cast<int>(std::ceil((hi - lo) / options.yaw_segment_rad - 1e-9)));
  for (int k = 0; k <= segments; ++k) grid.breakpoints.push_back(lo + (hi - lo) * k / segments);
  grid.configuration_breakpoints.assign(num_configurations, {});
  grid.reach.assign(num_configurations, {lo, hi});
  for (int cfg = 1; cfg < num_configurations; ++cfg) {
    double lo_b = lo, hi_b = hi;
    if (options.clip_yaw_to_reach) {
      const double turn = cfg * max_yaw_change_rad;
      lo_b = start_yaw_rad - turn;
      hi_b = start_yaw_rad + turn;
    }
    std::vector<double>& bp = grid.configuration_breakpoints[cfg];
    for (int k = 0; k < segments; ++k) {
      if (grid.breakpoints[k + 1] < lo_b || grid.breakpoints[k] > hi_b) continue;
      if (bp.empty()) bp.push_back(grid.breakpoints[k]);
      bp.push_back(grid.breakpoints[k + 1]);
    }
    grid.reach[cfg] = {std::max(lo, lo_b), std::min(hi, hi_b)};
  }
  return grid;
}

int SegmentHolding(const std::vector<double>& bp, double theta) {
  const int K = static_cast<int>(bp.size()) - 1;
  for (int k = 0; k < K; ++k) {
    if (theta <= bp[k + 1]) return k;
  }
  return K - 1;
}

void AddYawVariables(const YawGrid& grid, MiqpBuilder* b, FootstepVariables* vars) {
  const int B = static_cast<int>(grid.configuration_breakpoints.size());
  vars->theta.assign(B, -1);
  vars->s.assign(B, -1);
  vars->c.assign(B, -1);
  vars->segment.assign(B, {});
  vars->segment_theta.assign(B, {});
  for (int cfg = 1; cfg < B; ++cfg) {
    const YawRange r = RangeOf(grid.configuration_breakpoints[cfg]);
    // theta itself is bounded by the yaw it can reach; the big-M rows use the segments'
    // span, which contains that range.
    vars->theta[cfg] = b->AddVariable(StepName("theta", cfg), grid.reach[cfg].first, grid.reach[cfg].second, false);
    vars->s[cfg] = b->AddVariable(StepName("sin", cfg), r.s_lo, r.s_hi, false);
    vars->c[cfg] = b->AddVariable(StepName("cos", cfg), r.c_lo, r.c_hi, false);
  }
}

void AddYawChords(const StepExpressions& e, const YawGrid& grid, int cfg, YawEncoding encoding, MiqpBuilder* b,
                  FootstepVariables* vars) {
  const std::vector<double>& bp = grid.configuration_breakpoints[cfg];
  const int K = static_cast<int>(bp.size()) - 1;
  vars->segment[cfg] = AddExactlyOneBinaries("seg", "one_segment", cfg, K, b);
  if (encoding == YawEncoding::kConvexHull) {
    AddConvexHullChords(bp, cfg, b, vars);
  } else {
    AddBigMChords(e, bp, cfg, b, *vars);
  }
}

}  // namespace mfp
