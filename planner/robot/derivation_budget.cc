#include "planner/robot/derivation_budget.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace mfp {
namespace {

// Cells visited by the footprint flood fills: every stance candidate's grid and the
// final one, each with the grid's border and margin rings (about 7 cells across).
double GridCells(const DerivationOptions& options) {
  const double scan = options.scan_cells + 7.0, final = options.final_cells + 7.0;
  return options.stance_candidates * scan * scan + final * final;
}

}  // namespace

double DerivationWork(const RobotDescription& robot, const DerivationOptions& options) {
  double legs = 0.0;
  for (const LegChain& leg : robot.legs) legs += static_cast<double>(leg.num_dof()) * leg.num_dof();
  return legs * GridCells(options) / GridCells(DerivationOptions{});
}

DerivationOptions WithinDerivationBudget(DerivationOptions options, RobotDescription* robot) {
  const double work = DerivationWork(*robot, options);
  if (work <= kMaxDerivationWork) return options;
  const DerivationOptions full = options;
  // Shrink every count by the same factor, in 5 % steps, down to the floors.
  for (double scale = 0.95; scale > 0.0 && DerivationWork(*robot, options) > kMaxDerivationWork;
       scale -= 0.05) {
    options.final_cells = std::max(16, static_cast<int>(std::lround(full.final_cells * scale)));
    options.scan_cells = std::max(6, static_cast<int>(std::lround(full.scan_cells * scale)));
    options.stance_candidates = std::max(3, static_cast<int>(std::lround(full.stance_candidates * scale)));
  }
  std::ostringstream note;
  note << "derivation budget: " << robot->legs.size() << " legs, work " << std::lround(work)
       << " > " << kMaxDerivationWork << " (sum of joints^2 per leg at the default grids): "
       << "footprint grids of " << options.final_cells << " cells across (not " << full.final_cells
       << "), " << options.stance_candidates << " stance candidates on " << options.scan_cells
       << "-cell grids (not " << full.stance_candidates << " on " << full.scan_cells << ")";
  robot->notes.push_back(note.str());
  return options;
}

}  // namespace mfp
