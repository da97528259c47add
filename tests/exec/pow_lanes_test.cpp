// D3D pow as refx evaluates it (exec/lane_math.h powLanes): |x|^y rounded once to
// float, C's special cases, and the same bits at both vector widths.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "exec/lane_math.h"
#include "refx/core/cpu_features.h"

namespace refx::exec {
namespace {

constexpr int N = 16;

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// |x|^y correctly rounded to float: long double's pow (64-bit significand) rounded once.
// It differs from the correctly rounded value only where |x|^y lies within about 2^-60
// of a midpoint between two floats, which none of the inputs below do.
float roundedPower(float x, float y) {
  return static_cast<float>(std::pow(std::fabs(static_cast<long double>(x)), static_cast<long double>(y)));
}

// Random lanes: bases in [0, 1) with the exponents of specular powers (0 … 128), bases
// in (-4, 4) with exponents in (-8, 8), and arbitrary bit patterns of finite floats
// for the base with exponents of magnitude 2^-6 … 2^5.
void randomLanes(std::mt19937& rng, float (&x)[N], float (&y)[N]) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), power(0.0f, 128.0f), base(-4.0f, 4.0f), small(-8.0f, 8.0f);
  std::uniform_int_distribution<uint32_t> bits;
  for (int l = 0; l < N; ++l) {
    switch (l % 3) {
      case 0: x[l] = unit(rng), y[l] = power(rng); break;
      case 1: x[l] = base(rng), y[l] = small(rng); break;
      default: {
        uint32_t b = bits(rng) & 0x7f7fffffu;  // finite
        std::memcpy(&x[l], &b, sizeof b);
        const uint32_t e = bits(rng);
        const uint32_t yb = (e & 0x807fffffu) | ((e >> 23) % 12 + 121) << 23;
        std::memcpy(&y[l], &yb, sizeof yb);
      }
    }
  }
}

TEST(PowLanes, CorrectlyRoundedPowers) {
  std::mt19937 rng(2026);
  float x[N], y[N], r[N];
  int wrong = 0;
  for (int batch = 0; batch < 20000; ++batch) {
    randomLanes(rng, x, y);
    detail::powLanes(x, y, nullptr, r, 0);
    for (int l = 0; l < N; ++l) {
      const float want = roundedPower(x[l], y[l]);
      if (!sameBits(r[l], want) && ++wrong <= 5)
        ADD_FAILURE() << std::hexfloat << "pow(" << x[l] << ", " << y[l] << ") = " << r[l] << ", want " << want;
    }
  }
  EXPECT_EQ(wrong, 0);
}

TEST(PowLanes, ExactPowersAndTheEdgesOfTheRange) {
  // Powers whose value is a float: the correctly rounded result is that float.
  const float x[N] = {2, 4, 0.5f, -3, 10, 9, 2, 2, 2, 2, 0.5f, 1.5f, 0.25f, 16, 2, 0.75f};
  const float y[N] = {10, 0.5f, 3, 2, 3, -0.5f, -126, -149, -150, 127, -127, 2, -2, 0.25f, 128, 1};
  const float want[N] = {
      1024.0f,                // 2^10
      2.0f,                   // √4
      0.125f,                 // 0.5^3
      9.0f,                   // |−3|² (D3D's pow reads |x|)
      1000.0f,                // 10^3
      1.0f / 3.0f,            // 9^-½ = 1/3, the float nearest to it
      0x1p-126f,              // the smallest normal float
      0x1p-149f,              // the smallest subnormal
      0.0f,                   // 2^-150: halfway to 2^-149, ties to even (0)
      0x1p127f,               // the largest power of two
      0x1p127f,               // 0.5^-127
      2.25f,                  // 1.5²
      16.0f,                  // 0.25^-2
      2.0f,                   // 16^¼
      INFINITY,               // 2^128 overflows
      0.75f,                  // x^1 = x
  };
  float r[N];
  detail::powLanes(x, y, nullptr, r, 0);
  for (int l = 0; l < N; ++l) EXPECT_TRUE(sameBits(r[l], want[l])) << "lane " << l << ": pow(" << x[l] << ", " << y[l] << ") = " << std::hexfloat << r[l];
}

TEST(PowLanes, SpecialCasesAsC) {
  const float nan = std::nanf("");
  const float x[N] = {0, nan, 1, -1, 0, -0.0f, INFINITY, -INFINITY, 0.5f, 0.5f, 2, 2, nan, 2, 0, INFINITY};
  const float y[N] = {0, -0.0f, nan, nan, -1, 2, -1, 2, INFINITY, -INFINITY, INFINITY, -INFINITY, 1, nan, -INFINITY, -INFINITY};
  const float want[N] = {1, 1, 1, 1, INFINITY, 0, 0, INFINITY, 0, INFINITY, INFINITY, 0, nan, nan, INFINITY, 0};
  float r[N];
  detail::powLanes(x, y, nullptr, r, 0);
  for (int l = 0; l < N; ++l) {
    if (std::isnan(want[l])) EXPECT_TRUE(std::isnan(r[l])) << "lane " << l;
    else EXPECT_TRUE(sameBits(r[l], want[l])) << "lane " << l << ": pow(" << x[l] << ", " << y[l] << ") = " << r[l];
  }
}

// One whole exponent 2, 3 or 4 for every lane (HLSL's pow(x, 3)) is computed as
// products: still the correctly rounded power, exact midpoints rounded to even.
TEST(PowLanes, WholeExponentsOfAllLanes) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> base(-2.0f, 2.0f);
  float x[N], y[N], r[N];
  for (int batch = 0; batch < 6000; ++batch) {
    const float n = float(2 + batch % 3);
    for (int l = 0; l < N; ++l) x[l] = base(rng), y[l] = n;
    detail::powLanes(x, y, nullptr, r, 0);
    for (int l = 0; l < N; ++l)
      ASSERT_TRUE(sameBits(r[l], roundedPower(x[l], n))) << std::hexfloat << "pow(" << x[l] << ", " << n << ") = " << r[l];
  }
  // 4097² = 16785409 = 2^24 + 8193 lies halfway between the floats 16785408 and
  // 16785410: ties to even give 16785408 (significand 8392704, even).
  for (int l = 0; l < N; ++l) x[l] = 4097.0f, y[l] = 2.0f;
  x[1] = -0.0f, x[2] = INFINITY, x[3] = 1e30f;  // 0, inf, and 1e60 overflowing to inf
  detail::powLanes(x, y, nullptr, r, 0);
  EXPECT_EQ(r[0], 16785408.0f);
  EXPECT_TRUE(sameBits(r[1], 0.0f));
  EXPECT_EQ(r[2], INFINITY);
  EXPECT_EQ(r[3], INFINITY);
}

// A batch without a lane for the general evaluation: saturated dot products of 0
// raised to powers, and 1 to NaN.
TEST(PowLanes, BatchOfSpecialLanesOnly) {
  float x[N], y[N], r[N];
  for (int l = 0; l < N; ++l) x[l] = l % 2 ? 0.0f : -0.0f, y[l] = float(l % 4) - 1.0f;  // -1, 0, 1, 2
  x[15] = 1.0f, y[15] = std::nanf("");
  detail::powLanes(x, y, nullptr, r, 0);
  for (int l = 0; l < 15; ++l) {
    const float want = y[l] < 0 ? INFINITY : y[l] == 0 ? 1.0f : 0.0f;  // 0^-1 = inf, 0^0 = 1, 0^y = +0
    EXPECT_TRUE(sameBits(r[l], want)) << "lane " << l << ": pow(" << x[l] << ", " << y[l] << ") = " << r[l];
  }
  EXPECT_EQ(r[15], 1.0f);
}

// Both widths give the same bits, specials mixed into general lanes included.
TEST(PowLanes, BothWidthsAgree) {
  if (detectedIsa() != CpuIsa::Avx512) GTEST_SKIP() << "no AVX-512 on this CPU";
  std::mt19937 rng(9);
  float x[N], y[N], narrow[N], wide[N];
  const float specials[] = {0, -0.0f, 1, INFINITY, std::nanf("")};
  for (int batch = 0; batch < 20000; ++batch) {
    randomLanes(rng, x, y);
    if (batch % 4 == 0) x[batch % N] = specials[batch / 4 % 5];
    if (batch % 4 == 1) y[batch % N] = specials[batch / 4 % 5];
    detail::powLanesAvx2(x, y, narrow);
    detail::powLanesAvx512(x, y, wide);
    ASSERT_EQ(std::memcmp(narrow, wide, sizeof wide), 0) << "batch " << batch;
  }
}

}  // namespace
}  // namespace refx::exec
