#include "geometry/internal/convex_polygon_difference.h"

#include "base/check.h"

namespace mfp {
namespace {

// An overlap this small is rounding where a cut touches the polygon [m^2].
constexpr double kTouchAreaM2 = 1e-10;

}  // namespace

double PolygonArea2d(const std::vector<Eigen::Vector2d>& polygon) {
  double twice = 0.0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[(i + 1) % polygon.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * twice;
}

std::vector<std::vector<Eigen::Vector2d>> ConvexPolygonMinus(const std::vector<Eigen::Vector2d>& polygon,
                                                             const std::vector<Eigen::Vector2d>& cut,
                                                             double margin_m, double min_area_m2) {
  MFP_CHECK(cut.size() >= 3);
  MFP_CHECK(margin_m >= 0.0);
  // polygon \ cut = union over the cut's edges i of (outside edge i, inside edges 0..i-1):
  // disjoint, each an intersection of half-planes with the polygon, hence convex.
  // A cut that only touches the polygon (an abutting box, a face already inset by the
  // margin) leaves it whole rather than in strips along the cut's edges.
  std::vector<Eigen::Vector2d> overlap = polygon;
  for (size_t i = 0; i < cut.size() && overlap.size() >= 3; ++i) {
    const Eigen::Vector2d e = cut[(i + 1) % cut.size()] - cut[i];
    if (e.norm() <= 1e-12) continue;
    const Eigen::Vector2d n = Eigen::Vector2d(e.y(), -e.x()).normalized();
    overlap = KeepBelowLine(overlap, n, n.dot(cut[i]) + margin_m);
  }
  if (overlap.size() < 3 || PolygonArea2d(overlap) <= kTouchAreaM2) return {polygon};
  std::vector<std::vector<Eigen::Vector2d>> pieces;
  std::vector<Eigen::Vector2d> rest = polygon;  // polygon inside the edges seen so far
  for (size_t i = 0; i < cut.size() && rest.size() >= 3; ++i) {
    const Eigen::Vector2d e = cut[(i + 1) % cut.size()] - cut[i];
    if (e.norm() <= 1e-12) continue;
    const Eigen::Vector2d n = Eigen::Vector2d(e.y(), -e.x()).normalized();  // outward for counter-clockwise
    const double c = n.dot(cut[i]) + margin_m;
    std::vector<Eigen::Vector2d> outside = KeepBelowLine(rest, -n, -c);
    if (outside.size() >= 3 && PolygonArea2d(outside) >= min_area_m2) pieces.push_back(std::move(outside));
    rest = KeepBelowLine(rest, n, c);
  }
  return pieces;
}

}  // namespace mfp
