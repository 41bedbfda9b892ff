// Deadlines and stop flags hold inside a solve: the interior point QP and Ipopt stop at
// their next iteration, the search at its next node, the planner with the best so far.
#include "base/deadline.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "base/check.h"
#include "geometry/region_reachability.h"
#include "io/robot_loader.h"
#include "io/scenario_yaml.h"
#include "planner/formulation/miqp_formulation.h"
#include "planner/miqp/miqp_builder.h"
#include "planner/planning/footstep_planner.h"
#include "planner/qp/interior_point_qp.h"
#include "planner/qp/internal/ipm_relaxation_solver.h"
#include "planner/qp/internal/ipopt_relaxation_solver.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "planner/search/branch_and_bound.h"

namespace mfp {
namespace {

TEST(Deadline, NeverAfterWithinAndStop) {
  EXPECT_FALSE(Deadline().Expired());
  EXPECT_EQ(Deadline().RemainingSeconds(), std::numeric_limits<double>::infinity());
  EXPECT_TRUE(Deadline::After(0.0).Expired());
  EXPECT_FALSE(Deadline::After(100.0).Expired());
  EXPECT_LE(Deadline::After(100.0).Within(1.0).RemainingSeconds(), 1.0);
  EXPECT_LE(Deadline().Within(2.0).RemainingSeconds(), 2.0);
  EXPECT_LE(Deadline::After(1.0).Within(100.0).RemainingSeconds(), 1.0);
  std::atomic<bool> stop{false};
  const Deadline d = Deadline::After(100.0).WithStop(&stop).Within(50.0);
  EXPECT_FALSE(d.Expired());
  stop = true;
  EXPECT_TRUE(d.Expired());
  EXPECT_TRUE(d.Stopped());
  EXPECT_EQ(d.RemainingSeconds(), 0.0);
}

TEST(Deadline, ExtendedByMovesTheTimeAndKeepsTheFlag) {
  EXPECT_FALSE(Deadline().ExtendedBy(1.0).finite());
  EXPECT_TRUE(Deadline::After(0.0).ExtendedBy(0.0).Expired());
  const Deadline later = Deadline::After(0.0).ExtendedBy(50.0);
  EXPECT_FALSE(later.Expired());
  EXPECT_GT(later.RemainingSeconds(), 40.0);
  EXPECT_LE(later.RemainingSeconds(), 50.0);
  EXPECT_LE(Deadline::After(1.0).ExtendedBy(-5.0).RemainingSeconds(), 1.0);  // never sooner
  EXPECT_GT(Deadline::After(1.0).ExtendedBy(-5.0).RemainingSeconds(), 0.5);
  std::atomic<bool> stop{false};
  const Deadline d = Deadline::After(0.0).WithStop(&stop).ExtendedBy(50.0);
  EXPECT_FALSE(d.Expired());
  stop = true;
  EXPECT_TRUE(d.Expired());
}

// n variables, each pulled to a target outside a shared budget row: many iterations.
Miqp Qp(int n) {
  MiqpBuilder b;
  LinExpr sum;
  for (int j = 0; j < n; ++j) {
    const int x = b.AddVariable("x" + std::to_string(j), -1, 1, j % 2 == 0);
    b.AddSquaredCost(LinExpr::Var(x) - LinExpr::Constant(0.3 + 0.01 * j), 1.0);
    sum += LinExpr::Var(x);
  }
  b.AddRow("budget", sum, -kInfinity, 0.5);
  return b.Build();
}

TEST(Deadline, EverySolverStopsAtItsNextIterationWhenStopped) {
  const Miqp p = Qp(20);
  std::atomic<bool> stop{true};
  const Deadline stopped = Deadline().WithStop(&stop);
  InteriorPointOptions options;
  options.deadline = stopped;
  const RelaxationResult direct = SolveQpInteriorPoint(p, p.var_lower, p.var_upper, nullptr, options);
  EXPECT_EQ(direct.status, RelaxationStatus::kIterationLimit);
  EXPECT_EQ(direct.iterations, 0);
  for (RelaxationBackend backend : {RelaxationBackend::kIpopt, RelaxationBackend::kInteriorPointWithIpoptFallback}) {
    const auto solver = MakeRelaxationSolver(backend);
    RelaxationRequest request;
    request.deadline = stopped;
    const RelaxationResult r = solver->Solve(p, request);
    EXPECT_EQ(r.status, RelaxationStatus::kIterationLimit) << solver->Name();
    stop = false;  // the same request solves once the flag is down
    EXPECT_EQ(solver->Solve(p, request).status, RelaxationStatus::kSolved)
        << solver->Name();
    stop = true;
  }
}

// n variables in a chain of coupling rows: Ipopt iterates tens of times over it.
Miqp ChainQp(int n) {
  MiqpBuilder b;
  std::vector<int> x;
  for (int j = 0; j < n; ++j) {
    x.push_back(b.AddVariable("x" + std::to_string(j), -10, 10, false));
    b.AddSquaredCost(LinExpr::Var(x.back()) - LinExpr::Constant(std::sin(0.1 * j)), 1.0);
  }
  for (int j = 0; j + 1 < n; ++j) {
    b.AddRow("chain" + std::to_string(j), LinExpr::Var(x[j]) - LinExpr::Var(x[j + 1]), -0.01, 0.01);
  }
  return b.Build();
}

TEST(Deadline, IpoptStopsInsideASolveAtItsIntermediateCallback) {
  // The deadline passes while Ipopt iterates: its intermediate callback ends the solve
  // after some iterations but before it converges (the check before a solve is not it:
  // the solve has begun).
  const Miqp p = ChainQp(4000);
  const auto solver = MakeRelaxationSolver(RelaxationBackend::kIpopt);
  const auto start = std::chrono::steady_clock::now();
  const RelaxationResult full = solver->Solve(p, RelaxationRequest());
  const double full_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(full.status, RelaxationStatus::kSolved);
  ASSERT_GE(full.iterations, 8) << "the test needs a solve of several iterations";
  // Stopped by a flag raised from another thread, as the daemon's SIGTERM handler does.
  std::atomic<bool> stop{false};
  RelaxationRequest flagged;
  flagged.deadline = Deadline().WithStop(&stop);
  std::thread raise([&stop, full_s] {
    std::this_thread::sleep_for(std::chrono::duration<double>(0.4 * full_s));
    stop = true;
  });
  const RelaxationResult stopped = solver->Solve(p, flagged);
  raise.join();
  EXPECT_EQ(stopped.status, RelaxationStatus::kIterationLimit);
  EXPECT_LT(stopped.iterations, full.iterations);
  // A deadline (no flag) stops it the same way, and the solve had begun: the check
  // before a solve passes (the deadline is half a solve away), so the stop is Ipopt's.
  RelaxationRequest timed_request;
  timed_request.deadline = Deadline::After(0.5 * full_s);
  const RelaxationResult timed = solver->Solve(p, timed_request);
  EXPECT_EQ(timed.status, RelaxationStatus::kIterationLimit);
  EXPECT_GE(timed.iterations, 1);
  EXPECT_LT(timed.iterations, full.iterations);
}

TEST(Deadline, SearchStopsWhenTheFlagIsSetDuringIt) {
  // The flag goes up inside the root's rounding, mid-search: no node after the root is
  // solved and the result says time_limit, keeping the rounding's incumbent.
  const Miqp p = Qp(16);
  std::atomic<bool> stop{false};
  BranchAndBoundOptions options;
  options.time_limit_s = 3600.0;
  options.deadline = Deadline().WithStop(&stop);
  const RoundingHeuristic raise = [&stop](const Eigen::VectorXd&) {
    stop = true;
    return std::vector<Eigen::VectorXd>{};
  };
  const auto solver = MakeRelaxationSolver(RelaxationBackend::kInteriorPointWithIpoptFallback);
  const BranchAndBoundResult r = SolveBranchAndBound(p, *solver, options, raise);
  EXPECT_TRUE(stop);
  EXPECT_EQ(r.nodes, 1);
  EXPECT_TRUE(r.status == SolveStatus::kTimeLimit || r.status == SolveStatus::kNoSolution)
      << ToString(r.status);
  // Without the flag the same search goes on past the root.
  std::atomic<bool> never{false};
  options.deadline = Deadline().WithStop(&never);
  EXPECT_GT(SolveBranchAndBound(p, *solver, options).nodes, 1);
}

TEST(Deadline, APlanStopsAtTheFlagAndKeepsWhatItHas) {
  // A stop flag raised after the first window (from the progress callback, as a daemon's
  // SIGTERM handler would from its own thread): the plan returns at once, with the first
  // window's steps and status partial (a valid plan short of the goal, safe to execute)
  // whose message says it was stopped.
  const Scenario s = LoadScenario(std::string(MFP_SOURCE_DIR) + "/config/scenarios/hexapod_flat.yaml");
  const RobotModel robot = LoadRobot(s.robot_path);
  const std::vector<ConvexRegion> regions = ScenarioRegions(s, robot, nullptr);
  PlanRequest request = ScenarioRequest(s, robot, regions);
  std::atomic<bool> stop{false};
  request.deadline = Deadline().WithStop(&stop);
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(s.options.solvers.backend, 1);
  int windows = 0;
  const Plan plan = PlanFootsteps(robot, regions, request, s.options, solvers.workers(),
                                  [&](const PlanProgress& p) {
                                    windows = p.window;
                                    stop = true;
                                  });
  EXPECT_EQ(windows, 1);
  EXPECT_EQ(plan.status, SolveStatus::kPartial);
  EXPECT_NE(plan.message.find("stopped"), std::string::npos) << plan.message;
  EXPECT_GT(plan.footsteps.size(), static_cast<size_t>(robot.num_legs()));
  EXPECT_FALSE(plan.reaches_goal);
}

// A grid of rows x cols touching 20 cm squares at z = 0: every one reachable from the
// first, through chains that visit them all.
std::vector<ConvexRegion> SquareGrid(int rows, int cols) {
  std::vector<ConvexRegion> out;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const double x = 0.2 * c, y = 0.2 * r;
      out.push_back(MakeRegionFromPolygon(static_cast<int>(out.size()),
                                          {{x, y, 0.0}, {x + 0.2, y, 0.0}, {x + 0.2, y + 0.2, 0.0}, {x, y + 0.2, 0.0}},
                                          0.0));
    }
  }
  return out;
}

TEST(Deadline, RegionReachabilityEndsAtAnExpiredDeadlineOrTheFlag) {
  const std::vector<ConvexRegion> regions = SquareGrid(25, 40);  // 1000 regions
  const std::vector<Eigen::Vector3d> feet = {{0.1, 0.1, 0.0}};
  const std::optional<std::vector<int>> all = ReachableRegionIndices(regions, feet, 0.1, 0.05, 0.01);
  ASSERT_TRUE(all.has_value());
  EXPECT_EQ(all->size(), regions.size());
  EXPECT_FALSE(ReachableRegionIndices(regions, feet, 0.1, 0.05, 0.01, Deadline::After(0.0)).has_value());
  std::atomic<bool> stop{true};
  EXPECT_FALSE(ReachableRegionIndices(regions, feet, 0.1, 0.05, 0.01, Deadline().WithStop(&stop)).has_value());
}

// Deriving a robot from its URDF: an expired deadline or a set stop flag ends it with
// TimeLimitError naming the stage; a robot YAML that names a URDF gets the same.
TEST(Deadline, RobotDerivationEndsAtAnExpiredDeadlineOrTheFlag) {
  const std::string urdf = std::string(MFP_SOURCE_DIR) + "/config/robots/octopod.urdf";
  const std::string yaml = std::string(MFP_SOURCE_DIR) + "/config/robots/hexapod.yaml";
  for (const std::string& path : {urdf, yaml}) {
    try {
      LoadRobot(path, nullptr, Deadline::After(0.0));
      ADD_FAILURE() << path << ": derived past an expired deadline";
    } catch (const TimeLimitError& e) {
      EXPECT_NE(std::string(e.what()).find("time limit reached while deriving the robot"), std::string::npos)
          << e.what();
    }
  }
  std::atomic<bool> stop{true};
  EXPECT_THROW(LoadRobot(urdf, nullptr, Deadline().WithStop(&stop)), TimeLimitError);
  EXPECT_EQ(LoadRobot(urdf, nullptr, Deadline::After(600.0)).num_legs(), 8);
}

struct HexapodFlat {
  HexapodFlat()
      : scenario(LoadScenario(std::string(MFP_SOURCE_DIR) + "/config/scenarios/hexapod_flat.yaml")),
        robot(LoadRobot(scenario.robot_path)),
        regions(ScenarioRegions(scenario, robot, nullptr)),
        request(ScenarioRequest(scenario, robot, regions)) {}
  Scenario scenario;
  RobotModel robot;
  std::vector<ConvexRegion> regions;
  PlanRequest request;
};

TEST(Deadline, AWindowMiqpBuildStopsAtAnExpiredDeadlineOrTheFlag) {
  const HexapodFlat h;
  const FootstepProblem problem = FirstWindowProblem(h.robot, h.regions, h.request, h.scenario.options);
  const MiqpFormulation built(problem, h.scenario.options.formulation);
  EXPECT_FALSE(built.out_of_time());
  EXPECT_GT(built.miqp().num_integer(), 0);
  const MiqpFormulation expired(problem, h.scenario.options.formulation, Deadline::After(0.0));
  EXPECT_TRUE(expired.out_of_time());
  EXPECT_EQ(expired.miqp().num_variables(), 0);  // nothing built
  std::atomic<bool> stop{true};
  const MiqpFormulation stopped(problem, h.scenario.options.formulation, Deadline().WithStop(&stop));
  EXPECT_TRUE(stopped.out_of_time());
}

TEST(Deadline, APlanGivenAnExpiredDeadlineEndsOnTimeLimitBeforeAnyWindow) {
  // Unguided, the first stage to see the deadline is the reachable regions: status
  // time_limit naming it, no window built, no node solved.
  HexapodFlat h;
  PlannerOptions options = h.scenario.options;
  options.route_guidance = false;
  h.request.deadline = Deadline::After(0.0);
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(options.solvers.backend, 1);
  const Plan timed = PlanFootsteps(h.robot, h.regions, h.request, options, solvers.workers());
  EXPECT_EQ(timed.status, SolveStatus::kTimeLimit) << timed.message;
  EXPECT_NE(timed.message.find("time limit reached while the regions the start stance can reach"), std::string::npos)
      << timed.message;
  EXPECT_EQ(timed.windows, 0);
  EXPECT_EQ(timed.nodes, 0);
  std::atomic<bool> stop{true};
  h.request.deadline = Deadline().WithStop(&stop);
  const Plan stopped = PlanFootsteps(h.robot, h.regions, h.request, options, solvers.workers());
  EXPECT_EQ(stopped.status, SolveStatus::kTimeLimit);
  EXPECT_EQ(stopped.message.rfind("stopped", 0), 0u) << stopped.message;
  EXPECT_EQ(stopped.windows, 0);
}

}  // namespace
}  // namespace mfp
