#pragma once
// Implied-bound and clique cuts from probing the root's binaries (root cut loop,
// BranchAndBoundOptions::root_cut_families). Each 0/1 variable z is fixed to 1 and to 0
// in turn and the bounds propagated over the rows (bound_propagation.h); what that
// implies gives
// - implied-bound cuts: z = 1 implies x <= u' below x's bound U, so x <= U - (U - u') z
//   (z = 0 implies x <= u': x <= u' + (U - u') z; likewise for lower bounds);
// - the conflict graph: z = 1 implies z' = 0 (or propagation proves z = 1 infeasible),
//   and clique cuts sum_{z in C} z <= 1 over pairwise conflicting binaries C, grown
//   greedily from the relaxation point's largest fractional values.
// Both hold for every integer-feasible point within the bounds probed (the cuts are
// derived from the rows and integrality alone). A case that propagation proves
// infeasible fixes its binary the other way (RootProbing::fixed).
#include <Eigen/Core>
#include <utility>
#include <vector>

#include "base/deadline.h"
#include "planner/miqp/miqp.h"
#include "planner/search/internal/mir_cuts.h"

namespace mfp {

// One bound that a probed case implies, tighter than the root's.
struct ImpliedBound {
  int variable;
  bool upper;    // true: x <= value, false: x >= value
  double value;
};

struct ProbedBinary {
  int z = -1;
  std::vector<ImpliedBound> when_one, when_zero;  // on continuous variables
  std::vector<int> conflicts;  // binaries that z = 1 forces to 0, sorted
};

struct RootProbing {
  std::vector<ProbedBinary> binaries;       // every 0/1 variable left open by the bounds probed
  std::vector<std::pair<int, double>> fixed;  // (binary, value) that probing fixed
};

// Probes every open 0/1 variable within lower/upper (the root's bounds after
// propagation). An implied bound counts when it tightens the root's by more than
// min_tightening (in the variable's units); only those on continuous variables are kept
// (the cuts' own), with the conflicts between binaries. Stops between binaries once the
// deadline passes, or before a probe that could take the kept implied bounds past
// max_implied_bounds (memory: 16 bytes each): what it found so far stays valid.
RootProbing ProbeRootBinaries(const Miqp& problem, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                              const Deadline& deadline = Deadline(), double min_tightening = 1e-6,
                              long max_implied_bounds = 1L << 20);

// Violated implied-bound cuts at x on continuous variables, most efficacious first.
std::vector<LinearCut> SeparateImpliedBoundCuts(const Miqp& problem, const RootProbing& probing,
                                                const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                                const Eigen::VectorXd& x, double min_efficacy);

// Violated clique cuts at x (at most one per starting binary), most efficacious first.
std::vector<LinearCut> SeparateCliqueCuts(const RootProbing& probing, const Eigen::VectorXd& x, double min_efficacy);

}  // namespace mfp
