// Relax-and-fix on a Table I instance: a feasible plan near the proven optimum.
#include "planner/planning/internal/relax_and_fix.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "planner/formulation/miqp_formulation.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "planner/search/branch_and_bound.h"
#include "tests/test_scenarios.h"

namespace mfp {
namespace {

TEST(RelaxAndFix, EndedByItsTimeLimitStillCompletesThePlan) {
  // When relax-and-fix's time runs out, the configurations it has not searched are
  // rounded from the latest stage's solution and their QPs solved. Those QPs run under
  // the caller's deadline, not under the deadline of the stage search that the time
  // limit has just ended (issue 26: with the solver's old setters they inherited that
  // expired deadline, and relax-and-fix ended with no plan).
  Course c = LoadCourse("hexapod_stepping_stones_45.yaml");
  c.request.window_steps = 12;
  const MiqpFormulation formulation(FirstWindowProblem(c.robot, c.regions, c.request, c.scenario.options),
                                    c.scenario.options.formulation);
  ASSERT_GE(formulation.num_configurations(), 3) << "the test needs a stage before the last";
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(c.scenario.options.solvers.backend, 1);
  RelaxAndFixOptions rf;
  rf.stage = c.scenario.options.branch_and_bound;
  rf.stage_rounding = true;  // the first stage's root rounding gives it a plan at once
  rf.time_limit_s = 2.0;
  // The second node any stage search settles waits past the whole time limit: that
  // search ends on its deadline, and relax-and-fix on its time limit.
  int nodes_settled = 0;
  rf.stage.equivalent_point = [&nodes_settled, &rf](const Eigen::VectorXd&, const Eigen::VectorXd&,
                                                    Eigen::VectorXd*) {
    if (++nodes_settled == 2) std::this_thread::sleep_for(std::chrono::duration<double>(1.25 * rf.time_limit_s));
    return false;  // the point is kept as it is
  };
  const RelaxAndFixResult r = RelaxAndFix(formulation, solvers.workers(), rf);
  ASSERT_GE(nodes_settled, 2);
  ASSERT_TRUE(r.x.has_value()) << "relax-and-fix ended by its time limit without a plan";
  EXPECT_TRUE(r.completed_by_rounding);
  const Miqp& m = formulation.miqp();
  EXPECT_LE(m.MaxViolation(*r.x), 1e-5);
  EXPECT_EQ(m.MaxIntegrality(*r.x), 0.0);
}

TEST(RelaxAndFix, FindsAFeasiblePlanNearTheProvenOptimum) {
  // The hexapod stones with 24 new steps (Table I): relax-and-fix fixes the four
  // configurations one at a time. Its plan must meet every row and bound with integral
  // choices and lie within 1 % of the optimum the branch-and-bound proves (measured: 0 %).
  Course c = LoadCourse("hexapod_stepping_stones_45.yaml");
  c.request.window_steps = 24;
  const MiqpFormulation formulation(FirstWindowProblem(c.robot, c.regions, c.request, c.scenario.options),
                                    c.scenario.options.formulation);
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(c.scenario.options.solvers.backend, 1);
  RelaxAndFixOptions rf;
  rf.stage = c.scenario.options.branch_and_bound;
  rf.time_limit_s = 300.0;
  const RelaxAndFixResult r = RelaxAndFix(formulation, solvers.workers(), rf);
  ASSERT_TRUE(r.x.has_value());
  EXPECT_EQ(r.stages, formulation.num_configurations() - 1);
  const Miqp& m = formulation.miqp();
  EXPECT_LE(m.MaxViolation(*r.x), 1e-5);
  EXPECT_EQ(m.MaxIntegrality(*r.x), 0.0);

  BranchAndBoundOptions bnb = c.scenario.options.branch_and_bound;
  bnb.time_limit_s = 300.0;
  const BranchAndBoundResult proof = SolveBranchAndBound(m, solvers.workers(), bnb);
  ASSERT_EQ(ToString(proof.status), "optimal");
  // No plan beats the proven bound, up to the relaxations' own accuracy (relative).
  EXPECT_GE(m.Objective(*r.x), proof.bound - 1e-8 * std::abs(proof.bound)) << m.Objective(*r.x) - proof.bound;
  EXPECT_LE(m.Objective(*r.x), proof.objective + 0.01 * std::abs(proof.objective));

  // Stopped after one stage (as when its time runs out), the configurations left are
  // rounded: still a complete plan that meets every row, no better than the optimum.
  rf.max_searched_stages = 1;
  const RelaxAndFixResult partial = RelaxAndFix(formulation, solvers.workers(), rf);
  ASSERT_TRUE(partial.x.has_value());
  EXPECT_TRUE(partial.completed_by_rounding);
  EXPECT_FALSE(r.completed_by_rounding);
  EXPECT_EQ(partial.stages, 1);
  EXPECT_LE(m.MaxViolation(*partial.x), 1e-5);
  EXPECT_EQ(m.MaxIntegrality(*partial.x), 0.0);
  EXPECT_GE(m.Objective(*partial.x), proof.bound - 1e-6);

  // A complete plan: integral choices that meet every row, within 1 % of the optimum.
  const auto expect_plan_near_optimum = [&](const RelaxAndFixResult& run) {
    ASSERT_TRUE(run.x.has_value());
    EXPECT_LE(m.MaxViolation(*run.x), 1e-5);
    EXPECT_EQ(m.MaxIntegrality(*run.x), 0.0);
    EXPECT_LE(m.Objective(*run.x), proof.objective + 0.01 * std::abs(proof.objective));
  };

  // The stages with the steps they have not reached in the full relaxation of their
  // region binaries (the hull is the default): also a complete plan within 1 %.
  rf.max_searched_stages = 0;
  rf.hull_for_later_steps = false;
  expect_plan_near_optimum(RelaxAndFix(formulation, solvers.workers(), rf));

  // With the search's rounding heuristic in the stages (off by default): rounding QPs
  // on top of the node relaxations, and still a complete plan within 1 %.
  rf.hull_for_later_steps = true;
  rf.stage_rounding = true;
  const RelaxAndFixResult rounded = RelaxAndFix(formulation, solvers.workers(), rf);
  expect_plan_near_optimum(rounded);
  EXPECT_GT(rounded.relaxations - rounded.nodes, r.relaxations - r.nodes);
  rf.stage_rounding = false;

  // Two paths side by side with two workers: the first is the one-worker run, so the
  // plan is never worse than that one, and it is a plan.
  rf.hull_for_later_steps = true;
  const RelaxAndFixResult one = RelaxAndFix(formulation, solvers.workers(), rf);
  const RelaxationSolverSet two_workers = MakeRelaxationSolvers(c.scenario.options.solvers.backend, 2);
  const RelaxAndFixResult two = RelaxAndFixTwoPaths(formulation, two_workers.workers(), rf);
  ASSERT_TRUE(one.x.has_value());
  ASSERT_TRUE(two.x.has_value());
  EXPECT_LE(m.MaxViolation(*two.x), 1e-5);
  EXPECT_EQ(m.MaxIntegrality(*two.x), 0.0);
  EXPECT_LE(m.Objective(*two.x), m.Objective(*one.x) + 1e-9 * std::abs(m.Objective(*one.x)));
  EXPECT_EQ(two.stages, 2 * one.stages);
}

}  // namespace
}  // namespace mfp
