// `decl USAGE[N]:TYPE ...` in scene scripts: a stream-0 vertex declaration whose
// elements are packed in the order given (offsets are the running sum of sizes).
#include <gtest/gtest.h>

#include <cstring>
#include <variant>

#include "scene/scene_helpers.h"
#include "refx/scene/scene_script.h"

using namespace refx;
using namespace refx::scene;
using namespace refx::test;

TEST(SceneDecl, PacksElementsAndVertices) {
  SceneScript s = parseSceneScript(
      "size 4 4\n"
      "decl position0:float3 position1:float3 normal0:float3 color0:d3dcolor blendindices:ubyte4\n"
      "v 1 2 3  4 5 6  0 0 -1  0x80ff0000  1 2 3 4\n"
      "draw pointlist\n",
      "s.scene");
  const Draw* draw = nullptr;
  for (const Command& c : s.commands)
    if (const auto* d = std::get_if<Draw>(&c.action)) draw = d;
  ASSERT_NE(draw, nullptr);
  ASSERT_TRUE(draw->declaration.has_value());
  const auto& e = draw->declaration->elements;
  ASSERT_EQ(e.size(), 5u);
  // offsets: 0, 12 (after a float3), 24, 36 (a D3DCOLOR is 4 bytes), 40; stride 44
  EXPECT_EQ(e[0].offset, 0);
  EXPECT_EQ(e[1].offset, 12);
  EXPECT_EQ(e[1].usage, d3d::DECLUSAGE_POSITION);
  EXPECT_EQ(e[1].usageIndex, 1);
  EXPECT_EQ(e[2].offset, 24);
  EXPECT_EQ(e[3].offset, 36);
  EXPECT_EQ(e[3].type, d3d::DECLTYPE_D3DCOLOR);
  EXPECT_EQ(e[4].offset, 40);
  EXPECT_EQ(e[4].usage, d3d::DECLUSAGE_BLENDINDICES);
  EXPECT_EQ(draw->stride, 44u);
  ASSERT_EQ(draw->vertices.size(), 44u);
  float f[3];
  std::memcpy(f, draw->vertices.data() + 12, 12);
  EXPECT_EQ(f[0], 4.0f);
  EXPECT_EQ(f[2], 6.0f);
  uint32_t color;
  std::memcpy(&color, draw->vertices.data() + 36, 4);
  EXPECT_EQ(color, 0x80ff0000u);
  EXPECT_EQ(draw->vertices[40], 1);
  EXPECT_EQ(draw->vertices[43], 4);
}

TEST(SceneDecl, FvfReplacesTheDeclaration) {
  SceneScript s = parseSceneScript(
      "size 4 4\n"
      "decl position0:float3\n"
      "fvf xyz\n"
      "v 0 0 0\n"
      "draw pointlist\n",
      "s.scene");
  for (const Command& c : s.commands) {
    if (const auto* d = std::get_if<Draw>(&c.action)) {
      EXPECT_FALSE(d->declaration.has_value());
    }
  }
}

TEST(SceneDecl, ErrorsNameTheElement) {
  EXPECT_NE(parseError("decl position0:float5\n").find("s.scene:1:6: error: decl: expected USAGE[N]:TYPE"),
            std::string::npos);
  EXPECT_NE(parseError("decl normal0:float3\n").find("expected a position0 or positiont0 element"),
            std::string::npos);
  EXPECT_NE(parseError("decl position0:float3 position0:float4\n").find("'position0:float4' is given twice"),
            std::string::npos);
  EXPECT_NE(parseError("decl position16:float3\n").find("usage index 16 is out of range"),
            std::string::npos);
  EXPECT_NE(parseError("decl position0:float3\nv 1 2\n").find("expected 3 values for decl"),
            std::string::npos);
  EXPECT_NE(parseError("decl position0:float3 blendindices0:ubyte4\nv 1 2 3 0 0 0 256\n")
                .find("s.scene:2:"),
            std::string::npos);
}
