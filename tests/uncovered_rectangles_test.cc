#include "terrain/extraction/internal/uncovered_rectangles.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "terrain/extraction/internal/rectangle_cover.h"

namespace mfp {
namespace {

void ExpectSameRect(const CellRect& a, const CellRect& b) {
  EXPECT_EQ(a.row0, b.row0);
  EXPECT_EQ(a.col0, b.col0);
  EXPECT_EQ(a.rows, b.rows);
  EXPECT_EQ(a.cols, b.cols);
}

// A floor with scattered holes and a few long walls, density `fill`.
std::vector<uint8_t> RandomMask(std::mt19937* rng, int rows, int cols, double fill) {
  std::bernoulli_distribution set(fill);
  std::vector<uint8_t> mask(static_cast<size_t>(rows) * cols);
  for (uint8_t& m : mask) m = set(*rng) ? 1 : 0;
  std::uniform_int_distribution<int> row(0, rows - 1), col(0, cols - 1);
  for (int wall = 0; wall < 3; ++wall) {
    const int r = row(*rng);
    for (int c = 0; c < cols; ++c) mask[static_cast<size_t>(r) * cols + c] = 0;
  }
  return mask;
}

// Any rectangle of the grid, possibly over cells cleared already.
CellRect RandomRect(std::mt19937* rng, int rows, int cols) {
  std::uniform_int_distribution<int> row(0, rows - 1), col(0, cols - 1);
  CellRect rect;
  rect.row0 = row(*rng);
  rect.col0 = col(*rng);
  rect.rows = std::uniform_int_distribution<int>(1, rows - rect.row0)(*rng);
  rect.cols = std::uniform_int_distribution<int>(1, cols - rect.col0)(*rng);
  return rect;
}

TEST(UncoveredRectanglesTest, AnswersAsTheFullScanAfterEveryClear) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const int rows = std::uniform_int_distribution<int>(1, 30)(rng);
    const int cols = std::uniform_int_distribution<int>(1, 30)(rng);
    const double fill = std::uniform_real_distribution<double>(0.5, 1.0)(rng);
    std::vector<uint8_t> cells = RandomMask(&rng, rows, cols, fill);
    UncoveredRectangles tracker(cells, rows, cols);
    for (int step = 0; step < 40; ++step) {
      ExpectSameRect(tracker.Largest(), LargestRectangle(cells, rows, cols));
      ASSERT_EQ(tracker.cells(), cells);
      // Half the time the largest rectangle (the greedy cover's step), else any rectangle.
      const CellRect largest = LargestRectangle(cells, rows, cols);
      const CellRect rect = step % 2 == 0 && largest.Area() > 0 ? largest : RandomRect(&rng, rows, cols);
      size_t set = 0;
      for (int r = rect.row0; r < rect.row0 + rect.rows; ++r) {
        for (int c = rect.col0; c < rect.col0 + rect.cols; ++c) {
          set += cells[static_cast<size_t>(r) * cols + c];
          cells[static_cast<size_t>(r) * cols + c] = 0;
        }
      }
      EXPECT_EQ(tracker.Clear(rect), set);
    }
  }
}

TEST(UncoveredRectanglesTest, ClearingAnyCellsAnswersAsTheFullScan) {
  // The convex cover closes the squares a piece meets: any shape, not a rectangle.
  std::mt19937 rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    const int rows = std::uniform_int_distribution<int>(1, 30)(rng);
    const int cols = std::uniform_int_distribution<int>(1, 30)(rng);
    std::vector<uint8_t> cells = RandomMask(&rng, rows, cols, std::uniform_real_distribution<double>(0.5, 1.0)(rng));
    UncoveredRectangles tracker(cells, rows, cols);
    std::uniform_int_distribution<size_t> any(0, cells.size() - 1);
    for (int step = 0; step < 40; ++step) {
      std::vector<size_t> clear;
      const int n = std::uniform_int_distribution<int>(0, 12)(rng);
      for (int k = 0; k < n; ++k) clear.push_back(any(rng));  // repeats and cleared cells too
      size_t set = 0;
      for (size_t i : clear) {
        set += cells[i];
        cells[i] = 0;
      }
      EXPECT_EQ(tracker.ClearCells(clear), set);
      ASSERT_EQ(tracker.cells(), cells);
      ExpectSameRect(tracker.Largest(), LargestRectangle(cells, rows, cols));
    }
  }
}

TEST(UncoveredRectanglesTest, TiesGoToTheFirstRectangleOfTheRowByRowScan) {
  // Two 2 x 2 squares: the one whose bottom row comes first wins, then the left one.
  const std::vector<uint8_t> mask = {1, 1, 0, 0, 0,  //
                                     1, 1, 0, 1, 1,  //
                                     0, 0, 0, 1, 1};
  UncoveredRectangles tracker(mask, 3, 5);
  ExpectSameRect(tracker.Largest(), CellRect{0, 0, 2, 2});
  EXPECT_EQ(tracker.Clear(CellRect{0, 0, 2, 2}), 4u);
  ExpectSameRect(tracker.Largest(), CellRect{1, 3, 2, 2});
  EXPECT_EQ(tracker.Clear(CellRect{0, 0, 3, 5}), 4u);
  EXPECT_EQ(tracker.Largest().Area(), 0);
}

// The bridge step scans only the bridge's bounding box: the same rectangle, ties included,
// as the full scan of a mask whose cells all lie in the box.
TEST(UncoveredRectanglesTest, TheLargestRectangleWithinABoxHoldingEveryCellIsTheFullScans) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 400; ++trial) {
    const int rows = std::uniform_int_distribution<int>(1, 30)(rng);
    const int cols = std::uniform_int_distribution<int>(1, 30)(rng);
    std::vector<uint8_t> mask = RandomMask(&rng, rows, cols, std::uniform_real_distribution<double>(0.5, 1.0)(rng));
    const CellRect box = RandomRect(&rng, rows, cols);
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < cols; ++c) {
        const bool inside = r >= box.row0 && r < box.row0 + box.rows && c >= box.col0 && c < box.col0 + box.cols;
        if (!inside) mask[static_cast<size_t>(r) * cols + c] = 0;
      }
    }
    ExpectSameRect(LargestRectangleWithin(mask, rows, cols, box), LargestRectangle(mask, rows, cols));
  }
}

TEST(UncoveredRectanglesTest, ABridgesBoundsHoldItsCellsTightly) {
  // Two covered pieces (columns 0 and 6) joined by an uncovered L in rows 2-4.
  const int rows = 6, cols = 7;
  std::vector<int> owner(static_cast<size_t>(rows) * cols, -1);
  std::vector<uint8_t> uncovered(owner.size(), 0);
  for (int r = 0; r < rows; ++r) {
    owner[static_cast<size_t>(r) * cols] = 0;
    owner[static_cast<size_t>(r) * cols + 6] = 1;
  }
  for (int c = 1; c < 6; ++c) uncovered[static_cast<size_t>(2) * cols + c] = 1;
  uncovered[static_cast<size_t>(3) * cols + 3] = uncovered[static_cast<size_t>(4) * cols + 3] = 1;
  CellRect bounds;
  const std::vector<uint8_t> bridge = UncoveredBridge(uncovered, owner, rows, cols, &bounds);
  ASSERT_EQ(bridge, uncovered);
  ExpectSameRect(bounds, CellRect{2, 1, 3, 5});
}

}  // namespace
}  // namespace mfp
