#pragma once
// The robot as the footstep planner sees it: legs with nominal offsets about the centre
// of contacts, a cyclic gait, and the reach limits of the paper. Filled by the robot
// loaders (YAML now, URDF derivation in urdf_robot_loader); plain data, no I/O.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace mfp {

// One face of a leg's footprint polygon: normal . w <= offset_m for a foot at w from the
// nominal foot, body frame [m] (normal a unit vector).
struct ReachFace {
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();
  double offset_m = 0.0;
};

struct LegModel {
  std::string name;
  // Foot position at the nominal stance relative to the centre of contacts, body frame,
  // x forward, y left [m]. The paper's L_leg = |o|, phi = atan2(o_y, o_x).
  Eigen::Vector2d nominal_offset_body_m = Eigen::Vector2d::Zero();
  // Hip (first joint of the leg chain) in the body frame [m]; zero when unknown.
  Eigen::Vector3d hip_body_m = Eigen::Vector3d::Zero();
  // The leg's footprint polygon (ReachShape::kFootprint): a convex polygon about the
  // nominal foot inside the leg's reachable footprint at the stance height; empty for the
  // other shapes.
  std::vector<ReachFace> footprint_faces;
};

// Cost weights of the paper's objective. The goal term must dominate.
struct PlannerWeights {
  // A foot moves for the goal only while weight * error^2 beats one trimmed step, so
  // 1000 leaves feet within ~3 cm (sqrt(1 / 1000) m) of their goal spots.
  double goal_position = 1000.0;  // per m^2 of final-stance foot error (x, y)
  double goal_yaw = 100.0;       // per rad^2 of final yaw error (~0.1 rad left at most)
  double trim_step = -1.0;       // per trimmed step (negative: rewards shorter plans)
  double displacement = 1.0;     // per m^2 of centre-of-contacts motion between configurations
};

// The body's extent for clearance: a box in plan view, in the body frame about the centre
// of contacts of the nominal stance (x forward, y left), and the height band it fills
// above the feet's plane at the nominal stance. It keeps out the base link's box and the
// legs' upper joints (hips, knees) at the nominal stance, in plan view, within the
// base's height band; it does not keep out lower legs, feet in swing, knees below the
// base's band, or the body's motion between configurations. All zero: unknown (no check).
struct BodyExtent {
  Eigen::Vector2d min_m = Eigen::Vector2d::Zero();  // rear-right corner [m]
  Eigen::Vector2d max_m = Eigen::Vector2d::Zero();  // front-left corner [m]
  double bottom_m = 0.0;  // lowest point above the feet's plane [m]
  double top_m = 0.0;     // highest point above the feet's plane [m]

  bool known() const { return (max_m - min_m).minCoeff() > 0.0 && top_m > bottom_m; }
  double length_m() const { return max_m.x() - min_m.x(); }
  double width_m() const { return max_m.y() - min_m.y(); }
};

// Corners of the body's plan box for a configuration at (x, y) and yaw, counter-clockwise
// [m, world].
std::vector<Eigen::Vector2d> BodyFootprint(const BodyExtent& body, double x_m, double y_m, double yaw_rad);

// The polygon a foot's new position keeps about its previous nominal spot (the paper's
// reachability limit), world-aligned, d_lim its half-width on each axis:
//   kBox          the paper's square |dx|, |dy| <= d_lim; its corners lie sqrt(2) d_lim
//                 from the spot, so it holds at every body yaw only where the leg reaches
//                 that far in every direction;
//   kOctagon      the square with the diagonal rows |dx +- dy| <= sqrt(2) d_lim: the
//                 regular octagon of apothem d_lim, corners d_lim / cos(pi/8) from the spot;
//   kHexadecagon  the regular 16-gon of apothem d_lim (faces normal to multiples of pi/8),
//                 corners d_lim / cos(pi/16) from the spot.
//   kFootprint    each leg's own footprint polygon (LegModel::footprint_faces), turned with
//                 the body: both the reference rows (about r_nom,i) and the reachability rows
//                 (about r_nom,i-n) keep the foot inside it at every yaw the configuration
//                 may take; d_lim is then the inscribed 16-gon's apothem, the reach the
//                 polygon has in every direction.
// The octagon, the 16-gon and the footprint polygon are derived inside the leg's reachable
// footprint at every body yaw (robot_derivation.h).
enum class ReachShape { kBox, kOctagon, kHexadecagon, kFootprint };

// "box", "octagon", "hexadecagon" or "footprint".
const char* ReachShapeName(ReachShape shape);

// The regular shape's number of sides: 4, 8 or 16; 16 for the footprint (its inscribed
// 16-gon, which d_lim is the apothem of).
int ReachShapeSides(ReachShape shape);

struct RobotModel {
  std::string name;
  std::vector<LegModel> legs;
  // Cyclic order in which legs move (indices into legs); each leg exactly once.
  std::vector<int> gait;
  double stance_height_m = 0.0;     // hip height above the feet at the nominal stance [m]
  double foot_radius_m = 0.0;       // contact radius; terrain regions are inset by it [m]
  double d_lim_m = 0.0;             // half-width of the reach polygon on each axis [m]
  ReachShape reach_shape = ReachShape::kBox;
  double l_bnd_m = 0.0;             // half-side of the reference square about r_nom [m]
  double dz_max_m = 0.0;            // largest height change of one step [m]
  double max_yaw_change_rad = 0.0;  // largest body yaw change between configurations [rad]
  double max_slope_rad = 0.5;       // steepest surface a foot may stand on [rad]
  PlannerWeights weights;
  BodyExtent body;  // for body clearance; unknown unless derived or given
  // One line per parameter saying where its value came from ("d_lim_m = 0.070 m:
  // override in robot.yaml (derived 0.064 m)"). Printed by mfp-robot.
  std::vector<std::string> provenance;

  int num_legs() const { return static_cast<int>(legs.size()); }
};

// Throws InputError naming the first field that is out of range (non-finite values,
// empty legs, a gait that is not a permutation, non-positive limits, ...).
void ValidateRobotModel(const RobotModel& robot);

// Where a leg's foot stands in plan view at the nominal stance of a body pose: the pose
// (x, y) plus the leg's nominal offset rotated by yaw [m, world].
Eigen::Vector2d NominalFootXY(const RobotModel& robot, int leg, double x_m, double y_m, double yaw_rad);

// Centre of contacts of a stance in plan view: the mean of its feet's (x, y) (the paper's
// eq. 2 for the n feet standing) [m, world]. At least one foot.
Eigen::Vector2d StanceCentreXY(const std::vector<Eigen::Vector3d>& feet_world_m);

// Farthest nominal foot from the centre of contacts, max over legs of |o_leg| [m].
double LegReach(const RobotModel& robot);

// The yaw change that moves a foot leg_reach_m from the centre by d_lim_m,
// 2 asin(d_lim / (2 leg_reach)) [rad] (pi/4 when leg_reach is 0).
double MaxYawChangeFor(double d_lim_m, double leg_reach_m);

// Mean of the nominal offsets; offsets are expected to be centred (mean zero) so that
// the centre of contacts of a nominal stance is the body origin.
Eigen::Vector2d MeanNominalOffset(const RobotModel& robot);

}  // namespace mfp
