#pragma once
// The seed paper's mixed-integer footstep program for n legs, as a Miqp.
//
// Steps i = 0 .. n-1 are the start stance (fixed); steps n .. N-1 are new. Step i moves
// leg gait[(gait_phase + i) mod n]. Configuration (block) b = floor(i / n) shares one
// yaw theta_b with s_b, c_b standing for sin/cos through a piecewise-linear chord
// approximation selected by one segment binary per block and segment. Block 0 is the
// start and has its exact yaw.
//
// Centre of contacts p_i = mean of the n latest footsteps ending at i (paper eq. 2);
// footsteps before the plan started are the start stance. Every constraint is listed in
// miqp_formulation.cc next to the code that writes it.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "planner/miqp.h"
#include "planner/plan.h"
#include "planner/robot_model.h"
#include "terrain/convex_region.h"

namespace mfp {

enum class RegionEncoding {
  kBigM,        // A_r f <= b_r + M_r (1 - H_ir), M as tight as the workspace box allows
  kConvexHull,  // f_i = sum_r f_ir, A_r f_ir <= b_r H_ir (disaggregated, tighter)
};

enum class YawEncoding {
  kBigM,        // S_k => psi_k <= theta <= psi_k+1 and s, c on the segment's chords (big-M)
  kConvexHull,  // disaggregated theta_k per segment: the relaxation is the hull of the curves
};

struct FormulationOptions {
  double yaw_segment_rad = 0.3927;   // width of one sin/cos chord segment [rad] (pi/8)
  double yaw_margin_rad = 0.3927;    // yaw range = [min(start, goal) - m, max(start, goal) + m]
  RegionEncoding region_encoding = RegionEncoding::kBigM;
  YawEncoding yaw_encoding = YawEncoding::kConvexHull;
  // Drop region binaries a step cannot use: regions farther from the start stance than
  // the step's block could travel at d_lim + l_bnd per configuration.
  bool prune_unreachable_regions = true;
  // Trimmed steps form a suffix (t_i <= t_{i+1}): removes symmetric solutions.
  bool monotone_trimming = true;
  // Each configuration's yaw is also bounded by the yaw it can reach from the start at
  // max_yaw_change per configuration, and the chord segments outside that range are left
  // out. Same plans (the yaw change rows imply the range); the relaxation of sin/cos is
  // tighter for the first configurations, whose range is narrow.
  bool clip_yaw_to_reach = true;
  // A configuration whose first step is trimmed keeps the yaw of the one before
  // (|theta_b - theta_b-1| <= max_yaw_change (1 - t_bn)): with trimming as a suffix the
  // goal cost then weighs the yaw of the last step taken, the plan's final body yaw.
  bool trimmed_configurations_hold_yaw = true;
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
  int num_new_steps = 0;  // N - n
};

// Index of each decision variable in the Miqp (-1 where absent).
struct FootstepVariables {
  std::vector<int> x, y, z;              // per step; -1 for start steps (constants)
  std::vector<int> px, py;               // centre of contacts p_i per step; -1 for start steps
  std::vector<int> theta, s, c;          // per block
  std::vector<int> trim;                 // per step; -1 for start steps
  std::vector<std::vector<int>> region;  // [step][region index] -> H_ir or -1 when pruned
  std::vector<std::vector<int>> segment; // [block][segment] -> binary
  std::vector<std::vector<int>> segment_theta;  // [block][segment] -> theta_k (hull encoding)
  // Convex-hull encoding only: [step][region] -> first of 3 copies (x, y, z) or -1.
  std::vector<std::vector<int>> region_copy;
};

class MiqpFormulation {
 public:
  // Throws InputError when the problem is malformed (sizes, non-finite numbers).
  MiqpFormulation(const FootstepProblem& problem, const FormulationOptions& options);

  const Miqp& miqp() const { return miqp_; }
  const FootstepVariables& vars() const { return vars_; }
  const FootstepProblem& problem() const { return problem_; }
  const FormulationOptions& options() const { return options_; }

  int num_legs() const { return n_; }
  int num_steps() const { return num_steps_; }  // N, including the start stance
  int num_blocks() const { return num_blocks_; }
  int LegOfStep(int step) const;
  int BlockOfStep(int step) const { return step / n_; }
  // Breakpoints of the yaw segments [rad] (num segments + 1 values): the uniform grid
  // over the whole yaw range.
  const std::vector<double>& yaw_breakpoints() const { return breakpoints_; }
  // The breakpoints of configuration blk's own segments (vars().segment[blk][k] spans
  // [k, k+1]): the grid's segments that meet the yaw the configuration can reach. Empty
  // for block 0.
  const std::vector<double>& block_yaw_breakpoints(int blk) const { return block_breakpoints_[blk]; }
  // Goal foot position (x, y) of a leg [m].
  Eigen::Vector2d GoalFoot(int leg) const;

  // Non-empty when the problem is infeasible by construction (a step that can reach no
  // region); the Miqp is then not worth solving.
  const std::string& infeasible_reason() const { return infeasible_reason_; }

  // Footsteps of a solution, start stance included, with the region each step uses.
  std::vector<Footstep> ExtractFootsteps(const Eigen::VectorXd& x) const;
  // Number of new steps not trimmed in a solution.
  int CountUntrimmedSteps(const Eigen::VectorXd& x) const;

  // Roundings of a relaxation point that follow the plan step by step: the yaw segment
  // holding the relaxed yaw, for each step the region holding the relaxed foot (a
  // trimmed step keeps its foot's region), and trimming as a suffix. Proposals differ in
  // where trimming starts: where the relaxation passes one half, and nowhere.
  std::vector<Eigen::VectorXd> RoundAlongPlan(const Eigen::VectorXd& relaxed) const;

  // The Miqp with the region choice of steps first_step .. N-1 relaxed to the convex hull
  // of the union of each step's regions (RegionUnionHull: half-planes on (x, y) and the
  // height range): their region rows are left out, their region binaries (and copies)
  // fixed at 0, and the hull's rows added after the others. Same variables, so points
  // move between the two; the other rows keep their order. Relax-and-fix uses it for the
  // steps it has not reached: the relaxed choice in a few rows instead of a binary and a
  // handful of rows per region, so its stage QPs are smaller. first_step >= N: miqp().
  Miqp WithRegionsRelaxedFrom(int first_step) const;

  // Yaw segments that are fractional only because the relaxed yaw lies where one
  // segment alone represents it (typically on a breakpoint shared by two segments: the
  // goal yaw is one), set to that segment, within lower/upper (a node's bounds), with the
  // yaw's disaggregated parts moved to it. Returns true when x changed. For
  // BranchAndBoundOptions::equivalent_point: without it a search branches on such a
  // segment and explores the same plans under both children.
  bool SnapYawToOneSegment(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, Eigen::VectorXd* x) const;

 private:
  void Build();
  // One rounding with steps first_trimmed .. N-1 trimmed; false when a step has no region.
  bool RoundWithTrimming(const Eigen::VectorXd& relaxed, int first_trimmed, Eigen::VectorXd* rounded) const;

  FootstepProblem problem_;
  FormulationOptions options_;
  int n_ = 0;
  int num_steps_ = 0;
  int num_blocks_ = 0;
  std::vector<double> breakpoints_;
  std::vector<std::vector<double>> block_breakpoints_;
  std::vector<std::pair<double, double>> yaw_reach_;  // per block: [lowest, highest] yaw [rad]
  Miqp miqp_;
  FootstepVariables vars_;
  // Per step: the rows [first, last) that encode its region choice (-1, -1 for start
  // steps and steps that reach no region).
  std::vector<std::pair<int, int>> region_rows_;
  std::string infeasible_reason_;
};

}  // namespace mfp
