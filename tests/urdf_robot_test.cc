// Robots from URDFs: legs found, named and ordered; feet at collision-sphere centres;
// derived models valid for 4, 6 and 8 legs; the derived reach polygon (by default each leg's
// footprint polygon, the 16-gon where none fits) and height range really reachable (inverse
// kinematics); every bad URDF a clear InputError and exit code 2.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "base/check.h"
#include "io/robot_loader.h"
#include "planner/robot/internal/footprint_grid.h"
#include "planner/robot/internal/reach_choice.h"
#include "planner/robot/reach_polygon.h"
#include "planner/robot/robot_derivation.h"
#include "planner/robot/urdf_reader.h"

namespace mfp {
namespace {

std::string Source(const std::string& rel) { return std::string(MFP_SOURCE_DIR) + "/" + rel; }
std::string TestRobot(const std::string& name) { return Source("tests/data/robots/" + name); }

TEST(UrdfReader, LittleDogLegsHipsAndSphereFeet) {
  const RobotDescription robot = ReadUrdfRobot(Source("config/robots/littledog.urdf"));
  ASSERT_EQ(robot.legs.size(), 4u);
  const char* names[] = {"front_left", "front_right", "hind_left", "hind_right"};
  for (int k = 0; k < 4; ++k) {
    const LegChain& leg = robot.legs[k];
    EXPECT_EQ(leg.name, names[k]);
    EXPECT_EQ(leg.num_dof(), 3);
    const double sx = k < 2 ? 1 : -1, sy = k % 2 == 0 ? 1 : -1;
    EXPECT_TRUE(HipPosition(leg).isApprox(Eigen::Vector3d(0.101 * sx, 0.03625 * sy, 0)));
    EXPECT_TRUE(leg.p_footlink_foot_m.isApprox(Eigen::Vector3d(-0.0265 * sx, 0, -0.0985)));
    EXPECT_DOUBLE_EQ(leg.foot_sphere_radius_m, 0.01);
    const Eigen::Vector3d zero = FootPosition(leg, Eigen::Vector3d::Zero());
    EXPECT_NEAR(zero.x(), sx * (0.101 - 0.0265), 1e-12);
    EXPECT_NEAR(zero.y(), sy * 0.05985, 1e-12);
    EXPECT_NEAR(zero.z(), -0.1736, 1e-12);
  }
}

TEST(UrdfReader, SphereFeetWithoutFootLinksAndAFixedSensorIgnored) {
  const RobotDescription robot = ReadUrdfRobot(TestRobot("sphere_quad.urdf"));
  ASSERT_EQ(robot.legs.size(), 4u);  // the fixed imu link is not a leg
  const LegChain& fl = robot.legs[0];
  EXPECT_EQ(fl.name, "fl");
  EXPECT_EQ(fl.foot_link, "fl_tibia");
  EXPECT_TRUE(fl.p_footlink_foot_m.isApprox(Eigen::Vector3d(0.12, 0, -0.02)));
  EXPECT_DOUBLE_EQ(fl.foot_sphere_radius_m, 0.02);
  // Zero pose: hip at 0.14 m on the 45 degree ray, coxa 0.03 + femur 0.10 + 0.12 out.
  const Eigen::Vector3d foot = FootPosition(fl, Eigen::Vector3d::Zero());
  const double r = 0.14 + 0.03 + 0.10 + 0.12;
  EXPECT_NEAR(foot.x(), r * std::cos(M_PI / 4), 1e-6);  // the URDF has 6 digits
  EXPECT_NEAR(foot.y(), r * std::sin(M_PI / 4), 1e-6);
  EXPECT_NEAR(foot.z(), -0.02, 1e-9);
}

TEST(UrdfReader, EightLegsEndInFootLinksThroughFixedJoints) {
  const RobotDescription robot = ReadUrdfRobot(TestRobot("octopod.urdf"));
  ASSERT_EQ(robot.legs.size(), 8u);
  EXPECT_EQ(robot.legs[0].name, "left1");
  EXPECT_EQ(robot.legs[0].foot_link, "left1_foot");
  EXPECT_EQ(robot.legs[0].joints.size(), 4u);  // coxa, femur, tibia, fixed foot
  EXPECT_EQ(robot.legs[0].num_dof(), 3);
}

TEST(UrdfReader, ExplicitFootLinks) {
  // The tibia's origin is the knee: without a foot offset the URDF holds no foot there.
  try {
    ReadUrdfRobot(TestRobot("octopod.urdf"), {"left1_tibia", "right1_tibia"});
    ADD_FAILURE() << "a foot on the knee axis was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("holds no foot for leg 'left1'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("foot_offset"), std::string::npos) << e.what();
  }
  const RobotDescription robot = ReadUrdfRobot(TestRobot("octopod.urdf"), {"left1_tibia", "right1_tibia"},
                                               Eigen::Vector3d(0, 0, -0.1));
  ASSERT_EQ(robot.legs.size(), 2u);
  EXPECT_EQ(robot.legs[0].foot_link, "left1_tibia");
  EXPECT_TRUE(robot.legs[0].p_footlink_foot_m.isApprox(Eigen::Vector3d(0, 0, -0.1)));
  EXPECT_THROW(ReadUrdfRobot(TestRobot("octopod.urdf"), {"no_such_link"}), InputError);
}

class DerivedRobot : public ::testing::TestWithParam<std::pair<std::string, int>> {};

TEST_P(DerivedRobot, UrdfAloneGivesAValidModel) {
  const auto& [path, legs] = GetParam();
  RobotDerivation derivation;
  const RobotModel robot = LoadRobot(Source(path), &derivation);
  ASSERT_EQ(robot.num_legs(), legs);
  EXPECT_NO_THROW(ValidateRobotModel(robot));
  EXPECT_LT(MeanNominalOffset(robot).norm(), 1e-9);
  EXPECT_GT(robot.d_lim_m, 0.02);
  EXPECT_NEAR(robot.l_bnd_m, 0.5 * robot.d_lim_m, 1e-12);
  EXPECT_GT(robot.dz_max_m, 0.0);
  EXPECT_GT(robot.stance_height_m, 0.0);
  EXPECT_FALSE(robot.provenance.empty());

  // The reach polygon about each nominal foot (by default the leg's own footprint polygon)
  // is reachable at the stance height: inverse kinematics converges within the joint limits
  // at its corners and the middles of its edges (every body yaw: reach_soundness_test), and
  // the foot reaches dz_max above and below the nominal foot.
  EXPECT_EQ(robot.reach_shape, ReachShape::kFootprint) << path;
  const RobotDescription description = ReadUrdfRobot(Source(path));
  for (int k = 0; k < robot.num_legs(); ++k) {
    const LegChain& chain = description.legs[k];
    const LegDerivation& leg = derivation.legs[k];
    const std::vector<Eigen::Vector2d> corners = ReachFaceCorners(robot.legs[k].footprint_faces);
    EXPECT_GE(corners.size(), 3u) << path << " leg " << k;
    for (size_t i = 0; i < 2 * corners.size(); ++i) {
      const Eigen::Vector2d& c = corners[i / 2];
      const Eigen::Vector2d edge = i % 2 == 0 ? c : 0.5 * (c + corners[(i / 2 + 1) % corners.size()]);
      const Eigen::Vector3d target = leg.nominal_foot_body_m + Eigen::Vector3d(edge.x(), edge.y(), 0);
      IkResult ik = SolveFootIk(chain, target, leg.nominal_q, 1e-5, 300);
      EXPECT_TRUE(ik.converged) << path << " leg " << k << " point " << i << " error "
                                << ik.error_m;
    }
    for (double dz : {robot.dz_max_m, -robot.dz_max_m}) {
      const IkResult ik = SolveFootIk(chain, leg.nominal_foot_body_m + Eigen::Vector3d(0, 0, dz),
                                      leg.nominal_q, 1e-5, 300);
      EXPECT_TRUE(ik.converged) << path << " leg " << k << " dz " << dz;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    FourSixEightLegs, DerivedRobot,
    ::testing::Values(std::make_pair(std::string("config/robots/littledog.urdf"), 4),
                      std::make_pair(std::string("config/robots/hexapod.urdf"), 6),
                      std::make_pair(std::string("tests/data/robots/octopod.urdf"), 8),
                      std::make_pair(std::string("tests/data/robots/sphere_quad.urdf"), 4)));

// The default reach of a URDF robot is each leg's footprint polygon of
// DerivationOptions::footprint_faces faces, and its provenance says it is the default.
TEST(DerivedRobot, AUrdfRobotGetsItsLegsFootprintPolygonsByDefault) {
  const RobotModel robot = LoadRobot(Source("config/robots/littledog.urdf"));
  ASSERT_EQ(robot.reach_shape, ReachShape::kFootprint);
  for (const LegModel& leg : robot.legs) {
    EXPECT_EQ(static_cast<int>(leg.footprint_faces.size()), DerivationOptions{}.footprint_faces) << leg.name;
  }
  int lines = 0;
  for (const std::string& line : robot.provenance) {
    lines += line.rfind("reach_shape = footprint: the default for a robot derived from a URDF", 0) == 0;
  }
  EXPECT_EQ(lines, 1);
}

// Two legs on one hand-made footprint (cells of 0.5 m, a ring of empty cells about 7 x 7
// occupied ones, one of them empty): leg 'sound' stands two cells from the empty one, leg
// 'touched' on the corner the empty cell shares with three occupied ones. A derived leg
// never stands there (DeriveRobot requires an inscribed square wider than a cell), and
// faces pointing into the empty cell clear it at offset 0; a 4-face polygon has none such,
// so no 4-face polygon about 'touched''s nominal foot fits the footprint.
std::vector<LegDerivation> LegsBesideAnEmptyCell() {
  FootprintGrid grid(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(2.0, 2.0), 0.5);
  for (int iy = 1; iy + 1 < grid.ny(); ++iy) {
    for (int ix = 1; ix + 1 < grid.nx(); ++ix) grid.Set(ix, iy, !(ix == 3 && iy == 3));
  }
  grid.UpdateBoundary();
  std::vector<LegDerivation> legs(2);
  for (LegDerivation& leg : legs) leg.footprint = grid;
  legs[0].nominal_foot_body_m = Eigen::Vector3d(1.5, 1.5, -0.2);
  // The corner between cells (3, 3) and (4, 4): it lies in cell (4, 4), which is occupied.
  legs[1].nominal_foot_body_m = Eigen::Vector3d(0.75, 0.75, -0.2);
  return legs;
}

TEST(ReachChoice, TheDefaultFootprintFallsBackToThe16gonWhereNoPolygonFitsALeg) {
  const std::vector<LegDerivation> legs = LegsBesideAnEmptyCell();
  const std::vector<std::string> names = {"sound", "touched"};
  DerivationOptions options;
  const ReachChoice sound = ChooseReach({legs[0]}, {names[0]}, 0.5, options);
  EXPECT_EQ(sound.shape, ReachShape::kFootprint);
  ASSERT_EQ(sound.faces.size(), 1u);
  EXPECT_EQ(static_cast<int>(sound.faces[0].size()), options.footprint_faces);
  EXPECT_EQ(sound.why.rfind("the default", 0), 0u) << sound.why;

  options.footprint_faces = 4;
  const ReachChoice fallback = ChooseReach(legs, names, 0.5, options);
  EXPECT_EQ(fallback.shape, ReachShape::kHexadecagon);
  EXPECT_TRUE(fallback.faces.empty());
  EXPECT_NE(fallback.why.find("fallback: no footprint polygon fits leg 'touched'"), std::string::npos)
      << fallback.why;

  // Stated, the footprint is the caller's choice: an error, not a quiet 16-gon.
  options.reach_shape_given = "in robot.yaml";
  EXPECT_THROW(ChooseReach(legs, names, 0.5, options), InputError);
  options.reach_shape = ReachShape::kOctagon;
  EXPECT_EQ(ChooseReach(legs, names, 0.5, options).shape, ReachShape::kOctagon);
}

TEST(DerivedRobot, MirrorImageLegsGetMirrorImageOffsets) {
  const RobotModel robot = LoadRobot(Source("config/robots/littledog.urdf"));
  const Eigen::Vector2d fl = robot.legs[0].nominal_offset_body_m;
  EXPECT_NEAR(robot.legs[1].nominal_offset_body_m.y(), -fl.y(), 1e-6);
  EXPECT_NEAR(robot.legs[2].nominal_offset_body_m.x(), -fl.x(), 1e-6);
  EXPECT_NEAR(robot.legs[3].nominal_offset_body_m.norm(), fl.norm(), 1e-6);
}

TEST(DerivedRobot, WaveGaitGoesAroundTheBody) {
  std::vector<LegModel> legs(4);
  legs[0].nominal_offset_body_m = {1, 1};    // front left
  legs[1].nominal_offset_body_m = {1, -1};   // front right
  legs[2].nominal_offset_body_m = {-1, 1};   // hind left
  legs[3].nominal_offset_body_m = {-1, -1};  // hind right
  EXPECT_EQ(WaveGait(legs), (std::vector<int>{2, 0, 1, 3}));
}

struct BadCase {
  const char* file;
  const char* message_part;
};

class BadUrdf : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadUrdf, ClearErrorAndExitCodeTwo) {
  const BadCase& c = GetParam();
  const std::string path = TestRobot(c.file);
  try {
    LoadRobot(path);
    FAIL() << c.file << " was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(c.message_part), std::string::npos) << e.what();
  }
  const std::string command = std::string(MFP_BINARY_DIR) + "/tools/mfp-robot " + path +
                              " >/dev/null 2>&1";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2) << command;
}

INSTANTIATE_TEST_SUITE_P(
    EachCase, BadUrdf,
    ::testing::Values(BadCase{"missing.urdf", "no such file"},
                      BadCase{"bad_malformed.urdf", "malformed XML"},
                      BadCase{"bad_no_legs.urdf", "no legs found"},
                      BadCase{"bad_zero_axis.urdf", "axis has zero length"},
                      BadCase{"bad_limits_inverted.urdf", "is above upper"},
                      BadCase{"bad_nan_limit.urdf", "'lower' = 'nan' is not a finite number"},
                      BadCase{"bad_inf_origin.urdf", "'xyz' = '0 inf -0.1' is not a finite"},
                      BadCase{"bad_unreachable.urdf", "cannot reach the ground"}));

TEST(LoadRobot, RejectsUnknownExtensions) {
  EXPECT_THROW(LoadRobot(TestRobot("octopod.txt")), InputError);
}

}  // namespace
}  // namespace mfp
