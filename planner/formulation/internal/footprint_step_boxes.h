#pragma once
// Where each new step's foot can be under the footprint reach (ReachShape::kFootprint), as
// plan-view boxes: region pruning for many-legged robots. A step's region binaries are
// the formulation's largest part, and MaxMovesXY's bound (a leg moves at most its
// polygon's diameter per step, about the leg's start foot) lets a window's later steps
// reach regions no plan can use. The rows bound them tighter: step i's foot lies in its
// leg's polygon about r_nom,i-n = p_i-n + R(theta) o, turned by configuration b(i-n)'s yaw
// (step_limits.h), and p_i-n is the mean of the n feet before it, so boxes follow step by
// step from the start stance's constants. Private to planner/formulation.
#include <vector>

#include <Eigen/Geometry>

#include "planner/formulation/internal/step_expressions.h"
#include "planner/miqp/miqp_builder.h"
#include "planner/robot/robot_model.h"

namespace mfp {

// Per step (index as the steps, empty boxes for the start steps): a box [world, m] that
// holds f_i in plan view in every point that satisfies step i's reachability rows and the
// bounds b holds for the yaw, sin and cos variables: the box of p_i-n (a constant for a
// start step, else the mean of its steps' boxes), plus the box of R(theta) o over the sin
// and cos bounds (interval arithmetic, sound for the chords), plus the box of the leg's
// polygon turned by the two ends of configuration b(i-n)'s yaw range (its rows hold the
// offset in the polygon at both). The robot's shape must be the footprint.
std::vector<Eigen::AlignedBox2d> FootprintStepBoxes(const StepExpressions& e, const MiqpBuilder& b,
                                                    const RobotModel& robot, int num_steps);

}  // namespace mfp
