// The convex-hull (disaggregated) encoding of the region choice has a relaxation no
// weaker than the big-M one, checked on a hand-built instance: its root bound is at
// least big-M's, and with the region binaries held at an even split (a fractional point
// of both relaxations) strictly above it: there a big-M foot may stand anywhere the
// loosened rows allow, a hull foot only at the mean of a point of each stone.
//
// Instance: the square test quadruped (d_lim 0.15, l_bnd 0.05) starts at the origin on
// r0 = [-0.5, 0.15] x [-0.5, 0.5] (z 0); r1 = [0.25, 1.0] x [0.3, 0.5] (z 0.05) lies
// ahead and to the left; the goal (0.5, -0.3) ahead and to the right.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "planner/formulation/miqp_formulation.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "tests/test_robots.h"

namespace mfp {
namespace {

ConvexRegion Rectangle(int id, double x0, double x1, double y0, double y1, double z) {
  return MakeRegionFromPolygon(id, {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}}, 0.0);
}

// The relaxation's optimum; with split_regions, every region binary held at 1 / (number
// of regions of its step).
double RelaxationBound(const FootstepProblem& problem, RegionEncoding encoding, bool split_regions) {
  FormulationOptions options;
  options.region_encoding = encoding;
  options.prune_unreachable_regions = false;  // both stones for every step
  const MiqpFormulation formulation(problem, options);
  const Miqp& m = formulation.miqp();
  RelaxationRequest request;
  request.lower = m.var_lower;
  request.upper = m.var_upper;
  if (split_regions) {
    for (const std::vector<int>& step : formulation.vars().region) {
      const auto members = std::count_if(step.begin(), step.end(), [](int h) { return h >= 0; });
      for (int h : step) {
        if (h >= 0) request.lower(h) = request.upper(h) = 1.0 / static_cast<double>(members);
      }
    }
  }
  const RelaxationResult r = MakeRelaxationSolver(RelaxationBackend::kIpopt)->Solve(m, request);
  EXPECT_EQ(r.status, RelaxationStatus::kSolved);
  return r.objective;
}

TEST(RegionEncodingBound, ConvexHullRelaxationIsNoWeakerThanBigM) {
  const RobotModel robot = SquareQuadruped(0.15, 0.05);
  FootstepProblem problem;
  problem.robot = &robot;
  problem.regions = {Rectangle(0, -0.5, 0.15, -0.5, 0.5, 0.0), Rectangle(1, 0.25, 1.0, 0.3, 0.5, 0.05)};
  problem.start_feet_world_m = {{0.1, 0.1, 0}, {0.1, -0.1, 0}, {-0.1, 0.1, 0}, {-0.1, -0.1, 0}};
  problem.goal_x_m = 0.5;
  problem.goal_y_m = -0.3;
  problem.num_new_steps = 8;
  for (const bool split : {false, true}) {
    const double big_m = RelaxationBound(problem, RegionEncoding::kBigM, split);
    const double hull = RelaxationBound(problem, RegionEncoding::kConvexHull, split);
    const double tol = 1e-6 * std::max(1.0, std::abs(big_m));
    EXPECT_GE(hull, big_m - tol) << (split ? "regions split evenly" : "root");
    if (split) {
      EXPECT_GT(hull, big_m + 1e-3 * std::abs(big_m)) << "the split is where the hull is tighter";
    }
  }
}

}  // namespace
}  // namespace mfp
