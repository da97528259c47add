// The bilinear kernel divides x = S/256 by 65280 (S = texel·weight sums, integers in
// [0, 255·65536]), and the point kernel bytes b by 255, without a division:
// fma(x, hi, x·lo) with the reciprocal split into two floats hi + lo
// (resource/sampler_kernels.h). That is only allowed because it gives the correctly
// rounded quotient for every such x: checked here over all 16.7 million values (and
// all 256 bytes), against the division itself.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "refx/core/color.h"
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

// The 8-bit output of the bilinear kernel (PreparedSampler::sampleImplicitArgb8) is
// floor(x/256 + 1/2) for x = S/256, computed as one fma in float and truncated; it must
// be the byte the output merger makes of the float result q = x/65280: unorm8(q) =
// trunc(min(max(q, 0), 1)·255 + 0.5) (core/color.h), for every filter sum S. Both sides
// stand for round(S/65536) with ties up (q·255 = S/65536).
TEST(FilterQuotient, ByteOfTheFilterSumIsTheUnorm8OfItsQuotient) {
  long mismatches = 0;
  for (long s = 0; s <= 255L * 65536; ++s) {
    const float x = float(s) / 256.0f;
    const float q = std::fma(x, kInv65280Hi, x * kInv65280Lo);
    const int viaFloat = int(std::fma(x, 1.0f / 256.0f, 0.5f));
    const int want = int(refx::unorm8(q));
    mismatches += viaFloat != want || int((s + 32768) >> 16) != want;
  }
  EXPECT_EQ(mismatches, 0);
}
