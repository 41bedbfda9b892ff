#pragma once
// The expressions the paper's constraints and cost are written in, over the variables of
// the footstep MIQP as far as they have been added: footstep positions f_j (constants for
// the start stance and before it), the centre of contacts p_i (eq. 2), the configuration
// yaw theta_b with its sin/cos stand-ins s_b, c_b (constants for configuration 0, the
// start), and the nominal foot r_nom,i = p_i + R(theta_b(i)) o_leg(i) (eq. 3).
#include <string>
#include <vector>

#include "planner/formulation/internal/footstep_problem.h"
#include "planner/miqp/miqp_builder.h"

namespace mfp {

// Leg that step i moves: gait[(gait_phase + i) mod n] (any integer i).
int LegOfStep(const FootstepProblem& problem, int step);

// "what_i".
std::string StepName(const char* what, int i);

// A choice of one among `count` options at index i (a configuration's yaw segment, its body
// region): adds binaries named "<binary_prefix>_<i>_<k>" for k = 0..count-1, in that order,
// then the row "<row_name>_<i>": their sum = 1. Returns the binaries' indices.
std::vector<int> AddExactlyOneBinaries(const char* binary_prefix, const char* row_name, int i, int count,
                                       MiqpBuilder* b);

class StepExpressions {
 public:
  // Both must outlive this object; vars is read at each call, so expressions use the
  // variables added so far.
  StepExpressions(const FootstepProblem& problem, const FootstepVariables& vars);

  int num_legs() const { return n_; }
  int LegOfStep(int j) const { return mfp::LegOfStep(problem_, j); }
  // Position of step j on one axis (0 x, 1 y, 2 z). Steps before the plan (j < 0) are the
  // given history, or without one the start stance of the same leg: a cyclic gait moves
  // leg(j) = leg(j + n).
  LinExpr Position(int j, int axis) const;
  // Mean of the n latest footsteps ending at step i (eq. 2) on axis 0 (x) or 1 (y).
  LinExpr CentreOfContactsSum(int i, int axis) const;
  // p_i: the variable defined by that mean for new steps, the mean itself otherwise.
  LinExpr CentreOfContacts(int i, int axis) const;
  LinExpr Yaw(int cfg) const;
  LinExpr Sin(int cfg) const;
  LinExpr Cos(int cfg) const;
  // Nominal foot of step i on axis 0 or 1. Start steps of a later window keep the yaw
  // they were planned with (FootstepProblem::start_step_yaw_rad).
  LinExpr NominalFoot(int i, int axis) const;
  // The constant yaw the nominal foot of start step i (0 <= i < n) is turned by: the yaw it
  // was planned with in a later window, else the start yaw [rad].
  double StartStepYaw(int i) const;

 private:
  const FootstepProblem& problem_;
  const FootstepVariables& vars_;
  int n_;
};

}  // namespace mfp
