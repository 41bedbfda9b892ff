// Each constraint family of the footstep MIQP checked against a point worked out by hand.
//
// Robot: four legs with nominal offsets o0 = (0.1, 0.1), o1 = (0.1, -0.1),
// o2 = (-0.1, 0.1), o3 = (-0.1, -0.1); gait 0, 1, 2, 3; l_bnd 0.05, d_lim 0.15,
// dz_max 0.1, yaw change 0.3. Regions: r0 = [-0.5, 0.5]^2 at z = 0 and
// r1 = [0.6, 1.5] x [-0.5, 0.5] at z = 0.05. Start: nominal stance at the origin, yaw 0.
// Four new steps (N = 8, configurations 0 and 1); goal (0.5, 0, 0).
//
// The hand-made point: every foot moves 0.1 m forward, yaw 0, all in r0, nothing trimmed:
//   f4 = (0.2, 0.1, 0), f5 = (0.2, -0.1, 0), f6 = (0, 0.1, 0), f7 = (0, -0.1, 0).
// Centres of contacts (mean of the 4 latest feet; before the plan, the start stance):
//   p4 = (0.1 - 0.1 - 0.1 + 0.2) / 4 = 0.025, p5 = 0.05, p6 = 0.075, p7 = 0.1 (y = 0).
#include "planner/formulation/miqp_formulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "base/check.h"
#include "tests/test_robots.h"

namespace mfp {
namespace {

RobotModel TestRobot() {
  RobotModel robot = SquareQuadruped(0.15, 0.05);
  robot.weights.goal_position = 100.0;  // the objective test below is worked out with these
  robot.weights.goal_yaw = 10.0;
  robot.weights.trim_step = -1.0;
  robot.weights.displacement = 1.0;
  return robot;
}

ConvexRegion Square(int id, double x0, double x1, double y0, double y1, double z) {
  return MakeRegionFromPolygon(id, {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}}, 0.0);
}

class FormulationTest : public ::testing::Test {
 protected:
  FormulationTest() : robot_(TestRobot()) {
    problem_.robot = &robot_;
    problem_.regions = {Square(0, -0.5, 0.5, -0.5, 0.5, 0.0), Square(1, 0.6, 1.5, -0.5, 0.5, 0.05)};
    problem_.start_feet_world_m = {{0.1, 0.1, 0}, {0.1, -0.1, 0}, {-0.1, 0.1, 0}, {-0.1, -0.1, 0}};
    problem_.goal_x_m = 0.5;
    problem_.num_new_steps = 4;
    FormulationOptions options;
    options.prune_unreachable_regions = false;  // keep H_i1 for the big-M checks
    options.yaw_encoding = YawEncoding::kBigM;  // the chord rows checked below
    formulation_ = std::make_unique<MiqpFormulation>(problem_, options);
    x_ = HandPoint();
  }

  // The hand-made point described at the top of the file.
  Eigen::VectorXd HandPoint() const {
    const FootstepVariables& v = formulation_->vars();
    Eigen::VectorXd x = Eigen::VectorXd::Zero(formulation_->miqp().num_variables());
    const double feet[4][2] = {{0.2, 0.1}, {0.2, -0.1}, {0.0, 0.1}, {0.0, -0.1}};
    const double coc_x[4] = {0.025, 0.05, 0.075, 0.1};
    for (int k = 0; k < 4; ++k) {
      const int i = 4 + k;
      x(v.x[i]) = feet[k][0];
      x(v.y[i]) = feet[k][1];
      x(v.px[i]) = coc_x[k];
      x(v.region[i][0]) = 1.0;
    }
    x(v.theta[1]) = 0.0;
    x(v.s[1]) = 0.0;
    x(v.c[1]) = 1.0;
    x(v.segment[1][1]) = 1.0;  // theta = 0 is the lower end of segment 1, [0, pi/8]
    return x;
  }

  // Violation of one named row at x: max(lower - a.x, a.x - upper, 0).
  double RowViolation(const std::string& name, const Eigen::VectorXd& x) const {
    const Miqp& m = formulation_->miqp();
    for (int r = 0; r < m.num_rows(); ++r) {
      if (m.row_names[r] != name) continue;
      const double ax = m.A.row(r).dot(x.transpose());
      return std::max({0.0, m.row_lower(r) - ax, ax - m.row_upper(r)});
    }
    ADD_FAILURE() << "no row named " << name;
    return -1.0;
  }

  double MaxViolationOfRowsStarting(const std::string& prefix, const Eigen::VectorXd& x) const {
    const Miqp& m = formulation_->miqp();
    double worst = 0.0;
    int found = 0;
    for (int r = 0; r < m.num_rows(); ++r) {
      if (m.row_names[r].rfind(prefix, 0) != 0) continue;
      ++found;
      worst = std::max(worst, RowViolation(m.row_names[r], x));
    }
    EXPECT_GT(found, 0) << prefix;
    return worst;
  }

  RobotModel robot_;
  FootstepProblem problem_;
  std::unique_ptr<MiqpFormulation> formulation_;
  Eigen::VectorXd x_;
};

TEST_F(FormulationTest, SizesAndGait) {
  EXPECT_EQ(formulation_->num_steps(), 8);
  EXPECT_EQ(formulation_->num_configurations(), 2);
  // yaw range [-pi/8, pi/8] in segments of pi/8: two segments.
  EXPECT_EQ(formulation_->yaw_breakpoints().size(), 3u);
  for (int i = 0; i < 8; ++i) EXPECT_EQ(formulation_->LegOfStep(i), i % 4);
  // Binaries: 4 steps x (2 regions + 1 trim) + 2 segments.
  EXPECT_EQ(formulation_->miqp().num_integer(), 14);
}

TEST_F(FormulationTest, CentreOfContactsDefinitions) {
  for (int i = 4; i < 8; ++i) {
    EXPECT_NEAR(RowViolation("def_px_" + std::to_string(i), x_), 0.0, 1e-12) << i;
    EXPECT_NEAR(RowViolation("def_py_" + std::to_string(i), x_), 0.0, 1e-12) << i;
  }
  // A wrong centre is caught by exactly its error: p4 = 0.03 instead of 0.025.
  Eigen::VectorXd bad = x_;
  bad(formulation_->vars().px[4]) = 0.03;
  EXPECT_NEAR(RowViolation("def_px_4", bad), 0.005, 1e-12);
}

TEST_F(FormulationTest, ReferenceBox) {
  // Step 4 (leg 0): f4.x - (p4.x + o0.x) = 0.2 - (0.025 + 0.1) = 0.075 > l_bnd = 0.05.
  EXPECT_NEAR(RowViolation("ref_x_4", x_), 0.025, 1e-12);
  // y: 0.1 - (0 + 0.1) = 0.
  EXPECT_NEAR(RowViolation("ref_y_4", x_), 0.0, 1e-12);
  // Step 7 (leg 3): 0 - (0.1 - 0.1) = 0 and -0.1 - (0 - 0.1) = 0.
  EXPECT_NEAR(RowViolation("ref_x_7", x_), 0.0, 1e-12);
  EXPECT_NEAR(RowViolation("ref_y_7", x_), 0.0, 1e-12);
}

TEST_F(FormulationTest, ReachabilityFromThePreviousConfiguration) {
  // Step 4 against the nominal foot of step 0: p0 = start centroid (0, 0), so
  // r_nom,0 = (0.1, 0.1); |0.2 - 0.1| = 0.1 <= d_lim = 0.15.
  EXPECT_NEAR(RowViolation("reach_x_4", x_), 0.0, 1e-12);
  // Move f4 to x = 0.3: |0.3 - 0.1| = 0.2 exceeds d_lim by 0.05.
  Eigen::VectorXd far = x_;
  far(formulation_->vars().x[4]) = 0.3;
  EXPECT_NEAR(RowViolation("reach_x_4", far), 0.05, 1e-12);
}

TEST_F(FormulationTest, HeightChange) {
  Eigen::VectorXd high = x_;
  high(formulation_->vars().z[5]) = 0.13;  // 0.13 above the start foot, dz_max 0.1
  EXPECT_NEAR(RowViolation("dz_5", high), 0.03, 1e-12);
  EXPECT_NEAR(RowViolation("dz_5", x_), 0.0, 1e-12);
}

TEST_F(FormulationTest, YawSegmentsAndChords) {
  const FootstepVariables& v = formulation_->vars();
  EXPECT_NEAR(MaxViolationOfRowsStarting("seg_", x_), 0.0, 1e-12);
  EXPECT_NEAR(MaxViolationOfRowsStarting("sin_chord_", x_), 0.0, 1e-12);
  EXPECT_NEAR(MaxViolationOfRowsStarting("cos_chord_", x_), 0.0, 1e-12);
  // theta = 0.2 in segment 1 = [0, pi/8]: the sin chord is m theta with
  // m = sin(pi/8) / (pi/8) = 0.974495, so s = 0.194899; exact sin(0.2) = 0.198669 is
  // 0.003770 above the chord.
  Eigen::VectorXd y = x_;
  y(v.theta[1]) = 0.2;
  const double top = formulation_->yaw_breakpoints()[2];  // the options' pi/8, 0.3927
  EXPECT_NEAR(top, 0.3927, 1e-12);
  const double m = std::sin(top) / top;
  const double mc = (std::cos(top) - 1.0) / top;
  y(v.s[1]) = m * 0.2;
  y(v.c[1]) = 1.0 + mc * 0.2;
  EXPECT_NEAR(MaxViolationOfRowsStarting("sin_chord_", y), 0.0, 1e-12);
  EXPECT_NEAR(MaxViolationOfRowsStarting("cos_chord_", y), 0.0, 1e-12);
  y(v.s[1]) = std::sin(0.2);
  EXPECT_NEAR(RowViolation("sin_chord_up_1_1", y), std::sin(0.2) - m * 0.2, 1e-12);
  EXPECT_NEAR(std::sin(0.2) - m * 0.2, 0.003770, 1e-6);  // hand value
  // Segment 0 = [-pi/8, 0] selected with theta = 0.2: theta <= 0 is violated by 0.2.
  Eigen::VectorXd z = x_;
  z(v.theta[1]) = 0.2;
  z(v.segment[1][1]) = 0.0;
  z(v.segment[1][0]) = 1.0;
  EXPECT_NEAR(RowViolation("seg_hi_1_0", z), 0.2, 1e-12);
  EXPECT_NEAR(RowViolation("one_segment_1", z), 0.0, 1e-12);
  z(v.segment[1][1]) = 1.0;  // two segments at once
  EXPECT_NEAR(RowViolation("one_segment_1", z), 1.0, 1e-12);
}

TEST_F(FormulationTest, YawConvexHullEncoding) {
  // The disaggregated encoding: theta = sum theta_k, psi_k S_k <= theta_k <= psi_k+1 S_k,
  // s = sum (m_k theta_k + q_k S_k). At theta = 0.2 in segment 1 = [0, 0.3927] the only
  // consistent s is the chord value m * 0.2 = 0.194899 (sin(0.2) = 0.198669 is not).
  FormulationOptions options;
  options.prune_unreachable_regions = false;
  options.yaw_encoding = YawEncoding::kConvexHull;
  const MiqpFormulation hull(problem_, options);
  const FootstepVariables& v = hull.vars();
  ASSERT_EQ(v.segment_theta[1].size(), 2u);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(hull.miqp().num_variables());
  const double top = hull.yaw_breakpoints()[2];
  const double m = std::sin(top) / top, mc = (std::cos(top) - 1.0) / top;
  x(v.theta[1]) = 0.2;
  x(v.segment[1][1]) = 1.0;
  x(v.segment_theta[1][1]) = 0.2;
  x(v.s[1]) = m * 0.2;
  x(v.c[1]) = 1.0 + mc * 0.2;
  const Miqp& q = hull.miqp();
  auto violation = [&](const std::string& name, const Eigen::VectorXd& point) {
    for (int r = 0; r < q.num_rows(); ++r) {
      if (q.row_names[r] != name) continue;
      const double ax = q.A.row(r).dot(point.transpose());
      return std::max({0.0, q.row_lower(r) - ax, ax - q.row_upper(r)});
    }
    ADD_FAILURE() << name;
    return -1.0;
  };
  for (const char* row : {"theta_sum_1", "sin_def_1", "cos_def_1", "seg_lo_1_1", "seg_hi_1_1", "seg_lo_1_0", "seg_hi_1_0"}) {
    EXPECT_NEAR(violation(row, x), 0.0, 1e-12) << row;
  }
  Eigen::VectorXd exact = x;
  exact(v.s[1]) = std::sin(0.2);
  EXPECT_NEAR(violation("sin_def_1", exact), std::sin(0.2) - m * 0.2, 1e-12);
  // theta_k outside its segment while selected: theta_1 = 0.5 > 0.3927.
  Eigen::VectorXd outside = x;
  outside(v.segment_theta[1][1]) = 0.5;
  EXPECT_NEAR(violation("seg_hi_1_1", outside), 0.5 - top, 1e-12);
  // An unselected segment forces its theta_k to zero.
  Eigen::VectorXd unselected = x;
  unselected(v.segment_theta[1][0]) = -0.1;
  EXPECT_NEAR(violation("seg_lo_1_0", unselected), 0.1, 1e-12);
}

TEST_F(FormulationTest, ConfigurationsOnlyGetTheYawSegmentsTheyCanReach) {
  // Goal yaw 1.2 rad: the grid spans [-pi/8, 1.2 + pi/8] in 6 segments of 0.3309 rad
  // (breakpoints -0.3927, -0.0618, 0.2691, 0.6000, 0.9309, 1.2618, 1.5927). With a yaw
  // change of 0.3 rad per configuration, configuration 1 reaches [-0.3, 0.3] (3 segments) and
  // configuration 3 [-0.3927, 0.9] (4 segments).
  FootstepProblem problem = problem_;
  problem.goal_yaw_rad = 1.2;
  problem.num_new_steps = 12;
  FormulationOptions options;
  const MiqpFormulation clipped(problem, options);
  ASSERT_EQ(clipped.yaw_breakpoints().size(), 7u);
  EXPECT_EQ(clipped.vars().segment[1].size(), 3u);
  EXPECT_EQ(clipped.vars().segment[3].size(), 4u);
  const Miqp& m = clipped.miqp();
  EXPECT_NEAR(m.var_lower(clipped.vars().theta[1]), -0.3, 1e-12);
  EXPECT_NEAR(m.var_upper(clipped.vars().theta[1]), 0.3, 1e-12);
  EXPECT_NEAR(m.var_upper(clipped.vars().theta[3]), 0.9, 1e-12);
  // The kept segments are the grid's own, so their chords (and the plans) are unchanged.
  for (int cfg = 1; cfg < clipped.num_configurations(); ++cfg) {
    const std::vector<double>& bp = clipped.configuration_yaw_breakpoints(cfg);
    ASSERT_EQ(bp.size(), clipped.vars().segment[cfg].size() + 1);
    const auto& grid = clipped.yaw_breakpoints();
    const auto first = std::find(grid.begin(), grid.end(), bp.front());
    ASSERT_NE(first, grid.end()) << cfg;
    for (size_t k = 0; k < bp.size(); ++k) EXPECT_EQ(bp[k], *(first + k)) << cfg;
  }
  options.clip_yaw_to_reach = false;
  const MiqpFormulation full(problem, options);
  for (int cfg = 1; cfg < full.num_configurations(); ++cfg) EXPECT_EQ(full.vars().segment[cfg].size(), 6u) << cfg;
  EXPECT_LT(m.num_integer(), full.miqp().num_integer());
}

TEST_F(FormulationTest, YawChangeBound) {
  Eigen::VectorXd y = x_;
  y(formulation_->vars().theta[1]) = 0.35;  // from the start yaw 0, bound 0.3
  EXPECT_NEAR(RowViolation("yaw_change_1", y), 0.05, 1e-12);
}

TEST_F(FormulationTest, SafeRegionsBigM) {
  const FootstepVariables& v = formulation_->vars();
  EXPECT_NEAR(MaxViolationOfRowsStarting("region_4_", x_), 0.0, 1e-12);
  EXPECT_NEAR(RowViolation("one_region_4", x_), 0.0, 1e-12);
  // Put step 4 in r1 = [0.6, 1.5] x ..., z = 0.05: f4.x = 0.2 is 0.4 short of its left
  // edge (the plane row is off by 0.05 only).
  Eigen::VectorXd y = x_;
  y(v.region[4][0]) = 0.0;
  y(v.region[4][1]) = 1.0;
  EXPECT_NEAR(MaxViolationOfRowsStarting("region_4_1_", y), 0.4, 1e-9);
  EXPECT_NEAR(MaxViolationOfRowsStarting("region_4_0_", y), 0.0, 1e-12);  // relaxed by M
}

TEST_F(FormulationTest, TrimmingKeepsTheFootStillAndFormsASuffix) {
  const FootstepVariables& v = formulation_->vars();
  Eigen::VectorXd y = x_;
  y(v.trim[4]) = 1.0;  // step 4 trimmed, but leg 0 moved 0.1 m in x
  EXPECT_NEAR(RowViolation("trim_up_x_4", y), 0.1, 1e-12);
  EXPECT_NEAR(RowViolation("trim_dn_y_4", y), 0.0, 1e-12);
  // Monotone: step 4 trimmed but step 5 not.
  EXPECT_NEAR(RowViolation("trim_suffix_5", y), 1.0, 1e-12);
  y(v.trim[5]) = y(v.trim[6]) = y(v.trim[7]) = 1.0;
  EXPECT_NEAR(MaxViolationOfRowsStarting("trim_suffix_", y), 0.0, 1e-12);
}

TEST_F(FormulationTest, ObjectiveMatchesHandValue) {
  // Goal feet (0.5, 0) + o_k; every final foot is 0.4 m behind its goal spot:
  //   100 * 4 * 0.16 = 64. Yaw error 0. No trims. Displacement of the centre of contacts
  //   against p_{i-4} = (0, 0): 0.025^2 + 0.05^2 + 0.075^2 + 0.1^2 = 0.01875.
  EXPECT_NEAR(formulation_->miqp().Objective(x_), 64.01875, 1e-9);
  // One trimmed step adds the (negative) trim weight.
  Eigen::VectorXd y = x_;
  y(formulation_->vars().trim[7]) = 1.0;
  EXPECT_NEAR(formulation_->miqp().Objective(y), 64.01875 - 1.0, 1e-9);
}

TEST_F(FormulationTest, ExtractsFootstepsWithRegionsAndYaw) {
  const std::vector<Footstep> steps = formulation_->ExtractFootsteps(x_);
  ASSERT_EQ(steps.size(), 8u);
  EXPECT_EQ(steps[0].region_id, 0);
  EXPECT_NEAR(steps[4].position_world_m.x(), 0.2, 1e-12);
  EXPECT_EQ(steps[4].leg, 0);
  EXPECT_EQ(steps[4].region_id, 0);
  EXPECT_EQ(formulation_->CountUntrimmedSteps(x_), 4);
}

TEST_F(FormulationTest, PruningDropsRegionsOutOfReach) {
  // From the origin a foot moves at most d_lim + l_bnd = 0.2 m per step (plus its
  // offset from nominal, 0 here). A region 1.0 m away is out of reach for one step per
  // leg, so it gets no binaries.
  FootstepProblem p = problem_;
  p.regions.push_back(Square(7, 1.2, 1.6, -0.2, 0.2, 0.0));
  const MiqpFormulation pruned(p, FormulationOptions());
  for (int i = 4; i < 8; ++i) EXPECT_EQ(pruned.vars().region[i][2], -1) << i;
  EXPECT_GE(pruned.vars().region[4][0], 0);
}

// The group order that search.branching group_order follows: per configuration its yaw
// segments then its steps' regions, or (segments_first) every configuration's segments
// before any region; the same groups either way.
TEST_F(FormulationTest, SegmentsFirstListsEveryYawSegmentGroupBeforeTheRegions) {
  problem_.num_new_steps = 8;  // configurations 1 and 2 choose a yaw segment
  FormulationOptions options;
  options.prune_unreachable_regions = false;
  const MiqpFormulation plan_order(problem_, options);
  options.group_order = GroupOrder::kSegmentsFirst;
  const MiqpFormulation segments_first(problem_, options);
  const FootstepVariables& v = plan_order.vars();
  ASSERT_FALSE(v.segment[1].empty());
  ASSERT_FALSE(v.segment[2].empty());
  const std::vector<int> regions_of_step_4 = {v.region[4][0], v.region[4][1]};
  const std::vector<std::vector<int>>& plan = plan_order.miqp().sos1_groups;
  const std::vector<std::vector<int>>& first = segments_first.miqp().sos1_groups;
  ASSERT_EQ(plan.size(), 10u);  // two segment groups and eight steps' regions
  EXPECT_EQ(plan[0], v.segment[1]);
  EXPECT_EQ(plan[1], regions_of_step_4);
  EXPECT_EQ(plan[5], v.segment[2]);
  EXPECT_EQ(first[0], v.segment[1]);
  EXPECT_EQ(first[1], v.segment[2]);
  EXPECT_EQ(first[2], regions_of_step_4);
  std::vector<std::vector<int>> a = plan, b = first;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_EQ(a, b);
}

TEST_F(FormulationTest, RegionsRelaxedToTheirHullFromAStep) {
  const Miqp& full = formulation_->miqp();
  const FootstepVariables& v = formulation_->vars();
  EXPECT_EQ(formulation_->WithRegionsRelaxedFrom(8).num_rows(), full.num_rows());  // no step left
  const Miqp relaxed = formulation_->WithRegionsRelaxedFrom(6);
  ASSERT_EQ(relaxed.num_variables(), full.num_variables());
  auto has_row = [&](const std::string& name) {
    return std::find(relaxed.row_names.begin(), relaxed.row_names.end(), name) != relaxed.row_names.end();
  };
  // Steps 4 and 5 keep their region rows; 6 and 7 have the hull of r0 and r1 instead,
  // the rectangle [-0.5, 1.5] x [-0.5, 0.5] (4 rows), heights [0, 0.05], no binaries.
  EXPECT_TRUE(has_row("one_region_5"));
  EXPECT_TRUE(has_row("region_4_1_0"));
  EXPECT_FALSE(has_row("one_region_6"));
  EXPECT_FALSE(has_row("region_7_0_0"));
  EXPECT_TRUE(has_row("union_hull_6_3"));
  EXPECT_FALSE(has_row("union_hull_6_4"));
  EXPECT_FALSE(has_row("union_hull_5_0"));
  for (int i : {6, 7}) {
    for (int r : {0, 1}) EXPECT_EQ(relaxed.var_upper(v.region[i][r]), 0.0);
    EXPECT_EQ(relaxed.var_lower(v.z[i]), 0.0);
    EXPECT_NEAR(relaxed.var_upper(v.z[i]), 0.05, 1e-12);
  }
  EXPECT_EQ(relaxed.var_upper(v.region[5][1]), 1.0);
  // The hand-made point, its later region choices cleared, is no further from meeting
  // the relaxed model than the full one (it is not a whole plan: yaw and chords are
  // left at 0), and the hull rows hold it.
  Eigen::VectorXd y = x_;
  y(v.region[6][0]) = y(v.region[7][0]) = 0.0;
  EXPECT_LE(relaxed.MaxViolation(y), full.MaxViolation(x_) + 1e-12);
  // Step 6 in the gap between the stones: no region of the full model holds it, the
  // hull does. Past the far edge of r1, the hull does not hold it either (other rows,
  // such as reachability, are not the point here).
  auto hull_violation = [&](const Eigen::VectorXd& point) {
    double worst = 0.0;
    for (int r = 0; r < relaxed.num_rows(); ++r) {
      if (relaxed.row_names[r].rfind("union_hull_6_", 0) != 0) continue;
      const double ax = relaxed.A.row(r).dot(point.transpose());
      worst = std::max({worst, relaxed.row_lower(r) - ax, ax - relaxed.row_upper(r)});
    }
    return worst;
  };
  y(v.x[6]) = 0.55;
  EXPECT_NEAR(hull_violation(y), 0.0, 1e-12);
  y(v.x[6]) = 1.6;
  EXPECT_NEAR(hull_violation(y), 0.1, 1e-12);
}

TEST_F(FormulationTest, YawOnABreakpointSnapsToOneSegment) {
  // The fixture's configuration 1 has segments [-pi/8, 0] (0) and [0, pi/8] (1) among
  // others; yaw 0 is the breakpoint they share, where both chords give (sin, cos) =
  // (0, 1). Big-M encoding: only the segment binaries move.
  const FootstepVariables& v = formulation_->vars();
  const std::vector<double>& bp = formulation_->configuration_yaw_breakpoints(1);
  const auto zero = std::find_if(bp.begin(), bp.end(), [](double b) { return std::abs(b) < 1e-12; });
  ASSERT_NE(zero, bp.end());
  ASSERT_NE(zero, bp.begin());
  const int right = static_cast<int>(zero - bp.begin()), left = right - 1;
  const Miqp& m = formulation_->miqp();
  Eigen::VectorXd x = x_;
  for (int s : v.segment[1]) x(s) = 0.0;
  x(v.segment[1][left]) = 0.4;
  x(v.segment[1][right]) = 0.6;
  Eigen::VectorXd snapped = x;
  ASSERT_TRUE(formulation_->SnapYawToOneSegment(m.var_lower, m.var_upper, &snapped));
  EXPECT_EQ(snapped(v.segment[1][right]), 1.0);  // the larger share
  EXPECT_EQ(snapped(v.segment[1][left]), 0.0);
  EXPECT_NEAR(MaxViolationOfRowsStarting("sin_chord_", snapped), 0.0, 1e-12);
  EXPECT_NEAR(MaxViolationOfRowsStarting("cos_chord_", snapped), 0.0, 1e-12);
  EXPECT_FALSE(formulation_->SnapYawToOneSegment(m.var_lower, m.var_upper, &snapped));  // nothing left
  // A node that ruled out the right segment gets the left one.
  Eigen::VectorXd upper = m.var_upper;
  upper(v.segment[1][right]) = 0.0;
  snapped = x;
  ASSERT_TRUE(formulation_->SnapYawToOneSegment(m.var_lower, upper, &snapped));
  EXPECT_EQ(snapped(v.segment[1][left]), 1.0);
  // Off the chords ((sin, cos) pulled inside the circle, as a relaxation may), no single
  // segment represents the point: nothing changes.
  x(v.c[1]) = 0.99;
  snapped = x;
  EXPECT_FALSE(formulation_->SnapYawToOneSegment(m.var_lower, m.var_upper, &snapped));
  EXPECT_EQ(snapped, x);
}

// User input is checked before it reaches the formulation (request_check_test.cc); a
// malformed problem here is the planner's own bug and aborts with file and line.
using FormulationDeathTest = FormulationTest;
TEST_F(FormulationDeathTest, MalformedProblemsAreProgrammerErrors) {
  FootstepProblem p = problem_;
  p.start_feet_world_m.pop_back();
  EXPECT_DEATH(MiqpFormulation(p, FormulationOptions()), "start stance has");
  p = problem_;
  p.goal_x_m = std::nan("");
  EXPECT_DEATH(MiqpFormulation(p, FormulationOptions()), "isfinite");
  p = problem_;
  p.regions.clear();
  EXPECT_DEATH(MiqpFormulation(p, FormulationOptions()), "regions");
}

// The footprint shape (each leg's polygon, here a regular octagon of 0.15 m about the
// nominal foot): a face row whose nominal foot turns with a yaw variable is written on the
// offset f_i - r_nom,i as two variables of its own, so every face row touches at most two
// variables (the reference rows' offsets otherwise touch the foot, the centre of contacts
// and the chords); at the hand-made point, with the offsets their definitions give, every
// face row holds, and 10 cm more forward for the first new foot breaks both kinds.
TEST_F(FormulationTest, FootprintFaceRowsTouchOnlyTheStepsSharedOffset) {
  RobotModel robot = TestRobot();
  robot.reach_shape = ReachShape::kFootprint;
  for (LegModel& leg : robot.legs) {
    leg.footprint_faces.clear();
    for (int j = 0; j < 8; ++j) {
      leg.footprint_faces.push_back({Eigen::Vector2d(std::cos(j * M_PI / 4), std::sin(j * M_PI / 4)), 0.15});
    }
  }
  FootstepProblem problem = problem_;
  problem.robot = &robot;
  FormulationOptions options;
  options.prune_unreachable_regions = false;
  options.yaw_encoding = YawEncoding::kBigM;
  formulation_ = std::make_unique<MiqpFormulation>(problem, options);
  const Miqp& m = formulation_->miqp();
  Eigen::VectorXd x = HandPoint();
  // The shared offsets' values at x: each definition row reads w - expr = 0.
  const auto set_shared = [&m](Eigen::VectorXd* point) {
    int shared = 0;
    for (int r = 0; r < m.num_rows(); ++r) {
      const std::string& name = m.row_names[r];
      if (name.find("_fp_w") == std::string::npos || name.size() < 4 || name.substr(name.size() - 4) != "_def") continue;
      const auto w = std::find(m.var_names.begin(), m.var_names.end(), name.substr(0, name.size() - 4));
      EXPECT_NE(w, m.var_names.end()) << name;
      if (w == m.var_names.end()) continue;
      const int j = static_cast<int>(w - m.var_names.begin());
      (*point)(j) = 0.0;
      (*point)(j) = m.row_lower(r) - m.A.row(r).dot(point->transpose());
      ++shared;
    }
    return shared;
  };
  const int shared = set_shared(&x);
  EXPECT_EQ(shared, 2 * 4) << "the reference rows' offsets of the 4 new steps (their reach rows refer to the start)";
  int faces = 0;
  for (int r = 0; r < m.num_rows(); ++r) {
    const std::string& name = m.row_names[r];
    const bool face = (name.rfind("ref_fp_", 0) == 0 || name.rfind("reach_fp_", 0) == 0) &&
                      name.find("_fp_w") == std::string::npos;
    if (!face) continue;
    ++faces;
    int touched = 0;
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(m.A, r); it; ++it) touched += it.value() != 0.0;
    EXPECT_LE(touched, 2) << name;
    EXPECT_EQ(RowViolation(name, x), 0.0) << name;
  }
  EXPECT_GT(faces, 0);
  x(formulation_->vars().x[4]) += 0.1;
  set_shared(&x);
  EXPECT_GT(MaxViolationOfRowsStarting("reach_fp_", x), 0.0);
  EXPECT_GT(MaxViolationOfRowsStarting("ref_fp_", x), 0.0);
}

}  // namespace
}  // namespace mfp
