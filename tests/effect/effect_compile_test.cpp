// Effects whose shaders are `compile PROFILE Entry(args)` expressions: the effect's
// HLSL goes through refx's compiler, and parameters reach the registers the compiled
// shader's constant table names, as D3DX binds them. Expected values are worked out
// from the HLSL next to each assertion.
#include <gtest/gtest.h>

#include <cstring>

#include "pipeline/device_helpers.h"
#include "refx/effect/effect.h"
#include "refx/shader/constant_table.h"

using namespace refx;
using namespace refx::effect;
using namespace refx::d3d;

namespace {

// A quad over the whole 8x8 target, positions in clip space, (u, v) in TEXCOORD0.
void drawQuad(Device& dev) {
  struct V {
    float x, y, z, u, v;
  };
  const V quad[4] = {{-1, 1, 0.5f, 0, 0}, {1, 1, 0.5f, 1, 0}, {-1, -1, 0.5f, 0, 1}, {1, -1, 0.5f, 1, 1}};
  dev.setFVF(FVF_XYZ | (1u << FVF_TEXCOUNT_SHIFT));
  dev.drawPrimitiveUP(PT_TRIANGLESTRIP, 2, quad, sizeof(V));
}

TexturePtr texel(uint32_t argb) {
  auto t = Texture::create2D(Format::A8R8G8B8, 1, 1, 1);
  std::memcpy(t->data(0, 0), &argb, 4);
  t->markDirty();
  return t;
}

uint32_t renderPass(Effect& fx, Device& dev, int pass = 0) {
  dev.clear(CLEAR_TARGET | CLEAR_ZBUFFER, 0xff000000, 1, 0);
  fx.begin(dev, 0);
  fx.beginPass(pass);
  drawQuad(dev);
  fx.endPass();
  fx.end();
  return test::pixel(dev, 4, 4);
}

constexpr const char* kTexturedEffect = R"(
float4x4 WorldViewProj : WORLDVIEWPROJECTION;
float4 Color = {1, 0.5, 0.25, 1};
texture Unused;
texture Tex;
sampler UnusedSampler = sampler_state { Texture = <Unused>; };
sampler Samp = sampler_state { Texture = <Tex>; MinFilter = Point; MagFilter = Point; };
struct VSOUT { float4 pos : POSITION; float2 uv : TEXCOORD0; };
VSOUT VS(float4 p : POSITION, float2 uv : TEXCOORD0) {
  VSOUT o;
  o.pos = mul(p, WorldViewProj);
  o.uv = uv;
  return o;
}
float4 PS(float2 uv : TEXCOORD0, uniform float k) : COLOR { return tex2D(Samp, uv) * Color * k; }
VertexShader vsh = compile vs_2_0 VS();
technique Compiled { pass P0 { VertexShader = (vsh); PixelShader = compile ps_2_0 PS(2.0); CullMode = None; } }
)";

// tex2D(Samp) * Color * k with the texel (128, 64, 32, 255), Color (1, 0.5, 0.25, 1) and
// k = 2 from the compile expression: red 128/255 * 1 * 2 = 1.004 → saturates to 255;
// green 64/255 * 0.5 * 2 = 64/255 → 64; blue 32/255 * 0.25 * 2 = 16/255 → 16; alpha 2 → 255.
// Samp is the only sampler the pixel shader reads, so the constant table puts it on s0,
// and the effect applies Samp's sampler_state (its texture) to sampler 0.
TEST(EffectCompile, ParametersReachTheCompiledShadersThroughTheConstantTable) {
  auto fx = Effect::fromText(kTexturedEffect, "textured.fx");
  ASSERT_TRUE(fx->diagnostics().empty()) << fx->diagnostics()[0].str();
  fx->setMatrix(fx->parameterByName("WorldViewProj"), Matrix::identity());
  fx->setTexture(fx->parameterByName("Tex"), texel(0xff804020));
  fx->setTexture(fx->parameterByName("Unused"), texel(0xffffffff));
  auto dev = test::makeDevice(8, 8);
  EXPECT_EQ(renderPass(*fx, *dev), 0xffff4010u);
  fx->begin(*dev, 0);
  fx->beginPass(0);
  EXPECT_EQ(dev->state().textures[0], fx->getTexture(fx->parameterByName("Tex")));
  fx->endPass();
  fx->end();

  // A changed parameter reaches the shader at the next pass: Color (0.5, 1, 1, 1) gives
  // red 128/255 * 0.5 * 2 = 128/255, green 64/255 * 2 = 128/255, blue 32/255 * 2 = 64/255.
  fx->setVector(fx->parameterByName("Color"), Vec4(0.5f, 1, 1, 1));
  EXPECT_EQ(renderPass(*fx, *dev), 0xff808040u);
}

// The matrix goes in column-major (the compiler's default packing: one register per
// column, so dp4 with each register computes one output component). A translation by
// +1 in x (row-vector convention: the last row is (1, 0, 0, 1)) moves the quad from
// [-1, 1] to [0, 2] in x: the left half of the target stays clear, the right half is drawn.
// Transposed by mistake, the translation would land in w (w = 1 + x) and the quad would
// cover the left side too.
TEST(EffectCompile, MatricesArePackedAsTheConstantTableSays) {
  auto fx = Effect::fromText(kTexturedEffect, "textured.fx");
  Matrix m = Matrix::identity();
  m.m[3][0] = 1;
  fx->setMatrix(fx->parameterByName("WorldViewProj"), m);
  fx->setTexture(fx->parameterByName("Tex"), texel(0xffffffff));
  auto dev = test::makeDevice(8, 8);
  renderPass(*fx, *dev);
  EXPECT_EQ(test::pixel(*dev, 1, 4), 0xff000000u);
  EXPECT_EQ(test::pixel(*dev, 2, 4), 0xff000000u);
  // Colour: white * (1, 0.5, 0.25, 1) * 2 = (2, 1, 0.5, 2) → (255, 255, 128, 255).
  EXPECT_EQ(test::pixel(*dev, 5, 4), 0xffffff80u);
  EXPECT_EQ(test::pixel(*dev, 7, 4), 0xffffff80u);
}

// The same entry point with other arguments is another shader: k = 0.5 halves white
// times Color: (0.5, 0.25, 0.125, 0.5) → (128, 64, 32, 128) (x * 255 rounded).
TEST(EffectCompile, EntryArgumentsSelectTheShader) {
  auto fx = Effect::fromText(R"(
float4 Color = {1, 0.5, 0.25, 1};
float Scale = 0.5;
float4 VS(float4 p : POSITION) : POSITION { return p; }
float4 PS(uniform float k, uniform float3 tint) : COLOR { return Color * k * float4(tint, 1); }
technique Half { pass { VertexShader = compile vs_1_1 VS(); PixelShader = compile ps_2_0 PS(Scale, float3(1, 1, 1)); } }
technique Quarter { pass { VertexShader = compile vs_1_1 VS(); PixelShader = compile ps_2_0 PS(0.5, float3(0.5, 0.5, 0.5)); } }
)",
                             "args.fx");
  ASSERT_TRUE(fx->diagnostics().empty()) << fx->diagnostics()[0].str();
  auto dev = test::makeDevice(8, 8);
  dev->setRenderState(RS_CULLMODE, CULL_NONE);
  fx->setTechnique(fx->techniqueByName("Half"));
  EXPECT_EQ(renderPass(*fx, *dev), 0x80804020u);
  // Quarter: Color * 0.5 * (0.5, 0.5, 0.5, 1) = (0.25, 0.125, 0.0625, 0.5) →
  // (63.75, 31.875, 15.9375, 127.5) → (64, 32, 16, 128).
  fx->setTechnique(fx->techniqueByName("Quarter"));
  EXPECT_EQ(renderPass(*fx, *dev), 0x80402010u);
}

// A compile error breaks only its technique: the error carries the HLSL file position
// and fxc's code (X3004: undeclared identifier), the good technique still validates.
TEST(EffectCompile, ACompileErrorBreaksOnlyItsTechnique) {
  auto fx = Effect::fromText(R"(
float4 Good() : COLOR { return 1; }
float4 Bad() : COLOR { return missing; }
float4 VS(float4 p : POSITION) : POSITION { return p; }
technique Broken { pass { VertexShader = compile vs_2_0 VS(); PixelShader = compile ps_2_0 Bad(); } }
technique Fine { pass { VertexShader = compile vs_2_0 VS(); PixelShader = compile ps_2_0 Good(); } }
technique WrongKind { pass { VertexShader = compile ps_2_0 Good(); } }
)",
                             "broken.fx");
  ASSERT_EQ(fx->techniqueCount(), 3);
  ASSERT_GE(fx->diagnostics().size(), 2u);
  const EffectDiagnostic& d = fx->diagnostics()[0];
  EXPECT_EQ(d.where.file, "broken.fx");
  EXPECT_EQ(d.where.line, 3);
  EXPECT_NE(d.message.find("X3004"), std::string::npos) << d.message;
  EXPECT_NE(d.message.find("missing"), std::string::npos) << d.message;
  EXPECT_FALSE(fx->techniqueDesc(0).brokenReason.empty());
  EXPECT_TRUE(fx->techniqueDesc(1).brokenReason.empty());
  EXPECT_NE(fx->techniqueDesc(2).brokenReason.find("vertex shader profile"), std::string::npos)
      << fx->techniqueDesc(2).brokenReason;
  const CapsProfile caps = loadCapsProfile("ref");
  EXPECT_FALSE(fx->validateTechnique(0, caps).ok);
  EXPECT_TRUE(fx->validateTechnique(1, caps).ok);
  EXPECT_EQ(fx->findNextValidTechnique(-1, caps), 1);
}

// Validation sees the compiled shader's version: a vs_2_0 / ps_2_0 technique is invalid
// on dx81 (vs 1.1, ps 1.4) with the reason naming the version.
TEST(EffectCompile, CompiledShadersValidateByTheirVersion) {
  auto fx = Effect::fromText(kTexturedEffect, "textured.fx");
  const TechniqueValidation v = fx->validateTechnique(0, loadCapsProfile("dx81"));
  EXPECT_FALSE(v.ok);
  EXPECT_NE(v.reason.find("vs_2_0"), std::string::npos) << v.reason;
  EXPECT_TRUE(fx->validateTechnique(0, loadCapsProfile("dx9")).ok);
}

}  // namespace
