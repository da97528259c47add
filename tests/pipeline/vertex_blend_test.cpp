// Fixed-function vertex blending through the device API: the 256 world matrices,
// FVF blend layouts, tweening and indexed blending from a vertex declaration.
// VIEW and PROJECTION stay identity, so blended positions are clip space; on a W-pixel
// target clip x maps to screen x = (x + 1) * W/2 and y to (1 - y) * H/2.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "device_helpers.h"
#include "refx/core/diagnostics.h"
#include "refx/resource/vertex_format.h"

namespace refx {
namespace {

using namespace d3d;

Matrix translation(float x, float y, float z) {
  Matrix m = Matrix::identity();
  m.m[3][0] = x, m.m[3][1] = y, m.m[3][2] = z;
  return m;
}

TEST(VertexBlendTransforms, AllWorldMatricesSetAndGet) {
  auto dev = test::makeDevice(4, 4);
  // Every world matrix starts as identity (D3D9's default).
  EXPECT_EQ(dev->getTransform(worldMatrix(255)), Matrix::identity());
  dev->setTransform(worldMatrix(255), translation(1, 2, 3));
  dev->setTransform(worldMatrix(17), translation(4, 5, 6));
  EXPECT_EQ(dev->getTransform(worldMatrix(255)).m[3][1], 2.0f);
  EXPECT_EQ(dev->getTransform(worldMatrix(17)).m[3][2], 6.0f);
  EXPECT_EQ(dev->state().worldMatrix(255).m[3][0], 1.0f);
  // D3DTS_WORLD is D3DTS_WORLDMATRIX(0) = 256, DeviceState::world.
  EXPECT_EQ(worldMatrix(0), uint32_t(TS_WORLD));
  dev->setTransform(worldMatrix(0), translation(7, 8, 9));
  EXPECT_EQ(dev->getTransform(TS_WORLD).m[3][0], 7.0f);
  EXPECT_EQ(dev->state().world.m[3][2], 9.0f);
  EXPECT_EQ(dev->getTransform(worldMatrix(1)), Matrix::identity());
}

TEST(VertexBlendTransforms, IndexBeyond255IsAnError) {
  auto dev = test::makeDevice(4, 4);
  try {
    dev->setTransform(worldMatrix(256), Matrix::identity());  // 512
    FAIL() << "D3DTS_WORLDMATRIX(256) was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("0-255"), std::string::npos) << e.what();
  }
  EXPECT_THROW(dev->getTransform(worldMatrix(300)), Error);
  EXPECT_THROW(dev->setTransform(1000, Matrix::identity()), Error);
  // A failed set changes nothing.
  EXPECT_EQ(dev->getTransform(worldMatrix(255)), Matrix::identity());
}

// D3DFVF_XYZBn: n betas after x y z. With D3DFVF_LASTBETA_* the last beta is the
// BLENDINDICES DWORD; XYZB5 always ends with it (BLENDWEIGHT has at most 4 floats).
TEST(VertexBlendFVF, BetasBecomeBlendWeightAndIndices) {
  struct Case {
    uint32_t fvf;
    int weightType;   // DECLTYPE of BLENDWEIGHT, -1 = none
    int indicesType;  // DECLTYPE of BLENDINDICES, -1 = none
    uint32_t stride;  // 12 + 4 * betas, + 4 for the diffuse color
  };
  const Case cases[] = {
      {FVF_XYZB1, DECLTYPE_FLOAT1, -1, 20},
      {FVF_XYZB2, DECLTYPE_FLOAT2, -1, 24},
      {FVF_XYZB3, DECLTYPE_FLOAT3, -1, 28},
      {FVF_XYZB4, DECLTYPE_FLOAT4, -1, 32},
      {FVF_XYZB5, DECLTYPE_FLOAT4, DECLTYPE_FLOAT1, 36},
      {FVF_XYZB1 | FVF_LASTBETA_UBYTE4, -1, DECLTYPE_UBYTE4, 20},
      {FVF_XYZB2 | FVF_LASTBETA_UBYTE4, DECLTYPE_FLOAT1, DECLTYPE_UBYTE4, 24},
      {FVF_XYZB4 | FVF_LASTBETA_D3DCOLOR, DECLTYPE_FLOAT3, DECLTYPE_D3DCOLOR, 32},
      {FVF_XYZB5 | FVF_LASTBETA_UBYTE4, DECLTYPE_FLOAT4, DECLTYPE_UBYTE4, 36},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.fvf);
    const VertexDeclaration d = VertexDeclaration::fromFVF(c.fvf | FVF_DIFFUSE);
    const VertexElement* w = d.find(DECLUSAGE_BLENDWEIGHT, 0);
    const VertexElement* i = d.find(DECLUSAGE_BLENDINDICES, 0);
    EXPECT_EQ(w ? int(w->type) : -1, c.weightType);
    EXPECT_EQ(i ? int(i->type) : -1, c.indicesType);
    if (w) {
      EXPECT_EQ(w->offset, 12);
    }
    if (i) {
      EXPECT_EQ(i->offset, c.stride - 8);  // the last beta, before the color
    }
    EXPECT_EQ(d.find(DECLUSAGE_COLOR, 0)->offset, c.stride - 4);
    EXPECT_EQ(d.streamStride(0), c.stride);
    // D3DX meshes lay out the same FVF with the same stride.
    EXPECT_EQ(fvfStride(c.fvf | FVF_DIFFUSE), c.stride);
  }
}

TEST(VertexBlendFVF, InvalidCombinationsAreErrors) {
  auto message = [](uint32_t fvf) {
    try {
      VertexDeclaration::fromFVF(fvf);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_NE(message(FVF_XYZB2 | FVF_LASTBETA_UBYTE4 | FVF_LASTBETA_D3DCOLOR).find("exclude"),
            std::string::npos);
  EXPECT_NE(message(FVF_XYZ | FVF_LASTBETA_UBYTE4).find("XYZB1-XYZB5"), std::string::npos);
  EXPECT_NE(message(FVF_XYZRHW | FVF_LASTBETA_D3DCOLOR).find("XYZB1-XYZB5"), std::string::npos);
  // Position bits 0x4006: XYZW's flag with XYZB1's code, no D3D position type.
  EXPECT_NE(message(0x4006).find("not a D3DFVF position type"), std::string::npos);
}

// One stream: POSITION0, POSITION1, NORMAL0, NORMAL1, COLOR0.
struct TweenVertex {
  float p0[3], p1[3], n0[3], n1[3];
  uint32_t color;
};

VertexDeclaration tweenDeclaration() {
  VertexDeclaration d;
  d.elements = {{0, 0, DECLTYPE_FLOAT3, 0, DECLUSAGE_POSITION, 0},
                {0, 12, DECLTYPE_FLOAT3, 0, DECLUSAGE_POSITION, 1},
                {0, 24, DECLTYPE_FLOAT3, 0, DECLUSAGE_NORMAL, 0},
                {0, 36, DECLTYPE_FLOAT3, 0, DECLUSAGE_NORMAL, 1},
                {0, 48, DECLTYPE_D3DCOLOR, 0, DECLUSAGE_COLOR, 0}};
  return d;
}

// A quad over x in [x0, x1], y in [-1, 1] as a strip; POSITION1 = POSITION0 + dx.
std::vector<TweenVertex> tweenQuad(float x0, float x1, float dx, const float n0[3],
                                   const float n1[3], uint32_t color) {
  std::vector<TweenVertex> v;
  for (auto [x, y] : {std::pair{x0, 1.0f}, {x1, 1.0f}, {x0, -1.0f}, {x1, -1.0f}}) {
    TweenVertex t{{x, y, 0.5f}, {x + dx, y, 0.5f}, {}, {}, color};
    std::memcpy(t.n0, n0, sizeof t.n0);
    std::memcpy(t.n1, n1, sizeof t.n1);
    v.push_back(t);
  }
  return v;
}

TEST(VertexBlendTweening, PositionMovesByTweenFactor) {
  // POSITION = POSITION0 * (1 - t) + POSITION1 * t with t = 0.25 and POSITION1 =
  // POSITION0 + (1, 0, 0): x + 0.25. The quad x in [-1, 0] covers [-0.75, 0.25], screen
  // x = (x + 1)*8 in [2, 10] on a 16-pixel target. (t ignored: [0, 8]; POSITION1 alone:
  // [8, 16].)
  auto dev = test::makeDevice(16, 4);
  test::useDiffuseOnly(*dev);
  dev->setRenderState(RS_LIGHTING, 0);
  dev->setRenderState(RS_VERTEXBLEND, VBF_TWEENING);
  dev->setRenderState(RS_TWEENFACTOR, floatBits(0.25f));
  dev->setVertexDeclaration(tweenDeclaration());
  const float n[3] = {0, 0, -1};
  auto v = tweenQuad(-1, 0, 1, n, n, 0xff00ff00);
  dev->drawPrimitiveUP(PT_TRIANGLESTRIP, 2, v.data(), sizeof(TweenVertex));
  EXPECT_EQ(test::pixel(*dev, 1, 2), 0xff000000u);
  EXPECT_EQ(test::pixel(*dev, 3, 2), 0xff00ff00u);
  EXPECT_EQ(test::pixel(*dev, 9, 2), 0xff00ff00u);
  EXPECT_EQ(test::pixel(*dev, 11, 2), 0xff000000u);
}

TEST(VertexBlendTweening, NormalsAreTweenedBeforeLighting) {
  // NORMAL0 = (0, 0, -1), NORMAL1 = (-1, 0, 0), t = 0.5: N = (-0.5, 0, -0.5).
  // Directional light along (1, 0, 1): L = (-1, 0, -1)/sqrt(2). Material and light diffuse
  // white, no ambient: color = N.L.
  //   NORMALIZENORMALS FALSE: N.L = 1/sqrt(2) = 0.7071 -> 180.3 -> 180 (+-1)
  //   NORMALIZENORMALS TRUE:  N = (-1, 0, -1)/sqrt(2), N.L = 1 -> 255
  // (Either normal alone gives 0.7071 with or without normalization.)
  for (bool normalize : {false, true}) {
    SCOPED_TRACE(normalize);
    auto dev = test::makeDevice(4, 4);
    test::useDiffuseOnly(*dev);
    Material m;
    m.diffuse = {1, 1, 1, 1};
    dev->setMaterial(m);
    Light l;
    l.type = LIGHT_DIRECTIONAL;
    l.diffuse = {1, 1, 1, 1};
    l.direction = {1, 0, 1};
    dev->setLight(0, l);
    dev->lightEnable(0, true);
    dev->setRenderState(RS_NORMALIZENORMALS, normalize);
    dev->setRenderState(RS_VERTEXBLEND, VBF_TWEENING);
    dev->setRenderState(RS_TWEENFACTOR, floatBits(0.5f));
    dev->setVertexDeclaration(tweenDeclaration());
    const float n0[3] = {0, 0, -1}, n1[3] = {-1, 0, 0};
    auto v = tweenQuad(-1, 1, 0, n0, n1, 0xffffffff);
    // The vertices carry a diffuse color; lighting takes the material's (MCS_MATERIAL).
    dev->setRenderState(RS_DIFFUSEMATERIALSOURCE, MCS_MATERIAL);
    dev->drawPrimitiveUP(PT_TRIANGLESTRIP, 2, v.data(), sizeof(TweenVertex));
    const uint32_t p = test::pixel(*dev, 2, 2);
    const int g = int((p >> 8) & 0xff);
    if (normalize) {
      EXPECT_EQ(p, 0xffffffffu);
    } else {
      EXPECT_NEAR(g, 180, 1) << std::hex << p;
    }
  }
}

// Indexed blending from a declaration: BLENDWEIGHT FLOAT2 and BLENDINDICES UBYTE4.
struct SkinVertex {
  float x, y, z;
  float weights[2];
  uint8_t indices[4];
  uint32_t color;
};

TEST(VertexBlendIndexed, DeclarationBlendWeightAndIndices) {
  // D3DVBF_2WEIGHTS, indices (3, 17, 250), weights (0.5, 0.25) and 1 - 0.75 = 0.25.
  // WORLD3 translates by (+1, 0, 0), WORLD17 by (-1, 0, 0), WORLD250 by (0, +1, 0):
  // P' = P + (0.5 - 0.25, 0.25, 0). The quad x, y in [-1, 0] covers x, y in
  // [-0.75, 0.25]: screen x in [2, 10], screen y = (1 - y)*8 in [6, 14] (16x16).
  // WORLD0-2 (non-indexed blending) move it off screen.
  auto dev = test::makeDevice(16, 16);
  test::useDiffuseOnly(*dev);
  dev->setRenderState(RS_LIGHTING, 0);
  dev->setRenderState(RS_VERTEXBLEND, VBF_2WEIGHTS);
  dev->setRenderState(RS_INDEXEDVERTEXBLENDENABLE, 1);
  for (int i = 0; i < 3; ++i) dev->setTransform(worldMatrix(i), translation(-5, 0, 0));
  dev->setTransform(worldMatrix(3), translation(1, 0, 0));
  dev->setTransform(worldMatrix(17), translation(-1, 0, 0));
  dev->setTransform(worldMatrix(250), translation(0, 1, 0));
  VertexDeclaration d;
  d.elements = {{0, 0, DECLTYPE_FLOAT3, 0, DECLUSAGE_POSITION, 0},
                {0, 12, DECLTYPE_FLOAT2, 0, DECLUSAGE_BLENDWEIGHT, 0},
                {0, 20, DECLTYPE_UBYTE4, 0, DECLUSAGE_BLENDINDICES, 0},
                {0, 24, DECLTYPE_D3DCOLOR, 0, DECLUSAGE_COLOR, 0}};
  dev->setVertexDeclaration(d);
  std::vector<SkinVertex> v;
  for (auto [x, y] : {std::pair{-1.0f, 0.0f}, {0.0f, 0.0f}, {-1.0f, -1.0f}, {0.0f, -1.0f}})
    v.push_back({x, y, 0.5f, {0.5f, 0.25f}, {3, 17, 250, 0}, 0xffff0000});
  dev->drawPrimitiveUP(PT_TRIANGLESTRIP, 2, v.data(), sizeof(SkinVertex));
  EXPECT_EQ(test::pixel(*dev, 3, 7), 0xffff0000u);
  EXPECT_EQ(test::pixel(*dev, 9, 13), 0xffff0000u);
  EXPECT_EQ(test::pixel(*dev, 1, 10), 0xff000000u);
  EXPECT_EQ(test::pixel(*dev, 11, 10), 0xff000000u);
  EXPECT_EQ(test::pixel(*dev, 5, 4), 0xff000000u);
  EXPECT_EQ(test::pixel(*dev, 5, 15), 0xff000000u);
}

}  // namespace
}  // namespace refx
