// Rasterization rules of Direct3D 9: integer pixel centres, top-left fill
// convention, perspective-correct interpolation, near-plane clipping, culling,
// and output independent of the thread count.
#include <gtest/gtest.h>

#include "device_helpers.h"

using namespace refx;
using namespace refx::test;
using namespace refx::d3d;

namespace {

// Additive blending of 0x40 per coverage: a pixel covered once reads 0x40, twice 0x80.
void additive(Device& dev) {
  useDiffuseOnly(dev);
  dev.setRenderState(RS_CULLMODE, CULL_NONE);
  dev.setRenderState(RS_ALPHABLENDENABLE, 1);
  dev.setRenderState(RS_SRCBLEND, BLEND_ONE);
  dev.setRenderState(RS_DESTBLEND, BLEND_ONE);
}

TEST(Raster, TopLeftRuleSharedEdgesCoverEachPixelOnce) {
  auto dev = makeDevice(8, 8, 0x00000000);
  additive(*dev);
  const uint32_t c = 0x40404040;
  // Quad (0,0)-(4,4) as two triangles sharing the diagonal (0,0)-(4,4). Every edge
  // passes through pixel centres: left/top edges include them, right/bottom exclude.
  drawTL(*dev, PT_TRIANGLELIST, {{0, 0, 0.5f, 1, c, 0, 0}, {4, 0, 0.5f, 1, c, 0, 0}, {4, 4, 0.5f, 1, c, 0, 0},
                                 {0, 0, 0.5f, 1, c, 0, 0}, {4, 4, 0.5f, 1, c, 0, 0}, {0, 4, 0.5f, 1, c, 0, 0}});
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const uint32_t expected = (x < 4 && y < 4) ? 0x40404040u : 0u;
      EXPECT_EQ(pixel(*dev, x, y), expected) << x << "," << y;
    }
}

TEST(Raster, FanAroundCentreCoversEachPixelOnce) {
  auto dev = makeDevice(8, 8, 0x00000000);
  additive(*dev);
  const uint32_t c = 0x40404040;
  // Four triangles meeting at pixel centre (4,4) of a quad (2,2)-(6,6): pixels 2..5 once each.
  drawTL(*dev, PT_TRIANGLEFAN, {{4, 4, 0.5f, 1, c, 0, 0}, {2, 2, 0.5f, 1, c, 0, 0}, {6, 2, 0.5f, 1, c, 0, 0},
                                {6, 6, 0.5f, 1, c, 0, 0}, {2, 6, 0.5f, 1, c, 0, 0}, {2, 2, 0.5f, 1, c, 0, 0}});
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const uint32_t expected = (x >= 2 && x < 6 && y >= 2 && y < 6) ? 0x40404040u : 0u;
      EXPECT_EQ(pixel(*dev, x, y), expected) << x << "," << y;
    }
}

TEST(Raster, PixelCentresAtIntegerCoordinates) {
  // A quad from -0.5 to 3.5 covers exactly pixels 0..3 and interpolates the diffuse
  // red channel linearly in x: red(x) = (x + 0.5) / 4 * 255 at pixel centre x.
  auto dev = makeDevice(8, 8, 0xff000000);
  useDiffuseOnly(*dev);
  dev->setRenderState(RS_CULLMODE, CULL_NONE);
  drawTL(*dev, PT_TRIANGLESTRIP, {{-0.5f, -0.5f, 0.5f, 1, 0xff000000, 0, 0},
                                  {3.5f, -0.5f, 0.5f, 1, 0xffff0000, 0, 0},
                                  {-0.5f, 3.5f, 0.5f, 1, 0xff000000, 0, 0},
                                  {3.5f, 3.5f, 0.5f, 1, 0xffff0000, 0, 0}});
  for (int x = 0; x < 4; ++x) {
    const int expected = int((x + 0.5f) / 4 * 255 + 0.5f);  // 32, 96, 159, 223
    const int red = (pixel(*dev, x, 1) >> 16) & 0xff;
    EXPECT_NEAR(red, expected, 1) << x;
  }
  EXPECT_EQ(pixel(*dev, 4, 1), 0xff000000u);
  EXPECT_EQ(pixel(*dev, 1, 4), 0xff000000u);
}

TEST(Raster, PerspectiveCorrectInterpolation) {
  // Edge from x=0 (rhw 1, red 0) to x=8 (rhw 0.25, i.e. w = 4, red 255), constant in y.
  // Perspective-correct: red(x) = (t * 1 * 0.25) / ((1 - t) * 1 + t * 0.25) with t = x/8.
  // At x = 4: t = 0.5 -> 0.125 / 0.625 = 0.2 -> 51.
  auto dev = makeDevice(8, 8, 0xff000000);
  useDiffuseOnly(*dev);
  dev->setRenderState(RS_CULLMODE, CULL_NONE);
  drawTL(*dev, PT_TRIANGLESTRIP, {{0, 0, 0.5f, 1, 0xff000000, 0, 0},
                                  {8, 0, 0.5f, 0.25f, 0xffff0000, 0, 0},
                                  {0, 8, 0.5f, 1, 0xff000000, 0, 0},
                                  {8, 8, 0.5f, 0.25f, 0xffff0000, 0, 0}});
  EXPECT_NEAR((pixel(*dev, 4, 3) >> 16) & 0xff, 51, 1);
  // x = 2: t = 0.25 -> 0.0625 / 0.8125 = 0.0769 -> 20 (linear would give 64).
  EXPECT_NEAR((pixel(*dev, 2, 3) >> 16) & 0xff, 20, 1);
}

TEST(Raster, NearPlaneClipping) {
  // Identity transforms: clip space = object space. A triangle with one vertex behind
  // the near plane (z = -1) is cut at z = 0; the part with z < 0 is not drawn.
  auto dev = makeDevice(8, 8, 0xff000000);
  useDiffuseOnly(*dev);
  dev->setRenderState(RS_LIGHTING, 0);
  dev->setRenderState(RS_CULLMODE, CULL_NONE);
  dev->setFVF(kColorVertexFVF);
  // Full-height strip; z goes from 1 at x = -1 to -1 at x = 1, so z >= 0 only for x <= 0
  // in clip space, i.e. screen x <= 4 (x_screen = (1 + x) * 4).
  std::vector<ColorVertex> v = {{-1, 1, 1, 0xffffffff}, {1, 1, -1, 0xffffffff},
                                {-1, -1, 1, 0xffffffff}, {1, -1, -1, 0xffffffff}};
  dev->drawPrimitiveUP(PT_TRIANGLESTRIP, 2, v.data(), sizeof(ColorVertex));
  EXPECT_EQ(pixel(*dev, 1, 4), 0xffffffffu);
  EXPECT_EQ(pixel(*dev, 3, 4), 0xffffffffu);
  EXPECT_EQ(pixel(*dev, 5, 4), 0xff000000u);
  EXPECT_EQ(pixel(*dev, 7, 4), 0xff000000u);
}

TEST(Raster, CullModes) {
  // Screen-clockwise triangle (y down): (0,0) (8,0) (0,8).
  std::vector<TLVertex> cw = {{0, 0, 0.5f, 1, 0xffffffff, 0, 0}, {8, 0, 0.5f, 1, 0xffffffff, 0, 0},
                              {0, 8, 0.5f, 1, 0xffffffff, 0, 0}};
  std::vector<TLVertex> ccw = {cw[0], cw[2], cw[1]};
  for (uint32_t cull : {CULL_NONE, CULL_CW, CULL_CCW}) {
    for (bool clockwise : {true, false}) {
      auto dev = makeDevice(8, 8, 0xff000000);
      useDiffuseOnly(*dev);
      dev->setRenderState(RS_CULLMODE, cull);
      drawTL(*dev, PT_TRIANGLELIST, clockwise ? cw : ccw);
      const bool culled = (cull == CULL_CW && clockwise) || (cull == CULL_CCW && !clockwise);
      EXPECT_EQ(pixel(*dev, 1, 1), culled ? 0xff000000u : 0xffffffffu) << cull << clockwise;
    }
  }
}

TEST(Raster, ThreadCountDoesNotChangeOutput) {
  // Many overlapping blended triangles across tile borders: bytes must be identical
  // for 1, 2 and 8 threads.
  std::vector<std::vector<uint8_t>> images;
  for (int threads : {1, 2, 8}) {
    auto dev = makeDevice(200, 150, 0xff102030, threads);
    useDiffuseOnly(*dev);
    dev->setRenderState(RS_CULLMODE, CULL_NONE);
    dev->setRenderState(RS_ALPHABLENDENABLE, 1);
    dev->setRenderState(RS_SRCBLEND, BLEND_SRCALPHA);
    dev->setRenderState(RS_DESTBLEND, BLEND_INVSRCALPHA);
    std::vector<TLVertex> v;
    uint32_t seed = 1;
    auto rnd = [&] { seed = seed * 1664525u + 1013904223u; return seed >> 8; };
    for (int i = 0; i < 300; ++i) {
      v.push_back({float(rnd() % 220) - 10, float(rnd() % 170) - 10, 0.5f, 1, 0x80000000u | (rnd() & 0xffffff), 0, 0});
    }
    drawTL(*dev, PT_TRIANGLELIST, v);
    const Texture& t = *dev->renderTarget();
    images.emplace_back(t.data(0, 0), t.data(0, 0) + t.dataSize(0, 0));
  }
  EXPECT_TRUE(images[0] == images[1]);
  EXPECT_TRUE(images[0] == images[2]);
}

}  // namespace
