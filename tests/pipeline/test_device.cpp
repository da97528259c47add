// Device API behaviour: state blocks, render-to-texture, indexed draws from vertex
// and index buffers, lines, points, fill modes, clears and FVF layouts.
#include <gtest/gtest.h>

#include "device_helpers.h"
#include "refx/core/diagnostics.h"

using namespace refx;
using namespace refx::test;
using namespace refx::d3d;

namespace {

TEST(Device, DefaultsFollowD3D9) {
  DeviceState s;
  EXPECT_EQ(s.rs(RS_CULLMODE), uint32_t(CULL_CCW));
  EXPECT_EQ(s.rs(RS_LIGHTING), 1u);
  EXPECT_EQ(s.rs(RS_ZENABLE), uint32_t(ZB_FALSE));
  EXPECT_EQ(s.rs(RS_ZFUNC), uint32_t(CMP_LESSEQUAL));
  EXPECT_EQ(s.rs(RS_COLORWRITEENABLE), 0xfu);
  EXPECT_EQ(s.rsFloat(RS_FOGEND), 1.0f);
  EXPECT_EQ(s.tss(0, TSS_COLOROP), uint32_t(TOP_MODULATE));
  EXPECT_EQ(s.tss(0, TSS_ALPHAOP), uint32_t(TOP_SELECTARG1));
  EXPECT_EQ(s.tss(1, TSS_COLOROP), uint32_t(TOP_DISABLE));
  EXPECT_EQ(s.tss(3, TSS_TEXCOORDINDEX), 3u);
  EXPECT_EQ(s.samp(0, SAMP_ADDRESSU), 1u);  // WRAP
  EXPECT_EQ(s.samp(0, SAMP_MAGFILTER), 1u);  // POINT
}

TEST(Device, FVFLayoutOffsets) {
  // XYZ(12) NORMAL(12) DIFFUSE(4) SPECULAR(4) TEX2 with set 0 = 2 floats, set 1 = 3 floats.
  const uint32_t fvf = FVF_XYZ | FVF_NORMAL | FVF_DIFFUSE | FVF_SPECULAR | (2u << FVF_TEXCOUNT_SHIFT) |
                       fvfTexCoordSize(3, 1);
  VertexDeclaration d = VertexDeclaration::fromFVF(fvf);
  ASSERT_EQ(d.elements.size(), 6u);
  EXPECT_EQ(d.find(DECLUSAGE_NORMAL, 0)->offset, 12);
  EXPECT_EQ(d.find(DECLUSAGE_COLOR, 0)->offset, 24);
  EXPECT_EQ(d.find(DECLUSAGE_COLOR, 1)->offset, 28);
  EXPECT_EQ(d.find(DECLUSAGE_TEXCOORD, 0)->offset, 32);
  EXPECT_EQ(d.find(DECLUSAGE_TEXCOORD, 1)->offset, 40);
  EXPECT_EQ(d.find(DECLUSAGE_TEXCOORD, 1)->type, DECLTYPE_FLOAT3);
  EXPECT_EQ(d.streamStride(0), 52u);  // 40 + 12
}

TEST(Device, StateBlockCaptureAndApply) {
  auto dev = makeDevice(4, 4);
  dev->setRenderState(RS_SRCBLEND, BLEND_SRCALPHA);
  dev->setTextureStageState(1, TSS_COLOROP, TOP_ADD);
  dev->setSamplerState(2, SAMP_ADDRESSU, 3);
  StateBlock sb = dev->createStateBlock();
  dev->setRenderState(RS_SRCBLEND, BLEND_ONE);
  dev->setTextureStageState(1, TSS_COLOROP, TOP_DISABLE);
  dev->setSamplerState(2, SAMP_ADDRESSU, 1);
  dev->applyStateBlock(sb);
  EXPECT_EQ(dev->getRenderState(RS_SRCBLEND), uint32_t(BLEND_SRCALPHA));
  EXPECT_EQ(dev->getTextureStageState(1, TSS_COLOROP), uint32_t(TOP_ADD));
  EXPECT_EQ(dev->getSamplerState(2, SAMP_ADDRESSU), 3u);
}

TEST(Device, ClearRespectsViewport) {
  auto dev = makeDevice(8, 8, 0xff000000);
  dev->setViewport(Viewport{2, 2, 4, 4, 0, 1});
  dev->clear(CLEAR_TARGET, 0xff00ff00, 1.0f, 0);
  EXPECT_EQ(pixel(*dev, 1, 1), 0xff000000u);
  EXPECT_EQ(pixel(*dev, 2, 2), 0xff00ff00u);
  EXPECT_EQ(pixel(*dev, 5, 5), 0xff00ff00u);
  EXPECT_EQ(pixel(*dev, 6, 6), 0xff000000u);
}

TEST(Device, RenderToTextureThenSampleIt) {
  // Pass 1 renders a red/green split into an 8x8 texture; pass 2 maps that texture 1:1
  // onto the 8x8 back buffer with point sampling.
  auto dev = makeDevice(8, 8, 0xff000000);
  TexturePtr backBuffer = dev->renderTarget();
  TexturePtr rtt = Texture::create2D(Format::A8R8G8B8, 8, 8);
  dev->setRenderTarget(rtt);
  dev->clear(CLEAR_TARGET, 0xff00ff00, 1.0f, 0);  // green
  useDiffuseOnly(*dev);
  dev->setRenderState(RS_CULLMODE, CULL_NONE);
  // Left half red: x in [-0.5, 3.5).
  drawTL(*dev, PT_TRIANGLESTRIP, {{-0.5f, -0.5f, 0.5f, 1, 0xffff0000, 0, 0}, {3.5f, -0.5f, 0.5f, 1, 0xffff0000, 0, 0},
                                  {-0.5f, 7.5f, 0.5f, 1, 0xffff0000, 0, 0}, {3.5f, 7.5f, 0.5f, 1, 0xffff0000, 0, 0}});
  dev->setRenderTarget(backBuffer);
  dev->setTexture(0, rtt);
  dev->setTextureStageState(0, TSS_COLOROP, TOP_SELECTARG1);
  dev->setTextureStageState(0, TSS_COLORARG1, TA_TEXTURE);
  drawTL(*dev, PT_TRIANGLESTRIP, {{-0.5f, -0.5f, 0.5f, 1, 0xffffffff, 0, 0}, {7.5f, -0.5f, 0.5f, 1, 0xffffffff, 1, 0},
                                  {-0.5f, 7.5f, 0.5f, 1, 0xffffffff, 0, 1}, {7.5f, 7.5f, 0.5f, 1, 0xffffffff, 1, 1}});
  EXPECT_EQ(pixel(*dev, 1, 4), 0xffff0000u);
  EXPECT_EQ(pixel(*dev, 3, 4), 0xffff0000u);
  EXPECT_EQ(pixel(*dev, 4, 4), 0xff00ff00u);
  EXPECT_EQ(pixel(*dev, 6, 4), 0xff00ff00u);
}

TEST(Device, IndexedDrawFromBuffers16And32Bit) {
  for (bool index32 : {false, true}) {
    auto dev = makeDevice(8, 8, 0xff000000);
    useDiffuseOnly(*dev);
    dev->setRenderState(RS_CULLMODE, CULL_NONE);
    // Two unused vertices first; baseVertex 2 skips them.
    std::vector<TLVertex> v = {{0, 0, 0, 1, 0xff0000ff, 0, 0},      {0, 0, 0, 1, 0xff0000ff, 0, 0},
                               {-0.5f, -0.5f, 0.5f, 1, 0xffffff00, 0, 0}, {7.5f, -0.5f, 0.5f, 1, 0xffffff00, 0, 0},
                               {-0.5f, 7.5f, 0.5f, 1, 0xffffff00, 0, 0},  {7.5f, 7.5f, 0.5f, 1, 0xffffff00, 0, 0}};
    auto vb = std::make_shared<VertexBuffer>();
    vb->data.resize(v.size() * sizeof(TLVertex));
    std::memcpy(vb->data.data(), v.data(), vb->data.size());
    auto ib = std::make_shared<IndexBuffer>();
    ib->index32 = index32;
    const uint32_t idx[6] = {0, 1, 2, 2, 1, 3};
    for (uint32_t i : idx) {
      const size_t n = index32 ? 4 : 2;
      const size_t at = ib->data.size();
      ib->data.resize(at + n);
      std::memcpy(ib->data.data() + at, &i, n);  // little-endian low bytes for 16-bit
    }
    dev->setFVF(kTLVertexFVF);
    dev->setStreamSource(0, vb, 0, sizeof(TLVertex));
    dev->setIndices(ib);
    dev->drawIndexedPrimitive(PT_TRIANGLELIST, 2, 0, 4, 0, 2);
    EXPECT_EQ(pixel(*dev, 0, 0), 0xffffff00u) << index32;
    EXPECT_EQ(pixel(*dev, 7, 7), 0xffffff00u) << index32;
  }
}

TEST(Device, LineListDrawsOnePixelPerColumn) {
  // Horizontal line from x = 0 to x = 6 along pixel row 2: pixels (0..6, 2) lit, row 1/3 not.
  auto dev = makeDevice(8, 8, 0xff000000);
  useDiffuseOnly(*dev);
  drawTL(*dev, PT_LINELIST, {{0, 2, 0.5f, 1, 0xffffffff, 0, 0}, {6, 2, 0.5f, 1, 0xffffffff, 0, 0}});
  for (int x = 0; x <= 6; ++x) {
    EXPECT_EQ(pixel(*dev, x, 2), 0xffffffffu) << x;
    EXPECT_EQ(pixel(*dev, x, 1), 0xff000000u) << x;
    EXPECT_EQ(pixel(*dev, x, 3), 0xff000000u) << x;
  }
  // A 45-degree line (1,1)-(5,5) lights the diagonal pixels only.
  auto dev2 = makeDevice(8, 8, 0xff000000);
  useDiffuseOnly(*dev2);
  drawTL(*dev2, PT_LINELIST, {{1, 1, 0.5f, 1, 0xffffffff, 0, 0}, {5, 5, 0.5f, 1, 0xffffffff, 0, 0}});
  for (int i = 1; i <= 4; ++i) {
    EXPECT_EQ(pixel(*dev2, i, i), 0xffffffffu) << i;
    EXPECT_EQ(pixel(*dev2, i + 1, i), 0xff000000u) << i;
  }
}

TEST(Device, PointListDrawsThePixelAtTheCentre) {
  auto dev = makeDevice(8, 8, 0xff000000);
  useDiffuseOnly(*dev);
  // Point size 1 at (3,5): the pixel whose centre is (3,5).
  drawTL(*dev, PT_POINTLIST, {{3, 5, 0.5f, 1, 0xff00ffff, 0, 0}});
  EXPECT_EQ(pixel(*dev, 3, 5), 0xff00ffffu);
  EXPECT_EQ(pixel(*dev, 2, 5), 0xff000000u);
  EXPECT_EQ(pixel(*dev, 4, 5), 0xff000000u);
  EXPECT_EQ(pixel(*dev, 3, 4), 0xff000000u);
}

TEST(Device, WireframeFillDrawsEdgesOnly) {
  auto dev = makeDevice(16, 16, 0xff000000);
  useDiffuseOnly(*dev);
  dev->setRenderState(RS_FILLMODE, FILL_WIREFRAME);
  dev->setRenderState(RS_CULLMODE, CULL_NONE);
  drawTL(*dev, PT_TRIANGLELIST, {{2, 2, 0.5f, 1, 0xffffffff, 0, 0}, {12, 2, 0.5f, 1, 0xffffffff, 0, 0},
                                 {2, 12, 0.5f, 1, 0xffffffff, 0, 0}});
  EXPECT_EQ(pixel(*dev, 6, 2), 0xffffffffu);   // top edge
  EXPECT_EQ(pixel(*dev, 2, 6), 0xffffffffu);   // left edge
  EXPECT_EQ(pixel(*dev, 4, 4), 0xff000000u);   // interior stays empty
}

TEST(Device, FlatShadingUsesFirstVertexColor) {
  auto dev = makeDevice(8, 8, 0xff000000);
  useDiffuseOnly(*dev);
  dev->setRenderState(RS_SHADEMODE, SHADE_FLAT);
  dev->setRenderState(RS_CULLMODE, CULL_NONE);
  drawTL(*dev, PT_TRIANGLELIST, {{-0.5f, -0.5f, 0.5f, 1, 0xffff0000, 0, 0}, {7.5f, -0.5f, 0.5f, 1, 0xff00ff00, 0, 0},
                                 {-0.5f, 7.5f, 0.5f, 1, 0xff0000ff, 0, 0}});
  EXPECT_EQ(pixel(*dev, 1, 1), 0xffff0000u);
  EXPECT_EQ(pixel(*dev, 4, 2), 0xffff0000u);
}

TEST(Device, DrawWithoutRenderTargetIsAnError) {
  Device dev{CapsProfile{}, {}};
  useDiffuseOnly(dev);
  std::vector<TLVertex> v(3);
  dev.setFVF(kTLVertexFVF);
  EXPECT_THROW(dev.drawPrimitiveUP(PT_TRIANGLELIST, 1, v.data(), sizeof(TLVertex)), Error);
}

TEST(Device, VertexBufferTooSmallIsAnError) {
  auto dev = makeDevice(4, 4);
  auto vb = std::make_shared<VertexBuffer>();
  vb->data.resize(2 * sizeof(TLVertex));
  dev->setFVF(kTLVertexFVF);
  dev->setStreamSource(0, vb, 0, sizeof(TLVertex));
  EXPECT_THROW(dev->drawPrimitive(PT_TRIANGLELIST, 0, 1), Error);
}

}  // namespace
