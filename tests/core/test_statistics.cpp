#include <gtest/gtest.h>

#include <vector>

#include "refx/core/statistics.h"

namespace refx {
namespace {

// Nearest rank of n values: rank ceil(q * n), counted from 1, at least 1.
TEST(Statistics, NearestRankOfTenValues) {
  const std::vector<double> v{1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  EXPECT_EQ(nearestRank(v, 0.0), 1);   // rank 0, raised to 1
  EXPECT_EQ(nearestRank(v, 0.1), 1);   // ceil(1.0) = 1
  EXPECT_EQ(nearestRank(v, 0.25), 3);  // ceil(2.5) = 3
  EXPECT_EQ(nearestRank(v, 0.5), 5);   // ceil(5.0) = 5
  EXPECT_EQ(nearestRank(v, 0.9), 9);   // ceil(9.0) = 9
  EXPECT_EQ(nearestRank(v, 0.95), 10);  // ceil(9.5) = 10
  EXPECT_EQ(nearestRank(v, 1.0), 10);
}

TEST(Statistics, NearestRankOfFewValues) {
  EXPECT_EQ(nearestRank({7}, 0.1), 7);  // one value is every quantile
  EXPECT_EQ(nearestRank({7}, 0.9), 7);
  const std::vector<double> two{2, 4};
  EXPECT_EQ(nearestRank(two, 0.5), 2);  // ceil(1.0) = 1: the lower one
  EXPECT_EQ(nearestRank(two, 0.51), 4);  // ceil(1.02) = 2
}

}  // namespace
}  // namespace refx
