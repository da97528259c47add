// D3DX mesh layouts with blend weights: D3DFVF_XYZB1-5 hold x y z and 1-5 betas; the
// last beta is the packed matrix indices with D3DFVF_LASTBETA_* (and always for XYZB5).
#include <gtest/gtest.h>

#include <cstring>

#include "refx/d3dx/mesh.h"

using namespace refx;
using namespace refx::d3dx;

TEST(MeshBlendFVF, LayoutOfBetas) {
  // XYZB1: 12 + 4 bytes, one weight.
  FVFLayout a = FVFLayout::of(d3d::FVF_XYZB1 | d3d::FVF_NORMAL);
  EXPECT_EQ(a.blendWeights, 12);
  EXPECT_EQ(a.blendWeightCount, 1);
  EXPECT_EQ(a.blendIndices, -1);
  EXPECT_EQ(a.normal, 16);
  EXPECT_EQ(a.stride, 28u);
  // XYZB3 | LASTBETA_UBYTE4: two weights, then the indices DWORD at 12 + 8.
  FVFLayout b = FVFLayout::of(d3d::FVF_XYZB3 | d3d::FVF_LASTBETA_UBYTE4 | d3d::FVF_DIFFUSE);
  EXPECT_EQ(b.blendWeightCount, 2);
  EXPECT_EQ(b.blendIndices, 20);
  EXPECT_EQ(b.diffuse, 24);
  EXPECT_EQ(b.stride, 28u);
  // XYZB5: four weights and the indices; 12 + 20 bytes.
  FVFLayout c = FVFLayout::of(d3d::FVF_XYZB5);
  EXPECT_EQ(c.blendWeightCount, 4);
  EXPECT_EQ(c.blendIndices, 28);
  EXPECT_EQ(c.stride, 32u);
  // XYZB1 | LASTBETA_D3DCOLOR: the only beta is the indices.
  FVFLayout d = FVFLayout::of(d3d::FVF_XYZB1 | d3d::FVF_LASTBETA_D3DCOLOR);
  EXPECT_EQ(d.blendWeightCount, 0);
  EXPECT_EQ(d.blendWeights, -1);
  EXPECT_EQ(d.blendIndices, 12);
  EXPECT_EQ(fvfStride(d3d::FVF_XYZB1 | d3d::FVF_LASTBETA_D3DCOLOR), 16u);
}

TEST(MeshBlendFVF, CloneCarriesWeightsAndIndices) {
  // XYZB3 | LASTBETA_UBYTE4 (weights 0.25, 0.5; indices 0x00c80701) cloned to
  // XYZB2 | LASTBETA_UBYTE4 keeps the first weight and the indices; to XYZB4 |
  // LASTBETA_UBYTE4 keeps both weights, the third reads 0.
  Mesh m(d3d::FVF_XYZB3 | d3d::FVF_LASTBETA_UBYTE4, 1, 0);
  const float v[5] = {1, 2, 3, 0.25f, 0.5f};
  const uint32_t indices = 0x00c80701;
  std::memcpy(m.vertices.data(), v, sizeof v);
  std::memcpy(m.vertices.data() + 20, &indices, 4);

  Mesh fewer = cloneMeshFVF(m, d3d::FVF_XYZB2 | d3d::FVF_LASTBETA_UBYTE4);
  ASSERT_EQ(fewer.stride, 20u);
  float f[4];
  uint32_t i;
  std::memcpy(f, fewer.vertices.data(), 16);
  std::memcpy(&i, fewer.vertices.data() + 16, 4);
  EXPECT_EQ(f[2], 3.0f);
  EXPECT_EQ(f[3], 0.25f);
  EXPECT_EQ(i, indices);

  Mesh more = cloneMeshFVF(m, d3d::FVF_XYZB4 | d3d::FVF_LASTBETA_UBYTE4);
  ASSERT_EQ(more.stride, 28u);
  float g[6];
  std::memcpy(g, more.vertices.data(), 24);
  std::memcpy(&i, more.vertices.data() + 24, 4);
  EXPECT_EQ(g[3], 0.25f);
  EXPECT_EQ(g[4], 0.5f);
  EXPECT_EQ(g[5], 0.0f);
  EXPECT_EQ(i, indices);
}
