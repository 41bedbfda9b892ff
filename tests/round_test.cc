#include "base/round.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace mfp {
namespace {

std::vector<double> EdgeValues() {
  std::vector<double> v = {0.0, -0.0, 0.5, -0.5, 1.5, -1.5, 2.5, -2.5, 0.49999999999999994, -0.49999999999999994,
                           1e-300, -1e-300, 4503599627370495.5, -4503599627370495.5, 4503599627370496.0,
                           9007199254740993.0, 1e18, -1e18, 123456.49999999999, -98765.50000000001};
  for (double base : {0.5, 1.5, 1000.5, 65536.5}) {
    v.push_back(std::nextafter(base, 0.0));
    v.push_back(std::nextafter(base, 1e9));
    v.push_back(-std::nextafter(base, 0.0));
    v.push_back(-std::nextafter(base, 1e9));
  }
  return v;
}

TEST(RoundTest, MatchesTheLibraryOnEdgeValues) {
  for (double x : EdgeValues()) {
    EXPECT_EQ(RoundToLongLong(x), std::llround(x)) << x;
    EXPECT_EQ(RoundToDouble(x), std::round(x)) << x;
  }
}

TEST(RoundTest, MatchesTheLibraryOnRandomValues) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> wide(-1e7, 1e7), unit(-3.0, 3.0);
  std::uniform_int_distribution<int> half(-200000, 200000);
  for (int i = 0; i < 200000; ++i) {
    // Coordinates over a voxel size as the map readers form them, near and at halves.
    for (double x : {wide(rng), unit(rng), half(rng) * 0.5, (wide(rng) - 0.5 * 0.05) / 0.05}) {
      ASSERT_EQ(RoundToLongLong(x), std::llround(x)) << x;
      ASSERT_EQ(RoundToDouble(x), std::round(x)) << x;
    }
  }
}

TEST(RoundTest, LeavesNonFiniteValuesToTheLibrary) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(RoundToDouble(inf), inf);
  EXPECT_EQ(RoundToDouble(-inf), -inf);
  EXPECT_TRUE(std::isnan(RoundToDouble(std::numeric_limits<double>::quiet_NaN())));
}

}  // namespace
}  // namespace mfp
