#include "planner/search/internal/group_probing.h"

#include <algorithm>
#include <deque>
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

}  // namespace

GroupProber::GroupProber(const Miqp& problem) : p_(problem), rows_of_(problem.num_variables()) {
  for (int row = 0; row < p_.A.outerSize(); ++row) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(p_.A, row); it; ++it) {
      rows_of_[it.col()].push_back(row);
    }
  }
}

// One case of a group: member `one` set to 1 (-1: none) and the other open members to 0,
// then the rows of what moved, in turn, until nothing moves or the work bound is spent.
// Returns false when the case is infeasible.
bool GroupProber::ProbeCase(const std::vector<int>& open, int one, double tolerance, Eigen::VectorXd* l,
                            Eigen::VectorXd* u, long* visits) const {
  std::deque<int> queue;
  std::vector<char> queued(p_.num_rows(), 0);
  const auto enqueue_rows_of = [&](int j) {
    for (int row : rows_of_[j]) {
      if (!queued[row]) {
        queued[row] = 1;
        queue.push_back(row);
      }
    }
  };
  for (int j : open) {
    const double v = j == one ? 1.0 : 0.0;
    if ((*l)(j) > v || (*u)(j) < v) return false;
    (*l)(j) = (*u)(j) = v;
    enqueue_rows_of(j);
  }
  std::vector<int> moved;
  long visits_left = 2L * p_.num_rows();
  while (!queue.empty() && visits_left-- > 0) {
    ++*visits;
    const int row = queue.front();
    queue.pop_front();
    queued[row] = 0;
    moved.clear();
    if (!TightenByRow(p_, row, tolerance, l, u, &moved)) return false;
    for (int j : moved) enqueue_rows_of(j);
  }
  return true;
}

bool GroupProber::ProbeGroup(const std::vector<int>& group, double tolerance, Eigen::VectorXd* lower_ptr,
                             Eigen::VectorXd* upper_ptr, GroupProbingResult* result) const {
  Eigen::VectorXd& lower = *lower_ptr;
  Eigen::VectorXd& upper = *upper_ptr;
  std::vector<int> open;
  for (int j : group) {
    if (lower(j) >= 1.0) return true;  // a member already at 1 fixes the group
    if (upper(j) >= 1.0) open.push_back(j);
  }
  if (open.size() < 2) return true;
  CaseHull hull;
  for (int k = -1; k < static_cast<int>(open.size()); ++k) {
    const int one = k < 0 ? -1 : open[k];
    Eigen::VectorXd l = lower, u = upper;
    ++result->probes;
    if (ProbeCase(open, one, tolerance, &l, &u, &result->row_visits)) {
      hull.Add(l, u);
    } else if (one >= 0) {
      ++result->members_ruled_out;
    }
  }
  if (hull.empty) return false;
  lower = lower.cwiseMax(hull.lower);
  upper = upper.cwiseMin(hull.upper);
  return true;
}

GroupProbingResult GroupProber::Probe(Eigen::VectorXd* lower, Eigen::VectorXd* upper,
                                      const GroupProbingLimits& limits, double tolerance) const {
  MFP_CHECK(lower->size() == p_.num_variables() && upper->size() == p_.num_variables());
  const int groups = static_cast<int>(p_.sos1_groups.size());
  const int centre = std::clamp(limits.centre_group, 0, std::max(groups - 1, 0));
  GroupProbingResult result;
  // k-th group of the sweep: centre, centre + 1, centre - 1, centre + 2, ... (the list's
  // order when no centre is given), skipping indices outside the list.
  for (int k = 0, visited = 0; visited < groups; ++k) {
    int g = k;
    if (limits.centre_group >= 0) g = centre + (k % 2 == 1 ? (k + 1) / 2 : -(k / 2));
    if (g < 0 || g >= groups) continue;
    ++visited;
    if ((limits.max_row_visits >= 0 && result.row_visits >= limits.max_row_visits) || limits.deadline.Expired()) {
      result.stopped = true;
      return result;
    }
    if (!ProbeGroup(p_.sos1_groups[g], tolerance, lower, upper, &result)) {
      result.infeasible = true;
      return result;
    }
  }
  return result;
}

}  // namespace mfp
