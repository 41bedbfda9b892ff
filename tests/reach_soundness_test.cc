// A robot derived from a URDF without a stated reach_shape gets a reach polygon its legs can
// truly step at every body yaw: by default each leg's footprint polygon, which turns with the
// body, so each of its corners and edge middles about the leg's nominal foot is reached; and
// the 16-gon the default falls back to where no footprint polygon fits, each corner of it
// turned by yaws over a full turn. Reached means by that leg's inverse kinematics at the
// stance height within the joint limits (the kinematics themselves, not the model's d_lim
// nor the derivation's footprint grid). The paper's box, derived for the same robots,
// fails the same check (its corners lie beyond the legs' reach when the body is turned).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "io/robot_loader.h"
#include "planner/robot/derivation_budget.h"
#include "planner/robot/reach_polygon.h"
#include "planner/robot/robot_derivation.h"
#include "planner/robot/urdf_reader.h"

namespace mfp {
namespace {

constexpr int kYawStepDegrees = 5;
constexpr double kIkToleranceM = 1e-5;
constexpr int kRandomStarts = 200;

// The repository's URDFs the tests load.
std::vector<std::string> RepositoryUrdfs() {
  std::vector<std::string> files;
  for (const char* file : {"config/robots/littledog.urdf", "config/robots/hexapod.urdf", "config/robots/octopod.urdf",
                           "tests/data/robots/sphere_quad.urdf"}) {
    files.push_back(std::string(MFP_SOURCE_DIR) + "/" + file);
  }
  return files;
}

// The zoo's quadrupeds (robot_zoo_test.sh's cached example-robot-data), when installed.
std::vector<std::string> ZooUrdfs() {
  namespace fs = std::filesystem;
  const char* venv_env = std::getenv("MFP_ZOO_VENV");
  const char* home = std::getenv("HOME");
  const fs::path venv = venv_env ? fs::path(venv_env) : fs::path(home ? home : "/nonexistent") / ".cache/mfp/zoo-venv";
  std::error_code error;
  if (!fs::is_directory(venv / "lib", error)) return {};
  std::vector<std::string> files;
  for (const fs::directory_entry& python : fs::directory_iterator(venv / "lib", error)) {
    const fs::path robots = python.path() / "site-packages/cmeel.prefix/share/example-robot-data/robots";
    for (const char* file : {"go1_description/urdf/go1.urdf", "go2_description/urdf/go2.urdf",
                             "a1_description/urdf/a1.urdf", "anymal_c_simple_description/urdf/anymal.urdf",
                             "anymal_b_simple_description/robots/anymal.urdf",
                             "hyq_description/robots/hyq_no_sensors.urdf", "solo_description/robots/solo12.urdf"}) {
      if (fs::is_regular_file(robots / file, error)) files.push_back((robots / file).string());
    }
  }
  return files;
}

// True when the leg's foot reaches `target` (body frame) within its joint limits: inverse
// kinematics from the last solution found (`*q_hint`), else by continuation along the
// straight line from the nominal foot (the disk the polygon lies in is star-shaped about
// it), each point solved from the one before.
bool Reaches(const LegChain& leg, const Eigen::Vector3d& nominal_foot, const Eigen::Vector3d& target,
             const Eigen::VectorXd& q_nominal, Eigen::VectorXd* q_hint) {
  IkResult ik = SolveFootIk(leg, target, *q_hint, kIkToleranceM, 400);
  if (ik.converged) {
    *q_hint = ik.q;
    return true;
  }
  constexpr int kContinuationSteps = 16;
  Eigen::VectorXd q = q_nominal;
  bool converged = true;
  for (int t = 1; t <= kContinuationSteps && converged; ++t) {
    const double share = static_cast<double>(t) / kContinuationSteps;
    ik = SolveFootIk(leg, nominal_foot + share * (target - nominal_foot), q, kIkToleranceM, 400);
    converged = ik.converged;
    q = ik.q;
  }
  if (converged) {
    *q_hint = q;
    return true;
  }
  // Other branches of the leg (a knee bent the other way): starts spread over the joint box.
  const Eigen::VectorXd lower = leg.LowerLimits(), upper = leg.UpperLimits();
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int start = 0; start < kRandomStarts; ++start) {
    Eigen::VectorXd q_start = lower;
    for (int j = 0; j < q_start.size(); ++j) q_start(j) += unit(random) * (upper(j) - lower(j));
    ik = SolveFootIk(leg, target, q_start, kIkToleranceM, 400);
    if (ik.converged) {
      *q_hint = ik.q;
      return true;
    }
  }
  return false;
}

// Corners of the robot's reach polygon about each leg's nominal foot, at body yaws every
// kYawStepDegrees over a full turn, that the leg cannot reach, counted up to `stop_after`;
// each named in `failures` (the first few).
int UnreachableCorners(const std::string& file, const RobotModel& robot, const RobotDerivation& derivation,
                       int stop_after, std::vector<std::string>* failures) {
  RobotDescription description = ReadUrdfRobot(file);
  WithinDerivationBudget(DerivationOptions{}, &description);
  EXPECT_EQ(description.legs.size(), derivation.legs.size()) << file;
  int unreachable = 0;
  for (size_t k = 0; k < derivation.legs.size() && k < description.legs.size(); ++k) {
    const LegDerivation& leg = derivation.legs[k];
    Eigen::VectorXd q_hint = leg.nominal_q;
    for (int degrees = 0; degrees < 360; degrees += kYawStepDegrees) {
      const Eigen::Rotation2Dd turn(degrees * M_PI / 180.0);
      for (const Eigen::Vector2d& corner : ReachPolygon(robot.reach_shape, robot.d_lim_m)) {
        Eigen::Vector3d target = leg.nominal_foot_body_m;
        target.head<2>() += turn * corner;
        if (Reaches(description.legs[k], leg.nominal_foot_body_m, target, leg.nominal_q, &q_hint)) continue;
        if (++unreachable >= stop_after) return unreachable;
        if (failures->size() < 3) {
          failures->push_back("leg " + std::to_string(k) + " at " + std::to_string(degrees) + " deg, corner (" +
                              std::to_string(corner.x()) + ", " + std::to_string(corner.y()) + ")");
        }
      }
    }
  }
  return unreachable;
}

std::string Join(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& line : lines) out += "\n  " + line;
  return out;
}

// Points of each leg's footprint polygon (reach_shape footprint: its corners and the
// middles of its edges, about the nominal foot; the polygon turns with the body, so no yaw
// sweep) the leg's inverse kinematics does not reach; the first few named in `failures`.
int UnreachableFootprintPoints(const std::string& file, const RobotDerivation& derivation,
                               std::vector<std::string>* failures) {
  RobotDescription description = ReadUrdfRobot(file);
  WithinDerivationBudget(DerivationOptions{}, &description);
  EXPECT_EQ(derivation.model.reach_shape, ReachShape::kFootprint) << file;
  int unreachable = 0;
  for (size_t k = 0; k < derivation.legs.size() && k < description.legs.size(); ++k) {
    const LegDerivation& leg = derivation.legs[k];
    const std::vector<Eigen::Vector2d> corners = ReachFaceCorners(derivation.model.legs[k].footprint_faces);
    EXPECT_GE(corners.size(), 3u) << file << " leg " << k;
    Eigen::VectorXd q_hint = leg.nominal_q;
    for (size_t c = 0; c < corners.size(); ++c) {
      const Eigen::Vector2d middle = 0.5 * (corners[c] + corners[(c + 1) % corners.size()]);
      for (const Eigen::Vector2d& point : {corners[c], middle}) {
        Eigen::Vector3d target = leg.nominal_foot_body_m;
        target.head<2>() += point;
        if (Reaches(description.legs[k], leg.nominal_foot_body_m, target, leg.nominal_q, &q_hint)) continue;
        ++unreachable;
        if (failures->size() < 3) {
          failures->push_back(file + " leg " + std::to_string(k) + " point (" + std::to_string(point.x()) + ", " +
                              std::to_string(point.y()) + ")");
        }
      }
    }
  }
  return unreachable;
}

// The robot derived from `file` with the reach polygon `shape` stated by the caller.
RobotDerivation DeriveShaped(const std::string& file, ReachShape shape) {
  RobotDescription description = ReadUrdfRobot(file);
  DerivationOptions options = WithinDerivationBudget(DerivationOptions{}, &description);
  options.reach_shape = shape;
  options.reach_shape_given = "by the test";
  return DeriveRobot(description, options);
}

// Expects the robot's default reach polygon (each leg's footprint polygon) steppable, and
// the 16-gon the default falls back to steppable at every yaw; returns 1 when a corner of
// the paper's box, derived for the same robot, is not (0 when every corner is).
int ExpectSoundByDefault(const std::string& file) {
  RobotDerivation derivation;
  LoadRobot(file, &derivation);
  std::vector<std::string> failures;
  EXPECT_EQ(UnreachableFootprintPoints(file, derivation, &failures), 0) << file << Join(failures);
  const RobotDerivation hexadecagon = DeriveShaped(file, ReachShape::kHexadecagon);
  std::vector<std::string> hexadecagon_failures;
  EXPECT_EQ(UnreachableCorners(file, hexadecagon.model, hexadecagon, 1 << 30, &hexadecagon_failures), 0)
      << file << Join(hexadecagon_failures);
  const RobotDerivation box = DeriveShaped(file, ReachShape::kBox);
  std::vector<std::string> box_failures;
  return UnreachableCorners(file, box.model, box, /*stop_after=*/1, &box_failures);
}

TEST(ReachSoundness, EveryRepositoryUrdfRobotsDefaultReachIsSteppableAtEveryBodyYaw) {
  int box_unreachable = 0;
  for (const std::string& file : RepositoryUrdfs()) box_unreachable += ExpectSoundByDefault(file);
  // The check can fail: the paper's box leaves the legs' reach once the body is turned
  // (measured: for every one of these robots).
  EXPECT_EQ(box_unreachable, static_cast<int>(RepositoryUrdfs().size()));
}

TEST(ReachSoundness, EveryZooQuadrupedsDefaultReachIsSteppableAtEveryBodyYaw) {
  const std::vector<std::string> files = ZooUrdfs();
  ASSERT_FALSE(files.empty()) << "the robot zoo's venv (made by robot_zoo_test, which ctest runs first) is missing: "
                                 "run `ctest -R robot_zoo_test`, or set MFP_ZOO_VENV to it";
  int box_unreachable = 0;
  for (const std::string& file : files) box_unreachable += ExpectSoundByDefault(file);
  EXPECT_GT(box_unreachable, 0);
}

}  // namespace
}  // namespace mfp
