#include "terrain/extraction/internal/surface_layers.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <iterator>
#include <limits>
#include <memory>
#include <optional>
#include <utility>

#include "base/check.h"
#include "base/round.h"
#include "terrain/extraction/internal/parallel_work.h"
#include "terrain/extraction/leaf_budget.h"

namespace mfp {
namespace {

struct Interval {
  long long lo = 0, hi = 0;  // voxel indices [lo, hi) along z
};

// Per-column interval lists in compressed rows: column c owns [offset[c], offset[c + 1]).
struct Columns {
  std::vector<size_t> offset;
  std::vector<Interval> runs;
  const Interval* begin(int c) const { return runs.data() + offset[c]; }
  const Interval* end(int c) const { return runs.data() + offset[c + 1]; }
};

// A leaf's cell range on the grid: columns [c0, c0 + n) x rows [r0, r0 + n), voxels
// [z0, z0 + n) along z.
struct Footprint {
  long long z0;
  int c0, r0, n;
};

// Calls emit(footprint) for the leaves that overlap the grid and the voxels [z_lo, z_hi]
// along z (the others add no run that is asked), in order. free_cells (optional) gets
// every leaf's FreeLeafColumnCells inside the grid (the occupied extent) added, in order.
template <typename Emit>
void ForEachFootprint(const OccupiedLeaf* begin, const OccupiedLeaf* end, const HeightMap& hm, long long z_lo,
                      long long z_hi, double* free_cells, Emit&& emit) {
  const double res = hm.resolution_m;
  const long long x_lo = RoundToLongLong(hm.origin_world_m.x() / res);
  const long long y_lo = RoundToLongLong(hm.origin_world_m.y() / res);
  double cells = 0.0;  // the leaves' FreeLeafColumnCells so far (whole numbers, exact below 2^53 in any order)
  for (const OccupiedLeaf* it = begin; it != end; ++it) {
    const OccupiedLeaf& leaf = *it;
    const double n_d = leaf.size_m / res;
    if (!leaf.center_world_m.allFinite() || !std::isfinite(n_d) || n_d < 0.5) continue;  // the budget skips it too
    const double x_d = (leaf.center_world_m.x() - 0.5 * leaf.size_m) / res;
    const double y_d = (leaf.center_world_m.y() - 0.5 * leaf.size_m) / res;
    const long long n = n_d <= 65536.5 ? RoundToLongLong(n_d) : 0, x = RoundToLongLong(x_d), y = RoundToLongLong(y_d);
    bool on_grid = false;  // known to overlap the grid (the test below then passes)
    if (free_cells != nullptr) {
      // FreeLeafColumnCells from the rounded corner and width: the same whole numbers
      // (exact below 2^52); beyond, its own arithmetic.
      constexpr double kExact = 4503599627370496.0;  // 2^52
      if (n_d <= 65536.5 && std::abs(x_d) < kExact && std::abs(y_d) < kExact) {
        const long long dx = std::min(x + n, x_lo + hm.cols) - std::max(x, x_lo);
        const long long dy = std::min(y + n, y_lo + hm.rows) - std::max(y, y_lo);
        // With n >= 1 and a grid of at least one cell, dx > 0 and dy > 0 say the leaf
        // overlaps the grid: the test below on c0, r0 and n.
        if (dx <= 0 || dy <= 0) continue;
        cells += static_cast<double>(dx) * static_cast<double>(dy);
        on_grid = true;
      } else {
        const double x0 = static_cast<double>(x_lo), y0 = static_cast<double>(y_lo);
        cells += FreeLeafColumnCells(leaf, res, x0, y0, x0 + hm.cols, y0 + hm.rows);
      }
    }
    if (n_d > 65536.5) continue;
    const long long z0 = RoundToLongLong((leaf.center_world_m.z() - 0.5 * leaf.size_m) / res);
    if (z0 > z_hi || z0 + n <= z_lo) continue;
    const long long c0 = x - x_lo, r0 = y - y_lo;
    if (!on_grid && (c0 >= hm.cols || r0 >= hm.rows || c0 + n <= 0 || r0 + n <= 0)) continue;
    emit(Footprint{z0, static_cast<int>(c0), static_cast<int>(r0), static_cast<int>(n)});
  }
  if (free_cells != nullptr) *free_cells += cells;
}

// ForEachFootprint's footprints, in order.
std::vector<Footprint> FootprintsOf(const OccupiedLeaf* begin, const OccupiedLeaf* end, const HeightMap& hm,
                                    long long z_lo = std::numeric_limits<long long>::min(),
                                    long long z_hi = std::numeric_limits<long long>::max(),
                                    double* free_cells = nullptr) {
  std::vector<Footprint> prints;
  prints.reserve(static_cast<size_t>(end - begin));
  ForEachFootprint(begin, end, hm, z_lo, z_hi, free_cells, [&](const Footprint& f) { prints.push_back(f); });
  return prints;
}

// Sorts a column's runs by their lower end: insertion sort, as most columns hold a few.
void SortRuns(Interval* b, Interval* e) {
  if (e - b > 24) {
    std::sort(b, e, [](const Interval& p, const Interval& q) { return p.lo < q.lo; });
    return;
  }
  for (Interval* it = b + 1; it < e; ++it) {
    const Interval v = *it;
    Interval* j = it;
    for (; j > b && (j - 1)->lo > v.lo; --j) *j = *(j - 1);
    *j = v;
  }
}

// Footprints cut into per-column intervals, each column's in the order of prints.
Columns UnsortedColumnsOf(const std::vector<Footprint>& prints, const HeightMap& hm) {
  const int cells = hm.rows * hm.cols;
  // Per column its run count at offset[c + 1], then the running sum: the column's start.
  Columns cols;
  cols.offset.assign(static_cast<size_t>(cells) + 1, 0);
  for (const Footprint& f : prints) {
    for (int r = std::max(0, f.r0); r < std::min(hm.rows, f.r0 + f.n); ++r) {
      for (int c = std::max(0, f.c0); c < std::min(hm.cols, f.c0 + f.n); ++c) {
        ++cols.offset[static_cast<size_t>(r) * hm.cols + c + 1];
      }
    }
  }
  for (int c = 0; c < cells; ++c) cols.offset[c + 1] += cols.offset[c];
  cols.runs.resize(cols.offset[cells]);
  // Each column filled from its end down: offset[c + 1] ends at column c's start.
  for (const Footprint& f : prints) {
    for (int r = std::max(0, f.r0); r < std::min(hm.rows, f.r0 + f.n); ++r) {
      for (int c = std::max(0, f.c0); c < std::min(hm.cols, f.c0 + f.n); ++c) {
        cols.runs[--cols.offset[static_cast<size_t>(r) * hm.cols + c + 1]] = {f.z0, f.z0 + f.n};
      }
    }
  }
  std::copy(cols.offset.begin() + 1, cols.offset.end(), cols.offset.begin());
  cols.offset[cells] = cols.runs.size();
  return cols;
}

// Footprints cut into per-column intervals, sorted and merged (touching runs join).
Columns ColumnsOf(const std::vector<Footprint>& prints, const HeightMap& hm) {
  const int cells = hm.rows * hm.cols;
  Columns cols = UnsortedColumnsOf(prints, hm);
  // Sort and merge each column in place, compacting as it goes (a column's new start is
  // never after its old one).
  size_t out = 0;
  for (int c = 0; c < cells; ++c) {
    Interval* b = cols.runs.data() + cols.offset[c];
    Interval* e = cols.runs.data() + cols.offset[c + 1];
    SortRuns(b, e);
    cols.offset[c] = out;
    for (Interval* it = b; it != e; ++it) {
      if (out > cols.offset[c] && it->lo <= cols.runs[out - 1].hi) {
        cols.runs[out - 1].hi = std::max(cols.runs[out - 1].hi, it->hi);
      } else {
        cols.runs[out++] = *it;
      }
    }
  }
  cols.offset[cells] = out;
  cols.runs.resize(out);
  return cols;
}

// The voxel a surface at height `level` [m] has on top (SurfaceLayers::unseen's rounding).
long long TopVoxelOf(float level, double res) { return RoundToLongLong(level / res) - 1; }

// Known free space as far as the extraction asks it: ColumnHas of one voxel in a column at
// a surface candidate's top t (the voxel above an occupied run) or at TopVoxelOf its height
// or the voxel under that. Layer heights are candidate heights and every run's top is a
// leaf's, so every voxel asked lies between those of the lowest and the highest occupied
// leaf top; free leaves wholly outside are left out. Returns false when no voxel is asked.
bool FreeVoxelsAsked(const std::vector<Footprint>& occupied, double res, long long* z_lo, long long* z_hi) {
  if (occupied.empty()) return false;
  long long top_lo = std::numeric_limits<long long>::max(), top_hi = std::numeric_limits<long long>::min();
  for (const Footprint& f : occupied) {
    top_lo = std::min(top_lo, f.z0 + f.n);
    top_hi = std::max(top_hi, f.z0 + f.n);
  }
  // TopVoxelOf(float(t * res)) is monotone in t, so its extremes are those of the extreme tops.
  *z_lo = std::min(top_lo, TopVoxelOf(static_cast<float>(top_lo * res), res) - 1);
  *z_hi = std::max(top_hi, TopVoxelOf(static_cast<float>(top_hi * res), res));
  return true;
}

// UnsortedColumnsOf of the prints of every part in order, the grid's rows in `bands` bands
// on the threads: each band counts and then fills only its own columns, in the prints'
// order, so every column's runs are those (and in the order) UnsortedColumnsOf gives.
Columns UnsortedColumnsInBands(const std::vector<std::vector<Footprint>>& parts, const HeightMap& hm, int bands,
                               int threads) {
  const size_t cells = static_cast<size_t>(hm.rows) * hm.cols;
  Columns cols;
  cols.offset.assign(cells + 1, 0);
  std::vector<size_t> band_runs(static_cast<size_t>(bands), 0);
  auto rows_of = [&](int b) { return std::make_pair(hm.rows * b / bands, hm.rows * (b + 1) / bands); };
  // Calls add(index past the column's slot) for every cell of a print in rows [r0, r1).
  auto for_cells = [&](int r0, int r1, auto&& add) {
    for (const std::vector<Footprint>& prints : parts) {
      for (const Footprint& f : prints) {
        const int fr0 = std::max(r0, f.r0), fr1 = std::min(r1, f.r0 + f.n);
        const int c0 = std::max(0, f.c0), c1 = std::min(hm.cols, f.c0 + f.n);
        for (int r = fr0; r < fr1; ++r) {
          for (int c = c0; c < c1; ++c) add(static_cast<size_t>(r) * hm.cols + c + 1, f);
        }
      }
    }
  };
  // Per column its run count at offset[c + 1], then the running sum within the band.
  ParallelFor(bands, threads, [&](int b) {
    const auto [r0, r1] = rows_of(b);
    for_cells(r0, r1, [&](size_t i, const Footprint&) { ++cols.offset[i]; });
    const size_t a = static_cast<size_t>(r0) * hm.cols, e = static_cast<size_t>(r1) * hm.cols;
    for (size_t i = a + 1; i < e; ++i) cols.offset[i + 1] += cols.offset[i];
    band_runs[static_cast<size_t>(b)] = e > a ? cols.offset[e] : 0;
  });
  std::vector<size_t> band_start(static_cast<size_t>(bands), 0);
  for (int b = 1; b < bands; ++b) band_start[b] = band_start[b - 1] + band_runs[b - 1];
  cols.runs.resize(band_start.back() + band_runs.back());
  // Each column filled from its end down: offset[c + 1] ends at column c's start.
  ParallelFor(bands, threads, [&](int b) {
    const auto [r0, r1] = rows_of(b);
    const size_t a = static_cast<size_t>(r0) * hm.cols, e = static_cast<size_t>(r1) * hm.cols;
    for (size_t i = a + 1; i <= e; ++i) cols.offset[i] += band_start[static_cast<size_t>(b)];
    for_cells(r0, r1, [&](size_t i, const Footprint& f) { cols.runs[--cols.offset[i]] = {f.z0, f.z0 + f.n}; });
  });
  std::copy(cols.offset.begin() + 1, cols.offset.end(), cols.offset.begin());
  cols.offset[cells] = cols.runs.size();
  return cols;
}

bool ColumnHas(const Columns& cols, int c, long long z_lo, long long z_hi) {
  for (const Interval* it = cols.begin(c); it != cols.end(c); ++it) {
    if (it->lo < z_hi && it->hi > z_lo) return true;
  }
  return false;
}

// The known free voxels the extraction asks about (FreeVoxelsAsked's band [z_lo, z_hi]),
// one of two ways: a bit per voxel of the band in every column, set straight from the
// leaves (no footprints kept, no counting or sorting, one test a voxel), or, when those
// bits would take more memory than the footprints and runs may, the free columns' runs.
// The bits are set by several threads at once (an atomic OR: the same bits in any order).
struct FreeSpace {
  long long z0 = 0;  // the voxel of each column's first bit
  size_t words = 0;  // 64-bit words per column; 0: runs
  std::unique_ptr<uint64_t[]> bits;  // words per column, column after column
  Columns runs;
  // Every column's words, zero, in `threads` parts at once.
  void ZeroBits(size_t columns, int threads) {
    const size_t n = columns * words;
    bits.reset(new uint64_t[n]);
    const int parts = std::max(1, threads);
    ParallelFor(parts, threads, [&](int p) {
      const size_t k = static_cast<size_t>(p), m = static_cast<size_t>(parts);
      std::fill(bits.get() + n * k / m, bits.get() + n * (k + 1) / m, uint64_t{0});
    });
  }
  // Whether voxel z of column col is known free; z in the band.
  bool Has(int col, long long z) const {
    if (words == 0) return ColumnHas(runs, col, z, z + 1);
    const long long d = z - z0;
    if (d < 0 || d >= static_cast<long long>(words) * 64) return false;
    const auto word = static_cast<size_t>(col) * words + static_cast<size_t>(d >> 6);
    return (bits[word] >> (d & 63)) & 1u;
  }
  // An OR other threads may make at the same time (the bits are read once all are made).
  static void Or(uint64_t* word, uint64_t mask) { __atomic_fetch_or(word, mask, __ATOMIC_RELAXED); }
  // Sets the bits of a leaf's footprint on the grid, its voxels clipped to the bits' span
  // (a leaf one voxel wide: on the grid and in the band, as ForEachFootprint gives it).
  void Set(const Footprint& f, const HeightMap& hm) {
    if (f.n == 1) {  // most leaves: on the grid and in the band
      const long long a = f.z0 - z0;
      Or(&bits[(static_cast<size_t>(f.r0) * hm.cols + f.c0) * words + static_cast<size_t>(a >> 6)], uint64_t{1} << (a & 63));
      return;
    }
    const int r0 = std::max(0, f.r0), r1 = std::min(hm.rows, f.r0 + f.n);
    const int c0 = std::max(0, f.c0), c1 = std::min(hm.cols, f.c0 + f.n);
    const long long a = std::max(f.z0, z0) - z0, e = std::min(f.z0 + f.n - z0, static_cast<long long>(words) * 64);
    for (long long w = a >> 6; a < e && w <= (e - 1) >> 6; ++w) {
      const long long lo = std::max(a, w * 64) - w * 64, hi = std::min(e, w * 64 + 64) - w * 64;
      const uint64_t mask = (hi - lo == 64 ? ~uint64_t{0} : ((uint64_t{1} << (hi - lo)) - 1)) << lo;
      for (int r = r0; r < r1; ++r) {
        for (int c = c0; c < c1; ++c) {
          Or(&bits[(static_cast<size_t>(r) * hm.cols + c) * words + static_cast<size_t>(w)], mask);
        }
      }
    }
  }
};

// 64-bit words a column's bits of the band [z_lo, z_hi] take.
uint64_t BandWords(long long z_lo, long long z_hi) { return (static_cast<uint64_t>(z_hi - z_lo) + 64) / 64; }

}  // namespace

namespace {

// The columns [lo, hi) of a row that hold its surface cells (lo == hi: none).
struct RowSpan {
  int lo = 0, hi = 0;
};

// The cells of rows [r0, r1) with a surface in their 3 x 3 neighbourhood (itself
// included), in row order, appended to near: the only cells the noise repair and the
// unseen bits can change, as both look at neighbours only. spans (optional) gets the
// RowSpan of each of the rows [r0, r1) at spans[r - r0].
void NearCellsInRows(const HeightMap& hm, int r0, int r1, std::vector<int>* near, RowSpan* spans = nullptr) {
  // Per row from r0 - 1 to r1 (clipped), which columns hold a surface and their span.
  const int first = std::max(0, r0 - 1), last = std::min(hm.rows - 1, r1);
  if (first > last) return;
  std::vector<uint8_t> has(static_cast<size_t>(last - first + 1) * hm.cols, 0);
  std::vector<RowSpan> span(static_cast<size_t>(last - first + 1));
  for (int r = first; r <= last; ++r) {
    const float* h = &hm.height_m[static_cast<size_t>(r) * hm.cols];
    uint8_t* out = &has[static_cast<size_t>(r - first) * hm.cols];
    uint8_t any = 0;
    for (int c = 0; c < hm.cols; ++c) any |= out[c] = !std::isnan(h[c]);
    if (!any) continue;  // RowSpan{}: none
    const auto lo = static_cast<int>(std::find(out, out + hm.cols, uint8_t{1}) - out);
    int hi = hm.cols;
    while (!out[hi - 1]) --hi;
    span[static_cast<size_t>(r - first)] = RowSpan{lo, hi};
  }
  if (spans != nullptr) {
    for (int r = r0; r < r1; ++r) spans[r - r0] = span[static_cast<size_t>(r - first)];
  }
  std::vector<uint8_t> column(static_cast<size_t>(hm.cols));  // a surface in the column within a row
  for (int r = r0; r < r1; ++r) {
    // The columns [lo, hi) of the rows r - 1 to r + 1 that hold a surface: the near cells
    // lie in [lo - 1, hi + 1).
    int lo = hm.cols, hi = 0;
    for (int rr = std::max(first, r - 1); rr <= std::min(last, r + 1); ++rr) {
      const RowSpan& sp = span[static_cast<size_t>(rr - first)];
      if (sp.lo == sp.hi) continue;
      lo = std::min(lo, sp.lo);
      hi = std::max(hi, sp.hi);
    }
    if (lo >= hi) continue;
    std::fill(column.begin() + lo, column.begin() + hi, 0);
    for (int rr = std::max(first, r - 1); rr <= std::min(last, r + 1); ++rr) {
      const uint8_t* in = &has[static_cast<size_t>(rr - first) * hm.cols];
      for (int c = lo; c < hi; ++c) column[static_cast<size_t>(c)] |= in[c];
    }
    for (int c = std::max(0, lo - 1); c < std::min(hm.cols, hi + 1); ++c) {
      const bool left = c - 1 >= lo && column[static_cast<size_t>(c) - 1], right = c + 1 < hi && column[static_cast<size_t>(c) + 1];
      if (left || (c >= lo && c < hi && column[static_cast<size_t>(c)]) || right) near->push_back(hm.Index(r, c));
    }
  }
}

// Whether FillSingleCellNoise may change the cell whose height is `centre` (NaN: empty)
// given its 8 neighbours: an empty cell needs all 8 present; a surface cell needs 7 and a
// neighbour one voxel off it (the most common neighbour height is one of them). A cheap
// necessary condition: most cells of a floor fail it after 8 reads.
bool MayRepair(float centre, const float neighbours[8], double res) {
  int present = 0;
  bool voxel_off = false;
  for (int k = 0; k < 8; ++k) {
    if (std::isnan(neighbours[k])) continue;
    ++present;
    voxel_off = voxel_off || std::abs(std::abs(centre - neighbours[k]) - res) < 0.01 * res;
  }
  return std::isnan(centre) ? present == 8 : present >= 7 && voxel_off;
}

// The repairs of FillSingleCellNoise at the cells [begin, end) of NearCellsInRows (which no
// repair changes: a filled cell's 8 neighbours are surface cells already), each cell
// judged on the heights as they are: (cell, new height) appended in order to repairs.
void CollectRepairs(const HeightMap& hm, const std::vector<uint8_t>* unseen, const int* begin, const int* end,
                    std::vector<std::pair<int, float>>* repairs) {
  const double res = hm.resolution_m;
  for (const int* it = begin; it != end; ++it) {
    const int i = *it;
    const int r = i / hm.cols, c = i % hm.cols;
    if (r < 1 || r + 1 >= hm.rows || c < 1 || c + 1 >= hm.cols) continue;
    float around[8];
    for (int k = 0, j = 0; k < 9; ++k) {
      if (k != 4) around[j++] = hm.height_m[static_cast<size_t>(hm.Index(r + k / 3 - 1, c + k % 3 - 1))];
    }
    const float h = hm.height_m[static_cast<size_t>(i)];
    if (!MayRepair(h, around, res)) continue;
    // The most common neighbour height (the first of the most common, in row order) and
    // how many of the 8 have it.
    float h0 = std::numeric_limits<float>::quiet_NaN();
    int best = 0, present = 0;
    for (int k = 0; k < 8; ++k) {
      const float g = around[k];
      if (std::isnan(g)) continue;
      ++present;
      // A height equal to an earlier one has its count, which cannot beat the best.
      if (std::find(around, around + k, g) != around + k) continue;
      int same = 0;
      for (int j = 0; j < 8; ++j) same += !std::isnan(around[j]) && std::abs(around[j] - g) < 0.01 * res;
      if (same > best) {
        best = same;
        h0 = g;
      }
    }
    if (std::isnan(h)) {
      const bool may_fill = unseen == nullptr || ((*unseen)[static_cast<size_t>(i)] & kEmptyColumn);
      if (best == 8 && may_fill) repairs->emplace_back(i, h0);  // a one-cell hole in a level surface
    } else if (best >= 7 && present >= 7 && std::abs(std::abs(h - h0) - res) < 0.01 * res) {
      repairs->emplace_back(i, h0);  // one voxel off a level neighbourhood
    }
  }
}

// The cells within one cell (8-neighbours and itself) of the changed cells, ascending.
std::vector<int> CellsAround(const HeightMap& hm, const std::vector<std::pair<int, float>>& changes) {
  std::vector<int> cells;
  cells.reserve(9 * changes.size());
  for (const auto& change : changes) {
    const int r = change.first / hm.cols, c = change.first % hm.cols;
    for (int dr = -1; dr <= 1; ++dr) {
      for (int dc = -1; dc <= 1; ++dc) {
        if (hm.Inside(r + dr, c + dc)) cells.push_back(hm.Index(r + dr, c + dc));
      }
    }
  }
  std::sort(cells.begin(), cells.end());
  cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
  return cells;
}

// Applies repairs in order. `before` (optional) gets each changed cell with its old height.
void ApplyRepairs(const std::vector<std::pair<int, float>>& repairs, HeightMap* hm, std::vector<int>* changed_cells,
                  std::vector<std::pair<int, float>>* before = nullptr) {
  for (const auto& [cell, height] : repairs) {
    if (before != nullptr) before->emplace_back(cell, hm->height_m[static_cast<size_t>(cell)]);
    hm->height_m[static_cast<size_t>(cell)] = height;
    if (changed_cells != nullptr) changed_cells->push_back(cell);
  }
}

}  // namespace

int FillSingleCellNoise(HeightMap* hm, const std::vector<uint8_t>* unseen, std::vector<int>* changed_cells) {
  std::vector<int> near;
  NearCellsInRows(*hm, 0, hm->rows, &near);
  std::vector<std::pair<int, float>> repairs;
  CollectRepairs(*hm, unseen, near.data(), near.data() + near.size(), &repairs);
  ApplyRepairs(repairs, hm, changed_cells);
  return static_cast<int>(repairs.size());
}
namespace {

// Isolated single voxels: no occupied voxel in the 26-neighbourhood. One flag per run of
// occ; counted in *isolated. Bands of rows on `threads` threads (each flag is its run's).
std::vector<uint8_t> IsolatedVoxels(const HeightMap& grid, const Columns& occ, int threads, int* isolated) {
  std::vector<uint8_t> dropped(occ.runs.size(), 0);
  const int band_rows = BandRows(grid.cols), bands = (grid.rows + band_rows - 1) / band_rows;
  std::vector<int> band_isolated(static_cast<size_t>(bands), 0);
  ParallelFor(bands, threads, [&](int b) {
    for (int r = b * band_rows; r < std::min(grid.rows, (b + 1) * band_rows); ++r) {
      for (int c = 0; c < grid.cols; ++c) {
        const int col = grid.Index(r, c);
        for (size_t i = occ.offset[col]; i < occ.offset[col + 1]; ++i) {
          const Interval& run = occ.runs[i];
          if (run.hi - run.lo != 1) continue;
          bool alone = true;
          for (int dr = -1; dr <= 1 && alone; ++dr) {
            for (int dc = -1; dc <= 1 && alone; ++dc) {
              if ((dr == 0 && dc == 0) || !grid.Inside(r + dr, c + dc)) continue;
              alone = !ColumnHas(occ, grid.Index(r + dr, c + dc), run.lo - 1, run.hi + 1);
            }
          }
          if (alone) {
            dropped[i] = 1;
            ++band_isolated[static_cast<size_t>(b)];
          }
        }
      }
    }
  });
  for (int n : band_isolated) *isolated += n;
  return dropped;
}

// Candidate surfaces per column, in compressed rows: column c owns [offset[c],
// offset[c + 1]) of height and col.
struct Candidates {
  std::vector<size_t> offset;
  std::vector<float> height;  // [m]
  std::vector<int> col;       // the column of each candidate
};

// The tops of the runs of columns [begin, end) with room above them (and, with free space
// known, seen from above), appended to heights; each column's first entry (relative to
// heights' start) at offset[col]; the runs passed over counted in *no_room, *unseen.
void CandidatesOfColumns(const Columns& occ, const FreeSpace* free, const std::vector<uint8_t>& dropped,
                         double clearance_voxels, double res, int begin, int end, size_t* offset,
                         std::vector<float>* heights, int* no_room, int* unseen) {
  for (int col = begin; col < end; ++col) {
    offset[col] = heights->size();
    const size_t b = occ.offset[col], e = occ.offset[col + 1];
    for (size_t i = b; i < e; ++i) {
      if (dropped[i]) continue;
      const long long top = occ.runs[i].hi;
      size_t next = i + 1;
      while (next < e && dropped[next]) ++next;
      if (next < e && static_cast<double>(occ.runs[next].lo - top) < clearance_voxels - 1e-6) {
        ++*no_room;
        continue;
      }
      if (free != nullptr && !free->Has(col, top)) {
        ++*unseen;
        continue;
      }
      heights->push_back(static_cast<float>(top * res));
    }
  }
}

// The tops of the runs with room above them (and, with free space known, seen from above),
// in column order: bands of rows on options.threads threads, joined in order.
Candidates SurfaceCandidates(const HeightMap& grid, const Columns& occ, const FreeSpace* free,
                             const std::vector<uint8_t>& dropped, const SurfaceLayerOptions& options,
                             SurfaceLayers* out) {
  const int cells = grid.rows * grid.cols;
  const int band_cols = BandRows(grid.cols) * std::max(1, grid.cols);
  const int bands = cells > 0 ? (cells + band_cols - 1) / band_cols : 0;
  struct Band {
    std::vector<float> heights;
    int no_room = 0, unseen = 0;
  };
  std::vector<Band> parts(static_cast<size_t>(bands));
  Candidates cand;
  cand.offset.assign(static_cast<size_t>(cells) + 1, 0);
  ParallelFor(bands, options.threads, [&](int b) {
    Band& band = parts[static_cast<size_t>(b)];
    CandidatesOfColumns(occ, free, dropped, options.clearance_m / grid.resolution_m, grid.resolution_m,
                        b * band_cols, std::min(cells, (b + 1) * band_cols), cand.offset.data(), &band.heights,
                        &band.no_room, &band.unseen);
  });
  std::vector<size_t> start(static_cast<size_t>(bands) + 1, 0);
  for (int b = 0; b < bands; ++b) {
    const Band& band = parts[static_cast<size_t>(b)];
    start[static_cast<size_t>(b) + 1] = start[static_cast<size_t>(b)] + band.heights.size();
    out->no_room_above += band.no_room;
    out->not_seen_from_above += band.unseen;
  }
  cand.height.resize(start.back());
  cand.col.resize(start.back());
  cand.offset[cells] = start.back();
  ParallelFor(bands, options.threads, [&](int b) {
    const Band& band = parts[static_cast<size_t>(b)];
    const size_t first = start[static_cast<size_t>(b)];
    std::copy(band.heights.begin(), band.heights.end(), cand.height.begin() + static_cast<std::ptrdiff_t>(first));
    const int end = std::min(cells, (b + 1) * band_cols);
    for (int col = b * band_cols; col < end; ++col) {
      cand.offset[col] += first;
      const size_t next = col + 1 < end ? cand.offset[col + 1] + first : start[static_cast<size_t>(b) + 1];
      for (size_t k = cand.offset[col]; k < next; ++k) cand.col[k] = col;
    }
  });
  return cand;
}

// Sheets (lists of candidate indices) by flood fill over 4-neighbours, at most one
// surface per column each, neighbours within the step gate.
std::vector<std::vector<int>> GrowSheets(const HeightMap& grid, const Candidates& cand, double step_gate_m) {
  std::vector<int> cand_sheet(cand.height.size(), -1);
  std::vector<int> column_claim(static_cast<size_t>(grid.rows) * grid.cols, -1);
  std::vector<std::vector<int>> sheets;
  for (size_t seed = 0; seed < cand.height.size(); ++seed) {
    if (cand_sheet[seed] >= 0) continue;
    const int id = static_cast<int>(sheets.size());
    sheets.emplace_back();
    cand_sheet[seed] = id;
    column_claim[cand.col[seed]] = id;
    // The sheet is its own first-in first-out queue: candidates join it in the order
    // they are reached and are visited in that order.
    std::vector<int>& sheet = sheets.back();
    sheet.push_back(static_cast<int>(seed));
    for (size_t head = 0; head < sheet.size(); ++head) {
      const int k = sheet[head];
      const int col = cand.col[k];
      const int r = col / grid.cols, c = col % grid.cols;
      const int dr[4] = {1, -1, 0, 0}, dc[4] = {0, 0, 1, -1};
      for (int d = 0; d < 4; ++d) {
        if (!grid.Inside(r + dr[d], c + dc[d])) continue;
        const int ncol = grid.Index(r + dr[d], c + dc[d]);
        if (column_claim[ncol] == id) continue;
        int best = -1;
        float best_dz = static_cast<float>(step_gate_m) + 1e-6f;
        for (size_t q = cand.offset[ncol]; q < cand.offset[ncol + 1]; ++q) {
          const float dz = std::abs(cand.height[q] - cand.height[k]);
          if (cand_sheet[q] < 0 && dz <= best_dz) {
            best = static_cast<int>(q);
            best_dz = dz;
          }
        }
        if (best < 0) continue;
        cand_sheet[best] = id;
        column_claim[ncol] = id;
        sheet.push_back(best);
      }
    }
  }
  return sheets;
}

// Layers: largest sheets first, each into the first layer where its columns are empty;
// at least one layer.
std::vector<HeightMap> StackSheets(const HeightMap& grid, const Candidates& cand,
                                   const std::vector<std::vector<int>>& sheets) {
  std::vector<int> order(sheets.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return sheets[a].size() > sheets[b].size(); });
  HeightMap empty = grid;
  std::fill(empty.height_m.begin(), empty.height_m.end(), std::numeric_limits<float>::quiet_NaN());
  std::vector<HeightMap> layers;
  for (int s : order) {
    size_t layer = 0;
    for (; layer < layers.size(); ++layer) {
      bool fits = true;
      for (int k : sheets[s]) {
        if (!std::isnan(layers[layer].height_m[cand.col[k]])) {
          fits = false;
          break;
        }
      }
      if (fits) break;
    }
    if (layer == layers.size()) layers.push_back(empty);
    for (int k : sheets[s]) layers[layer].height_m[cand.col[k]] = cand.height[k];
  }
  if (layers.empty()) layers.push_back(empty);
  return layers;
}

// Voxels of room a surface needs above it (SurfaceLayerOptions::clearance_m).
long long RoomVoxels(double clearance_m, double res) {
  return std::isfinite(clearance_m) ? static_cast<long long>(std::ceil(clearance_m / res - 1e-6))
                                    : std::numeric_limits<long long>::max() / 4;
}

// SurfaceLayers::unseen bits of empty column `col` beside a surface at `level` [m].
uint8_t UnseenBits(const Columns& occ, const FreeSpace* free, int col, float level, double res, long long room) {
  const long long top_voxel = TopVoxelOf(level, res);
  if (occ.begin(col) != occ.end(col) && occ.begin(col)->lo < top_voxel + 1 + room) return 0;
  // A ray through the voxel under the floor's level went into a hole: a drop.
  if (free != nullptr && free->Has(col, top_voxel - 1)) return 0;
  const bool erased = free != nullptr && free->Has(col, top_voxel);
  return static_cast<uint8_t>(kEmptyColumn | (erased ? 0 : kNotErased));
}

// SurfaceLayers::unseen bits of cell (r, c) of layer: 0 unless it is empty beside a surface.
uint8_t UnseenCell(const HeightMap& layer, const Columns& occ, const FreeSpace* free, int r, int c, long long room) {
  if (!std::isnan(layer.height_m[static_cast<size_t>(layer.Index(r, c))])) return 0;
  float level = -std::numeric_limits<float>::infinity();
  const int dr[4] = {1, -1, 0, 0}, dc[4] = {0, 0, 1, -1};
  for (int k = 0; k < 4; ++k) {
    if (!layer.HasSurface(r + dr[k], c + dc[k])) continue;
    level = std::max(level, layer.height_m[static_cast<size_t>(layer.Index(r + dr[k], c + dc[k]))]);
  }
  if (!std::isfinite(level)) return 0;
  return UnseenBits(occ, free, layer.Index(r, c), level, layer.resolution_m, room);
}

// `unseen` (the layer's unseen bits before the cells `changed` got a surface or a new
// height) brought up to date: only those cells and their 4-neighbours can differ.
void UpdateUnseenCells(const HeightMap& layer, const Columns& occ, const FreeSpace* free, double clearance_m,
                       const int* changed, size_t n_changed, std::vector<uint8_t>* unseen) {
  const long long room = RoomVoxels(clearance_m, layer.resolution_m);
  for (size_t k = 0; k < n_changed; ++k) {
    const int r = changed[k] / layer.cols, c = changed[k] % layer.cols;
    const int dr[5] = {0, 1, -1, 0, 0}, dc[5] = {0, 0, 0, 1, -1};
    for (int d = 0; d < 5; ++d) {
      if (!layer.Inside(r + dr[d], c + dc[d])) continue;
      (*unseen)[static_cast<size_t>(layer.Index(r + dr[d], c + dc[d]))] =
          UnseenCell(layer, occ, free, r + dr[d], c + dc[d], room);
    }
  }
}

// The heights of the nearest surface cell along each of the 8 grid directions from (r, c),
// at most radius cells away; false when a direction has none (or leaves the grid).
bool SurfaceAllRound(const HeightMap& layer, int r, int c, int radius, float hits[8]) {
  int k = 0;
  for (int dr = -1; dr <= 1; ++dr) {
    for (int dc = -1; dc <= 1; ++dc) {
      if (dr == 0 && dc == 0) continue;
      bool found = false;
      for (int step = 1; step <= radius && !found; ++step) {
        if (!layer.Inside(r + step * dr, c + step * dc)) return false;
        const float h = layer.height_m[static_cast<size_t>(layer.Index(r + step * dr, c + step * dc))];
        if (!std::isnan(h)) hits[k] = h, found = true;
      }
      if (!found) return false;
      ++k;
    }
  }
  return true;
}

// Unseen floor enclosed by seen floor (docs/unseen_floor.md): an empty cell whose nearest
// surface along every one of the 8 grid directions lies within radius cells, all of them
// within one voxel of each other, and whose column is unseen at that level (nothing
// occupied down to the map's bottom or within the clearance above, no ray through the
// floor's voxel or the one under it: SurfaceLayers::unseen's kEmptyColumn | kNotErased)
// gets the lower of the surrounding heights' middle pair. The cells of rows [r0, r1) to
// fill, judged on the layer as it is (so fills do not chain), are appended in row order
// to fills with their heights.
// spans: the RowSpan of each of the rows [r0, r1) (cells outside it have no surface on
// one side in their row, so none is enclosed).
void CollectEnclosedFills(const HeightMap& seen, const Columns& occ, const FreeSpace& free, double clearance_m,
                          int radius, int r0, int r1, const RowSpan* spans, std::vector<std::pair<int, float>>* fills) {
  const double res = seen.resolution_m;
  const long long room = RoomVoxels(clearance_m, res);
  std::vector<int> next_right(static_cast<size_t>(seen.cols));
  for (int r = r0; r < r1; ++r) {
    const RowSpan span = spans[r - r0];
    if (span.lo == span.hi) continue;  // no surface in the row
    // The nearest surface at or right of each column, and the last one left of it: a cell
    // without one within radius on both sides of its row is not enclosed.
    const float* row = &seen.height_m[static_cast<size_t>(seen.Index(r, 0))];
    int next = std::numeric_limits<int>::max() / 2;
    for (int c = span.hi - 1; c >= span.lo; --c) next_right[static_cast<size_t>(c)] = next = std::isnan(row[c]) ? next : c;
    int last_left = std::numeric_limits<int>::min() / 2;
    for (int c = span.lo; c < span.hi; ++c) {
      const size_t i = static_cast<size_t>(seen.Index(r, c));
      if (!std::isnan(seen.height_m[i])) {
        last_left = c;
        continue;
      }
      if (c - last_left > radius || next_right[static_cast<size_t>(c)] - c > radius) continue;
      float hits[8];
      if (!SurfaceAllRound(seen, r, c, radius, hits)) continue;
      std::sort(hits, hits + 8);
      if (hits[7] - hits[0] > res * (1.0 + 1e-3)) continue;
      const float level = hits[3];
      const int col = seen.Index(r, c);
      if (UnseenBits(occ, &free, col, level, res, room) != (kEmptyColumn | kNotErased)) continue;
      if (UnseenBits(occ, &free, col, hits[7], res, room) != (kEmptyColumn | kNotErased)) continue;
      fills->emplace_back(col, level);
    }
  }
}

// The run of column c holding voxel z, or nullptr.
const Interval* RunHolding(const Columns& cols, int c, long long z) {
  for (const Interval* it = cols.begin(c); it != cols.end(c) && it->lo <= z; ++it) {
    if (it->hi > z) return it;
  }
  return nullptr;
}

// Material rising beside each surface cell of rows [r0, r1) of layer
// (SurfaceLayers::solid_beside), written to those rows of bits; spans: the RowSpan of
// each of those rows.
void SolidBesideRows(const HeightMap& layer, const Columns& occ, int r0, int r1, const RowSpan* spans,
                     std::vector<uint8_t>* bits) {
  const double res = layer.resolution_m;
  for (int r = r0; r < r1; ++r) {
    for (int c = spans[r - r0].lo; c < spans[r - r0].hi; ++c) {
      const float h = layer.height_m[static_cast<size_t>(layer.Index(r, c))];
      if (std::isnan(h)) continue;
      const long long top_voxel = RoundToLongLong(h / res) - 1;
      uint8_t b = 0;
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          if ((dr == 0 && dc == 0) || !layer.Inside(r + dr, c + dc)) continue;
          // Occupied above the top voxel, and at its level or one higher still. Runs are
          // merged (a gap between any two), so both lie in the run holding the first.
          const Interval* run = RunHolding(occ, layer.Index(r + dr, c + dc), top_voxel + 1);
          if (run != nullptr && (run->lo <= top_voxel || run->hi >= top_voxel + 3)) {
            b = static_cast<uint8_t>(b | (1u << NeighbourBit(dr, dc)));
          }
        }
      }
      (*bits)[static_cast<size_t>(layer.Index(r, c))] = b;
    }
  }
}

// The cells the noise repair changed (not those it filled), at their seen height; NaN
// elsewhere. changes: each changed cell with its height before that change, in order.
HeightMap MovedCellsAsSeen(const HeightMap& repaired, const std::vector<std::pair<int, float>>& changes) {
  HeightMap moved = repaired;
  std::fill(moved.height_m.begin(), moved.height_m.end(), std::numeric_limits<float>::quiet_NaN());
  // Latest first, so each cell ends with its height before its first change.
  for (auto it = changes.rbegin(); it != changes.rend(); ++it) moved.height_m[static_cast<size_t>(it->first)] = it->second;
  for (const auto& change : changes) {
    float& seen = moved.height_m[static_cast<size_t>(change.first)];
    if (seen == repaired.height_m[static_cast<size_t>(change.first)]) seen = std::numeric_limits<float>::quiet_NaN();
  }
  return moved;
}

// Marks in `filled` (SurfaceLayers::filled) the cells among `changes` (the noise repair's)
// that were empty: unseen or erased floor by their unseen bits (kNotErased).
void RecordFills(const HeightMap& layer, const std::vector<uint8_t>& unseen,
                 const std::vector<std::pair<int, float>>& changes, std::vector<uint8_t>* filled) {
  for (const auto& change : changes) {
    const auto cell = static_cast<size_t>(change.first);
    if (!std::isnan(layer.height_m[cell])) continue;  // a moved cell, not a fill
    (*filled)[cell] = (unseen[cell] & kNotErased) ? kFilledUnseen : kFilledErased;
  }
}

// What BuildSurfaceLayers keeps of one layer besides its heights.
struct LayerFinish {
  std::vector<uint8_t> unseen, solid_beside, filled;  // SurfaceLayers::unseen, solid_beside, filled of the layer
  std::optional<HeightMap> moved_as_seen;      // when the noise repair changed a cell
  int noise_cells_filled = 0, enclosed_unseen_filled = 0;
};

// Rows [r0, r1) of one layer: the unit of FinishLayers' passes.
struct LayerBand {
  size_t layer;
  int r0, r1;
  std::vector<int> near;                       // NearCellsInRows of the band
  std::vector<RowSpan> spans;                  // each row's, from NearCellsInRows: no change moves them
  std::vector<std::pair<int, float>> changes;  // a pass's repairs or fills in the band, in order
};

// Every layer's noise repair and enclosed-unseen fill (as options say), its unseen bits
// (computed once, then brought up to date after each change) and, from the final heights,
// its solid_beside bits. free: nullptr when free space is not known. Each pass runs over
// bands of rows of every layer on options.threads threads, judging every cell on the
// heights before the pass; its changes are then made per layer in row order: the result a
// single thread passing over each layer in row order gives.
std::vector<LayerFinish> FinishLayers(std::vector<HeightMap>* layers, const Columns& occ, const FreeSpace* free,
                                      const SurfaceLayerOptions& options) {
  const int rows = layers->front().rows, cols = layers->front().cols;
  const int band_rows = BandRows(cols);
  std::vector<LayerBand> bands;
  for (size_t l = 0; l < layers->size(); ++l) {
    for (int r0 = 0; r0 < rows; r0 += band_rows) bands.push_back({l, r0, std::min(rows, r0 + band_rows), {}, {}, {}});
  }
  std::vector<LayerFinish> out(layers->size());
  for (LayerFinish& f : out) {
    f.unseen.assign(static_cast<size_t>(rows) * cols, 0);
    f.filled.assign(static_cast<size_t>(rows) * cols, 0);
  }
  const long long room = RoomVoxels(options.clearance_m, layers->front().resolution_m);
  auto each_band = [&](const std::function<void(LayerBand&, HeightMap&, LayerFinish&)>& work) {
    ParallelFor(static_cast<int>(bands.size()), options.threads, [&](int i) {
      LayerBand& band = bands[static_cast<size_t>(i)];
      work(band, (*layers)[band.layer], out[band.layer]);
    });
  };
  // Makes every band's changes, layer by layer in row order, and brings the unseen bits up
  // to date; `before` (optional, per layer) gets each changed cell with its old height.
  auto make_changes = [&](std::vector<std::vector<std::pair<int, float>>>* before, int LayerFinish::*count) {
    ParallelFor(static_cast<int>(layers->size()), options.threads, [&](int l) {
      HeightMap& layer = (*layers)[static_cast<size_t>(l)];
      std::vector<int> changed;
      for (const LayerBand& band : bands) {
        if (band.layer != static_cast<size_t>(l)) continue;
        ApplyRepairs(band.changes, &layer, &changed, before != nullptr ? &(*before)[static_cast<size_t>(l)] : nullptr);
      }
      UpdateUnseenCells(layer, occ, free, options.clearance_m, changed.data(), changed.size(),
                        &out[static_cast<size_t>(l)].unseen);
      out[static_cast<size_t>(l)].*count += static_cast<int>(changed.size());
    });
  };
  each_band([&](LayerBand& band, HeightMap& layer, LayerFinish& finish) {
    band.spans.resize(static_cast<size_t>(band.r1 - band.r0));
    NearCellsInRows(layer, band.r0, band.r1, &band.near, band.spans.data());
    for (int i : band.near) finish.unseen[static_cast<size_t>(i)] = UnseenCell(layer, occ, free, i / cols, i % cols, room);
  });
  if (options.fill_single_cell_noise) {
    std::vector<std::vector<std::pair<int, float>>> before(layers->size());
    // Twice: a hole beside a displaced cell is filled once that cell is back.
    // The second pass judges only the near cells within one cell of a first pass's change:
    // the others see the heights and unseen bits the first pass judged (no repair then).
    std::vector<std::vector<int>> around(layers->size());
    for (int pass = 0; pass < 2; ++pass) {
      each_band([&](LayerBand& band, HeightMap& layer, LayerFinish& finish) {
        band.changes.clear();
        std::vector<int> judged;
        if (pass == 1) {
          const std::vector<int>& touched = around[band.layer];
          std::set_intersection(band.near.begin(), band.near.end(), touched.begin(), touched.end(),
                                std::back_inserter(judged));
        }
        const std::vector<int>& cells = pass == 0 ? band.near : judged;
        CollectRepairs(layer, &finish.unseen, cells.data(), cells.data() + cells.size(), &band.changes);
        RecordFills(layer, finish.unseen, band.changes, &finish.filled);
      });
      make_changes(&before, &LayerFinish::noise_cells_filled);
      if (pass == 0) {
        for (size_t l = 0; l < layers->size(); ++l) around[l] = CellsAround((*layers)[l], before[l]);
      }
    }
    for (size_t l = 0; l < layers->size(); ++l) {
      if (!before[l].empty()) out[l].moved_as_seen = MovedCellsAsSeen((*layers)[l], before[l]);
    }
  }
  if (free != nullptr && options.enclosed_unseen_radius_cells > 0) {
    each_band([&](LayerBand& band, HeightMap& layer, LayerFinish& finish) {
      band.changes.clear();
      CollectEnclosedFills(layer, occ, *free, options.clearance_m, options.enclosed_unseen_radius_cells, band.r0,
                           band.r1, band.spans.data(), &band.changes);
      for (const auto& change : band.changes) finish.filled[static_cast<size_t>(change.first)] = kFilledUnseen;
    });
    make_changes(nullptr, &LayerFinish::enclosed_unseen_filled);
  }
  for (LayerFinish& f : out) f.solid_beside.assign(static_cast<size_t>(rows) * cols, 0);
  each_band([&](LayerBand& band, HeightMap& layer, LayerFinish& finish) {
    SolidBesideRows(layer, occ, band.r0, band.r1, band.spans.data(), &finish.solid_beside);
  });
  return out;
}

// FootprintsOf every occupied leaf, in `threads` parts of the leaves at once, joined in
// order: the same prints as one pass.
std::vector<Footprint> OccupiedFootprints(const OccupancyMap& map, const HeightMap& grid, int threads) {
  const int parts = std::max(1, threads);
  const size_t n = map.leaves.size();
  const OccupiedLeaf* leaves = map.leaves.data();
  std::vector<std::vector<Footprint>> part_prints(static_cast<size_t>(parts));
  ParallelFor(parts, threads, [&](int p) {
    const size_t k = static_cast<size_t>(p), m = static_cast<size_t>(parts);
    part_prints[k] = FootprintsOf(leaves + n * k / m, leaves + n * (k + 1) / m, grid);
  });
  if (parts == 1) return std::move(part_prints.front());
  size_t total = 0;
  for (const std::vector<Footprint>& part : part_prints) total += part.size();
  std::vector<Footprint> prints;
  prints.reserve(total);
  for (const std::vector<Footprint>& part : part_prints) prints.insert(prints.end(), part.begin(), part.end());
  return prints;
}

// The grid (HeightMapGrid), its errors preceded by the leaf budget's as when the budget
// was checked first.
HeightMap GridAfterBudget(const OccupancyMap& map, const SurfaceLayerOptions& options) {
  try {
    return HeightMapGrid(map, options.max_cells, options.threads);
  } catch (const InputError&) {
    CheckLeafColumnBudget(map, options.max_leaf_columns, options.threads);
    throw;
  }
}

// Throws CheckLeafColumnBudget's error when `cells` (an exact sum of column cells, at
// most the map's LeafColumnCells) is over the budget: the map's own count is then too.
void CheckBudgetPart(const OccupancyMap& map, double cells, const SurfaceLayerOptions& options) {
  if (ColumnCellsFromSum(cells) > options.max_leaf_columns) CheckLeafColumnBudget(map, options.max_leaf_columns, options.threads);
}

}  // namespace

SurfaceLayers BuildSurfaceLayers(const OccupancyMap& map, const SurfaceLayerOptions& options) {
  MFP_CHECK(options.clearance_m > 0.0 && options.step_gate_m >= 0.0);
  SurfaceLayers out;
  // The grid and the validation of the leaves are the height map's (its heights are not
  // needed: the layers are built from the columns). The grid and the footprints are
  // bounded by the map's size; the leaf budget is checked before any leaf is expanded
  // into columns.
  HeightMap grid = GridAfterBudget(map, options);
  if (grid.rows * grid.cols == 0) {
    out.layers.push_back(grid);
    out.solid_beside.emplace_back();
    return out;
  }
  const bool know_free = !map.free_leaves.empty() && options.require_seen_from_above;
  const std::vector<Footprint> occupied = OccupiedFootprints(map, grid, options.threads);
  // The leaf budget (CheckLeafColumnBudget) in parts, each before what it bounds is
  // expanded: the occupied leaves' n^2 (the grid holds each whole) before their columns,
  // all the leaves' before the free columns (the free leaves' part summed by the pass
  // that takes their footprints; when that pass is not made, the budget's own).
  double occupied_cells = 0.0;
  for (const Footprint& f : occupied) occupied_cells += static_cast<double>(f.n) * f.n;
  CheckBudgetPart(map, occupied_cells, options);
  long long z_lo = 0, z_hi = 0;
  const bool free_asked = know_free && FreeVoxelsAsked(occupied, grid.resolution_m, &z_lo, &z_hi);
  if (!free_asked && !map.free_leaves.empty()) CheckLeafColumnBudget(map, options.max_leaf_columns, options.threads);
  // The free space as bits when they take no more memory than the footprints the runs
  // are cut from (a band's words per column against an offset per column and two words a
  // leaf): bounded by the map's size, as those are.
  FreeSpace free;
  const double grid_cells = static_cast<double>(grid.rows) * grid.cols;
  const bool bits = free_asked && static_cast<double>(BandWords(z_lo, z_hi)) * grid_cells <=
                                      grid_cells + 1 + 2 * static_cast<double>(map.free_leaves.size());
  if (bits) {
    free.z0 = z_lo;
    free.words = static_cast<size_t>(BandWords(z_lo, z_hi));
    free.ZeroBits(static_cast<size_t>(grid_cells), options.threads);
  }
  // The occupied columns beside the free leaves' footprints (in parts, four for each
  // thread so the threads end together beside the occupied columns' one item): with bits, a leaf one voxel wide sets its bit at
  // once and a wider one waits for the budget; else every footprint is kept for the runs.
  const int parts = free_asked ? 4 * std::max(1, options.threads) : 0;
  std::vector<std::vector<Footprint>> free_prints(static_cast<size_t>(parts));
  std::vector<double> free_cells(static_cast<size_t>(parts), 0.0);
  Columns occ;
  ParallelFor(1 + parts, options.threads, [&](int job) {
    if (job == 0) {
      occ = ColumnsOf(occupied, grid);
      return;
    }
    const size_t n = map.free_leaves.size(), k = static_cast<size_t>(job - 1), m = static_cast<size_t>(parts);
    const OccupiedLeaf* begin = map.free_leaves.data() + n * k / m;
    const OccupiedLeaf* end = map.free_leaves.data() + n * (k + 1) / m;
    if (!bits) {
      free_prints[k] = FootprintsOf(begin, end, grid, z_lo, z_hi, &free_cells[k]);
      return;
    }
    ForEachFootprint(begin, end, grid, z_lo, z_hi, &free_cells[k], [&](const Footprint& f) {
      if (f.n == 1) {
        free.Set(f, grid);
      } else {
        free_prints[k].push_back(f);
      }
    });
  });
  if (free_asked) {
    double all_cells = occupied_cells;
    for (double cells : free_cells) all_cells += cells;
    CheckBudgetPart(map, all_cells, options);
  }
  if (bits) {
    ParallelFor(parts, options.threads, [&](int k) {
      for (const Footprint& f : free_prints[static_cast<size_t>(k)]) free.Set(f, grid);
    });
  } else if (know_free) {
    free.runs = UnsortedColumnsInBands(free_prints, grid, std::max(1, options.threads), options.threads);
  }
  const std::vector<uint8_t> dropped = options.drop_isolated_voxels
                                           ? IsolatedVoxels(grid, occ, options.threads, &out.isolated_voxels)
                                           : std::vector<uint8_t>(occ.runs.size(), 0);
  const Candidates cand = SurfaceCandidates(grid, occ, know_free ? &free : nullptr, dropped, options, &out);
  out.candidates = static_cast<int>(cand.height.size());
  out.layers = StackSheets(grid, cand, GrowSheets(grid, cand, options.step_gate_m));
  const FreeSpace* free_or_null = know_free ? &free : nullptr;
  std::vector<LayerFinish> finished = FinishLayers(&out.layers, occ, free_or_null, options);
  for (LayerFinish& f : finished) {
    out.unseen.push_back(std::move(f.unseen));
    out.solid_beside.push_back(std::move(f.solid_beside));
    out.filled.push_back(std::move(f.filled));
    out.noise_cells_filled += f.noise_cells_filled;
    out.enclosed_unseen_filled += f.enclosed_unseen_filled;
    if (f.moved_as_seen) out.moved_as_seen.push_back(std::move(*f.moved_as_seen));
  }
  return out;
}

}  // namespace mfp
