// Probing over one-of groups on a hand-built MIQP: a foot coordinate x in [0, 10] stands
// on one of three stones [1, 2], [4, 5], [8, 9] (big-M rows, M = 10), H0 + H1 + H2 = 1.
// Row-by-row propagation leaves x in [0, 10] while the H are open; probing gives the hull
// of the stones still open, and rules out a stone that another row excludes.
#include "planner/search/internal/group_probing.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "planner/miqp/miqp_builder.h"
#include "planner/search/internal/bound_propagation.h"

namespace mfp {
namespace {

constexpr double kTol = 1e-6;

// extra_x_min: a row x >= extra_x_min (0: none that binds).
Miqp ThreeStones(double extra_x_min) {
  const double M = 10.0;
  const double stones[3][2] = {{1.0, 2.0}, {4.0, 5.0}, {8.0, 9.0}};
  MiqpBuilder b;
  const int x = b.AddVariable("x", 0.0, 10.0, false);
  std::vector<int> h;
  for (int r = 0; r < 3; ++r) h.push_back(b.AddBinary("H" + std::to_string(r)));
  for (int r = 0; r < 3; ++r) {
    const std::string stone = "stone" + std::to_string(r);
    const LinExpr big_m = LinExpr::Var(h[r], M);
    b.AddRow(stone + "_max", LinExpr::Var(x) + big_m, -kInfinity, stones[r][1] + M);         // x <= max + M (1 - H)
    b.AddRow(stone + "_min", LinExpr::Var(x, -1.0) + big_m, -kInfinity, -stones[r][0] + M);  // x >= min - M (1 - H)
  }
  b.AddRow("one_stone", LinExpr::Var(h[0]) + LinExpr::Var(h[1]) + LinExpr::Var(h[2]), 1.0, 1.0);
  b.AddRow("x_min", LinExpr::Var(x), extra_x_min, kInfinity);
  b.AddSos1Group(h);
  return b.Build();
}

TEST(GroupProbing, AFootIsBoundedByTheHullOfTheStonesItMayStillUse) {
  const Miqp p = ThreeStones(0.0);
  Eigen::VectorXd lower = p.var_lower, upper = p.var_upper;
  ASSERT_FALSE(PropagateBounds(p, &lower, &upper).infeasible);
  EXPECT_NEAR(lower(0), 0.0, kTol);  // propagation alone: nothing
  EXPECT_NEAR(upper(0), 10.0, kTol);
  const GroupProbingResult r = GroupProber(p).Probe(&lower, &upper);
  EXPECT_FALSE(r.infeasible);
  EXPECT_EQ(r.members_ruled_out, 0);
  EXPECT_NEAR(lower(0), 1.0, kTol);
  EXPECT_NEAR(upper(0), 9.0, kTol);

  // The far stone ruled out by a branch: x within the first two stones.
  lower = p.var_lower;
  upper = p.var_upper;
  upper(3) = 0.0;
  ASSERT_FALSE(GroupProber(p).Probe(&lower, &upper).infeasible);
  EXPECT_NEAR(lower(0), 1.0, kTol);
  EXPECT_NEAR(upper(0), 5.0, kTol);
}

TEST(GroupProbing, StonesAnotherRowExcludesAreRuledOutAndTheLastOneIsChosen) {
  const Miqp p = ThreeStones(6.0);  // x >= 6: only the third stone
  Eigen::VectorXd lower = p.var_lower, upper = p.var_upper;
  const GroupProbingResult r = GroupProber(p).Probe(&lower, &upper);
  EXPECT_FALSE(r.infeasible);
  EXPECT_EQ(r.members_ruled_out, 2);
  EXPECT_EQ(upper(1), 0.0);
  EXPECT_EQ(upper(2), 0.0);
  EXPECT_EQ(lower(3), 1.0);
  EXPECT_NEAR(lower(0), 8.0, kTol);
  EXPECT_NEAR(upper(0), 9.0, kTol);
}

TEST(GroupProbing, AGroupWithNoFeasibleMemberMakesTheNodeInfeasible) {
  const Miqp p = ThreeStones(6.0);
  Eigen::VectorXd lower = p.var_lower, upper = p.var_upper;
  upper(3) = 0.0;  // the only stone the row allows is ruled out
  EXPECT_TRUE(GroupProber(p).Probe(&lower, &upper).infeasible);
}

// Two feet, each on one of three stones: x0 with the group H0..H2 (group 0), x1 with
// H3..H5 (group 1).
Miqp TwoFeet() {
  const double M = 10.0;
  const double stones[3][2] = {{1.0, 2.0}, {4.0, 5.0}, {8.0, 9.0}};
  MiqpBuilder b;
  for (int foot = 0; foot < 2; ++foot) b.AddVariable("x" + std::to_string(foot), 0.0, 10.0, false);
  for (int foot = 0; foot < 2; ++foot) {
    std::vector<int> h;
    LinExpr one;
    for (int r = 0; r < 3; ++r) {
      h.push_back(b.AddBinary("H" + std::to_string(foot) + std::to_string(r)));
      one += LinExpr::Var(h.back());
      const std::string stone = "foot" + std::to_string(foot) + "_stone" + std::to_string(r);
      const LinExpr big_m = LinExpr::Var(h[r], M);
      b.AddRow(stone + "_max", LinExpr::Var(foot) + big_m, -kInfinity, stones[r][1] + M);
      b.AddRow(stone + "_min", LinExpr::Var(foot, -1.0) + big_m, -kInfinity, -stones[r][0] + M);
    }
    b.AddRow("foot" + std::to_string(foot) + "_one_stone", one, 1.0, 1.0);
    b.AddSos1Group(h);
  }
  return b.Build();
}

TEST(GroupProbing, ASpentWorkCapOrAnExpiredDeadlineStopsTheSweepBeforeAnyGroup) {
  const Miqp p = TwoFeet();
  const GroupProber prober(p);
  GroupProbingLimits no_work;
  no_work.max_row_visits = 0;
  GroupProbingLimits expired;
  expired.deadline = Deadline::After(0.0);
  for (const GroupProbingLimits& limits : {no_work, expired}) {
    Eigen::VectorXd lower = p.var_lower, upper = p.var_upper;
    const GroupProbingResult r = prober.Probe(&lower, &upper, limits);
    EXPECT_TRUE(r.stopped);
    EXPECT_EQ(r.probes, 0);
    EXPECT_EQ(lower, p.var_lower);
    EXPECT_EQ(upper, p.var_upper);
  }
}

TEST(GroupProbing, UnderACapTheCentreGroupIsProbedFirst) {
  const Miqp p = TwoFeet();
  const GroupProber prober(p);
  for (int centre : {0, 1}) {
    SCOPED_TRACE(centre);
    GroupProbingLimits limits;
    limits.max_row_visits = 1;  // spent by the first group's cases
    limits.centre_group = centre;
    Eigen::VectorXd lower = p.var_lower, upper = p.var_upper;
    const GroupProbingResult r = prober.Probe(&lower, &upper, limits);
    EXPECT_TRUE(r.stopped);
    EXPECT_EQ(r.probes, 4);  // none and each of the three stones, of one group
    EXPECT_GE(r.row_visits, 1);
    const int probed = centre, other = 1 - centre;
    EXPECT_NEAR(lower(probed), 1.0, kTol);
    EXPECT_NEAR(upper(probed), 9.0, kTol);
    EXPECT_EQ(lower(other), 0.0);
    EXPECT_EQ(upper(other), 10.0);
  }
  // Without a cap both feet are probed, in either order.
  Eigen::VectorXd lower = p.var_lower, upper = p.var_upper;
  GroupProbingLimits limits;
  limits.centre_group = 1;
  const GroupProbingResult r = prober.Probe(&lower, &upper, limits);
  EXPECT_FALSE(r.stopped);
  EXPECT_EQ(r.probes, 8);
  for (int foot = 0; foot < 2; ++foot) {
    EXPECT_NEAR(lower(foot), 1.0, kTol);
    EXPECT_NEAR(upper(foot), 9.0, kTol);
  }
}

}  // namespace
}  // namespace mfp
