// The output merges specialised for common states (chooseMerge) against the generic
// mergeBatch, the reference: random batches (colours in and out of [0,1], NaN, partial
// coverage, batches at the target's edge) must leave identical bytes and depths. The
// same for the early depth tests chooseEarlyDepthTest picks against earlyDepthTest.
#include <gtest/gtest.h>

#include <algorithm>
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

// The alpha test of a case (MergeState fixes only whether there is one).
struct AlphaTest {
  uint32_t func = CMP_ALWAYS;
  uint8_t ref = 0;
};

RasterDraw drawFor(const MergeState& m, const AlphaTest& alpha, Surfaces& s, bool hasAlpha) {
  RasterDraw d;
  d.width = kW;
  d.height = kH;
  d.targets[0].data = s.color.data();
  d.targets[0].pitch = kW * 4;
  d.targets[0].hasAlpha = hasAlpha;
  d.targets[0].writeMask = 0xf;
  d.depth = &s.depth;
  d.blend = m.blend;
  d.alphaTest = m.alphaTest;
  d.alphaFunc = alpha.func;
  d.alphaRef = alpha.ref;
  d.depthTest = m.depthTest;
  d.depthWrite = m.depthWrite;
  d.depthFunc = m.depthFunc;
  d.earlyDepth = m.earlyDepth;
  return d;
}

float randomColor(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-0.25f, 1.25f);
  const int pick = int(rng() % 16);
  if (pick == 0) return std::nanf("");
  if (pick == 1) return 0.0f;
  if (pick == 2) return 1.0f;
  if (pick == 3) return float(rng() % 256) / 255.0f;  // exactly on an 8-bit step
  if (pick == 4) return -0.0f;
  return u(rng);
}

// A batch's depth: one of the stored depths' values (ties), sometimes NaN (which fails
// every comparison but NOTEQUAL and ALWAYS).
float randomDepth(std::mt19937& rng) { return rng() % 8 == 0 ? std::nanf("") : float(rng() % 5) / 4.0f; }

// A random batch position and coverage: a quarter of the batches fully covered
// (where inside the target), the lanes outside the target never live.
void randomBatch(std::mt19937& rng, int& bx, int& by, uint16_t& mask) {
  bx = 4 * int(rng() % 3);
  by = 4 * int(rng() % 3);
  mask = rng() % 4 == 0 ? 0xffff : uint16_t(rng());
  for (int l = 0; l < kBatchLanes; ++l)
    if (bx + kLaneX[l] >= kW || by + kLaneY[l] >= kH) mask = uint16_t(mask & ~(1u << l));
}

void randomSurfaces(std::mt19937& rng, Surfaces& s) {
  for (auto& b : s.color) b = uint8_t(rng());
  for (auto& z : s.depth.depth) z = float(rng() % 5) / 4.0f;  // ties with the batch's z too
}

void runCase(const MergeState& m, AlphaTest alpha, bool hasAlpha, std::mt19937& rng) {
  const MergeBatchFn specialised = chooseMerge(m);
  ASSERT_NE(specialised, &mergeBatch) << "the state has a specialised merge";
  for (int round = 0; round < 200; ++round) {
    Surfaces reference;
    randomSurfaces(rng, reference);
    Surfaces fast = reference;
    int bx, by;
    uint16_t mask;
    randomBatch(rng, bx, by, mask);
    exec::LaneVec4 colors[kMaxRenderTargets]{};
    float z[kBatchLanes];
    for (int l = 0; l < kBatchLanes; ++l) {
      for (int c = 0; c < 4; ++c) colors[0].c[c][l] = randomColor(rng);
      z[l] = randomDepth(rng);
    }
    if (m.alphaTest) alpha.ref = uint8_t(rng());
    const RasterDraw dr = drawFor(m, alpha, reference, hasAlpha);
    const RasterDraw df = drawFor(m, alpha, fast, hasAlpha);
    mergeBatch(dr, bx, by, mask, colors, z, m.earlyDepth, false);
    specialised(df, bx, by, mask, colors, z, m.earlyDepth, false);
    ASSERT_EQ(0, std::memcmp(reference.color.data(), fast.color.data(), reference.color.size()))
        << "colour bytes differ, round " << round;
    ASSERT_EQ(0, std::memcmp(reference.depth.depth.data(), fast.depth.depth.data(),
                             reference.depth.depth.size() * sizeof(float)))
        << "depths differ, round " << round;
  }
}

struct BlendCase {
  bool enable;
  uint32_t src, dst;
};
constexpr BlendCase kBlends[] = {{false, BLEND_ONE, BLEND_ZERO},
                                 {true, BLEND_SRCALPHA, BLEND_INVSRCALPHA},
                                 {true, BLEND_BOTHSRCALPHA, BLEND_ZERO},  // = SRCALPHA/INVSRCALPHA
                                 {true, BLEND_ONE, BLEND_ONE},
                                 {true, BLEND_ZERO, BLEND_SRCCOLOR},
                                 {true, BLEND_DESTCOLOR, BLEND_ZERO},
                                 {true, BLEND_DESTCOLOR, BLEND_SRCCOLOR},
                                 {true, BLEND_SRCALPHA, BLEND_ONE}};
struct DepthCase {
  bool test, write;
  uint32_t func;
};
constexpr DepthCase kDepths[] = {{false, false, CMP_LESSEQUAL}, {true, false, CMP_LESS},
                                 {true, true, CMP_LESS},        {true, false, CMP_LESSEQUAL},
                                 {true, true, CMP_LESSEQUAL},   {true, false, CMP_GREATER},
                                 {true, true, CMP_GREATER},     {true, true, CMP_GREATEREQUAL},
                                 {true, false, CMP_EQUAL},      {true, true, CMP_EQUAL}};

TEST(MergeSpecialised, SameBytesAndDepthsAsTheGenericMerge) {
  std::mt19937 rng(12345);
  for (const BlendCase& b : kBlends)
    for (const DepthCase& dc : kDepths)
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
          runCase(m, {}, hasAlpha, rng);
        }
}

// The destination's bytes as the generic merge reads them (b / 255.0f), to the bit: with
// ONE/ONE each byte b is added to sources spaced one float step of b / 255 apart around
// 0.5 / 255, where the sum rounds to b or b + 1, so a destination value one step off
// moves a lane across the boundary.
TEST(MergeSpecialised, DestinationBytesReadExactly) {
  MergeState m;
  m.blend = {true, BLEND_ONE, BLEND_ONE, BLENDOP_ADD, BLEND_ONE, BLEND_ONE, BLENDOP_ADD, {}};
  m.targets[0] = MergeState::Target::Unorm8Full;
  const MergeBatchFn specialised = chooseMerge(m);
  ASSERT_NE(specialised, &mergeBatch);
  for (int b = 0; b < 256; ++b) {
    Surfaces reference;
    std::fill(reference.color.begin(), reference.color.end(), uint8_t(b));
    Surfaces fast = reference;
    const float d = float(b) / 255.0f;
    const float step = std::nextafter(d + 0.5f / 255.0f, 2.0f) - (d + 0.5f / 255.0f);
    exec::LaneVec4 colors[kMaxRenderTargets]{};
    for (int l = 0; l < kBatchLanes; ++l)
      for (int c = 0; c < 4; ++c) colors[0].c[c][l] = 0.5f / 255.0f + float(l - 8) * step;
    float z[kBatchLanes] = {};
    const RasterDraw dr = drawFor(m, {}, reference, true);
    const RasterDraw df = drawFor(m, {}, fast, true);
    mergeBatch(dr, 0, 0, 0xffff, colors, z, false, false);
    specialised(df, 0, 0, 0xffff, colors, z, false, false);
    ASSERT_EQ(0, std::memcmp(reference.color.data(), fast.color.data(), reference.color.size()))
        << "destination byte " << b;
  }
}

TEST(MergeSpecialised, AlphaTestSameAsTheGenericMerge) {
  std::mt19937 rng(777);
  for (uint32_t func = CMP_NEVER; func <= CMP_ALWAYS; ++func)
    for (const BlendCase& b : {kBlends[0], kBlends[1], kBlends[4]})
      for (const DepthCase& dc : {kDepths[0], kDepths[4], kDepths[7]}) {
        SCOPED_TRACE(testing::Message() << "alpha func " << func << ", blend " << b.enable << " " << b.src << "/"
                                        << b.dst << ", depth " << dc.test << " func " << dc.func);
        MergeState m;
        m.alphaTest = true;
        m.blend = {b.enable, b.src, b.dst, BLENDOP_ADD, b.src, b.dst, BLENDOP_ADD, {}};
        m.depthTest = dc.test;
        m.depthWrite = dc.write;
        m.depthFunc = dc.func;
        m.targets[0] = MergeState::Target::Unorm8Full;
        runCase(m, {func, 0}, true, rng);
      }
}

TEST(MergeSpecialised, EarlyDepthTestSameAsTheGenericOne) {
  std::mt19937 rng(4242);
  for (const DepthCase& dc : kDepths) {
    if (!dc.test) continue;
    SCOPED_TRACE(testing::Message() << "depth func " << dc.func << " write " << dc.write);
    const EarlyDepthFn specialised = chooseEarlyDepthTest(dc.func, dc.write);
    ASSERT_NE(specialised, &earlyDepthTest);
    for (int round = 0; round < 300; ++round) {
      Surfaces reference;
      randomSurfaces(rng, reference);
      Surfaces fast = reference;
      int bx, by;
      uint16_t mask;
      randomBatch(rng, bx, by, mask);
      float z[kBatchLanes];
      for (float& v : z) v = randomDepth(rng);
      MergeState m;
      m.depthTest = true;
      m.depthWrite = dc.write;
      m.depthFunc = dc.func;
      const RasterDraw dr = drawFor(m, {}, reference, true);
      const RasterDraw df = drawFor(m, {}, fast, true);
      ASSERT_EQ(earlyDepthTest(dr, bx, by, mask, z, dc.write), specialised(df, bx, by, mask, z, dc.write))
          << "passing lanes differ, round " << round;
      ASSERT_EQ(0, std::memcmp(reference.depth.depth.data(), fast.depth.depth.data(),
                               reference.depth.depth.size() * sizeof(float)))
          << "depths differ, round " << round;
    }
  }
  EXPECT_EQ(chooseEarlyDepthTest(CMP_NOTEQUAL, true), &earlyDepthTest);
}

TEST(MergeSpecialised, OtherStatesUseTheGenericMerge) {
  MergeState m;
  m.targets[0] = MergeState::Target::Unorm8Full;
  MergeState stencil = m;
  stencil.stencil = true;
  EXPECT_EQ(chooseMerge(stencil), &mergeBatch);
  MergeState notEqual = m;
  notEqual.depthTest = true;
  notEqual.depthFunc = CMP_NOTEQUAL;
  EXPECT_EQ(chooseMerge(notEqual), &mergeBatch);
  MergeState masked = m;
  masked.targets[0] = MergeState::Target::Unorm8Masked;
  EXPECT_EQ(chooseMerge(masked), &mergeBatch);
  MergeState floatTarget = m;
  floatTarget.targets[0] = MergeState::Target::Float;
  EXPECT_EQ(chooseMerge(floatTarget), &mergeBatch);
  MergeState two = m;
  two.targets[1] = MergeState::Target::Unorm8Full;
  EXPECT_EQ(chooseMerge(two), &mergeBatch);
  MergeState subtract = m;
  subtract.blend = {true, BLEND_ONE, BLEND_ONE, BLENDOP_SUBTRACT, BLEND_ONE, BLEND_ONE, BLENDOP_SUBTRACT, {}};
  EXPECT_EQ(chooseMerge(subtract), &mergeBatch);
  MergeState separate = m;
  separate.blend = {true, BLEND_ONE, BLEND_ONE, BLENDOP_ADD, BLEND_ZERO, BLEND_ONE, BLENDOP_ADD, {}};
  EXPECT_EQ(chooseMerge(separate), &mergeBatch);
  MergeState factor = m;
  factor.blend = {true, BLEND_BLENDFACTOR, BLEND_ZERO, BLENDOP_ADD, BLEND_BLENDFACTOR, BLEND_ZERO, BLENDOP_ADD, {}};
  EXPECT_EQ(chooseMerge(factor), &mergeBatch);
  MergeState dither = m;
  dither.dither = true;
  EXPECT_EQ(chooseMerge(dither), &mergeBatch);
  MergeState srgb = m;
  srgb.srgbWrite = true;
  EXPECT_EQ(chooseMerge(srgb), &mergeBatch);
}

}  // namespace
