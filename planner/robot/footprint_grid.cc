#include "planner/robot/internal/footprint_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "base/check.h"

namespace mfp {

FootprintGrid::FootprintGrid(const Eigen::Vector2d& min_m, const Eigen::Vector2d& max_m,
                             double cell_m, int margin_cells)
    : cell_m_(cell_m) {
  MFP_CHECK(margin_cells >= 1 && margin_cells < 1000);
  // The extent comes from a robot's description: sized only once it is known to be
  // finite and the grid bounded, never from an overflowed or NaN count.
  const Eigen::Vector2d span_cells = (max_m - min_m) / cell_m;
  if (!(cell_m > 0.0) || !min_m.allFinite() || !max_m.allFinite() || !span_cells.allFinite() ||
      !(span_cells.minCoeff() >= 0.0) ||
      (span_cells.x() + 1.0) * (span_cells.y() + 1.0) > static_cast<double>(kMaxFootprintGridCells)) {
    std::ostringstream msg;
    msg << "reachable footprint grid: x in [" << min_m.x() << ", " << max_m.x() << "] m, y in ["
        << min_m.y() << ", " << max_m.y() << "] m at cells of " << cell_m
        << " m is not a finite grid of at most " << kMaxFootprintGridCells
        << " cells: the robot's lengths are out of range";
    throw InputError(msg.str());
  }
  nx_ = static_cast<int>(std::ceil(span_cells.x())) + 1 + 2 * margin_cells;
  ny_ = static_cast<int>(std::ceil(span_cells.y())) + 1 + 2 * margin_cells;
  origin_m_ = min_m - Eigen::Vector2d::Constant(margin_cells * cell_m);
  cells_.assign(static_cast<size_t>(nx_) * ny_, 0);
}

void FootprintGrid::Set(int ix, int iy, bool occupied) {
  MFP_CHECK(InGrid(ix, iy));
  cells_[Index(ix, iy)] = occupied ? 1 : 0;
  boundary_stale_ = true;
}

bool FootprintGrid::CellOf(const Eigen::Vector2d& p, int* ix, int* iy) const {
  const Eigen::Vector2d u = (p - origin_m_) / cell_m_;
  *ix = static_cast<int>(std::floor(u.x() + 0.5));
  *iy = static_cast<int>(std::floor(u.y() + 0.5));
  return InGrid(*ix, *iy);
}

bool FootprintGrid::OccupiedAt(const Eigen::Vector2d& p) const {
  int ix = 0, iy = 0;
  return CellOf(p, &ix, &iy) && Occupied(ix, iy);
}

Eigen::Vector2d FootprintGrid::CellCentre(int ix, int iy) const {
  return origin_m_ + cell_m_ * Eigen::Vector2d(ix, iy);
}

int FootprintGrid::CountOccupied() const {
  return static_cast<int>(std::count(cells_.begin(), cells_.end(), 1));
}

void FootprintGrid::UpdateBoundary() {
  boundary_stale_ = false;
  boundary_centres_m_.clear();
  occupied_centres_m_.clear();
  for (int iy = 0; iy < ny_; ++iy) {
    for (int ix = 0; ix < nx_; ++ix) {
      if (Occupied(ix, iy)) {
        occupied_centres_m_.push_back(CellCentre(ix, iy));
        continue;
      }
      bool borders = false;
      for (int dy = -1; dy <= 1 && !borders; ++dy) {
        for (int dx = -1; dx <= 1 && !borders; ++dx) borders = Occupied(ix + dx, iy + dy);
      }
      if (borders) boundary_centres_m_.push_back(CellCentre(ix, iy));
    }
  }
}

namespace {

// The least `norm` of the per-axis gap from p to the box of each cell centred in
// `centres` (half-side half_m) [m]; infinity when there is none.
template <class Norm>
double NearestEmptyCellGap(const std::vector<Eigen::Vector2d>& centres, double half_m, const Eigen::Vector2d& p,
                           Norm norm) {
  double clearance = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& c : centres) {
    const Eigen::Vector2d gap = ((p - c).cwiseAbs().array() - half_m).cwiseMax(0.0);
    clearance = std::min(clearance, norm(gap));
  }
  return clearance;
}

}  // namespace

double FootprintGrid::Clearance(const Eigen::Vector2d& p) const {
  MFP_CHECK_MSG(!boundary_stale_, "FootprintGrid::UpdateBoundary() not called after Set()");
  const double half = 0.5 * cell_m_;
  if (!OccupiedAt(p)) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector2d& c : occupied_centres_m_) {
      nearest = std::min(nearest, (p - c).cwiseAbs().maxCoeff());
    }
    return occupied_centres_m_.empty() ? -1.0 : -nearest;
  }
  // Inside: the L-infinity distance from p to the nearest empty cell (a closed box).
  // The grid's outer ring is empty, so the boundary list bounds every square.
  return NearestEmptyCellGap(boundary_centres_m_, half, p, [](const Eigen::Vector2d& gap) { return gap.maxCoeff(); });
}

double FootprintGrid::DiskClearance(const Eigen::Vector2d& p) const {
  MFP_CHECK_MSG(!boundary_stale_, "FootprintGrid::UpdateBoundary() not called after Set()");
  if (!OccupiedAt(p)) return 0.0;
  // As Clearance, with the Euclidean distance from p to each bordering empty cell's box.
  return NearestEmptyCellGap(boundary_centres_m_, 0.5 * cell_m_, p, [](const Eigen::Vector2d& gap) { return gap.norm(); });
}

}  // namespace mfp
