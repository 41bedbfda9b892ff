// Region pruning by the footprint shape's step boxes (FootprintStepBoxes): each box holds
// every point the MIQP's continuous relaxation can give the step's foot (so no region a
// plan can stand on is dropped), a first configuration's box is exactly the polygon's, and
// the pruning keeps far fewer binaries than MaxMovesXY's bound.
//
// Robot: four legs at (+-0.1, +-0.1), each with the same lopsided footprint polygon about
// its nominal foot (0.2 m forward, 0.08 m back, 0.12 m to each side, cut at the diagonals),
// two configurations (8 new steps) towards a goal turned 0.4 rad. Regions: a field of
// 6 cm squares every 15 cm over [-0.6, 0.6]^2.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "planner/formulation/centre_of_contacts.h"
#include "planner/formulation/internal/footprint_step_boxes.h"
#include "planner/formulation/internal/step_expressions.h"
#include "planner/formulation/internal/yaw_chords.h"
#include "planner/formulation/miqp_formulation.h"
#include "planner/formulation/step_limits.h"
#include "planner/formulation/workspace_box.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "tests/test_robots.h"

namespace mfp {
namespace {

RobotModel LopsidedFootprintQuadruped() {
  RobotModel robot = SquareQuadruped(0.1, 0.05);
  robot.reach_shape = ReachShape::kFootprint;
  const double s = 1.0 / std::sqrt(2.0);
  for (LegModel& leg : robot.legs) {
    leg.footprint_faces = {{{1, 0}, 0.2},  {{-1, 0}, 0.08}, {{0, 1}, 0.12},  {{0, -1}, 0.12},
                           {{s, s}, 0.2},  {{s, -s}, 0.2},  {{-s, s}, 0.12}, {{-s, -s}, 0.12}};
  }
  return robot;
}

FootstepProblem StonesProblem(const RobotModel& robot) {
  FootstepProblem problem;
  problem.robot = &robot;
  int id = 0;
  for (double x = -0.6; x < 0.6 + 1e-9; x += 0.15) {
    for (double y = -0.6; y < 0.6 + 1e-9; y += 0.15) {
      problem.regions.push_back(MakeRegionFromPolygon(
          id++, {{x - 0.03, y - 0.03, 0}, {x + 0.03, y - 0.03, 0}, {x + 0.03, y + 0.03, 0}, {x - 0.03, y + 0.03, 0}},
          0.0));
    }
  }
  problem.start_feet_world_m = {{0.1, 0.1, 0}, {0.1, -0.1, 0}, {-0.1, 0.1, 0}, {-0.1, -0.1, 0}};
  problem.goal_x_m = 1.0;
  problem.goal_y_m = 0.3;
  problem.goal_yaw_rad = 0.4;
  problem.num_new_steps = 8;
  return problem;
}

// Regions whose box meets [lo, hi] in plan view.
std::vector<int> RegionsMeeting(const FootstepProblem& problem, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  std::vector<int> out;
  for (int r = 0; r < static_cast<int>(problem.regions.size()); ++r) {
    Eigen::Vector2d rlo = Eigen::Vector2d::Constant(1e9), rhi = Eigen::Vector2d::Constant(-1e9);
    for (const Eigen::Vector3d& v : problem.regions[r].vertices_world_m) {
      rlo = rlo.cwiseMin(v.head<2>());
      rhi = rhi.cwiseMax(v.head<2>());
    }
    if ((rlo - hi).maxCoeff() <= 0.0 && (lo - rhi).maxCoeff() <= 0.0) out.push_back(r);
  }
  return out;
}

// The step boxes as the formulation computes them: the same positions, centres of contacts
// and yaw variables (their bounds are all FootprintStepBoxes reads).
std::vector<Eigen::AlignedBox2d> StepBoxes(const FootstepProblem& problem) {
  const RobotModel& robot = *problem.robot;
  const int n = robot.num_legs(), N = n + problem.num_new_steps;
  FootstepVariables vars;
  MiqpBuilder b;
  const StepExpressions e(problem, vars);
  const Box3 box = MakeWorkspaceBox(problem.regions, problem.start_feet_world_m);
  AddFootstepPositions(box, N, n, &b, &vars);
  AddCentreOfContacts(e, box, N, &b, &vars);
  AddYawVariables(MakeYawGrid(problem.start_yaw_rad, problem.goal_yaw_rad, robot.max_yaw_change_rad, (N + n - 1) / n,
                              FormulationOptions()),
                  &b, &vars);
  return FootprintStepBoxes(e, b, robot, N);
}

TEST(FootprintStepBoxes, PruningKeepsEveryRegionTheRelaxationCanReachAndDropsMoreThanTheMoveBound) {
  const RobotModel robot = LopsidedFootprintQuadruped();
  const FootstepProblem problem = StonesProblem(robot);
  FormulationOptions all;
  all.prune_unreachable_regions = false;
  const MiqpFormulation unpruned(problem, all);
  const MiqpFormulation pruned(problem, FormulationOptions());
  ASSERT_TRUE(unpruned.infeasible_reason().empty());
  ASSERT_TRUE(pruned.infeasible_reason().empty());
  // Where the continuous relaxation of the unpruned MIQP can put each new foot (each
  // coordinate minimised and maximised: a linear objective, the binaries in [0, 1]). Every
  // plan is a point of it, and the boxes are derived from rows and bounds it keeps, so a
  // region that meets these extremes' box must keep its binary.
  const std::unique_ptr<RelaxationSolver> solver = MakeRelaxationSolver(RelaxationBackend::kInteriorPointWithIpoptFallback);
  Miqp lp = unpruned.miqp();
  lp.Q.setZero();
  const FootstepVariables& v = unpruned.vars();
  const int n = robot.num_legs();
  int kept_pruned = 0, kept_by_move_bound = 0;
  const StepExpressions e(problem, v);
  const std::vector<double> moves = MaxMovesXY(e, robot, n + problem.num_new_steps);
  const std::vector<Eigen::AlignedBox2d> boxes = StepBoxes(problem);
  std::vector<double> reach(n + problem.num_new_steps, 0.0);  // a leg's move bound summed over its steps
  for (int i = n; i < n + problem.num_new_steps; ++i) {
    Eigen::Vector2d lo, hi;
    for (int axis = 0; axis < 2; ++axis) {
      for (const double sign : {1.0, -1.0}) {
        lp.c.setZero();
        lp.c(axis == 0 ? v.x[i] : v.y[i]) = sign;
        const RelaxationResult r = solver->Solve(lp, RelaxationRequest());
        ASSERT_EQ(r.status, RelaxationStatus::kSolved) << "step " << i;
        const double at = r.x(axis == 0 ? v.x[i] : v.y[i]);
        (sign > 0 ? lo : hi)(axis) = at + (sign > 0 ? -1e-6 : 1e-6);
      }
    }
    // The box holds the relaxation's extremes; a first configuration's box is the start
    // nominal foot's polygon box, which the relaxation reaches on every side.
    EXPECT_TRUE(boxes[i].contains(Eigen::AlignedBox2d(lo + Eigen::Vector2d::Constant(2e-6), hi - Eigen::Vector2d::Constant(2e-6))))
        << "step " << i << ": relaxation [" << lo.transpose() << "] - [" << hi.transpose() << "], box ["
        << boxes[i].min().transpose() << "] - [" << boxes[i].max().transpose() << "]";
    if (i < 2 * n) {
      EXPECT_LT((boxes[i].min() - lo).cwiseAbs().maxCoeff(), 1e-4) << "step " << i;
      EXPECT_LT((boxes[i].max() - hi).cwiseAbs().maxCoeff(), 1e-4) << "step " << i;
    }
    for (const int r : RegionsMeeting(problem, lo, hi)) {
      EXPECT_GE(pruned.vars().region[i][r], 0) << "step " << i << " lost region " << r << ", which the relaxation reaches";
    }
    for (int r = 0; r < static_cast<int>(problem.regions.size()); ++r) kept_pruned += pruned.vars().region[i][r] >= 0;
    // What MaxMovesXY's bound alone keeps: regions within the leg's moves so far of its start foot.
    reach[i] = (i - n < n ? 0.0 : reach[i - n]) + moves[i];
    const Eigen::Vector2d start = problem.start_feet_world_m[(i - n) % n].head<2>();
    kept_by_move_bound += static_cast<int>(
        RegionsMeeting(problem, start - Eigen::Vector2d::Constant(reach[i]), start + Eigen::Vector2d::Constant(reach[i]))
            .size());
  }
  EXPECT_LT(kept_pruned, 0.6 * kept_by_move_bound) << kept_pruned << " binaries against " << kept_by_move_bound;
}

}  // namespace
}  // namespace mfp
