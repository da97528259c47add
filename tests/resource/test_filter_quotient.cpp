// The bilinear kernel divides x = S/256 by 65280 (S = texel·weight sums, integers in
// [0, 255·65536]), and the point kernel bytes b by 255, without a division:
// fma(x, hi, x·lo) with the reciprocal split into two floats hi + lo
// (resource/sampler_kernels.h). That is only allowed because it gives the correctly
// rounded quotient for every such x: checked here over all 16.7 million values (and
// all 256 bytes), against the division itself.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "resource/sampler_kernels.h"

using namespace refx::resource::kernels;

// The split is what its definition says: hi the float nearest 1/d, lo the float
// nearest the rest, computed in double here as well.
TEST(FilterQuotient, ReciprocalSplitsAreTheNearestFloats) {
  EXPECT_EQ(kInv65280Hi, float(1.0 / 65280.0));
  EXPECT_EQ(kInv65280Lo, float(1.0 / 65280.0 - double(float(1.0 / 65280.0))));
  EXPECT_EQ(kInv255Hi, float(1.0 / 255.0));
  EXPECT_EQ(kInv255Lo, float(1.0 / 255.0 - double(float(1.0 / 255.0))));
  EXPECT_NE(kInv65280Lo, 0.0f);
  EXPECT_NE(kInv255Lo, 0.0f);
}

TEST(FilterQuotient, SplitReciprocalWithOneFmaEqualsDivisionForEveryFilterSum) {
  long mismatches = 0;
  for (long s = 0; s <= 255L * 65536; ++s) {
    const float x = float(s) / 256.0f;  // exact: s < 2^24
    const float want = x / 65280.0f;
    const float got = std::fma(x, kInv65280Hi, x * kInv65280Lo);
    mismatches += std::memcmp(&got, &want, sizeof got) != 0;
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(FilterQuotient, SplitReciprocalWithOneFmaEqualsDivisionForEveryByte) {
  for (int i = 0; i <= 255; ++i) {
    const float b = float(i);
    const float want = b / 255.0f, got = std::fma(b, kInv255Hi, b * kInv255Lo);
    ASSERT_EQ(std::memcmp(&got, &want, sizeof got), 0) << "byte " << i;
  }
}
