#pragma once
// Derives the planner's robot model (robot_model.h) from leg kinematics alone:
//  - reachable footprint of each foot at a height: the cells of a grid in the body frame
//    whose centre the foot reaches at that height within the joint limits (inverse
//    kinematics, flood-filled from joint-space samples);
//  - stance height: unless given, among candidates spanning 25 %..95 % of the smallest
//    downward reach (full extension below the hips), the one nearest stance_fraction
//    (70 %: legged robots stand with the knee bent, at 60-80 % of full extension) where
//    every leg's inscribed square is at least half the best over the candidates;
//  - nominal foot: the centre of the largest square inscribed in the footprint at the
//    stance height (the paper puts the workspace centre at the nominal foot), ties broken
//    towards the point below the hip; o_k = nominal foot - mean of the nominal feet;
//  - d_lim: the half-width on each axis of the reach polygon (robot_model.h ReachShape):
//    for the paper's box, the smallest of the legs' inscribed half-sides, less half a grid
//    cell; for the octagon and the 16-gon, the apothem of the regular polygon inscribed in
//    the smallest of the legs' largest disks about their nominal feet, less half a grid cell
//    (the polygon then lies in the footprint at every body yaw, which the box does not);
//    for the footprint shape (the default), d_lim is the 16-gon's and each leg also gets its
//    footprint polygon (footprint_polygon.h), faces pulled in by half a cell; when some leg's
//    footprint holds none and the shape was not stated (reach_shape_given empty), the model
//    gets the 16-gon instead, with a provenance line naming the leg;
//  - dz_max: the smallest, over legs and up/down, vertical travel of the foot from the
//    nominal foot that stays reachable (continuation inverse kinematics);
//  - l_bnd = l_bnd_fraction * d_lim; max yaw change: the yaw about the centre of contacts
//    that moves the farthest nominal foot by d_lim, 2 asin(d_lim / (2 max L_leg));
//  - gait: a wave around the body, legs in decreasing angle of o_k, starting from the
//    one nearest the rear left (angle closest to +pi).
// Every value gets a provenance line saying how it was derived.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "base/deadline.h"
#include "planner/robot/internal/footprint_grid.h"
#include "planner/robot/internal/leg_kinematics.h"
#include "planner/robot/robot_model.h"

namespace mfp {

struct DerivationOptions {
  std::optional<double> stance_height_m;  // fixed stance height (YAML); else chosen
  int samples_per_leg = 40000;            // joint-space grid used to seed the footprints
  int final_cells = 96;                   // footprint cells across the leg's horizontal reach
  int scan_cells = 24;                    // coarser cells while choosing the stance height
  int stance_candidates = 15;             // heights tried when choosing the stance height
  double stance_fraction = 0.70;          // preferred stance: this fraction of the downward reach
  double l_bnd_fraction = 0.5;            // l_bnd = l_bnd_fraction * d_lim
  // Which polygon d_lim is derived for. The default, each leg's own footprint polygon turned
  // with the body, holds at every body yaw (as the octagon and the 16-gon do) and keeps the
  // footprint's longer reach forward and back, so the robot crosses the gaps its legs can
  // cross; the paper's box only when a robot file states it (reach_shape_given). When a
  // leg's footprint holds no polygon about its nominal foot, the default falls back to the
  // 16-gon, so that no URDF robot becomes unplannable by it; a stated footprint throws.
  ReachShape reach_shape = ReachShape::kFootprint;
  std::string reach_shape_given;          // who stated it ("by the caller", "in FILE"; "": the default)
  // Faces of each leg's footprint polygon (reach_shape footprint): enough to follow the
  // footprint's rounded front and back, which give the long steps the shape is chosen for
  // (fewer faces plan faster and step shorter: docs/measurements.md, stop 38).
  int footprint_faces = 12;
  double centre_weight_per_m = 0.1;       // tie-break towards the point below the hip
  double ik_tolerance_m = 1e-5;
  // The request's deadline and stop flag: checked between legs and stance candidates and
  // inside the footprints' flood fill; once expired DeriveRobot throws TimeLimitError.
  Deadline deadline;
};

struct LegDerivation {
  Eigen::Vector3d hip_body_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d nominal_foot_body_m = Eigen::Vector3d::Zero();
  Eigen::VectorXd nominal_q;       // joint positions of the nominal stance [rad or m]
  double square_half_side_m = 0;   // this leg's inscribed square (before the half-cell margin)
  double disk_radius_m = 0;        // largest disk about the nominal foot in the footprint (likewise)
  double dz_up_m = 0;              // reachable rise above the stance at the nominal foot
  double dz_down_m = 0;            // reachable drop below it
  double lowest_foot_z_m = 0;      // lowest foot point over the joint space (body frame)
  FootprintGrid footprint;         // at the stance height
};

struct RobotDerivation {
  RobotModel model;
  std::vector<LegDerivation> legs;
  double feet_plane_z_body_m = 0;  // body-frame height of the ground at the nominal stance
};

// Throws InputError when a leg cannot reach the ground at any stance height (or at the
// given one), the legs have no common stance height, or a stated footprint shape
// (reach_shape_given) finds no polygon about some leg's nominal foot.
RobotDerivation DeriveRobot(const RobotDescription& robot, const DerivationOptions& options);

// The default wave gait for nominal offsets (see above).
std::vector<int> WaveGait(const std::vector<LegModel>& legs);

}  // namespace mfp
