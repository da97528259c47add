// Vertex and pixel shaders through the Device API (IDirect3DDevice9 style): creation,
// constants, state blocks, ValidateDevice against caps profiles, the profile's
// PixelShader1xMaxValue, and DirectX 8 declaration registers. Expected pixels are
// worked out by hand from D3D9's semantics.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "device_helpers.h"
#include "error_helpers.h"
#include "pipeline/shader_lowering.h"
#include "refx/core/diagnostics.h"
#include "refx/pipeline/device.h"
#include "refx/pipeline/dx8_declaration.h"
#include "refx/shader/assembler.h"

using namespace refx;
using namespace refx::test;

namespace {

std::vector<uint32_t> tokens(std::string_view text) { return shader::assembleTokens(text, "t.sh"); }

PixelShaderPtr pixelShader(const Device& dev, std::string_view text) {
  return dev.createPixelShader(tokens(text));
}
VertexShaderPtr vertexShader(const Device& dev, std::string_view text) {
  return dev.createVertexShader(tokens(text));
}

// An 8x8 pretransformed quad covering every pixel centre, texcoords 0..1.
void drawQuad(Device& dev, uint32_t diffuse = 0xffffffff) {
  drawTL(dev, d3d::PT_TRIANGLESTRIP,
         {{-0.5f, -0.5f, 0.5f, 1, diffuse, 0, 0},
          {7.5f, -0.5f, 0.5f, 1, diffuse, 1, 0},
          {-0.5f, 7.5f, 0.5f, 1, diffuse, 0, 1},
          {7.5f, 7.5f, 0.5f, 1, diffuse, 1, 1}});
}

std::unique_ptr<Device> profileDevice(const std::string& profile) {
  auto dev = std::make_unique<Device>(loadCapsProfile(profile), DeviceOptions{1});
  dev->setRenderTarget(Texture::create2D(Format::A8R8G8B8, 8, 8));
  dev->setDepthStencilSurface(std::make_shared<DepthStencilSurface>(8, 8));
  dev->clear(d3d::CLEAR_TARGET | d3d::CLEAR_ZBUFFER, 0xff000000, 1.0f, 0);
  return dev;
}

int channel(uint32_t argb, int shift) { return int((argb >> shift) & 0xff); }

void expectPixel(const Device& dev, int x, int y, int r, int g, int b, int a, int tol = 2) {
  const uint32_t p = pixel(dev, x, y);
  EXPECT_NEAR(channel(p, 16), r, tol) << "red at " << x << "," << y;
  EXPECT_NEAR(channel(p, 8), g, tol) << "green at " << x << "," << y;
  EXPECT_NEAR(channel(p, 0), b, tol) << "blue at " << x << "," << y;
  EXPECT_NEAR(channel(p, 24), a, tol) << "alpha at " << x << "," << y;
}

}  // namespace

TEST(ShaderDevice, PixelShaderReadsApiConstantsAndDiffuse) {
  auto dev = makeDevice(8, 8);
  dev->setPixelShader(pixelShader(*dev, "ps_1_1\nmul r0, v0, c2\n"));
  const float c2[4] = {0.5f, 1.0f, 0.25f, 1.0f};
  dev->setPixelShaderConstantF(2, c2, 1);
  drawQuad(*dev, 0xff80ff40);
  // v0 = (128, 255, 64, 255)/255 = (0.50196, 1, 0.25098, 1); times c2:
  // (0.25098, 1, 0.06275, 1) -> 64 255 16 255
  expectPixel(*dev, 3, 3, 64, 255, 16, 255);
}

TEST(ShaderDevice, NullShadersReturnToFixedFunction) {
  auto dev = makeDevice(8, 8);
  useDiffuseOnly(*dev);
  dev->setPixelShader(pixelShader(*dev, "ps_1_1\ndef c0, 1, 0, 0, 1\nmov r0, c0\n"));
  drawQuad(*dev, 0xff00ff00);
  expectPixel(*dev, 1, 1, 255, 0, 0, 255);
  dev->setPixelShader(nullptr);
  drawQuad(*dev, 0xff00ff00);  // stage 0 selects the diffuse green
  expectPixel(*dev, 1, 1, 0, 255, 0, 255);
}

TEST(ShaderDevice, StateBlocksCaptureShadersAndConstants) {
  auto dev = makeDevice(8, 8);
  PixelShaderPtr ps = pixelShader(*dev, "ps_1_1\nmov r0, c0\n");
  dev->setPixelShader(ps);
  const float red[4] = {1, 0, 0, 1}, blue[4] = {0, 0, 1, 1};
  const int ints[4] = {3, 1, 2, 0}, bools[2] = {1, 0};
  dev->setPixelShaderConstantF(0, red, 1);
  dev->setVertexShaderConstantI(1, ints, 1);
  dev->setPixelShaderConstantB(14, bools, 2);
  StateBlock saved = dev->createStateBlock();
  dev->setPixelShaderConstantF(0, blue, 1);
  dev->setPixelShader(nullptr);
  dev->applyStateBlock(saved);
  EXPECT_EQ(dev->getPixelShader(), ps);
  EXPECT_EQ(dev->state().vsConstI[1], (std::array<int, 4>{3, 1, 2, 0}));
  EXPECT_TRUE(dev->state().psConstB[14]);
  EXPECT_FALSE(dev->state().psConstB[15]);
  drawQuad(*dev);
  expectPixel(*dev, 4, 4, 255, 0, 0, 255);
}

TEST(ShaderDevice, ConstantRangesAreChecked) {
  auto dev = makeDevice(8, 8);
  const float f[8] = {};
  const int i[4] = {};
  EXPECT_EQ(errorOf([&] { dev->setPixelShaderConstantF(223, f, 2); }),
            "SetPixelShaderConstantF: registers 223 to 224 are beyond the last register 223");
  EXPECT_EQ(errorOf([&] { dev->setVertexShaderConstantI(16, i, 1); }),
            "SetVertexShaderConstantI: registers 16 to 16 are beyond the last register 15");
  EXPECT_EQ(errorOf([&] { dev->setVertexShaderConstantF(255, f, 1); }), "(no error)");
}

TEST(ShaderDevice, CreationChecksTheShaderType) {
  auto dev = makeDevice(8, 8);
  std::string e = errorOf([&] { dev->createPixelShader(tokens("vs_1_1\ndcl_position v0\nmov oPos, v0\n")); });
  EXPECT_EQ(e, "a pixel shader expected, got vs_1_1");
}

TEST(ShaderDevice, ValidateDeviceChecksShaderVersionsAgainstTheProfile) {
  auto dev = profileDevice("dx8");
  dev->setPixelShader(pixelShader(*dev, "ps_1_4\ndef c0, 1, 0, 0, 1\nmov r0, c0\n"));
  EXPECT_EQ(dev->validate().reason, "pixel shader ps_1_4 needs PixelShaderVersion 1.4; dx8 has 1.1");
  dev->setPixelShader(pixelShader(*dev, "ps_1_1\ndef c0, 1, 0, 0, 1\nmov r0, c0\n"));
  EXPECT_TRUE(dev->validate().ok) << dev->validate().reason;
  dev->setVertexShader(vertexShader(*dev, "vs_2_0\ndcl_position v0\nmov oPos, v0\n"));
  EXPECT_EQ(dev->validate().reason, "vertex shader vs_2_0 needs VertexShaderVersion 2.0; dx8 has 1.1");
  // c95 is the last of dx8's 96 constants; c100 is beyond them.
  dev->setVertexShader(vertexShader(*dev, "vs_1_1\ndcl_position v0\nadd oPos, v0, c95\n"));
  EXPECT_TRUE(dev->validate().ok) << dev->validate().reason;
  auto ref = profileDevice("ref");
  ref->setVertexShader(vertexShader(*ref, "vs_1_1\ndcl_position v0\nadd oPos, v0, c100\n"));
  EXPECT_TRUE(ref->validate().ok) << ref->validate().reason;
  dev->setVertexShader(ref->getVertexShader());
  EXPECT_EQ(dev->validate().reason, "vertex shader vs_1_1 uses c100 but dx8 has MaxVertexShaderConst 96");

  auto dx7 = profileDevice("dx7");
  dx7->setPixelShader(pixelShader(*dx7, "ps_1_1\ndef c0, 1, 0, 0, 1\nmov r0, c0\n"));
  EXPECT_EQ(dx7->validate().reason, "pixel shader ps_1_1 needs PixelShaderVersion 1.1; dx7 has none");
}

TEST(ShaderDevice, Ps30NeedsAVs30) {
  auto dev = profileDevice("ref");
  dev->setPixelShader(pixelShader(*dev, "ps_3_0\ndef c0, 1, 0, 0, 1\nmov oC0, c0\n"));
  EXPECT_EQ(dev->validate().reason,
            "pixel shader ps_3_0 needs a vs_3_0 vertex shader, not fixed-function vertex processing");
  dev->setVertexShader(vertexShader(*dev, "vs_2_0\ndcl_position v0\nmov oPos, v0\n"));
  EXPECT_EQ(dev->validate().reason, "pixel shader ps_3_0 needs a vs_3_0 vertex shader, not vs_2_0");
  dev->setVertexShader(
      vertexShader(*dev, "vs_3_0\ndcl_position v0\ndcl_position o0\nmov o0, v0\n"));
  EXPECT_TRUE(dev->validate().ok) << dev->validate().reason;
}

TEST(ShaderDevice, PixelShaderSkipsTheStageCascadeInValidation) {
  auto dev = profileDevice("dx8");
  // PREMODULATE is not in dx8's TextureOpCaps; with a pixel shader the stages do not matter.
  dev->setTextureStageState(0, d3d::TSS_COLOROP, d3d::TOP_PREMODULATE);
  EXPECT_FALSE(dev->validate().ok);
  dev->setPixelShader(pixelShader(*dev, "ps_1_1\ndef c0, 1, 0, 0, 1\nmov r0, c0\n"));
  EXPECT_TRUE(dev->validate().ok) << dev->validate().reason;
}

TEST(ShaderDevice, Ps1xIntermediateRangeFollowsTheProfile) {
  // add r0, c0, c0 with c0 = 1 gives 2; x0.25 -> 0.25 where registers hold [-1, 1]
  // (dx8: PixelShader1xMaxValue 1) and 0.5 where they are not clamped (ref: FLT_MAX).
  const char* text = "ps_1_1\ndef c0, 1, 1, 1, 1\ndef c1, 0.25, 0.25, 0.25, 1\n"
                     "add r0, c0, c0\nmul r0, r0, c1\n";
  auto dx8 = profileDevice("dx8");
  dx8->setPixelShader(pixelShader(*dx8, text));
  drawQuad(*dx8);
  expectPixel(*dx8, 2, 2, 64, 64, 64, 255);  // (0.25, 0.25, 0.25, 1)
  auto ref = profileDevice("ref");
  ref->setPixelShader(pixelShader(*ref, text));
  drawQuad(*ref);
  expectPixel(*ref, 2, 2, 128, 128, 128, 255);  // (0.5, 0.5, 0.5, 2 -> 1)
}

TEST(ShaderDevice, PrecisionSettingReachesTheLowering) {
  auto dev = profileDevice("dx81");
  const shader::Version ps14{shader::ShaderType::Pixel, 1, 4};
  EXPECT_EQ(pipeline::shaderLoweringOptions(*dev, ps14).precision, exec::Precision::Exact);
  EXPECT_EQ(pipeline::shaderLoweringOptions(*dev, ps14).pixelShader1xMaxValue, 8.0f);
  dev->setPrecision(Precision::Hardware);
  EXPECT_EQ(pipeline::shaderLoweringOptions(*dev, ps14).precision, exec::Precision::Hardware);
  // A profile without pixel shaders falls back to the version's minimum range.
  auto dx7 = profileDevice("dx7");
  EXPECT_EQ(pipeline::shaderLoweringOptions(*dx7, ps14).pixelShader1xMaxValue, 8.0f);
  EXPECT_EQ(pipeline::shaderLoweringOptions(*dx7, {shader::ShaderType::Pixel, 1, 1}).pixelShader1xMaxValue, 1.0f);
}

TEST(ShaderDevice, VertexShaderFeedsFixedFunctionPixels) {
  auto dev = makeDevice(8, 8);
  useDiffuseOnly(*dev);
  // Clip-space positions passed through; oD0 = v1 * c0 with c0 = (1, 0.5, 2, 1):
  // diffuse (0.4, 0.4, 0.4, 1) -> (0.4, 0.2, 0.8, 1) -> 102 51 204 255.
  dev->setVertexShader(vertexShader(*dev, "vs_1_1\ndcl_position v0\ndcl_color v1\n"
                                          "mov oPos, v0\nmul oD0, v1, c0\n"));
  const float c0[4] = {1, 0.5f, 2, 1};
  dev->setVertexShaderConstantF(0, c0, 1);
  const uint32_t d = 0xff666666;  // 0x66 = 102 -> 0.4
  std::vector<ColorVertex> v = {{-1.125f, 1.125f, 0.5f, d}, {0.875f, 1.125f, 0.5f, d},
                                {-1.125f, -0.875f, 0.5f, d}, {0.875f, -0.875f, 0.5f, d}};
  dev->setFVF(kColorVertexFVF);
  dev->drawPrimitiveUP(d3d::PT_TRIANGLESTRIP, 2, v.data(), sizeof(ColorVertex));
  expectPixel(*dev, 5, 2, 102, 51, 204, 255);
}

TEST(ShaderDevice, Dx8DeclarationRegistersFeedShadersWithoutDcl) {
  auto dev = makeDevice(8, 8);
  useDiffuseOnly(*dev);
  // A DirectX 8 style vs_1_1 (no dcl): the declaration puts the position in v0 and the
  // color in v7 (D3DVSD_REG). oD0 = v7.
  dev->setVertexShader(vertexShader(*dev, "vs_1_1\nmov oPos, v0\nmov oD0, v7\n"));
  VertexDeclaration decl = VertexDeclaration::fromFVF(kColorVertexFVF);
  decl.fvf = 0;
  for (VertexElement& el : decl.elements)
    el.shaderRegister = el.usage == d3d::DECLUSAGE_COLOR ? 7 : 0;
  dev->setVertexDeclaration(decl);
  const uint32_t d = 0xff3366cc;  // (0.2, 0.4, 0.8)
  std::vector<ColorVertex> v = {{-1.125f, 1.125f, 0.5f, d}, {0.875f, 1.125f, 0.5f, d},
                                {-1.125f, -0.875f, 0.5f, d}, {0.875f, -0.875f, 0.5f, d}};
  dev->drawPrimitiveUP(d3d::PT_TRIANGLESTRIP, 2, v.data(), sizeof(ColorVertex));
  expectPixel(*dev, 4, 4, 0x33, 0x66, 0xcc, 255);
}

TEST(ShaderDevice, Dx8VsdDeclarationMapsRegistersAndLoadsConstants) {
  auto dev = makeDevice(8, 8);
  useDiffuseOnly(*dev);
  // Stream 0: position (float3) -> v0, a skipped DWORD, color -> v9; D3DVSD_CONST puts
  // (0.5, 1, 0.25, 1) into c4. oD0 = v9 * c4 (RacorX-style shader without dcl).
  const shader::VsDeclaration vsd = shader::parseVsDeclaration(
      "DWORD dwDecl[] = { D3DVSD_STREAM(0), D3DVSD_REG(0, D3DVSDT_FLOAT3), D3DVSD_SKIP(1),"
      " D3DVSD_REG(9, D3DVSDT_D3DCOLOR), D3DVSD_CONST(4, 1), 0.5f, 1.0f, 0.25f, 1.0f,"
      " D3DVSD_END() };",
      "decl.h");
  VertexShaderPtr vs = vertexShader(*dev, "vs_1_1\nmov oPos, v0\nmul oD0, v9, c4\n");
  const VertexDeclaration decl = vertexDeclarationFromVsd(vsd);
  ASSERT_EQ(decl.elements.size(), 2u);
  EXPECT_EQ(decl.elements[1].offset, 16);  // 12 bytes of position + 1 skipped DWORD
  EXPECT_EQ(decl.elements[1].shaderRegister, 9);
  dev->setVertexShader(vs);
  dev->setVertexDeclaration(decl);
  setVsdConstants(*dev, vsd);
  struct V {
    float x, y, z;
    uint32_t skipped, color;
  };
  const uint32_t d = 0xffcc6680;  // (0.8, 0.4, 0.50196)
  std::vector<V> v = {{-1.125f, 1.125f, 0.5f, 0, d}, {0.875f, 1.125f, 0.5f, 0, d},
                      {-1.125f, -0.875f, 0.5f, 0, d}, {0.875f, -0.875f, 0.5f, 0, d}};
  dev->drawPrimitiveUP(d3d::PT_TRIANGLESTRIP, 2, v.data(), sizeof(V));
  // (0.8*0.5, 0.4*1, 0.50196*0.25, 1) = (0.4, 0.4, 0.12549, 1) -> 102 102 32 255
  expectPixel(*dev, 4, 4, 102, 102, 32, 255);
}

TEST(ShaderDevice, Dx8VsdConstWithNoRegistersLoadsNothing) {
  // D3DVSD_CONST(4, 0) carries no data: c4 keeps the value set before, and c5 gets the
  // one register of the D3DVSD_CONST(5, 1) after it.
  auto dev = makeDevice(8, 8);
  const float before[4] = {0.5f, 0.5f, 0.5f, 0.5f};
  dev->setVertexShaderConstantF(4, before, 1);
  const shader::VsDeclaration vsd = shader::parseVsDeclaration(
      "DWORD dwDecl[] = { D3DVSD_STREAM(0), D3DVSD_REG(0, D3DVSDT_FLOAT3), D3DVSD_CONST(4, 0),"
      " D3DVSD_CONST(5, 1), 1.0f, 2.0f, 3.0f, 4.0f, D3DVSD_END() };",
      "decl.h");
  setVsdConstants(*dev, vsd);
  EXPECT_EQ(dev->state().vsConstF[4], (Vec4{0.5f, 0.5f, 0.5f, 0.5f}));
  EXPECT_EQ(dev->state().vsConstF[5], (Vec4{1, 2, 3, 4}));
}

TEST(ShaderDevice, TrianglesWithUnrepresentablePositionsAreNotDrawn) {
  // Pretransformed vertices are not clipped: a triangle with a NaN or a 1e30 screen
  // coordinate cannot be set up in fixed point and draws nothing; the pixel keeps the
  // clear color, and a normal triangle after them still draws.
  auto dev = makeDevice(8, 8);
  dev->clear(d3d::CLEAR_TARGET, 0xff000000, 1, 0);
  dev->setFVF(d3d::FVF_XYZRHW | d3d::FVF_DIFFUSE);
  struct V {
    float x, y, z, rhw;
    uint32_t color;
  };
  const uint32_t red = 0xffff0000;
  const V nan[3] = {{0, 0, 0.5f, 1, red}, {std::nanf(""), 0, 0.5f, 1, red}, {0, 16, 0.5f, 1, red}};
  const V huge[3] = {{0, 0, 0.5f, 1, red}, {1e30f, 0, 0.5f, 1, red}, {0, 1e30f, 0.5f, 1, red}};
  dev->drawPrimitiveUP(d3d::PT_TRIANGLELIST, 1, nan, sizeof(V));
  dev->drawPrimitiveUP(d3d::PT_TRIANGLELIST, 1, huge, sizeof(V));
  expectPixel(*dev, 1, 1, 0, 0, 0, 255);
  const V green[3] = {{0, 0, 0.5f, 1, 0xff00ff00}, {16, 0, 0.5f, 1, 0xff00ff00},
                      {0, 16, 0.5f, 1, 0xff00ff00}};
  dev->drawPrimitiveUP(d3d::PT_TRIANGLELIST, 1, green, sizeof(V));
  expectPixel(*dev, 1, 1, 0, 255, 0, 255);
}

TEST(ShaderDevice, ShaderDepthOutputReplacesInterpolatedDepth) {
  auto dev = makeDevice(8, 8);
  dev->setRenderState(d3d::RS_ZENABLE, d3d::ZB_TRUE);
  dev->setRenderState(d3d::RS_ZFUNC, d3d::CMP_LESS);
  dev->clear(d3d::CLEAR_ZBUFFER, 0, 0.5f, 0);
  // oDepth = 0.25 for a quad drawn at z = 0.5 (which LESS against 0.5 would reject).
  dev->setPixelShader(pixelShader(*dev, "ps_2_0\ndef c0, 0.25, 0.25, 0.25, 0.25\ndef c1, 0, 1, 0, 1\n"
                                        "mov oDepth, c0\nmov oC0, c1\n"));
  drawQuad(*dev);
  expectPixel(*dev, 3, 3, 0, 255, 0, 255);
  EXPECT_FLOAT_EQ(dev->depthStencilSurface()->depth[3 * 8 + 3], 0.25f);
}
