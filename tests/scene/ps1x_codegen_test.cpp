// HLSL compiled for ps_1_1 … ps_1_4: the instruction listing (texture instructions,
// modifiers, co-issue, slot counts) and the result of running it on refx's shader
// engine. The engine's samplers return their coordinates plus a per-stage offset
// as the color, so every expected value below is worked out by hand from the HLSL
// and the ps_1_x semantics next to it.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>

#include "exec/shader_probe.h"
#include "refx/hlsl/compiler.h"
#include "refx/shader/disassembler.h"
#include "refx/shader/validator.h"

namespace {

using namespace probe;

constexpr int kV0 = 0, kV1 = 1, kTC0 = 2;  // pixel inputs of lowered programs: v0, v1, t0 …

hlsl::CompileResult compilePs(const char* source, const char* profile) {
  hlsl::CompileOptions o;
  o.profile = profile;
  return hlsl::compile(source, "ps.hlsl", o);
}

// The instructions without comments, one per line, trimmed.
std::string listing(const hlsl::CompileResult& r) {
  std::istringstream in(sh::disassemble(r.shader));
  std::string line, out;
  while (std::getline(in, line)) {
    size_t b = line.find_first_not_of(' ');
    if (b == std::string::npos || line.compare(b, 2, "//") == 0) continue;
    out += line.substr(b) + "\n";
  }
  return out;
}

const Diagnostic* firstError(const hlsl::CompileResult& r) {
  for (const Diagnostic& d : r.diagnostics)
    if (d.severity == Severity::Error) return &d;
  return nullptr;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// ---- compile and run -------------------------------------------------------------------------

TEST(HlslPs1x, ConstantColor) {
  const char* src = "float4 main() : COLOR { return float4(0.5, 0.25, 1.0, 1.0); }";
  for (const char* profile : {"ps_1_1", "ps_1_4"}) {
    auto r = compilePs(src, profile);
    ASSERT_TRUE(r.ok()) << profile << "\n" << r.messages();
    EXPECT_EQ(listing(r), std::string(profile) + "\ndef c0, 0.5, 0.25, 1, 1\nmov r0, c0\n") << profile;
    EXPECT_EQ(r.instructionSlots, 1);
    ShaderRun run(r.shader);
    run.execute();
    expectNear(run.output(0), {0.5f, 0.25f, 1.0f, 1.0f});
  }
}

// tex2D(s, In.Tex) at the sampler's own TEXCOORD is `tex t0` (ps_1_1) / `texld r0, t0`
// (ps_1_4); COLOR0 is v0.
TEST(HlslPs1x, TextureModulatedByDiffuse) {
  const char* src = R"(
    sampler2D Base;
    float4 main(float2 uv : TEXCOORD0, float4 diffuse : COLOR0) : COLOR { return tex2D(Base, uv) * diffuse; })";
  for (const char* profile : {"ps_1_1", "ps_1_2", "ps_1_3", "ps_1_4"}) {
    auto r = compilePs(src, profile);
    ASSERT_TRUE(r.ok()) << profile << "\n" << r.messages();
    bool ps14 = std::string(profile) == "ps_1_4";
    EXPECT_EQ(listing(r), std::string(profile) + (ps14 ? "\ntexld r0, t0\nmul r0, r0, v0\n" : "\ntex t0\nmul r0, t0, v0\n"));
    sh::SlotCount slots = sh::countSlots(r.shader);
    EXPECT_EQ(slots.texture, 1);
    EXPECT_EQ(slots.arithmetic, 1);
    ShaderRun run(r.shader);
    run.fakes[0].offset = 0.125f;
    run.input(kTC0, {0.25f, 0.5f, 0.0f, 0.5f}).input(kV0, {0.5f, 1.0f, 0.25f, 0.8f}).execute();
    // sample = coordinates + 0.125 = (0.375, 0.625, 0.125, 0.625); times v0
    expectNear(run.output(0), {0.375f * 0.5f, 0.625f, 0.125f * 0.25f, 0.625f * 0.8f});
  }
}

// The same tex2D twice is one texture instruction (one per stage in ps_1_x).
TEST(HlslPs1x, RepeatedTextureReadIsOneInstruction) {
  const char* src = R"(
    sampler2D s;
    float4 main(float2 uv : TEXCOORD0, float4 d : COLOR0) : COLOR { return tex2D(s, uv) * d + tex2D(s, uv).a * 0.5; })";
  for (const char* profile : {"ps_1_1", "ps_1_4"}) {
    auto r = compilePs(src, profile);
    ASSERT_TRUE(r.ok()) << profile << "\n" << r.messages();
    EXPECT_EQ(sh::countSlots(r.shader).texture, 1) << listing(r);
    ShaderRun run(r.shader);
    run.input(kTC0, {0.25f, 0.5f, 0.0f, 0.5f}).input(kV0, {0.5f, 1.0f, 0.25f, 0.8f}).execute();
    // t * d + t.a / 2 = (0.125, 0.5, 0, 0.4) + 0.25
    expectNear(run.output(0), {0.375f, 0.75f, 0.25f, 0.65f});
  }
}

// lerp(a, b, s) is one lrp with s first.
TEST(HlslPs1x, LerpIsOneLrp) {
  const char* src = R"(
    sampler2D A;
    sampler2D B;
    float4 main(float2 uv0 : TEXCOORD0, float2 uv1 : TEXCOORD1, float4 d : COLOR0) : COLOR
    {
        return lerp(tex2D(A, uv0), tex2D(B, uv1), d.a);
    })";
  for (const char* profile : {"ps_1_1", "ps_1_4"}) {
    auto r = compilePs(src, profile);
    ASSERT_TRUE(r.ok()) << profile << "\n" << r.messages();
    std::string l = listing(r);
    EXPECT_TRUE(contains(l, std::string("lrp r0, v0.w, ") + (profile[5] == '4' ? "r1, r0" : "t1, t0"))) << l;
    EXPECT_EQ(sh::countSlots(r.shader).arithmetic, 1);
    ShaderRun run(r.shader);
    run.input(kTC0, {0.2f, 0.4f, 0.6f, 0.8f}).input(kTC0 + 1, {1.0f, 0.5f, 0.0f, 0.25f});
    run.input(kV0, {0, 0, 0, 0.25f}).execute();
    // a + 0.25 * (b - a): (0.2 + 0.2, 0.4 + 0.025, 0.6 - 0.15, 0.8 - 0.1375)
    expectNear(run.output(0), {0.4f, 0.425f, 0.45f, 0.6625f});
  }
}

// A normal map dotted with a light vector held in [0, 1] (a color): both read with
// _bx2, one dp3_sat.
TEST(HlslPs1x, Dot3BumpWithBx2) {
  const char* src = R"(
    sampler2D NormalMap;
    float4 main(float2 uv : TEXCOORD0, float4 light : COLOR0) : COLOR
    {
        float3 n = 2 * (tex2D(NormalMap, uv).rgb - 0.5);
        float3 l = 2 * light.rgb - 1;
        return saturate(dot(n, l));
    })";
  for (const char* profile : {"ps_1_1", "ps_1_4"}) {
    auto r = compilePs(src, profile);
    ASSERT_TRUE(r.ok()) << profile << "\n" << r.messages();
    std::string l = listing(r);
    EXPECT_TRUE(contains(l, profile[5] == '4' ? "dp3_sat r0, r0_bx2, v0_bx2" : "dp3_sat r0, t0_bx2, v0_bx2")) << l;
    EXPECT_EQ(r.instructionSlots, 2);  // the texture read and the dp3: no constants, no other arithmetic
    ShaderRun run(r.shader);
    // lane 0: texel (0.8, 0.5, 0.9) → n = (0.6, 0, 0.8); v0 (0.5, 0.8, 0.9) → l = (0, 0.6, 0.8)
    //         n.l = 0.64
    // lane 1: same n; v0 (0.2, 0.5, 0.1) → l = (-0.6, 0, -0.8): n.l = -1 → saturate 0
    run.input(kTC0, {0.8f, 0.5f, 0.9f, 1.0f});
    run.setInput(kV0, 0, {0.5f, 0.8f, 0.9f, 1.0f}).setInput(kV0, 1, {0.2f, 0.5f, 0.1f, 1.0f}).execute();
    expectNear(run.output(0, 0), {0.64f, 0.64f, 0.64f, 0.64f});
    expectNear(run.output(0, 1), {0, 0, 0, 0});
  }
}

// A light vector in a texture coordinate: texcoord (ps_1_1) clamps it to [0, 1],
// texcrd (ps_1_4) keeps it.
TEST(HlslPs1x, Dot3BumpWithTexcoordLight) {
  const char* src = R"(
    sampler2D NormalMap;
    float4 main(float2 uv : TEXCOORD0, float3 light : TEXCOORD1) : COLOR
    {
        float3 n = 2 * (tex2D(NormalMap, uv).rgb - 0.5);
        return saturate(dot(n, light));
    })";
  auto r11 = compilePs(src, "ps_1_1");
  auto r14 = compilePs(src, "ps_1_4");
  ASSERT_TRUE(r11.ok() && r14.ok()) << r11.messages() << r14.messages();
  EXPECT_EQ(listing(r11), "ps_1_1\ntex t0\ntexcoord t1\ndp3_sat r0, t0_bx2, t1\n");
  EXPECT_TRUE(contains(listing(r14), "texcrd r1.xyz, t1\n")) << listing(r14);
  EXPECT_TRUE(contains(listing(r14), "texld r0, t0\n")) << listing(r14);
  // texel (0.8, 0.5, 0.9) → n = (0.6, 0, 0.8); light (-0.6, 0, 0.8)
  for (auto* r : {&r11, &r14}) {
    ShaderRun run(r->shader);
    run.input(kTC0, {0.8f, 0.5f, 0.9f, 1.0f}).input(kTC0 + 1, {-0.6f, 0.0f, 0.8f, 1.0f}).execute();
    // ps_1_1: texcoord → (0, 0, 0.8): n.l = 0.64; ps_1_4: n.l = -0.36 + 0.64 = 0.28
    float expected = r == &r11 ? 0.64f : 0.28f;
    expectNear(run.output(0), {expected, expected, expected, expected});
  }
}

// saturate(d * 4) is mov_x4_sat: the 4 never becomes a constant.
TEST(HlslPs1x, SaturateAndShift) {
  const char* src = R"(
    float4 k;
    float4 main(float4 d : COLOR0, float4 s : COLOR1) : COLOR { return saturate(d * 4) * k + s; })";
  for (const char* profile : {"ps_1_1", "ps_1_4"}) {
    auto r = compilePs(src, profile);
    ASSERT_TRUE(r.ok()) << profile << "\n" << r.messages();
    EXPECT_EQ(listing(r), std::string(profile) + "\nmov_x4_sat r1, v0\nmad r0, r1, c0, v1\n");
    ShaderRun run(r.shader);
    run.constant(0, {0.5f, 0.5f, 0.5f, 1.0f});  // k
    run.input(kV0, {0.1f, 0.2f, 0.3f, 0.05f}).input(kV1, {0.1f, 0.1f, 0.1f, 0.1f}).execute();
    // saturate(4d) = (0.4, 0.8, 1, 0.2); * k + s = (0.3, 0.5, 0.6, 0.3)
    expectNear(run.output(0), {0.3f, 0.5f, 0.6f, 0.3f});
  }
}

// An .rgb and an .a computation share one slot.
TEST(HlslPs1x, ColorAndAlphaAreCoIssued) {
  const char* src = R"(
    sampler2D Base;
    float4 main(float2 uv : TEXCOORD0, float4 d : COLOR0) : COLOR
    {
        float4 t = tex2D(Base, uv);
        return float4(t.rgb * d.rgb, t.a * 0.5);
    })";
  auto r = compilePs(src, "ps_1_1");
  ASSERT_TRUE(r.ok()) << r.messages();
  EXPECT_EQ(listing(r), "ps_1_1\ntex t0\nmul r0.xyz, t0, v0\n+mov_d2 r0.w, t0\n");
  EXPECT_EQ(sh::countSlots(r.shader).arithmetic, 1);
  ShaderRun run(r.shader);
  run.input(kTC0, {0.5f, 0.25f, 1.0f, 0.75f}).input(kV0, {0.5f, 0.5f, 0.5f, 0.0f}).execute();
  // rgb = t * d = (0.25, 0.125, 0.5); a = t.a / 2 = 0.375
  expectNear(run.output(0), {0.25f, 0.125f, 0.5f, 0.375f});
}

// 1 - x and x - 0.5 are the complement and bias source modifiers.
TEST(HlslPs1x, ComplementAndBias) {
  const char* src = R"(
    sampler2D Base;
    float4 main(float2 uv : TEXCOORD0, float4 d : COLOR0) : COLOR { return (1 - tex2D(Base, uv)) * d + (d - 0.5); })";
  auto r = compilePs(src, "ps_1_1");
  ASSERT_TRUE(r.ok()) << r.messages();
  EXPECT_EQ(listing(r), "ps_1_1\ntex t0\nmad r0, 1-t0, v0, v0_bias\n");
  ShaderRun run(r.shader);
  run.input(kTC0, {0.25f, 0.5f, 1.0f, 0.0f}).input(kV0, {0.5f, 0.75f, 1.0f, 0.8f}).execute();
  // (1 - t) * d + d - 0.5 = (0.375 + 0, 0.375 + 0.25, 0 + 0.5, 0.8 + 0.3)
  expectNear(run.output(0), {0.375f, 0.625f, 0.5f, 1.0f});  // alpha 1.1 clamps to the ps_1_1 range [-1, 1]
}

// ps_1_1 – 1_3 select only .a (and .b in the alpha pipe): another component is copied
// into all four by a dp3 with a unit vector; ps_1_4 selects it directly.
TEST(HlslPs1x, SingleComponentSelection) {
  const char* src = R"(
    sampler2D Base;
    float4 main(float2 uv : TEXCOORD0, float4 d : COLOR0) : COLOR { return d * tex2D(Base, uv).g; })";
  auto r11 = compilePs(src, "ps_1_1");
  auto r14 = compilePs(src, "ps_1_4");
  ASSERT_TRUE(r11.ok() && r14.ok()) << r11.messages() << r14.messages();
  EXPECT_EQ(listing(r11), "ps_1_1\ndef c0, 0, 1, 0, 0\ntex t0\ndp3 r1, t0, c0\nmul r0, v0, r1\n");
  EXPECT_EQ(listing(r14), "ps_1_4\ntexld r0, t0\nmul r0, v0, r0.y\n");
  for (auto* r : {&r11, &r14}) {
    ShaderRun run(r->shader);
    run.input(kTC0, {0.9f, 0.5f, 0.1f, 0.3f}).input(kV0, {0.2f, 0.4f, 0.6f, 1.0f}).execute();
    expectNear(run.output(0), {0.1f, 0.2f, 0.3f, 0.5f});  // d * 0.5
  }
}

// pow with a literal whole exponent is repeated squaring: x^8 = ((x²)²)².
TEST(HlslPs1x, WholePowerIsMultiplication) {
  const char* src = R"(
    float4 main(float4 d : COLOR0) : COLOR { return pow(saturate(dot(d.rgb, d.rgb)), 8); })";
  auto r = compilePs(src, "ps_1_1");
  ASSERT_TRUE(r.ok()) << r.messages();
  EXPECT_EQ(sh::countSlots(r.shader).arithmetic, 4);  // dp3 and three mul
  ShaderRun run(r.shader);
  run.input(kV0, {0.5f, 0.5f, 0.5f, 1.0f}).execute();
  // dot = 0.75; 0.75^8 = 0.100112915
  expectNear(run.output(0), {0.100112915f, 0.100112915f, 0.100112915f, 0.100112915f});
}

// min/max/comparisons are cmp (ps_1_2 and later); min and max of the same pair share
// the difference.
TEST(HlslPs1x, MinMaxWithCmp) {
  const char* src = R"(
    float4 main(float4 d : COLOR0, float4 s : COLOR1) : COLOR { return max(d, s) - min(d, s) * 0.5; })";
  for (const char* profile : {"ps_1_2", "ps_1_3", "ps_1_4"}) {
    auto r = compilePs(src, profile);
    ASSERT_TRUE(r.ok()) << profile << "\n" << r.messages();
    std::string l = listing(r);
    EXPECT_TRUE(contains(l, "cmp_d2")) << l;
    ShaderRun run(r.shader);
    run.input(kV0, {0.2f, 0.8f, 0.5f, 1.0f}).input(kV1, {0.6f, 0.4f, 0.5f, 0.0f}).execute();
    // max - min / 2 = (0.6 - 0.1, 0.8 - 0.2, 0.5 - 0.25, 1 - 0)
    expectNear(run.output(0), {0.5f, 0.6f, 0.25f, 1.0f});
  }
}

// ps_1_4 computes dependent coordinates in phase 1 and samples with them in phase 2.
TEST(HlslPs1x, Ps14DependentReadUsesAPhase) {
  const char* src = R"(
    sampler2D Offset;
    sampler2D Env;
    float4 main(float2 uv : TEXCOORD0) : COLOR { return tex2D(Env, tex2D(Offset, uv).xy * 0.5 + 0.25); })";
  auto r = compilePs(src, "ps_1_4");
  ASSERT_TRUE(r.ok()) << r.messages();
  EXPECT_EQ(listing(r),
            "ps_1_4\ndef c0, 0.5, 0.5, 0.5, 0.5\ndef c1, 0.25, 0.25, 0.25, 0.25\ntexld r0, t0\nmad r1.xyz, r0, c0, c1\n"
            "phase\ntexld r1, r1\nmov r0, r1\n");
  ShaderRun run(r.shader);
  run.fakes[1].offset = 0.125f;  // Env is stage 1
  run.input(kTC0, {0.5f, 0.25f, 0.0f, 0.0f}).execute();
  // Offset returns (0.5, 0.25, 0, 0); coordinates (0.5, 0.25) * 0.5 + 0.25 = (0.5, 0.375);
  // Env returns them + 0.125
  Vec4 c = run.output(0);
  EXPECT_NEAR(c.x, 0.625f, 1e-5f);
  EXPECT_NEAR(c.y, 0.5f, 1e-5f);
}

// The alpha of phase-1 registers is lost at the phase marker: phase 2 samples the
// stage whose alpha it needs again.
TEST(HlslPs1x, Ps14SamplesAgainForAlphaAfterThePhase) {
  const char* src = R"(
    sampler2D A;
    sampler2D B;
    float4 main(float2 uv : TEXCOORD0) : COLOR
    {
        float4 t = tex2D(A, uv);
        return tex2D(B, t.xy) * t.a;
    })";
  auto r = compilePs(src, "ps_1_4");
  ASSERT_TRUE(r.ok()) << r.messages();
  EXPECT_EQ(listing(r), "ps_1_4\ntexld r0, t0\nphase\ntexld r1, r0\ntexld r0, t0\nmul r0, r1, r0.w\n");
  ShaderRun run(r.shader);
  run.fakes[1].offset = 0.125f;
  run.input(kTC0, {0.25f, 0.5f, 0.0f, 0.75f}).execute();
  // t = (0.25, 0.5, 0, 0.75); B at (0.25, 0.5) = (0.375, 0.625, …); times t.a
  Vec4 c = run.output(0);
  EXPECT_NEAR(c.x, 0.375f * 0.75f, 1e-5f);
  EXPECT_NEAR(c.y, 0.625f * 0.75f, 1e-5f);
}

// ---- what does not fit -----------------------------------------------------------------------

// A program the profile cannot run: the first error has `code`, points at the first
// occurrence of `at` in the source (a call's name, a binary expression's operator)
// and says each of `says`.
struct Refusal {
  const char* profile;
  const char* source;
  const char* code;
  const char* at;
  std::vector<const char*> says;
};

void expectRefused(const Refusal& f) {
  auto r = compilePs(f.source, f.profile);
  EXPECT_FALSE(r.ok()) << f.source;
  const Diagnostic* e = firstError(r);
  ASSERT_NE(e, nullptr) << f.source;
  EXPECT_EQ(e->code, f.code) << e->message;
  int line = 0, column = 0;
  if (f.at) {
    std::string src = f.source;
    size_t pos = src.find(f.at);
    ASSERT_NE(pos, std::string::npos) << f.at;
    line = 1 + int(std::count(src.begin(), src.begin() + long(pos), '\n'));
    column = int(pos - (src.rfind('\n', pos) == std::string::npos ? 0 : src.rfind('\n', pos) + 1)) + 1;
  }
  EXPECT_EQ(e->where.line, line) << e->message;
  EXPECT_EQ(e->where.column, column) << e->message;
  for (const char* s : f.says) EXPECT_TRUE(contains(e->message, s)) << "'" << s << "' not in: " << e->message;
}

TEST(HlslPs1x, TooManyArithmeticInstructions) {
  // ten dependent multiplications of colors: 10 arithmetic slots, ps_1_1 has 8
  expectRefused({"ps_1_1", R"(float4 a, b, c;
float4 main(float4 d : COLOR0, float4 s : COLOR1) : COLOR
{
    float4 x = d * a;
    x = x * s + b;
    x = x * d;
    x = x * c + s;
    x = x * x;
    x = x * d + a;
    x = x * s;
    x = x * b + d;
    x = x * x;
    return x * c;
})", "X4532", "* c;", {"ps_1_1", "allows 8 arithmetic instructions, this shader has 10"}});
}

TEST(HlslPs1x, TooManyTextures) {
  expectRefused({"ps_1_1", R"(sampler2D s0, s1, s2, s3, s4;
float4 main(float2 a : TEXCOORD0, float2 b : TEXCOORD1, float2 c : TEXCOORD2, float2 d : TEXCOORD3,
            float2 e : TEXCOORD4) : COLOR
{
    return tex2D(s0, a) * tex2D(s1, b) + tex2D(s2, c) * tex2D(s3, d) + tex2D(s4, e);
})", "X4532", "tex2D(s4, e)", {"ps_1_1 allows 4 texture instructions, this shader has 5"}});
}

TEST(HlslPs1x, PowAndReciprocal) {
  expectRefused({"ps_1_1", "float e;\nfloat4 main(float4 d : COLOR0) : COLOR { return pow(d, e); }", "X4532", "pow(",
                 {"ps_1_1", "pow needs log and exp"}});
  expectRefused({"ps_1_4", "float4 main(float4 d : COLOR0, float4 s : COLOR1) : COLOR\n{\n    return d / s;\n}",
                 "X4532", "/ s", {"ps_1_4", "division and rcp need a reciprocal (rcp)"}});
  expectRefused({"ps_1_4", "float4 main(float3 n : TEXCOORD0) : COLOR { return float4(normalize(n), 1); }", "X4532",
                 "normalize(", {"normalize needs rsq"}});
}

TEST(HlslPs1x, LiteralOutsideTheConstantRange) {
  // 1.5 is no power of two a shift could take: it would be a def outside [-1, 1]
  // (d * 1.5 + 0.25 is one mad, located at its +)
  expectRefused({"ps_1_1", "float4 main(float4 d : COLOR0) : COLOR\n{\n    return d * 1.5 + 0.25;\n}", "X4532", "+ 0.25",
                 {"the literal 1.5 is outside [-1, 1], the range of ps_1_1 constants"}});
}

TEST(HlslPs1x, TooManyConstants) {
  expectRefused({"ps_1_4", R"(float4 k0, k1, k2, k3, k4, k5, k6, k7, k8;
float4 main(float4 d : COLOR0) : COLOR { return d * k0 + k1 * k2 + k3 * k4 + k5 * k6 + k7 * k8; })", "X4550", "main(",
                 {"ps_1_4 has 8 constant registers"}});
}

TEST(HlslPs1x, DependentReadNeedsPs14) {
  expectRefused({"ps_1_3", R"(sampler2D Offset, Env;
float4 main(float2 uv : TEXCOORD0) : COLOR { return tex2D(Env, tex2D(Offset, uv).xy); })", "X4532", "tex2D(Env",
                 {"'Env' is sampled at coordinates the shader computes", "ps_1_3"}});
}

TEST(HlslPs1x, CmpNeedsPs12) {
  expectRefused({"ps_1_1", "float4 main(float4 d : COLOR0, float4 s : COLOR1) : COLOR { return max(d, s); }", "X4532",
                 "max(d, s)", {"min, max and clamp need cmp, which ps_1_1 does not have (ps_1_2 or later)"}});
}

}  // namespace
