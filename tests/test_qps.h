#pragma once
// Small QPs solved by hand, shared by the relaxation solver tests.
#include <string>
#include <vector>

#include "planner/miqp/miqp_builder.h"

namespace mfp {

// min (x - target_x)^2 + (y - target_y)^2  s.t.  x + y <= 2, x, y in [lo, hi]: the point
// of the box below the line nearest the target.
inline Miqp NearestPointBelowTheLine(double target_x, double target_y, double lo, double hi) {
  MiqpBuilder b;
  const int x = b.AddVariable("x", lo, hi, false), y = b.AddVariable("y", lo, hi, false);
  b.AddSquaredCost(LinExpr::Var(x) - LinExpr::Constant(target_x), 1.0);
  b.AddSquaredCost(LinExpr::Var(y) - LinExpr::Constant(target_y), 1.0);
  b.AddRow("sum", LinExpr::Var(x) + LinExpr::Var(y), -kInfinity, 2.0);
  return b.Build();
}

// min (x - 2)^2 + (y - 1)^2  s.t.  x + y <= 2, x, y in [-5, 5].
// The unconstrained optimum (2, 1) violates x + y <= 2; projecting it onto x + y = 2
// gives (1.5, 0.5) with cost 0.25 + 0.25 = 0.5.
inline Miqp Projection() { return NearestPointBelowTheLine(2.0, 1.0, -5.0, 5.0); }

// min (y - 2)^2 over x in {0, 1} (variable 0), y in [0, 2] (variable 1), with rows that a
// node fixing x = 1 makes redundant or one-sided:
//   big_m:  y + 2x <= 5       -> y <= 3: the box keeps it
//   loose:  y - x >= -5       -> y >= -4: the box keeps it
//   range:  0.5 <= y + x <= 10 -> -0.5 <= y <= 9: the box keeps both sides
//   cap:    -3 <= y + x <= 2.5 -> y <= 1.5 binds; its lower side y >= -4 does not
// At x = 1 the optimum is y = 1.5 with cost 0.25.
inline Miqp RowsTheBoxMostlyKeeps() {
  MiqpBuilder b;
  const int x = b.AddVariable("x", 0, 1, true), y = b.AddVariable("y", 0, 2, false);
  b.AddRow("big_m", LinExpr::Var(y) + LinExpr::Var(x, 2.0), -kInfinity, 5.0);
  b.AddRow("loose", LinExpr::Var(y) - LinExpr::Var(x), -5.0, kInfinity);
  b.AddRow("range", LinExpr::Var(y) + LinExpr::Var(x), 0.5, 10.0);
  b.AddRow("cap", LinExpr::Var(y) + LinExpr::Var(x), -3.0, 2.5);
  b.AddSquaredCost(LinExpr::Var(y) - LinExpr::Constant(2.0), 1.0);
  return b.Build();
}

// A chain of `feet` positions y_i in [0, 10], each in one of three intervals chosen by a
// one-of group with big-M rows, consecutive feet at most 1.2 apart, each drawn to a target
// between the intervals: the relaxation spreads every group's weight, so the search
// branches along the chain over many nodes.
inline Miqp IntervalChain(int feet) {
  MiqpBuilder b;
  const std::vector<double> lo = {0.0, 3.5, 7.0}, hi = {2.0, 5.0, 10.0};
  const double kBigM = 10.0;
  int previous = -1;
  for (int i = 0; i < feet; ++i) {
    const std::string foot = "y" + std::to_string(i);
    const int y = b.AddVariable(foot, 0.0, 10.0, false);
    LinExpr one;
    std::vector<int> group;
    for (size_t k = 0; k < lo.size(); ++k) {
      const int h = b.AddBinary(foot + "_h" + std::to_string(k));
      group.push_back(h);
      one += LinExpr::Var(h);
      b.AddRow(foot + "_lo" + std::to_string(k), LinExpr::Var(y) - LinExpr::Var(h, kBigM), lo[k] - kBigM, kInfinity);
      b.AddRow(foot + "_hi" + std::to_string(k), LinExpr::Var(y) + LinExpr::Var(h, kBigM), -kInfinity, hi[k] + kBigM);
      b.AddLinearCost(LinExpr::Var(h, 0.05 * static_cast<double>((i + k) % 3)));
    }
    b.AddRow(foot + "_one", one, 1, 1);
    b.AddSos1Group(group);
    if (previous >= 0) b.AddRow(foot + "_reach", LinExpr::Var(y) - LinExpr::Var(previous), -1.2, 1.2);
    const double target = (i % 2 == 0) ? 2.8 : 6.0;
    b.AddSquaredCost(LinExpr::Var(y) - LinExpr::Constant(target), 1.0);
    previous = y;
  }
  return b.Build();
}

}  // namespace mfp
