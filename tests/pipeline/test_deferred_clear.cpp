// Clear is deferred to the next draw when only the device holds the surfaces; every
// way of looking at them must see the cleared values.
#include <gtest/gtest.h>

#include "device_helpers.h"

namespace refx {
namespace {

using namespace d3d;
using test::drawTL;
using test::makeDevice;
using test::pixel;
using test::TLVertex;
using test::useDiffuseOnly;

// A small red quad over pixels [x0, x1) x [y0, y1) at depth z.
void redQuad(Device& dev, float x0, float y0, float x1, float y1, float z) {
  useDiffuseOnly(dev);
  dev.setRenderState(RS_CULLMODE, CULL_NONE);
  const uint32_t red = 0xffff0000;
  drawTL(dev, PT_TRIANGLESTRIP, {{x0 - 0.5f, y0 - 0.5f, z, 1, red, 0, 0}, {x1 - 0.5f, y0 - 0.5f, z, 1, red, 0, 0},
                                 {x0 - 0.5f, y1 - 0.5f, z, 1, red, 0, 0}, {x1 - 0.5f, y1 - 0.5f, z, 1, red, 0, 0}});
}

TEST(DeferredClear, SeenThroughTheAccessorWithoutADraw) {
  auto dev = makeDevice(100, 70, 0xff000000);
  dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER, 0xff123456, 0.25f, 0);
  EXPECT_EQ(pixel(*dev, 0, 0), 0xff123456u);
  EXPECT_EQ(pixel(*dev, 99, 69), 0xff123456u);
  EXPECT_EQ(dev->depthStencilSurface()->depth[70 * 100 - 1], 0.25f);
}

TEST(DeferredClear, TilesWithoutPrimitivesAreClearedByTheDraw) {
  // 200x150: tiles of 64 pixels; the quad touches only the first tile.
  for (int threads : {1, 2}) {
    auto dev = makeDevice(200, 150, 0xff000000, threads);
    dev->clear(CLEAR_TARGET, 0xff00ff00, 1.0f, 0);
    redQuad(*dev, 2, 2, 6, 6, 0.5f);
    EXPECT_EQ(pixel(*dev, 3, 3), 0xffff0000u);
    EXPECT_EQ(pixel(*dev, 1, 1), 0xff00ff00u);    // same tile, outside the quad
    EXPECT_EQ(pixel(*dev, 199, 149), 0xff00ff00u);  // a tile no primitive touches
    EXPECT_EQ(pixel(*dev, 130, 10), 0xff00ff00u);
  }
}

TEST(DeferredClear, DepthClearAppliesBeforeTheDepthTest) {
  auto dev = makeDevice(80, 80, 0xff000000);
  dev->setRenderState(RS_ZENABLE, ZB_TRUE);
  dev->setRenderState(RS_ZFUNC, CMP_LESS);
  dev->clear(CLEAR_TARGET | CLEAR_ZBUFFER, 0xff0000ff, 0.5f, 0);
  redQuad(*dev, 0, 0, 40, 80, 0.75f);   // behind the cleared depth 0.5: rejected
  redQuad(*dev, 40, 0, 80, 80, 0.25f);  // in front: drawn
  EXPECT_EQ(pixel(*dev, 10, 10), 0xff0000ffu);
  EXPECT_EQ(pixel(*dev, 60, 10), 0xffff0000u);
  EXPECT_EQ(dev->depthStencilSurface()->depth[10 * 80 + 10], 0.5f);
  EXPECT_EQ(dev->depthStencilSurface()->depth[10 * 80 + 60], 0.25f);
}

TEST(DeferredClear, ViewportRectIsKept) {
  auto dev = makeDevice(96, 96, 0xff000000);
  dev->setViewport(Viewport{10, 20, 30, 40, 0, 1});
  dev->clear(CLEAR_TARGET, 0xffffffff, 1.0f, 0);
  dev->setViewport(Viewport{0, 0, 96, 96, 0, 1});
  redQuad(*dev, 90, 90, 94, 94, 0.5f);
  EXPECT_EQ(pixel(*dev, 9, 30), 0xff000000u);
  EXPECT_EQ(pixel(*dev, 10, 20), 0xffffffffu);
  EXPECT_EQ(pixel(*dev, 39, 59), 0xffffffffu);
  EXPECT_EQ(pixel(*dev, 40, 59), 0xff000000u);
  EXPECT_EQ(pixel(*dev, 91, 91), 0xffff0000u);
}

TEST(DeferredClear, HeldTargetIsClearedAtOnce) {
  auto dev = makeDevice(16, 16, 0xff000000);
  TexturePtr held = dev->renderTarget();  // another owner: Clear must not wait for a draw
  dev->clear(CLEAR_TARGET, 0xffabcdef, 1.0f, 0);
  uint32_t v;
  std::memcpy(&v, held->data(0, 0) + 5 * held->rowPitch(0) + 7 * 4, 4);
  EXPECT_EQ(v, 0xffabcdefu);
}

TEST(DeferredClear, SwitchingTargetsWritesThePendingClear) {
  auto dev = makeDevice(16, 16, 0xff000000);
  const Texture* first = dev->renderTarget().get();
  TexturePtr keep = dev->renderTarget();
  keep.reset();  // only the device holds it again
  dev->clear(CLEAR_TARGET, 0xff445566, 1.0f, 0);
  TexturePtr firstPtr;
  {
    // Read the first target through the accessor after switching away and back.
    TexturePtr other = Texture::create2D(Format::A8R8G8B8, 16, 16);
    firstPtr = dev->renderTarget();
    dev->setRenderTarget(other);
    dev->setRenderTarget(firstPtr);
  }
  EXPECT_EQ(dev->renderTarget().get(), first);
  EXPECT_EQ(pixel(*dev, 3, 3), 0xff445566u);
}

}  // namespace
}  // namespace refx
