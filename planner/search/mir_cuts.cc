#include "planner/search/internal/mir_cuts.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "base/check.h"

namespace mfp {
namespace {

constexpr double kTinyCoefficient = 1e-12;
// The MIR's rounding needs the right-hand side's fractional part away from 0 and 1: close
// to either, the cut is numerically the base inequality itself.
constexpr double kMinFraction = 0.01;
constexpr double kMaxFraction = 0.99;
constexpr int kMaxDivisors = 8;        // distinct integer coefficients tried as divisors
constexpr int kDivisorHalvings = 3;    // the best divisor is also tried halved this often
// A cut's right-hand side is loosened by this (relative) so that rounding errors in its
// arithmetic cannot cut off a feasible point.
constexpr double kRhsSafety = 1e-9;

// x_j <= offset + slope * x_z (an upper variable bound) or >= (a lower one), read off a
// row with exactly the continuous x_j and the integer x_z (a region's big-M row).
struct VariableBound {
  double offset;
  double slope;
  int z;
  int row;  // the row it is read off
};
struct VariableBounds {
  std::vector<std::vector<VariableBound>> lower, upper;  // per variable
  std::vector<int> group_of;  // the problem's one-of group of each variable, -1: none
};

VariableBounds FindVariableBounds(const Miqp& p, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) {
  VariableBounds vb;
  vb.lower.resize(p.num_variables());
  vb.upper.resize(p.num_variables());
  vb.group_of.assign(p.num_variables(), -1);
  for (size_t g = 0; g < p.sos1_groups.size(); ++g) {
    for (int j : p.sos1_groups[g]) vb.group_of[j] = static_cast<int>(g);
  }
  for (int i = 0; i < p.num_rows(); ++i) {
    if (p.A.row(i).nonZeros() != 2) continue;
    Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(p.A, i);
    int j = static_cast<int>(it.col());
    double a = it.value();
    ++it;
    int z = static_cast<int>(it.col());
    double b = it.value();
    if (p.is_integer[j]) std::swap(j, z), std::swap(a, b);
    if (p.is_integer[j] || !p.is_integer[z] || std::abs(a) <= kTinyCoefficient) continue;
    if (!std::isfinite(lower(z)) || !std::isfinite(upper(z))) continue;
    // a x_j + b x_z <= row_upper, >= row_lower: x_j against (bound - b x_z) / a.
    for (int side : {1, -1}) {
      const double bound = side > 0 ? p.row_upper(i) : p.row_lower(i);
      if (!std::isfinite(bound)) continue;
      const bool gives_upper = (side > 0) == (a > 0.0);
      (gives_upper ? vb.upper : vb.lower)[j].push_back({bound / a, -b / a, z, i});
    }
  }
  return vb;
}

// A base inequality sum_j value[j] x_j <= rhs, dense over the variables with the list of
// those touched (cheap to clear).
class Aggregate {
 public:
  explicit Aggregate(int n) : value_(Eigen::VectorXd::Zero(n)), touched_(n, false) {}

  void Clear() {
    for (int j : support_) {
      value_(j) = 0.0;
      touched_[j] = false;
    }
    support_.clear();
    rhs_ = 0.0;
  }
  // Adds multiplier * (side * row i <= side's bound); side +1: the row's upper bound,
  // -1: its lower bound (multiplied by -1 to read as <=).
  void AddRow(const Miqp& p, int i, int side, double multiplier) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(p.A, i); it; ++it) {
      Add(static_cast<int>(it.col()), multiplier * side * it.value());
    }
    rhs_ += multiplier * (side > 0 ? p.row_upper(i) : -p.row_lower(i));
  }
  void Cancel(int j) { value_(j) = 0.0; }
  double value(int j) const { return value_(j); }
  double rhs() const { return rhs_; }
  const std::vector<int>& support() const { return support_; }

 private:
  void Add(int j, double v) {
    if (!touched_[j]) {
      touched_[j] = true;
      support_.push_back(j);
    }
    value_(j) += v;
  }
  Eigen::VectorXd value_;
  std::vector<bool> touched_;
  std::vector<int> support_;
  double rhs_ = 0.0;
};

// A variable of the base inequality after the shift to a bound:
//   x_j = offset + slope * x_z + t (at_upper false) or x_j = offset + slope * x_z - t
//   (at_upper true), t >= 0,
// with coefficient `coefficient` on t. Integers and simple bounds have slope 0; a
// continuous variable may be shifted to a variable bound (z >= 0: the binary of a
// two-variable row such as a region's big-M row), which moves slope * x_z into the
// integer part of the row: the MIR then rounds it.
struct Shifted {
  int j;
  bool at_upper;
  double offset;
  double coefficient;
  double t_star;  // t at the separated point
  double slope = 0.0;
  int z = -1;
};

struct ShiftedRow {
  std::vector<Shifted> integers;
  std::vector<Shifted> continuous;  // only those with negative coefficient (the rest are dropped)
  double rhs = 0.0;
};

double Fraction(double v) { return v - std::floor(v); }

// The bound a continuous variable is shifted to on one side: the simple bound, or the
// variable bound nearest to x there.
struct SideBound {
  double offset = kInfinity;
  double slope = 0.0;
  int z = -1;
  double distance = kInfinity;  // |x_j - bound| at the point
};

// Variable bounds read off a row of the aggregate itself are skipped: substituting a row
// into itself gives nothing to round.
SideBound NearestBound(const VariableBounds& vb, int j, bool at_upper, const Eigen::VectorXd& lower,
                       const Eigen::VectorXd& upper, const Eigen::VectorXd& x, const std::vector<int>& used) {
  SideBound best;
  const double simple = at_upper ? upper(j) : lower(j);
  if (std::isfinite(simple)) best = {simple, 0.0, -1, std::abs(simple - x(j))};
  for (const VariableBound& b : at_upper ? vb.upper[j] : vb.lower[j]) {
    if (std::find(used.begin(), used.end(), b.row) != used.end()) continue;
    const double value = b.offset + b.slope * x(b.z);
    const double distance = at_upper ? value - x(j) : x(j) - value;
    if (distance >= -1e-9 && distance < best.distance - 1e-9) best = {b.offset, b.slope, b.z, std::max(distance, 0.0)};
  }
  return best;
}

// Adds to the row, for each one-of group it touches, the group's equality sum = 1 times
// minus the member coefficient of largest magnitude: that member leaves the row and the
// others take its complement (how "x <= u_r + M (1 - H_r)" becomes "x <= u_r + M sum of
// the other H"). terms: sorted by variable, may repeat a variable.
void CancelInGroups(const Miqp& p, const VariableBounds& vb, std::vector<std::pair<int, double>>* terms, double* rhs) {
  std::vector<std::pair<int, double>> largest;  // (group, coefficient of largest magnitude)
  for (size_t k = 0; k < terms->size();) {
    const int j = (*terms)[k].first;
    double a = 0.0;
    for (; k < terms->size() && (*terms)[k].first == j; ++k) a += (*terms)[k].second;
    const int g = vb.group_of[j];
    if (g < 0 || std::abs(a) <= kTinyCoefficient) continue;
    auto it = std::find_if(largest.begin(), largest.end(), [g](const auto& e) { return e.first == g; });
    if (it == largest.end()) {
      largest.push_back({g, a});
    } else if (std::abs(a) > std::abs(it->second)) {
      it->second = a;
    }
  }
  for (const auto& [g, a] : largest) {
    for (int j : p.sos1_groups[g]) terms->push_back({j, -a});
    *rhs -= a;
  }
  std::sort(terms->begin(), terms->end());
}

// Shifts every variable of the aggregate to its nearer usable bound, continuous ones
// possibly to variable bounds. Empty when an integer lacks a finite bound or a continuous
// variable lacks a finite one on the side it needs.
std::optional<ShiftedRow> Shift(const Miqp& p, const VariableBounds& vb, const Aggregate& agg,
                                const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, const Eigen::VectorXd& x,
                                const std::vector<int>& used, bool cancel_in_groups) {
  ShiftedRow row;
  row.rhs = agg.rhs();
  std::vector<std::pair<int, double>> integer_terms;
  for (int j : agg.support()) {
    const double a = agg.value(j);
    if (std::abs(a) <= kTinyCoefficient) continue;
    if (p.is_integer[j]) {
      integer_terms.push_back({j, a});
      continue;
    }
    const SideBound lo = NearestBound(vb, j, false, lower, upper, x, used);
    const SideBound up = NearestBound(vb, j, true, lower, upper, x, used);
    if (!std::isfinite(lo.offset) && !std::isfinite(up.offset)) return std::nullopt;
    const bool at_upper = up.distance < lo.distance;
    const SideBound& b = at_upper ? up : lo;
    // a x_j = a offset + a slope x_z + (at_upper ? -a : a) t
    row.rhs -= a * b.offset;
    if (b.z >= 0) integer_terms.push_back({b.z, a * b.slope});
    const double coefficient = at_upper ? -a : a;
    if (coefficient < 0.0) row.continuous.push_back({j, at_upper, b.offset, coefficient, b.distance, b.slope, b.z});
  }
  std::sort(integer_terms.begin(), integer_terms.end());
  if (cancel_in_groups) CancelInGroups(p, vb, &integer_terms, &row.rhs);
  for (size_t k = 0; k < integer_terms.size();) {
    const int j = integer_terms[k].first;
    double a = 0.0;
    for (; k < integer_terms.size() && integer_terms[k].first == j; ++k) a += integer_terms[k].second;
    if (std::abs(a) <= kTinyCoefficient) continue;
    if (!std::isfinite(lower(j)) || !std::isfinite(upper(j))) return std::nullopt;
    const bool at_upper = upper(j) - x(j) < x(j) - lower(j);
    const double bound = at_upper ? upper(j) : lower(j);
    row.rhs -= a * bound;
    row.integers.push_back({j, at_upper, bound, at_upper ? -a : a, at_upper ? bound - x(j) : x(j) - bound});
  }
  return row;
}

// The MIR of the shifted row divided by delta, in the shifted variables: its violation at
// the point per unit coefficient norm (the shift keeps coefficient magnitudes), or
// -infinity when the divisor gives no cut.
double MirEfficacy(const ShiftedRow& row, double delta) {
  const double beta = row.rhs / delta;
  const double f0 = Fraction(beta);
  if (f0 < kMinFraction || f0 > kMaxFraction) return -kInfinity;
  double activity = 0.0, norm2 = 0.0;
  for (const Shifted& v : row.integers) {
    const double g = v.coefficient / delta;
    const double pi = std::floor(g) + std::max(0.0, Fraction(g) - f0) / (1.0 - f0);
    activity += pi * v.t_star;
    norm2 += pi * pi;
  }
  for (const Shifted& v : row.continuous) {
    const double mu = v.coefficient / (delta * (1.0 - f0));
    activity += mu * v.t_star;
    norm2 += mu * mu;
  }
  if (norm2 <= 0.0) return -kInfinity;
  return (activity - std::floor(beta)) / std::sqrt(norm2);
}

// The cut of the shifted row and divisor in the original variables, with tiny
// coefficients removed safely and the whole scaled to a largest |coefficient| of 1.
std::optional<LinearCut> MirCut(const ShiftedRow& row, double delta, const Eigen::VectorXd& lower,
                                const Eigen::VectorXd& upper, const MirSeparationOptions& options) {
  const double beta = row.rhs / delta;
  const double f0 = Fraction(beta);
  LinearCut cut;
  cut.rhs = std::floor(beta);
  // Coefficient c on t = sigma (x_j - offset - slope x_z), sigma = -1 at the upper bound.
  std::vector<std::pair<int, double>> terms;
  const auto add = [&cut, &terms](const Shifted& v, double c) {
    if (c == 0.0) return;
    const double sc = v.at_upper ? -c : c;
    terms.push_back({v.j, sc});
    if (v.z >= 0) terms.push_back({v.z, -sc * v.slope});
    cut.rhs += sc * v.offset;
  };
  for (const Shifted& v : row.integers) {
    const double g = v.coefficient / delta;
    add(v, std::floor(g) + std::max(0.0, Fraction(g) - f0) / (1.0 - f0));
  }
  for (const Shifted& v : row.continuous) add(v, v.coefficient / (delta * (1.0 - f0)));
  std::sort(terms.begin(), terms.end());
  for (size_t k = 0; k < terms.size();) {
    const int j = terms[k].first;
    double c = 0.0;
    for (; k < terms.size() && terms[k].first == j; ++k) c += terms[k].second;
    if (c != 0.0) cut.coefficients.push_back({j, c});
  }
  double largest = 0.0;
  for (const auto& [j, c] : cut.coefficients) largest = std::max(largest, std::abs(c));
  if (largest <= 0.0) return std::nullopt;
  std::vector<std::pair<int, double>> kept;
  for (const auto& [j, c] : cut.coefficients) {
    if (std::abs(c) * options.max_coefficient_ratio < largest) {
      // c x_j >= min(c lower, c upper): moving it to the right-hand side keeps the cut valid.
      const double least = std::min(c * lower(j), c * upper(j));
      if (!std::isfinite(least)) return std::nullopt;
      cut.rhs -= least;
      continue;
    }
    kept.push_back({j, c / largest});
  }
  cut.coefficients = std::move(kept);
  cut.rhs /= largest;
  cut.rhs += kRhsSafety * std::max(1.0, std::abs(cut.rhs));
  return cut;
}

std::optional<LinearCut> BestMirOfShift(const std::optional<ShiftedRow>& row, const Eigen::VectorXd& lower,
                                        const Eigen::VectorXd& upper, const Eigen::VectorXd& x,
                                        const MirSeparationOptions& options);

// The best c-MIR cut of one base inequality, as it is or with its one-of groups' members
// cancelled (CancelInGroups), or none.
std::optional<LinearCut> BestMir(const Miqp& p, const VariableBounds& vb, const Aggregate& agg, const std::vector<int>& used,
                                 const Eigen::VectorXd& lower,
                                 const Eigen::VectorXd& upper, const Eigen::VectorXd& x,
                                 const MirSeparationOptions& options) {
  std::optional<LinearCut> best;
  for (bool cancel_in_groups : {false, true}) {
    std::optional<LinearCut> cut = BestMirOfShift(Shift(p, vb, agg, lower, upper, x, used, cancel_in_groups), lower,
                                                  upper, x, options);
    if (cut && (!best || cut->efficacy > best->efficacy)) best = std::move(cut);
  }
  return best;
}

std::optional<LinearCut> BestMirOfShift(const std::optional<ShiftedRow>& row, const Eigen::VectorXd& lower,
                                        const Eigen::VectorXd& upper, const Eigen::VectorXd& x,
                                        const MirSeparationOptions& options) {
  if (!row) return std::nullopt;
  std::vector<double> divisors;
  for (const Shifted& v : row->integers) {
    const double d = std::abs(v.coefficient);
    if (v.t_star <= 1e-6 || v.t_star >= (upper(v.j) - lower(v.j)) - 1e-6 || d <= kTinyCoefficient) continue;
    if (std::none_of(divisors.begin(), divisors.end(), [d](double e) { return std::abs(d - e) <= 1e-9 * d; })) {
      divisors.push_back(d);
    }
    if (static_cast<int>(divisors.size()) >= kMaxDivisors) break;
  }
  if (divisors.empty()) return std::nullopt;
  double best_delta = 0.0, best = -kInfinity;
  for (double d : divisors) {
    const double e = MirEfficacy(*row, d);
    if (e > best) best = e, best_delta = d;
  }
  if (best_delta <= 0.0) return std::nullopt;
  const double base_delta = best_delta;
  for (int k = 1, scale = 2; k <= kDivisorHalvings; ++k, scale *= 2) {
    const double e = MirEfficacy(*row, base_delta / scale);
    if (e > best) best = e, best_delta = base_delta / scale;
  }
  if (best < options.min_efficacy) return std::nullopt;
  std::optional<LinearCut> cut = MirCut(*row, best_delta, lower, upper, options);
  if (!cut) return std::nullopt;
  double norm2 = 0.0;
  for (const auto& [j, c] : cut->coefficients) norm2 += c * c;
  cut->efficacy = (cut->Activity(x) - cut->rhs) / std::sqrt(norm2);
  if (cut->efficacy < options.min_efficacy) return std::nullopt;
  return cut;
}

// The row (other than those used) that cancels continuous variable j from the aggregate
// with a positive multiplier and is nearest to tight at x: (row, side, slack).
struct AggregationRow {
  int row = -1;
  int side = 0;
};

AggregationRow FindAggregationRow(const Miqp& p, const Eigen::SparseMatrix<double>& columns, const Eigen::VectorXd& ax,
                                  const std::vector<int>& used, int j, double aj,
                                  const MirSeparationOptions& options) {
  AggregationRow best;
  double best_slack = kInfinity;
  for (Eigen::SparseMatrix<double>::InnerIterator it(columns, j); it; ++it) {
    const int r = static_cast<int>(it.row());
    if (std::abs(it.value()) <= kTinyCoefficient || std::find(used.begin(), used.end(), r) != used.end()) continue;
    // multiplier * side * a_rj = -aj with multiplier > 0.
    const int side = aj * it.value() > 0.0 ? -1 : 1;
    const double bound = side > 0 ? p.row_upper(r) : p.row_lower(r);
    if (!std::isfinite(bound)) continue;
    const double slack = side > 0 ? bound - ax(r) : ax(r) - bound;
    if (slack > options.max_aggregation_slack || slack >= best_slack) continue;
    best_slack = slack;
    best = {r, side};
  }
  return best;
}

// Adds to the aggregate a row that cancels one of its continuous variables lying
// inside its bounds (the one farthest from them first); false when none can be cancelled.
bool AggregateOneMore(const Miqp& p, const Eigen::SparseMatrix<double>& columns, const Eigen::VectorXd& ax,
                      const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, const Eigen::VectorXd& x,
                      const MirSeparationOptions& options, std::vector<int>* used, Aggregate* agg) {
  std::vector<std::pair<double, int>> candidates;  // (distance to the nearer bound, variable)
  for (int j : agg->support()) {
    if (p.is_integer[j] || std::abs(agg->value(j)) <= kTinyCoefficient) continue;
    const double distance = std::min(x(j) - lower(j), upper(j) - x(j));
    if (distance > options.min_bound_distance) candidates.push_back({distance, j});
  }
  std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (const auto& [distance, j] : candidates) {
    const double aj = agg->value(j);
    const AggregationRow found = FindAggregationRow(p, columns, ax, *used, j, aj, options);
    if (found.row < 0) continue;
    const double a_rj = p.A.coeff(found.row, j);
    agg->AddRow(p, found.row, found.side, -aj / (found.side * a_rj));
    agg->Cancel(j);
    used->push_back(found.row);
    return true;
  }
  return false;
}

// The value of the upper (at_upper) or lower variable bound of x_j over member z's
// choice (z = 1) for the members of group g, keyed by member; NaN: no such bound.
struct GroupBound {
  int member;
  double value;
};

std::vector<GroupBound> BoundsOverGroup(const VariableBounds& vb, int j, int g, bool at_upper,
                                        const Eigen::VectorXd& lower, const Eigen::VectorXd& upper) {
  std::vector<GroupBound> bounds;
  for (const VariableBound& b : at_upper ? vb.upper[j] : vb.lower[j]) {
    if (vb.group_of[b.z] != g || lower(b.z) != 0.0 || upper(b.z) != 1.0) continue;
    const double value = b.offset + b.slope;
    auto it = std::find_if(bounds.begin(), bounds.end(), [&b](const GroupBound& e) { return e.member == b.z; });
    if (it == bounds.end()) {
      bounds.push_back({b.z, value});
    } else {
      it->value = at_upper ? std::min(it->value, value) : std::max(it->value, value);
    }
  }
  return bounds;
}

// x_j <= U - sum_r (U - u_r) z_r (or the mirror for lower bounds) for one variable, one
// group and one side, when violated.
std::optional<LinearCut> GroupBoundCut(const VariableBounds& vb, int j, int g, bool at_upper,
                                       const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                       const Eigen::VectorXd& x, double min_efficacy) {
  const double outer = at_upper ? upper(j) : lower(j);
  if (!std::isfinite(outer)) return std::nullopt;
  const double sign = at_upper ? 1.0 : -1.0;  // the cut read as sign * x_j + ... <= sign * outer
  LinearCut cut;
  cut.coefficients.push_back({j, sign});
  cut.rhs = sign * outer;
  for (const GroupBound& b : BoundsOverGroup(vb, j, g, at_upper, lower, upper)) {
    const double tightening = sign * (outer - b.value);  // how much member r lowers the bound
    if (tightening > kTinyCoefficient) cut.coefficients.push_back({b.member, tightening});
  }
  if (cut.coefficients.size() < 2) return std::nullopt;
  std::sort(cut.coefficients.begin(), cut.coefficients.end());
  double largest = 0.0, norm2 = 0.0;
  for (const auto& [k, c] : cut.coefficients) largest = std::max(largest, std::abs(c));
  for (auto& [k, c] : cut.coefficients) {
    c /= largest;
    norm2 += c * c;
  }
  cut.rhs /= largest;
  cut.rhs += kRhsSafety * std::max(1.0, std::abs(cut.rhs));
  cut.efficacy = (cut.Activity(x) - cut.rhs) / std::sqrt(norm2);
  if (cut.efficacy < min_efficacy) return std::nullopt;
  return cut;
}

}  // namespace

std::vector<LinearCut> SeparateGroupBoundCuts(const Miqp& p, const Eigen::VectorXd& lower,
                                              const Eigen::VectorXd& upper, const Eigen::VectorXd& x,
                                              double min_efficacy) {
  const VariableBounds vb = FindVariableBounds(p, lower, upper);
  std::vector<LinearCut> cuts;
  for (int j = 0; j < p.num_variables(); ++j) {
    if (p.is_integer[j]) continue;
    for (bool at_upper : {true, false}) {
      std::vector<int> groups;
      for (const VariableBound& b : at_upper ? vb.upper[j] : vb.lower[j]) {
        const int g = vb.group_of[b.z];
        if (g >= 0 && std::find(groups.begin(), groups.end(), g) == groups.end()) groups.push_back(g);
      }
      for (int g : groups) {
        if (std::optional<LinearCut> cut = GroupBoundCut(vb, j, g, at_upper, lower, upper, x, min_efficacy)) {
          cuts.push_back(std::move(*cut));
        }
      }
    }
  }
  std::sort(cuts.begin(), cuts.end(), [](const LinearCut& a, const LinearCut& b) { return a.efficacy > b.efficacy; });
  return cuts;
}

double LinearCut::Activity(const Eigen::VectorXd& x) const {
  double sum = 0.0;
  for (const auto& [j, c] : coefficients) sum += c * x(j);
  return sum;
}

std::vector<LinearCut> SeparateMirCuts(const Miqp& p, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                       const Eigen::VectorXd& x, const MirSeparationOptions& options) {
  const int n = p.num_variables();
  MFP_CHECK(lower.size() == n && upper.size() == n && x.size() == n);
  const Eigen::SparseMatrix<double> columns = p.A;  // column access for the aggregation
  const Eigen::VectorXd ax = p.A * x;
  const VariableBounds vb = FindVariableBounds(p, lower, upper);
  Aggregate agg(n);
  std::vector<LinearCut> cuts;
  std::vector<int> used;
  for (int i = 0; i < p.num_rows(); ++i) {
    for (int side : {1, -1}) {
      if (!std::isfinite(side > 0 ? p.row_upper(i) : p.row_lower(i))) continue;
      agg.Clear();
      agg.AddRow(p, i, side, 1.0);
      used.assign(1, i);
      for (int step = 0;; ++step) {
        if (std::optional<LinearCut> cut = BestMir(p, vb, agg, used, lower, upper, x, options)) {
          cuts.push_back(std::move(*cut));
          break;
        }
        if (step >= options.max_aggregations ||
            !AggregateOneMore(p, columns, ax, lower, upper, x, options, &used, &agg)) {
          break;
        }
      }
    }
  }
  std::sort(cuts.begin(), cuts.end(), [](const LinearCut& a, const LinearCut& b) { return a.efficacy > b.efficacy; });
  return cuts;
}

}  // namespace mfp
