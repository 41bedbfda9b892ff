#pragma once
// Probing over one-of groups (a disjunctive bound propagation): within a node's bounds, a
// group's integer points set exactly one open member to 1 (or none, when the rows allow
// it). Each case is fixed and propagated over the rows (bound_propagation.h); a member
// whose case is infeasible is ruled out, and every variable's bounds shrink to the hull of
// the feasible cases' bounds. A foot's box becomes the box of the stones it may still use
// (and what they imply for the other steps through the reach rows), which row-by-row
// propagation cannot derive while the group's members are fractional.
#include <Eigen/Core>

#include "planner/miqp/miqp.h"

namespace mfp {

struct GroupProbingResult {
  bool infeasible = false;  // no case of some group is feasible
  int members_ruled_out = 0;
  int probes = 0;  // propagations run
};

// Tightens lower/upper in place, one sweep over the groups (each group sees the bounds the
// groups before it left). max_passes and tolerance are PropagateBounds' per case.
GroupProbingResult ProbeOneOfGroups(const Miqp& problem, Eigen::VectorXd* lower, Eigen::VectorXd* upper,
                                    int max_passes = 2, double tolerance = 1e-7);

}  // namespace mfp
