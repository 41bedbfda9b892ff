// The footprint grid's clearance and the NLopt inscribed square on footprints with known
// answers.
#include "planner/robot/internal/inscribed_square.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "planner/robot/internal/footprint_grid.h"

namespace mfp {
namespace {

FootprintGrid Fill(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double cell,
                   const std::function<bool(const Eigen::Vector2d&)>& inside) {
  FootprintGrid grid(lo, hi, cell);
  for (int iy = 0; iy < grid.ny(); ++iy) {
    for (int ix = 0; ix < grid.nx(); ++ix) grid.Set(ix, iy, inside(grid.CellCentre(ix, iy)));
  }
  grid.UpdateBoundary();
  return grid;
}

TEST(InscribedSquare, RectangleClearanceIsExactAndTiesGoToThePreferredCentre) {
  // Cells with centres in [0, 0.4] x [0, 0.1] at 0.01 m: the footprint is the union of
  // closed cells, [-0.005, 0.405] x [-0.005, 0.105]; best half-side 0.055.
  const double cell = 0.01;
  const FootprintGrid grid =
      Fill({-0.1, -0.1}, {0.5, 0.2}, cell, [](const Eigen::Vector2d& p) {
        return p.x() > -1e-9 && p.x() < 0.4 + 1e-9 && p.y() > -1e-9 && p.y() < 0.1 + 1e-9;
      });
  EXPECT_NEAR(grid.Clearance({0.2, 0.05}), 0.055, 1e-9);
  EXPECT_NEAR(grid.Clearance({0.02, 0.05}), 0.025, 1e-9);
  EXPECT_LT(grid.Clearance({0.45, 0.05}), 0.0);
  const InscribedSquare square = LargestInscribedSquare(grid, {0.3, 0.0}, 0.1);
  EXPECT_NEAR(square.half_side_m, 0.055, 1e-4);
  EXPECT_NEAR(square.centre_m.x(), 0.3, 2e-3);  // the tie-break picks the preferred x
  EXPECT_NEAR(square.centre_m.y(), 0.05, 2e-3);
}

TEST(InscribedSquare, DiscGivesHalfSideRadiusOverRootTwoAndTheSquareIsInside) {
  const double R = 0.1, cell = 0.002;
  const FootprintGrid grid = Fill({-0.12, -0.12}, {0.12, 0.12}, cell,
                                  [&](const Eigen::Vector2d& p) { return p.norm() <= R; });
  const InscribedSquare square = LargestInscribedSquare(grid, {0.0, 0.0}, 0.1);
  EXPECT_NEAR(square.half_side_m, R / std::sqrt(2.0), 1.5 * cell);
  EXPECT_LT(square.centre_m.norm(), 2 * cell);
  // Every point of the square lies in an occupied cell.
  for (double u = -1; u <= 1; u += 0.05) {
    for (double v = -1; v <= 1; v += 0.05) {
      const Eigen::Vector2d p = square.centre_m + 0.999 * square.half_side_m * Eigen::Vector2d(u, v);
      EXPECT_TRUE(grid.OccupiedAt(p)) << p.transpose();
    }
  }
}

TEST(InscribedSquare, EmptyFootprintGivesZero) {
  const FootprintGrid grid =
      Fill({0, 0}, {0.1, 0.1}, 0.01, [](const Eigen::Vector2d&) { return false; });
  EXPECT_EQ(LargestInscribedSquare(grid, {0.05, 0.05}, 0.1).half_side_m, 0.0);
}

}  // namespace
}  // namespace mfp
