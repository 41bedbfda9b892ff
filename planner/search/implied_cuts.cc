#include "planner/search/internal/implied_cuts.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <unordered_map>

#include "base/check.h"
#include "planner/search/internal/bound_propagation.h"

namespace mfp {
namespace {

// A cut's right-hand side is loosened by this share of its size, so that the rounding
// of the arithmetic cannot cut off a point that meets the rows exactly.
constexpr double kRhsSafety = 1e-9;

bool IsOpenBinary(const Miqp& p, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, int j) {
  return p.is_integer[j] && lower(j) == 0.0 && upper(j) == 1.0;
}

// The bounds that fixing z to value implies, tighter than lower/upper; nullopt when
// propagation proves the case infeasible.
std::optional<std::vector<ImpliedBound>> ProbeCase(const Miqp& p, const Eigen::VectorXd& lower,
                                                   const Eigen::VectorXd& upper, int z, double value,
                                                   double min_tightening) {
  Eigen::VectorXd l = lower, u = upper;
  l(z) = u(z) = value;
  if (PropagateBounds(p, &l, &u).infeasible) return std::nullopt;
  std::vector<ImpliedBound> implied;
  for (int j = 0; j < p.num_variables(); ++j) {
    if (j == z) continue;
    if (u(j) < upper(j) - min_tightening) implied.push_back({j, true, u(j)});
    if (l(j) > lower(j) + min_tightening) implied.push_back({j, false, l(j)});
  }
  return implied;
}

// Makes the conflict lists symmetric and sorted (z = 1 forcing z' = 0 is the same
// statement as z' = 1 forcing z = 0).
void SymmetrizeConflicts(std::vector<ProbedBinary>* binaries) {
  std::unordered_map<int, size_t> index;
  for (size_t k = 0; k < binaries->size(); ++k) index[(*binaries)[k].z] = k;
  std::vector<std::vector<int>> extra(binaries->size());
  for (const ProbedBinary& b : *binaries) {
    for (int other : b.conflicts) {
      const auto it = index.find(other);
      if (it != index.end()) extra[it->second].push_back(b.z);
    }
  }
  for (size_t k = 0; k < binaries->size(); ++k) {
    std::vector<int>& c = (*binaries)[k].conflicts;
    c.insert(c.end(), extra[k].begin(), extra[k].end());
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
  }
}

// Scales the cut so that its largest |coefficient| is 1, loosens it by kRhsSafety and
// sets its efficacy at x.
LinearCut Finish(LinearCut cut, const Eigen::VectorXd& x) {
  std::sort(cut.coefficients.begin(), cut.coefficients.end());
  double largest = 0.0, norm2 = 0.0;
  for (const auto& [j, c] : cut.coefficients) largest = std::max(largest, std::abs(c));
  MFP_CHECK(largest > 0.0);
  for (auto& [j, c] : cut.coefficients) {
    c /= largest;
    norm2 += c * c;
  }
  cut.rhs /= largest;
  cut.rhs += kRhsSafety * std::max(1.0, std::abs(cut.rhs));
  cut.efficacy = (cut.Activity(x) - cut.rhs) / std::sqrt(norm2);
  return cut;
}

// x_j <= U - (U - u') z (z = 1 implies x_j <= u') or x_j <= u' + (U - u') z (z = 0 implies
// it), mirrored for lower bounds: sign * x_j + coefficient * z <= sign * outer.
std::optional<LinearCut> ImpliedBoundCut(const ImpliedBound& b, int z, bool when_one, const Eigen::VectorXd& lower,
                                         const Eigen::VectorXd& upper, const Eigen::VectorXd& x) {
  const double outer = b.upper ? upper(b.variable) : lower(b.variable);
  if (!std::isfinite(outer)) return std::nullopt;
  const double sign = b.upper ? 1.0 : -1.0;
  const double tightening = sign * (outer - b.value);
  if (tightening <= 1e-9) return std::nullopt;  // probing's bound no longer below the root's
  LinearCut cut;
  cut.coefficients.push_back({b.variable, sign});
  if (when_one) {
    cut.coefficients.push_back({z, tightening});
    cut.rhs = sign * outer;
  } else {
    cut.coefficients.push_back({z, -tightening});
    cut.rhs = sign * b.value;
  }
  return Finish(std::move(cut), x);
}

bool InConflict(const ProbedBinary& b, int other) {
  return std::binary_search(b.conflicts.begin(), b.conflicts.end(), other);
}

}  // namespace

RootProbing ProbeRootBinaries(const Miqp& p, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                              const Deadline& deadline, double min_tightening, long max_implied_bounds) {
  RootProbing probing;
  long kept = 0;  // implied bounds held
  auto continuous_only = [&p](std::vector<ImpliedBound>* bounds) {
    bounds->erase(std::remove_if(bounds->begin(), bounds->end(),
                                 [&p](const ImpliedBound& ib) { return p.is_integer[ib.variable]; }),
                  bounds->end());
  };
  for (int z = 0; z < p.num_variables(); ++z) {
    if (!IsOpenBinary(p, lower, upper, z)) continue;
    if (deadline.Expired() || kept + 2L * p.num_variables() > max_implied_bounds) break;
    std::optional<std::vector<ImpliedBound>> one = ProbeCase(p, lower, upper, z, 1.0, min_tightening);
    std::optional<std::vector<ImpliedBound>> zero = ProbeCase(p, lower, upper, z, 0.0, min_tightening);
    if (!one || !zero) {  // the other value is forced (both infeasible: the search finds out)
      if (one || zero) probing.fixed.push_back({z, one ? 1.0 : 0.0});
      continue;
    }
    ProbedBinary b;
    b.z = z;
    for (const ImpliedBound& ib : *one) {
      if (!ib.upper || !IsOpenBinary(p, lower, upper, ib.variable) || ib.value > 0.0) continue;
      b.conflicts.push_back(ib.variable);
    }
    continuous_only(&*one);
    continuous_only(&*zero);
    kept += static_cast<long>(one->size() + zero->size());
    b.when_one = std::move(*one);
    b.when_zero = std::move(*zero);
    probing.binaries.push_back(std::move(b));
  }
  SymmetrizeConflicts(&probing.binaries);
  return probing;
}

std::vector<LinearCut> SeparateImpliedBoundCuts(const Miqp& p, const RootProbing& probing,
                                                const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                                const Eigen::VectorXd& x, double min_efficacy) {
  std::vector<LinearCut> cuts;
  for (const ProbedBinary& b : probing.binaries) {
    for (bool when_one : {true, false}) {
      for (const ImpliedBound& ib : when_one ? b.when_one : b.when_zero) {
        if (p.is_integer[ib.variable]) continue;
        std::optional<LinearCut> cut = ImpliedBoundCut(ib, b.z, when_one, lower, upper, x);
        if (cut && cut->efficacy >= min_efficacy) cuts.push_back(std::move(*cut));
      }
    }
  }
  std::sort(cuts.begin(), cuts.end(), [](const LinearCut& a, const LinearCut& b) { return a.efficacy > b.efficacy; });
  return cuts;
}

std::vector<LinearCut> SeparateCliqueCuts(const RootProbing& probing, const Eigen::VectorXd& x, double min_efficacy) {
  constexpr double kPositive = 1e-6;  // a binary counts as fractional or one above this
  std::unordered_map<int, const ProbedBinary*> by_variable;
  for (const ProbedBinary& b : probing.binaries) by_variable[b.z] = &b;
  std::vector<const ProbedBinary*> starts;
  for (const ProbedBinary& b : probing.binaries) {
    if (x(b.z) > kPositive && x(b.z) < 1.0 - kPositive && !b.conflicts.empty()) starts.push_back(&b);
  }
  std::sort(starts.begin(), starts.end(), [&x](const ProbedBinary* a, const ProbedBinary* b) { return x(a->z) > x(b->z); });
  std::vector<std::vector<int>> seen;
  std::vector<LinearCut> cuts;
  for (const ProbedBinary* start : starts) {
    // Neighbours by decreasing value: the positive ones make the violation, the rest
    // only strengthen the cut.
    std::vector<int> candidates = start->conflicts;
    std::stable_sort(candidates.begin(), candidates.end(), [&x](int a, int b) { return x(a) > x(b); });
    std::vector<const ProbedBinary*> clique = {start};
    for (int v : candidates) {
      const auto it = by_variable.find(v);
      if (it == by_variable.end()) continue;
      if (std::all_of(clique.begin(), clique.end(), [v](const ProbedBinary* m) { return InConflict(*m, v); })) {
        clique.push_back(it->second);
      }
    }
    std::vector<int> members;
    double sum = 0.0;
    for (const ProbedBinary* m : clique) members.push_back(m->z), sum += x(m->z);
    std::sort(members.begin(), members.end());
    if (members.size() < 2 || (sum - 1.0) / std::sqrt(static_cast<double>(members.size())) < min_efficacy) continue;
    if (std::find(seen.begin(), seen.end(), members) != seen.end()) continue;
    seen.push_back(members);
    LinearCut cut;
    for (int m : members) cut.coefficients.push_back({m, 1.0});
    cut.rhs = 1.0;
    cuts.push_back(Finish(std::move(cut), x));
  }
  std::sort(cuts.begin(), cuts.end(), [](const LinearCut& a, const LinearCut& b) { return a.efficacy > b.efficacy; });
  return cuts;
}

}  // namespace mfp
