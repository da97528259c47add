// Primitive setup and binning of large draws in ranges on several threads
// (setupPrimitives, rasterize): the primitives must reach each tile in draw order, so
// with no depth test the last primitive over a pixel gives its color, and a strip's
// triangles keep the winding of their position in the whole strip (odd ones swap two
// vertices) whatever range they are set up in. Expected colors follow from the
// geometry alone.
#include <gtest/gtest.h>

#include <vector>

#include "device_helpers.h"

namespace refx::test {
namespace {

constexpr int kSize = 64;
constexpr uint32_t kClear = 0xff000000;

std::unique_ptr<Device> bandDevice(int threads, uint32_t cull) {
  auto dev = makeDevice(kSize, kSize, kClear, threads);
  useDiffuseOnly(*dev);
  dev->setRenderState(d3d::RS_ZENABLE, 0);
  dev->setRenderState(d3d::RS_CULLMODE, cull);
  return dev;
}

// Band r: rows [bandTop(r), bandTop(r) + 4), the whole width, color bandColor(r). The
// bands move down the target as r grows, so the last band over a row comes from every
// part of the draw (each thread's range decides some rows).
int bandTop(int r) { return r * (kSize - 4) / 600; }
uint32_t bandColor(int r) { return 0xff000000u | uint32_t(r) * 0x00010307u % 0x01000000u; }

// 600 bands, two triangles each (1200 primitives, clockwise on screen, so CULL_CCW keeps
// them), drawn in order over each other.
std::vector<TLVertex> bands() {
  std::vector<TLVertex> v;
  for (int r = 0; r < 600; ++r) {
    const float y0 = float(bandTop(r)), y1 = y0 + 4, x1 = float(kSize);
    const uint32_t c = bandColor(r);
    const TLVertex a{0, y0, 0.5f, 1, c, 0, 0}, b{x1, y0, 0.5f, 1, c, 0, 0};
    const TLVertex d{0, y1, 0.5f, 1, c, 0, 0}, e{x1, y1, 0.5f, 1, c, 0, 0};
    for (const TLVertex& t : {a, b, d, b, e, d}) v.push_back(t);
  }
  return v;
}

TEST(ParallelSetup, LastBandOverAPixelGivesItsColorWhateverTheThreadCount) {
  // Row y shows the last band whose rows hold y (pixel centres y + 0.5 inside
  // [top, top + 4)); rows no band covers keep the clear color.
  uint32_t expected[kSize];
  for (int y = 0; y < kSize; ++y) {
    expected[y] = kClear;
    for (int r = 0; r < 600; ++r)
      if (y >= bandTop(r) && y < bandTop(r) + 4) expected[y] = bandColor(r);
  }
  const std::vector<TLVertex> v = bands();
  for (const int threads : {1, 2, 3}) {
    auto dev = bandDevice(threads, d3d::CULL_CCW);
    drawTL(*dev, d3d::PT_TRIANGLELIST, v);
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; x += 9)
        ASSERT_EQ(pixel(*dev, x, y), expected[y]) << threads << " threads, pixel (" << x << ", " << y << ")";
  }
}

// A strip of 1001 thin triangles down the target: vertex 2k at (0, y_k), 2k + 1 at
// (64, y_k). Triangle 0 (v0, v1, v2) is clockwise on screen; the odd ones, swapped, too.
TEST(ParallelSetup, StripTrianglesKeepTheirWindingInEveryRange) {
  constexpr int kTriangles = 1001;
  std::vector<TLVertex> v;
  for (int i = 0; i < kTriangles + 2; ++i) {
    const float y = float(i / 2) * float(kSize) / float((kTriangles + 1) / 2);
    v.push_back({i % 2 ? float(kSize) : 0.0f, y, 0.5f, 1, 0xff20c040u, 0, 0});
  }
  for (const int threads : {1, 2, 3}) {
    for (const uint32_t cull : {uint32_t(d3d::CULL_CCW), uint32_t(d3d::CULL_CW)}) {
      auto dev = bandDevice(threads, cull);
      drawTL(*dev, d3d::PT_TRIANGLESTRIP, v);
      // CULL_CCW keeps every (clockwise) triangle: the strip covers the target; CULL_CW
      // removes them all.
      const uint32_t want = cull == d3d::CULL_CCW ? 0xff20c040u : kClear;
      for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; x += 7)
          ASSERT_EQ(pixel(*dev, x, y), want) << threads << " threads, cull " << cull << ", (" << x << ", " << y << ")";
    }
  }
}

}  // namespace
}  // namespace refx::test
