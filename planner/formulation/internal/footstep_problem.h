#pragma once
// The data of the footstep MIQP: its options, the problem it is built for and the index of
// each of its variables. Steps i = 0 .. n-1 are the start stance (fixed); steps n .. N-1
// are new. Step i moves leg gait[(gait_phase + i) mod n]; configuration b = floor(i / n)
// shares one yaw theta_b.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "geometry/convex_region.h"
#include "geometry/free_region_2d.h"
#include "planner/robot/robot_model.h"

namespace mfp {

enum class RegionEncoding {
  kBigM,        // A_r f <= b_r + M_r (1 - H_ir), M as tight as the workspace box allows
  kConvexHull,  // f_i = sum_r f_ir, A_r f_ir <= b_r H_ir (disaggregated, tighter)
};

enum class YawEncoding {
  kBigM,        // S_k => psi_k <= theta <= psi_k+1 and s, c on the segment's chords (big-M)
  kConvexHull,  // disaggregated theta_k per segment: the relaxation is the hull of the curves
};

// The order of the Miqp's one-of groups, which the group_order branching rule follows.
enum class GroupOrder {
  kPlan,           // per configuration: its yaw segments, then its steps' regions
  kSegmentsFirst,  // every configuration's yaw segments, then the regions in plan order
};

struct FormulationOptions {
  double yaw_segment_rad = 0.3927;   // width of one sin/cos chord segment [rad] (pi/8)
  double yaw_margin_rad = 0.3927;    // yaw range = [min(start, goal) - m, max(start, goal) + m]
  RegionEncoding region_encoding = RegionEncoding::kBigM;
  YawEncoding yaw_encoding = YawEncoding::kConvexHull;
  GroupOrder group_order = GroupOrder::kPlan;
  // Drop region binaries a step cannot use: regions farther from the start stance than
  // the step's configuration could travel at d_lim + l_bnd per configuration.
  bool prune_unreachable_regions = true;
  // Trimmed steps form a suffix (t_i <= t_{i+1}): removes symmetric solutions.
  bool monotone_trimming = true;
  // Each configuration's yaw is also bounded by the yaw it can reach from the start at
  // max_yaw_change per configuration, and the chord segments outside that range are left
  // out. Same plans (the yaw change rows imply the range); the relaxation of sin/cos is
  // tighter for the first configurations, whose range is narrow.
  bool clip_yaw_to_reach = true;
  // A configuration whose first step is trimmed keeps the yaw of the one before
  // (AddTrimmedConfigurationsHoldYaw): the goal cost then weighs the yaw of the last step
  // taken, the plan's final body yaw.
  bool trimmed_configurations_hold_yaw = true;
  // Body regions (body_region_faces.h): each configuration's body plan box in one of the
  // problem's body regions, chosen by binaries. Off (the default): body_regions are
  // ignored. Off by default because with a scanned map's obstacles a window can be
  // infeasible at its start (docs/body_clearance.md); the route and the window body check
  // keep the body clear without them.
  bool body_regions = false;
  // The body box is kept this far inside its region [m] (above the chords' own error).
  double body_margin_m = 0.002;
  // At most this many body regions per window (the planner grows them; each costs one
  // binary per configuration and 4 n rows per face).
  int max_body_regions = 6;
};

struct FootstepProblem {
  const RobotModel* robot = nullptr;          // not owned; outlives the formulation
  std::vector<ConvexRegion> regions;
  // Start stance in step order: start_feet[i] is the foot of leg gait[(gait_phase + i) % n].
  std::vector<Eigen::Vector3d> start_feet_world_m;
  int gait_phase = 0;
  double start_yaw_rad = 0.0;  // yaw of the configuration the new steps start from [rad]
  // Optional, for windows after the first: the n footsteps before the start stance (step
  // order) and the yaw each start step was planned with. Empty: the robot stood still
  // in the start stance with start_yaw_rad, as at the beginning of a plan.
  std::vector<Eigen::Vector3d> history_feet_world_m;
  std::vector<double> start_step_yaw_rad;
  double goal_x_m = 0.0;
  double goal_y_m = 0.0;
  double goal_yaw_rad = 0.0;
  // The goal term's weights are at least these (the robot's weights otherwise): a plan's
  // finishing windows raise them (planner/planning/internal/horizon_policy.h) [per m^2, per rad^2].
  double min_goal_position_weight = 0.0;
  double min_goal_yaw_weight = 0.0;
  int num_new_steps = 0;  // N - n
  // Convex regions of the plan free of the body obstacles in the body's band (world
  // frame). Empty (as without obstacles or without a known body): no body rows, the
  // MIQP is the seed paper's.
  std::vector<FreeRegion2d> body_regions;
};

// Index of each decision variable in the Miqp (-1 where absent).
struct FootstepVariables {
  std::vector<int> x, y, z;              // per step; -1 for start steps (constants)
  std::vector<int> px, py;               // centre of contacts p_i per step; -1 for start steps
  std::vector<int> theta, s, c;          // per configuration
  std::vector<int> trim;                 // per step; -1 for start steps
  std::vector<std::vector<int>> region;  // [step][region index] -> H_ir or -1 when pruned
  std::vector<std::vector<int>> segment; // [configuration][segment] -> binary
  std::vector<std::vector<int>> segment_theta;  // [configuration][segment] -> theta_k (hull encoding)
  // Convex-hull encoding only: [step][region] -> first of 3 copies (x, y, z) or -1.
  std::vector<std::vector<int>> region_copy;
  // [configuration][body region] -> G_br, the body's region (empty without body regions;
  // none for configuration 0, the start).
  std::vector<std::vector<int>> body_region;
};

}  // namespace mfp
