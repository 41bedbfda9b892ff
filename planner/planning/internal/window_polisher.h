#pragma once
// The polisher: one window's plan solved again with exact sin and cos.
//
// The MIQP meets the reference and reachability boxes with a piecewise-linear chord for
// the sin and cos of each configuration's yaw, so its footsteps can lie outside the
// boxes once R(yaw) is exact (millimetres on the stepping stones). With the integer
// assignment of the MIQP's solution fixed (each step's region, which steps are
// trimmed), the polisher minimises the same cost over the footstep positions and the
// configurations' yaws with every constraint written with exact trigonometry:
//   reference box   |f_i - p_i - R(theta_b(i)) o_leg(i)|_inf <= l_bnd
//   reachability    |f_i - p_i-n - R(theta_b(i-n)) o_leg(i)|_inf <= d_lim
//   height change   |z_i - z_i-n| <= dz_max
//   yaw change      |theta_b - theta_b-1| <= max_yaw_change, theta_b within its MIQP bounds
//   regions         A_r f_i <= b_r for the region the MIQP chose for step i
//   body regions    the body box's corners p_i + R(theta_b(i)) k in the body region the
//                   MIQP chose for configuration b (body_region_faces.h), when it has them
//   trimming        a trimmed step stays where its leg stood (f_i = f_i-n, by substitution)
// p_i is the centre of contacts of the n latest footsteps (paper eq. 2). These rows are
// the formulation's own families written through the ExactEncoder (exact_encoder.h,
// window_program.h); the cost is the MIQP's, evaluated at the MIQP point the polished
// variables stand for. The boxes are tightened by margin_m so that the solver's own
// tolerance leaves the plan inside them.
// It starts from the MIQP's solution: first a sequential QP on mfp's sparse interior
// point (rounds of a trust-region QP with sin/cos linearised, each followed by the exact
// QP of the footsteps alone at the yaws it chose); where that ends outside the
// constraints, NLopt's SLSQP behind nonlinear_program.h, with a Gauss-Newton feasibility
// projection when SLSQP stops outside them. The result is used only when every constraint holds
// within feasibility_tolerance_m (rad for yaw rows); otherwise the caller keeps the
// MIQP's plan and says why (PolishReport::message).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "planner/formulation/miqp_formulation.h"
#include "planner/formulation/plan.h"

namespace mfp {

struct PolishOptions {
  bool enabled = true;
  double time_limit_s = 0.5;              // per window
  // Kept for the exactness step out of every window search's deadline: this fraction of
  // the plan's time limit, at most time_limit_s and at most half of the time left. A
  // search that ran to the plan's limit left the polisher nothing, and its window, with
  // a plan, was dropped (Table I's LittleDog 36 ended no_solution).
  double reserve_fraction = 0.05;
  double margin_m = 1e-7;                 // boxes, heights and region faces tightened by this
  double feasibility_tolerance_m = 1e-6;  // largest violation of an accepted polished plan
  // The solver first sees only the inequalities within this of their bound at the MIQP's
  // point [m, or rad for yaw rows]; the others are checked after, and added when violated.
  double active_slack = 0.02;
  // Method: sequential QP on mfp's sparse interior point first (sequential_qp); NLopt's
  // SLSQP when that ends outside the constraints (slsqp_fallback), or alone.
  bool sequential_qp = true;
  bool slsqp_fallback = true;
  double sqp_trust_rad = 0.05;        // first trust region of the yaws per round
  double sqp_min_trust_rad = 1e-3;    // rounds stop once a failing round shrinks it below this
  int sqp_max_rounds = 6;
  double sqp_relative_gain = 1e-6;    // rounds stop once one gains less than this x |cost|
  // The planner's answer to a window the polisher cannot make exact: plan it again with
  // the boxes shrunk by the chords' error (exact_window.h). false: keep the MIQP's plan
  // and say so in the plan's message.
  bool replan_when_inexact = true;
  // A re-plan that ends without a plan on the plan's deadline completes the window's own
  // integer choices with one QP (exact_window.h), which may run this long past that
  // deadline [s] (a stop flag still ends it at once). The polisher of the plan's first
  // window gets at least this long when the plan's time is spent (window_exactness.h).
  double completion_overrun_s = 0.25;
};

struct PolishReport {
  bool attempted = false;
  bool accepted = false;            // the polished footsteps replaced the MIQP's
  bool exact = false;               // the footsteps used meet every constraint with exact sin/cos
                                    // (polished, or the MIQP's when its chords happen to fit)
  double time_s = 0.0;
  double objective_before = 0.0;    // the MIQP solution's objective (chords)
  double objective_after = 0.0;     // the polished plan's objective (exact); = before when not accepted
  double excess_before = 0.0;       // largest constraint violation of the MIQP's plan, exact trigonometry
  double excess_after = 0.0;        // the same for the polished point
  std::string message;              // why the polished point was not used; empty when accepted
  std::string stops;                // how each solver phase stopped ("cost: target reached, ...")
};

struct PolishedWindow {
  std::vector<Footstep> footsteps;  // as MiqpFormulation::ExtractFootsteps, start stance included
  PolishReport report;
};

// A bound on |(R_chords(theta) - R(theta)) o|_inf over every yaw of the formulation's
// grid and every leg's nominal offset o [m]: the reference and reachability boxes of a
// formulation built with l_bnd and d_lim shrunk by this hold with exact trigonometry at
// every solution of its MIQP (a sound inner approximation).
double ChordErrorBound(const MiqpFormulation& formulation);

// miqp_x: a solution of formulation.miqp() (integer variables integral). With
// options.enabled false, the MIQP's footsteps and a report with attempted = false.
PolishedWindow PolishWindow(const MiqpFormulation& formulation, const Eigen::VectorXd& miqp_x,
                            const PolishOptions& options);

}  // namespace mfp
