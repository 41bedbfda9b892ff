// Pseudo-costs: per-unit means per direction, the all-variable mean as the prior for a
// variable never branched on, and the product score.
#include "planner/search/internal/pseudo_costs.h"

#include <gtest/gtest.h>

namespace mfp {
namespace {

TEST(PseudoCosts, MeanPerUnitPerDirection) {
  PseudoCosts pc(3);
  pc.Record(0, /*up=*/true, /*gain=*/2.0, /*distance=*/0.5);  // 4 per unit
  pc.Record(0, true, 1.0, 0.5);                                 // 2 per unit
  pc.Record(0, false, 0.3, 0.3);                                // 1 per unit
  EXPECT_DOUBLE_EQ(pc.PerUnit(0, true), 3.0);
  EXPECT_DOUBLE_EQ(pc.PerUnit(0, false), 1.0);
  EXPECT_EQ(pc.Count(0, true), 2);
  EXPECT_EQ(pc.Count(0, false), 1);
  EXPECT_EQ(pc.Count(1, true), 0);
}

TEST(PseudoCosts, UnseenVariableTakesTheMeanOfAllAndNegativeGainsCountAsZero) {
  PseudoCosts pc(3);
  EXPECT_DOUBLE_EQ(pc.PerUnit(2, false), 1.0);  // nothing seen yet: a neutral 1
  pc.Record(0, false, 1.0, 0.25);  // 4
  pc.Record(1, false, -5.0, 0.5);  // a child below its parent (solver tolerance): 0
  EXPECT_DOUBLE_EQ(pc.PerUnit(1, false), 0.0);
  EXPECT_DOUBLE_EQ(pc.PerUnit(2, false), 2.0);
}

TEST(PseudoCosts, ProductScorePrefersBalancedGains) {
  EXPECT_GT(PseudoCosts::Score(2.0, 2.0), PseudoCosts::Score(4.0, 0.5));
  EXPECT_GT(PseudoCosts::Score(0.0, 3.0), PseudoCosts::Score(0.0, 2.0));  // the floor keeps order
}

TEST(PseudoCostsDeathTest, ZeroDistanceIsAProgrammerError) {
  PseudoCosts pc(1);
  EXPECT_DEATH(pc.Record(0, true, 1.0, 0.0), "");
}

}  // namespace
}  // namespace mfp
