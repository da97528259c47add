// SetClipPlane / GetClipPlane, the clip-space form of user planes, the w-buffer's far
// plane and the caps' MaxPointSize, driven through refx::Device and the pipeline's
// clipping helpers.
#include <gtest/gtest.h>

#include <limits>

#include "device_helpers.h"
#include "pipeline/clip.h"
#include "pipeline/depth.h"
#include "refx/core/diagnostics.h"

using namespace refx;
using namespace refx::test;
using namespace refx::d3d;

namespace {

TEST(ClipPlanes, SetAndGetRoundTripAndRangeIsChecked) {
  auto dev = makeDevice(4, 4);
  EXPECT_EQ(dev->getClipPlane(5), Vec4(0, 0, 0, 0));  // D3D9 default: all zero
  const float plane[4] = {1, -2, 3, 0.5f};
  dev->setClipPlane(5, plane);
  EXPECT_EQ(dev->getClipPlane(5), Vec4(1, -2, 3, 0.5f));
  EXPECT_EQ(dev->state().clipPlanes[5], Vec4(1, -2, 3, 0.5f));
  EXPECT_THROW(dev->setClipPlane(6, plane), Error);
  EXPECT_THROW(dev->setClipPlane(-1, plane), Error);
  EXPECT_THROW(dev->getClipPlane(6), Error);
  // A state block captures the planes.
  const StateBlock sb = dev->createStateBlock();
  const float other[4] = {0, 0, 0, 0};
  dev->setClipPlane(5, other);
  dev->applyStateBlock(sb);
  EXPECT_EQ(dev->getClipPlane(5), Vec4(1, -2, 3, 0.5f));
}

TEST(ClipPlanes, FixedFunctionPlanesGoThroughTheInverseTransposeOfViewProjection) {
  DeviceState st;
  st.clipPlanes[0] = Vec4(1, 0, 0, 0.5f);  // world x >= -0.5
  st.clipPlanes[3] = Vec4(0, 1, 0, 0);
  st.renderStates[RS_CLIPPLANEENABLE] = 1u | 8u;
  st.view = matrixTranslation(0.5f, 0, 0);
  st.projection = matrixScaling(2, 1, 1);
  // clip x = 2 * (world x + 0.5): world x >= -0.5 is clip x >= 0 -> (1, 0, 0, 0);
  // world y >= 0 is clip y >= 0 -> (0, 1, 0, 0) (planes up to a positive factor).
  pipeline::ClipPlanes planes;
  pipeline::userClipPlanes(st, false, planes);
  ASSERT_EQ(planes.userCount, 2);
  EXPECT_NEAR(planes.user[0].x, 0.5f, 1e-6f);  // (1, 0, 0, 0.5) * inverse-transpose
  EXPECT_NEAR(planes.user[0].w, 0.0f, 1e-6f);
  EXPECT_EQ(planes.user[1], Vec4(0, 1, 0, 0));
  // The point on the plane (clip x = 0) is kept, just left of it is not.
  EXPECT_TRUE(planes.insideUser(Vec4(0, 0, 0.5f, 1)));
  EXPECT_FALSE(planes.insideUser(Vec4(-0.01f, 0, 0.5f, 1)));
  // With a vertex shader the planes are already in clip space.
  pipeline::userClipPlanes(st, true, planes);
  ASSERT_EQ(planes.userCount, 2);
  EXPECT_EQ(planes.user[0], Vec4(1, 0, 0, 0.5f));
  // D3DRS_CLIPPING FALSE: no clipping at all.
  st.renderStates[RS_CLIPPING] = 0;
  pipeline::userClipPlanes(st, false, planes);
  EXPECT_EQ(planes.userCount, 0);
}

TEST(ClipPlanes, PolygonClippedByAUserPlaneKeepsTheInsidePart) {
  pipeline::ClipPlanes planes;
  planes.guardBand = 4;
  planes.userCount = 1;
  planes.user[0] = Vec4(1, 0, 0, 0);  // x >= 0
  std::vector<pipeline::ClipVertex> poly(3);
  poly[0].v[0] = Vec4(-1, -1, 0.5f, 1);
  poly[1].v[0] = Vec4(1, -1, 0.5f, 1);
  poly[2].v[0] = Vec4(1, 1, 0.5f, 1);
  poly[0].v[1] = Vec4(0, 0, 0, 0);  // a varying: 0 at x = -1, 1 at x = 1
  poly[1].v[1] = Vec4(1, 0, 0, 0);
  poly[2].v[1] = Vec4(1, 0, 0, 0);
  pipeline::clipPolygon(poly, planes);
  // The triangle (-1,-1) (1,-1) (1,1) cut at x = 0: (0,-1) (1,-1) (1,1) (0,0).
  ASSERT_EQ(poly.size(), 4u);
  for (const auto& v : poly) EXPECT_GE(v.v[0].x, 0.0f);
  // The new vertices carry the varying at the cut: halfway, 0.5.
  int cut = 0;
  for (const auto& v : poly)
    if (v.v[0].x == 0) {
      EXPECT_FLOAT_EQ(v.v[1].x, 0.5f);
      ++cut;
    }
  EXPECT_EQ(cut, 2);
}

TEST(DepthBuffer, FarPlaneWOfProjections) {
  // W-friendly perspective (zn, zf): _33 = zf/(zf-zn), _43 = -zn*zf/(zf-zn), _34 = 1
  // -> w at the far plane = zf.
  Matrix p = Matrix::identity();
  p.m[2][2] = 50.0f / 49.5f;
  p.m[3][2] = -0.5f * 50.0f / 49.5f;
  p.m[2][3] = 1;
  p.m[3][3] = 0;
  EXPECT_NEAR(pipeline::projectionFarW(p), 50.0f, 1e-3f);
  // Identity (orthographic, w = 1 everywhere): 1.
  EXPECT_EQ(pipeline::projectionFarW(Matrix::identity()), 1.0f);
  // _33 = _34: no far plane -> 1.
  p.m[2][2] = 1;
  EXPECT_EQ(pipeline::projectionFarW(p), 1.0f);
}

TEST(DepthBuffer, DepthOffsetIsBiasPlusSlopeScaleTimesTheLargerSlope) {
  // 0.25 + 2 * max(|-0.5|, |0.125|) = 1.25
  EXPECT_FLOAT_EQ(pipeline::depthOffset(0.25f, 2.0f, -0.5f, 0.125f), 1.25f);
  EXPECT_FLOAT_EQ(pipeline::depthOffset(-0.001f, 0.0f, 3.0f, 3.0f), -0.001f);
}

TEST(Points, MaxPointSizeOneDrawsOnePixelWhateverThePointSize) {
  // CapsProfile{} has MaxPointSize 1 (no point size control): POINTSIZE 8 draws the
  // single pixel whose centre is the vertex.
  auto dev = makeDevice(8, 8, 0xff000000);
  useDiffuseOnly(*dev);
  dev->setRenderState(RS_POINTSIZE, floatBits(8.0f));
  drawTL(*dev, PT_POINTLIST, {{3, 5, 0.5f, 1, 0xff00ffff, 0, 0}});
  EXPECT_EQ(pixel(*dev, 3, 5), 0xff00ffffu);
  EXPECT_EQ(pixel(*dev, 2, 5), 0xff000000u);
  EXPECT_EQ(pixel(*dev, 4, 5), 0xff000000u);
  EXPECT_EQ(pixel(*dev, 3, 4), 0xff000000u);
  // MaxPointSize 4: POINTSIZE 8 is limited to 4 -> [1, 5) x [3, 7).
  CapsProfile caps = dev->caps();
  caps.maxPointSize = 4;
  dev->setCaps(caps);
  drawTL(*dev, PT_POINTLIST, {{3, 5, 0.5f, 1, 0xffff0000, 0, 0}});
  EXPECT_EQ(pixel(*dev, 1, 3), 0xffff0000u);
  EXPECT_EQ(pixel(*dev, 4, 6), 0xffff0000u);
  EXPECT_EQ(pixel(*dev, 0, 5), 0xff000000u);
  EXPECT_EQ(pixel(*dev, 5, 5), 0xff000000u);
  EXPECT_EQ(pixel(*dev, 3, 7), 0xff000000u);
}

TEST(Points, NonFiniteSizesAndPositionsDoNotCrash) {
  auto dev = makeDevice(8, 8, 0xff000000);
  CapsProfile caps = dev->caps();
  caps.maxPointSize = 256;
  dev->setCaps(caps);
  useDiffuseOnly(*dev);
  struct SizedVertex {
    float x, y, z, rhw, psize;
    uint32_t diffuse;
  };
  dev->setFVF(FVF_XYZRHW | FVF_PSIZE | FVF_DIFFUSE);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const SizedVertex v[] = {
      {3, 5, 0.5f, 1, nan, 0xff00ff00},    // NaN size: drawn as size 1
      {1e30f, 2, 0.5f, 1, 4, 0xffff0000},  // far off the target: nothing
      {nan, 2, 0.5f, 1, 4, 0xffff0000},    // NaN position: nothing
      {6, 1, 0.5f, 1, inf, 0xffff0000},    // infinite size: POINTSIZE_MAX 64, the whole target
  };
  dev->drawPrimitiveUP(PT_POINTLIST, 3, v, sizeof(SizedVertex));
  EXPECT_EQ(pixel(*dev, 3, 5), 0xff00ff00u);
  EXPECT_EQ(pixel(*dev, 2, 5), 0xff000000u);
  EXPECT_EQ(pixel(*dev, 7, 7), 0xff000000u);
  dev->drawPrimitiveUP(PT_POINTLIST, 1, v + 3, sizeof(SizedVertex));
  EXPECT_EQ(pixel(*dev, 0, 0), 0xffff0000u);
  EXPECT_EQ(pixel(*dev, 7, 7), 0xffff0000u);
}

}  // namespace
