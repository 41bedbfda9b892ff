#include "planner/formulation/region_faces.h"

#include <string>

namespace mfp {

void AddRegionFaces(StepEncoder& e, const ConvexRegion& region, int i, int indicator, const Box3& box) {
  const std::string tag = std::to_string(i) + "_" + std::to_string(region.id);
  for (int row = 0; row < region.A.rows(); ++row) {
    const Eigen::Vector3d a = region.A.row(row).transpose();
    StepExpr af;
    for (int axis = 0; axis < 3; ++axis) af += a(axis) * e.Position(i, axis);
    e.AddImpliedRow(RowKind::kRegionFace, "region_" + tag + "_" + std::to_string(row), indicator, af, region.b(row),
                    MaxOverBox(a, region.b(row), box));
  }
}

}  // namespace mfp
