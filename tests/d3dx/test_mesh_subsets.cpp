// Index buffer encoding and the attribute table (subsets) of d3dx::Mesh.
#include <gtest/gtest.h>

#include <cstring>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/mesh.h"

using namespace refx;
using namespace refx::d3dx;

namespace {

Mesh fourFaces() {
  Mesh m(d3d::FVF_XYZ, 8, 4);
  // Face f uses vertices 2f, 2f+1, (2f+2) mod 8.
  for (uint32_t f = 0; f < 4; ++f) {
    m.indices[3 * f] = 2 * f;
    m.indices[3 * f + 1] = 2 * f + 1;
    m.indices[3 * f + 2] = (2 * f + 2) % 8;
  }
  m.attributes = {1, 0, 1, 0};
  return m;
}

TEST(MeshSubsets, IndexBufferData16And32Bit) {
  Mesh m = fourFaces();
  const auto b16 = m.indexBufferData(false), b32 = m.indexBufferData(true);
  ASSERT_EQ(b16.size(), 24u);  // 12 indices x 2 bytes
  ASSERT_EQ(b32.size(), 48u);  // 12 indices x 4 bytes
  // Index 3 (face 1, first corner) = vertex 2: bytes 6-7, little-endian;
  // index 4 (face 1, second corner) = vertex 3: bytes 8-9.
  EXPECT_EQ(b16[6], 2);
  EXPECT_EQ(b16[7], 0);
  EXPECT_EQ(b16[8], 3);
  uint32_t v = 0;
  std::memcpy(&v, b32.data() + 4 * 11, 4);  // last index: (2*3+2) mod 8 = 0
  EXPECT_EQ(v, 0u);
  m.indices[0] = 70000;
  EXPECT_THROW(m.indexBufferData(false), Error);
  EXPECT_NO_THROW(m.indexBufferData(true));
}

TEST(MeshSubsets, SortByAttributeMakesOneRangePerSubset) {
  Mesh m = fourFaces();
  // Unsorted: four runs 1,0,1,0.
  EXPECT_EQ(m.attributeTable().size(), 4u);
  m.sortFacesByAttribute();
  // Stable: faces 1,3 (attribute 0) then 0,2 (attribute 1).
  EXPECT_EQ(m.attributes, (std::vector<uint32_t>{0, 0, 1, 1}));
  EXPECT_EQ(m.indices[0], 2u);  // old face 1 = (2,3,4)
  EXPECT_EQ(m.indices[3], 6u);  // old face 3 = (6,7,0)
  const auto t = m.attributeTable();
  ASSERT_EQ(t.size(), 2u);
  // Subset 0: faces 0-1 use vertices {2,3,4,6,7,0} -> range 0..7 (8 vertices).
  EXPECT_EQ(t[0], (Mesh::AttributeRange{0, 0, 2, 0, 8}));
  // Subset 1: faces 2-3 use {0,1,2,4,5,6} -> range 0..6 (7 vertices).
  EXPECT_EQ(t[1], (Mesh::AttributeRange{1, 2, 2, 0, 7}));
}

TEST(MeshSubsets, NoAttributesIsOneSubsetZero) {
  Mesh m = fourFaces();
  m.attributes.clear();
  const auto t = m.attributeTable();
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0], (Mesh::AttributeRange{0, 0, 4, 0, 8}));
}

}  // namespace
