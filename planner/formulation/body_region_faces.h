#pragma once
// The body in the windows (issue 29). Each configuration b >= 1 puts the body's plan box
// (RobotModel::body, about the centre of contacts) in one of the problem's body regions
// (FootstepProblem::body_regions: convex, free of the body obstacles in the body's band),
// chosen by binaries G_br with sum_r G_br = 1: for each new step i of b, each corner k of
// the box and each face a . x <= b_f of region r,
//   G_br => a . (p_i + R(theta_b) k) <= b_f - margin - chord_error |k|
// The box is convex, so its four corners in the convex region put all of it there. In the
// MIQP R(theta) is made of the sin/cos chords, whose point lies at most chord_error from
// the circle's at the same yaw, so the true corners are in the region too; the polisher
// writes the same rows with the exact R (chord_error 0) for the region its MIQP point
// chose. What this keeps out and what it does not: docs/body_clearance.md.
#include <Eigen/Core>
#include <vector>

#include "planner/formulation/internal/footstep_problem.h"
#include "planner/formulation/step_encoder.h"
#include "planner/formulation/workspace_box.h"
#include "planner/miqp/miqp_builder.h"

namespace mfp {

// Whether the formulation writes body rows: the option on, body regions given, the body known.
bool UsesBodyRegions(const FootstepProblem& problem, const FormulationOptions& options);

// The body box's corners in the body frame, counter-clockwise [m].
std::vector<Eigen::Vector2d> BodyCornersBody(const BodyExtent& body);

// Region `region_index`'s rows for new step i under indicator G_br; box: the variables'
// box, over which each row's big-M is taken.
void AddBodyRegionFaces(StepEncoder& e, const BodyExtent& body, const FreeRegion2d& region, int region_index, int i,
                        int indicator, double chord_error, double margin_m, const Box3& box);

// The MIQP's binaries G_br (configurations 1 .. B-1, in order), their one-region rows and
// every step's rows. vars->body_region is sized B (empty lists without body regions).
void AddBodyRegionChoice(StepEncoder& e, const FootstepProblem& problem, const FormulationOptions& options,
                         double chord_error, const Box3& box, int num_steps, MiqpBuilder* b, FootstepVariables* vars);

// For rounding a relaxation: the body region (index) that holds configuration cfg's body
// boxes best at x (centres of contacts and yaw of x, exact rotation), the larger weight
// first among those that hold them; -1 without body regions.
int BodyRegionHolding(const FootstepProblem& problem, const FootstepVariables& vars, const Eigen::VectorXd& x, int cfg,
                      int num_steps);

}  // namespace mfp
