// The first plan when the clock runs short (issue 26): every path by which a Table I
// search could end without a plan once its root relaxation was solved, each driven to
// the deadline at a chosen point by a solver that stalls there (not by loading the
// machine): the root's roundings, relax-and-fix's rounding dive, relax-and-fix's seed
// and its completion; a root relaxation not solved in time ends with a status that says
// so; the rounding dive tells a stage whose roundings all failed from one cut short;
// every QP of the root heuristics is counted in the plan's fallbacks when its solver's
// fallback solved it.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "planner/formulation/miqp_formulation.h"
#include "planner/planning/internal/relax_and_fix.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "tests/test_scenarios.h"

namespace mfp {
namespace {

Course LittleDogTableI(int steps) { return LoadTableICourse("littledog_stepping_stones_45.yaml", steps); }

int FullIntegers(const Course& c) {
  const MiqpFormulation formulation(FirstWindowProblem(c.robot, c.regions, c.request, c.scenario.options),
                                    c.scenario.options.formulation);
  return formulation.miqp().num_integer();
}

// Passes every solve on to `inner`. Once, at the solve that `stall_at` picks (by its
// problem and 1-based call number), it waits until the deadline of the first request it
// saw has passed (the root relaxation's: the search's deadline in force), after the solve
// or, with `before`, before it: the clock runs short at a chosen point, however fast the
// machine is.
class StallingSolver : public RelaxationSolver {
 public:
  using Pick = std::function<bool(const Miqp& problem, int call)>;
  StallingSolver(RelaxationSolver* inner, Pick stall_at, bool before = false)
      : inner_(inner), stall_at_(std::move(stall_at)), before_(before) {}
  // Stalls until `until` has passed instead (the whole plan's time limit, say).
  StallingSolver(RelaxationSolver* inner, Pick stall_at, bool before, const Deadline& until)
      : inner_(inner), stall_at_(std::move(stall_at)), before_(before), until_(until) {}
  RelaxationResult Solve(const Miqp& problem, const RelaxationRequest& request) override {
    if (++calls == 1) first_deadline_ = until_.finite() ? until_ : request.deadline;
    const bool stall = !stalled && stall_at_(problem, calls);
    if (stall && before_) Stall();
    RelaxationResult r = inner_->Solve(problem, request);
    if (stall && !before_) Stall();
    return r;
  }
  std::string Name() const override { return "stalling " + inner_->Name(); }
  int calls = 0;
  bool stalled = false;

 private:
  void Stall() {
    stalled = true;
    while (!first_deadline_.Expired()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  RelaxationSolver* inner_;
  Pick stall_at_;
  bool before_;
  Deadline until_;
  Deadline first_deadline_;
};

// Table I's options for these tests: no polisher (so no exactness reserve: the window's
// deadline is the plan's) and a first-plan overrun generous enough for a loaded machine.
PlannerOptions ShortClockOptions(const Course& c) {
  PlannerOptions options = c.scenario.options;
  options.polish.enabled = false;
  options.polish.completion_overrun_s = 10.0;
  return options;
}

Plan PlanWith(const Course& c, const PlannerOptions& options, StallingSolver* solver) {
  return PlanFootsteps(c.robot, c.regions, c.request, options, std::vector<RelaxationSolver*>{solver});
}

// A plan of the window (trimmed steps, which stay where their leg stood, are not listed).
void ExpectCompletePlan(const Course& c, const Plan& plan) {
  ASSERT_TRUE(HasPlan(plan.status)) << ToString(plan.status) << ": " << plan.message;
  EXPECT_GT(static_cast<int>(plan.footsteps.size()), c.robot.num_legs());
  EXPECT_LE(static_cast<int>(plan.footsteps.size()), c.robot.num_legs() + c.request.max_steps);
}

TEST(FirstPlanDeadline, RootRoundingsCutByTheDeadlineStillGiveAPlan) {
  // LittleDog 24, whose root roundings give a plan: the deadline passes right after the
  // root relaxation. (Before, their QPs got the expired deadline, so did the dives and the
  // seed after them: no_solution.)
  Course c = LittleDogTableI(24);
  c.request.time_limit_s = 2.0;
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(c.scenario.options.solvers.backend, 1);
  StallingSolver late(solvers.workers().front(), [](const Miqp&, int call) { return call == 1; });
  const Plan plan = PlanWith(c, ShortClockOptions(c), &late);
  ASSERT_TRUE(late.stalled);
  ExpectCompletePlan(c, plan);
}

TEST(FirstPlanDeadline, ARoundingDiveCutByTheDeadlineAfterItsFirstStageStillGivesAPlan) {
  // LittleDog 36, none of whose root roundings is feasible: the deadline passes after the
  // rounding dive's first stage QP. The dive is the first plan's work and goes on past the
  // deadline, within the overrun. (Before, its stages stopped there, no rounding of the
  // first stage's point is feasible, and the stage-search dive and the seed had no time:
  // no_solution.)
  Course c = LittleDogTableI(36);
  c.request.time_limit_s = 2.0;
  const int full = FullIntegers(c);
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(c.scenario.options.solvers.backend, 1);
  StallingSolver late(solvers.workers().front(), [full](const Miqp& p, int) { return p.num_integer() < full; });
  const Plan plan = PlanWith(c, ShortClockOptions(c), &late);
  ASSERT_TRUE(late.stalled);
  ExpectCompletePlan(c, plan);
}

TEST(FirstPlanDeadline, ARoundingDiveBegunEarlyRunsToTheFirstPlansDeadlineNotToItsShare) {
  // LittleDog 36: the clock passes the window's deadline by 1 s right after the rounding
  // dive's first stage QP, within the first plan's overrun (10 s here). The dive's share
  // (the window's time counted from the dive's start, a little after the window's own
  // start) has passed too, but the first plan's deadline has not: the rounding dive carries
  // on to its plan. (Before, the share ended it there, its first stage's point rounded to no
  // plan, and the stage-search dive began again from the root: 18 or more QPs more, which
  // a loaded machine could not fit in the overrun.)
  Course c = LittleDogTableI(36);
  c.request.time_limit_s = 1.0;
  const int full = FullIntegers(c);
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(c.scenario.options.solvers.backend, 1);
  StallingSolver late(solvers.workers().front(), [full](const Miqp& p, int) { return p.num_integer() < full; },
                      /*before=*/false, Deadline::After(c.request.time_limit_s + 1.0));
  const Plan plan = PlanWith(c, ShortClockOptions(c), &late);
  ASSERT_TRUE(late.stalled);
  ExpectCompletePlan(c, plan);
  // The rounding dive's 9 stage QPs (one per configuration, each rounding completed at
  // its first proposal); no stage-search dive.
  EXPECT_LE(plan.window_records.front().heuristic_relaxations, 9);
}

TEST(FirstPlanDeadline, ASeedCutByTheDeadlineWithoutAFirstPlanIsCompletedByRounding) {
  // LittleDog 36 without the quick dive: relax-and-fix's seed is the only source of a plan,
  // and the deadline passes right after the relaxation of its stage `cut_stage`. The
  // seed's completion (the rest rounded from the latest completed stage's point) runs
  // within the overrun. (Before, it ran under the expired deadline: each QP ended at once,
  // no plan.)
  Course c = LittleDogTableI(36);
  c.request.time_limit_s = 2.0;
  PlannerOptions options = ShortClockOptions(c);
  options.relax_and_fix.first_plan_dive = false;
  // Quick stages (one node, rounded): the seed reaches cut_stage within the limit.
  options.relax_and_fix.nodes_per_stage = 1;
  options.relax_and_fix.stage_rounding = true;
  const int full = FullIntegers(c);
  const int cut_stage = 8;
  std::set<int> stages;  // a stage's problem has its own integer count, fewer than the window's
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(options.solvers.backend, 1);
  StallingSolver late(solvers.workers().front(), [&](const Miqp& p, int) {
    if (p.num_integer() < full) stages.insert(p.num_integer());
    return static_cast<int>(stages.size()) == cut_stage;
  });
  const Plan plan = PlanWith(c, options, &late);
  ASSERT_TRUE(late.stalled);
  ExpectCompletePlan(c, plan);
}

TEST(FirstPlanDeadline, ARootRelaxationNotSolvedInTimeEndsWithAStatusThatSaysSo) {
  // The deadline passes before the root relaxation's solve: nothing to round, no plan, and
  // the message says why (before: "no_solution after 1 nodes" alone).
  Course c = LittleDogTableI(24);
  c.request.time_limit_s = 1.0;
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(c.scenario.options.solvers.backend, 1);
  StallingSolver late(solvers.workers().front(), [](const Miqp&, int call) { return call == 1; }, /*before=*/true);
  const Plan plan = PlanWith(c, ShortClockOptions(c), &late);
  ASSERT_TRUE(late.stalled);
  EXPECT_EQ(plan.status, SolveStatus::kNoSolution);
  EXPECT_NE(plan.message.find("before its root relaxation was solved"), std::string::npos) << plan.message;
}

// Passes solves on to `inner` until `good_stage_calls` solves of a dive's stage problems
// (fewer integers than the window's) have been made; every later solve of a stage problem
// ends `failure` without solving, the first one after sleeping past the dive's share. The
// full problem's solves (the completion's) are passed on and counted apart.
class FailingStagesSolver : public RelaxationSolver {
 public:
  FailingStagesSolver(RelaxationSolver* inner, int full_integers, int good_stage_calls, RelaxationStatus failure,
                      double sleep_s)
      : inner_(inner), full_(full_integers), good_(good_stage_calls), failure_(failure), sleep_s_(sleep_s) {}
  RelaxationResult Solve(const Miqp& problem, const RelaxationRequest& request) override {
    ++calls;
    if (problem.num_integer() >= full_) {
      ++full_problem_calls;
      return inner_->Solve(problem, request);
    }
    if (++stage_calls <= good_) return inner_->Solve(problem, request);
    if (stage_calls == good_ + 1) std::this_thread::sleep_for(std::chrono::duration<double>(sleep_s_));
    RelaxationResult r;
    r.status = failure_;
    return r;
  }
  std::string Name() const override { return "failing " + inner_->Name(); }
  int calls = 0, stage_calls = 0, full_problem_calls = 0;

 private:
  RelaxationSolver* inner_;
  int full_, good_;
  RelaxationStatus failure_;
  double sleep_s_;
};

TEST(FirstPlanDeadline, ARoundingDiveStageWhoseRoundingsAllFailIsNotTakenForOneCutShort) {
  // LittleDog 36's rounding dive with a 1 s share: after its first two stage QPs, every
  // stage QP fails, the first after a 1.2 s pause, so the share has passed when the stage's
  // roundings have all failed. Infeasible roundings are a failed choice: no completion (its
  // QPs would solve the same roundings on the whole problem). (Before, a share that had
  // passed made it a stage cut short, and the completion solved them again.) A stage QP
  // ending unsolved after the share (kIterationLimit, as a deadline ends it) is a stage
  // cut short: the completion runs, on the whole problem.
  const Course c = LittleDogTableI(36);
  const PlannerOptions& options = c.scenario.options;
  const MiqpFormulation formulation(FirstWindowProblem(c.robot, c.regions, c.request, options), options.formulation);
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(options.solvers.backend, 1);
  const RelaxationResult root = solvers.workers().front()->Solve(formulation.miqp(), RelaxationRequest{});
  ASSERT_EQ(root.status, RelaxationStatus::kSolved);
  RelaxAndFixOptions rf = options.relax_and_fix;
  rf.stage = options.branch_and_bound;
  rf.stage.deadline = Deadline();
  rf.time_limit_s = 1.0;
  const int full = formulation.miqp().num_integer();

  FailingStagesSolver infeasible(solvers.workers().front(), full, 2, RelaxationStatus::kInfeasible, 1.2);
  const RelaxAndFixResult failed = RoundingDive(formulation, infeasible, root.x, rf);
  EXPECT_FALSE(failed.x.has_value());
  EXPECT_FALSE(failed.completed_by_rounding);
  EXPECT_EQ(infeasible.full_problem_calls, 0) << "the failed stage's roundings were solved again";
  EXPECT_EQ(failed.relaxations, infeasible.calls);

  FailingStagesSolver cut(solvers.workers().front(), full, 2, RelaxationStatus::kIterationLimit, 1.2);
  const RelaxAndFixResult completed = RoundingDive(formulation, cut, root.x, rf);
  EXPECT_EQ(completed.stages, failed.stages);
  EXPECT_EQ(cut.stage_calls, 3) << "a QP cut by the share leaves the stage's other roundings unjudged";
  EXPECT_GT(cut.full_problem_calls, 0) << "a stage cut short was not completed";
  EXPECT_EQ(completed.relaxations, cut.calls);
}

// Counts the solves it passes on to `inner`.
class CountingSolver : public RelaxationSolver {
 public:
  explicit CountingSolver(RelaxationSolver* inner) : inner_(inner) {}
  RelaxationResult Solve(const Miqp& problem, const RelaxationRequest& request) override {
    ++calls;
    return inner_->Solve(problem, request);
  }
  std::string Name() const override { return "counting " + inner_->Name(); }
  int calls = 0;

 private:
  RelaxationSolver* inner_;
};

// The QPs a window's search solves up to its first plan, its root relaxation included
// (the solve after which the first incumbent was offered), on an unhurried clock.
int QpsToTheFirstPlan(const Course& c, const PlannerOptions& options) {
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(options.solvers.backend, 1);
  CountingSolver counting(solvers.workers().front());
  int first = -1;
  PlannerOptions counted = options;
  counted.branch_and_bound.on_incumbent = [&](const BranchAndBoundResult&) {
    if (first < 0) first = counting.calls;
  };
  const Plan plan = PlanFootsteps(c.robot, c.regions, c.request, counted, std::vector<RelaxationSolver*>{&counting});
  EXPECT_TRUE(HasPlan(plan.status)) << ToString(plan.status) << ": " << plan.message;
  return first;
}

// Every QP index k from the root relaxation's to the first plan's, the deadline passing
// right after QP k (or, with `before`, while QP k runs: it starts once the deadline has
// passed): the indices at which the search ended without a plan. A root relaxation cut
// by the deadline (k = 1 with `before`) has nothing to round and is left out.
// With `past_the_plan`, the stall lasts until the whole plan's time limit has passed
// (the exactness step's reserve spent too), and one QP past the first plan is swept.
std::vector<int> StallsWithoutAPlan(const Course& c, const PlannerOptions& options, bool before,
                                    bool past_the_plan = false) {
  const int first = QpsToTheFirstPlan(c, options);
  EXPECT_GE(first, 1);
  std::vector<int> without_plan;
  for (int k = before ? 2 : 1; k <= first + (past_the_plan ? 1 : 0); ++k) {
    const RelaxationSolverSet solvers = MakeRelaxationSolvers(options.solvers.backend, 1);
    const Deadline plan_deadline = past_the_plan ? Deadline::After(c.request.time_limit_s) : Deadline();
    StallingSolver late(solvers.workers().front(), [k](const Miqp&, int call) { return call == k; }, before,
                        plan_deadline);
    const Plan plan = PlanWith(c, options, &late);
    if (!HasPlan(plan.status)) {
      without_plan.push_back(k);
      std::printf("  k = %d%s: %s: %s\n", k, before ? " (during)" : "", ToString(plan.status).c_str(),
                  plan.message.c_str());
    }
  }
  return without_plan;
}

std::string Listed(const std::vector<int>& ks) {
  std::string s;
  for (int k : ks) s += (s.empty() ? "" : " ") + std::to_string(k);
  return s;
}

// The sweep on a Table I instance.
void ExpectAPlanAtEveryStall(const std::string& file_name, int steps) {
  Course c = LoadTableICourse(file_name, steps);
  c.request.time_limit_s = 1.0;
  const PlannerOptions options = ShortClockOptions(c);
  for (bool before : {false, true}) {
    const std::vector<int> without_plan = StallsWithoutAPlan(c, options, before);
    EXPECT_TRUE(without_plan.empty()) << file_name << " " << steps << " steps: no plan when the deadline passed "
                                      << (before ? "during" : "after") << " QP k = " << Listed(without_plan);
  }
  // The exactness step on (the planner's own options), the stall running past the whole
  // plan's limit, so that the exactness step's reserve is spent too. The overrun is as
  // generous as above: how far a loaded machine gets within the default is the bench's
  // measure (docs/measurements.md), not a test's.
  PlannerOptions exact = c.scenario.options;
  exact.polish.completion_overrun_s = options.polish.completion_overrun_s;
  for (bool before : {false, true}) {
    const std::vector<int> without_plan = StallsWithoutAPlan(c, exact, before, /*past_the_plan=*/true);
    EXPECT_TRUE(without_plan.empty()) << file_name << " " << steps << " steps: no plan when the plan's limit passed "
                                      << (before ? "during" : "after") << " QP k = " << Listed(without_plan);
  }
}

TEST(FirstPlanDeadline, EveryQpAtWhichTheDeadlinePassesStillGivesAPlanLittleDog36) {
  ExpectAPlanAtEveryStall("littledog_stepping_stones_45.yaml", 36);
}

TEST(FirstPlanDeadline, EveryQpAtWhichTheDeadlinePassesStillGivesAPlanLittleDog24) {
  ExpectAPlanAtEveryStall("littledog_stepping_stones_45.yaml", 24);
}

TEST(FirstPlanDeadline, EveryQpAtWhichTheDeadlinePassesStillGivesAPlanLittleDog12) {
  ExpectAPlanAtEveryStall("littledog_stepping_stones_45.yaml", 12);
}

TEST(FirstPlanDeadline, EveryQpAtWhichTheDeadlinePassesStillGivesAPlanHexapod) {
  ExpectAPlanAtEveryStall("hexapod_stepping_stones_45.yaml", 12);
  ExpectAPlanAtEveryStall("hexapod_stepping_stones_45.yaml", 24);
  ExpectAPlanAtEveryStall("hexapod_stepping_stones_45.yaml", 36);
}

TEST(FirstPlanDeadline, AFirstPlanFoundAsThePlansTimeRunsOutIsStillPolished) {
  // LittleDog 36 (its MIQP plan exceeds the exact reach by the chords' error): the clock
  // passes the whole plan's limit right after the QP that follows its first plan, so the
  // exactness step's reserve is spent before the polisher starts. The polisher of the
  // plan's first plan runs within the overrun and makes it exact. (Before, it got a
  // millisecond, made nothing exact, and the window was planned again within the chords'
  // error with no time: on a loaded machine hexapod 36 ended no_solution that way with a
  // plan in hand, 2 of 10 runs at --time-limit 1.)
  Course c = LittleDogTableI(36);
  c.request.time_limit_s = 1.0;
  PlannerOptions options = c.scenario.options;
  options.polish.completion_overrun_s = 10.0;  // generous for a loaded machine
  const int first = QpsToTheFirstPlan(c, options);
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(options.solvers.backend, 1);
  StallingSolver late(solvers.workers().front(), [first](const Miqp&, int call) { return call == first + 1; },
                      /*before=*/false, Deadline::After(c.request.time_limit_s));
  const Plan plan = PlanWith(c, options, &late);
  ASSERT_TRUE(late.stalled);
  ExpectCompletePlan(c, plan);
  EXPECT_TRUE(plan.window_records.front().polished) << plan.message;
  EXPECT_FALSE(plan.window_records.front().replanned) << plan.message;
}

// Passes solves on to `inner`, each marked as solved by the solver's fallback.
class AllFallbackSolver : public RelaxationSolver {
 public:
  explicit AllFallbackSolver(RelaxationSolver* inner) : inner_(inner) {}
  RelaxationResult Solve(const Miqp& problem, const RelaxationRequest& request) override {
    RelaxationResult r = inner_->Solve(problem, request);
    r.fallbacks += 1;
    return r;
  }
  std::string Name() const override { return "fallback " + inner_->Name(); }

 private:
  RelaxationSolver* inner_;
};

TEST(FirstPlanDeadline, ThePlansFallbacksCountItsRootHeuristicsQps) {
  // LittleDog 36 cut to its root node, every QP marked as a fallback's: the rounding dive
  // gives the first plan and the seed runs after it; the plan's fallbacks are all its QPs.
  // (Before, the dives' and the seed's fallbacks were not counted.)
  Course c = LittleDogTableI(36);
  c.request.time_limit_s = 5.0;
  PlannerOptions options = c.scenario.options;
  options.branch_and_bound.max_nodes = 1;
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(options.solvers.backend, 1);
  AllFallbackSolver marked(solvers.workers().front());
  const Plan plan = PlanFootsteps(c.robot, c.regions, c.request, options, std::vector<RelaxationSolver*>{&marked});
  ASSERT_TRUE(HasPlan(plan.status)) << ToString(plan.status) << ": " << plan.message;
  ASSERT_GT(plan.window_records.front().heuristic_relaxations, 0);
  EXPECT_EQ(plan.relaxation_fallbacks, plan.relaxations);
}

}  // namespace
}  // namespace mfp
