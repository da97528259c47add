// Effects whose shaders are `compile PROFILE Entry(args)` expressions: the effect's
// HLSL goes through refx's compiler, and parameters reach the registers the compiled
// shader's constant table names, as D3DX binds them. Expected values are worked out
// from the HLSL next to each assertion.
#include <gtest/gtest.h>

#include <array>
#include <cstring>

#include "pipeline/device_helpers.h"
#include "refx/effect/effect.h"
#include "refx/shader/constant_table.h"
#include "refx/shader/validator.h"

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

using test::texel;

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

// Preshader: Tint * Intensity * 0.5 reads only parameters, so the CPU computes it at
// BeginPass and the pixel shader is one mov from the register it lands in.
// Tint (1, 0.5, 0.25, 1), Intensity 1: (0.5, 0.25, 0.125, 0.5) → (128, 64, 32, 128);
// after SetFloat(Intensity, 2) and CommitChanges: (1, 0.5, 0.25, 1) → (255, 128, 64, 255).
TEST(EffectCompile, PreshadersRunAtBeginPassAndCommitChanges) {
  auto fx = Effect::fromText(R"(
float4 Tint = {1, 0.5, 0.25, 1};
float Intensity = 1;
float4 VS(float4 p : POSITION) : POSITION { return p; }
float4 PS() : COLOR { return Tint * Intensity * 0.5; }
technique T { pass { VertexShader = compile vs_2_0 VS(); PixelShader = compile ps_2_0 PS(); CullMode = None; } }
)",
                             "preshader.fx");
  ASSERT_TRUE(fx->diagnostics().empty()) << fx->diagnostics()[0].str();
  auto dev = test::makeDevice(8, 8);
  fx->begin(*dev, 0);
  fx->beginPass(0);
  // The pixel shader computes nothing: its one arithmetic instruction is the mov to oC0.
  const shader::SlotCount slots = shader::countSlots(dev->state().pixelShader->decoded());
  EXPECT_EQ(slots.total(), 1);
  drawQuad(*dev);
  EXPECT_EQ(test::pixel(*dev, 4, 4), 0x80804020u);
  fx->setFloat(fx->parameterByName("Intensity"), 2);
  fx->commitChanges();
  drawQuad(*dev);
  EXPECT_EQ(test::pixel(*dev, 4, 4), 0xffff8040u);
  fx->endPass();
  fx->end();
}

// ---- the seeds' HLSL effects on a flat quad --------------------------------------------
// The quad faces the camera: positions (±1, ±1, 0.5) in clip space (matWorldViewProj and
// matWorld identity), normal N = (0, 0, -1), tangent T = (1, 0, 0), (u, v) from 0 to 1.
// Pixel (4, 4) of the 8x8 target is clip (0, 0): there every interpolated value is the
// mean of the diagonal vertices (1, -1) and (-1, 1). Where a program uses the world
// position it is normalize(float4(x, y, 0.5, 1)), whose mean on that diagonal is
// (0, 0, 0.5 / sqrt(3.25)) = (0, 0, 0.27735). The eye is at vecEye = (0, 0, -10), so
// V = vecEye - PosWorld = (0, 0, -10.27735) at the probe: the view direction (0, 0, -1).
const std::string kEffects = std::string(REFX_DATA_DIR) + "/effects/";

struct QuadVertex {
  float x, y, z, nx, ny, nz, u, v, tx, ty, tz;
};
constexpr QuadVertex kQuad[4] = {{-1, 1, 0.5f, 0, 0, -1, 0, 0, 1, 0, 0},
                                 {1, 1, 0.5f, 0, 0, -1, 1, 0, 1, 0, 0},
                                 {-1, -1, 0.5f, 0, 0, -1, 0, 1, 1, 0, 0},
                                 {1, -1, 0.5f, 0, 0, -1, 1, 1, 1, 0, 0}};

std::unique_ptr<Effect> lightingEffect(const std::string& file, const Vec4& lightDir) {
  auto fx = Effect::fromFile(kEffects + file);
  for (const auto& d : fx->diagnostics()) ADD_FAILURE() << d.str();
  fx->setMatrix(fx->parameterByName("matWorldViewProj"), Matrix::identity());
  if (Handle h = fx->parameterByName("matWorld"); h >= 0) fx->setMatrix(h, Matrix::identity());
  if (Handle h = fx->parameterByName("vecEye"); h >= 0) fx->setVector(h, Vec4(0, 0, -10, 1));
  if (Handle h = fx->parameterByName("vecLightDir"); h >= 0) fx->setVector(h, lightDir);
  return fx;
}

// Draws the quad with a declaration of position, normal, TEXCOORD0 and TANGENT;
// `samplerTextures` go on s0, s1 (the registers the constant table gives, checked).
uint32_t renderLitQuad(Effect& fx, std::vector<std::pair<std::string, TexturePtr>> samplerTextures = {}) {
  auto dev = test::makeDevice(8, 8);
  VertexDeclaration decl;
  auto element = [&](uint16_t offset, uint8_t type, uint8_t usage) {
    VertexElement e;
    e.offset = offset;
    e.type = type;
    e.usage = usage;
    decl.elements.push_back(e);
  };
  element(0, DECLTYPE_FLOAT3, DECLUSAGE_POSITION);
  element(12, DECLTYPE_FLOAT3, DECLUSAGE_NORMAL);
  element(24, DECLTYPE_FLOAT2, DECLUSAGE_TEXCOORD);
  element(32, DECLTYPE_FLOAT3, DECLUSAGE_TANGENT);
  EXPECT_EQ(fx.begin(*dev, 0), 1);
  fx.beginPass(0);
  const auto table = shader::readConstantTable(dev->state().pixelShader->decoded());
  for (const auto& [name, texture] : samplerTextures) {
    const shader::ShaderConstant* c = table ? table->find(name) : nullptr;
    EXPECT_TRUE(c && c->registerSet == shader::RegisterSet::Sampler) << name;
    if (c) dev->setTexture(c->registerIndex, texture);
  }
  dev->setVertexDeclaration(decl);
  dev->drawPrimitiveUP(PT_TRIANGLESTRIP, 2, kQuad, sizeof(QuadVertex));
  fx.endPass();
  fx.end();
  return test::pixel(*dev, 4, 4);
}

void expectColor(uint32_t got, int r, int g, int b, int a, int tolerance = 1) {
  EXPECT_NEAR(int(got >> 16 & 0xff), r, tolerance) << std::hex << got;
  EXPECT_NEAR(int(got >> 8 & 0xff), g, tolerance) << std::hex << got;
  EXPECT_NEAR(int(got & 0xff), b, tolerance) << std::hex << got;
  EXPECT_NEAR(int(got >> 24), a, tolerance) << std::hex << got;
}

// Ambient: the pixel shader returns (0.5, 0.075, 0.075, 1): 127.5 → 128, 19.125 → 19.
TEST(HlslSeedEffects, AmbientIsItsConstant) {
  auto fx = lightingEffect("hlsl_ambient.fx", {});
  EXPECT_EQ(renderLitQuad(*fx), 0xff801313u);
}

// The DirectX 8 fallbacks compute the same colour: ps_1_1 and ps_1_4 constants hold
// (0.5, 0.075, 0.075, 1) exactly in refx's exact precision model.
TEST(HlslSeedEffects, AmbientFallbacksForDirectX8) {
  for (const char* technique : {"Ambient_ps_1_4", "Ambient_ps_1_1"}) {
    auto fx = lightingEffect("hlsl_ambient.fx", {});
    fx->setTechnique(fx->techniqueByName(technique));
    EXPECT_EQ(renderLitQuad(*fx), 0xff801313u) << technique;
  }
}

// Diffuse: ambient (0.1, 0, 0, 1) + (1, 0, 0, 1) * saturate(L.N) with L = (0, 0.6, -0.8),
// N = (0, 0, -1): L.N = 0.8 → (0.9, 0, 0, 1.8 → 1) = (229.5, 0, 0, 255).
TEST(HlslSeedEffects, DiffuseIsAmbientPlusNDotL) {
  auto fx = lightingEffect("hlsl_diffuse.fx", Vec4(0, 0.6f, -0.8f, 0));
  expectColor(renderLitQuad(*fx), 230, 0, 0, 255);
  // ps_1_4 reads the vectors with texcrd (range ±8): the same 0.9.
  fx->setTechnique(fx->techniqueByName("Diffuse_ps_1_4"));
  expectColor(renderLitQuad(*fx), 230, 0, 0, 255);
  // ps_1_1's texcoord clamps to [0, 1]: L = (0, 0.6, 0), N = (0, 0, 0), so N.L = 0 and
  // only the ambient 0.1 is left (25.5 → 26).
  fx->setTechnique(fx->techniqueByName("Diffuse_ps_1_1"));
  expectColor(renderLitQuad(*fx), 26, 0, 0, 255);
}

// Specular: diff = N.L = 0.8; R = normalize(2 * 0.8 * N - L) = (0, -0.6, -0.8); R.V with
// V = (0, 0, -1) is 0.8, 0.8^8 = 0.16777. ambient + diffuse * diff + specular =
// (0.1 + 0.8 + 0.168, 0.168, 0.168, 1 + 0.8 + 0.168) → (255, 42.8, 42.8, 255).
TEST(HlslSeedEffects, SpecularAddsRDotVToTheEighth) {
  auto fx = lightingEffect("hlsl_specular.fx", Vec4(0, 0.6f, -0.8f, 0));
  expectColor(renderLitQuad(*fx), 255, 43, 43, 255);
}

// Self-shadowing: a grazing light L = (0, 0.994987, -0.1) (unit length): N.L = 0.1, the
// shadow term saturate(4 * 0.1) = 0.4; R = normalize((0, 0, -0.2) - L) =
// (0, -0.994987, -0.1), R.V = 0.1, 0.1^8 = 1e-8. ambient + 0.4 * (diffuse * 0.1 + 1e-8) =
// (0.1 + 0.04, 0, 0, 1 + 0.04 → 1) → (35.7, 0, 0, 255); without the term red would be 51.
TEST(HlslSeedEffects, SelfShadowDimsGrazingLight) {
  auto fx = lightingEffect("hlsl_self_shadow.fx", Vec4(0, 0.994987f, -0.1f, 0));
  expectColor(renderLitQuad(*fx), 36, 0, 0, 255);
}

// Bump: the flat normal texel (128, 128, 255) gives bumpNormal = 2 * (t - 0.5) =
// (0.003922, 0.003922, 1). The tangent frame rows are T = (1, 0, 0), cross(T, N) =
// (0, 1, 0), N = (0, 0, -1), so L = (0, 0.6, -0.8) is (0, 0.6, 0.8) in tangent space and
// V = (0, 0, 1). diff = 0.003922 * 0.6 + 0.8 = 0.802353, shadow = 1;
// R = normalize(2 * diff * bump - L) = (0.006293, -0.593725, 0.804706) / 1.000032,
// R.V = 0.804680, ^3 = 0.521035; spec = min(that, colour alpha 64/255 = 0.250980).
// 0.2 * c + c * diff + spec with c = (0.4, 0.6, 0.8, 0.250980) (texel 102, 153, 204, 64):
// (0.652922, 0.853392, 1.052863 → 1, 0.502550) → (166.5, 217.6, 255, 128.2).
TEST(HlslSeedEffects, BumpLightsTheNormalMapWithAGlossMask) {
  auto fx = lightingEffect("hlsl_bump.fx", Vec4(0, 0.6f, -0.8f, 0));
  expectColor(renderLitQuad(*fx, {{"ColorMapSampler", texel(0x406699cc)}, {"BumpMapSampler", texel(0xff8080ff)}}),
              166, 218, 255, 128);
}

// Point light at vecLightDir = (0, 0, -0.5): Light = light - PosWorld = (0, 0, -0.777350)
// at the probe, so Att = Light and the attenuation is 1 - Att.Att = 1 - 0.604273 =
// 0.395727. In tangent space L = (0, 0, 0.777350) → (0, 0, 1): diff = bump.L = 1, shadow
// = 1; R = normalize(2 * bump - L) = (0.007843, 0.007843, 1) / 1.000062, R.V = 0.999938,
// ^3 = 0.999815; spec = min(that, 0.250980) = 0.250980.
// (c * (1 + 0.2) + spec) * 0.395727 with c = (0.4, 0.6, 0.8, 0.250980):
// (0.289264, 0.384239, 0.479214, 0.218502) → (73.8, 98.0, 122.2, 55.7).
TEST(HlslSeedEffects, PointLightFadesWithDistance) {
  auto fx = lightingEffect("hlsl_point_light.fx", Vec4(0, 0, -0.5f, 1));
  expectColor(renderLitQuad(*fx, {{"ColorMapSampler", texel(0x406699cc)}, {"BumpMapSampler", texel(0xff8080ff)}}),
              74, 98, 122, 56);
}

// Wood, with a noise volume of zeros (so PP = P and the ring position is exact) and
// ringscale 10.5: at the probe the object position is (0, 0, 0.5), r = 0.5 * 10.5 = 5.25,
// frc → 0.25. The listing's smoothstep(a, b, s) with s = 0.25 (s2 = 0.0625,
// s3 = 0.015625; sV1 = 0.84375, sT1 = 0.140625, sV2 = 0.15625, sT2 = -0.046875):
// smoothstep(0, 0.8) = 0.140625 + 0.125 - 0.046875 = 0.21875; smoothstep(0.83, 1) =
// 0.700313 + 0.140625 + 0.15625 - 0.046875 = 0.950313; r = -0.731563.
// lerp(lightwood, darkwood, r) = (0.3, 0.12, 0.03) - 0.731563 * (-0.25, -0.11, -0.025) =
// (0.482891, 0.200472, 0.048289). With ambient_color = diffuse_color = 1, L = N =
// (0, 0, -1): Ka + Kd * N.L = 0.6; specular_color = 0. Colour alpha 1:
// (0.289734, 0.120283, 0.028973, 1) → (73.9, 30.7, 7.4, 255).
TEST(HlslSeedEffects, WoodRingsFromTheWhitePapersListing) {
  auto fx = Effect::fromFile(kEffects + "wood.fx");
  for (const auto& d : fx->diagnostics()) ADD_FAILURE() << d.str();
  fx->setMatrix(fx->parameterByName("WoodWorldViewProj"), Matrix::identity());
  fx->setMatrix(fx->parameterByName("WoodWorld"), Matrix::identity());
  fx->setFloat(fx->parameterByName("ringscale"), 10.5f);
  fx->setFloatArray(fx->parameterByName("ambient_color"), std::array<float, 3>{1, 1, 1}.data(), 3);
  fx->setFloatArray(fx->parameterByName("diffuse_color"), std::array<float, 3>{1, 1, 1}.data(), 3);
  fx->setFloatArray(fx->parameterByName("L"), std::array<float, 3>{0, 0, -1}.data(), 3);
  fx->setFloatArray(fx->parameterByName("I"), std::array<float, 3>{0, 0, 1}.data(), 3);
  auto noise = Texture::createVolume(Format::A8R8G8B8, 1, 1, 1);
  std::memset(noise->data(0, 0), 0, 4);
  noise->markDirty();
  fx->setTexture(fx->parameterByName("noise"), noise);
  expectColor(renderLitQuad(*fx), 74, 31, 7, 255);
}

}  // namespace
