#include "io/terrain_yaml.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "base/check.h"
#include "tests/input_error_of.h"
#include "tests/test_temp_path.h"

namespace mfp {
namespace {

TerrainDescription Parse(const std::string& text) {
  return ParseTerrainDescription(YAML::Load(text), YamlContext{"scenario.yaml", "terrain"});
}

std::string ErrorOf(const std::string& text) {
  return InputErrorOf([&] { Parse(text); });
}

TEST(TerrainYamlTest, ReadsBoxesWithDefaults) {
  const TerrainDescription t = Parse(
      "resolution: 0.05\n"
      "boxes:\n"
      "  - {name: s1, center: [1, 2, 3], size: [0.2, 0.3, 0.4], rpy: [0, 0.1, 0.2]}\n"
      "  - {center: [0, 0, -0.05], size: [2, 2, 0.1]}\n");
  EXPECT_DOUBLE_EQ(t.resolution_m, 0.05);
  ASSERT_EQ(t.boxes.size(), 2u);
  EXPECT_EQ(t.boxes[0].name, "s1");
  EXPECT_DOUBLE_EQ(t.boxes[0].center_world_m.y(), 2.0);
  EXPECT_DOUBLE_EQ(t.boxes[0].size_m.z(), 0.4);
  EXPECT_DOUBLE_EQ(t.boxes[0].rpy_rad.z(), 0.2);
  EXPECT_TRUE(t.boxes[1].rpy_rad.isZero());
  EXPECT_DOUBLE_EQ(Parse("boxes: []").resolution_m, 0.02);
}

TEST(TerrainYamlTest, ErrorsNameFileKeyAndRange) {
  const std::string e = ErrorOf("boxes:\n  - {center: [0, 0, 0], size: [1, -1, 1]}\n");
  EXPECT_NE(e.find("scenario.yaml"), std::string::npos) << e;
  EXPECT_NE(e.find("terrain.boxes[0].size[1]"), std::string::npos) << e;
  EXPECT_NE(e.find("allowed range"), std::string::npos) << e;
  EXPECT_NE(ErrorOf("resolution: 5\nboxes: []").find("terrain.resolution"), std::string::npos);
  EXPECT_NE(ErrorOf("boxes:\n  - {center: [0, 0], size: [1, 1, 1]}").find("3 numbers"),
            std::string::npos);
  EXPECT_NE(ErrorOf("boxes:\n  - {size: [1, 1, 1]}").find("center"), std::string::npos);
  EXPECT_NE(ErrorOf("boxs: []").find("unknown key 'boxs'"), std::string::npos);
  EXPECT_NE(ErrorOf("resolution: 0.02").find("boxes"), std::string::npos);
}

TEST(TerrainYamlTest, LoadsTheTerrainBlockOfAScenarioFile) {
  const std::string path =
      TestTempPath("scenario.yaml");
  {
    std::ofstream out(path);
    out << "robot: littledog\nterrain:\n  boxes:\n    - {center: [0, 0, 0], size: [1, 1, 1]}\n";
  }
  EXPECT_EQ(LoadTerrainDescription(path).boxes.size(), 1u);
  {
    std::ofstream out(path);
    out << "robot: littledog\n";
  }
  EXPECT_THROW(LoadTerrainDescription(path), InputError);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace mfp
