#pragma once
// A primal-dual interior-point solver (Mehrotra predictor-corrector) for the convex QPs
// of branch-and-bound nodes, in plain Eigen with a sparse LDL' factorisation.
//
// Rows are made elastic: every one-sided row a'x <= b becomes a'x - e <= b with e >= 0
// and a cost penalty * e. The elastic problem always has an interior, so every node
// converges in a few dozen iterations, infeasible ones included; its optimum never
// exceeds the true one, so its objective is a valid bound; and a node whose elastic
// variables stay positive is reported infeasible. Variable bounds stay hard (they are
// always consistent: fixed variables are removed before, see fixed_variable_reduction.h).
#include <Eigen/Core>

#include "base/deadline.h"
#include "planner/miqp/miqp.h"
#include "planner/qp/relaxation_solver.h"

namespace mfp {

// The crossover's checks (InteriorPointOptions::polish_tolerance; interior_point_polish.h).
struct ActiveSetPolishOptions {
  // Rows' and bounds' violation allowed at the polished point, relative to 1 + |d|_inf
  // (the interior point's primal scale).
  double primal_tolerance = 1e-7;
  // objective - floor allowed, relative to max(1, |objective|): the check that the guess
  // was right (a wrong one leaves a multiplier of the wrong sign, which the floor pays).
  double gap = 1e-8;
  // The KKT system [Q + D, G_A'; G_A, -dI] (D_jj = d (1 + |Q_jj|)) is quasidefinite for
  // d > 0, so an LDL' of it
  // exists in any order even when G_A's rows are dependent or Q is singular on the free
  // variables; refinement against the unregularised system removes d's error where that
  // system is regular, and leaves the interior point's values where it is not.
  double regularisation = 1e-6;
  int refinement_steps = 8;
  // A multiplier this far below 0 (relative to 1 + |c|_inf) is of the wrong sign.
  double dual_tolerance = 1e-9;
  // KKT solves at most: the guess, then primal-dual active-set corrections (a free
  // variable out of its box onto its bound, a violated row into the set, a bound or row
  // whose multiplier has the wrong sign out of it) while they change the set.
  int max_rounds = 4;
};

struct InteriorPointOptions {
  double tolerance = 1e-8;          // relative residual and complementarity at convergence
  double acceptable_dual = 1e-3;    // relative dual residual accepted once complementarity is tiny
  int max_iterations = 80;
  double elastic_penalty = 1e6;     // cost per unit of row violation; far above any dual here
  double infeasible_violation = 1e-6;  // a row violated by more than this: infeasible
  // ... and by more than this many times the tolerance (relative to the rows' scale): a
  // looser tolerance leaves larger residual violations at convergence, which are not
  // infeasibility. Calling a feasible node infeasible would prune it; the reverse only
  // costs a node.
  double infeasible_violation_per_tolerance = 100.0;
  // Warm start: x from the given point (pulled this share of the way to its box's
  // middle), the elastic variables, slacks and duals set so that every slack-dual product
  // starts at warm_start_complementarity (a centred point), slacks at least
  // warm_start_min_slack. A cold start (slacks >= 1, duals 1 and half the penalty) leaves
  // products of the order of the penalty for every solve to bring down; the centred start
  // takes fewer iterations per node QP. The product's value was chosen on Table I
  // (docs/measurements.md).
  double warm_start_pull = 0.01;
  double warm_start_complementarity = 110.0;
  double warm_start_min_slack = 1e-3;
  // Iterative refinement steps per Newton solve at most (each a product with K and a
  // pair of triangular solves), taken while the solve's residual is above a hundredth of
  // the tolerance. Convergence and the floors are judged on the iterate's own residuals,
  // so these change the path and the cost per iteration, never what a result certifies
  // (0: no refinement). refinement_steps holds for the corrector's solve, whose
  // direction is the step taken; predictor_refinement_steps for the predictor's, which
  // only sets the centring and the corrector's second-order term. Fewer steps make each
  // iteration cheaper and move every iterate a little, so a search takes other paths to
  // optima within its gap (0 and 1 measured in docs/measurements.md, not the default).
  int refinement_steps = 2;
  int predictor_refinement_steps = 2;
  // Stop with kCutoff once the iterate's Lagrangian floor (see RelaxationResult::
  // cost_floor) reaches this; infinite: solve to convergence.
  double cutoff = kInfinity;
  // Checked at every iteration and while the KKT pattern is built: once expired the
  // solve returns kIterationLimit.
  Deadline deadline;
  // Work budget of one solve: the terms of G'G its KKT assembly would store (16 bytes
  // each; the factorisation's fill grows with them), counted before anything is
  // allocated. A QP beyond it (long windows over many regions: rows over thousands of
  // variables) is not assembled: kFailed with over_work_budget set, which the factory's
  // fallback does not take over either (Ipopt's ordering alone took longer than the
  // plan's time limit on such a QP: docs/measurements.md).
  double max_kkt_terms = 2e7;
  // Crossover (interior_point_polish.h), off at 0: once the iterate meets this relative
  // accuracy (the convergence test with it as the tolerance; at least tolerance), the
  // solver guesses the active set, solves its KKT system and returns that point when it
  // is feasible and its certificate within polish.gap of its objective (exact optimum and
  // floor); otherwise it iterates on and tries once more at convergence. A looser value
  // stops the interior point sooner; a wrong guess costs one factorisation of the
  // active set's system.
  double polish_tolerance = 0.0;
  ActiveSetPolishOptions polish;
};

// Solves min 0.5 x'Qx + c'x + constant s.t. row bounds, lower <= x <= upper (all finite,
// lower < upper). warm_start may be null.
RelaxationResult SolveQpInteriorPoint(const Miqp& problem, const Eigen::VectorXd& lower,
                                      const Eigen::VectorXd& upper, const Eigen::VectorXd* warm_start,
                                      const InteriorPointOptions& options);

}  // namespace mfp
