// The anytime guarantee on the hardest Table I instances (LittleDog, 24 and 36 new
// steps): a search cut short, by its node cap or by a slow root heuristic that takes its
// whole time, still ends with a plan; where no rounding of the root is feasible (36 steps)
// the first plan comes from relax-and-fix's dive; a search that takes the whole limit
// leaves the exactness step its reserve.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include "planner/formulation/miqp_formulation.h"
#include "planner/planning/internal/exact_window.h"
#include "planner/planning/internal/relax_and_fix.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "planner/search/branch_and_bound.h"
#include "tests/test_scenarios.h"

namespace mfp {
namespace {

Course LittleDogTableI(int steps) { return LoadTableICourse("littledog_stepping_stones_45.yaml", steps); }

Course LittleDog24() { return LittleDogTableI(24); }

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

namespace mfp {
namespace {

TEST(AnytimePlan, ThirtySixStepsWithoutAFeasibleRoundingGetTheDivesPlanAtTheRoot) {
  // LittleDog 36: none of the root's roundings is feasible, so a search capped at its root
  // has no plan; the first-plan heuristic (relax-and-fix's dive, one node per stage)
  // gives it one there.
  const Course c = LittleDogTableI(36);
  const PlannerOptions& options = c.scenario.options;
  const MiqpFormulation formulation(FirstWindowProblem(c.robot, c.regions, c.request, options), options.formulation);
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(options.solvers.backend, 1);
  BranchAndBoundOptions bnb = options.branch_and_bound;
  bnb.max_nodes = 1;
  const RoundingHeuristic rounding = [&](const Eigen::VectorXd& relaxed) { return formulation.RoundAlongPlan(relaxed); };
  const BranchAndBoundResult roundings_only = SolveBranchAndBound(formulation.miqp(), solvers.workers(), bnb, rounding);
  ASSERT_EQ(roundings_only.x.size(), 0) << "a rounding of the root is feasible: this case no longer needs the dive";

  int dives = 0;
  bnb.first_plan_heuristic = [&](const Eigen::VectorXd&) {
    ++dives;
    RelaxAndFixOptions rf = options.relax_and_fix;
    rf.stage = options.branch_and_bound;
    rf.time_limit_s = 60.0;
    std::vector<Eigen::VectorXd> plans;
    if (const RelaxAndFixResult r = RelaxAndFix(formulation, solvers.workers(), DiveOptions(rf)); r.x) {
      EXPECT_FALSE(r.completed_by_rounding);
      EXPECT_EQ(r.nodes, formulation.num_configurations() - 1);  // one node per stage
      plans.push_back(*r.x);
    }
    return plans;
  };
  const BranchAndBoundResult r = SolveBranchAndBound(formulation.miqp(), solvers.workers(), bnb, rounding);
  EXPECT_EQ(dives, 1);
  ASSERT_GT(r.x.size(), 0) << "the dive found no plan";
  const Miqp& m = formulation.miqp();
  EXPECT_LE(m.MaxViolation(r.x), bnb.feasibility_tolerance);
  EXPECT_EQ(m.MaxIntegrality(r.x), 0.0);
  EXPECT_GE(r.objective, r.root_bound);
}

// LittleDog 36's first window, its solvers and its root relaxation: the dives' start.
struct LittleDog36Root {
  const Course c = LittleDogTableI(36);
  const PlannerOptions& options = c.scenario.options;
  const MiqpFormulation formulation{FirstWindowProblem(c.robot, c.regions, c.request, options), options.formulation};
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(options.solvers.backend, 1);
  const RelaxationResult root = solvers.workers().front()->Solve(formulation.miqp(), RelaxationRequest{});

  const Miqp& miqp() const { return formulation.miqp(); }
  RelaxationSolver& worker() const { return *solvers.workers().front(); }
  int stages() const { return formulation.num_configurations() - 1; }
  // The planner's relax-and-fix options, its stages searched as the planner's tree search
  // is, with this share of time.
  RelaxAndFixOptions DiveShare(double time_limit_s) const {
    RelaxAndFixOptions rf = options.relax_and_fix;
    rf.stage = options.branch_and_bound;
    rf.time_limit_s = time_limit_s;
    return rf;
  }
  // x meets every row within the search's tolerance, with integral choices.
  ::testing::AssertionResult IsPlan(const Eigen::VectorXd& x) const {
    const double violation = miqp().MaxViolation(x), fraction = miqp().MaxIntegrality(x);
    if (violation <= options.branch_and_bound.feasibility_tolerance && fraction == 0.0) {
      return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure() << "violation " << violation << ", integrality " << fraction;
  }
};

TEST(AnytimePlan, ThirtySixStepsGetTheRoundingDivesPlanFromTheRootWithOneQpPerStage) {
  // LittleDog 36 again: the rounding dive (RelaxAndFixOptions::rounding_dive) rounds each
  // configuration from the previous stage's completion, starting at the root relaxation's
  // point, and completes it with one QP: a plan that meets every row with integral
  // choices, from at most two QPs per stage (one per rounding proposal) where the
  // stage-search dive solves a relaxation and a rounding each.
  const LittleDog36Root ld;
  ASSERT_EQ(ld.root.status, RelaxationStatus::kSolved);
  const RelaxAndFixResult r = RoundingDive(ld.formulation, ld.worker(), ld.root.x, ld.DiveShare(60.0));
  ASSERT_TRUE(r.x.has_value()) << "the rounding dive found no plan";
  EXPECT_EQ(r.stages, ld.stages());
  EXPECT_GE(r.relaxations, ld.stages());
  EXPECT_LE(r.relaxations, 2 * ld.stages());
  EXPECT_TRUE(ld.IsPlan(*r.x));
  EXPECT_GE(ld.miqp().Objective(*r.x), ld.root.objective - 1e-6 * std::abs(ld.root.objective));
  // Out of time before it starts: no plan, and no QP.
  const RelaxAndFixResult none = RoundingDive(ld.formulation, ld.worker(), ld.root.x, ld.DiveShare(0.0));
  EXPECT_FALSE(none.x.has_value());
  EXPECT_EQ(none.relaxations, 0);
}

// A solver that passes every solve on to `inner`, keeps each request's time left, and
// sleeps `pause_s` after its pause_after_solved-th solve that succeeds: a share spent at a
// known point (a dive's stage completed), however fast the machine is.
class PausingSolver : public RelaxationSolver {
 public:
  PausingSolver(RelaxationSolver* inner, int pause_after_solved, double pause_s)
      : inner_(inner), pause_after_solved_(pause_after_solved), pause_s_(pause_s) {}
  RelaxationResult Solve(const Miqp& problem, const RelaxationRequest& request) override {
    time_left_s.push_back(request.deadline.RemainingSeconds());
    RelaxationResult r = inner_->Solve(problem, request);
    if (r.status == RelaxationStatus::kSolved && ++solved_ == pause_after_solved_) {
      std::this_thread::sleep_for(std::chrono::duration<double>(pause_s_));
    }
    return r;
  }
  std::string Name() const override { return "pausing " + inner_->Name(); }
  std::vector<double> time_left_s;  // per solve, its request's deadline's seconds left

 private:
  RelaxationSolver* inner_;
  int pause_after_solved_;
  double pause_s_;
  int solved_ = 0;
};

TEST(AnytimePlan, ARoundingDiveCutShortByItsShareEndsWithTheRoundingOfItsLatestStage) {
  // LittleDog 36's rounding dive, given a 1 s share (time_limit_s) and no deadline of the
  // caller's, with a 1.5 s pause after a stage's completed QP: the share passes there.
  // Its stage QPs run under the share (never the caller's endless deadline). Cut short
  // two stages before its end, the stages left are rounded along the plan from the
  // latest stage's point under the caller's deadline: a complete plan, every QP counted.
  // Cut short after its first stage, no rounding of that point is feasible (as none of
  // the root's is): no plan, and the planner's stage-search dive (RelaxAndFix with
  // DiveOptions, its own share) ends with a complete plan. (Before, the QPs ran under the
  // caller's deadline and a dive cut short by its share ended without a plan.)
  const LittleDog36Root ld;
  ASSERT_EQ(ld.root.status, RelaxationStatus::kSolved);
  RelaxAndFixOptions rf = ld.DiveShare(1.0);
  rf.stage.deadline = Deadline();
  const int stages = ld.stages();
  PausingSolver late(&ld.worker(), stages - 2, 1.5);
  const RelaxAndFixResult r = RoundingDive(ld.formulation, late, ld.root.x, rf);
  ASSERT_TRUE(r.x.has_value()) << "the dive cut short by its share ended without a plan";
  EXPECT_TRUE(r.completed_by_rounding);
  EXPECT_EQ(r.stages, stages - 2);
  EXPECT_TRUE(ld.IsPlan(*r.x));
  ASSERT_GT(late.time_left_s.size(), static_cast<size_t>(stages - 2));
  EXPECT_EQ(r.relaxations, static_cast<int>(late.time_left_s.size()));
  for (int k = 0; k < stages - 2; ++k) EXPECT_LE(late.time_left_s[k], rf.time_limit_s);  // the stages: the share
  EXPECT_TRUE(std::isinf(late.time_left_s.back()));  // the completion: the caller's deadline

  PausingSolver early(&ld.worker(), 1, 1.5);
  const RelaxAndFixResult none = RoundingDive(ld.formulation, early, ld.root.x, rf);
  EXPECT_FALSE(none.x.has_value());
  EXPECT_EQ(none.relaxations, static_cast<int>(early.time_left_s.size()));
  rf.time_limit_s = 60.0;
  const RelaxAndFixResult fallback = RelaxAndFix(ld.formulation, ld.solvers.workers(), DiveOptions(rf));
  ASSERT_TRUE(fallback.x.has_value()) << "the stage-search dive found no plan";
  EXPECT_LE(ld.miqp().MaxViolation(*fallback.x), ld.options.branch_and_bound.feasibility_tolerance);
  EXPECT_GT(fallback.relaxations, 0);
}

TEST(AnytimePlan, APlansRelaxationsCountItsRootHeuristicsQps) {
  // LittleDog 36 with its search cut to the root node: no rounding of the root is
  // feasible, so the rounding dive gives the first plan (one QP per stage at least) and
  // relax-and-fix's seed runs after it. Their QPs are the window's heuristic_relaxations
  // and are counted in its relaxations and the plan's, beside the search's own (the root
  // relaxation and its roundings at least). (Before, neither heuristic's QPs were counted.)
  Course c = LittleDogTableI(36);
  c.request.time_limit_s = 5.0;  // the seed runs to its share; the dive takes well under a second
  PlannerOptions options = c.scenario.options;
  options.branch_and_bound.max_nodes = 1;
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(options.solvers);
  const Plan plan = PlanFootsteps(c.robot, c.regions, c.request, options, solvers.workers());
  ASSERT_TRUE(HasPlan(plan.status)) << ToString(plan.status) << ": " << plan.message;
  int relaxations = 0;
  for (const WindowRecord& w : plan.window_records) relaxations += w.relaxations;
  EXPECT_EQ(plan.relaxations, relaxations);
  const WindowRecord& first = plan.window_records.front();
  const MiqpFormulation formulation(FirstWindowProblem(c.robot, c.regions, c.request, options), options.formulation);
  EXPECT_GE(first.heuristic_relaxations, formulation.num_configurations() - 1);
  EXPECT_GT(first.relaxations, first.heuristic_relaxations + 1);
}

TEST(AnytimePlan, ThirtySixStepsEndWithAPlanWhenTheSearchTakesTheWholeLimit) {
  // LittleDog 36 as Table I runs it, with a limit far too short to prove it: the search
  // runs to its deadline, which leaves the polisher its reserve, so the plan ends with
  // the search's best plan made exact, no worse than the first plan it held. (Before,
  // the search took the whole limit, the polisher got 1 ms, the completion on the shrunk
  // boxes was infeasible, and the instance ended no_solution at any limit.)
  Course c = LittleDogTableI(36);
  c.request.time_limit_s = 3.0;
  PlannerOptions options = c.scenario.options;
  std::vector<double> incumbents;
  options.branch_and_bound.on_incumbent = [&](const BranchAndBoundResult& r) { incumbents.push_back(r.objective); };
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(options.solvers);
  const Plan plan = PlanFootsteps(c.robot, c.regions, c.request, options, solvers.workers());
  ASSERT_TRUE(HasPlan(plan.status)) << ToString(plan.status) << ": " << plan.message;
  EXPECT_GT(plan.gap, 0.0);  // not proven in 3 s
  ASSERT_FALSE(incumbents.empty());
  EXPECT_LE(plan.objective, incumbents.front());
  ASSERT_EQ(plan.window_records.size(), 1u);
  EXPECT_TRUE(plan.window_records.front().polished);
  EXPECT_GT(plan.footsteps.size(), static_cast<size_t>(c.robot.num_legs()));
}

}  // namespace
}  // namespace mfp

namespace mfp {
namespace {

TEST(AnytimePlan, ASearchThatProvesSoonDoesWithoutTheSeedWhenItsRootPlanIsNearTheBound) {
  // Hexapod 24 of Table I: the root's rounding lies 24.5 % above the root bound, within the
  // default wait gap (0.3), and the search proves the optimum in about 134 nodes, fewer than
  // relax_and_fix.after_nodes (200): relax-and-fix's seed never runs. With a wait gap below
  // the root plan's (0.2) the seed runs at the root, and the optimum is the same.
  Course c = LoadTableICourse("hexapod_stepping_stones_45.yaml", 24);
  c.request.time_limit_s = 120.0;  // far more than the proof takes on a loaded machine
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(c.scenario.options.solvers);
  const Plan waited = PlanFootsteps(c.robot, c.regions, c.request, c.scenario.options, solvers.workers());
  ASSERT_EQ(waited.status, SolveStatus::kOptimal) << waited.message;
  EXPECT_EQ(waited.window_records.front().heuristic_relaxations, 0);
  PlannerOptions at_root = c.scenario.options;
  at_root.relax_and_fix.wait_gap = 0.2;
  const Plan seeded = PlanFootsteps(c.robot, c.regions, c.request, at_root, solvers.workers());
  ASSERT_EQ(seeded.status, SolveStatus::kOptimal) << seeded.message;
  EXPECT_GT(seeded.window_records.front().heuristic_relaxations, 0);
  EXPECT_NEAR(waited.objective, seeded.objective, 1e-4 * std::abs(seeded.objective));
}

}  // namespace
}  // namespace mfp
