#pragma once
// The largest axis-aligned square inside a reachable footprint: the paper's "polygon
// inscribed in the biggest circle in the workspace". The maximisation runs in NLopt
// (this file's .cc is the only one that includes it); callers see plain Eigen types.
#include <Eigen/Core>

#include "planner/robot/internal/footprint_grid.h"

namespace mfp {

struct InscribedSquare {
  Eigen::Vector2d centre_m = Eigen::Vector2d::Zero();
  double half_side_m = 0.0;  // 0 when the centre is not in the footprint
};

// Maximises clearance(c) - centre_weight_per_m * |c - preferred_centre_m|^2 over centres c.
// The small weight only breaks ties between equally large squares (a footprint longer
// than wide has a whole segment of best centres) in favour of the preferred centre, so
// that mirror-image legs get mirror-image nominal feet. The grid must have had
// UpdateBoundary() called. Starts from the best cell centre, then refines below the cell
// size with NLopt's derivative-free COBYLA.
InscribedSquare LargestInscribedSquare(const FootprintGrid& grid,
                                       const Eigen::Vector2d& preferred_centre_m,
                                       double centre_weight_per_m);

}  // namespace mfp
