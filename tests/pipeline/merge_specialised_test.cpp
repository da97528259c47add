// The output merges specialised for common states (chooseMerge) against the generic
// mergeBatch, the reference: random batches (colours in and out of [0,1], NaN, partial
// coverage, batches at the target's edge) must leave identical bytes and depths.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "pipeline/output_merger.h"

using namespace refx;
using namespace refx::pipeline;
using namespace refx::d3d;

namespace {

constexpr int kW = 10, kH = 10;  // not a multiple of 4: edge batches are partly outside

struct Surfaces {
  std::vector<uint8_t> color = std::vector<uint8_t>(size_t(kW) * kH * 4);
  DepthStencilSurface depth{kW, kH};
};

RasterDraw drawFor(const MergeState& m, Surfaces& s, bool hasAlpha) {
  RasterDraw d;
  d.width = kW;
  d.height = kH;
  d.targets[0].data = s.color.data();
  d.targets[0].pitch = kW * 4;
  d.targets[0].hasAlpha = hasAlpha;
  d.targets[0].writeMask = 0xf;
  d.depth = &s.depth;
  d.blend = m.blend;
  d.depthTest = m.depthTest;
  d.depthWrite = m.depthWrite;
  d.depthFunc = m.depthFunc;
  return d;
}

float randomColor(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-0.25f, 1.25f);
  const int pick = int(rng() % 16);
  if (pick == 0) return std::nanf("");
  if (pick == 1) return 0.0f;
  if (pick == 2) return 1.0f;
  if (pick == 3) return float(rng() % 256) / 255.0f;  // exactly on an 8-bit step
  return u(rng);
}

void runCase(const MergeState& m, bool hasAlpha, bool depthAlreadyTested, std::mt19937& rng) {
  const MergeBatchFn specialised = chooseMerge(m);
  ASSERT_NE(specialised, &mergeBatch) << "the state has a specialised merge";
  for (int round = 0; round < 200; ++round) {
    Surfaces reference;
    for (auto& b : reference.color) b = uint8_t(rng());
    for (auto& z : reference.depth.depth) z = float(rng() % 5) / 4.0f;  // ties with the batch's z too
    Surfaces fast = reference;
    const int bx = 4 * int(rng() % 3), by = 4 * int(rng() % 3);
    uint16_t mask = uint16_t(rng());
    for (int l = 0; l < kBatchLanes; ++l)
      if (bx + kLaneX[l] >= kW || by + kLaneY[l] >= kH) mask = uint16_t(mask & ~(1u << l));
    exec::LaneVec4 colors[kMaxRenderTargets]{};
    float z[kBatchLanes];
    for (int l = 0; l < kBatchLanes; ++l) {
      for (int c = 0; c < 4; ++c) colors[0].c[c][l] = randomColor(rng);
      z[l] = float(rng() % 5) / 4.0f;
    }
    const RasterDraw dr = drawFor(m, reference, hasAlpha);
    const RasterDraw df = drawFor(m, fast, hasAlpha);
    mergeBatch(dr, bx, by, mask, colors, z, depthAlreadyTested, false);
    specialised(df, bx, by, mask, colors, z, depthAlreadyTested, false);
    ASSERT_EQ(0, std::memcmp(reference.color.data(), fast.color.data(), reference.color.size()))
        << "colour bytes differ, round " << round;
    ASSERT_EQ(0, std::memcmp(reference.depth.depth.data(), fast.depth.depth.data(),
                             reference.depth.depth.size() * sizeof(float)))
        << "depths differ, round " << round;
  }
}

TEST(MergeSpecialised, SameBytesAndDepthsAsTheGenericMerge) {
  std::mt19937 rng(12345);
  struct BlendCase {
    bool enable;
    uint32_t src, dst;
  };
  const BlendCase blends[] = {{false, BLEND_ONE, BLEND_ZERO},
                              {true, BLEND_SRCALPHA, BLEND_INVSRCALPHA},
                              {true, BLEND_ONE, BLEND_ONE}};
  struct DepthCase {
    bool test, write;
    uint32_t func;
  };
  const DepthCase depths[] = {{false, false, CMP_LESSEQUAL}, {true, false, CMP_LESS}, {true, true, CMP_LESS},
                              {true, false, CMP_LESSEQUAL}, {true, true, CMP_LESSEQUAL}};
  for (const BlendCase& b : blends)
    for (const DepthCase& dc : depths)
      for (bool hasAlpha : {true, false})
        for (bool early : {false, true}) {
          SCOPED_TRACE(testing::Message() << "blend " << b.enable << " " << b.src << "/" << b.dst << ", depth "
                                          << dc.test << " func " << dc.func << " write " << dc.write
                                          << ", alpha " << hasAlpha << ", early " << early);
          MergeState m;
          m.blend = {b.enable, b.src, b.dst, BLENDOP_ADD, b.src, b.dst, BLENDOP_ADD, {}};
          m.depthTest = dc.test;
          m.depthWrite = dc.write;
          m.depthFunc = dc.func;
          m.earlyDepth = early && dc.test;
          m.targets[0] = MergeState::Target::Unorm8Full;
          runCase(m, hasAlpha, m.earlyDepth, rng);
        }
}

TEST(MergeSpecialised, OtherStatesUseTheGenericMerge) {
  MergeState m;
  m.targets[0] = MergeState::Target::Unorm8Full;
  MergeState alpha = m;
  alpha.alphaTest = true;
  EXPECT_EQ(chooseMerge(alpha), &mergeBatch);
  MergeState stencil = m;
  stencil.stencil = true;
  EXPECT_EQ(chooseMerge(stencil), &mergeBatch);
  MergeState greater = m;
  greater.depthTest = true;
  greater.depthFunc = CMP_GREATER;
  EXPECT_EQ(chooseMerge(greater), &mergeBatch);
  MergeState masked = m;
  masked.targets[0] = MergeState::Target::Unorm8Masked;
  EXPECT_EQ(chooseMerge(masked), &mergeBatch);
  MergeState two = m;
  two.targets[1] = MergeState::Target::Unorm8Full;
  EXPECT_EQ(chooseMerge(two), &mergeBatch);
  MergeState subtract = m;
  subtract.blend = {true, BLEND_ONE, BLEND_ONE, BLENDOP_SUBTRACT, BLEND_ONE, BLEND_ONE, BLENDOP_SUBTRACT, {}};
  EXPECT_EQ(chooseMerge(subtract), &mergeBatch);
  MergeState dither = m;
  dither.dither = true;
  EXPECT_EQ(chooseMerge(dither), &mergeBatch);
}

}  // namespace
