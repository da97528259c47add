// Inputs whose values agree at every vertex of a draw are interpolated once and copied
// (RasterDraw::inputCopies). Two texture coordinate sets that agree at two vertices of
// a triangle but not at the third must still be interpolated each on its own.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <vector>

#include "device_helpers.h"
#include "refx/shader/assembler.h"

using namespace refx;
using namespace refx::test;
using namespace refx::d3d;

namespace {

struct TwoSetVertex {  // D3DFVF_XYZRHW | D3DFVF_TEX2
  float x, y, z, rhw;
  float u0, v0, u1, v1;
};

// Red = t1.x - t0.x at each pixel of a 64x64 target holding the triangle (0,0),
// (64,0), (0,64), rhw 1 (no perspective).
std::vector<uint32_t> renderDifference(const TwoSetVertex (&tri)[3]) {
  auto dev = makeDevice(64, 64, 0xff000000);
  dev->setRenderState(RS_ZENABLE, ZB_FALSE);
  dev->setRenderState(RS_CULLMODE, CULL_NONE);
  dev->setPixelShader(dev->createPixelShader(
      shader::assembleTokens("ps_2_0\ndcl t0\ndcl t1\nmov r1, t0\nadd r0, t1, -r1\nmov oC0, r0\n", "difference.psh")));
  dev->setFVF(FVF_XYZRHW | fvfTex(2));
  dev->drawPrimitiveUP(PT_TRIANGLELIST, 1, tri, sizeof(TwoSetVertex));
  const Texture& t = *dev->renderTarget(0);
  std::vector<uint32_t> px(64 * 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      std::memcpy(&px[size_t(y) * 64 + size_t(x)], t.data(0, 0) + y * t.rowPitch(0) + x * 4, 4);
  return px;
}

int red(uint32_t argb) { return int(argb >> 16 & 0xff); }

TEST(InputCopies, SetsThatDifferAtOneVertexAreInterpolatedApart) {
  // t0.x = 0.5 everywhere; t1.x = 0.5 but 1.0 at the third vertex (0, 64), so t1.x - t0.x
  // = 0.5 * b3, b3 = y / 64 the third vertex's barycentric weight at pixel centre y.
  const TwoSetVertex tri[3] = {{0, 0, 0.5f, 1, 0.5f, 0.25f, 0.5f, 0.25f},
                               {64, 0, 0.5f, 1, 0.5f, 0.25f, 0.5f, 0.25f},
                               {0, 64, 0.5f, 1, 0.5f, 0.25f, 1.0f, 0.25f}};
  const std::vector<uint32_t> px = renderDifference(tri);
  // (8, 40): 0.5 * 40.5 / 64 = 0.3164, * 255 = 80.7 -> 81; (40, 8): 0.5 * 8.5 / 64 * 255
  // = 16.9 -> 17 (one step either way for the interpolation's rounding).
  EXPECT_NEAR(red(px[40 * 64 + 8]), 81, 1);
  EXPECT_NEAR(red(px[8 * 64 + 40]), 17, 1);
}

TEST(InputCopies, SetsThatAgreeEverywhereGiveNoDifference) {
  // The same values in both sets, different at each vertex: t1 - t0 = 0 at every
  // covered pixel, whether the second set is copied or interpolated.
  const TwoSetVertex tri[3] = {{0, 0, 0.5f, 1, 0.1f, 0.2f, 0.1f, 0.2f},
                               {64, 0, 0.5f, 1, 0.9f, 0.4f, 0.9f, 0.4f},
                               {0, 64, 0.5f, 1, 0.3f, 0.8f, 0.3f, 0.8f}};
  const std::vector<uint32_t> px = renderDifference(tri);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x + y < 63; ++x) ASSERT_EQ(red(px[size_t(y) * 64 + size_t(x)]), 0) << x << "," << y;
}

}  // namespace
