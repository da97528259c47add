// Sampler tests: expected values are worked out by hand from the D3D9 rules
// (reference/fixed-function.md §9 sampling, §10 cube maps); the formula is next to
// each value.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <cstring>
#include <functional>
#include <random>

#include "refx/resource/sampler.h"
#include "resource/sampler_internal.h"

namespace refx {
namespace {

using namespace resource;

constexpr int N = kBatchLanes;
constexpr float kEps = 1e-5f;

// A8R8G8B8 as a little-endian DWORD 0xAARRGGBB.
uint32_t argb(int a, int r, int g, int b) {
  return (uint32_t(a) << 24) | (uint32_t(r) << 16) | (uint32_t(g) << 8) | uint32_t(b);
}

// Writes every texel of one face/level of an A8R8G8B8 texture.
void fill(Texture& t, int face, int level, const std::function<uint32_t(int, int, int)>& f) {
  uint8_t* p = t.data(face, level);
  const int w = t.width(level), h = t.height(level), d = t.depth(level);
  for (int z = 0; z < d; ++z)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        uint32_t v = f(x, y, z);
        std::memcpy(p + ((size_t(z) * h + y) * w + x) * 4, &v, 4);
      }
  t.markDirty();
}

// Mip chain whose level L is solid (r = 80·L, g = 0, b = 0, a = 255).
TexturePtr solidLevels2D(int size) {
  auto t = Texture::create2D(Format::A8R8G8B8, size, size, 0);
  for (int l = 0; l < t->levelCount(); ++l)
    fill(*t, 0, l, [&](int, int, int) { return argb(255, 80 * l, 0, 0); });
  return t;
}

struct Batch {
  float u[N] = {}, v[N] = {}, w[N] = {}, lod[N] = {};
  float ddx[3][N] = {}, ddy[3][N] = {};
  float out[4][N] = {};
  SampleRequest req(LodMode mode = LodMode::Explicit, uint16_t mask = 0xffff) const {
    SampleRequest r;
    r.u = u, r.v = v, r.w = w, r.lod = lod, r.lodMode = mode, r.laneMask = mask;
    for (int i = 0; i < 3; ++i) r.ddx[i] = ddx[i], r.ddy[i] = ddy[i];
    return r;
  }
  // Samples with sampleTexture and checks that the scalar reference path agrees.
  void run(const Texture& t, const SamplerState& s, LodMode mode = LodMode::Explicit,
           uint16_t mask = 0xffff) {
    SampleRequest r = req(mode, mask);
    sampleTexture(t, s, r, out);
    float ref[4][N];
    sampleTextureReference(t, s, r, ref);
    for (int ch = 0; ch < 4; ++ch)
      for (int l = 0; l < N; ++l) EXPECT_EQ(out[ch][l], ref[ch][l]) << "ch " << ch << " lane " << l;
  }
  // Four quads, each with top-left (u0,v0), stepping du per pixel in x and dv in y.
  void quads(float u0, float v0, float du, float dv) {
    for (int l = 0; l < N; ++l) {
      u[l] = u0 + du * float(l & 1);
      v[l] = v0 + dv * float((l >> 1) & 1);
    }
  }
};

SamplerState linearState() {
  SamplerState s;
  s.magFilter = s.minFilter = TextureFilter::Linear;
  return s;
}

// ---------------------------------------------------------------- addressing

// A 4-texel row, texel i has r = 40 + 40·i. u_k = -1 + 0.25·k + 0.125 (k = 0..15) puts
// u·4 at -3.5, -2.5, ... 11.5, so POINT picks texel floor(u·4) = k - 4 before addressing.
class AddressModes : public ::testing::Test {
 protected:
  void SetUp() override {
    tex = Texture::create2D(Format::A8R8G8B8, 4, 1);
    fill(*tex, 0, 0, [](int x, int, int) { return argb(255, 40 + 40 * x, 0, 0); });
    for (int k = 0; k < N; ++k) b.u[k] = -1.0f + 0.25f * float(k) + 0.125f, b.v[k] = 0.5f;
  }
  // expected texel index per lane, -1 = border color
  void check(TextureAddress mode, const int (&expected)[N]) {
    SamplerState s;
    s.addressU = mode;
    s.addressV = TextureAddress::Clamp;
    s.borderColor = {0.2f, 0.4f, 0.6f, 0.8f};
    b.run(*tex, s);
    for (int k = 0; k < N; ++k) {
      SCOPED_TRACE("lane " + std::to_string(k) + " u " + std::to_string(b.u[k]));
      if (expected[k] < 0) {
        EXPECT_NEAR(b.out[0][k], 0.2f, kEps);
        EXPECT_NEAR(b.out[1][k], 0.4f, kEps);
        EXPECT_NEAR(b.out[3][k], 0.8f, kEps);
      } else {
        EXPECT_FLOAT_EQ(b.out[0][k], float(40 + 40 * expected[k]) / 255.0f);
        EXPECT_FLOAT_EQ(b.out[1][k], 0.0f);
        EXPECT_FLOAT_EQ(b.out[3][k], 1.0f);
      }
    }
  }
  TexturePtr tex;
  Batch b;
};

TEST_F(AddressModes, Wrap) {
  // (k - 4) mod 4
  check(TextureAddress::Wrap, {0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3});
}

TEST_F(AddressModes, Mirror) {
  // t = u - 2·floor(u/2); u' = t <= 1 ? t : 2 - t. u = -0.875: t = 1.125, u' = 0.875 -> 3.
  check(TextureAddress::Mirror, {3, 2, 1, 0, 0, 1, 2, 3, 3, 2, 1, 0, 0, 1, 2, 3});
}

TEST_F(AddressModes, Clamp) {
  // clamp(floor(u·4), 0, 3)
  check(TextureAddress::Clamp, {0, 0, 0, 0, 0, 1, 2, 3, 3, 3, 3, 3, 3, 3, 3, 3});
}

TEST_F(AddressModes, Border) {
  // outside [0,1) -> border color
  check(TextureAddress::Border, {-1, -1, -1, -1, 0, 1, 2, 3, -1, -1, -1, -1, -1, -1, -1, -1});
}

TEST_F(AddressModes, MirrorOnce) {
  // u' = clamp(|u|, 0, 1): u = -0.875 -> 0.875 -> 3; u >= 1 -> edge texel 3.
  check(TextureAddress::MirrorOnce, {3, 2, 1, 0, 0, 1, 2, 3, 3, 3, 3, 3, 3, 3, 3, 3});
}

TEST_F(AddressModes, InvalidModeActsAsWrap) {
  check(TextureAddress(0), {0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3});
}

TEST(Sampler, BorderColorIsFilteredWithEdgeTexels) {
  auto tex = Texture::create2D(Format::A8R8G8B8, 4, 1);
  fill(*tex, 0, 0, [](int x, int, int) { return argb(255, 200, 100, 0); });
  SamplerState s = linearState();
  s.addressU = TextureAddress::Border;
  s.addressV = TextureAddress::Clamp;
  s.borderColor = {0.0f, 1.0f, 0.5f, 0.0f};
  Batch b;
  b.u[0] = 0.0f;  // x = 0·4 - 0.5 = -0.5: texels -1 (border) and 0, weights 0.5 each
  b.u[1] = 1.5f;  // x = 5.5: texels 5 and 6, both border
  b.u[2] = 0.5f;  // x = 1.5: texels 1 and 2, inside
  for (int l = 0; l < N; ++l) b.v[l] = 0.5f;
  b.run(*tex, s);
  // lane 0: 0.5·border + 0.5·texel
  EXPECT_NEAR(b.out[0][0], 0.5f * 0.0f + 0.5f * 200 / 255.0f, kEps);
  EXPECT_NEAR(b.out[1][0], 0.5f * 1.0f + 0.5f * 100 / 255.0f, kEps);
  EXPECT_NEAR(b.out[2][0], 0.5f * 0.5f + 0.0f, kEps);
  EXPECT_NEAR(b.out[3][0], 0.5f * 0.0f + 0.5f * 1.0f, kEps);
  // lane 1: border color itself
  EXPECT_NEAR(b.out[0][1], 0.0f, kEps);
  EXPECT_NEAR(b.out[1][1], 1.0f, kEps);
  EXPECT_NEAR(b.out[2][1], 0.5f, kEps);
  EXPECT_NEAR(b.out[3][1], 0.0f, kEps);
  // lane 2: the texel color
  EXPECT_NEAR(b.out[0][2], 200 / 255.0f, kEps);
}

// ---------------------------------------------------------------- filtering

TEST(Sampler, BilinearBetweenTexels) {
  auto tex = Texture::create2D(Format::A8R8G8B8, 4, 1);
  const int r[4] = {0, 100, 200, 50};
  fill(*tex, 0, 0, [&](int x, int, int) { return argb(255, r[x], 0, 0); });
  SamplerState s = linearState();
  Batch b;
  b.u[0] = 0.5f;     // x = 0.5·4 - 0.5 = 1.5: (100 + 200)/2 = 150
  b.u[1] = 0.4375f;  // x = 1.25: 100 + 0.25·(200 - 100) = 125
  b.u[2] = 0.375f;   // x = 1.0: texel 1 exactly = 100
  b.u[3] = 0.0f;     // x = -0.5: wraps to texel 3 and texel 0: (50 + 0)/2 = 25
  for (int l = 0; l < N; ++l) b.v[l] = 0.5f;
  b.run(*tex, s);
  EXPECT_NEAR(b.out[0][0], 150 / 255.0f, kEps);
  EXPECT_NEAR(b.out[0][1], 125 / 255.0f, kEps);
  EXPECT_FLOAT_EQ(b.out[0][2], 100 / 255.0f);
  EXPECT_NEAR(b.out[0][3], 25 / 255.0f, kEps);
}

TEST(Sampler, BilinearIn2D) {
  // 2x2 texels r: (0,0)=0 (1,0)=100 (0,1)=200 (1,1)=40; u = v = 0.5 is the middle of
  // all four: (0 + 100 + 200 + 40)/4 = 85.
  auto tex = Texture::create2D(Format::A8R8G8B8, 2, 2);
  const int r[2][2] = {{0, 100}, {200, 40}};
  fill(*tex, 0, 0, [&](int x, int y, int) { return argb(255, r[y][x], 0, 0); });
  SamplerState s = linearState();
  s.addressU = s.addressV = TextureAddress::Clamp;
  Batch b;
  b.u[0] = b.v[0] = 0.5f;
  b.u[1] = 0.5f, b.v[1] = 0.25f;  // y = 0: top row, x = 0.5: 50
  b.run(*tex, s);
  EXPECT_NEAR(b.out[0][0], 85 / 255.0f, kEps);
  EXPECT_NEAR(b.out[0][1], 50 / 255.0f, kEps);
}

// Filter weights have 8 bits of sub-texel precision: the position is rounded to a
// multiple of 1/256 texel (half to even), weight w/256 of the second texel. For 8-bit
// texels the sample is S/(255·65536), S = sum texel·wx·wy with wx, wy in 1/256 units.
TEST(Sampler, BilinearWeightsHaveEightFractionBits) {
  auto tex = Texture::create2D(Format::A8R8G8B8, 2, 2);
  // r: (0,0)=0 (1,0)=255 (0,1)=255 (1,1)=0; g: 0 and 100 along x in both rows
  fill(*tex, 0, 0, [](int x, int y, int) { return argb(255, (x ^ y) ? 255 : 0, 100 * x, 0); });
  SamplerState s = linearState();
  s.addressU = s.addressV = TextureAddress::Clamp;
  Batch b;
  for (int l = 0; l < N; ++l) b.u[l] = b.v[l] = 0.25f;  // x = y = 0: texel (0,0) alone
  // lane 0: x = 0.4·2 - 0.5 = 0.3 -> round(0.3·256 = 76.8) = 77, weight 77/256 (not 0.3);
  // y = 0 (top row).
  b.u[0] = 0.4f;
  // lane 1: x = 0.3 as above, y = 0.6·2 - 0.5 = 0.7 -> round(179.2) = 179.
  b.u[1] = 0.4f, b.v[1] = 0.6f;
  // lanes 2, 3: x = 1.5/256 exactly -> 2 (tie to even); x = 0.5/256 -> 0.
  b.u[2] = 0.25f + 0.75f / 256, b.u[3] = 0.25f + 0.25f / 256;
  b.run(*tex, s);
  // lane 0, r: 255·77/256 = 76.70 -> 76.70/255 = 77/256 = 0.30078125 (float weights: 0.3)
  EXPECT_EQ(b.out[0][0], 0.30078125f);
  // lane 0, g: 100·77/256 = 30.078125 -> /255 (one rounding of an exact quotient)
  EXPECT_EQ(b.out[1][0], 30.078125f / 255.0f);
  // lane 1, r: S = 255·(179·179 + 77·77) over the four texels (wx0 = 179, wx1 = 77,
  // wy0 = 77, wy1 = 179) = 255·37970 -> 37970/65536 = 0.579376220703125
  EXPECT_EQ(b.out[0][1], 0.579376220703125f);
  EXPECT_EQ(b.out[1][1], 30.078125f / 255.0f);  // g does not change along y
  EXPECT_EQ(b.out[0][2], 2.0f / 256);           // 255·2/256 / 255
  EXPECT_EQ(b.out[0][3], 0.0f);
  EXPECT_EQ(b.out[3][1], 1.0f);                 // alpha 255 everywhere: 255·65536/(255·65536)
}

// Float texels are weighted with the same 1/256 steps.
TEST(Sampler, FloatTexelsUseTheSameWeights) {
  auto tex = Texture::create2D(Format::A32B32G32R32F, 2, 1);
  const float texels[2][4] = {{0, 0, 0, 1}, {1, 0.5f, 0, 1}};  // R, G, B, A
  std::memcpy(tex->data(0, 0), texels, sizeof texels);
  tex->markDirty();
  SamplerState s = linearState();
  s.addressU = s.addressV = TextureAddress::Clamp;
  Batch b;
  for (int l = 0; l < N; ++l) b.u[l] = 0.4f, b.v[l] = 0.5f;  // x = 0.3 -> 77/256
  b.run(*tex, s);
  EXPECT_EQ(b.out[0][0], 0.30078125f);   // 0 + 77/256·(1 - 0)
  EXPECT_EQ(b.out[1][0], 0.150390625f);  // 77/256·0.5
}

TEST(Sampler, TexelCentersGiveTheTexelWithLinear) {
  // u = (i + 0.5)/W, v = (j + 0.5)/H -> x = i, y = j exactly, weight 1 on texel (i,j).
  const int W = 5, H = 3;
  auto tex = Texture::create2D(Format::A8R8G8B8, W, H);
  fill(*tex, 0, 0, [](int x, int y, int) { return argb(255 - x, 17 * x + 3, 60 * y + 1, 9); });
  SamplerState s = linearState();
  Batch b;
  for (int l = 0; l < W * H; ++l) {
    int i = l % W, j = l / W;
    b.u[l] = (float(i) + 0.5f) / W;
    b.v[l] = (float(j) + 0.5f) / H;
  }
  b.run(*tex, s);
  for (int l = 0; l < W * H; ++l) {
    int i = l % W, j = l / W;
    EXPECT_NEAR(b.out[0][l], float(17 * i + 3) / 255.0f, 1e-5f) << i << "," << j;
    EXPECT_NEAR(b.out[1][l], float(60 * j + 1) / 255.0f, 1e-5f) << i << "," << j;
    EXPECT_NEAR(b.out[2][l], 9 / 255.0f, 1e-5f);
    EXPECT_NEAR(b.out[3][l], float(255 - i) / 255.0f, 1e-5f);
  }
}

TEST(Sampler, PointPicksFloorOfUTimesW) {
  // POINT: texel floor(u·W); u = 0.49 on W = 2 -> floor(0.98) = 0, u = 0.51 -> 1.
  auto tex = Texture::create2D(Format::A8R8G8B8, 2, 1);
  fill(*tex, 0, 0, [](int x, int, int) { return argb(255, 10 + 200 * x, 0, 0); });
  SamplerState s;
  Batch b;
  b.u[0] = 0.49f, b.u[1] = 0.51f, b.u[2] = 0.99f, b.u[3] = 0.0f;
  b.run(*tex, s);
  EXPECT_FLOAT_EQ(b.out[0][0], 10 / 255.0f);
  EXPECT_FLOAT_EQ(b.out[0][1], 210 / 255.0f);
  EXPECT_FLOAT_EQ(b.out[0][2], 210 / 255.0f);
  EXPECT_FLOAT_EQ(b.out[0][3], 10 / 255.0f);
}

TEST(Sampler, MagFilterForLambdaAtMostZeroMinFilterAbove) {
  // 2x1 texels r = 0, 200; u = 0.5: LINEAR x = 0.5 -> 100; POINT floor(1.0) = 1 -> 200.
  auto tex = Texture::create2D(Format::A8R8G8B8, 2, 1);
  fill(*tex, 0, 0, [](int x, int, int) { return argb(255, 200 * x, 0, 0); });
  SamplerState s;
  s.magFilter = TextureFilter::Linear;
  s.minFilter = TextureFilter::Point;
  Batch b;
  for (int l = 0; l < N; ++l) b.u[l] = 0.5f;
  b.lod[0] = -1.0f;  // magnification: LINEAR
  b.lod[1] = 0.0f;   // λ <= 0 is magnification
  b.lod[2] = 0.5f;   // minification: POINT (MIPFILTER NONE keeps level 0)
  b.run(*tex, s);
  EXPECT_NEAR(b.out[0][0], 100 / 255.0f, kEps);
  EXPECT_NEAR(b.out[0][1], 100 / 255.0f, kEps);
  EXPECT_FLOAT_EQ(b.out[0][2], 200 / 255.0f);
}

TEST(Sampler, AnisotropicFiltersLikeLinearAndNoneLikePoint) {
  auto tex = Texture::create2D(Format::A8R8G8B8, 2, 1);
  fill(*tex, 0, 0, [](int x, int, int) { return argb(255, 200 * x, 0, 0); });
  Batch b;
  for (int l = 0; l < N; ++l) b.u[l] = 0.5f;
  SamplerState s;
  s.magFilter = s.minFilter = TextureFilter::Anisotropic;
  b.run(*tex, s);
  EXPECT_NEAR(b.out[0][0], 100 / 255.0f, kEps);  // (0 + 200)/2
  s.magFilter = s.minFilter = TextureFilter::None;
  b.run(*tex, s);
  EXPECT_FLOAT_EQ(b.out[0][0], 200 / 255.0f);  // floor(0.5·2) = 1
}

// ---------------------------------------------------------------- mipmapping

float levelRed(int level) { return float(80 * level) / 255.0f; }

TEST(Sampler, QuadDerivativesSelectTheMipLevel) {
  // 8x8, levels 8,4,2,1. Each quad steps 2 texels of level 0 per pixel in x and y:
  // ddx = (2,0), ddy = (0,2) texels, ρ = 2, λ = log2 2 = 1 -> level 1.
  auto tex = solidLevels2D(8);
  SamplerState s;
  s.mipFilter = TextureFilter::Point;
  Batch b;
  b.quads(0.3f, 0.3f, 2.0f / 8, 2.0f / 8);
  b.run(*tex, s, LodMode::Derivatives);
  for (int l = 0; l < N; ++l) EXPECT_FLOAT_EQ(b.out[0][l], levelRed(1)) << l;

  // 4 texels per pixel in x only: ρ = max(4, 0) = 4, λ = 2.
  b.quads(0.3f, 0.3f, 4.0f / 8, 0.0f);
  b.run(*tex, s, LodMode::Derivatives);
  EXPECT_FLOAT_EQ(b.out[0][0], levelRed(2));
}

TEST(Sampler, TwoDimensionalLambdaIgnoresTheThirdCoordinate) {
  // As QuadDerivativesSelectTheMipLevel (ρ = 2, level 1), with w varying wildly across
  // each quad, infinite or NaN: a 2D texture's footprint has no third axis.
  auto tex = solidLevels2D(8);
  SamplerState s;
  s.mipFilter = TextureFilter::Point;
  const float odd[4] = {0.0f, 1e30f, std::numeric_limits<float>::infinity(),
                        std::numeric_limits<float>::quiet_NaN()};
  Batch b;
  b.quads(0.3f, 0.3f, 2.0f / 8, 2.0f / 8);
  for (int l = 0; l < N; ++l) b.w[l] = odd[(l + l / 4) % 4];
  b.run(*tex, s, LodMode::Derivatives);
  for (int l = 0; l < N; ++l) EXPECT_FLOAT_EQ(b.out[0][l], levelRed(1)) << l;
}

TEST(Sampler, PointMipRoundsLambdaToNearestLevel) {
  auto tex = solidLevels2D(8);
  SamplerState s;
  s.mipFilter = TextureFilter::Point;
  Batch b;
  // step 2^0.4 texels: λ = 0.4 -> level 0; 2^0.6: λ = 0.6 -> level 1
  b.quads(0.3f, 0.3f, std::exp2(0.4f) / 8, 0.0f);
  b.run(*tex, s, LodMode::Derivatives);
  EXPECT_FLOAT_EQ(b.out[0][0], levelRed(0));
  b.quads(0.3f, 0.3f, std::exp2(0.6f) / 8, 0.0f);
  b.run(*tex, s, LodMode::Derivatives);
  EXPECT_FLOAT_EQ(b.out[0][0], levelRed(1));
  // explicit λ (texldl)
  b.lod[0] = 0.4f, b.lod[1] = 0.6f, b.lod[2] = 2.4f, b.lod[3] = 7.0f, b.lod[4] = -3.0f;
  b.run(*tex, s, LodMode::Explicit);
  EXPECT_FLOAT_EQ(b.out[0][0], levelRed(0));
  EXPECT_FLOAT_EQ(b.out[0][1], levelRed(1));
  EXPECT_FLOAT_EQ(b.out[0][2], levelRed(2));
  EXPECT_FLOAT_EQ(b.out[0][3], levelRed(3));  // clamped to the last level
  EXPECT_FLOAT_EQ(b.out[0][4], levelRed(0));
}

TEST(Sampler, LodBiasStateAndPerLaneBias) {
  auto tex = solidLevels2D(8);
  SamplerState s;
  s.mipFilter = TextureFilter::Point;
  Batch b;
  b.quads(0.3f, 0.3f, 2.0f / 8, 2.0f / 8);  // λ = 1
  s.mipLodBias = 1.0f;                      // λ = 1 + 1 = 2
  b.run(*tex, s, LodMode::Derivatives);
  EXPECT_FLOAT_EQ(b.out[0][0], levelRed(2));
  s.mipLodBias = 0.0f;
  // texldb: λ = 1 + lod[lane]
  b.lod[0] = 0.0f, b.lod[1] = 1.0f, b.lod[2] = -1.0f, b.lod[3] = 2.0f;
  b.run(*tex, s, LodMode::Bias);
  EXPECT_FLOAT_EQ(b.out[0][0], levelRed(1));
  EXPECT_FLOAT_EQ(b.out[0][1], levelRed(2));
  EXPECT_FLOAT_EQ(b.out[0][2], levelRed(0));
  EXPECT_FLOAT_EQ(b.out[0][3], levelRed(3));
}

TEST(Sampler, GradientsGiveLambdaPerLane) {
  auto tex = solidLevels2D(8);
  SamplerState s;
  s.mipFilter = TextureFilter::Point;
  Batch b;
  for (int l = 0; l < N; ++l) b.u[l] = b.v[l] = 0.3f;
  b.ddx[0][0] = 4.0f / 8;  // 4 texels in x: λ = 2
  b.ddy[1][1] = 2.0f / 8;  // 2 texels in y: λ = 1
  b.ddx[0][2] = 3.0f / 8, b.ddx[1][2] = 4.0f / 8;  // |(3,4)| = 5 texels: λ = 2.32 -> 2
  b.run(*tex, s, LodMode::Gradients);
  EXPECT_FLOAT_EQ(b.out[0][0], levelRed(2));
  EXPECT_FLOAT_EQ(b.out[0][1], levelRed(1));
  EXPECT_FLOAT_EQ(b.out[0][2], levelRed(2));
  EXPECT_FLOAT_EQ(b.out[0][3], levelRed(0));  // zero gradients: λ = -inf
}

TEST(Sampler, MaxMipLevelClampsTheMostDetailedLevel) {
  auto tex = solidLevels2D(8);
  SamplerState s;
  s.mipFilter = TextureFilter::Point;
  s.maxMipLevel = 2;
  Batch b;
  b.lod[0] = 0.0f, b.lod[1] = 1.0f, b.lod[2] = 3.0f, b.lod[3] = -5.0f;
  b.run(*tex, s);
  EXPECT_FLOAT_EQ(b.out[0][0], levelRed(2));  // λ clamped to [2, 3]
  EXPECT_FLOAT_EQ(b.out[0][1], levelRed(2));
  EXPECT_FLOAT_EQ(b.out[0][2], levelRed(3));
  EXPECT_FLOAT_EQ(b.out[0][3], levelRed(2));
  s.maxMipLevel = 9;  // beyond the chain: the last level
  b.run(*tex, s);
  EXPECT_FLOAT_EQ(b.out[0][0], levelRed(3));
}

TEST(Sampler, MipFilterNoneIgnoresMaxMipLevel) {
  auto tex = solidLevels2D(8);
  SamplerState s;
  s.mipFilter = TextureFilter::None;
  s.maxMipLevel = 2;
  Batch b;
  b.lod[0] = 3.0f, b.lod[1] = 0.0f;
  b.run(*tex, s);
  EXPECT_FLOAT_EQ(b.out[0][0], levelRed(0));
  EXPECT_FLOAT_EQ(b.out[0][1], levelRed(0));
}

TEST(Sampler, LinearMipBlendsTwoLevels) {
  auto tex = solidLevels2D(8);
  SamplerState s = linearState();
  s.mipFilter = TextureFilter::Linear;
  Batch b;
  b.lod[0] = 1.5f;   // (80 + 160)/2 = 120
  b.lod[1] = 1.25f;  // 80 + 0.25·80 = 100
  b.lod[2] = 2.0f;   // level 2 alone = 160
  b.lod[3] = 3.5f;   // clamped to the last level 3 = 240
  b.run(*tex, s);
  EXPECT_NEAR(b.out[0][0], 120 / 255.0f, kEps);
  EXPECT_NEAR(b.out[0][1], 100 / 255.0f, kEps);
  EXPECT_FLOAT_EQ(b.out[0][2], 160 / 255.0f);
  EXPECT_FLOAT_EQ(b.out[0][3], 240 / 255.0f);
  // λ = 1.3 -> round(1.3·256 = 332.8) = 333 = 1 + 77/256: 80 + 77/256·80 = 104.0625
  // (frac 0.3 unquantised: 104)
  b.lod[4] = 1.3f;
  b.run(*tex, s);
  EXPECT_NEAR(b.out[0][4], 104.0625f / 255.0f, 1e-6f);
  // from derivatives: step 2^1.5 texels -> λ = 1.5
  b.quads(0.3f, 0.3f, std::exp2(1.5f) / 8, 0.0f);
  b.run(*tex, s, LodMode::Derivatives);
  EXPECT_NEAR(b.out[0][0], 120 / 255.0f, 1e-4f);
}

TEST(Sampler, MaskedOffLanesStillGiveDerivatives) {
  // Only the top-left lane is asked for; its λ comes from the quad's other lanes
  // (2 texels per pixel: λ = 1). Lanes not asked for read 0.
  auto tex = solidLevels2D(8);
  SamplerState s;
  s.mipFilter = TextureFilter::Point;
  Batch b;
  b.quads(0.3f, 0.3f, 2.0f / 8, 2.0f / 8);
  b.run(*tex, s, LodMode::Derivatives, 0x0001);
  EXPECT_FLOAT_EQ(b.out[0][0], levelRed(1));
  EXPECT_FLOAT_EQ(b.out[3][0], 1.0f);
  EXPECT_FLOAT_EQ(b.out[3][1], 0.0f);
}

// ---------------------------------------------------------------- cube maps

TEST(CubeMap, FaceSelectionAxesAndTies) {
  struct Case {
    float x, y, z;
    int face;
  } cases[] = {
      {1, 0, 0, 0},   {-1, 0, 0, 1},  {0, 1, 0, 2},  {0, -1, 0, 3},    {0, 0, 1, 4},
      {0, 0, -1, 5},  {1, 1, 0, 2},   {1, -1, 0, 3}, {1, 0, 1, 4},     {0, 1, 1, 4},
      {1, 1, 1, 4},   {-1, -1, -1, 5}, {2, 1, -1, 0}, {-3, 1, 2.9f, 1}, {0.5f, -0.7f, 0.1f, 3},
  };
  for (const Case& c : cases) {
    float u, v;
    EXPECT_EQ(cubeFaceCoords(c.x, c.y, c.z, u, v), c.face) << c.x << "," << c.y << "," << c.z;
  }
  float u, v;
  cubeFaceCoords(1, 0, 0, u, v);  // axis: face center
  EXPECT_FLOAT_EQ(u, 0.5f);
  EXPECT_FLOAT_EQ(v, 0.5f);
  // +Z: sc = +rx, tc = -ry, ma = rz: (0.5, 0.25, 1) -> u = (0.5 + 1)/2, v = (-0.25 + 1)/2
  EXPECT_EQ(cubeFaceCoords(0.5f, 0.25f, 1.0f, u, v), 4);
  EXPECT_FLOAT_EQ(u, 0.75f);
  EXPECT_FLOAT_EQ(v, 0.375f);
  // -X: sc = +rz, tc = -ry, |ma| = 2: (-2, 1, 1) -> u = (0.5 + 1)/2, v = (-0.5 + 1)/2
  EXPECT_EQ(cubeFaceCoords(-2.0f, 1.0f, 1.0f, u, v), 1);
  EXPECT_FLOAT_EQ(u, 0.75f);
  EXPECT_FLOAT_EQ(v, 0.25f);
}

// The direction of texel (x, y) of face f, s = 2(x+0.5)/S - 1, t = 2(y+0.5)/S - 1:
// +X (1,-t,-s)  -X (-1,-t,s)  +Y (s,1,t)  -Y (s,-1,-t)  +Z (s,-t,1)  -Z (-s,-t,-1).
void texelDirection(int face, int x, int y, int size, float d[3]) {
  float s = 2.0f * (float(x) + 0.5f) / float(size) - 1.0f;
  float t = 2.0f * (float(y) + 0.5f) / float(size) - 1.0f;
  const float dirs[6][3] = {{1, -t, -s}, {-1, -t, s}, {s, 1, t},
                            {s, -1, -t}, {s, -t, 1},  {-s, -t, -1}};
  for (int i = 0; i < 3; ++i) d[i] = dirs[face][i];
}

TEST(CubeMap, TexelOrientationOnEveryFace) {
  const int S = 4;
  auto tex = Texture::createCube(Format::A8R8G8B8, S, 1);
  for (int f = 0; f < 6; ++f)
    fill(*tex, f, 0, [&](int x, int y, int) { return argb(255, 10 + 40 * f, 60 * x, 60 * y); });
  for (bool linear : {false, true}) {
    SamplerState s = linear ? linearState() : SamplerState{};
    for (int f = 0; f < 6; ++f) {
      Batch b;
      for (int l = 0; l < N; ++l) {
        float d[3];
        texelDirection(f, l % S, l / S, S, d);
        b.u[l] = d[0], b.v[l] = d[1], b.w[l] = d[2];
      }
      b.run(*tex, s);
      for (int l = 0; l < N; ++l) {
        SCOPED_TRACE("face " + std::to_string(f) + " texel " + std::to_string(l % S) + "," +
                     std::to_string(l / S) + (linear ? " linear" : " point"));
        EXPECT_NEAR(b.out[0][l], float(10 + 40 * f) / 255.0f, 1e-5f);
        EXPECT_NEAR(b.out[1][l], float(60 * (l % S)) / 255.0f, 1e-5f);
        EXPECT_NEAR(b.out[2][l], float(60 * (l / S)) / 255.0f, 1e-5f);
      }
    }
  }
}

TEST(CubeMap, FilteringClampsWithinTheFace) {
  // Direction toward the +Z face's left edge, u = 0: LINEAR reads texel -1 clamped to
  // column 0, so the result is the edge texel, not the neighbouring face.
  auto tex = Texture::createCube(Format::A8R8G8B8, 4, 1);
  for (int f = 0; f < 6; ++f)
    fill(*tex, f, 0, [&](int x, int, int) { return argb(255, 40 * f, 50 * x, 0); });
  SamplerState s = linearState();
  s.addressU = s.addressV = TextureAddress::Wrap;  // ignored for cube maps
  Batch b;
  b.u[0] = -1.0f, b.v[0] = -0.25f, b.w[0] = 1.0f;  // +Z: u = (-1 + 1)/2 = 0, v = 0.625
  b.run(*tex, s);
  EXPECT_NEAR(b.out[0][0], 160 / 255.0f, kEps);  // face 4
  EXPECT_NEAR(b.out[1][0], 0.0f, kEps);          // column 0
}

TEST(CubeMap, MipFromFaceProjectedDerivatives) {
  // Size 8. Around +Z the face coordinate is u = (rx/rz + 1)/2, so a direction step of
  // 0.5 in rx at rz = 1 moves u by 0.25 = 2 texels: λ = 1 -> level 1.
  auto tex = Texture::createCube(Format::A8R8G8B8, 8, 0);
  for (int f = 0; f < 6; ++f)
    for (int l = 0; l < tex->levelCount(); ++l)
      fill(*tex, f, l, [&](int, int, int) { return argb(255, 80 * l, 0, 0); });
  SamplerState s;
  s.mipFilter = TextureFilter::Point;
  Batch b;
  b.quads(0.0f, 0.0f, 0.5f, 0.5f);  // rx, ry
  for (int l = 0; l < N; ++l) b.w[l] = 1.0f;
  b.run(*tex, s, LodMode::Derivatives);
  EXPECT_FLOAT_EQ(b.out[0][0], levelRed(1));
  // the same direction scaled by 3 has the same face coordinates and footprint
  for (int l = 0; l < N; ++l) b.u[l] *= 3, b.v[l] *= 3, b.w[l] *= 3;
  b.run(*tex, s, LodMode::Derivatives);
  EXPECT_FLOAT_EQ(b.out[0][0], levelRed(1));

  // Gradients at (0.5, 0, 1): u = (rx/rz + 1)/2, du/drx = 1/(2rz), du/drz = -rx/(2rz²).
  Batch g;
  for (int l = 0; l < N; ++l) g.u[l] = 0.5f, g.w[l] = 1.0f;
  g.ddx[0][0] = 0.5f;  // du = 0.25 = 2 texels: λ = 1
  g.ddx[2][1] = 1.0f;  // du = -0.25 = 2 texels: λ = 1
  g.ddx[2][2] = 0.5f;  // du = -0.125 = 1 texel: λ = 0
  g.ddx[0][3] = 2.0f;  // du = 1 = 8 texels: λ = 3
  g.run(*tex, s, LodMode::Gradients);
  EXPECT_FLOAT_EQ(g.out[0][0], levelRed(1));
  EXPECT_FLOAT_EQ(g.out[0][1], levelRed(1));
  EXPECT_FLOAT_EQ(g.out[0][2], levelRed(0));
  EXPECT_FLOAT_EQ(g.out[0][3], levelRed(3));
}

// ---------------------------------------------------------------- volumes

TEST(VolumeTexture, TexelLookupAndTrilinear) {
  // 4x4x2, texel (x,y,z): r = 50x + 10, g = 50y + 5, b = 100z + 20.
  auto tex = Texture::createVolume(Format::A8R8G8B8, 4, 4, 2, 1);
  fill(*tex, 0, 0, [](int x, int y, int z) { return argb(255, 50 * x + 10, 50 * y + 5, 100 * z + 20); });
  SamplerState s;
  Batch b;
  for (int l = 0; l < N; ++l) {  // centers of texels (l%4, l/4%4, l/8)
    b.u[l] = (float(l % 4) + 0.5f) / 4;
    b.v[l] = (float((l / 4) % 4) + 0.5f) / 4;
    b.w[l] = (float(l / 8) + 0.5f) / 2;
  }
  b.run(*tex, s);
  for (int l = 0; l < N; ++l) {
    EXPECT_FLOAT_EQ(b.out[0][l], float(50 * (l % 4) + 10) / 255.0f) << l;
    EXPECT_FLOAT_EQ(b.out[1][l], float(50 * ((l / 4) % 4) + 5) / 255.0f) << l;
    EXPECT_FLOAT_EQ(b.out[2][l], float(100 * (l / 8) + 20) / 255.0f) << l;
  }
  Batch t;
  t.u[0] = 1.5f / 4, t.v[0] = 2.5f / 4, t.w[0] = 0.5f;  // z = 0.5·2 - 0.5 = 0.5: between slices
  t.u[1] = 1.5f / 4, t.v[1] = 2.5f / 4, t.w[1] = 1.25f;  // POINT: floor(2.5) = 2, wraps to slice 0
  s.magFilter = s.minFilter = TextureFilter::Linear;
  t.run(*tex, s);
  EXPECT_NEAR(t.out[0][0], 60 / 255.0f, kEps);            // texel x = 1
  EXPECT_NEAR(t.out[1][0], 105 / 255.0f, kEps);           // texel y = 2
  EXPECT_NEAR(t.out[2][0], (20 + 120) / 2 / 255.0f, kEps);  // (20 + 120)/2 = 70
  s.magFilter = s.minFilter = TextureFilter::Point;
  t.run(*tex, s);
  EXPECT_FLOAT_EQ(t.out[2][1], 20 / 255.0f);
}

TEST(VolumeTexture, DerivativesIncludeDepth) {
  // 8x8x8: a quad stepping 4 texels in w per pixel (x) gives ρ = 4, λ = 2.
  auto tex = Texture::createVolume(Format::A8R8G8B8, 8, 8, 8, 0);
  for (int l = 0; l < tex->levelCount(); ++l)
    fill(*tex, 0, l, [&](int, int, int) { return argb(255, 80 * l, 0, 0); });
  SamplerState s;
  s.mipFilter = TextureFilter::Point;
  Batch b;
  for (int l = 0; l < N; ++l) b.u[l] = b.v[l] = 0.3f, b.w[l] = 0.2f + 0.5f * float(l & 1);
  b.run(*tex, s, LodMode::Derivatives);
  EXPECT_FLOAT_EQ(b.out[0][0], levelRed(2));
}

// ---------------------------------------------------------------- formats

TEST(Sampler, SrgbConvertsColorNotAlpha) {
  // ((0.5 + 0.055)/1.055)^2.4 = 0.21404
  auto tex = Texture::create2D(Format::A32B32G32R32F, 1, 1);
  tex->setTexel(0, 0, 0, 0, 0, {0.5f, 0.5f, 0.02f, 0.5f});
  SamplerState s;
  s.srgb = true;
  Batch b;
  b.run(*tex, s);
  EXPECT_NEAR(b.out[0][0], 0.21404f, 1e-4f);
  EXPECT_NEAR(b.out[1][0], 0.21404f, 1e-4f);
  EXPECT_NEAR(b.out[2][0], 0.02f / 12.92f, 1e-6f);  // linear segment: c/12.92
  EXPECT_FLOAT_EQ(b.out[3][0], 0.5f);
}

TEST(Sampler, SrgbOf8BitTexelsBeforeFiltering) {
  // texels r = 128, 0 (and 255 for alpha): 128/255 = 0.50196 -> ((0.50196+0.055)/1.055)^2.4
  // = 0.21586. Filtering linear values: midpoint of 0 and 1 (r = 0 and 255) is 0.5.
  auto tex = Texture::create2D(Format::A8R8G8B8, 2, 1);
  fill(*tex, 0, 0, [](int x, int, int) { return argb(128, x ? 255 : 128, x ? 255 : 0, 0); });
  SamplerState s;
  s.srgb = true;
  Batch b;
  b.u[0] = 0.25f;  // texel 0 (POINT)
  b.run(*tex, s);
  EXPECT_NEAR(b.out[0][0], 0.21586f, 1e-4f);
  EXPECT_NEAR(b.out[3][0], 128 / 255.0f, kEps);  // alpha not converted
  s.magFilter = s.minFilter = TextureFilter::Linear;
  b.u[0] = 0.5f;  // x = 0.5: half of texel 0, half of texel 1
  b.run(*tex, s);
  EXPECT_NEAR(b.out[1][0], 0.5f, 1e-5f);                        // (0 + 1)/2
  EXPECT_NEAR(b.out[0][0], (0.21586f + 1.0f) / 2, 1e-4f);       // (lin(128) + 1)/2
}

TEST(Sampler, FloatTexelsAreNotClamped) {
  auto tex = Texture::create2D(Format::A32B32G32R32F, 2, 1);
  tex->setTexel(0, 0, 0, 0, 0, {2.5f, -3.0f, 100.0f, -0.5f});
  tex->setTexel(0, 0, 1, 0, 0, {-2.0f, 4.0f, 0.0f, 1.0f});
  Batch b;
  b.u[0] = 0.25f;  // POINT texel 0
  SamplerState s;
  b.run(*tex, s);
  EXPECT_FLOAT_EQ(b.out[0][0], 2.5f);
  EXPECT_FLOAT_EQ(b.out[1][0], -3.0f);
  EXPECT_FLOAT_EQ(b.out[2][0], 100.0f);
  EXPECT_FLOAT_EQ(b.out[3][0], -0.5f);
  b.u[0] = 0.5f;  // LINEAR midpoint: (2.5 - 2)/2, (-3 + 4)/2, (100 + 0)/2, (-0.5 + 1)/2
  s = linearState();
  b.run(*tex, s);
  EXPECT_FLOAT_EQ(b.out[0][0], 0.25f);
  EXPECT_FLOAT_EQ(b.out[1][0], 0.5f);
  EXPECT_FLOAT_EQ(b.out[2][0], 50.0f);
  EXPECT_FLOAT_EQ(b.out[3][0], 0.25f);
}

TEST(Sampler, SignedTexelsKeepTheirSign) {
  // V8U8: U = 0x81 = -127 -> -1, V = 0x40 = 64 -> 64/127; shader sees (U, V, 1, 1).
  auto tex = Texture::create2D(Format::V8U8, 1, 1);
  uint8_t* p = tex->data(0, 0);
  p[0] = 0x81, p[1] = 0x40;
  tex->markDirty();
  Batch b;
  SamplerState s;
  b.run(*tex, s);
  EXPECT_NEAR(b.out[0][0], -1.0f, kEps);
  EXPECT_NEAR(b.out[1][0], 64 / 127.0f, kEps);
  EXPECT_FLOAT_EQ(b.out[2][0], 1.0f);
  EXPECT_FLOAT_EQ(b.out[3][0], 1.0f);
}

// ---------------------------------------------------------------- fast path vs reference

// Random coordinates, sizes and states; the vectorised kernel must give exactly what the
// scalar reference path gives.
TEST(SamplerPaths, FastPathMatchesReference) {
  std::mt19937 rng(1234);
  std::uniform_real_distribution<float> coord(-3.0f, 3.0f), unit(0.0f, 1.0f);
  const TextureAddress modes[] = {TextureAddress::Wrap, TextureAddress::Mirror,
                                  TextureAddress::Clamp, TextureAddress::MirrorOnce,
                                  TextureAddress::Border};
  const int sizes[][2] = {{1, 1}, {7, 5}, {16, 16}, {256, 3}, {3, 64}, {33, 17}};
  int compared = 0;
  for (int iter = 0; iter < 3000; ++iter) {
    const auto& sz = sizes[iter % 6];
    const bool cube = iter % 7 == 3;
    TexturePtr tex = cube ? Texture::createCube(Format::A8R8G8B8, sz[0], 0)
                          : Texture::create2D(Format::A8R8G8B8, sz[0], sz[1], 0);
    for (int f = 0; f < tex->faceCount(); ++f)
      for (int l = 0; l < tex->levelCount(); ++l)
        fill(*tex, f, l, [&](int, int, int) { return uint32_t(rng()); });
    SamplerState s;
    s.addressU = modes[rng() % 5];
    s.addressV = modes[rng() % 5];
    s.magFilter = TextureFilter(rng() % 4);
    s.minFilter = TextureFilter(rng() % 4);
    s.mipFilter = TextureFilter(rng() % 3);
    s.maxMipLevel = rng() % 3;
    s.mipLodBias = unit(rng) * 2 - 1;
    s.borderColor = {unit(rng), unit(rng), unit(rng), unit(rng)};
    Batch b;
    for (int l = 0; l < N; ++l) {
      b.u[l] = coord(rng), b.v[l] = coord(rng), b.w[l] = coord(rng);
      b.lod[l] = unit(rng) * 6 - 2;
    }
    if (iter % 5 == 0)  // small quads, so λ varies across levels
      for (int l = 0; l < N; ++l) {
        float scale = 0.002f + unit(rng) * 0.2f;
        b.u[l] = b.u[l & ~3] + scale * unit(rng), b.v[l] = b.v[l & ~3] + scale * unit(rng);
      }
    const LodMode mode = LodMode(rng() % 3);
    const uint16_t mask = iter % 3 == 0 ? uint16_t(rng()) : uint16_t(0xffff);
    SampleRequest req = b.req(mode, mask);
    float fast[4][N], ref[4][N];
    sampleTexture(*tex, s, req, fast);
    sampleTextureReference(*tex, s, req, ref);
    for (int ch = 0; ch < 4; ++ch)
      for (int l = 0; l < N; ++l) {
        ASSERT_EQ(fast[ch][l], ref[ch][l]) << "iter " << iter << " ch " << ch << " lane " << l;
        ++compared;
      }
  }
  EXPECT_EQ(compared, 3000 * 4 * N);
}

TEST(SamplerPaths, DegenerateCoordinatesStayInRange) {
  auto tex = Texture::create2D(Format::A8R8G8B8, 5, 3, 0);
  for (int l = 0; l < tex->levelCount(); ++l)
    fill(*tex, 0, l, [&](int x, int y, int) { return argb(255, 30 * x, 40 * y, 80 * l); });
  const float bad[] = {NAN, INFINITY, -INFINITY, 1e30f, -1e30f, 3e9f, -3e9f, 1e-40f};
  for (TextureAddress a : {TextureAddress::Wrap, TextureAddress::Mirror, TextureAddress::Clamp,
                           TextureAddress::MirrorOnce, TextureAddress::Border}) {
    for (TextureFilter f : {TextureFilter::Point, TextureFilter::Linear}) {
      SamplerState s;
      s.addressU = s.addressV = a;
      s.magFilter = s.minFilter = s.mipFilter = f;
      Batch b;
      for (int l = 0; l < N; ++l) {
        b.u[l] = bad[l % 8], b.v[l] = bad[(l * 3 + 1) % 8], b.lod[l] = bad[(l + 5) % 8];
      }
      for (LodMode mode : {LodMode::Derivatives, LodMode::Explicit}) {
        b.run(*tex, s, mode);
        float ref[4][N];
        SampleRequest req = b.req(mode);
        sampleTextureReference(*tex, s, req, ref);
        for (int ch = 0; ch < 4; ++ch)
          for (int l = 0; l < N; ++l) {
            EXPECT_GE(b.out[ch][l], 0.0f);
            EXPECT_LE(b.out[ch][l], 1.0f);
            EXPECT_EQ(b.out[ch][l], ref[ch][l]);
          }
      }
    }
  }
}

}  // namespace
}  // namespace refx
