// provenQuadRho (pipeline/raster_lod.h): the ranges of ρ² it proves for a primitive's
// quads, worked by hand for affine coordinates, and, for random perspective planes,
// checked against the sampler itself: the group lookups given the proven range sample
// exactly what they sample when they classify every batch's quads.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "pipeline/raster_interpolate.h"
#include "pipeline/output_merger.h"
#include "pipeline/raster_lod.h"
#include "refx/core/batch.h"
#include "refx/core/cpu_features.h"
#include "refx/resource/sampler.h"
#include "refx/resource/texture.h"

namespace refx::pipeline {
namespace {

const float kUnitW[3] = {1, 0, 0};  // 1/w = 1 everywhere

// A range from binade `low` to binade `high`, both ends away from the binades' edges.
void expectRange(const ProvenRho& rho, int low, int high) {
  EXPECT_EQ(rho.low, low);
  EXPECT_EQ(rho.high, high);
  EXPECT_FALSE(rho.lowNearEdge);
  EXPECT_FALSE(rho.highNearEdge);
}

// u = x/128 and v = y/128 on a 256² texture: every difference times the size is 2, so
// ρ² = 2² + 0² = 4 in every quad. The bounds hold 4 with rounding margins on both
// sides: from just below 4 (binade 1, [2, 4)) to just above (binade 2, [4, 8)), far
// from the edges at 2 and 8.
TEST(ProvenQuadRho, AffineCoordinatesOfAKnownScale) {
  const float u[3] = {0, 1.0f / 128, 0}, v[3] = {0, 0, 1.0f / 128};
  expectRange(provenQuadRho(kUnitW, {u, false}, {v, false}, 0.5f, 0.5f, 0, 0, 63, 63, 256, 256), 1, 2);
  // x/256 and y/256: ρ² = 1, between binades -1 and 0.
  const float u1[3] = {0, 1.0f / 256, 0}, v1[3] = {0, 0, 1.0f / 256};
  const ProvenRho one = provenQuadRho(kUnitW, {u1, true}, {v1, true}, 0.5f, 0.5f, 0, 0, 63, 63, 256, 256);
  EXPECT_EQ(one.low, -1);
  EXPECT_EQ(one.high, 0);
  // x/100 and y/300 on 256²: the differences times the size are 2.56 and 0.853..., so
  // ρ² = max(2.56², 0.853²) = 6.5536, inside binade 2 ([4, 8)) and far from its edges.
  const float u2[3] = {0.25f, 1.0f / 100, 0}, v2[3] = {0.75f, 0, 1.0f / 300};
  expectRange(provenQuadRho(kUnitW, {u2, false}, {v2, false}, 10.5f, 20.5f, 8, 16, 39, 47, 256, 256), 2, 2);
}

// 1/w that reaches 0 or below in the region: no bound.
TEST(ProvenQuadRho, NothingWhereOneOverWIsNotPositive) {
  const float invW[3] = {0.5f, -0.02f, 0};  // 0 at x = 25 from the origin
  const float u[3] = {0, 0.01f, 0}, v[3] = {0, 0, 0.01f};
  EXPECT_EQ(provenQuadRho(invW, {u, false}, {v, false}, 0.5f, 0.5f, 0, 0, 31, 31, 256, 256).low, kUnprovenExponent);
  EXPECT_NE(provenQuadRho(invW, {u, false}, {v, false}, 0.5f, 0.5f, 0, 0, 15, 15, 256, 256).low, kUnprovenExponent);
}

// A value plane as the rasterizer evaluates it for a block's lanes (enterBatch's 1/w):
// base + dx·(ox + laneX) + dy·(oy + laneY), in that order.
void evalLanes(const float* plane, float ox, float oy, float* out) {
  for (int l = 0; l < kBatchLanes; ++l) {
    const float fx = ox + float(kLaneX[l]), fy = oy + float(kLaneY[l]);
    out[l] = plane[0] + plane[1] * fx + plane[2] * fy;
  }
}

// Random perspective planes whose ρ² spans the levels of a mipmapped texture, often
// near the edges between them: wherever provenQuadRho proves a range, the lookups
// with it give the same bits as without it, block group by block group.
TEST(ProvenQuadRho, LookupsWithTheProvenRangeSampleWhatClassifyingGives) {
  auto tex = Texture::create2D(Format::A8R8G8B8, 256, 128, 0);
  std::mt19937 rng(20261129);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 256; ++x) tex->setTexel(0, 0, x, y, 0, {unit(rng), unit(rng), unit(rng), unit(rng)});
  tex->generateMips();
  SamplerState state;
  state.minFilter = state.magFilter = TextureFilter::Linear;
  state.mipFilter = TextureFilter::Point;
  const PreparedSampler sampler(*tex, state);
  float width = 0, height = 0;
  if (!sampler.levelZeroSize(width, height)) GTEST_SKIP() << "the group lookups take no proven range here";
  ASSERT_EQ(width, 256.0f);
  ASSERT_EQ(height, 128.0f);
  const InterpolateInputsFn interpolate = chooseInterpolateInputs();
  // The level of binade e as the lookups choose it (MIPFILTER POINT, levels 0..8, LINEAR
  // both ways): the nearest to λ = log2(ρ), which lies in [e/2, (e + 1)/2).
  const auto level = [&](int e) { return std::clamp((e + 1) >> 1, 0, tex->levelCount() - 1); };
  int proven = 0, groups = 0, oneLevel = 0;
  for (int trial = 0; trial < 6000; ++trial) {
    float invW[3], planes[6];  // planes: u then v, value/w planes
    if (trial % 2 == 0) {
      // 1/w near 1 with a slope; u and v of a scale 2^s texels per pixel, s in [-2, 5].
      const float scale = std::exp2(unit(rng) * 7.0f - 2.0f) / 256.0f;
      invW[0] = 0.6f + unit(rng), invW[1] = (unit(rng) - 0.5f) * 0.01f, invW[2] = (unit(rng) - 0.5f) * 0.01f;
      for (int c = 0; c < 2; ++c) {
        planes[3 * c] = (unit(rng) - 0.5f) * 4.0f;
        planes[3 * c + 1] = (unit(rng) - 0.5f) * 2.0f * scale;
        planes[3 * c + 2] = (unit(rng) - 0.5f) * 2.0f * scale;
      }
    } else {
      // Coordinates far from 0 (their roundings are large against their differences)
      // whose ρ² lies within 1% of a level's edge, 2 or 8: only the bounds' margins
      // for rounding keep these apart.
      const float edge = trial % 4 == 1 ? 2.0f : 8.0f;
      const float rho = std::sqrt(edge * (1.0f + (unit(rng) - 0.5f) * 0.02f));
      invW[0] = 1, invW[1] = 0, invW[2] = 0;
      planes[0] = (unit(rng) - 0.5f) * 4000.0f, planes[1] = rho / 256.0f, planes[2] = 0;
      planes[3] = (unit(rng) - 0.5f) * 4000.0f, planes[4] = 0, planes[5] = 0.5f * rho / 128.0f;
    }
    const float originX = unit(rng) * 40.0f, originY = unit(rng) * 40.0f;
    const int x0 = 4 * int(unit(rng) * 8), y0 = 4 * int(unit(rng) * 8);
    const int blocksX = 1 + int(unit(rng) * 4), blocksY = 1 + int(unit(rng) * 3);
    const int x1 = x0 + 4 * blocksX - 1, y1 = y0 + 4 * blocksY - 1;
    const ProvenRho rho = provenQuadRho(invW, {planes, false}, {planes + 3, false}, originX, originY, x0, y0, x1, y1,
                                        width, height);
    if (rho.low == kUnprovenExponent) continue;
    ++proven;
    // Ranges of one level: the lookups then use it instead of classifying.
    const bool one = level(rho.low) == level(rho.high) && (!rho.lowNearEdge || level(rho.low - 1) == level(rho.low)) &&
                     (!rho.highNearEdge || level(rho.high + 1) == level(rho.high));
    // Every block of the region, in groups of up to four, as the rasterizer groups them.
    std::vector<std::array<int, 2>> blocks;
    for (int by = y0; by < y1; by += 4)
      for (int bx = x0; bx < x1; bx += 4) blocks.push_back({bx, by});
    for (size_t first = 0; first < blocks.size(); first += kMaxSampleGroup) {
      const int count = int(std::min<size_t>(kMaxSampleGroup, blocks.size() - first));
      alignas(64) float coords[kMaxSampleGroup][3][kBatchLanes] = {};
      alignas(64) float withRange[kMaxSampleGroup][4][kBatchLanes], classified[kMaxSampleGroup][4][kBatchLanes];
      SampleBatch a[kMaxSampleGroup], b[kMaxSampleGroup];
      uint16_t masks[kMaxSampleGroup];
      for (int g = 0; g < count; ++g) {
        const float ox = float(blocks[first + size_t(g)][0]) - originX;
        const float oy = float(blocks[first + size_t(g)][1]) - originY;
        alignas(64) float laneInvW[kBatchLanes], w[kBatchLanes];
        evalLanes(invW, ox, oy, laneInvW);
        const InputTarget targets[2] = {{coords[g][0], false}, {coords[g][1], false}};
        interpolate(planes, targets, 2, ox, oy, laneInvW, w);
        a[g] = {coords[g], withRange[g]};
        b[g] = {coords[g], classified[g]};
        masks[g] = 0xffff;
      }
      sampler.sampleImplicitGroup(count, masks, a, rho);
      sampler.sampleImplicitGroup(count, masks, b);
      ++groups;
      oneLevel += one;
      ASSERT_EQ(std::memcmp(withRange, classified, sizeof(float) * 4 * kBatchLanes * size_t(count)), 0)
          << "trial " << trial << " range " << rho.low << ".." << rho.high;
    }
  }
  // Most random regions get a bound (1/w stays positive over them).
  EXPECT_GT(proven, 4000);
  EXPECT_GT(groups, 4000);
  EXPECT_GT(oneLevel, 2000) << "of " << groups;
}

}  // namespace
}  // namespace refx::pipeline
