#include "planner/robot/internal/inscribed_square.h"

#include <nlopt.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "base/check.h"

namespace mfp {
namespace {

struct Objective {
  const FootprintGrid* grid;
  Eigen::Vector2d preferred;
  double weight;
  double operator()(const Eigen::Vector2d& c) const {
    return grid->Clearance(c) - weight * (c - preferred).squaredNorm();
  }
};

double NloptObjective(const std::vector<double>& x, std::vector<double>& /*grad*/, void* data) {
  const Objective& objective = *static_cast<const Objective*>(data);
  return objective(Eigen::Vector2d(x[0], x[1]));
}

}  // namespace

InscribedSquare LargestInscribedSquare(const FootprintGrid& grid,
                                       const Eigen::Vector2d& preferred_centre_m,
                                       double centre_weight_per_m) {
  MFP_CHECK(centre_weight_per_m >= 0.0);
  const Objective objective{&grid, preferred_centre_m, centre_weight_per_m};
  // Coarse start: the best occupied cell centre (clearance is exact there).
  InscribedSquare best;
  double best_value = -std::numeric_limits<double>::infinity();
  for (int iy = 0; iy < grid.ny(); ++iy) {
    for (int ix = 0; ix < grid.nx(); ++ix) {
      if (!grid.Occupied(ix, iy)) continue;
      const Eigen::Vector2d c = grid.CellCentre(ix, iy);
      const double value = objective(c);
      if (value > best_value) {
        best_value = value;
        best.centre_m = c;
      }
    }
  }
  if (!std::isfinite(best_value)) return best;  // empty footprint

  // Refine within one cell of the start: the clearance is piecewise linear in the centre,
  // so a sub-cell shift can gain up to half a cell on each side.
  const double h = grid.cell_m();
  nlopt::opt opt(nlopt::LN_COBYLA, 2);
  opt.set_max_objective(NloptObjective, const_cast<Objective*>(&objective));
  opt.set_lower_bounds({best.centre_m.x() - h, best.centre_m.y() - h});
  opt.set_upper_bounds({best.centre_m.x() + h, best.centre_m.y() + h});
  opt.set_initial_step(0.25 * h);
  opt.set_xtol_abs(1e-4 * h);
  opt.set_maxeval(400);
  std::vector<double> x = {best.centre_m.x(), best.centre_m.y()};
  double value = best_value;
  try {
    opt.optimize(x, value);
  } catch (const std::exception&) {
    // NLopt throws on roundoff-limited stops; x then holds its best point, checked below.
    value = objective(Eigen::Vector2d(x[0], x[1]));
  }
  const Eigen::Vector2d refined(x[0], x[1]);
  if (std::isfinite(value) && objective(refined) > best_value) best.centre_m = refined;
  best.half_side_m = std::max(0.0, grid.Clearance(best.centre_m));
  return best;
}

}  // namespace mfp
