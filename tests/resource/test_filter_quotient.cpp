// The bilinear kernel divides x = S/256 by 65280 (S = texel·weight sums, integers in
// [0, 255·65536]) with a multiply and one fma correction step instead of a division.
// That is only allowed because it gives the correctly rounded quotient for every such
// x: checked here over all 16.7 million values.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

TEST(FilterQuotient, ReciprocalWithFmaCorrectionEqualsDivisionForEveryFilterSum) {
  const float b = 65280.0f, r = 1.0f / 65280.0f;
  long mismatches = 0;
  for (long s = 0; s <= 255L * 65536; ++s) {
    const float x = float(s) / 256.0f;  // exact: s < 2^24
    const float want = x / b;
    const float q = x * r;
    const float got = std::fma(std::fma(-q, b, x), r, q);
    mismatches += std::memcmp(&got, &want, sizeof got) != 0;
  }
  EXPECT_EQ(mismatches, 0);
}
