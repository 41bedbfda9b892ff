#pragma once
// The seed paper's limits on one step i (leg l, configuration b(i)), about the nominal
// foot r_nom,i = p_i + R(theta_b(i)) o_l:
//   reference box   |f_i - r_nom,i|_inf   <= l_bnd   (x, y)
//   reachability    |f_i - r_nom,i-n|_inf <= d_lim   (x, y): from the previous configuration,
//                   and, for the octagon and the 16-gon (ReachShape), the other faces'
//                   rows |cos(phi) dx + sin(phi) dy| <= d_lim of that move
//   height change   |z_i - z_i-n|         <= dz_max
// written once through a StepEncoder: the MIQP's rows (chords) and the polisher's (exact
// sin/cos) alike, and evaluated by the plan validator.
#include <cmath>
#include <vector>

#include "planner/formulation/internal/step_expressions.h"
#include "planner/formulation/step_encoder.h"
#include "planner/miqp/miqp_builder.h"
#include "planner/robot/robot_model.h"

namespace mfp {

// Reference box, reachability and height change of new step i, in this order: ref x,
// reach x, ref y, reach y, (the polygon's other faces: the octagon's reach x+y, reach x-y), dz.
// For ReachShape::kFootprint: the leg's footprint polygon about r_nom,i (the reference
// rows) and about r_nom,i-n (the reachability rows), each at every yaw its configuration
// may take (StepEncoder::YawBounds; the yaws sampled at most kFootprintYawSpacing apart,
// the faces shrunk by the sagitta between samples), then dz.
void AddStepLimits(StepEncoder& e, const RobotModel& robot, int i);

// Largest spacing of the yaws at which the footprint polygon's rows are written [rad]: pi/8,
// the yaw grid's segment (the sagitta then costs 1.9 % of the farthest corner).
constexpr double kFootprintYawSpacing = M_PI / 8;

// Largest move in plan view (x or y) of each step, valid for every feasible plan: the
// reachability box about r_nom,i-n plus how far the previous foot can be from r_nom,i-n
// (l_bnd, or for a leg's first move how far its start foot is from its nominal foot); for
// the footprint shape, the leg's polygon's diameter, or for its first move the polygon's
// farthest corner plus that start offset.
// Indexed by step; 0 for start steps. Bounds big-M constants and region pruning.
std::vector<double> MaxMovesXY(const StepExpressions& e, const RobotModel& robot, int num_steps);

}  // namespace mfp
