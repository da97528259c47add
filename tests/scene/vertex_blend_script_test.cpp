// Scene scripts: `fvf xyzb1`..`xyzb5` with `lastbeta_ubyte4` / `lastbeta_d3dcolor`, and
// `transform WORLDn` (D3DTS_WORLDMATRIX(n)).
#include <gtest/gtest.h>

#include "scene/scene_helpers.h"

#include <cstring>
#include <string>

#include "refx/core/diagnostics.h"
#include "refx/scene/scene_script.h"

namespace refx {
namespace {

using namespace scene;
using namespace test;

const Draw& onlyDraw(const SceneScript& s) {
  for (const auto& c : s.commands)
    if (const Draw* d = std::get_if<Draw>(&c.action)) return *d;
  throw std::runtime_error("no draw");
}

TEST(VertexBlendScript, BlendPositionsPackBetasAndIndices) {
  // xyzb3 lastbeta_ubyte4 diffuse: x y z, two weights, the index DWORD, the color.
  SceneScript s = parseSceneScript(
      "fvf xyzb3 lastbeta_ubyte4 diffuse\n"
      "v 1 2 3 0.25 0.5 0x00c80701 0xff00ff00\n"
      "draw pointlist\n",
      "s.scene");
  const Draw& d = onlyDraw(s);
  EXPECT_EQ(d.fvf, uint32_t(d3d::FVF_XYZB3 | d3d::FVF_LASTBETA_UBYTE4 | d3d::FVF_DIFFUSE));
  ASSERT_EQ(d.stride, 28u);  // 3 + 3 betas + color, 4 bytes each
  ASSERT_EQ(d.vertices.size(), 28u);
  float w1;
  std::memcpy(&w1, d.vertices.data() + 16, 4);
  EXPECT_EQ(w1, 0.5f);
  // The DWORD is stored as written: bytes 01 07 c8 00.
  EXPECT_EQ(d.vertices[20], 0x01);
  EXPECT_EQ(d.vertices[21], 0x07);
  EXPECT_EQ(d.vertices[22], 0xc8);
  EXPECT_EQ(d.vertices[23], 0x00);

  const SceneScript s2 = parseSceneScript(
      "fvf xyzb5 lastbeta_d3dcolor normal\nv 0 0 0 1 2 3 4 0x01020304 0 0 -1\ndraw pointlist\n",
      "s.scene");
  const Draw& e = onlyDraw(s2);
  EXPECT_EQ(e.fvf, uint32_t(d3d::FVF_XYZB5 | d3d::FVF_LASTBETA_D3DCOLOR | d3d::FVF_NORMAL));
  EXPECT_EQ(e.stride, 44u);

  const SceneScript s3 = parseSceneScript("fvf xyzb5\nv 0 0 0 1 2 3 4 5\ndraw pointlist\n", "s.scene");
  const Draw& f = onlyDraw(s3);
  EXPECT_EQ(f.fvf, uint32_t(d3d::FVF_XYZB5));
  EXPECT_EQ(f.stride, 32u);
}

TEST(VertexBlendScript, WorldMatrixTransforms) {
  SceneScript s = parseSceneScript(
      "transform WORLD0 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n"
      "transform world17 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n"
      "transform D3DTS_WORLD255 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n",
      "s.scene");
  ASSERT_EQ(s.commands.size(), 3u);
  EXPECT_EQ(std::get<SetTransform>(s.commands[0].action).type, d3d::worldMatrix(0));
  EXPECT_EQ(std::get<SetTransform>(s.commands[1].action).type, d3d::worldMatrix(17));
  EXPECT_EQ(std::get<SetTransform>(s.commands[2].action).type, d3d::worldMatrix(255));
}

TEST(VertexBlendScript, VertexBlendValueNames) {
  // D3DVERTEXBLENDFLAGS: DISABLE 0, 1-3WEIGHTS 1-3, TWEENING 255, 0WEIGHTS 256.
  SceneScript s = parseSceneScript(
      "rs VERTEXBLEND 2WEIGHTS\nrs VERTEXBLEND D3DVBF_TWEENING\nrs VERTEXBLEND 0weights\n"
      "rs VERTEXBLEND 3\nrs VERTEXBLEND DISABLE\n",
      "s.scene");
  const uint32_t want[] = {2, 255, 256, 3, 0};
  ASSERT_EQ(s.commands.size(), 5u);
  for (size_t i = 0; i < 5; ++i)
    EXPECT_EQ(std::get<SetRenderState>(s.commands[i].action).value, want[i]) << i;
  EXPECT_NE(parseError("rs VERTEXBLEND 4WEIGHTS\n").find("unknown value '4WEIGHTS'"), std::string::npos);
}

TEST(VertexBlendScript, Errors) {
  EXPECT_NE(parseError("fvf xyzb6\n").find("s.scene:1"), std::string::npos);
  EXPECT_NE(parseError("fvf xyzb6\n").find("1 to 5 betas"), std::string::npos);
  EXPECT_NE(parseError("fvf xyzb0 diffuse\n").find("1 to 5 betas"), std::string::npos);
  EXPECT_NE(parseError("fvf xyz lastbeta_ubyte4\n").find("needs an xyzb1-xyzb5 position"),
            std::string::npos);
  EXPECT_NE(parseError("fvf xyzb2 lastbeta_ubyte4 lastbeta_d3dcolor\n").find("only one of"),
            std::string::npos);
  EXPECT_NE(parseError("fvf xyzb1 xyz\n").find("only one position element"), std::string::npos);
  EXPECT_NE(parseError("fvf xyzb2 lastbeta_ubyte4\nv 0 0 0 0.5 1.5\n").find("packed matrix indices"),
            std::string::npos);
  EXPECT_NE(parseError("fvf xyzb2 lastbeta_ubyte4\nv 0 0 0 0.5 0x100000000\n").find("s.scene:2"),
            std::string::npos);
  EXPECT_NE(parseError("transform WORLD256 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n")
                .find("world matrix index 256 is out of range (WORLD0-WORLD255)"),
            std::string::npos);
  EXPECT_NE(parseError("transform WORLDX 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n").find("unknown transform"),
            std::string::npos);
  EXPECT_NE(parseError("transform WORLD0x10 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n").find("unknown transform"),
            std::string::npos);
  EXPECT_NE(parseError("transform WORLD-1 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n").find("unknown transform"),
            std::string::npos);
}

}  // namespace
}  // namespace refx
