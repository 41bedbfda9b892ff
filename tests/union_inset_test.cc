// The union of convex polygons inset once (InsetUnionOfConvexPolygons): two faces that
// abut make one surface with no strip lost along their seam, a gap between them wider
// than the seam tolerance is kept clear, and every kept point has its inset disk inside
// the union and clear of obstacles.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/internal/convex_polygon_difference.h"
#include "geometry/internal/union_inset.h"

namespace mfp {
namespace {

Polygon2d Rect(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

bool Inside(const Polygon2d& p, const Eigen::Vector2d& q, double tol) {
  for (size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector2d e = p[(i + 1) % p.size()] - p[i];
    if (e.x() * (q - p[i]).y() - e.y() * (q - p[i]).x() < -tol * e.norm()) return false;
  }
  return true;
}

bool InAny(const std::vector<Polygon2d>& pieces, const Eigen::Vector2d& q, double tol) {
  for (const Polygon2d& p : pieces) {
    if (Inside(p, q, tol)) return true;
  }
  return false;
}

double Area(const std::vector<Polygon2d>& pieces) {
  double a = 0.0;
  for (const Polygon2d& p : pieces) a += PolygonArea2d(p);
  return a;
}

// Every piece point (a grid over each piece) has its disk of radius r (sampled on its
// rim) inside the faces and outside the obstacles.
int UnsoundPoints(const std::vector<Polygon2d>& pieces, const std::vector<Polygon2d>& faces,
                  const std::vector<Polygon2d>& obstacles, double r) {
  int bad = 0;
  for (const Polygon2d& piece : pieces) {
    Eigen::Vector2d lo = piece[0], hi = piece[0];
    for (const auto& v : piece) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    for (int i = 0; i <= 30; ++i) {
      for (int j = 0; j <= 30; ++j) {
        const Eigen::Vector2d q = lo + (hi - lo).cwiseProduct(Eigen::Vector2d(i / 30.0, j / 30.0));
        if (!Inside(piece, q, 0.0)) continue;
        for (int k = 0; k < 32; ++k) {
          const Eigen::Vector2d d = q + (r - 1e-9) * Eigen::Vector2d(std::cos(k * M_PI / 16), std::sin(k * M_PI / 16));
          if (!InAny(faces, d, 1e-9) || InAny(obstacles, d, -1e-9)) {
            ++bad;
            break;
          }
        }
      }
    }
  }
  return bad;
}

TEST(UnionInset, GrowConvexPolygonContainsTheMarginAndBevelsSharpCorners) {
  const Polygon2d spike = {{0, 0}, {1, 0}, {0, 0.1}};  // a sharp corner at (1, 0)
  const Polygon2d grown = GrowConvexPolygon(spike, 0.1);
  for (int k = 0; k < 64; ++k) {
    const Eigen::Vector2d rim = Eigen::Vector2d(1, 0) + 0.1 * Eigen::Vector2d(std::cos(k * M_PI / 32), std::sin(k * M_PI / 32));
    EXPECT_TRUE(Inside(grown, rim, 1e-12)) << k;
  }
  double reach = 0.0;  // the farthest grown vertex from the corner
  for (const auto& v : grown) reach = std::max(reach, (v - Eigen::Vector2d(1, 0)).norm() * (v.x() > 1 ? 1 : 0));
  EXPECT_LE(reach, 0.1 / std::cos(M_PI / 8) + 1e-12);  // a mitre would reach 0.1 / sin(2.9 deg) = 2 m
  EXPECT_NEAR(PolygonArea2d(GrowConvexPolygon(Rect(0, 0, 1, 1), 0.0)), 1.0, 1e-12);
}

TEST(UnionInset, IntersectionAndWidthOfConvexPolygons) {
  EXPECT_NEAR(PolygonArea2d(ConvexIntersection(Rect(0, 0, 2, 2), Rect(1, 1, 3, 3))), 1.0, 1e-12);
  EXPECT_TRUE(ConvexIntersection(Rect(0, 0, 1, 1), Rect(2, 2, 3, 3)).empty());
  EXPECT_NEAR(ConvexWidth(Rect(0, 0, 3, 0.2)), 0.2, 1e-12);
}

// Two tiles side by side: one surface, inset once (a 1.9 x 0.9 rectangle), not two
// tiles inset each (losing a 0.2 m strip along the seam).
TEST(UnionInset, AbuttingTilesAreInsetAsOneSurface) {
  const std::vector<Polygon2d> tiles = {Rect(0, 0, 1, 1), Rect(1, 0, 2, 1)};
  const std::vector<Polygon2d> pieces = InsetUnionOfConvexPolygons(tiles, {}, UnionInsetOptions{0.05});
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_NEAR(Area(pieces), 1.9 * 0.9, 1e-9);
  EXPECT_TRUE(InAny(pieces, {1.0, 0.5}, 0.0));
  EXPECT_EQ(UnsoundPoints(pieces, tiles, {}, 0.05), 0);
}

// A gap of 1 cm between the tiles is real: no point within the inset of it is kept.
TEST(UnionInset, AGapBetweenTilesIsKeptClear) {
  const std::vector<Polygon2d> tiles = {Rect(0, 0, 1, 1), Rect(1.01, 0, 2, 1)};
  const std::vector<Polygon2d> pieces = InsetUnionOfConvexPolygons(tiles, {}, UnionInsetOptions{0.05});
  EXPECT_FALSE(InAny(pieces, {1.005, 0.5}, 0.0));
  EXPECT_FALSE(InAny(pieces, {0.96, 0.5}, 0.0));
  EXPECT_TRUE(InAny(pieces, {0.94, 0.5}, 0.0));
  EXPECT_EQ(UnsoundPoints(pieces, tiles, {}, 0.05), 0);
}

// An L of rotated and axis-aligned boards with a post standing on it: sound everywhere,
// and the seam between the boards is covered.
TEST(UnionInset, RotatedBoardsAndAnObstacleStaySound) {
  const double c = std::cos(0.4), s = std::sin(0.4);
  Polygon2d rotated;
  for (const Eigen::Vector2d& p : Rect(-0.1, -0.3, 1.0, 0.3)) rotated.emplace_back(1.0 + c * p.x() - s * p.y(), s * p.x() + c * p.y());
  const std::vector<Polygon2d> boards = {Rect(-1, -0.3, 1.05, 0.3), rotated};
  const std::vector<Polygon2d> post = {Rect(-0.5, -0.05, -0.4, 0.05)};
  const std::vector<Polygon2d> pieces = InsetUnionOfConvexPolygons(boards, post, UnionInsetOptions{0.04});
  EXPECT_EQ(UnsoundPoints(pieces, boards, post, 0.04), 0);
  EXPECT_TRUE(InAny(pieces, {1.02, 0.0}, 0.0));  // on the seam
  EXPECT_FALSE(InAny(pieces, {-0.45, 0.0}, 0.0));
  EXPECT_LE(pieces.size(), 12u);
}

TEST(UnionInset, MergeConvexPiecesJoinsOnlyWhatStaysConvex) {
  const std::vector<Polygon2d> two = {Rect(0, 0, 1, 1), Rect(1, 0, 2, 1)};
  EXPECT_EQ(MergeConvexPieces(two, two).size(), 1u);
  const std::vector<Polygon2d> ell = {Rect(0, 0, 1, 1), Rect(1, 0, 2, 2)};
  EXPECT_EQ(MergeConvexPieces(ell, ell).size(), 2u);
  // Three pieces of a rectangle, no two of which make a convex union: one hull.
  const std::vector<Polygon2d> three = {Rect(0, 0, 1, 2), Rect(1, 0, 2, 1), Rect(1, 1, 2, 2)};
  const std::vector<Polygon2d> merged = MergeConvexPieces(three, three);
  ASSERT_EQ(merged.size(), 1u);
  EXPECT_NEAR(PolygonArea2d(merged[0]), 4.0, 1e-12);
}

}  // namespace
}  // namespace mfp
