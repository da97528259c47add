// A Clear deferred to the next draw is written block by block: a 4x4 block the draw
// overwrites whole is not filled first. Every pixel, depth and stencil value must end
// as Direct3D defines it: the clear's value where nothing of the draw lands, the
// draw's result (tested against and blended with the cleared values) where it does.
// Expected values are worked out by hand next to each check; the random scenes compare
// with the same frames drawn after a Clear written at once (a target held outside the
// device makes Clear write immediately).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "device_helpers.h"
#include "refx/pipeline/caps.h"
#include "refx/pipeline/device.h"
#include "refx/shader/assembler.h"

namespace refx {
namespace {

using namespace d3d;
using test::drawTL;
using test::makeDevice;
using test::pixel;
using test::TLVertex;
using test::useDiffuseOnly;

// A quad over pixels [x0, x1) x [y0, y1): vertex colours `left` at x0 and `right` at x1,
// depth z0 at x0 to z1 at x1, so pixel x (centre x) has z0 + (z1 - z0) * (x + 0.5 - x0) / (x1 - x0).
void quad(Device& dev, float x0, float y0, float x1, float y1, uint32_t left, uint32_t right, float z0,
          float z1) {
  drawTL(dev, PT_TRIANGLESTRIP, {{x0 - 0.5f, y0 - 0.5f, z0, 1, left, 0, 0}, {x1 - 0.5f, y0 - 0.5f, z1, 1, right, 0, 0},
                                 {x0 - 0.5f, y1 - 0.5f, z0, 1, left, 0, 0}, {x1 - 0.5f, y1 - 0.5f, z1, 1, right, 0, 0}});
}
void quad(Device& dev, float x0, float y0, float x1, float y1, uint32_t argb, float z) {
  quad(dev, x0, y0, x1, y1, argb, argb, z, z);
}

float depthAt(const Device& dev, int x, int y) {
  const auto& ds = *dev.depthStencilSurface();
  return ds.depth[size_t(y) * ds.width + x];
}
uint8_t stencilAt(const Device& dev, int x, int y) {
  const auto& ds = *dev.depthStencilSurface();
  return ds.stencil[size_t(y) * ds.width + x];
}

// A device drawing the diffuse colour with depth test LESS and write.
std::unique_ptr<Device> depthDevice(int w, int h, int threads = 1) {
  auto dev = makeDevice(w, h, 0xff000000, threads);
  useDiffuseOnly(*dev);
  dev->setRenderState(RS_CULLMODE, CULL_NONE);
  dev->setRenderState(RS_ZENABLE, ZB_TRUE);
  dev->setRenderState(RS_ZFUNC, CMP_LESS);
  return dev;
}

bool inside(int x, int y, int x0, int y0, int x1, int y1) { return x >= x0 && x < x1 && y >= y0 && y < y1; }

constexpr uint32_t kClear = 0xff102030, kRed = 0xffff0000, kGreen = 0xff00ff00;

TEST(LazyClear, FullCoverageOverwritesEveryPixel) {
  // Sizes that are and are not multiples of 4 and of the 64-pixel tile.
  for (auto [w, h] : {std::pair{70, 37}, {131, 67}, {64, 64}}) {
    for (int threads : {1, 2}) {
      auto dev = depthDevice(w, h, threads);
      dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER, kClear, 0.75f, 0);
      quad(*dev, 0, 0, float(w), float(h), kRed, 0.5f);  // 0.5 < 0.75 everywhere
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          ASSERT_EQ(pixel(*dev, x, y), kRed) << w << "x" << h << " at " << x << "," << y;
          ASSERT_EQ(depthAt(*dev, x, y), 0.5f) << w << "x" << h << " at " << x << "," << y;
        }
    }
  }
}

TEST(LazyClear, PartialCoverageKeepsTheClearAround) {
  for (int threads : {1, 2}) {
    auto dev = depthDevice(70, 37, threads);
    dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER, kClear, 0.75f, 0);
    quad(*dev, 3, 5, 45, 30, kRed, 0.5f);
    for (int y = 0; y < 37; ++y)
      for (int x = 0; x < 70; ++x) {
        const bool in = inside(x, y, 3, 5, 45, 30);
        ASSERT_EQ(pixel(*dev, x, y), in ? kRed : kClear) << x << "," << y;
        ASSERT_EQ(depthAt(*dev, x, y), in ? 0.5f : 0.75f) << x << "," << y;
      }
  }
}

TEST(LazyClear, ClearRectSmallerThanTheTarget) {
  // The viewport at (10, 6) size 40x24 limits the clear to [10, 50) x [6, 30) (edges off
  // the 4-pixel grid); outside it the target keeps black and depth 1 from makeDevice.
  auto dev = depthDevice(70, 37);
  dev->setViewport(Viewport{10, 6, 40, 24, 0, 1});
  dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER, 0xffffffff, 0.25f, 0);
  dev->setViewport(Viewport{0, 0, 70, 37, 0, 1});
  quad(*dev, 0, 0, 70, 37, kRed, 0.5f);  // passes against 1, fails against 0.25
  for (int y = 0; y < 37; ++y)
    for (int x = 0; x < 70; ++x) {
      const bool cleared = inside(x, y, 10, 6, 50, 30);
      ASSERT_EQ(pixel(*dev, x, y), cleared ? 0xffffffffu : kRed) << x << "," << y;
      ASSERT_EQ(depthAt(*dev, x, y), cleared ? 0.25f : 0.5f) << x << "," << y;
    }
}

TEST(LazyClear, LessFailsInSomeLanesAgainstTheClearedZ) {
  // z = (x + 0.5) / 62 over [0, 62): LESS than the cleared 0.5 for x <= 30 only, so the
  // block [28, 32) has three passing lanes a row and one failing.
  auto dev = depthDevice(70, 37);
  dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER, kClear, 0.5f, 0);
  quad(*dev, 0, 0, 62, 37, kRed, kRed, 0.0f, 1.0f);
  for (int y = 0; y < 37; ++y)
    for (int x = 0; x < 70; ++x) {
      const bool drawn = x <= 30;
      ASSERT_EQ(pixel(*dev, x, y), drawn ? kRed : kClear) << x << "," << y;
      if (drawn) ASSERT_NEAR(depthAt(*dev, x, y), (x + 0.5f) / 62, 1e-6f) << x << "," << y;
      else ASSERT_EQ(depthAt(*dev, x, y), 0.5f) << x << "," << y;
    }
}

TEST(LazyClear, GreaterFailsInSomeLanesAgainstTheClearedZ) {
  // z = (x + 0.5) / 62 GREATER than the cleared 0.5 for x >= 31 (up to 61).
  auto dev = depthDevice(70, 37);
  dev->setRenderState(RS_ZFUNC, CMP_GREATER);
  dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER, kClear, 0.5f, 0);
  quad(*dev, 0, 0, 62, 37, kRed, kRed, 0.0f, 1.0f);
  for (int x = 0; x < 70; ++x) {
    const bool drawn = x >= 31 && x < 62;
    ASSERT_EQ(pixel(*dev, x, 20), drawn ? kRed : kClear) << x;
    ASSERT_EQ(depthAt(*dev, x, 20) == 0.5f, !drawn) << x;
  }
}

TEST(LazyClear, GreaterAgainstZClearedToZero) {
  // z 0 is not GREATER than the cleared 0: nothing drawn, yet every block gets the
  // clear; the second draw of the frame (z 0.25 > 0) then covers its quad.
  auto dev = depthDevice(70, 37);
  dev->setRenderState(RS_ZFUNC, CMP_GREATER);
  dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER, kClear, 0.0f, 0);
  quad(*dev, 0, 0, 70, 37, kRed, 0.0f);
  for (int y = 0; y < 37; ++y)
    for (int x = 0; x < 70; ++x) {
      ASSERT_EQ(pixel(*dev, x, y), kClear) << x << "," << y;
      ASSERT_EQ(depthAt(*dev, x, y), 0.0f) << x << "," << y;
    }
  quad(*dev, 8, 8, 20, 20, kGreen, 0.25f);
  EXPECT_EQ(pixel(*dev, 8, 8), kGreen);
  EXPECT_EQ(pixel(*dev, 20, 8), kClear);
  EXPECT_EQ(depthAt(*dev, 19, 19), 0.25f);
}

TEST(LazyClear, AlphaTestLeavesTheClearWhereItFails) {
  // Alpha from 0 at x = -0.5 to 1 at x = 63.5: a = (x + 0.5) / 64, 8-bit round(a * 255)
  // is 126 at x = 31 (not GREATER than 128: discarded), 129 at x = 32 (kept).
  auto dev = depthDevice(70, 37);
  dev->setRenderState(RS_ALPHATESTENABLE, 1);
  dev->setRenderState(RS_ALPHAFUNC, CMP_GREATER);
  dev->setRenderState(RS_ALPHAREF, 0x80);
  dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER, kClear, 0.75f, 0);
  quad(*dev, 0, 0, 64, 37, 0x00ff0000, 0xffff0000, 0.5f, 0.5f);
  for (int x = 0; x < 70; ++x) {
    const bool drawn = x >= 32 && x < 64;
    const uint32_t p = pixel(*dev, x, 10);
    if (!drawn) {
      ASSERT_EQ(p, kClear) << x;
      ASSERT_EQ(depthAt(*dev, x, 10), 0.75f) << x;
      continue;
    }
    ASSERT_EQ(p & 0xffffff, 0xff0000u) << x;
    ASSERT_NEAR(double(p >> 24), std::floor((x + 0.5) / 64 * 255 + 0.5), 1.0) << x;
    ASSERT_EQ(depthAt(*dev, x, 10), 0.5f) << x;
  }
}

TEST(LazyClear, BlendingReadsTheClearedColour) {
  // SRCALPHA / INVSRCALPHA of (1, 0, 0, a = 128/255) over the cleared blue (0, 0, 1, 1):
  // r = a = 0.50196 -> 128, g = 0, b = 1 - a = 0.49804 -> 127, alpha = a*a + (1 - a) =
  // 0.75000 -> 191.25 -> 191.
  auto dev = depthDevice(70, 37);
  dev->setRenderState(RS_ALPHABLENDENABLE, 1);
  dev->setRenderState(RS_SRCBLEND, BLEND_SRCALPHA);
  dev->setRenderState(RS_DESTBLEND, BLEND_INVSRCALPHA);
  dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER, 0xff0000ff, 1.0f, 0);
  quad(*dev, 0, 0, 45, 37, 0x80ff0000, 0.5f);
  EXPECT_EQ(pixel(*dev, 0, 0), 0xbf80007fu);
  EXPECT_EQ(pixel(*dev, 44, 36), 0xbf80007fu);
  EXPECT_EQ(pixel(*dev, 45, 36), 0xff0000ffu);
  EXPECT_EQ(depthAt(*dev, 20, 20), 0.5f);
  EXPECT_EQ(depthAt(*dev, 60, 20), 1.0f);
}

TEST(LazyClear, ColourWriteMaskKeepsTheClearedChannels) {
  // Red and alpha written from 0xffff00ff; green and blue keep the cleared 0x40.
  auto dev = depthDevice(70, 37);
  dev->setRenderState(RS_COLORWRITEENABLE, CW_RED | CW_ALPHA);
  dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER, 0x80404040, 1.0f, 0);
  quad(*dev, 0, 0, 70, 37, 0xffff00ff, 0.5f);
  for (int y = 0; y < 37; ++y)
    for (int x = 0; x < 70; ++x) ASSERT_EQ(pixel(*dev, x, y), 0xffff4040u) << x << "," << y;
  EXPECT_EQ(depthAt(*dev, 69, 36), 0.5f);
}

TEST(LazyClear, StencilTestReadsTheClearedStencil) {
  // Stencil cleared to 1; EQUAL against ref 1 passes and INCR makes it 2; against ref 2
  // it fails (KEEP): the clear colour and stencil stay.
  for (uint32_t ref : {1u, 2u}) {
    auto dev = depthDevice(70, 37);
    dev->setRenderState(RS_STENCILENABLE, 1);
    dev->setRenderState(RS_STENCILFUNC, CMP_EQUAL);
    dev->setRenderState(RS_STENCILREF, ref);
    dev->setRenderState(RS_STENCILPASS, STENCILOP_INCR);
    dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER | CLEAR_STENCIL, kClear, 0.75f, 1);
    quad(*dev, 0, 0, 45, 37, kRed, 0.5f);
    const bool pass = ref == 1;
    EXPECT_EQ(pixel(*dev, 10, 10), pass ? kRed : kClear);
    EXPECT_EQ(stencilAt(*dev, 10, 10), pass ? 2 : 1);
    EXPECT_EQ(depthAt(*dev, 10, 10), pass ? 0.5f : 0.75f);
    EXPECT_EQ(pixel(*dev, 60, 10), kClear);
    EXPECT_EQ(stencilAt(*dev, 60, 10), 1);
  }
}

TEST(LazyClear, StencilClearedWithADrawThatDoesNotTestIt) {
  // The draw overwrites colour and depth; the stencil of its blocks still gets the 7.
  auto dev = depthDevice(70, 37);
  dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER | CLEAR_STENCIL, kClear, 0.75f, 7);
  quad(*dev, 0, 0, 70, 37, kRed, 0.5f);
  for (int y = 0; y < 37; ++y)
    for (int x = 0; x < 70; ++x) ASSERT_EQ(stencilAt(*dev, x, y), 7) << x << "," << y;
  EXPECT_EQ(pixel(*dev, 33, 17), kRed);
}

uint32_t texel32(const Texture& t, int x, int y) {
  uint32_t v;
  std::memcpy(&v, t.data(0, 0) + y * t.rowPitch(0) + x * 4, 4);
  return v;
}

std::unique_ptr<Device> mrtDevice(int w, int h) {
  auto dev = std::make_unique<Device>(loadCapsProfile("ref"), DeviceOptions{1});
  for (int i = 0; i < 2; ++i) dev->setRenderTarget(i, Texture::create2D(Format::A8R8G8B8, w, h));
  dev->setDepthStencilSurface(std::make_shared<DepthStencilSurface>(w, h));
  dev->setRenderState(RS_CULLMODE, CULL_NONE);
  dev->setRenderState(RS_ZENABLE, ZB_TRUE);
  dev->setRenderState(RS_ZFUNC, CMP_LESS);
  return dev;
}

TEST(LazyClear, SecondTargetIsClearedUnderAFixedFunctionDraw) {
  // Fixed function writes target 0 only: target 1 holds the clear everywhere.
  auto dev = mrtDevice(70, 37);
  useDiffuseOnly(*dev);
  dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER, kClear, 1.0f, 0);
  quad(*dev, 0, 0, 70, 37, kRed, 0.5f);
  for (int y = 0; y < 37; ++y)
    for (int x = 0; x < 70; ++x) {
      ASSERT_EQ(texel32(*dev->renderTarget(0), x, y), kRed) << x << "," << y;
      ASSERT_EQ(texel32(*dev->renderTarget(1), x, y), kClear) << x << "," << y;
    }
}

TEST(LazyClear, ShaderWritingTwoTargets) {
  // oC0 = (1, 0, 0, 1), oC1 = (0, 1, 0, 1) inside the quad, the clear outside.
  auto dev = mrtDevice(70, 37);
  dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER, kClear, 1.0f, 0);
  dev->setPixelShader(dev->createPixelShader(shader::assembleTokens(
      "ps_2_0\ndef c0, 1, 0, 0, 1\ndef c1, 0, 1, 0, 1\nmov oC0, c0\nmov oC1, c1\n", "t.psh")));
  quad(*dev, 3, 5, 45, 30, 0xffffffff, 0.5f);
  for (int y = 0; y < 37; ++y)
    for (int x = 0; x < 70; ++x) {
      const bool in = inside(x, y, 3, 5, 45, 30);
      ASSERT_EQ(texel32(*dev->renderTarget(0), x, y), in ? kRed : kClear) << x << "," << y;
      ASSERT_EQ(texel32(*dev->renderTarget(1), x, y), in ? kGreen : kClear) << x << "," << y;
    }
}

TEST(LazyClear, FloatTarget) {
  // The shader's (2.5, -1, 0.125, 0.5) stored as is inside the quad; outside the clear
  // 0x80ff4000 as (255, 64, 0, 128) / 255.
  DeviceOptions opt;
  opt.threads = 1;
  auto dev = std::make_unique<Device>(CapsProfile{}, opt);
  dev->setRenderTarget(Texture::create2D(Format::A32B32G32R32F, 70, 37));
  dev->setDepthStencilSurface(std::make_shared<DepthStencilSurface>(70, 37));
  dev->setRenderState(RS_CULLMODE, CULL_NONE);
  dev->setRenderState(RS_ZENABLE, ZB_TRUE);
  dev->setRenderState(RS_ZFUNC, CMP_LESS);
  dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER, 0x80ff4000, 1.0f, 0);
  dev->setPixelShader(dev->createPixelShader(
      shader::encode(shader::assemble("ps_2_0\ndef c0, 2.5, -1, 0.125, 0.5\nmov oC0, c0\n", "ps.psh"))));
  quad(*dev, 3, 5, 45, 30, 0xffffffff, 0.5f);
  const Texture& t = *dev->renderTarget();
  for (int y = 0; y < 37; ++y)
    for (int x = 0; x < 70; ++x) {
      std::array<float, 4> v;
      std::memcpy(v.data(), t.data(0, 0) + y * t.rowPitch(0) + x * 16, 16);
      const std::array<float, 4> expected = inside(x, y, 3, 5, 45, 30)
                                                ? std::array<float, 4>{2.5f, -1.0f, 0.125f, 0.5f}
                                                : std::array<float, 4>{1.0f, 64 / 255.0f, 0.0f, 128 / 255.0f};
      ASSERT_EQ(v, expected) << x << "," << y;
    }
}

TEST(LazyClear, DepthOnlyClear) {
  // The target holds red at depth 0.5 from a first frame; the depth is cleared to 0.25
  // alone: green at 0.5 fails everywhere, green at 0.125 passes inside its quad.
  auto dev = depthDevice(70, 37);
  quad(*dev, 0, 0, 70, 37, kRed, 0.5f);
  dev->clear(CLEAR_ZBUFFER, kClear, 0.25f, 0);
  quad(*dev, 0, 0, 70, 37, kGreen, 0.5f);
  for (int y = 0; y < 37; ++y)
    for (int x = 0; x < 70; ++x) {
      ASSERT_EQ(pixel(*dev, x, y), kRed) << x << "," << y;
      ASSERT_EQ(depthAt(*dev, x, y), 0.25f) << x << "," << y;
    }
  dev->clear(CLEAR_ZBUFFER, kClear, 0.25f, 0);
  quad(*dev, 3, 5, 45, 30, kGreen, 0.125f);
  for (int y = 0; y < 37; ++y)
    for (int x = 0; x < 70; ++x) {
      const bool in = inside(x, y, 3, 5, 45, 30);
      ASSERT_EQ(pixel(*dev, x, y), in ? kGreen : kRed) << x << "," << y;
      ASSERT_EQ(depthAt(*dev, x, y), in ? 0.125f : 0.25f) << x << "," << y;
    }
}

TEST(LazyClear, ColourOnlyClear) {
  // Depth 0.5 from a first frame stays: the colour is cleared alone, a quad at 0.75
  // fails against it (the clear colour stays), one at 0.25 passes inside its quad.
  auto dev = depthDevice(70, 37);
  quad(*dev, 0, 0, 70, 37, kRed, 0.5f);
  dev->clear(CLEAR_TARGET, kClear, 1.0f, 0);
  quad(*dev, 0, 0, 70, 37, kGreen, 0.75f);
  EXPECT_EQ(pixel(*dev, 0, 0), kClear);
  EXPECT_EQ(pixel(*dev, 69, 36), kClear);
  EXPECT_EQ(depthAt(*dev, 30, 30), 0.5f);
  dev->clear(CLEAR_TARGET, kClear, 1.0f, 0);
  quad(*dev, 3, 5, 45, 30, kGreen, 0.25f);
  for (int y = 0; y < 37; ++y)
    for (int x = 0; x < 70; ++x) {
      const bool in = inside(x, y, 3, 5, 45, 30);
      ASSERT_EQ(pixel(*dev, x, y), in ? kGreen : kClear) << x << "," << y;
      ASSERT_EQ(depthAt(*dev, x, y), in ? 0.25f : 0.5f) << x << "," << y;
    }
}

TEST(LazyClear, SecondDrawSeesTheFirst) {
  // Red over the whole target, then green ONE/ONE over part of it: (1, 1, 0) there.
  for (int threads : {1, 2}) {
    auto dev = depthDevice(131, 67, threads);
    dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER, kClear, 1.0f, 0);
    quad(*dev, 0, 0, 131, 67, kRed, 0.5f);
    dev->setRenderState(RS_ALPHABLENDENABLE, 1);
    dev->setRenderState(RS_SRCBLEND, BLEND_ONE);
    dev->setRenderState(RS_DESTBLEND, BLEND_ONE);
    quad(*dev, 3, 5, 100, 60, kGreen, 0.25f);
    for (int y = 0; y < 67; ++y)
      for (int x = 0; x < 131; ++x)
        ASSERT_EQ(pixel(*dev, x, y), inside(x, y, 3, 5, 100, 60) ? 0xffffff00u : kRed) << x << "," << y;
  }
}

TEST(LazyClear, DepthClearOutlivesADrawWithoutDepth) {
  // A draw without depth test or stencil leaves the depth and stencil of the Clear for
  // later: the next draw that tests depth sees them, and so does the accessor.
  auto dev = depthDevice(70, 37);
  dev->setRenderState(RS_ZENABLE, ZB_FALSE);
  dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER | CLEAR_STENCIL, kClear, 0.5f, 3);
  quad(*dev, 0, 0, 70, 37, kRed, 0.25f);  // no depth test: drawn everywhere
  dev->setRenderState(RS_ZENABLE, ZB_TRUE);
  quad(*dev, 0, 0, 35, 37, kGreen, 0.75f);  // 0.75 is not LESS than the cleared 0.5
  quad(*dev, 35, 0, 70, 37, kGreen, 0.375f);
  for (int y = 0; y < 37; ++y)
    for (int x = 0; x < 70; ++x) {
      ASSERT_EQ(pixel(*dev, x, y), x < 35 ? kRed : kGreen) << x << "," << y;
      ASSERT_EQ(depthAt(*dev, x, y), x < 35 ? 0.5f : 0.375f) << x << "," << y;
      ASSERT_EQ(stencilAt(*dev, x, y), 3) << x << "," << y;
    }
}

TEST(LazyClear, DepthClearLeftPendingIsSeenThroughTheAccessor) {
  auto dev = depthDevice(70, 37);
  dev->setRenderState(RS_ZENABLE, ZB_FALSE);
  dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER | CLEAR_STENCIL, kClear, 0.5f, 3);
  quad(*dev, 0, 0, 70, 37, kRed, 0.25f);
  EXPECT_EQ(depthAt(*dev, 0, 0), 0.5f);
  EXPECT_EQ(depthAt(*dev, 69, 36), 0.5f);
  EXPECT_EQ(stencilAt(*dev, 33, 20), 3);
}

TEST(LazyClear, DepthClearLeftPendingThenAPartialClear) {
  // The second Clear covers only [10, 50) x [6, 30): outside it the first one's 0.5 and
  // stencil 3 must stay; inside, 0.25 and 4 (its stencil flag set).
  for (uint32_t secondFlags : {uint32_t(CLEAR_ZBUFFER), uint32_t(CLEAR_ZBUFFER | CLEAR_STENCIL)}) {
    auto dev = depthDevice(70, 37);
    dev->setRenderState(RS_ZENABLE, ZB_FALSE);
    dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER | CLEAR_STENCIL, kClear, 0.5f, 3);
    quad(*dev, 0, 0, 70, 37, kRed, 0.25f);
    dev->setViewport(Viewport{10, 6, 40, 24, 0, 1});
    dev->clear(secondFlags, kClear, 0.25f, 4);
    dev->setViewport(Viewport{0, 0, 70, 37, 0, 1});
    quad(*dev, 0, 0, 70, 37, kRed, 0.25f);
    for (int y = 0; y < 37; ++y)
      for (int x = 0; x < 70; ++x) {
        const bool second = inside(x, y, 10, 6, 50, 30);
        ASSERT_EQ(depthAt(*dev, x, y), second ? 0.25f : 0.5f) << x << "," << y;
        ASSERT_EQ(stencilAt(*dev, x, y), second && (secondFlags & CLEAR_STENCIL) ? 4 : 3) << x << "," << y;
      }
  }
}

TEST(LazyClear, DepthClearLeftPendingIsReplacedByAWholeOne) {
  // Frames of Clear(TARGET | ZBUFFER) and a draw without depth: each frame's depth
  // clear replaces the last; the last one is what the surface holds.
  auto dev = depthDevice(70, 37);
  dev->setRenderState(RS_ZENABLE, ZB_FALSE);
  for (float z : {0.125f, 0.25f, 0.375f}) {
    dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER, kClear, z, 0);
    quad(*dev, 0, 0, 70, 37, kRed, 0.75f);
  }
  EXPECT_EQ(depthAt(*dev, 0, 0), 0.375f);
  EXPECT_EQ(depthAt(*dev, 69, 36), 0.375f);
  EXPECT_EQ(pixel(*dev, 40, 20), kRed);
  // A whole Clear of the depth alone does not replace a pending stencil clear.
  dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER | CLEAR_STENCIL, kClear, 0.5f, 6);
  quad(*dev, 0, 0, 70, 37, kRed, 0.75f);
  dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER, kClear, 0.25f, 0);
  quad(*dev, 0, 0, 70, 37, kRed, 0.75f);
  EXPECT_EQ(depthAt(*dev, 5, 5), 0.25f);
  EXPECT_EQ(stencilAt(*dev, 5, 5), 6);
}

// Random frames on a device whose Clear is deferred and on one whose Clear is written
// at once (its surfaces are held outside it): the same bytes, depths and stencils.
struct Frame {
  uint32_t clearFlags;
  uint32_t clearColor;
  float clearZ;
  uint8_t clearStencil;
  Viewport clearRect;
  struct Draw {
    uint32_t zfunc, zwrite, zenable, blend, alphaTest, writeMask, stencil;
    std::vector<TLVertex> tris;
  };
  std::vector<Draw> draws;
};

Frame randomFrame(std::mt19937& rng, int w, int h) {
  Frame f;
  const uint32_t flagChoices[] = {CLEAR_TARGET | CLEAR_ZBUFFER, CLEAR_TARGET | CLEAR_ZBUFFER | CLEAR_STENCIL,
                                  CLEAR_TARGET, CLEAR_ZBUFFER, CLEAR_TARGET | CLEAR_ZBUFFER};
  f.clearFlags = flagChoices[rng() % 5];
  f.clearColor = uint32_t(rng());
  f.clearZ = float(rng() % 5) / 4.0f;
  f.clearStencil = uint8_t(rng() % 3);
  f.clearRect = Viewport{0, 0, w, h, 0, 1};
  if (rng() % 4 == 0) {
    const int x = int(rng() % uint32_t(w / 2)), y = int(rng() % uint32_t(h / 2));
    f.clearRect = Viewport{x, y, 1 + int(rng() % uint32_t(w - x)), 1 + int(rng() % uint32_t(h - y)), 0, 1};
  }
  const int draws = 1 + int(rng() % 3);
  for (int i = 0; i < draws; ++i) {
    Frame::Draw d;
    const uint32_t funcs[] = {CMP_LESS, CMP_LESSEQUAL, CMP_GREATER, CMP_GREATEREQUAL, CMP_EQUAL, CMP_ALWAYS};
    d.zfunc = funcs[rng() % 6];
    d.zwrite = rng() % 4 != 0;
    d.zenable = rng() % 5 != 0;
    d.blend = rng() % 5 == 0;
    d.alphaTest = rng() % 6 == 0;
    d.writeMask = rng() % 6 == 0 ? CW_RED | CW_BLUE : 0xf;
    d.stencil = rng() % 6 == 0;
    // Large triangles (whole blocks) and small ones (partial blocks), z on the cleared
    // values' grid (ties) or between.
    const int tris = 1 + int(rng() % 4);
    for (int t = 0; t < tris * 3; ++t) {
      const bool big = rng() % 2 == 0;
      const float span = big ? 2.0f : 0.3f;
      std::uniform_real_distribution<float> ux(-0.5f * w * (span - 1), w * (0.5f + 0.5f * span));
      std::uniform_real_distribution<float> uy(-0.5f * h * (span - 1), h * (0.5f + 0.5f * span));
      const float z = rng() % 2 ? float(rng() % 5) / 4.0f : float(rng() % 1000) / 1000.0f;
      d.tris.push_back({ux(rng), uy(rng), z, 1, uint32_t(rng()), 0, 0});
    }
    f.draws.push_back(d);
  }
  return f;
}

void drawFrame(Device& dev, const Frame& f, int w, int h) {
  dev.setViewport(f.clearRect);
  dev.clear(f.clearFlags, f.clearColor, f.clearZ, f.clearStencil);
  dev.setViewport(Viewport{0, 0, w, h, 0, 1});
  for (const Frame::Draw& d : f.draws) {
    dev.setRenderState(RS_ZENABLE, d.zenable ? ZB_TRUE : ZB_FALSE);
    dev.setRenderState(RS_ZFUNC, d.zfunc);
    dev.setRenderState(RS_ZWRITEENABLE, d.zwrite);
    dev.setRenderState(RS_ALPHABLENDENABLE, d.blend);
    dev.setRenderState(RS_SRCBLEND, BLEND_SRCALPHA);
    dev.setRenderState(RS_DESTBLEND, BLEND_INVSRCALPHA);
    dev.setRenderState(RS_ALPHATESTENABLE, d.alphaTest);
    dev.setRenderState(RS_ALPHAFUNC, CMP_GREATER);
    dev.setRenderState(RS_ALPHAREF, 0x80);
    dev.setRenderState(RS_COLORWRITEENABLE, d.writeMask);
    dev.setRenderState(RS_STENCILENABLE, d.stencil);
    dev.setRenderState(RS_STENCILFUNC, CMP_EQUAL);
    dev.setRenderState(RS_STENCILREF, 1);
    dev.setRenderState(RS_STENCILPASS, STENCILOP_INCR);
    drawTL(dev, PT_TRIANGLELIST, d.tris);
  }
}

TEST(LazyClear, RandomFramesMatchAClearWrittenAtOnce) {
  std::mt19937 rng(1234);
  for (auto [w, h] : {std::pair{37, 29}, {70, 37}, {131, 67}, {200, 150}}) {
    for (int threads : {1, 2}) {
      auto lazy = depthDevice(w, h, threads);
      auto eager = depthDevice(w, h, threads);
      const TexturePtr heldTarget = eager->renderTarget();
      const DepthStencilPtr heldDepth = eager->depthStencilSurface();
      for (int frame = 0; frame < 12; ++frame) {
        const Frame f = randomFrame(rng, w, h);
        drawFrame(*lazy, f, w, h);
        drawFrame(*eager, f, w, h);
        const Texture& a = *lazy->renderTarget();
        const Texture& b = *eager->renderTarget();
        ASSERT_EQ(std::memcmp(a.data(0, 0), b.data(0, 0), size_t(h) * a.rowPitch(0)), 0)
            << w << "x" << h << " frame " << frame;
        ASSERT_EQ(lazy->depthStencilSurface()->depth, eager->depthStencilSurface()->depth)
            << w << "x" << h << " frame " << frame;
        ASSERT_EQ(lazy->depthStencilSurface()->stencil, eager->depthStencilSurface()->stencil)
            << w << "x" << h << " frame " << frame;
      }
    }
  }
}

}  // namespace
}  // namespace refx
