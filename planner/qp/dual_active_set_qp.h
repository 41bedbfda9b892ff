#pragma once
// A dual active-set QP solver (Goldfarb and Idnani's method, dense, in plain Eigen) for
// the node relaxations of one Miqp, warm-started from the last solve:
//   minimise 0.5 x'Qx + c'x + constant  s.t.  row bounds,  lower <= x <= upper.
//
// Q is only positive semidefinite here (binaries and some continuous variables carry no
// cost), so the method works on Q + diag(eps_j) with eps_j = regularisation /
// max(1, l_j^2, u_j^2) over the problem's own (root) bounds, the term
// (eps_j / 2) (x_j - centre_j)^2 centred at 0 (or at the parent's point: the option
// proximal_centre). For every x of a node's box the two objectives differ by at most
// 0.5 sum_j eps_j max((l_j - centre_j)^2, (u_j - centre_j)^2); that amount is subtracted
// from the cutoff's objective and from the regularised floor, so they stay true lower
// bounds of the unregularised node optimum. A solved node's cost_floor is the higher of
// that floor and the box certificate (planner/qp/internal/interior_point_kkt.h) of the
// unregularised problem at the node's x with its multipliers, which holds for any x and
// multipliers >= 0 and pays for the regularisation only its gradient times the box.
//
// Warm start: the object keeps the factorisation of the regularised Hessian, the last
// solve's active set and its QR factors. The next solve of the same problem changes the
// bounds' right-hand sides in place, drops the active constraints whose multipliers turn
// negative (the remaining set is then a dual-feasible start) and adds violated
// constraints from there. A child solved right after its parent costs a few O(n^2)
// steps. This is a cache only: the answer does not depend on what was solved before
// (up to ties and rounding).
//
// Infeasibility is reported only with a certificate checked in the node's own data: when
// a violated constraint p depends on the active ones with no inequality to drop, the
// combination y (1 for p, -r for the active set) gives sum_i y_i n_i = w and
// sum_i y_i b_i = beta, and every feasible x of the box would have w'x >= beta; the node
// is kInfeasible when max over the box of w'x falls short of beta by a margin (computed
// from the data, not from the factors). Otherwise kFailed, for a sound solver to decide
// (the factory hands it to the interior point).
#include <Eigen/Core>
#include <utility>
#include <vector>

#include "base/deadline.h"
#include "planner/miqp/miqp.h"
#include "planner/qp/relaxation_solver.h"

namespace mfp {

struct DualActiveSetOptions {
  // Hessian regularisation scale (objective units per unit of a variable's squared range).
  // Larger is better conditioned factors and fewer steps per node (docs/measurements.md,
  // nodeqp3), but the floors lose up to 0.5 * regularisation per variable (3e-3 on 600
  // variables, against objectives of 1e3-2e4 and a gap of 1e-4).
  double regularisation = 1e-5;
  // A constraint violated by more than this (relative to 1 + |its bound|, rows scaled to
  // unit norm) is not met.
  double feasibility_tolerance = 1e-9;
  // Dense method: problems with more variables end kFailed at once (another solver takes
  // them). Each step is O(n^2) dense work, so large problems lose to the interior point
  // per node (the crossover on Table I: docs/measurements.md, issue 26, dualqp2).
  int max_variables = 300;
  // Rebuild the factors from scratch after this many warm solves (rounding drift).
  int warm_solves_before_rebuild = 200;
  // Steps (additions plus drops) of one solve, as a multiple of variables + rows.
  int max_steps_per_size = 4;
  // Steps of one SolveFrom after its start is built, per variable: past it the solve ends
  // kIterationLimit (the interior point takes the node) rather than cost several of its solves.
  double max_warm_steps_per_variable = 2.0;
  // Active sets (with their factors, 2 n^2 numbers each) kept for later solves; each
  // solve starts from the one whose box differs from its own in the fewest bounds, so
  // that a heuristic's QP between two nodes does not cost the next node its start.
  int snapshots = 8;
  // SolveFrom with the parent's point: the regularisation is centred there,
  // (eps_j / 2) (x_j - parent_j)^2 instead of (eps_j / 2) x_j^2, so that on the singular
  // directions of Q the child's optimum is the point of its optimal face nearest the
  // parent's rather than the one nearest the origin.
  bool proximal_centre = false;
  // SolveFrom with the parent's point: a bound of the start's active set that the child
  // tightened keeps the parent's value until the start is built (x and the multipliers
  // are then the parent's), and enters afterwards as a violated constraint; without it
  // the new value moves x at once and multipliers that turn negative are dropped.
  bool enter_moved_bounds = false;
};

class DualActiveSetQp {
 public:
  explicit DualActiveSetQp(const DualActiveSetOptions& options = {}) : options_(options) {}

  // kSolved with the reduced costs (bound multipliers) and cost_floor, kCutoff once the
  // floor reaches cutoff, kIterationLimit on the deadline or the step cap, kInfeasible
  // with a checked certificate (above), kFailed on a problem it does not take or a node
  // it finds infeasible without one.
  RelaxationResult Solve(const Miqp& problem, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                         double cutoff, const Deadline& deadline);
  // The same from the active set `start` (a parent node's: its result's warm_token, or
  // ActiveSetAt of its point), not from the nearest box: the factors of `start` are built
  // from the stored state nearest to it in active constraints (one factor update per
  // constraint of the difference), the constraints whose multipliers are negative are
  // dropped, and the method goes on from there. Never a cold solve of the whole set: a
  // result whose floor drifted from its objective ends kFailed, for the interior point.
  // parent_point (optional: the parent's solved point) serves the options
  // proximal_centre and enter_moved_bounds; null: neither applies.
  RelaxationResult SolveFrom(const Miqp& problem, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                             double cutoff, const Deadline& deadline, const std::vector<int>& start,
                             const Eigen::VectorXd* parent_point = nullptr);

  // The constraints a solved point meets with equality, by complementarity, in the
  // indexing of warm tokens (j: x_j >= lower_j; n + j: x_j <= upper_j; 2n + i: row i's
  // lower side; 2n + m + i: its upper side). A variable at both bounds takes the side of
  // its larger reduced cost (rates may be empty). For seeding the dual method from an
  // interior point's answer.
  static std::vector<int> ActiveSetAt(const Miqp& problem, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                      const RelaxationResult& solved);

 private:
  enum class Step { kOptimal, kInfeasible, kCutoff, kLimit, kFailed };
  struct Snapshot {
    Eigen::VectorXd lower, upper;
    Eigen::MatrixXd J, R;
    std::vector<int> active;
    int warm_solves = 0;
    long used = -1;  // when last saved; -1: empty
  };
  int BoundsChanged(const Snapshot& snapshot) const;
  void RestoreNearest();
  int WarmStepBudget() const;
  int ActiveSetDistance(const std::vector<int>& from, const std::vector<int>& to);
  void LoadSnapshot(int slot);
  void BuildActiveSet(const std::vector<int>& target);
  void SaveSnapshot();

  bool Prepare(const Miqp& problem, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper);
  bool FactorHessian(const Miqp& problem);
  void ColdStart();
  void SetBounds(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper);
  bool WarmStart();
  Step Iterate(double cutoff, const Deadline& deadline);
  int MostViolated() const;
  Step AddConstraint(int p, const Deadline& deadline, double u_plus = 0.0);
  std::vector<std::pair<int, double>> HoldMovedBounds(const Eigen::VectorXd& parent_point);
  Step EnterMovedBounds(const std::vector<std::pair<int, double>>& moved, const Deadline& deadline);
  void SetCentre(const Eigen::VectorXd* centre);
  bool CertifiesInfeasible(int p, const Eigen::VectorXd& r) const;
  void AppendToFactors(int p, Eigen::VectorXd d);
  void DropFromFactors(int position);
  void SolveForActiveSet();
  Eigen::VectorXd TransposedJTimesNormal(int constraint) const;
  double NormalDot(int constraint, const Eigen::VectorXd& v) const;
  double Slack(int constraint) const;
  bool IsEquality(int constraint) const;
  void FillResult(const Miqp& problem, Step step, RelaxationResult* result) const;
  Eigen::VectorXd StationarityResidual(const Eigen::VectorXd& u) const;
  void RefineMultipliers();
  Step Polish(Step step, double cutoff, const Deadline& deadline);
  double RegularisedObjective() const;
  double FloorCorrection() const;

  DualActiveSetOptions options_;
  // The problem the factors belong to (address, shape and a fingerprint of its data: a
  // cache key; the pointers below are dereferenced only inside Solve).
  const Miqp* problem_ = nullptr;
  long key_rows_ = -1, key_nnz_q_ = -1, key_nnz_a_ = -1;
  double key_fingerprint_ = 0.0;
  int n_ = 0, m_ = 0;
  Eigen::VectorXd eps_;          // regularisation per variable
  Eigen::VectorXd c0_;           // the problem's linear cost
  Eigen::VectorXd centre_;       // the regularisation's centre (zero: none)
  Eigen::VectorXd c_;            // linear cost of the regularised problem: c0 - eps .* centre
  Eigen::MatrixXd H_;            // Q + diag(eps)
  Eigen::MatrixXd J_;            // L^-T times the active set's orthogonal factor
  Eigen::MatrixXd R_;            // upper triangular, active columns first
  Eigen::MatrixXd J0_;           // L^-T: J_ of the empty active set
  Eigen::VectorXd row_norm_;
  std::vector<char> is_equality_;  // per constraint: a side of an equality row
  const Eigen::SparseMatrix<double>* Q_ = nullptr;
  double constant_ = 0.0;
  // Constraint c: c < n: x_c >= l; c < 2n: -x >= -u; c < 2n+m: row >= row_lower; else -row >= -row_upper.
  Eigen::VectorXd rhs_;
  Eigen::VectorXd lower_, upper_;
  std::vector<int> active_;      // constraint per factor column
  std::vector<char> is_active_;
  std::vector<char> mark_;       // scratch, per constraint
  Eigen::VectorXd u_;            // multipliers of active_
  Eigen::VectorXd x_, ax_;
  int steps_ = 0;
  int step_limit_ = 0;  // steps_ at which the solve ends kIterationLimit
  int warm_solves_ = 0;
  bool warm_valid_ = false;
  std::vector<Snapshot> snapshots_;
  int live_slot_ = -1;  // the snapshot the live factors equal, or -1
  long clock_ = 0;
  const Eigen::SparseMatrix<double, Eigen::RowMajor>* A_ = nullptr;
};

}  // namespace mfp
