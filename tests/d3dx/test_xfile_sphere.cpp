// A .x sphere written outside refx (tests/d3dx/data/sphere.x: 8 slices x 6 stacks of
// quads, per-vertex normals, texture coordinates, two materials, a template block).
#include <gtest/gtest.h>

#include <cmath>

#include "refx/d3dx/xfile.h"

using namespace refx;

namespace {

TEST(XFileSphere, HandWrittenSphereWithMaterialListLoads) {
  const d3dx::Mesh m = d3dx::loadXFile(std::string(REFX_TEST_DIR) + "/d3dx/data/sphere.x");
  // (6 + 1) rings of (8 + 1) vertices = 63; 48 quads fanned into 96 triangles.
  ASSERT_EQ(m.vertexCount(), 63u);
  ASSERT_EQ(m.faceCount(), 96u);
  for (uint32_t i = 0; i < m.vertexCount(); ++i) {
    const Vec3 p = m.position(i), n = m.normal(i);
    EXPECT_NEAR(length(p), 1.0f, 1e-5f) << i;  // unit sphere
    EXPECT_NEAR(n.x, p.x, 1e-5f) << i;         // normal = position on a unit sphere
    EXPECT_NEAR(n.y, p.y, 1e-5f) << i;
    EXPECT_NEAR(n.z, p.z, 1e-5f) << i;
  }
  // Vertex 9 = ring 1, slice 0: (u, v) = (0/8, 1/6), position (0, cos 30deg, sin 30deg).
  EXPECT_NEAR(m.texCoord(9, 0).x, 0.0f, 1e-6f);
  EXPECT_NEAR(m.texCoord(9, 0).y, 1.0f / 6.0f, 1e-6f);
  EXPECT_NEAR(m.position(9).y, std::sqrt(3.0f) / 2, 1e-5f);
  EXPECT_NEAR(m.position(9).z, 0.5f, 1e-5f);
  // MeshMaterialList: the northern 24 quads use material 0 (Land, textured), the rest 1.
  ASSERT_EQ(m.materials.size(), 2u);
  EXPECT_EQ(m.materials[0].textureFilename, "earth.bmp");
  EXPECT_FLOAT_EQ(m.materials[0].diffuse.r, 0.8f);
  EXPECT_FLOAT_EQ(m.materials[0].diffuse.b, 0.5f);
  EXPECT_FLOAT_EQ(m.materials[0].power, 20.0f);
  EXPECT_TRUE(m.materials[1].textureFilename.empty());
  EXPECT_FLOAT_EQ(m.materials[1].power, 80.0f);
  ASSERT_EQ(m.attributes.size(), 96u);
  int sea = 0;
  for (uint32_t a : m.attributes) sea += a == 1;
  EXPECT_EQ(sea, 48);
  EXPECT_EQ(m.attribute(0), 0u);
  EXPECT_EQ(m.attribute(95), 1u);
}

}  // namespace
