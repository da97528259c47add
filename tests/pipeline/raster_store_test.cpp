// The AVX-512 opaque block store (pipeline/raster_store.h) against the conversion it
// implements, lane by lane in scalar floats: a channel c becomes the byte
// trunc(min(max(c, 0), 1) * 255 + 0.5) (NaN as 0), stored as the D3DCOLOR
// a << 24 | r << 16 | g << 8 | b (a = 0xff without alpha) at the lane's pixel of the block;
// the other lanes keep the target's pixel, or get `under` where one is given.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

#include "pipeline/raster_store.h"
#include "refx/core/cpu_features.h"

namespace refx::pipeline {
namespace {

constexpr int kLaneX[kBatchLanes] = {0, 1, 0, 1, 2, 3, 2, 3, 0, 1, 0, 1, 2, 3, 2, 3};
constexpr int kLaneY[kBatchLanes] = {0, 0, 1, 1, 0, 0, 1, 1, 2, 2, 3, 3, 2, 2, 3, 3};

uint32_t unorm8(float c) {
  const float v = std::isnan(c) ? 0.0f : std::fmin(std::fmax(c, 0.0f), 1.0f);
  const float scaled = v * 255.0f;  // two roundings, as the store's vmulps then vaddps
  return uint32_t(scaled + 0.5f);
}

TEST(RasterStore, Avx512BlockStoreConvertsAndMasksAsTheFormula) {
  if (detectedIsa() != CpuIsa::Avx512) GTEST_SKIP() << "no AVX-512 on this CPU";
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> value(-0.5f, 1.5f);
  const float specials[] = {std::numeric_limits<float>::quiet_NaN(), -0.0f, 0.0f, 1.0f, 0.5f / 255.0f,
                            1.5f / 255.0f, std::numeric_limits<float>::infinity(), -1e30f};
  constexpr int kPitch = 40;  // bytes: the block at column 2 of a 10-pixel-wide target
  for (int round = 0; round < 400; ++round) {
    alignas(64) float color[4][kBatchLanes];
    for (int c = 0; c < 4; ++c)
      for (int l = 0; l < kBatchLanes; ++l)
        color[c][l] = rng() % 4 == 0 ? specials[rng() % 8] : value(rng);
    const uint16_t mask = round % 5 == 0 ? 0xffff : uint16_t(rng());
    const bool hasAlpha = round % 2 == 0;
    const bool withUnder = round % 3 == 0;
    const uint32_t under = 0x12345678u;
    uint8_t target[4 * kPitch];
    for (uint8_t& b : target) b = uint8_t(rng());
    uint8_t before[sizeof target];
    std::memcpy(before, target, sizeof target);
    storeOpaqueBlockAvx512(target + 8, kPitch, hasAlpha, mask, color, withUnder ? &under : nullptr);
    for (int l = 0; l < kBatchLanes; ++l) {
      const size_t at = size_t(kLaneY[l]) * kPitch + 8 + size_t(kLaneX[l]) * 4;
      uint32_t got, old;
      std::memcpy(&got, target + at, 4);
      std::memcpy(&old, before + at, 4);
      uint32_t want = withUnder ? under : old;
      if (mask >> l & 1)
        want = (hasAlpha ? unorm8(color[3][l]) << 24 : 0xff000000u) | unorm8(color[0][l]) << 16 |
               unorm8(color[1][l]) << 8 | unorm8(color[2][l]);
      EXPECT_EQ(got, want) << "round " << round << " lane " << l;
      std::memcpy(target + at, &old, 4);  // what remains must be untouched
    }
    EXPECT_EQ(std::memcmp(target, before, sizeof target), 0) << "round " << round;
  }
}

}  // namespace
}  // namespace refx::pipeline
