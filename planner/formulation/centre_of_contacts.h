#pragma once
// Centre of contacts (seed paper eq. 2): p_i is the mean of the n latest footsteps ending
// at step i. One definition for the formulation (positions as LinExpr) and plan validation
// (positions as vectors).
#include "planner/formulation/internal/step_expressions.h"
#include "planner/formulation/workspace_box.h"
#include "planner/miqp/miqp_builder.h"

namespace mfp {

// position(j) for j = i - n + 1 .. i, summed in step order, times 1 / n.
template <class T, class Position>
T CentreOfContacts(int i, int n, const Position& position) {
  T sum = position(i - n + 1);
  for (int j = i - n + 2; j <= i; ++j) sum += position(j);
  return (1.0 / n) * sum;
}

// Footstep variables f_i = (x_i, y_i, z_i) of the new steps, bounded by the workspace box.
void AddFootstepPositions(const Box3& box, int num_steps, int n, MiqpBuilder* b, FootstepVariables* vars);

// For new steps p_i is a variable defined by an equality row, p_i = mean of the n latest
// footsteps: every constraint and cost that uses p_i then touches 1 column instead of n,
// which keeps the KKT systems of the relaxations sparse.
void AddCentreOfContacts(const StepExpressions& e, const Box3& box, int num_steps, MiqpBuilder* b,
                         FootstepVariables* vars);

}  // namespace mfp
