// The anytime guarantee on the hardest Table I instance (LittleDog, 24 new steps): a
// search cut short, by its node cap or by a slow root heuristic that takes its whole
// time, still ends with a plan.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "planner/formulation/miqp_formulation.h"
#include "planner/planning/internal/exact_window.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "planner/search/branch_and_bound.h"
#include "tests/test_scenarios.h"

namespace mfp {
namespace {

Course LittleDog24() {
  Course c = LoadCourse("littledog_stepping_stones_45.yaml");
  c.request.max_steps = 24;
  c.request.window_steps = 24;
  c.request.max_windows = 1;  // one MIQP, as in Table I
  return c;
}

TEST(AnytimePlan, RootRoundingsAreCompletedBeforeTheRootHeuristicTakesTheTime) {
  // The root heuristic (relax-and-fix's seed in the planner) sleeps past the search's
  // time limit and finds nothing. The root's roundings must have been completed before
  // it ran: the search ends on its time limit with their plan. (Before, the roundings'
  // QPs were solved after the slow heuristic, under an expired deadline: no plan.)
  const Course c = LittleDog24();
  const MiqpFormulation formulation(FirstWindowProblem(c.robot, c.regions, c.request, c.scenario.options),
                                    c.scenario.options.formulation);
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(c.scenario.options.solvers.backend, 1);
  BranchAndBoundOptions bnb = c.scenario.options.branch_and_bound;
  bnb.time_limit_s = 3.0;
  const auto start = std::chrono::steady_clock::now();
  bool heuristic_ran = false;
  bnb.root_heuristic = [&](const Eigen::VectorXd&) {
    heuristic_ran = true;
    std::this_thread::sleep_until(start + std::chrono::duration<double>(bnb.time_limit_s + 0.1));
    return std::vector<Eigen::VectorXd>{};
  };
  const RoundingHeuristic rounding = [&](const Eigen::VectorXd& relaxed) { return formulation.RoundAlongPlan(relaxed); };
  const BranchAndBoundResult r = SolveBranchAndBound(formulation.miqp(), solvers.workers(), bnb, rounding);
  ASSERT_TRUE(heuristic_ran);
  EXPECT_EQ(r.status, SolveStatus::kTimeLimit);
  ASSERT_GT(r.x.size(), 0) << "cut short by the root heuristic, the search ended without a plan";
  const Miqp& m = formulation.miqp();
  EXPECT_LE(m.MaxViolation(r.x), bnb.feasibility_tolerance);
  EXPECT_EQ(m.MaxIntegrality(r.x), 0.0);
  EXPECT_NEAR(r.objective, m.Objective(r.x), 1e-9 * std::abs(r.objective));
  EXPECT_GE(r.objective, r.root_bound);
}

TEST(AnytimePlan, NodeCappedPlannerStillReturnsAPlan) {
  // The planner on the instance with the search capped at its root node: the root's
  // roundings and relax-and-fix's plan are all it has, and they make a plan that meets
  // every row (a plan is all the caller asks of an anytime planner cut short).
  Course c = LittleDog24();
  c.scenario.options.branch_and_bound.max_nodes = 1;
  c.request.time_limit_s = 60.0;
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(c.scenario.options.solvers);
  const Plan plan = PlanFootsteps(c.robot, c.regions, c.request, c.scenario.options, solvers.workers());
  ASSERT_TRUE(HasPlan(plan.status)) << ToString(plan.status);
  EXPECT_GT(plan.gap, 0.0);  // a root alone proves nothing on this instance
  EXPECT_GT(plan.footsteps.size(), static_cast<size_t>(c.robot.num_legs()));
}

}  // namespace
}  // namespace mfp

namespace mfp {
namespace {

TEST(AnytimePlan, AWindowWithoutTimeToReplanKeepsItsOwnChoicesCompleted) {
  // A window the polisher cannot make exact is planned again within the chords' error;
  // when the window's search took all the time, that search gets none. The window's
  // own integer choices, completed on the shrunk MIQP (one QP), must still make a plan
  // (before, the window ended with none: LittleDog 24 of Table I, no_solution).
  const Course c = LittleDog24();
  const PlannerOptions& options = c.scenario.options;
  const MiqpFormulation formulation(FirstWindowProblem(c.robot, c.regions, c.request, options), options.formulation);
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(options.solvers.backend, 1);
  BranchAndBoundOptions bnb = options.branch_and_bound;
  bnb.max_nodes = 1;  // the root and its roundings: a plan of the window
  const RoundingHeuristic rounding = [&](const Eigen::VectorXd& relaxed) { return formulation.RoundAlongPlan(relaxed); };
  const BranchAndBoundResult window = SolveBranchAndBound(formulation.miqp(), solvers.workers(), bnb, rounding);
  ASSERT_GT(window.x.size(), 0);
  bnb.deadline = Deadline::After(0.0);  // nothing left for the re-plan's search
  PolishOptions no_polish;
  no_polish.enabled = false;
  // The completion runs past the deadline by at most completion_overrun_s, counted from
  // the deadline: building the shrunk MIQP takes part of it, so room to spare here.
  no_polish.completion_overrun_s = 10.0;
  const ExactReplan replan = ReplanWithinChordError(formulation, solvers.workers(), bnb, no_polish, &window.x);
  ASSERT_TRUE(replan.planned) << replan.note;
  EXPECT_EQ(replan.result.nodes, 0);
  const Miqp& shrunk = replan.formulation->miqp();
  EXPECT_LE(shrunk.MaxViolation(replan.result.x), bnb.feasibility_tolerance);
  EXPECT_EQ(shrunk.MaxIntegrality(replan.result.x), 0.0);
  // The same choices: every step stands on the same region.
  const std::vector<Footstep> before = formulation.ExtractFootsteps(window.x);
  const std::vector<Footstep> after = replan.formulation->ExtractFootsteps(replan.result.x);
  ASSERT_EQ(before.size(), after.size());
  for (size_t i = 0; i < before.size(); ++i) EXPECT_EQ(before[i].region_id, after[i].region_id) << "step " << i;
  // Without the window's point there is nothing to complete: no plan.
  EXPECT_FALSE(ReplanWithinChordError(formulation, solvers.workers(), bnb, no_polish).planned);
  // No overrun allowed, or the request stopped: the completion does not run past either.
  PolishOptions no_overrun = no_polish;
  no_overrun.completion_overrun_s = 0.0;
  EXPECT_FALSE(ReplanWithinChordError(formulation, solvers.workers(), bnb, no_overrun, &window.x).planned);
  std::atomic<bool> stop{true};
  BranchAndBoundOptions stopped = bnb;
  stopped.deadline = Deadline::After(0.0).WithStop(&stop);
  EXPECT_FALSE(ReplanWithinChordError(formulation, solvers.workers(), stopped, no_polish, &window.x).planned);
}

}  // namespace
}  // namespace mfp
