// Real robot descriptions in miniature (issue 15): each structural case seen in public
// URDFs built from a small quadruped of our own, and the hostile ones of issue 19 (long
// legs, loops, thousands of legs, names that are not UTF-8), each refused with a message
// naming the problem and exit code 2, or read as the robot is.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "base/check.h"
#include "io/robot_loader.h"
#include "planner/robot/robot_derivation.h"
#include "planner/robot/urdf_reader.h"
#include "tests/input_error_of.h"
#include "tests/test_temp_path.h"

namespace mfp {
namespace {

// A quadruped: hips at (+-0.2, +-0.1, 0); hip roll about x, hip pitch about y 0.05 m out,
// knee about y 0.2 m below, foot 0.2 m below the knee. Hooks add to each leg or the body.
struct Quad {
  std::string name = "quad";
  std::string root_prefix;   // links and joints above the body (a world frame)
  std::string body_extra;    // more elements
  std::string roll_type = "revolute", roll_limits = "<limit lower=\"-0.5\" upper=\"0.5\" effort=\"10\" velocity=\"10\"/>";
  std::string pitch_axis = "0 1 0";
  // Per leg (prefix, sx, sy): extra elements, and what the knee link ends in.
  std::function<std::string(const std::string&, int, int)> leg_extra;
  std::function<std::string(const std::string&, int, int)> foot;
  std::function<std::string(const std::string&, int, int)> hip_origin;
  double length_scale_x = 1.0, length_scale_y = 1.0;
};

// A link p_<link> hanging from leg p's shank by the fixed joint p_<joint>, origin xyz.
std::string FixedLeaf(const std::string& p, const std::string& link, const std::string& joint,
                      const std::string& xyz) {
  return "<link name=\"" + p + "_" + link + "\"/><joint name=\"" + p + "_" + joint +
         "\" type=\"fixed\"><parent link=\"" + p + "_shank\"/><child link=\"" + p + "_" + link +
         "\"/><origin xyz=\"" + xyz + "\"/></joint>\n";
}

std::string Leg(const Quad& q, const std::string& p, int sx, int sy) {
  std::ostringstream s;
  const std::string hip =
      q.hip_origin ? q.hip_origin(p, sx, sy)
                   : std::to_string(0.2 * sx * q.length_scale_x) + " " + std::to_string(0.1 * sy * q.length_scale_y) + " 0";
  s << "<link name=\"" << p << "_hip\"/><link name=\"" << p << "_thigh\"/><link name=\"" << p << "_shank\"/>\n"
    << "<joint name=\"" << p << "_roll\" type=\"" << q.roll_type << "\"><parent link=\"body\"/><child link=\"" << p
    << "_hip\"/><origin xyz=\"" << hip << "\"/><axis xyz=\"1 0 0\"/>" << q.roll_limits << "</joint>\n"
    << "<joint name=\"" << p << "_pitch\" type=\"revolute\"><parent link=\"" << p << "_hip\"/><child link=\"" << p
    << "_thigh\"/><origin xyz=\"0 " << 0.05 * sy << " 0\"/><axis xyz=\"" << q.pitch_axis
    << "\"/><limit lower=\"-1.5\" upper=\"1.5\" effort=\"10\" velocity=\"10\"/></joint>\n"
    << "<joint name=\"" << p << "_knee\" type=\"revolute\"><parent link=\"" << p << "_thigh\"/><child link=\"" << p
    << "_shank\"/><origin xyz=\"0 0 -0.2\"/><axis xyz=\"0 1 0\"/><limit lower=\"-2.6\" upper=\"-0.1\" effort=\"10\" velocity=\"10\"/></joint>\n";
  if (q.foot) {
    s << q.foot(p, sx, sy);
  } else {
    s << FixedLeaf(p, "foot", "foot_fixed", "0 0 -0.2");
  }
  if (q.leg_extra) s << q.leg_extra(p, sx, sy);
  return s.str();
}

std::string Urdf(const Quad& q) {
  std::ostringstream s;
  s << "<?xml version=\"1.0\"?>\n<robot name=\"" << q.name << "\">\n" << q.root_prefix << "<link name=\"body\"/>\n"
    << q.body_extra;
  const char* names[] = {"fl", "fr", "hl", "hr"};
  for (int k = 0; k < 4; ++k) s << Leg(q, names[k], k < 2 ? 1 : -1, k % 2 == 0 ? 1 : -1);
  s << "</robot>\n";
  return s.str();
}

std::string Write(const std::string& name, const std::string& text) {
  const std::string path = TestTempPath(name);
  std::ofstream(path) << text;
  return path;
}

std::string ErrorOf(const std::function<void()>& f) { return InputErrorOf(f, "(accepted)"); }

int ExitCode(const std::string& args) {
  const int status = std::system((std::string(MFP_BINARY_DIR) + "/tools/mfp-robot " + args + " >/dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Writes the URDF text to name and expects both LoadRobot and mfp-robot (exit code 2)
// to refuse it, the message holding each of `words`.
void ExpectRefused(const std::string& name, const std::string& text, const std::vector<std::string>& words) {
  const std::string path = Write(name, text);
  const std::string error = ErrorOf([&] { LoadRobot(path); });
  for (const std::string& word : words) EXPECT_NE(error.find(word), std::string::npos) << error;
  EXPECT_EQ(ExitCode(path), 2);
}

bool HasLine(const RobotModel& robot, const std::string& part) {
  for (const std::string& line : robot.provenance) {
    if (line.find(part) != std::string::npos) return true;
  }
  return false;
}

const char* kWorld =
    "<link name=\"world\"/><joint name=\"float\" type=\"floating\"><parent link=\"world\"/>"
    "<child link=\"body\"/><origin xyz=\"0 0 0.5\"/></joint>\n";

TEST(UrdfStructure, TheBaseline) {
  const RobotModel robot = LoadRobot(Write("q.urdf", Urdf(Quad{})));
  ASSERT_EQ(robot.num_legs(), 4);
  EXPECT_EQ(robot.legs[0].name, "fl");
  // Stance near 70 % of the 0.4 m full extension: knee bent, not crouched.
  EXPECT_GT(robot.stance_height_m, 0.6 * 0.4);
  EXPECT_LT(robot.stance_height_m, 0.8 * 0.4);
  EXPECT_GT(robot.dz_max_m, 0.05);
}

TEST(UrdfStructure, WorldRootWithAFloatingJointIsAFrameAboveTheBody) {
  Quad q;
  q.root_prefix = kWorld;
  const RobotModel robot = LoadRobot(Write("q.urdf", Urdf(q)));
  EXPECT_EQ(robot.num_legs(), 4);
  EXPECT_TRUE(HasLine(robot, "body: link 'body', below 'world' by the floating joint 'float'"));
  // The same robot without the frame: the same model.
  const RobotModel plain = LoadRobot(Write("p.urdf", Urdf(Quad{})));
  EXPECT_NEAR(robot.stance_height_m, plain.stance_height_m, 1e-9);
  EXPECT_NEAR(robot.d_lim_m, plain.d_lim_m, 1e-9);
}

TEST(UrdfStructure, LegNamesFromACommonSuffix) {
  // Mini Cheetah style names: "abduct_fr", "thigh_fr", "toe_fr".
  const std::string text = std::regex_replace(Urdf(Quad{}), std::regex("\"(fl|fr|hl|hr)_(\\w+)\""), "\"$2_$1\"");
  ASSERT_NE(text.find("\"hip_fl\""), std::string::npos);
  const RobotDescription robot = ReadUrdfRobot(Write("s.urdf", text));
  ASSERT_EQ(robot.legs.size(), 4u);
  EXPECT_EQ(robot.legs[0].name, "fl");
  EXPECT_EQ(robot.legs[3].name, "hr");
}

TEST(UrdfStructure, ALinkInNoJointIsIgnored) {
  Quad q;
  q.body_extra = "<link name=\"stray_marker\"/>\n";
  const RobotModel robot = LoadRobot(Write("q.urdf", Urdf(q)));
  EXPECT_EQ(robot.num_legs(), 4);
  EXPECT_TRUE(HasLine(robot, "link 'stray_marker' is in no joint: ignored"));
}

TEST(UrdfStructure, ContinuousJointsAndPlaceholderLimitsGetOneTurnReported) {
  Quad q;
  q.roll_type = "continuous";
  q.roll_limits = "";
  const RobotDescription cont = ReadUrdfRobot(Write("c.urdf", Urdf(q)));
  EXPECT_DOUBLE_EQ(cont.legs[0].joints[0].lower, -M_PI);
  EXPECT_DOUBLE_EQ(cont.legs[0].joints[0].upper, M_PI);
  q.roll_type = "revolute";
  q.roll_limits = "<limit lower=\"-10\" upper=\"10\" effort=\"10\" velocity=\"10\"/>";
  const std::string path = Write("w.urdf", Urdf(q));
  const RobotDescription wide = ReadUrdfRobot(path);
  EXPECT_DOUBLE_EQ(wide.legs[0].joints[0].lower, -M_PI);
  EXPECT_DOUBLE_EQ(wide.legs[0].joints[0].upper, M_PI);
  const RobotModel robot = LoadRobot(path);
  EXPECT_TRUE(HasLine(robot, "joint 'fl_roll': limits [-10, 10] rad span more than a turn"));
  Quad c;
  c.roll_type = "continuous";
  c.roll_limits = "";
  EXPECT_TRUE(HasLine(LoadRobot(Write("c2.urdf", Urdf(c))), "joint 'fl_roll': continuous"));
}

TEST(UrdfStructure, RotorsCoversAndSensorsAreNotFeet) {
  Quad q;
  // Unitree style: a rotor fixed to each leg link, a cover on the hip, an imu and a camera
  // on the body; the foot a sphere-less empty link on a fixed joint below the knee.
  q.leg_extra = [](const std::string& p, int, int) {
    std::string s;
    for (const char* on : {"hip", "thigh", "shank"}) {
      const std::string o = on;
      s += "<link name=\"" + p + "_" + o + "_rotor\"/><joint name=\"" + p + "_" + o +
           "_rotor_joint\" type=\"fixed\"><parent link=\"" + p + "_" + o + "\"/><child link=\"" + p + "_" + o +
           "_rotor\"/><origin xyz=\"0 0 -0.05\"/></joint>\n";
    }
    return s;
  };
  q.body_extra =
      "<link name=\"imu\"/><joint name=\"imu_joint\" type=\"fixed\"><parent link=\"body\"/><child link=\"imu\"/></joint>\n"
      "<link name=\"camera\"/><joint name=\"camera_joint\" type=\"fixed\"><parent link=\"body\"/><child "
      "link=\"camera\"/><origin xyz=\"0.3 0 0\"/></joint>\n";
  const RobotDescription robot = ReadUrdfRobot(Write("q.urdf", Urdf(q)));
  ASSERT_EQ(robot.legs.size(), 4u);
  for (const LegChain& leg : robot.legs) EXPECT_EQ(leg.foot_link, leg.name + "_foot");
  EXPECT_EQ(robot.legs[0].name, "fl");
}

TEST(UrdfStructure, SeveralLeavesPerLegKeepOneFoot) {
  // A CAD export: below the knee, a fixed 'shin_guard' leaf and a fixed empty end link;
  // the end link is farther along the leg, and a sphere beats both.
  Quad q;
  q.foot = [](const std::string& p, int, int) {
    return FixedLeaf(p, "shin_guard", "guard", "0.02 0 -0.08") + FixedLeaf(p, "end", "end_fixed", "0 0 -0.2");
  };
  const RobotDescription farthest = ReadUrdfRobot(Write("f.urdf", Urdf(q)));
  ASSERT_EQ(farthest.legs.size(), 4u);
  EXPECT_EQ(farthest.legs[0].foot_link, "fl_end");
  EXPECT_NE(farthest.notes.end(), std::find_if(farthest.notes.begin(), farthest.notes.end(), [](const std::string& n) {
              return n.find("foot link 'fl_end' chosen over 'fl_shin_guard'") != std::string::npos;
            }));
  q.foot = [](const std::string& p, int, int) {
    return FixedLeaf(p, "end", "end_fixed", "0 0 -0.25") + FixedLeaf(p, "toe", "toe_fixed", "0 0 -0.2") +
           "<link name=\"" + p + "_pad\"><collision><origin xyz=\"0 0 -0.2\"/><geometry><sphere radius=\"0.02\"/>"
           "</geometry></collision></link><joint name=\"" + p + "_pad_fixed\" type=\"fixed\"><parent link=\"" + p +
           "_shank\"/><child link=\"" + p + "_pad\"/></joint>\n";
  };
  const RobotDescription sphere = ReadUrdfRobot(Write("s.urdf", Urdf(q)));
  EXPECT_EQ(sphere.legs[0].foot_link, "fl_pad");
  EXPECT_DOUBLE_EQ(sphere.legs[0].foot_sphere_radius_m, 0.02);
}

TEST(UrdfStructure, AFootNameBeatsALongerLeaf) {
  Quad q;
  q.foot = [](const std::string& p, int, int) {
    return FixedLeaf(p, "end", "end_fixed", "0 0 -0.25") + FixedLeaf(p, "toe", "toe_fixed", "0 0 -0.2");
  };
  EXPECT_EQ(ReadUrdfRobot(Write("t.urdf", Urdf(q))).legs[0].foot_link, "fl_toe");
}

TEST(UrdfStructure, ALongAxisAlongYTurnsWithTheForwardKey) {
  Quad q;  // the legs spread along y: the robot walks along the URDF's y axis
  q.hip_origin = [](const std::string&, int sx, int sy) {
    return std::to_string(0.1 * sy) + " " + std::to_string(0.3 * sx) + " 0";
  };
  q.pitch_axis = "1 0 0";
  const std::string urdf = Write("y.urdf", Urdf(q));
  const std::string yaml = Write("y.yaml", "urdf: " + urdf + "\nforward: y\n");
  const RobotModel robot = LoadRobot(yaml);
  ASSERT_EQ(robot.num_legs(), 4);
  // After the turn the front legs ('fl', 'fr': +y in the URDF) are ahead (+x).
  EXPECT_GT(robot.legs[0].hip_body_m.x(), 0.25);
  EXPECT_GT(robot.legs[1].hip_body_m.x(), 0.25);
  EXPECT_TRUE(HasLine(robot, "forward: the URDF's y axis"));
  EXPECT_NE(ErrorOf([&] { LoadRobot(Write("z.yaml", "urdf: " + urdf + "\nforward: z\n")); }).find("not one of x, y, -x, -y"),
            std::string::npos);
}

TEST(UrdfStructure, ALeafOnTheKneeHoldsNoFootAndTheYamlGivesIt) {
  Quad q;  // the lower leg only in a mesh: the leaf link's origin is the knee
  q.foot = [](const std::string&, int, int) { return std::string(); };
  const std::string urdf = Write("k.urdf", Urdf(q));
  const std::string error = ErrorOf([&] { LoadRobot(urdf); });
  EXPECT_NE(error.find("the URDF holds no foot for leg 'fl'"), std::string::npos) << error;
  EXPECT_NE(error.find("foot_offset: [x, y, z]"), std::string::npos) << error;
  EXPECT_EQ(ExitCode(urdf), 2);
  const RobotModel robot = LoadRobot(Write("k.yaml", "urdf: " + urdf + "\nfoot_offset: [0, 0, -0.2]\n"));
  const RobotModel full = LoadRobot(Write("full.urdf", Urdf(Quad{})));
  EXPECT_NEAR(robot.stance_height_m, full.stance_height_m, 1e-9);
  EXPECT_NEAR(robot.d_lim_m, full.d_lim_m, 1e-9);
}

TEST(UrdfStructure, AHipOriginCopiedFromAnotherLegLiesOnTheAxis) {
  // The roll joint of every leg placed at the front-left hip's x, the offset carried by
  // the roll axis (x): the hip is where the axis passes nearest the leg.
  Quad q;
  q.hip_origin = [](const std::string&, int sx, int sy) {
    return std::to_string(0.2 * sx) + " " + std::to_string(0.1 * sy) + " 0";
  };
  const RobotDescription good = ReadUrdfRobot(Write("g.urdf", Urdf(q)));
  // Now move each roll origin along its own axis (x) by 0.17 m: the same leg.
  q.hip_origin = [](const std::string&, int sx, int sy) {
    return std::to_string(0.2 * sx + 0.17) + " " + std::to_string(0.1 * sy) + " 0";
  };
  const std::string shifted = Urdf(q);
  // ...with the pitch joints moved back by the same amount, so the legs are unchanged.
  std::string fixed = shifted;
  for (size_t at = fixed.find("<origin xyz=\"0 "); at != std::string::npos; at = fixed.find("<origin xyz=\"0 ", at + 1)) {
    if (fixed.compare(at + 15, 4, "0.05") == 0 || fixed.compare(at + 15, 5, "-0.05") == 0) {
      fixed.replace(at + 13, 1, "-0.17");
    }
  }
  const RobotDescription copied = ReadUrdfRobot(Write("c.urdf", fixed));
  for (size_t k = 0; k < 4; ++k) {
    EXPECT_TRUE(HipPosition(copied.legs[k]).isApprox(HipPosition(good.legs[k]), 1e-9))
        << HipPosition(copied.legs[k]).transpose() << " vs " << HipPosition(good.legs[k]).transpose();
  }
}

TEST(UrdfStructure, AStanceWithoutReachLeftIsRefusedNotAZeroLimit) {
  // The feet at full extension (0.4 m below the hip pitch joints): no travel down.
  const std::string urdf = Write("q.urdf", Urdf(Quad{}));
  const std::string yaml = Write("q.yaml", "urdf: " + urdf + "\nstance_height: 0.3999\n");
  const std::string error = ErrorOf([&] { LoadRobot(yaml); });
  EXPECT_NE(error.find("choose stance_height between"), std::string::npos) << error;
  EXPECT_EQ(ExitCode(yaml), 2);
}

TEST(UrdfStructure, PlanarLegsAreRefusedByName) {
  Quad q;  // no hip roll: the roll joint turns about y like the others
  q.pitch_axis = "0 1 0";
  std::string text = Urdf(q);
  for (size_t at = text.find("<axis xyz=\"1 0 0\"/>"); at != std::string::npos; at = text.find("<axis xyz=\"1 0 0\"/>")) {
    text.replace(at, 19, "<axis xyz=\"0 1 0\"/>");
  }
  ExpectRefused("planar.urdf", text, {"leg 'fl' is planar", "no sideways freedom"});
}

TEST(UrdfStructure, RotatingCLegsAreRefused) {
  std::string text = "<robot name=\"rhex\"><link name=\"body\"/>\n";
  for (int k = 0; k < 6; ++k) {
    const std::string p = "leg" + std::to_string(k);
    text += "<link name=\"" + p + "\"/><joint name=\"" + p + "_hip\" type=\"continuous\"><parent link=\"body\"/><child link=\"" +
            p + "\"/><origin xyz=\"" + std::to_string(0.2 * (k % 3 - 1)) + " " + (k < 3 ? "0.2" : "-0.2") +
            " 0\"/><axis xyz=\"0 1 0\"/></joint>\n";
  }
  text += "</robot>\n";
  ExpectRefused("rhex.urdf", text, {"single movable joint", "rotating C-legs"});
}

// --- hostile input (issue 19) ---

TEST(UrdfHostile, JointLoopsAndSelfParentsAreRefused) {
  Quad q;
  q.body_extra =
      "<link name=\"a\"/><link name=\"b\"/><link name=\"c\"/>"
      "<joint name=\"ab\" type=\"fixed\"><parent link=\"a\"/><child link=\"b\"/></joint>"
      "<joint name=\"ba\" type=\"revolute\"><parent link=\"b\"/><child link=\"a\"/><axis xyz=\"0 1 0\"/>"
      "<limit lower=\"-1\" upper=\"1\" effort=\"10\" velocity=\"10\"/></joint>"
      "<joint name=\"bc\" type=\"revolute\"><parent link=\"b\"/><child link=\"c\"/><axis xyz=\"0 1 0\"/>"
      "<limit lower=\"-1\" upper=\"1\" effort=\"10\" velocity=\"10\"/></joint>\n";
  const std::string loop = Write("loop.urdf", Urdf(q));
  const std::string error = ErrorOf([&] { LoadRobot(loop); });
  EXPECT_NE(error.find("the joints form a loop"), std::string::npos) << error;
  EXPECT_EQ(ExitCode(loop), 2);
  // The same through a robot YAML that names a foot in the loop.
  const std::string yaml = Write("loop.yaml", "urdf: " + loop + "\nfeet: [c]\n");
  EXPECT_NE(ErrorOf([&] { LoadRobot(yaml); }).find("the joints form a loop"), std::string::npos);
  EXPECT_EQ(ExitCode(yaml), 2);
  q.body_extra =
      "<link name=\"s\"/><joint name=\"self\" type=\"fixed\"><parent link=\"s\"/><child link=\"s\"/></joint>\n";
  const std::string self = Write("self.urdf", Urdf(q));
  EXPECT_NE(ErrorOf([&] { LoadRobot(self); }).find("link 's' is its own parent"), std::string::npos);
  EXPECT_EQ(ExitCode(self), 2);
}

std::string LongLeg(int revolute, int fixed_links) {
  std::string text = "<robot name=\"snake\"><link name=\"body\"/>\n";
  std::string parent = "body";
  for (int i = 0; i < revolute + fixed_links; ++i) {
    const std::string link = "l" + std::to_string(i);
    const bool movable = i < revolute;
    text += "<link name=\"" + link + "\"/><joint name=\"j" + std::to_string(i) + "\" type=\"" +
            (movable ? "revolute" : "fixed") + "\"><parent link=\"" + parent + "\"/><child link=\"" + link +
            "\"/><origin xyz=\"0 0 -0.01\"/>" +
            (movable ? std::string("<axis xyz=\"") + (i % 2 ? "1 0 0" : "0 1 0") + "\"/><limit lower=\"-1\" upper=\"1\" effort=\"10\" velocity=\"10\"/>" : "") +
            "</joint>\n";
    parent = link;
  }
  return text + "</robot>\n";
}

TEST(UrdfHostile, LegsWithManyJointsAreRefusedQuickly) {
  for (const auto& [revolute, fixed, expect] :
       std::vector<std::tuple<int, int, std::string>>{{32, 0, "has 32 movable joints; mfp reads at most 12"},
                                                      {64, 0, "has 64 movable joints; mfp reads at most 12"},
                                                      {3, 1000, "has more than 64 joints"}}) {
    ExpectRefused("long.urdf", LongLeg(revolute, fixed), {expect});
  }
}

std::string ManyLegs(int legs) {
  std::ostringstream text;
  text << "<robot name=\"centipede\"><link name=\"body\"/>\n";
  for (int k = 0; k < legs; ++k) {
    const std::string p = "g" + std::to_string(k);
    text << "<link name=\"" << p << "a\"/><link name=\"" << p << "b\"/><link name=\"" << p << "c\"/>"
         << "<joint name=\"" << p << "1\" type=\"revolute\"><parent link=\"body\"/><child link=\"" << p
         << "a\"/><origin xyz=\"" << 0.01 * k << " 0 0\"/><axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"10\" velocity=\"10\"/></joint>"
         << "<joint name=\"" << p << "2\" type=\"revolute\"><parent link=\"" << p << "a\"/><child link=\"" << p
         << "b\"/><axis xyz=\"1 0 0\"/><limit lower=\"-1\" upper=\"1\" effort=\"10\" velocity=\"10\"/></joint>"
         << "<joint name=\"" << p << "3\" type=\"fixed\"><parent link=\"" << p << "b\"/><child link=\"" << p
         << "c\"/><origin xyz=\"0 0.1 -0.1\"/></joint>\n";
  }
  text << "</robot>\n";
  return text.str();
}

TEST(UrdfHostile, ThousandsOfLegsAreRefusedQuickly) {
  const std::string thousand = Write("1000.urdf", ManyLegs(1000));
  EXPECT_NE(ErrorOf([&] { LoadRobot(thousand); }).find("more than 16 legs found"), std::string::npos);
  EXPECT_EQ(ExitCode(thousand), 2);
  const std::string many = Write("10000.urdf", ManyLegs(10000));
  EXPECT_NE(ErrorOf([&] { LoadRobot(many); }).find("more than 10000 links"), std::string::npos);
  EXPECT_EQ(ExitCode(many), 2);
}

TEST(UrdfHostile, ANameThatIsNotUtf8IsWrittenToJson) {
  Quad q;
  q.name = "quad\xff\xfe";
  const std::string urdf = Write("n.urdf", Urdf(q));
  const std::string json = TestTempPath("robot.json");
  EXPECT_EQ(ExitCode(urdf + " --json " + json), 0);
  std::ifstream in(json);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"name\": \"quad\xEF\xBF\xBD\xEF\xBF\xBD\""), std::string::npos) << text.substr(0, 200);
  // mfp-plan writes the robot object in the plan JSON too.
  const std::string scenario = Write("s.yaml", "robot: " + urdf +
                                                   "\nterrain:\n  source: top_faces\n  boxes:\n"
                                                   "    - {name: ground, center: [0.3, 0, -0.05], size: [2, 2, 0.1]}\n"
                                                   "start: [0, 0, 0]\ngoal: [0.2, 0, 0]\n");
  const std::string plan = TestTempPath("plan.json");
  const int status = std::system((std::string(MFP_BINARY_DIR) + "/tools/mfp-plan --scenario " + scenario +
                                  " --time-limit 20 --json " + plan + " >/dev/null 2>&1").c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  std::ifstream plan_in(plan);
  const std::string plan_text((std::istreambuf_iterator<char>(plan_in)), std::istreambuf_iterator<char>());
  EXPECT_NE(plan_text.find("quad\xEF\xBF\xBD\xEF\xBF\xBD"), std::string::npos) << plan_text.substr(0, 200);
}

}  // namespace
}  // namespace mfp
