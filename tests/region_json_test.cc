#include "io/region_json.h"

#include <gtest/gtest.h>

namespace mfp {
namespace {

TEST(RegionJsonTest, RegionObjectHasTheDesignFields) {
  const ConvexRegion r = MakeRegionFromPolygon(
      7, {{0, 0, 0.1}, {1, 0, 0.1}, {1, 2, 0.1}, {0, 2, 0.1}}, 0.01);
  const nlohmann::json j = RegionToJson(r);
  EXPECT_EQ(j["id"], 7);
  ASSERT_EQ(j["A"].size(), 6u);
  ASSERT_EQ(j["b"].size(), 6u);
  EXPECT_EQ(j["A"][0].size(), 3u);
  ASSERT_EQ(j["vertices"].size(), 4u);
  EXPECT_DOUBLE_EQ(j["vertices"][2][2].get<double>(), 0.1);
  EXPECT_NEAR(j["area"].get<double>(), 2.0, 1e-12);
  const nlohmann::json all = RegionsToJson({r, r});
  EXPECT_EQ(all["regions"].size(), 2u);
}

}  // namespace
}  // namespace mfp
