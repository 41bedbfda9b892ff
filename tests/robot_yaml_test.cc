// The robot YAML loader: hand-written robots, URDF robots with overrides that stay
// visible in the provenance, gait by name or index, and clear errors.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "base/check.h"
#include "io/robot_loader.h"
#include "io/robot_yaml.h"

namespace mfp {
namespace {

std::string Source(const std::string& rel) { return std::string(MFP_SOURCE_DIR) + "/" + rel; }

bool HasLine(const RobotModel& robot, const std::string& part) {
  for (const std::string& line : robot.provenance) {
    if (line.find(part) != std::string::npos) return true;
  }
  return false;
}

std::string WriteTemp(const std::string& name, const std::string& text) {
  const std::string path = std::string(MFP_BINARY_DIR) + "/" + name;
  std::ofstream(path) << text;
  return path;
}

TEST(RobotYaml, ConfigRobotsComeFromTheirUrdfs) {
  const RobotModel dog = LoadRobot(Source("config/robots/littledog.yaml"));
  ASSERT_EQ(dog.num_legs(), 4);
  EXPECT_EQ(dog.name, "littledog");
  EXPECT_EQ(dog.gait, (std::vector<int>{2, 0, 3, 1}));  // hind_left, front_left, ...
  EXPECT_DOUBLE_EQ(dog.max_slope_rad, 0.45);
  EXPECT_TRUE(HasLine(dog, "d_lim = "));
  EXPECT_TRUE(HasLine(dog, "gait = [hind_left, front_left, hind_right, front_right]: override"));
  const RobotModel hex = LoadRobot(Source("config/robots/hexapod.yaml"));
  ASSERT_EQ(hex.num_legs(), 6);
  EXPECT_GT(hex.d_lim_m, 0.15);  // sized for 2 m walks in few steps
  EXPECT_LT(hex.d_lim_m, 0.2);
}

TEST(RobotYaml, OverridesReplaceDerivedValuesVisibly) {
  const RobotModel derived = LoadRobot(Source("tests/data/robots/sphere_quad.urdf"));
  const RobotModel robot = LoadRobot(Source("tests/data/robots/sphere_quad_override.yaml"));
  EXPECT_EQ(robot.name, "sphere_quad_custom");
  EXPECT_DOUBLE_EQ(robot.d_lim_m, 0.05);
  EXPECT_DOUBLE_EQ(robot.dz_max_m, 0.03);
  EXPECT_DOUBLE_EQ(robot.stance_height_m, 0.12);
  EXPECT_DOUBLE_EQ(robot.l_bnd_m, 0.025);  // follows the overridden d_lim
  EXPECT_DOUBLE_EQ(robot.weights.goal_position, 50);
  EXPECT_EQ(robot.gait, (std::vector<int>{0, 3, 2, 1}));  // fl, 3, hr, hl
  EXPECT_TRUE(HasLine(robot, "d_lim = 0.0500 m: override in"));
  EXPECT_TRUE(HasLine(robot, "(derived 0."));
  EXPECT_TRUE(HasLine(robot, "stance_height = 0.1200 m: given in"));
  EXPECT_NE(robot.d_lim_m, derived.d_lim_m);
  // The default footprint polygons would not follow the d_lim override: the 16-gon does.
  EXPECT_EQ(derived.reach_shape, ReachShape::kFootprint);
  EXPECT_EQ(robot.reach_shape, ReachShape::kHexadecagon);
  EXPECT_TRUE(HasLine(robot, "reach_shape = hexadecagon: given by the d_lim override in"));
}

// A footprint robot's reach rows ignore d_lim and l_bnd: an override of either, without a
// stated shape, gives the 16-gon (which keeps both); with footprint stated it is refused.
TEST(RobotYaml, AReachLimitOverrideIsKeptByTheShapeOrRefused) {
  const std::string urdf = Source("tests/data/robots/sphere_quad.urdf");
  const RobotModel l_bnd_only = LoadRobot(WriteTemp("l_bnd_only.yaml", "urdf: " + urdf + "\nl_bnd: 0.01\n"));
  EXPECT_EQ(l_bnd_only.reach_shape, ReachShape::kHexadecagon);
  EXPECT_DOUBLE_EQ(l_bnd_only.l_bnd_m, 0.01);
  EXPECT_TRUE(HasLine(l_bnd_only, "reach_shape = hexadecagon: given by the l_bnd override in"));
  for (const char* limit : {"d_lim: 0.05", "l_bnd: 0.01"}) {
    const std::string stated = WriteTemp("footprint_override.yaml",
                                         "urdf: " + urdf + "\nreach_shape: footprint\n" + limit + "\n");
    try {
      LoadRobot(stated);
      FAIL() << limit;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("reach_shape: hexadecagon"), std::string::npos) << e.what();
    }
  }
}

TEST(RobotYaml, HandWrittenRobotsStillLoad) {
  const std::string path = WriteTemp("hand_robot.yaml", R"(
name: hand
legs:
  - {name: a, nominal_offset: [0.1, 0.1]}
  - {name: b, nominal_offset: [-0.1, -0.1]}
d_lim: 0.08
l_bnd: 0.05
dz_max: 0.05
max_yaw_change: 0.3
)");
  const RobotModel robot = LoadRobot(path);
  EXPECT_EQ(robot.num_legs(), 2);
  EXPECT_DOUBLE_EQ(robot.d_lim_m, 0.08);
}

TEST(RobotYaml, ClearErrors) {
  const std::string urdf = Source("tests/data/robots/sphere_quad.urdf");
  const std::string legs_with_urdf = WriteTemp(
      "legs_with_urdf.yaml", "urdf: " + urdf + "\nlegs: [{name: a, nominal_offset: [0, 0]}]\n");
  EXPECT_THROW(LoadRobot(legs_with_urdf), InputError);
  const std::string bad_foot = WriteTemp("bad_foot.yaml", "urdf: " + urdf + "\nfeet: [nope]\n");
  EXPECT_THROW(LoadRobot(bad_foot), InputError);
  const std::string bad_gait = WriteTemp("bad_gait.yaml", "urdf: " + urdf + "\ngait: [fl, fl, hr, hl]\n");
  EXPECT_THROW(LoadRobot(bad_gait), InputError);
  const std::string too_high =
      WriteTemp("too_high.yaml", "urdf: " + urdf + "\nstance_height: 5\n");
  try {
    LoadRobot(too_high);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot reach the stance height"), std::string::npos)
        << e.what();
  }
  const std::string missing_urdf = WriteTemp("missing_urdf.yaml", "urdf: nowhere.urdf\n");
  EXPECT_THROW(LoadRobot(missing_urdf), InputError);
}

}  // namespace
}  // namespace mfp
