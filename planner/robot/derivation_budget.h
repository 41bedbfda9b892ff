#pragma once
// A bound on the work of DeriveRobot, applied before it starts. Nearly all of it is inverse
// kinematics over the footprint grids: one grid per leg at each stance candidate (of
// about scan_cells across) and one at the stance (final_cells across), each cell tried
// from up to four neighbours, each try up to 60 iterations whose cost grows with the
// leg's joints. A robot inside the reader's caps (16 legs of 12 joints) did 50 times the
// work of the octopod, tens of seconds, with no time limit reaching it: such a robot is
// derived on coarser grids and fewer stance candidates instead, and says so.
#include <string>

#include "planner/robot/internal/leg_kinematics.h"
#include "planner/robot/robot_derivation.h"

namespace mfp {

// Largest derivation work, in DerivationWork's units: 100 joint^2-weighted legs at the
// default grids (every robot of the repository and of the zoo: the octopod is 72, a
// 4-leg robot of 5 joints a leg 100); about a second of one core.
constexpr double kMaxDerivationWork = 100.0;

// sum over legs of dof^2 (the measured growth of the IK cost with the joints of a leg),
// times the grid cells of the derivation relative to the default options'.
double DerivationWork(const RobotDescription& robot, const DerivationOptions& options);

// `options` unchanged when DerivationWork fits kMaxDerivationWork; else with
// final_cells, scan_cells and stance_candidates scaled down together (to at least 16, 6
// and 3) until it fits or reaches those floors, and a note appended to robot->notes
// (it becomes a provenance line of the model) naming the work and the grids used.
DerivationOptions WithinDerivationBudget(DerivationOptions options, RobotDescription* robot);

}  // namespace mfp
