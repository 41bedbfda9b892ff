#include "planner/search/internal/group_probing.h"

#include <algorithm>
#include <vector>

#include "base/check.h"
#include "planner/search/internal/bound_propagation.h"

namespace mfp {
namespace {

// The hull of the feasible cases' boxes, grown case by case.
struct CaseHull {
  Eigen::VectorXd lower, upper;
  bool empty = true;
  void Add(const Eigen::VectorXd& l, const Eigen::VectorXd& u) {
    if (empty) {
      lower = l;
      upper = u;
      empty = false;
      return;
    }
    lower = lower.cwiseMin(l);
    upper = upper.cwiseMax(u);
  }
};

// One case of a group: member `one` set to 1 (-1: none) and the other open members to 0,
// propagated. Returns false when the case is infeasible.
bool ProbeCase(const Miqp& p, const std::vector<int>& open, int one, int max_passes, double tolerance,
               Eigen::VectorXd* l, Eigen::VectorXd* u) {
  for (int j : open) {
    const double v = j == one ? 1.0 : 0.0;
    if ((*l)(j) > v || (*u)(j) < v) return false;
    (*l)(j) = (*u)(j) = v;
  }
  return !PropagateBounds(p, l, u, max_passes, tolerance).infeasible;
}

}  // namespace

GroupProbingResult ProbeOneOfGroups(const Miqp& p, Eigen::VectorXd* lower_ptr, Eigen::VectorXd* upper_ptr,
                                    int max_passes, double tolerance) {
  Eigen::VectorXd& lower = *lower_ptr;
  Eigen::VectorXd& upper = *upper_ptr;
  MFP_CHECK(lower.size() == p.num_variables() && upper.size() == p.num_variables());
  GroupProbingResult result;
  std::vector<int> open;
  for (const std::vector<int>& group : p.sos1_groups) {
    open.clear();
    bool decided = false;  // a member already at 1 fixes the group
    for (int j : group) {
      if (lower(j) >= 1.0) decided = true;
      if (upper(j) >= 1.0) open.push_back(j);
    }
    if (decided || open.size() < 2) continue;
    CaseHull hull;
    for (int k = -1; k < static_cast<int>(open.size()); ++k) {
      const int one = k < 0 ? -1 : open[k];
      Eigen::VectorXd l = lower, u = upper;
      ++result.probes;
      if (ProbeCase(p, open, one, max_passes, tolerance, &l, &u)) {
        hull.Add(l, u);
      } else if (one >= 0) {
        ++result.members_ruled_out;
      }
    }
    if (hull.empty) {
      result.infeasible = true;
      return result;
    }
    lower = lower.cwiseMax(hull.lower);
    upper = upper.cwiseMin(hull.upper);
  }
  return result;
}

}  // namespace mfp
