#include "geometry/half_plane_clip.h"

#include "base/check.h"

namespace mfp {

void KeepBelowLineInto(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& n, double c,
                       std::vector<Eigen::Vector2d>* out) {
  MFP_CHECK(out != &poly);
  out->clear();
  const size_t m = poly.size();
  for (size_t i = 0; i < m; ++i) {
    const Eigen::Vector2d& a = poly[i];
    const Eigen::Vector2d& b = poly[(i + 1) % m];
    const double da = n.dot(a) - c;
    const double db = n.dot(b) - c;
    if (da <= 0.0) out->push_back(a);
    if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) out->push_back(a + (b - a) * (da / (da - db)));
  }
}

std::vector<Eigen::Vector2d> KeepBelowLine(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& n, double c) {
  std::vector<Eigen::Vector2d> out;
  KeepBelowLineInto(poly, n, c, &out);
  return out;
}

}  // namespace mfp
