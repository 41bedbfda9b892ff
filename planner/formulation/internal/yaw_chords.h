#pragma once
// Yaw of each configuration with piecewise-linear sin/cos (the seed paper's chord
// approximation). The yaw range [min(start, goal) - margin, max(start, goal) + margin] is
// cut into equal segments psi_0 < psi_1 < ... ; configuration b chooses one segment by a
// binary S_bk (sum_k S_bk = 1), and on segment k, s_b and c_b lie on the chords of sin and
// cos over [psi_k, psi_k+1]. Two encodings of "S_bk => on segment k's chords":
//   big-M:        psi_k - M(1 - S) <= theta <= psi_k+1 + M(1 - S), |s - m_k theta - q_k| <= M(1 - S)
//   convex hull:  theta = sum_k theta_k, psi_k S_k <= theta_k <= psi_k+1 S_k,
//                 s = sum_k (m_k theta_k + q_k S_k) (likewise c): the relaxation is the hull
//                 of the curves, so (s, c) cannot shrink towards the origin.
#include <utility>
#include <vector>

#include "planner/formulation/internal/footstep_problem.h"
#include "planner/formulation/internal/step_expressions.h"
#include "planner/miqp/miqp_builder.h"

namespace mfp {

// The chord of sin (sine = true) or cos over [a, e]: v(theta) = slope theta + intercept.
// One definition for both encodings and for the snapping check.
struct Chord {
  double slope, intercept;
  double At(double theta) const { return slope * theta + intercept; }
};
Chord ChordOf(bool sine, double a, double e);

// Largest distance between the chords' point (cos, sin) at a yaw of a segment of width
// width_rad and the circle's point at that yaw (a bound: a fine grid's largest plus what
// the grid can miss).
double ChordPointError(double width_rad);

// Largest segment width of breakpoints bp [rad] (0 for fewer than two).
double LargestSegment(const std::vector<double>& bp);

struct YawGrid {
  // Breakpoints of the uniform grid over the whole yaw range [rad] (segments + 1 values).
  std::vector<double> breakpoints;
  // Per configuration: the breakpoints of its own segments (those of the grid that meet
  // the yaw it can reach); empty for configuration 0, the start.
  std::vector<std::vector<double>> configuration_breakpoints;
  // Per configuration: [lowest, highest] yaw it can reach [rad].
  std::vector<std::pair<double, double>> reach;
};

// start_yaw and goal_yaw as unwrapped by the formulation (goal within pi of the start).
// With options.clip_yaw_to_reach, configuration b keeps only the segments within
// b max_yaw_change of the start: the chords stay those of the grid, so the plans are
// exactly those of the full grid.
YawGrid MakeYawGrid(double start_yaw_rad, double goal_yaw_rad, double max_yaw_change_rad, int num_configurations,
                    const FormulationOptions& options);

// Index of the segment of breakpoints bp that holds theta (the last one above the range).
int SegmentHolding(const std::vector<double>& bp, double theta);

// Variables theta_b, s_b, c_b of configurations 1 .. B-1, bounded by the yaw each can
// reach and the range of sin/cos over its segments.
void AddYawVariables(const YawGrid& grid, MiqpBuilder* b, FootstepVariables* vars);

// Configuration cfg's segment binaries, its one-segment row and its chord rows in the
// chosen encoding.
void AddYawChords(const StepExpressions& e, const YawGrid& grid, int cfg, YawEncoding encoding, MiqpBuilder* b,
                  FootstepVariables* vars);

}  // namespace mfp
