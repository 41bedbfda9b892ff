#include "planner/search/internal/root_cuts.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>
#include <vector>

#include "planner/search/internal/bound_propagation.h"
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

// The most efficacious cuts (they come sorted), at most `limit`, none nearly parallel to
// one chosen before it.
std::vector<LinearCut> ChooseCuts(std::vector<LinearCut> cuts, int limit) {
  std::vector<LinearCut> chosen;
  for (LinearCut& cut : cuts) {
    if (static_cast<int>(chosen.size()) >= limit) break;
    const double norm = Norm(cut);
    const bool parallel = std::any_of(chosen.begin(), chosen.end(), [&](const LinearCut& other) {
      return std::abs(Dot(cut, other)) >= kMaxParallelism * norm * Norm(other);
    });
    if (!parallel) chosen.push_back(std::move(cut));
  }
  return chosen;
}

void AppendCuts(const std::vector<LinearCut>& cuts, Miqp* q) {
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
    for (const auto& [j, c] : cuts[k].coefficients) triplets.emplace_back(i, j, c);
    q->row_lower(i) = -kInfinity;
    q->row_upper(i) = cuts[k].rhs;
    q->row_names.push_back("cut_" + std::to_string(i - old_rows + 1));
  }
  q->A.resize(rows, q->num_variables());
  q->A.setFromTriplets(triplets.begin(), triplets.end());
}

}  // namespace

RootCutLoopResult RunRootCutLoop(const Miqp& problem, RelaxationSolver& solver, const BranchAndBoundOptions& options,
                                 const Deadline& deadline) {
  RootCutLoopResult result;
  result.problem = problem;
  Miqp& q = result.problem;
  RelaxationRequest request;
  request.lower = problem.var_lower;
  request.upper = problem.var_upper;
  request.deadline = deadline;
  // The root's propagated bounds hold for every feasible point: the cuts may use them.
  if (PropagateBounds(problem, &request.lower, &request.upper).infeasible) return result;
  MirSeparationOptions separation;
  separation.min_efficacy = options.root_cut_min_efficacy;
  const int first_cut_row = q.num_rows();
  for (int round = 0; !deadline.Expired(); ++round) {
    const RelaxationResult rel = solver.Solve(q, request);
    ++result.relaxations;
    if (rel.status != RelaxationStatus::kSolved) break;
    const double previous = result.bound_after;
    result.bound_after = rel.objective;
    if (round == 0) result.bound_before = rel.objective;
    const bool stalled =
        round > 0 && rel.objective - previous <= options.root_cut_min_progress * std::max(1.0, std::abs(rel.objective));
    if (round >= options.root_cut_rounds || stalled) break;
    request.warm_start = rel.x;
    std::vector<LinearCut> found = SeparateGroupBoundCuts(q, request.lower, request.upper, rel.x, separation.min_efficacy);
    std::vector<LinearCut> mir = SeparateMirCuts(q, request.lower, request.upper, rel.x, separation);
    found.insert(found.end(), std::make_move_iterator(mir.begin()), std::make_move_iterator(mir.end()));
    std::sort(found.begin(), found.end(), [](const LinearCut& a, const LinearCut& b) { return a.efficacy > b.efficacy; });
    std::vector<LinearCut> cuts = ChooseCuts(std::move(found), options.root_cuts_per_round);
    if (cuts.empty()) break;
    AppendCuts(cuts, &q);
    ++result.rounds;
  }
  result.cuts = q.num_rows() - first_cut_row;
  return result;
}

}  // namespace mfp
