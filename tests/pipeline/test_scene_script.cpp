// Scene script parser and texture generators. Nothing here draws: the expectations
// are parsed values and generated texels, worked out from the format description in
// reference/scene-script.md and D3D9's definitions.
#include <gtest/gtest.h>

#include "error_helpers.h"

#include <cmath>
#include <cstring>
#include <unistd.h>

#include "refx/core/diagnostics.h"
#include "refx/pipeline/scene_script.h"

using namespace refx;
using namespace refx::test;
using namespace refx::scene;

namespace {

template <typename T>
const T& nth(const SceneScript& s, size_t index) {
  const T* found = std::get_if<T>(&s.commands.at(index).action);
  if (!found) throw std::runtime_error("command " + std::to_string(index) + " has another type");
  return *found;
}

float readFloat(const std::vector<uint8_t>& bytes, size_t offset) {
  float f;
  std::memcpy(&f, bytes.data() + offset, 4);
  return f;
}
uint32_t readU32(const std::vector<uint8_t>& bytes, size_t offset) {
  uint32_t u;
  std::memcpy(&u, bytes.data() + offset, 4);
  return u;
}

void expectColor(Color4 got, Color4 want, float tol = 1e-6f) {
  EXPECT_NEAR(got.r, want.r, tol);
  EXPECT_NEAR(got.g, want.g, tol);
  EXPECT_NEAR(got.b, want.b, tol);
  EXPECT_NEAR(got.a, want.a, tol);
}

TexturePtr makeTexture(std::string_view line) {
  SceneScript s = parseSceneScript(line, "t.scene");
  return createSceneTexture(nth<TextureDef>(s, 0));
}

}  // namespace

TEST(SceneScript, SizeAndDefaults) {
  SceneScript a = parseSceneScript("# nothing\n", "a.scene");
  EXPECT_EQ(a.width, 64);
  EXPECT_EQ(a.height, 64);
  EXPECT_EQ(a.targetFormat, Format::A8R8G8B8);
  SceneScript b = parseSceneScript("size 32 16 X8R8G8B8\n", "b.scene");
  EXPECT_EQ(b.width, 32);
  EXPECT_EQ(b.height, 16);
  EXPECT_EQ(b.targetFormat, Format::X8R8G8B8);
  EXPECT_TRUE(b.commands.empty());
}

TEST(SceneScript, ClearAndStates) {
  SceneScript s = parseSceneScript(
      "clear 0xff0000ff 0.5 3\n"
      "clear 1,0,0\n"
      "rs ALPHABLENDENABLE TRUE\n"
      "rs SRCBLEND ZERO\n"
      "rs d3drs_destblend D3DBLEND_SRCCOLOR\n"
      "rs FOGSTART 0.25\n"
      "rs TEXTUREFACTOR 0x80ffffff\n"
      "rs COLORWRITEENABLE RED|ALPHA\n"
      "rs ZENABLE TRUE\n"
      "rs CULLMODE NONE\n"
      "rs ALPHAREF 0x80\n"
      "rs ALPHAFUNC GREATEREQUAL\n"
      "rs AMBIENT 0,1,0\n"
      "rs WRAP0 3\n"
      "rs LIGHTING 0\n"
      "tss 1 COLOROP DOTPRODUCT3\n"
      "tss 0 COLORARG1 TEXTURE|COMPLEMENT\n"
      "tss 0 TEXCOORDINDEX 1|CAMERASPACENORMAL\n"
      "tss 2 BUMPENVMAT00 -0.5\n"
      "tss 0 TEXTURETRANSFORMFLAGS COUNT2|PROJECTED\n"
      "tss 7 CONSTANT 0x11223344\n"
      "tss 0 TEXCOORDINDEX 3\n"
      "samp vs1 ADDRESSU CLAMP\n"
      "samp 15 MIPMAPLODBIAS -1\n"
      "samp 0 MINFILTER LINEAR\n"
      "samp 0 BORDERCOLOR 0,0,1\n",
      "s.scene");
  ASSERT_EQ(s.commands.size(), 26u);
  const Clear& c = nth<Clear>(s, 0);
  EXPECT_EQ(c.color, 0xff0000ffu);
  EXPECT_EQ(c.z, 0.5f);
  EXPECT_EQ(c.stencil, 3u);
  const Clear& c2 = nth<Clear>(s, 1);
  EXPECT_EQ(c2.color, 0xffff0000u);  // floats 1,0,0 with a = 1
  EXPECT_EQ(c2.z, 1.0f);
  EXPECT_EQ(c2.stencil, 0u);
  EXPECT_EQ(s.commands[0].line, 1);
  EXPECT_EQ(s.commands[25].line, 26);

  struct RS {
    size_t at;
    d3d::RenderState state;
    uint32_t value;
  } rs[] = {
      {2, d3d::RS_ALPHABLENDENABLE, 1},
      {3, d3d::RS_SRCBLEND, d3d::BLEND_ZERO},
      {4, d3d::RS_DESTBLEND, d3d::BLEND_SRCCOLOR},
      {5, d3d::RS_FOGSTART, floatBits(0.25f)},
      {6, d3d::RS_TEXTUREFACTOR, 0x80ffffff},
      {7, d3d::RS_COLORWRITEENABLE, 1 | 8},  // RED | ALPHA
      {8, d3d::RS_ZENABLE, d3d::ZB_TRUE},
      {9, d3d::RS_CULLMODE, d3d::CULL_NONE},
      {10, d3d::RS_ALPHAREF, 0x80},
      {11, d3d::RS_ALPHAFUNC, d3d::CMP_GREATEREQUAL},
      {12, d3d::RS_AMBIENT, 0xff00ff00},
      {13, d3d::RS_WRAP0, 3},
      {14, d3d::RS_LIGHTING, 0},
  };
  for (const RS& r : rs) {
    const SetRenderState& got = nth<SetRenderState>(s, r.at);
    EXPECT_EQ(got.state, r.state) << "command " << r.at;
    EXPECT_EQ(got.value, r.value) << "command " << r.at;
  }

  const SetStageState& t0 = nth<SetStageState>(s, 15);
  EXPECT_EQ(t0.stage, 1);
  EXPECT_EQ(t0.state, d3d::TSS_COLOROP);
  EXPECT_EQ(t0.value, d3d::TOP_DOTPRODUCT3);
  EXPECT_EQ(nth<SetStageState>(s, 16).value, 0x12u);     // D3DTA_TEXTURE | D3DTA_COMPLEMENT
  EXPECT_EQ(nth<SetStageState>(s, 17).value, 0x10001u);  // 1 | D3DTSS_TCI_CAMERASPACENORMAL
  EXPECT_EQ(nth<SetStageState>(s, 18).stage, 2);
  EXPECT_EQ(nth<SetStageState>(s, 18).value, floatBits(-0.5f));
  EXPECT_EQ(nth<SetStageState>(s, 19).value, 258u);  // D3DTTFF_COUNT2 | D3DTTFF_PROJECTED
  EXPECT_EQ(nth<SetStageState>(s, 20).stage, 7);
  EXPECT_EQ(nth<SetStageState>(s, 20).value, 0x11223344u);
  EXPECT_EQ(nth<SetStageState>(s, 21).value, 3u);

  const SetSamplerState& s0 = nth<SetSamplerState>(s, 22);
  EXPECT_EQ(s0.sampler, d3d::kVertexSampler0 + 1);
  EXPECT_EQ(s0.state, d3d::SAMP_ADDRESSU);
  EXPECT_EQ(s0.value, 3u);  // D3DTADDRESS_CLAMP
  EXPECT_EQ(nth<SetSamplerState>(s, 23).sampler, 15);
  EXPECT_EQ(nth<SetSamplerState>(s, 23).value, floatBits(-1.0f));
  EXPECT_EQ(nth<SetSamplerState>(s, 24).value, 2u);  // D3DTEXF_LINEAR
  EXPECT_EQ(nth<SetSamplerState>(s, 25).value, 0xff0000ffu);
}

TEST(SceneScript, TexturesShadersConstants) {
  SceneScript s = parseSceneScript(
      "texture t 2d A8R8G8B8 4 4 levels 0 checker 0xff000000 0xffffffff 2\n"
      "texture c cube V8U8 8 normalize\n"
      "texture v volume L8 4 4 2 levels 2 noise 7\n"
      "settex 0 t\n"
      "settex vs3 none\n"
      "vs <<END\n"
      "vs_1_1\n"
      "# not a comment here\n"
      "mov oPos, v0\n"
      "  END  \n"
      "ps file shaders/x.psh\n"
      "vs none\n"
      "vsconst c5 1 2 3 4 5 6 7 8\n"
      "psconsti i2 1 -2 3 4\n"
      "psconstb b1 TRUE 0 1\n"
      "psconst 3 0.5 0.5 0.5 1\n",
      "s.scene");
  ASSERT_EQ(s.commands.size(), 12u);
  const TextureDef& t = nth<TextureDef>(s, 0);
  EXPECT_EQ(t.name, "t");
  EXPECT_EQ(t.type, TextureType::Texture2D);
  EXPECT_EQ(t.width, 4);
  EXPECT_EQ(t.height, 4);
  EXPECT_EQ(t.levels, 0);
  EXPECT_EQ(t.generator, Generator::Checker);
  EXPECT_EQ(t.cell, 2);
  ASSERT_EQ(t.colors.size(), 2u);
  const TextureDef& c = nth<TextureDef>(s, 1);
  EXPECT_EQ(c.type, TextureType::Cube);
  EXPECT_EQ(c.format, Format::V8U8);
  EXPECT_EQ(c.width, 8);
  EXPECT_EQ(c.height, 8);
  EXPECT_EQ(c.generator, Generator::Normalize);
  const TextureDef& v = nth<TextureDef>(s, 2);
  EXPECT_EQ(v.type, TextureType::Volume);
  EXPECT_EQ(v.depth, 2);
  EXPECT_EQ(v.levels, 2);
  EXPECT_EQ(v.seed, 7u);
  EXPECT_EQ(nth<SetTexture>(s, 3).name, "t");
  EXPECT_EQ(nth<SetTexture>(s, 4).sampler, d3d::kVertexSampler0 + 3);
  EXPECT_EQ(nth<SetTexture>(s, 4).name, "");

  const Shader& vs = nth<Shader>(s, 5);
  EXPECT_FALSE(vs.pixel);
  EXPECT_EQ(vs.source, Shader::Source::Inline);
  EXPECT_EQ(vs.text, "vs_1_1\n# not a comment here\nmov oPos, v0\n");
  EXPECT_EQ(vs.textLine, 7);
  EXPECT_EQ(s.commands[5].line, 6);
  const Shader& ps = nth<Shader>(s, 6);
  EXPECT_TRUE(ps.pixel);
  EXPECT_EQ(ps.source, Shader::Source::File);
  EXPECT_EQ(ps.path, "shaders/x.psh");
  EXPECT_EQ(s.commands[6].line, 11);  // lines after the block keep their numbers
  EXPECT_EQ(nth<Shader>(s, 7).source, Shader::Source::None);

  const SetConstants& k0 = nth<SetConstants>(s, 8);
  EXPECT_FALSE(k0.pixel);
  EXPECT_EQ(k0.type, SetConstants::Type::Float);
  EXPECT_EQ(k0.reg, 5);
  EXPECT_EQ(k0.floats, (std::vector<float>{1, 2, 3, 4, 5, 6, 7, 8}));
  const SetConstants& k1 = nth<SetConstants>(s, 9);
  EXPECT_TRUE(k1.pixel);
  EXPECT_EQ(k1.type, SetConstants::Type::Int);
  EXPECT_EQ(k1.reg, 2);
  EXPECT_EQ(k1.ints, (std::vector<int32_t>{1, -2, 3, 4}));
  const SetConstants& k2 = nth<SetConstants>(s, 10);
  EXPECT_EQ(k2.type, SetConstants::Type::Bool);
  EXPECT_EQ(k2.reg, 1);
  EXPECT_EQ(k2.ints, (std::vector<int32_t>{1, 0, 1}));
  EXPECT_EQ(nth<SetConstants>(s, 11).reg, 3);
}

TEST(SceneScript, SceneAVerticesInDefaultLayout) {
  // Scene (a) of scene-script.md, without its shader.
  SceneScript s = parseSceneScript(
      "size 64 64\n"
      "clear 0xff0000ff\n"
      "v -0.5 -0.5 0.5 1   0xffffffff  0 0\n"
      "v 63.5 -0.5 0.5 1   0xffffffff  1 0\n"
      "v -0.5 63.5 0.5 1   0xffffffff  0 1\n"
      "v 63.5 63.5 0.5 1   0xffffffff  1 1\n"
      "draw tristrip\n"
      "# expect 10 10 255 0 0 255\n",
      "a.scene");
  ASSERT_EQ(s.commands.size(), 2u);
  const Draw& d = nth<Draw>(s, 1);
  EXPECT_EQ(d.type, d3d::PT_TRIANGLESTRIP);
  // D3DFVF_XYZRHW (0x4) | D3DFVF_DIFFUSE (0x40) | D3DFVF_TEX1 (0x100), TEXCOORDSIZE2 = 0.
  EXPECT_EQ(d.fvf, 0x144u);
  EXPECT_EQ(d.stride, 28u);  // 4 floats + D3DCOLOR + 2 floats
  EXPECT_EQ(d.vertexCount, 4u);
  EXPECT_EQ(d.primitiveCount, 2u);  // strip: 4 - 2
  ASSERT_EQ(d.vertices.size(), 4u * 28u);
  EXPECT_EQ(readFloat(d.vertices, 28 + 0), 63.5f);  // vertex 1 x
  EXPECT_EQ(readFloat(d.vertices, 28 + 4), -0.5f);
  EXPECT_EQ(readFloat(d.vertices, 28 + 12), 1.0f);  // rhw
  EXPECT_EQ(readU32(d.vertices, 28 + 16), 0xffffffffu);
  EXPECT_EQ(readFloat(d.vertices, 28 + 20), 1.0f);  // u
  EXPECT_EQ(readFloat(d.vertices, 28 + 24), 0.0f);  // v
  ASSERT_EQ(s.expectations.size(), 1u);
  EXPECT_EQ(s.expectations[0].line, 8);
  EXPECT_EQ(s.expectations[0].x, 10);
  EXPECT_EQ(s.expectations[0].rgba[0], 255);
  EXPECT_EQ(s.expectations[0].rgba[3], 255);
  EXPECT_EQ(s.expectations[0].tolerance, 2);
}

TEST(SceneScript, FvfLayoutAndIndices) {
  SceneScript s = parseSceneScript(
      "fvf xyz normal psize diffuse specular tex 2 3\n"
      "v 1 2 3  0 0 1  4  1,0,0  0x01020304  0.25 0.75  1 2 3\n"
      "v 1 2 3  0 0 1  4  1,0,0  0x01020304  0.25 0.75  1 2 3\n"
      "v 1 2 3  0 0 1  4  1,0,0,0.5  0x01020304  0.25 0.75  1 2 3\n"
      "i 0 1 2\n"
      "i 2 1 0\n"
      "draw TRIANGLELIST\n",
      "s.scene");
  const Draw& d = nth<Draw>(s, 0);
  // XYZ 0x2 | NORMAL 0x10 | PSIZE 0x20 | DIFFUSE 0x40 | SPECULAR 0x80 | TEX2 0x200 |
  // TEXCOORDSIZE3(1) = 1 << 18.
  EXPECT_EQ(d.fvf, 0x2u | 0x10u | 0x20u | 0x40u | 0x80u | 0x200u | 0x40000u);
  EXPECT_EQ(d.stride, 12u + 12u + 4u + 4u + 4u + 8u + 12u);
  EXPECT_EQ(d.vertexCount, 3u);
  EXPECT_EQ(d.indices, (std::vector<uint16_t>{0, 1, 2, 2, 1, 0}));
  EXPECT_EQ(d.primitiveCount, 2u);  // 6 indices / 3
  size_t v2 = 2 * d.stride;
  EXPECT_EQ(readFloat(d.vertices, v2 + 24), 4.0f);           // psize
  EXPECT_EQ(readU32(d.vertices, v2 + 28), 0x80ff0000u);      // 1,0,0,0.5: a = 127.5 -> 128
  EXPECT_EQ(readU32(d.vertices, v2 + 32), 0x01020304u);      // specular
  EXPECT_EQ(readFloat(d.vertices, v2 + 40), 0.75f);          // tex0 v
  EXPECT_EQ(readFloat(d.vertices, v2 + 52), 3.0f);           // tex1 w
}

TEST(SceneScript, PrimitiveCounts) {
  struct Case {
    const char* type;
    int vertices;
    uint32_t primitives;
  } cases[] = {
      {"trilist", 6, 2}, {"tristrip", 5, 3}, {"trifan", 5, 3},
      {"linelist", 4, 2}, {"linestrip", 3, 2}, {"pointlist", 5, 5},
  };
  for (const Case& c : cases) {
    std::string text;
    for (int k = 0; k < c.vertices; ++k) text += "v 0 0 0 1 0xffffffff 0 0\n";
    text += std::string("draw ") + c.type + "\n";
    SceneScript s = parseSceneScript(text, "s.scene");
    EXPECT_EQ(nth<Draw>(s, 0).primitiveCount, c.primitives) << c.type;
  }
}

TEST(SceneScript, TransformMaterialLightsViewport) {
  SceneScript s = parseSceneScript(
      "size 32 32\n"
      "transform WORLD 1 0 0 0  0 1 0 0  0 0 1 0  5 6 7 1\n"
      "transform texture1 2 0 0 0  0 2 0 0  0 0 1 0  0 0 0 1\n"
      "material 1,0,0 0,1,0 0,0,1 0x80808080 20\n"
      "light 0 directional 1,1,1 0,0,0 0.1,0.1,0.1 0 0 1\n"
      "light 1 point 1,1,1 0,0,0 0,0,0 1 2 3 10 1 0.5 0.25\n"
      "light 2 spot 1,1,1 0,0,0 0,0,0 1 2 3 0 0 1 10 1 0 0 1 0.5 1\n"
      "light 3 off\n"
      "light 4 point 1,1,1 0,0,0 0,0,0 1 2 3\n"
      "viewport 8 8 16 16 0.25 0.75\n"
      "scissor 1 2 30 31\n",
      "s.scene");
  ASSERT_EQ(s.commands.size(), 10u);
  const SetTransform& w = nth<SetTransform>(s, 0);
  EXPECT_EQ(w.type, uint32_t(d3d::TS_WORLD));
  EXPECT_EQ(w.matrix.m[3][0], 5.0f);  // _41
  EXPECT_EQ(w.matrix.m[3][2], 7.0f);  // _43
  EXPECT_EQ(nth<SetTransform>(s, 1).type, uint32_t(d3d::TS_TEXTURE0 + 1));
  EXPECT_EQ(nth<SetTransform>(s, 1).matrix.m[1][1], 2.0f);
  const Material& m = nth<SetMaterial>(s, 2).material;
  expectColor(m.diffuse, {1, 0, 0, 1});
  expectColor(m.ambient, {0, 1, 0, 1});
  expectColor(m.emissive, {128 / 255.0f, 128 / 255.0f, 128 / 255.0f, 128 / 255.0f});
  EXPECT_EQ(m.power, 20.0f);

  const SetLight& l0 = nth<SetLight>(s, 3);
  EXPECT_EQ(l0.index, 0);
  EXPECT_TRUE(l0.enable);
  EXPECT_EQ(l0.light.type, uint32_t(d3d::LIGHT_DIRECTIONAL));
  EXPECT_EQ(l0.light.direction, (Vec3{0, 0, 1}));
  expectColor(l0.light.ambient, {0.1f, 0.1f, 0.1f, 1});
  const Light& l1 = nth<SetLight>(s, 4).light;
  EXPECT_EQ(l1.type, uint32_t(d3d::LIGHT_POINT));
  EXPECT_EQ(l1.position, (Vec3{1, 2, 3}));
  EXPECT_EQ(l1.range, 10.0f);
  EXPECT_EQ(l1.attenuation0, 1.0f);
  EXPECT_EQ(l1.attenuation1, 0.5f);
  EXPECT_EQ(l1.attenuation2, 0.25f);
  const Light& l2 = nth<SetLight>(s, 5).light;
  EXPECT_EQ(l2.type, uint32_t(d3d::LIGHT_SPOT));
  EXPECT_EQ(l2.direction, (Vec3{0, 0, 1}));
  EXPECT_EQ(l2.falloff, 1.0f);
  EXPECT_EQ(l2.theta, 0.5f);
  EXPECT_EQ(l2.phi, 1.0f);
  EXPECT_EQ(nth<SetLight>(s, 6).index, 3);
  EXPECT_FALSE(nth<SetLight>(s, 6).enable);
  // Without RANGE: the largest D3D range, A0 = 1 (no attenuation).
  const Light& l4 = nth<SetLight>(s, 7).light;
  EXPECT_EQ(l4.range, std::sqrt(std::numeric_limits<float>::max()));
  EXPECT_EQ(l4.attenuation0, 1.0f);
  EXPECT_EQ(l4.attenuation2, 0.0f);

  const Viewport& vp = nth<SetViewport>(s, 8).viewport;
  EXPECT_EQ(vp.x, 8);
  EXPECT_EQ(vp.width, 16);
  EXPECT_EQ(vp.minZ, 0.25f);
  EXPECT_EQ(vp.maxZ, 0.75f);
  const Rect& r = nth<SetScissor>(s, 9).rect;
  EXPECT_EQ(r.left, 1);
  EXPECT_EQ(r.top, 2);
  EXPECT_EQ(r.right, 30);
  EXPECT_EQ(r.bottom, 31);
}

TEST(SceneScript, ClipPlane) {
  SceneScript s = parseSceneScript("clipplane 5 1 -2 0.5 -0.25\n", "s.scene");
  ASSERT_EQ(s.commands.size(), 1u);
  const SetClipPlane& c = nth<SetClipPlane>(s, 0);
  EXPECT_EQ(c.index, 5);
  EXPECT_EQ(c.plane, Vec4(1, -2, 0.5f, -0.25f));
}

TEST(SceneScript, Expectations) {
  SceneScript s = parseSceneScript(
      "size 8 8\n"
      "clear 0xff000000  # expect 1 2 0 0 0 255\n"
      "#expect 7 7 10 20 30 40 5\n"
      "# expected to be black: an ordinary comment\n",
      "e.scene");
  ASSERT_EQ(s.expectations.size(), 2u);
  EXPECT_EQ(s.expectations[0].line, 2);
  EXPECT_EQ(s.expectations[0].y, 2);
  EXPECT_EQ(s.expectations[1].line, 3);
  EXPECT_EQ(s.expectations[1].rgba[2], 30);
  EXPECT_EQ(s.expectations[1].tolerance, 5);
}

TEST(SceneScript, ErrorsNameFileLineAndWhatWasExpected) {
  struct Case {
    const char* text;
    const char* message;
  } cases[] = {
      {"clear 0xff000000\nfrob 1 2\n", "s.scene:2:1: error: unknown command 'frob'"},
      {"\nrs ZENABLED TRUE\n", "s.scene:2:4: error: rs: unknown render state 'ZENABLED'"},
      {"rs SRCBLEND ONEE\n", "s.scene:1:13: error: rs: unknown value 'ONEE' for SRCBLEND (expected ZERO, ONE,"},
      {"clear 0\n", "s.scene:1:7: error: clear: expected a color (0xAARRGGBB or r,g,b[,a]) for the clear color, got '0'"},
      {"rs SRCBLEND\n", "s.scene:1: error: rs: expected `rs NAME VALUE`, got 1 value"},
      {"rs FOGSTART near\n", "s.scene:1:13: error: rs: expected a number for FOGSTART, got 'near'"},
      {"rs TEXTUREFACTOR 1,2\n", "s.scene:1:18: error: rs: expected a color (0xAARRGGBB or r,g,b[,a])"},
      {"tss 8 COLOROP MODULATE\n", "s.scene:1:5: error: tss: stage 8 is out of range (0 to 7)"},
      {"tss 0 COLOROPS MODULATE\n", "s.scene:1:7: error: tss: unknown texture stage state 'COLOROPS'"},
      {"samp vs4 MINFILTER POINT\n", "s.scene:1:6: error: samp: expected a sampler 0-15 or vs0-vs3, got 'vs4'"},
      {"clear 0xff000000\nsize 8 8\n", "s.scene:2:1: error: size: must be the first command"},
      {"texture t 2d A8R8G8B8 2 2 pixels 0xff000000 0xff000000 0xff000000\n",
       "s.scene:1: error: texture: pixels: expected 4 colors (2x2x1), got 3"},
      {"texture t 2d A8R8G8B8 2 2 levels 0 mipcolors 0xff000000\n",
       "s.scene:1: error: texture: mipcolors: the texture has 2 levels, got 1 color"},
      {"texture t 2d A8R8G8B8 4 4 levels 4 solid 0\n",
       "s.scene:1:34: error: texture: levels 4 is out of range (0 to 3)"},
      {"texture t 2d DXT1 4 4 solid 0\n", "s.scene:1:14: error: texture: format DXT1 cannot be generated"},
      {"texture t 2d A8R8G8B8 4 4 normalize\n", "s.scene:1:27: error: texture: generator normalize needs a cube texture"},
      {"texture t 2d A8R8G8B8 4 4 sparkle\n", "s.scene:1:27: error: texture: unknown generator 'sparkle'"},
      {"texture t 2d A8R8G8B8 4 4 solid\n", "s.scene:1: error: texture: expected `solid COLOR`, got 0 values"},
      {"settex 0 missing\n", "s.scene:1:10: error: settex: unknown texture 'missing'"},
      {"vs <<END\nvs_1_1\n", "s.scene:1:4: error: vs: no closing 'END' line for this shader block"},
      {"ps\n", "s.scene:1: error: ps: expected `ps <<TAG ... TAG`"},
      {"vsconst c256 1 2 3 4\n", "s.scene:1:9: error: vsconst: expected a register c0-c255"},
      {"psconst c0 1 2 3\n", "s.scene:1: error: psconst: expected values in groups of 4"},
      {"fvf xyzrhw normal\n", "s.scene:1:5: error: fvf: normal cannot be used with xyzrhw"},
      {"fvf diffuse\n", "s.scene:1:5: error: fvf: expected a position element first"},
      {"fvf xyz tex 5\n", "s.scene:1:13: error: fvf: a texture coordinate dimension 5 is out of range (1 to 4)"},
      {"v 0 0 0 1 0xffffffff 0\n",
       "s.scene:1: error: v: expected 7 values for fvf `xyzrhw diffuse tex 2`, got 6"},
      {"v 0 0 0 1 0xffffffff 0 0\nv 0 0 0 1 0xffffffff 0 0\ndraw trilist\n",
       "s.scene:3:6: error: draw: trilist needs at least 3 vertices, got 2"},
      {"v 0 0 0 1 0xffffffff 0 0\nv 0 0 0 1 0xffffffff 0 0\nv 0 0 0 1 0xffffffff 0 0\n"
       "v 0 0 0 1 0xffffffff 0 0\ndraw trilist\n",
       "s.scene:5:6: error: draw: trilist needs a multiple of 3 vertices, got 4"},
      {"v 0 0 0 1 0xffffffff 0 0\nv 0 0 0 1 0xffffffff 0 0\ni 0 1\ni 2 0\ndraw linelist\n",
       "s.scene:4: error: i: index 2 is out of range: the draw has 2 vertices"},
      {"draw trilist\n", "s.scene:1:1: error: draw: no vertices to draw"},
      {"draw quads\n", "s.scene:1:6: error: draw: unknown primitive type 'quads'"},
      {"v 0 0 0 1 0xffffffff 0 0\n", "s.scene:1: error: v: vertices are never drawn"},
      {"transform WORLD 1 2 3\n", "s.scene:1: error: transform: expected `transform WORLD|VIEW|PROJECTION|TEXTUREn"},
      {"transform MODEL 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n", "s.scene:1:11: error: transform: unknown transform 'MODEL'"},
      {"light 8 off\n", "s.scene:1:7: error: light: the light index 8 is out of range (0 to 7)"},
      {"light 0 spot 1,1,1 0,0,0 0,0,0 0 0 0 0 0 1 10 1 0 0 1 2 1\n",
       "s.scene:1:55: error: light: THETA 2 is out of range (0 to PHI)"},
      {"light 0 point 1,1,1 0,0,0 0,0,0 1 2\n", "s.scene:1: error: light: expected `light N directional|point"},
      {"size 16 16\nviewport 8 8 16 16\n", "s.scene:2:10: error: viewport: 8,8 16x16 does not fit the 16x16 render target"},
      {"size 16 16\n# expect 16 0 0 0 0 0\n", "s.scene:2: error: expect: pixel 16,0 is outside the 16x16 render target"},
      {"clipplane 6 1 0 0 0\n", "s.scene:1:11: error: clipplane: N 6 is out of range (0 to 5)"},
      {"clipplane 0 1 0 0\n", "s.scene:1: error: clipplane: expected `clipplane N A B C D`, got 4 values"},
      {"clipplane 0 1 0 zero 0\n", "s.scene:1:17: error: clipplane: expected a number for C, got 'zero'"},
      {"# expect 1 2 3\n", "s.scene:1:3: error: expect: expected `# expect X Y r g b a [tolerance]`, got 3 values"},
      {"# expect 1 2 3 4 256 0\n", "s.scene:1:18: error: expect: expected a 0-255 channel value from 0 to 255, got '256'"},
  };
  for (const Case& c : cases) {
    std::string msg = parseError(c.text);
    EXPECT_EQ(msg.rfind(c.message, 0), 0u) << "script:\n" << c.text << "message: " << msg
                                           << "\nexpected to start with: " << c.message;
  }
}

TEST(SceneScript, LoadReportsMissingFile) {
  try {
    loadSceneScript("/nonexistent/dir/x.scene");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("/nonexistent/dir/x.scene: error: cannot open", 0), 0u)
        << e.what();
  }
}

// ---- texture generators

TEST(SceneTextures, SolidAndChannelMapping) {
  TexturePtr t = makeTexture("texture t 2d A8R8G8B8 2 2 solid 0x80ff0000");
  expectColor(t->texel(0, 0, 1, 1), {1, 0, 0, 128 / 255.0f});
  // L8 stores r; A8 stores a.
  TexturePtr l = makeTexture("texture t 2d L8 1 1 solid 0.5,0,0");
  EXPECT_EQ(l->data(0, 0)[0], 128);  // 0.5 * 255 + 0.5 = 128
  TexturePtr a = makeTexture("texture t 2d A8 1 1 solid 0,0,0,0.25");
  EXPECT_EQ(a->data(0, 0)[0], 64);  // 0.25 * 255 + 0.5 = 64.25 -> 64
}

TEST(SceneTextures, SignedFormatsStoreRoundV127) {
  TexturePtr t = makeTexture("texture t 2d V8U8 1 1 solid -1,0.5,0");
  // U = round(-1 * 127) = -127 = 0x81, V = round(0.5 * 127) = round(63.5) = 64.
  EXPECT_EQ(t->data(0, 0)[0], 0x81);
  EXPECT_EQ(t->data(0, 0)[1], 64);
  expectColor(t->texel(0, 0, 0, 0), {-1, 64 / 127.0f, 1, 1});
  // X8L8V8U8: L (unsigned) comes from b.
  TexturePtr x = makeTexture("texture t 2d X8L8V8U8 1 1 solid 0.25,-0.25,1");
  EXPECT_EQ(x->data(0, 0)[0], 32);    // round(31.75)
  EXPECT_EQ(x->data(0, 0)[1], 0xe0);  // round(-31.75) = -32
  EXPECT_EQ(x->data(0, 0)[2], 255);   // L = 1
}

TEST(SceneTextures, Checker) {
  TexturePtr t = makeTexture("texture t 2d A8R8G8B8 4 4 checker 0xff000000 0xffffffff 2");
  Color4 black{0, 0, 0, 1}, white{1, 1, 1, 1};
  expectColor(t->texel(0, 0, 0, 0), black);  // C0 at texel 0,0
  expectColor(t->texel(0, 0, 1, 1), black);
  expectColor(t->texel(0, 0, 2, 0), white);  // (2/2 + 0/2) odd
  expectColor(t->texel(0, 0, 1, 3), white);  // (0 + 1) odd
  expectColor(t->texel(0, 0, 3, 3), black);  // (1 + 1) even
  TexturePtr v = makeTexture("texture t volume A8R8G8B8 2 2 4 checker 0xff000000 0xffffffff 2");
  expectColor(v->texel(0, 0, 0, 0, 1), black);
  expectColor(v->texel(0, 0, 0, 0, 2), white);  // z/2 = 1
  expectColor(v->texel(0, 0, 1, 1, 3), white);
}

TEST(SceneTextures, GradientCornersExact) {
  TexturePtr t = makeTexture(
      "texture t 2d A32B32G32R32F 3 3 gradient 1,0,0 0,1,0 0,0,1 1,1,1,0");
  expectColor(t->texel(0, 0, 0, 0), {1, 0, 0, 1}, 0);
  expectColor(t->texel(0, 0, 2, 0), {0, 1, 0, 1}, 0);
  expectColor(t->texel(0, 0, 0, 2), {0, 0, 1, 1}, 0);
  expectColor(t->texel(0, 0, 2, 2), {1, 1, 1, 0}, 0);
  // Centre: u = v = 1/2, the mean of the four corners.
  expectColor(t->texel(0, 0, 1, 1), {0.5f, 0.5f, 0.5f, 0.75f});
  // Top edge middle: (TL + TR) / 2.
  expectColor(t->texel(0, 0, 1, 0), {0.5f, 0.5f, 0, 1});
  // 8-bit corners are exact too.
  TexturePtr b = makeTexture("texture t 2d A8R8G8B8 5 4 gradient 0xff102030 0xff405060 0xff708090 0xffa0b0c0");
  EXPECT_EQ(colorToD3D(b->texel(0, 0, 4, 0)), 0xff405060u);
  EXPECT_EQ(colorToD3D(b->texel(0, 0, 0, 3)), 0xff708090u);
  EXPECT_EQ(colorToD3D(b->texel(0, 0, 4, 3)), 0xffa0b0c0u);
}

TEST(SceneTextures, Coords) {
  TexturePtr t = makeTexture("texture t 2d A32B32G32R32F 4 2 coords");
  // r = (1 + .5) / 4, g = (0 + .5) / 2.
  expectColor(t->texel(0, 0, 1, 0), {0.375f, 0.25f, 0, 1});
  expectColor(t->texel(0, 0, 3, 1), {0.875f, 0.75f, 0, 1});
  TexturePtr v = makeTexture("texture t volume A32B32G32R32F 2 2 4 coords");
  expectColor(v->texel(0, 0, 0, 1, 3), {0.25f, 0.75f, 0.875f, 1});  // b = 3.5 / 4
}

TEST(SceneTextures, Pixels) {
  TexturePtr t = makeTexture("texture t 2d A8R8G8B8 2 2 pixels 0xff000001 0xff000002 0xff000003 0xff000004");
  EXPECT_EQ(colorToD3D(t->texel(0, 0, 1, 0)), 0xff000002u);  // row by row
  EXPECT_EQ(colorToD3D(t->texel(0, 0, 0, 1)), 0xff000003u);
  TexturePtr c = makeTexture("texture t cube A8R8G8B8 1 pixels 0xff000001 0xff000002 0xff000003 "
                             "0xff000004 0xff000005 0xff000006");
  EXPECT_EQ(colorToD3D(c->texel(3, 0, 0, 0)), 0xff000004u);  // -Y face
}

TEST(SceneTextures, NoiseIsSplitMix64) {
  // splitmix64 from state 0 first returns 0xE220A8397B1DCDAF; texel bytes r, g, b, a are
  // its low bytes in order: 0xAF 0xCD 0x1D 0x7B.
  TexturePtr t = makeTexture("texture t 2d A8R8G8B8 2 2 noise 0");
  EXPECT_EQ(colorToD3D(t->texel(0, 0, 0, 0)), 0x7bafcd1du);  // 0xAARRGGBB
  TexturePtr u = makeTexture("texture t 2d A8R8G8B8 2 2 noise 0");
  TexturePtr w = makeTexture("texture t 2d A8R8G8B8 2 2 noise 1");
  EXPECT_EQ(std::memcmp(t->data(0, 0), u->data(0, 0), 16), 0);
  EXPECT_NE(std::memcmp(t->data(0, 0), w->data(0, 0), 16), 0);
  // Signed: the same bytes as snorm8: 0xAF = -81 -> -81/127, 0xCD = -51, 0x1D = 29, 0x7B = 123.
  TexturePtr q = makeTexture("texture t 2d Q8W8V8U8 1 1 noise 0");
  expectColor(q->texel(0, 0, 0, 0), {-81 / 127.0f, -51 / 127.0f, 29 / 127.0f, 123 / 127.0f});
}

TEST(SceneTextures, Dome) {
  TexturePtr t = makeTexture("texture t 2d A32B32G32R32F 5 5 dome");
  // Centre texel (2,2): x = y = 0 -> n = (0,0,1) -> 0.5 + 0.5n = (0.5, 0.5, 1).
  expectColor(t->texel(0, 0, 2, 2), {0.5f, 0.5f, 1, 1});
  // Corner (0,0): x = y = -0.8, outside the circle -> (0,0,1).
  expectColor(t->texel(0, 0, 0, 0), {0.5f, 0.5f, 1, 1});
  // (3,2): x = 2*3.5/5 - 1 = 0.4, y = 0, z = sqrt(0.84) = 0.9165151.
  expectColor(t->texel(0, 0, 3, 2), {0.7f, 0.5f, 0.5f + 0.5f * 0.9165151f, 1});
  // (2,1): y = 2*1.5/5 - 1 = -0.4 (y down).
  expectColor(t->texel(0, 0, 2, 1), {0.5f, 0.3f, 0.5f + 0.5f * 0.9165151f, 1});
  // Signed formats hold n itself: round(0.4 * 127) = 51, round(0.9165 * 127) = 116.
  TexturePtr s = makeTexture("texture t 2d Q8W8V8U8 5 5 dome");
  expectColor(s->texel(0, 0, 3, 2), {51 / 127.0f, 0, 116 / 127.0f, 1});
  expectColor(s->texel(0, 0, 2, 2), {0, 0, 1, 1});
}

TEST(SceneTextures, NormalizationCube) {
  TexturePtr t = makeTexture("texture t cube A32B32G32R32F 3 normalize");
  // Face centres: +X -> (1,0,0) -> (1, 0.5, 0.5); -Y (face 3) -> (0,-1,0) -> (0.5, 0, 0.5);
  // -Z (face 5) -> (0,0,-1) -> (0.5, 0.5, 0).
  expectColor(t->texel(0, 0, 1, 1), {1, 0.5f, 0.5f, 1});
  expectColor(t->texel(3, 0, 1, 1), {0.5f, 0, 0.5f, 1});
  expectColor(t->texel(5, 0, 1, 1), {0.5f, 0.5f, 0, 1});
  // +X texel (0,0): s = t = -2/3 -> direction (1, -t, -s) = (1, 2/3, 2/3), length
  // sqrt(17)/3 -> (3, 2, 2)/sqrt(17) = (0.727607, 0.485071, 0.485071).
  expectColor(t->texel(0, 0, 0, 0), {0.5f + 0.5f * 0.727607f, 0.5f + 0.5f * 0.485071f,
                                     0.5f + 0.5f * 0.485071f, 1});
  // +Y (face 2) texel (2,0): s = 2/3, t = -2/3 -> (s, 1, t) = (2/3, 1, -2/3).
  expectColor(t->texel(2, 0, 2, 0), {0.5f + 0.5f * 0.485071f, 0.5f + 0.5f * 0.727607f,
                                     0.5f - 0.5f * 0.485071f, 1});
  // Signed: +X centre is stored as (127, 0, 0).
  TexturePtr s = makeTexture("texture t cube Q8W8V8U8 3 normalize");
  expectColor(s->texel(0, 0, 1, 1), {1, 0, 0, 1});
}

TEST(SceneTextures, FacesAndMipColors) {
  TexturePtr c = makeTexture(
      "texture t cube A8R8G8B8 2 faces 0xff000001 0xff000002 0xff000003 0xff000004 "
      "0xff000005 0xff000006");
  EXPECT_EQ(colorToD3D(c->texel(4, 0, 1, 1)), 0xff000005u);  // +Z
  TexturePtr m = makeTexture("texture t 2d A8R8G8B8 4 4 levels 0 mipcolors 0xffff0000 0xff00ff00 0xff0000ff");
  ASSERT_EQ(m->levelCount(), 3);
  EXPECT_EQ(colorToD3D(m->texel(0, 0, 3, 3)), 0xffff0000u);
  EXPECT_EQ(colorToD3D(m->texel(0, 1, 1, 1)), 0xff00ff00u);
  EXPECT_EQ(colorToD3D(m->texel(0, 2, 0, 0)), 0xff0000ffu);
}

TEST(SceneTextures, LowerLevelsAreBoxFiltered) {
  TexturePtr t = makeTexture("texture t 2d A32B32G32R32F 2 2 levels 2 pixels 0,0,0 1,1,1 0,0,0,0 1,0,1,0");
  // Level 1 = mean of the four texels: r = 2/4, g = 1/4, b = 2/4, a = 2/4.
  expectColor(t->texel(0, 1, 0, 0), {0.5f, 0.25f, 0.5f, 0.5f});
  TexturePtr v = makeTexture("texture t volume A32B32G32R32F 2 2 2 levels 0 checker 0,0,0 1,1,1 1");
  ASSERT_EQ(v->levelCount(), 2);
  // 2x2x2 checker: half the texels white -> 0.5.
  expectColor(v->texel(0, 1, 0, 0, 0), {0.5f, 0.5f, 0.5f, 1});
}

TEST(SceneTextures, FileCopiesAndChecksSize) {
  TexturePtr image = Texture::create2D(Format::A8R8G8B8, 2, 2);
  image->setTexel(0, 0, 1, 0, 0, {1, 0, 0, 1});
  SceneScript s = parseSceneScript(
      "texture a 2d A8R8G8B8 2 2 file img.png\n"
      "texture b 2d A8R8G8B8 4 2 file img.png\n"
      "texture c cube A8R8G8B8 2 file img.png\n",
      "s.scene");
  TexturePtr a = createSceneTexture(nth<TextureDef>(s, 0), image.get());
  EXPECT_EQ(colorToD3D(a->texel(0, 0, 1, 0)), 0xffff0000u);
  EXPECT_EQ(nth<TextureDef>(s, 0).path, "img.png");
  try {
    createSceneTexture(nth<TextureDef>(s, 1), image.get());
    FAIL() << "size mismatch accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("img.png is 2x2, the texture is 4x2"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(createSceneTexture(nth<TextureDef>(s, 2), image.get()), Error);
  EXPECT_THROW(createSceneTexture(nth<TextureDef>(s, 0), nullptr), Error);
}

// ---- running against a device (state only: nothing here depends on drawn pixels)

#include <filesystem>

#include "refx/pipeline/device.h"
#include "refx/resource/image_io.h"

namespace {

CapsProfile testCaps() {
  CapsProfile caps;
  caps.name = "test";
  return caps;
}

std::string runError(std::string_view text, CapsProfile caps = testCaps()) {
  Device device(caps);
  try {
    runSceneScript(parseSceneScript(text, "r.scene"), device);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(SceneRun, CreatesTargetAndAppliesState) {
  Device device(testCaps());
  SceneScript s = parseSceneScript(
      "size 8 4 X8R8G8B8\n"
      "rs SRCBLEND INVSRCALPHA\n"
      "rs FOGEND 0.75\n"
      "tss 1 ALPHAOP MODULATE2X\n"
      "samp vs0 MAGFILTER LINEAR\n"
      "texture t 2d A8R8G8B8 2 2 solid 0xff00ff00\n"
      "settex 3 t\n"
      "transform VIEW 1 0 0 0  0 1 0 0  0 0 1 0  0 0 9 1\n"
      "material 1,0,0 0,0,0 0,0,0 0,0,0 8\n"
      "light 2 point 1,1,1 0,0,0 0,0,0 1 2 3 10 1 0 0\n"
      "light 5 directional 1,1,1 0,0,0 0,0,0 0 0 1\n"
      "light 5 off\n"
      "viewport 2 1 4 2\n"
      "scissor 1 1 3 3\n"
      "vsconst c10 1 2 3 4\n"
      "psconsti i1 5 6 7 8\n"
      "vsconstb b15 TRUE\n"
      "vs none\n",
      "r.scene");
  SceneOutput out = runSceneScript(s, device);
  ASSERT_TRUE(out.target);
  EXPECT_EQ(out.target->width(), 8);
  EXPECT_EQ(out.target->height(), 4);
  EXPECT_EQ(out.target->format(), Format::X8R8G8B8);
  EXPECT_EQ(device.renderTarget(), out.target);
  ASSERT_TRUE(out.depthStencil);
  EXPECT_EQ(out.depthStencil->width, 8);
  EXPECT_EQ(device.depthStencilSurface(), out.depthStencil);

  EXPECT_EQ(device.getRenderState(d3d::RS_SRCBLEND), uint32_t(d3d::BLEND_INVSRCALPHA));
  EXPECT_EQ(device.getRenderState(d3d::RS_FOGEND), floatBits(0.75f));
  EXPECT_EQ(device.getTextureStageState(1, d3d::TSS_ALPHAOP), uint32_t(d3d::TOP_MODULATE2X));
  EXPECT_EQ(device.getSamplerState(d3d::kVertexSampler0, d3d::SAMP_MAGFILTER), 2u);
  const DeviceState& st = device.state();
  ASSERT_TRUE(st.textures[3]);
  EXPECT_EQ(colorToD3D(st.textures[3]->texel(0, 0, 1, 1)), 0xff00ff00u);
  EXPECT_EQ(device.getTransform(d3d::TS_VIEW).m[3][2], 9.0f);
  EXPECT_EQ(st.material.power, 8.0f);
  EXPECT_EQ(st.lights[2].type, uint32_t(d3d::LIGHT_POINT));
  EXPECT_EQ(st.lights[2].range, 10.0f);
  EXPECT_TRUE(st.lightEnabled[2]);
  EXPECT_FALSE(st.lightEnabled[5]);
  EXPECT_EQ(st.viewport.x, 2);
  EXPECT_EQ(st.viewport.height, 2);
  EXPECT_EQ(st.scissor.right, 3);
  EXPECT_EQ(st.vsConstF[10], (Vec4{1, 2, 3, 4}));
  EXPECT_EQ(st.psConstI[1], (std::array<int, 4>{5, 6, 7, 8}));
  EXPECT_TRUE(st.vsConstB[15]);
  EXPECT_EQ(st.vertexShader, nullptr);
}

TEST(SceneRun, RunTimeErrorsNameTheLine) {
  // Errors in an inline shader name the script line of the offending shader line.
  std::string bad = runError("clear 0xff000000\nvs <<END\nvs_1_1\ndcl_position v0\nmov oPos, q0\nEND\n");
  EXPECT_EQ(bad.rfind("r.scene:5:", 0), 0u) << bad;
  EXPECT_NE(bad.find(" error A2005: "), std::string::npos) << bad;  // the assembler's code for an unknown register
  EXPECT_EQ(runError("ps <<END\nvs_1_1\ndcl_position v0\nmov oPos, v0\nEND\n"),
            "r.scene:1: error: ps: expected a pixel shader (ps_1_1 to ps_3_0), got vs_1_1");
  std::string missing = runError("\nps file no/such/file.psh\n");
  EXPECT_EQ(missing.rfind("r.scene:2: error: ps: cannot open shader file", 0), 0u) << missing;
  CapsProfile small = testCaps();
  small.maxTextureWidth = small.maxTextureHeight = 16;
  std::string big = runError("texture t 2d A8R8G8B8 32 8 solid 0xff000000\n", small);
  EXPECT_EQ(big.rfind("r.scene:1: error: texture: 32x8 exceeds MaxTextureWidth/Height 16x16 of "
                      "caps profile test",
                      0),
            0u)
      << big;
  std::string nofile = runError("texture t 2d A8R8G8B8 2 2 file no-such-image.png\n");
  EXPECT_EQ(nofile.rfind("r.scene:1: error: texture: ", 0), 0u) << nofile;
}

TEST(SceneRun, FileTexturePathIsRelativeToTheScene) {
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("refx-scene-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir / "img");
  TexturePtr image = Texture::create2D(Format::A8R8G8B8, 2, 1);
  image->setTexel(0, 0, 0, 0, 0, colorFromD3D(0xff112233));
  image->setTexel(0, 0, 1, 0, 0, colorFromD3D(0xff445566));
  savePNG(*image, (dir / "img" / "two.png").string());
  SceneScript s = parseSceneScript("texture t 2d A8R8G8B8 2 1 file img/two.png\nsettex 0 t\n",
                                   (dir / "x.scene").string());
  Device device(testCaps());
  runSceneScript(s, device);
  ASSERT_TRUE(device.state().textures[0]);
  EXPECT_EQ(colorToD3D(device.state().textures[0]->texel(0, 0, 1, 0)), 0xff445566u);
  std::filesystem::remove_all(dir);
}

TEST(SceneRun, FilterSkipsCommands) {
  // The filter turns the second clear away: the target keeps the first clear's color,
  // and a command that does not run (the missing shader file) is not an error.
  SceneScript s = parseSceneScript(
      "size 2 2\nclear 0xff102030\nclear 0xff405060\nps file no/such/file.psh\n", "r.scene");
  Device device(testCaps());
  std::vector<std::string> seen;
  runSceneScript(s, device, [&](const scene::Command& c) {
    seen.push_back(c.name);
    return c.line == 2;
  });
  EXPECT_EQ(seen, (std::vector<std::string>{"clear", "clear", "ps"}));
  int rgba[4];
  readTargetPixel(*device.renderTarget(), 1, 1, rgba);  // resolves the deferred clear
  EXPECT_EQ(rgba[0], 0x10);
  EXPECT_EQ(rgba[1], 0x20);
  EXPECT_EQ(rgba[2], 0x30);
  EXPECT_EQ(rgba[3], 0xff);
}
