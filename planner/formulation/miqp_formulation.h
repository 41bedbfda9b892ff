#pragma once
// The seed paper's mixed-integer footstep program for n legs, as a Miqp.
//
// Steps i = 0 .. n-1 are the start stance (fixed); steps n .. N-1 are new. Step i moves
// leg gait[(gait_phase + i) mod n]. Configuration b = floor(i / n) shares one
// yaw theta_b with s_b, c_b standing for sin/cos through a piecewise-linear chord
// approximation selected by one segment binary per configuration and segment. Configuration 0 is the
// start and has its exact yaw.
//
// Build() writes the paper's equation families in this order, one unit each:
//   footstep positions and centre of contacts (eq. 2)   centre_of_contacts.h
//   yaw with its sin/cos chords                         yaw_chords.h
//   yaw change                                          yaw_change_limit.h
//   reference box, reachability, height                 step_limits.h
//   trimming                                            trimming.h
//   region choice (big-M or convex hull)                region_choice.h, region_faces.h
//   cost                                                cost.h
// The families the polisher shares (yaw change, step limits, region faces) write their
// rows through a StepEncoder (step_encoder.h): here the MiqpEncoder (chords), in the
// polisher the ExactEncoder (exact sin/cos), in the plan validator the plan's values.
// The order of variables and rows is part of the contract: the search's node counts
// depend on it.
#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "base/deadline.h"
#include "planner/formulation/internal/footstep_problem.h"
#include "planner/formulation/internal/yaw_chords.h"
#include "planner/formulation/plan.h"
#include "planner/miqp/miqp.h"

namespace mfp {

class MiqpFormulation {
 public:
  // Throws InputError when the problem is malformed (sizes, non-finite numbers).
  // deadline (and its stop flag) is checked between the equation families and before
  // each step's regions; once it expires the build stops and out_of_time() is true.
  MiqpFormulation(const FootstepProblem& problem, const FormulationOptions& options,
                  const Deadline& deadline = Deadline());

  const Miqp& miqp() const { return miqp_; }
  const FootstepVariables& vars() const { return vars_; }
  const FootstepProblem& problem() const { return problem_; }
  const FormulationOptions& options() const { return options_; }

  int num_legs() const { return n_; }
  int num_steps() const { return num_steps_; }  // N, including the start stance
  int num_configurations() const { return num_configurations_; }
  int LegOfStep(int step) const;
  int ConfigurationOfStep(int step) const { return step / n_; }
  // Breakpoints of the yaw segments [rad] (num segments + 1 values): the uniform grid
  // over the whole yaw range.
  const std::vector<double>& yaw_breakpoints() const { return yaw_.breakpoints; }
  // The breakpoints of configuration cfg's own segments (vars().segment[cfg][k] spans
  // [k, k+1]): the grid's segments that meet the yaw the configuration can reach. Empty
  // for configuration 0.
  const std::vector<double>& configuration_yaw_breakpoints(int cfg) const { return yaw_.configuration_breakpoints[cfg]; }
  // Goal foot position (x, y) of a leg [m].
  Eigen::Vector2d GoalFoot(int leg) const;

  // The build ran out of time (see the constructor): the Miqp is incomplete, not to be
  // solved or read; the caller ends on its time limit.
  bool out_of_time() const { return out_of_time_; }

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
  void Build(const Deadline& deadline);
  // One rounding with steps first_trimmed .. N-1 trimmed; false when a step has no region.
  bool RoundWithTrimming(const Eigen::VectorXd& relaxed, int first_trimmed, Eigen::VectorXd* rounded) const;

  FootstepProblem problem_;
  FormulationOptions options_;
  int n_ = 0;
  int num_steps_ = 0;
  int num_configurations_ = 0;
  YawGrid yaw_;
  Miqp miqp_;
  FootstepVariables vars_;
  // Per step: the rows [first, last) that encode its region choice (-1, -1 for start
  // steps and steps that reach no region).
  std::vector<std::pair<int, int>> region_rows_;
  std::string infeasible_reason_;
  bool out_of_time_ = false;
};

}  // namespace mfp
