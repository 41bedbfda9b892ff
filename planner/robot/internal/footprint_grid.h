#pragma once
// The reachable footprint of one foot at one height, as a 2-D occupancy grid in the body
// frame, and the exact clearance of a point in it: the half-side of the largest square
// centred there whose interior meets no unreachable cell. Plain Eigen, no I/O.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace mfp {

// Largest footprint grid [cells]; the derivation uses about 100 x 100.
constexpr int kMaxFootprintGridCells = 1 << 22;

class FootprintGrid {
 public:
  FootprintGrid() = default;
  // A grid covering [min_m, max_m] plus a ring of `margin_cells` empty cells on each side.
  // Throws InputError when the bounds or the cell are not finite, the bounds are inverted,
  // or the grid would exceed kMaxFootprintGridCells.
  FootprintGrid(const Eigen::Vector2d& min_m, const Eigen::Vector2d& max_m, double cell_m,
                int margin_cells = 2);

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  double cell_m() const { return cell_m_; }
  bool InGrid(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < nx_ && iy < ny_; }
  bool Occupied(int ix, int iy) const { return InGrid(ix, iy) && cells_[Index(ix, iy)] != 0; }
  void Set(int ix, int iy, bool occupied);
  // Cell containing p; false when p is outside the grid.
  bool CellOf(const Eigen::Vector2d& p, int* ix, int* iy) const;
  bool OccupiedAt(const Eigen::Vector2d& p) const;
  Eigen::Vector2d CellCentre(int ix, int iy) const;
  int CountOccupied() const;

  // L-infinity clearance of p [m]: the largest s such that the open square of half-side s
  // centred at p meets no empty cell (cells outside the grid count as empty). Negative
  // (minus the distance to the nearest occupied cell centre) when p is in an empty cell,
  // so that the function is continuous enough for a derivative-free optimiser.
  double Clearance(const Eigen::Vector2d& p) const;

  // Euclidean clearance of p [m]: the radius of the largest open disk centred at p that
  // meets no empty cell (cells outside the grid count as empty); 0 when p is in an empty
  // cell. The disk a reach polygon must stay inside to hold at every body yaw.
  double DiskClearance(const Eigen::Vector2d& p) const;

  // Recomputes the list of empty cells bordering occupied ones; call after edits and
  // before Clearance. (Only those cells can be the nearest empty cell to a point inside.)
  void UpdateBoundary();

 private:
  int Index(int ix, int iy) const { return iy * nx_ + ix; }

  Eigen::Vector2d origin_m_ = Eigen::Vector2d::Zero();  // centre of cell (0, 0)
  double cell_m_ = 1.0;
  int nx_ = 0;
  int ny_ = 0;
  std::vector<std::uint8_t> cells_;
  std::vector<Eigen::Vector2d> boundary_centres_m_;  // empty cells next to occupied ones
  std::vector<Eigen::Vector2d> occupied_centres_m_;
  bool boundary_stale_ = true;  // Set() since the last UpdateBoundary()
};

}  // namespace mfp
