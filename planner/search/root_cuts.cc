#include "planner/search/internal/root_cuts.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>
#include <vector>

#include "planner/search/internal/bound_propagation.h"
#include "planner/search/internal/implied_cuts.h"
#include "planner/search/internal/mir_cuts.h"

namespace mfp {
namespace {

// Two cuts whose coefficient vectors are this close to parallel are one cut for the
// loop: the second adds a row and almost no bound.
constexpr double kMaxParallelism = 0.99;

// Cut coefficients come sorted by variable (SeparateMirCuts).
double Dot(const LinearCut& a, const LinearCut& b) {
  double sum = 0.0;
  size_t i = 0, k = 0;
  const std::vector<std::pair<int, double>>& x = a.coefficients;
  const std::vector<std::pair<int, double>>& y = b.coefficients;
  while (i < x.size() && k < y.size()) {
    if (x[i].first == y[k].first) {
      sum += x[i++].second * y[k++].second;
    } else if (x[i].first < y[k].first) {
      ++i;
    } else {
      ++k;
    }
  }
  return sum;
}

double Norm(const LinearCut& a) { return std::sqrt(Dot(a, a)); }

// Integer values whose reduced-cost floor (RelaxationResult::cost_floor and rates) lies
// above the incumbent's objective cannot be part of a better plan: their bounds tighten.
int FixByReducedCostsAtRoot(const Miqp& p, const RelaxationResult& rel, double incumbent_objective,
                            double integrality_tolerance, Eigen::VectorXd* lower, Eigen::VectorXd* upper) {
  if (!std::isfinite(incumbent_objective) || rel.lower_cost_rate.size() != p.num_variables() ||
      !std::isfinite(rel.cost_floor)) {
    return 0;
  }
  const double room = incumbent_objective - rel.cost_floor;
  if (room < 0.0) return 0;
  int fixings = 0;
  for (int j = 0; j < p.num_variables(); ++j) {
    if (!p.is_integer[j] || (*lower)(j) >= (*upper)(j)) continue;
    const double lo = (*lower)(j), hi = (*upper)(j);
    const double up_rate = rel.lower_cost_rate(j), down_rate = rel.upper_cost_rate(j);
    if (up_rate > 0.0) (*upper)(j) = std::min(hi, std::floor(lo + room / up_rate + integrality_tolerance));
    if (down_rate > 0.0) (*lower)(j) = std::max(lo, std::ceil(hi - room / down_rate - integrality_tolerance));
    if ((*lower)(j) != lo || (*upper)(j) != hi) ++fixings;
  }
  return fixings;
}

// The cuts of the families asked for, violated at x, each family's tagged by its bit.
struct TaggedCut {
  LinearCut cut;
  int family;
};

std::vector<TaggedCut> SeparateFamilies(const Miqp& q, const RelaxationRequest& request, const RootProbing& probing,
                                        const Eigen::VectorXd& x, const BranchAndBoundOptions& options) {
  MirSeparationOptions separation;
  separation.min_efficacy = options.root_cut_min_efficacy;
  separation.max_aggregations = options.root_cut_aggregations;
  std::vector<TaggedCut> found;
  auto add = [&found](std::vector<LinearCut> cuts, int family) {
    for (LinearCut& c : cuts) found.push_back({std::move(c), family});
  };
  const int families = options.root_cut_families;
  const double eff = separation.min_efficacy;
  if (families & kGroupBoundCuts) add(SeparateGroupBoundCuts(q, request.lower, request.upper, x, eff), kGroupBoundCuts);
  if (families & kMirCuts) add(SeparateMirCuts(q, request.lower, request.upper, x, separation), kMirCuts);
  if (families & kImpliedBoundCuts) {
    add(SeparateImpliedBoundCuts(q, probing, request.lower, request.upper, x, eff), kImpliedBoundCuts);
  }
  if (families & kCliqueCuts) add(SeparateCliqueCuts(probing, x, eff), kCliqueCuts);
  std::stable_sort(found.begin(), found.end(),
                   [](const TaggedCut& a, const TaggedCut& b) { return a.cut.efficacy > b.cut.efficacy; });
  return found;
}

// The most efficacious cuts (they come sorted), at most `limit`, none nearly parallel to
// one chosen before it.
std::vector<TaggedCut> ChooseCuts(std::vector<TaggedCut> cuts, int limit) {
  std::vector<TaggedCut> chosen;
  for (TaggedCut& tagged : cuts) {
    if (static_cast<int>(chosen.size()) >= limit) break;
    const LinearCut& cut = tagged.cut;
    const double norm = Norm(cut);
    const bool parallel = std::any_of(chosen.begin(), chosen.end(), [&](const TaggedCut& other) {
      return std::abs(Dot(cut, other.cut)) >= kMaxParallelism * norm * Norm(other.cut);
    });
    if (!parallel) chosen.push_back(std::move(tagged));
  }
  return chosen;
}

int FamilyIndex(int family) {
  int k = 0;
  while ((family >> (k + 1)) != 0) ++k;
  return k;
}

// Probes the binaries once (when a probing family is asked for) and applies the values it
// forces: the bounds stay valid for every feasible point.
RootProbing ProbeAndFix(const Miqp& p, const BranchAndBoundOptions& options, RelaxationRequest* request,
                        RootCutLoopResult* result) {
  if (!(options.root_cut_families & (kImpliedBoundCuts | kCliqueCuts))) return {};
  RootProbing probing = ProbeRootBinaries(p, request->lower, request->upper, request->deadline);
  for (const auto& [z, value] : probing.fixed) request->lower(z) = request->upper(z) = value;
  result->probing_fixings = static_cast<int>(probing.fixed.size());
  return probing;
}

void AppendCuts(const std::vector<TaggedCut>& cuts, Miqp* q) {
  const int old_rows = q->num_rows();
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(q->A.nonZeros());
  for (int i = 0; i < old_rows; ++i) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(q->A, i); it; ++it) {
      triplets.emplace_back(i, static_cast<int>(it.col()), it.value());
    }
  }
  const int rows = old_rows + static_cast<int>(cuts.size());
  q->row_lower.conservativeResize(rows);
  q->row_upper.conservativeResize(rows);
  for (size_t k = 0; k < cuts.size(); ++k) {
    const int i = old_rows + static_cast<int>(k);
    for (const auto& [j, c] : cuts[k].cut.coefficients) triplets.emplace_back(i, j, c);
    q->row_lower(i) = -kInfinity;
    q->row_upper(i) = cuts[k].cut.rhs;
    q->row_names.push_back("cut_" + std::to_string(i - old_rows + 1));
  }
  q->A.resize(rows, q->num_variables());
  q->A.setFromTriplets(triplets.begin(), triplets.end());
}

}  // namespace

RootCutLoopResult RunRootCutLoop(const Miqp& problem, RelaxationSolver& solver, const BranchAndBoundOptions& options,
                                 const Deadline& deadline, double incumbent_objective) {
  RootCutLoopResult result;
  result.problem = problem;
  Miqp& q = result.problem;
  RelaxationRequest request;
  request.lower = problem.var_lower;
  request.upper = problem.var_upper;
  request.deadline = deadline;
  // The root's propagated bounds hold for every feasible point: the cuts may use them.
  if (PropagateBounds(problem, &request.lower, &request.upper).infeasible) return result;
  RootProbing probing;
  const int first_cut_row = q.num_rows();
  for (int round = 0; !deadline.Expired(); ++round) {
    const RelaxationResult rel = solver.Solve(q, request);
    ++result.relaxations;
    result.fallbacks += rel.fallbacks;
    result.fallback_time_s += rel.fallback_time_s;
    if (rel.status != RelaxationStatus::kSolved) break;
    const double previous = result.bound_after;
    result.bound_after = rel.objective;
    if (round == 0) {
      result.bound_before = rel.objective;
      result.reduced_cost_fixings = FixByReducedCostsAtRoot(q, rel, incumbent_objective,
                                                            options.integrality_tolerance, &request.lower,
                                                            &request.upper);
      probing = ProbeAndFix(q, options, &request, &result);
      if (PropagateBounds(q, &request.lower, &request.upper).infeasible) break;
    }
    const bool stalled =
        round > 0 && rel.objective - previous <= options.root_cut_min_progress * std::max(1.0, std::abs(rel.objective));
    if (round >= options.root_cut_rounds || stalled) break;
    request.warm_start = rel.x;
    std::vector<TaggedCut> cuts =
        ChooseCuts(SeparateFamilies(q, request, probing, rel.x, options), options.root_cuts_per_round);
    if (cuts.empty()) break;
    for (const TaggedCut& c : cuts) ++result.cuts_by_family[FamilyIndex(c.family)];
    AppendCuts(cuts, &q);
    ++result.rounds;
  }
  result.cuts = q.num_rows() - first_cut_row;
  if (std::isfinite(incumbent_objective)) {
    q.var_lower = request.lower;
    q.var_upper = request.upper;
  }
  return result;
}

}  // namespace mfp
