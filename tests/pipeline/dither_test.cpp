// Ordered dithering of 8-bit writes (D3DRS_DITHERENABLE): floor(v*255 + (B + 0.5)/16)
// with B the 4x4 Bayer entry of the pixel, against round-to-nearest without it.
#include <gtest/gtest.h>

#include "pipeline/output_merger.h"

namespace refx::pipeline {
namespace {

TEST(Dither, FractionOfAStepBecomesThatShareOfPixels) {
  // v*255 = 100 + m/16: a pixel gets 101 iff m/16 + (B + 0.5)/16 >= 1, i.e. B >= 16 - m
  // (B + 0.5 >= 16 - m for integer B), which m of the 16 entries 0..15 are. The mean
  // over a 4x4 block is therefore 100 + m/16: the value itself.
  for (int m = 0; m < 16; ++m) {
    const float v = (100.0f + float(m) / 16.0f) / 255.0f;
    int above = 0;
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x) {
        const uint8_t q = quantizeUnorm8(v, true, x, y);
        ASSERT_TRUE(q == 100 || q == 101) << "m " << m << " at " << x << "," << y << ": " << int(q);
        above += q == 101;
      }
    EXPECT_EQ(above, m) << "m = " << m;
  }
}

TEST(Dither, PatternRepeatsEveryFourPixels) {
  const float v = 100.5f / 255.0f;  // B >= 8: 101 where x + y is odd (see the matrix)
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      EXPECT_EQ(quantizeUnorm8(v, true, x, y), (x + y) % 2 ? 101 : 100) << x << "," << y;
}

TEST(Dither, EndsAndWholeStepsAreKept) {
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      EXPECT_EQ(quantizeUnorm8(0.0f, true, x, y), 0);
      EXPECT_EQ(quantizeUnorm8(-3.0f, true, x, y), 0);
      EXPECT_EQ(quantizeUnorm8(1.0f, true, x, y), 255);
      EXPECT_EQ(quantizeUnorm8(7.0f, true, x, y), 255);
      EXPECT_EQ(quantizeUnorm8(254.0f / 255.0f, true, x, y), 254);
      EXPECT_EQ(quantizeUnorm8(37.0f / 255.0f, true, x, y), 37);
    }
}

TEST(Dither, WithoutItRoundsToNearest) {
  // 100.25 -> 100 and 100.75 -> 101 at every pixel.
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      EXPECT_EQ(quantizeUnorm8(100.25f / 255.0f, false, x, y), 100);
      EXPECT_EQ(quantizeUnorm8(100.75f / 255.0f, false, x, y), 101);
    }
}

}  // namespace
}  // namespace refx::pipeline
