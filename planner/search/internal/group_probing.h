#pragma once
// Probing over one-of groups (a disjunctive bound propagation): within a node's bounds, a
// group's integer points set exactly one open member to 1 (or none, when the rows allow
// it). Each case is fixed and propagated over the rows it reaches (TightenByRow,
// bound_propagation.h, from the rows of the members it fixed outwards); a member whose
// case is infeasible is ruled out, and every variable's bounds shrink to the hull of the
// feasible cases' bounds. A foot's box becomes the box of the stones it may still use (and
// what they imply for the other steps through the reach rows), which row-by-row
// propagation cannot derive while the group's members are fractional.
#include <Eigen/Core>
#include <vector>

#include "base/deadline.h"
#include "planner/miqp/miqp.h"

namespace mfp {

struct GroupProbingResult {
  bool infeasible = false;  // no case of some group is feasible
  bool stopped = false;     // the work cap or the deadline ended the sweep before its last group
  int members_ruled_out = 0;
  int probes = 0;  // cases propagated
  long row_visits = 0;
};

// What one Probe may spend: the sweep stops between groups once either is spent (the
// groups probed so far keep their tightenings, which are valid on their own).
struct GroupProbingLimits {
  long max_row_visits = -1;  // over all cases of the sweep (< 0: no cap)
  Deadline deadline;         // default: never
  // The sweep's order: this group first, then its neighbours in the problem's list
  // alternately after and before it (the plan's order: the branched step's groups and the
  // steps around it come first under a cap). < 0: the list's order.
  int centre_group = -1;
};

class GroupProber {
 public:
  explicit GroupProber(const Miqp& problem);  // indexes each variable's rows; problem outlives this

  // Tightens lower/upper in place, one sweep over the groups in limits' order (each group
  // sees the bounds the groups before it left). Each case visits at most two rows per row of the problem
  // (the work of two PropagateBounds passes); tolerance as PropagateBounds'.
  GroupProbingResult Probe(Eigen::VectorXd* lower, Eigen::VectorXd* upper, const GroupProbingLimits& limits = {},
                           double tolerance = 1e-7) const;

 private:
  // Returns false when the case is infeasible; adds its row visits to *visits.
  bool ProbeCase(const std::vector<int>& open, int one, double tolerance, Eigen::VectorXd* lower,
                 Eigen::VectorXd* upper, long* visits) const;
  // Probes one group; false when none of its cases is feasible.
  bool ProbeGroup(const std::vector<int>& group, double tolerance, Eigen::VectorXd* lower, Eigen::VectorXd* upper,
                  GroupProbingResult* result) const;

  const Miqp& p_;
  std::vector<std::vector<int>> rows_of_;  // [variable] -> rows it appears in
};

}  // namespace mfp
