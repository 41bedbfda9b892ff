#include "planner/formulation/workspace_box.h"

#include <algorithm>

namespace mfp {

Box3 MakeWorkspaceBox(const std::vector<ConvexRegion>& regions, const std::vector<Eigen::Vector3d>& start_feet_world_m) {
  Box3 box;
  for (const ConvexRegion& r : regions) {
    for (const Eigen::Vector3d& v : r.vertices_world_m) {
      box.Add(v + Eigen::Vector3d(0, 0, r.plane_tolerance_m));
      box.Add(v - Eigen::Vector3d(0, 0, r.plane_tolerance_m));
    }
  }
  for (const Eigen::Vector3d& f : start_feet_world_m) box.Add(f);
  box.lo -= Eigen::Vector3d::Constant(1e-3);
  box.hi += Eigen::Vector3d::Constant(1e-3);
  return box;
}

double MaxOverBox(const Eigen::Vector3d& a, double b, const Box3& box) {
  double value = -b;
  for (int k = 0; k < 3; ++k) value += std::max(a(k) * box.lo(k), a(k) * box.hi(k));
  return value;
}

}  // namespace mfp
