// Erased floor (issue 25: "known-free floor-level cells are never floor"): a single cell of
// a seen floor with no occupied voxel in its column and its floor-level voxel known free is
// filled for the plane fit and the segmentation only. No region holds a foot centre whose
// disk reaches the cell, the seen surface leaves it out (start and goal footholds), and a
// plan across a floor with such cells puts no foot on one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "geometry/convex_region.h"
#include "geometry/seen_surface.h"
#include "planner/qp/relaxation_solver_factory.h"
#include "terrain/extraction/occupancy_map.h"
#include "terrain/extraction/region_extractor.h"
#include "tests/test_scenarios.h"

namespace mfp {
namespace {

constexpr double kRes = 0.05;  // voxel edge, as the scanned lab fr_079's [m]

// A flat floor seen from above, columns (i, j) for i in [0, nx), j in [0, ny) whose
// squares start at origin: one occupied voxel with its top at z = 0, known free space 0.6 m
// above it; an erased column has no occupied voxel and is known free from the floor's
// voxel up (a ray passed where the floor's top would be).
struct ErasedFloor {
  int nx = 0, ny = 0;
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();
  std::vector<std::pair<int, int>> erased;

  bool IsErased(int i, int j) const {
    return std::find(erased.begin(), erased.end(), std::make_pair(i, j)) != erased.end();
  }
  OccupancyMap Map() const {
    OccupancyMap map;
    map.resolution_m = kRes;
    for (int i = 0; i < nx; ++i) {
      for (int j = 0; j < ny; ++j) {
        const double x = origin_m.x() + (i + 0.5) * kRes, y = origin_m.y() + (j + 0.5) * kRes;
        const bool gone = IsErased(i, j);
        if (!gone) map.leaves.push_back({{x, y, -0.5 * kRes}, kRes});
        for (int k = gone ? -1 : 0; k < 12; ++k) map.free_leaves.push_back({{x, y, (k + 0.5) * kRes}, kRes});
      }
    }
    return map;
  }
  // Plan distance from p to the square of column (i, j) [m] (0 inside it).
  double DistanceToColumn(const Eigen::Vector2d& p, int i, int j) const {
    const Eigen::Vector2d lo = origin_m + kRes * Eigen::Vector2d(i, j), hi = lo + Eigen::Vector2d(kRes, kRes);
    const Eigen::Vector2d d = (lo - p).cwiseMax(p - hi).cwiseMax(0.0);
    return d.norm();
  }
  // The least plan distance from p to an erased column's square [m].
  double DistanceToErased(const Eigen::Vector2d& p) const {
    double best = INFINITY;
    for (const auto& [i, j] : erased) best = std::min(best, DistanceToColumn(p, i, j));
    return best;
  }
  Eigen::Vector2d Centre(int i, int j) const { return origin_m + kRes * Eigen::Vector2d(i + 0.5, j + 0.5); }
};

bool AnyRegionHolds(const std::vector<ConvexRegion>& regions, const Eigen::Vector2d& p) {
  return std::any_of(regions.begin(), regions.end(),
                     [&](const ConvexRegion& r) { return PlanDistanceToRegion(r, p) <= 0.0; });
}

TEST(ErasedFloor, NoRegionNorSeenSurfaceReachesASingleErasedCell) {
  const Course course = LoadCourse("hexapod_flat.yaml");
  const double foot_m = course.robot.foot_radius_m;
  ErasedFloor floor;
  floor.nx = floor.ny = 40;
  floor.erased = {{20, 20}};
  const RegionExtractorOptions options = ScenarioRegionOptions(course.scenario, course.robot);
  const RegionExtractionResult result = ExtractRegions(floor.Map(), options);
  // The cell is filled (one floor, one plane), and the fill is recorded as erased.
  ASSERT_EQ(result.filled.size(), result.layers.size());
  const HeightMap& layer = result.layers.front();
  const Eigen::Vector2d centre = floor.Centre(20, 20);
  const int cell = layer.Index(static_cast<int>(std::floor((centre.y() - layer.origin_world_m.y()) / kRes)),
                               static_cast<int>(std::floor((centre.x() - layer.origin_world_m.x()) / kRes)));
  EXPECT_FALSE(std::isnan(layer.height_m[static_cast<size_t>(cell)]));
  EXPECT_EQ(result.filled.front()[static_cast<size_t>(cell)], kFilledErased);
  // No foot centre whose disk overlaps the cell is in a region (sampled every 2 mm) ...
  int near_points = 0;
  for (double dx = -0.1; dx <= 0.1; dx += 0.002) {
    for (double dy = -0.1; dy <= 0.1; dy += 0.002) {
      const Eigen::Vector2d p = centre + Eigen::Vector2d(dx, dy);
      if (floor.DistanceToErased(p) >= foot_m) continue;
      ++near_points;
      EXPECT_FALSE(AnyRegionHolds(result.regions, p)) << p.transpose();
    }
  }
  EXPECT_GT(near_points, 100);
  // ... while the floor around it keeps its regions: no edge uncertainty is added there.
  const double clear_m = foot_m + options.edge_margin_m + 0.005;
  EXPECT_TRUE(AnyRegionHolds(result.regions, centre + Eigen::Vector2d(0.5 * kRes + clear_m, 0.0)));
  EXPECT_TRUE(AnyRegionHolds(result.regions, centre + Eigen::Vector2d(0.0, -0.5 * kRes - clear_m)));
  // The seen surface has nothing there, so no start or goal foothold is certified on it;
  // a foothold beside it is.
  const SeenSurface seen = SeenSurfaceOfLayers(result.layers, result.moved_as_seen, result.filled);
  EXPECT_FALSE(HighestSeenSurfaceAt(seen, centre).has_value());
  EXPECT_TRUE(HighestSeenSurfaceAt(seen, centre + Eigen::Vector2d(kRes, 0.0)).has_value());
  EXPECT_FALSE(FlatSeenDisk(seen, centre + Eigen::Vector2d(0.5 * kRes + 0.5 * foot_m, 0.0), foot_m).has_value());
  EXPECT_TRUE(FlatSeenDisk(seen, centre + Eigen::Vector2d(0.3, 0.0), foot_m).has_value());
}

TEST(ErasedFloor, APlanAcrossErasedCellsPutsNoFootOnOne) {
  Course course = LoadCourse("hexapod_flat.yaml");
  ErasedFloor floor;
  floor.origin_m = {-0.8, -0.8};
  floor.nx = 64;  // x in [-0.8, 2.4]
  floor.ny = 32;  // y in [-0.8, 0.8]
  // Single erased cells every 0.2 m between the start stance and the goal's, across the
  // hexapod's whole width: each has its 8 neighbours seen.
  for (int i = 22; i <= 36; i += 4) {
    for (int j = 2; j <= 30; j += 4) floor.erased.emplace_back(i, j);
  }
  const RegionExtractorOptions options = ScenarioRegionOptions(course.scenario, course.robot);
  const RegionExtractionResult result = ExtractRegions(floor.Map(), options);
  ScenarioTerrain terrain;
  terrain.regions = result.regions;
  terrain.seen_surface =
      std::make_shared<const SeenSurface>(SeenSurfaceOfLayers(result.layers, result.moved_as_seen, result.filled));
  course.scenario.goal = {1.2, 0.0, 0.0};
  PlanRequest request = ScenarioRequest(course.scenario, course.robot, terrain);
  request.time_limit_s = 60.0;
  const RelaxationSolverSet solvers = MakeRelaxationSolvers(course.scenario.options.solvers);
  const Plan plan = PlanFootsteps(course.robot, terrain.regions, request, course.scenario.options, solvers.workers());
  ASSERT_TRUE(HasPlan(plan.status)) << ToString(plan.status) << ": " << plan.message;
  EXPECT_TRUE(plan.reaches_goal);
  // Every footstep, the start and final stances included, keeps its disk off every erased cell.
  int steps_among_erased = 0;
  for (const Footstep& step : plan.footsteps) {
    const Eigen::Vector2d p = step.position_world_m.head<2>();
    EXPECT_GE(floor.DistanceToErased(p), course.robot.foot_radius_m)
        << "step " << step.index << " at " << p.transpose() << " region " << step.region_id;
    steps_among_erased += p.x() > floor.Centre(22, 0).x() && p.x() < floor.Centre(36, 0).x() ? 1 : 0;
  }
  EXPECT_GT(steps_among_erased, 0);  // the plan does cross the erased cells' field
}

}  // namespace
}  // namespace mfp
