#include "io/region_json.h"

namespace mfp {

nlohmann::json RegionToJson(const ConvexRegion& region) {
  nlohmann::json A = nlohmann::json::array();
  nlohmann::json b = nlohmann::json::array();
  for (Eigen::Index j = 0; j < region.A.rows(); ++j) {
    A.push_back({region.A(j, 0), region.A(j, 1), region.A(j, 2)});
    b.push_back(region.b(j));
  }
  nlohmann::json vertices = nlohmann::json::array();
  for (const Eigen::Vector3d& v : region.vertices_world_m) vertices.push_back({v.x(), v.y(), v.z()});
  return {{"id", region.id},
          {"A", A},
          {"b", b},
          {"vertices", vertices},
          {"area", region.area_m2},
          {"slope", region.SlopeRad()},
          {"normal", {region.normal_world.x(), region.normal_world.y(), region.normal_world.z()}},
          {"plane_tolerance", region.plane_tolerance_m}};
}

nlohmann::json RegionsToJson(const std::vector<ConvexRegion>& regions) {
  nlohmann::json list = nlohmann::json::array();
  for (const ConvexRegion& r : regions) list.push_back(RegionToJson(r));
  return {{"regions", list}};
}

}  // namespace mfp
