#pragma once
// Safe regions (seed paper): a binary H_ir per new step i and region r, sum_r H_ir = 1,
// and H_ir => A_r f_i <= b_r. Two encodings:
//   big-M:        A_r f_i <= b_r + M_r (1 - H_ir), M_r as tight as the workspace box allows
//   convex hull:  f_i = sum_r f_ir, A_r f_ir <= b_r H_ir, box_lo H_ir <= f_ir <= box_hi H_ir
//                 (disaggregated copies: a tighter relaxation, more variables)
// A region no feasible plan can reach from the start stance (its box is farther from the
// leg's start foot than the leg's moves so far can carry it, or, given step boxes, it
// misses the step's box) gets no binary when pruning.
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "base/deadline.h"
#include "planner/formulation/internal/footstep_problem.h"
#include "planner/formulation/internal/step_expressions.h"
#include "planner/formulation/workspace_box.h"
#include "planner/miqp/miqp_builder.h"

namespace mfp {

struct RegionChoiceRows {
  // Per step: the rows [first, last) that encode its region choice (-1, -1 for start
  // steps and steps that reach no region).
  std::vector<std::pair<int, int>> rows;
  // Non-empty when some step can reach no region: the MIQP is infeasible by construction.
  std::string infeasible_reason;
  // The deadline expired (or its stop flag was set) before every step had its rows: the
  // builder holds only some of them.
  bool out_of_time = false;
};

// max_move_xy: MaxMovesXY (step_limits.h); step_boxes: empty, or per step a plan-view box
// that holds the step's foot in every feasible plan (FootprintStepBoxes). deadline is
// checked before each step's regions (a step of a large map writes rows for hundreds of them).
RegionChoiceRows AddRegionChoice(const StepExpressions& e, const FootstepProblem& problem,
                                 const FormulationOptions& options, const Box3& box,
                                 const std::vector<double>& max_move_xy,
                                 const std::vector<Eigen::AlignedBox2d>& step_boxes, int num_steps, MiqpBuilder* b,
                                 FootstepVariables* vars, const Deadline& deadline);

}  // namespace mfp
