// ps_1_1 – ps_1_4: arithmetic with the ps_1_x modifiers and ranges, co-issue, every
// texture-address instruction (with a sampler that returns its coordinates as the
// color), and the hardware precision model.
#include <set>

#include "shader_probe.h"

using namespace probe;

namespace {

constexpr int kV0 = kPixelInDiffuse, kV1 = kPixelInSpecular, kTC0 = kPixelInTex0;

Vec4 color(ShaderRun& r, int lane = 0) { return r.output(0, lane); }

TEST(ShaderPs1x, SourceModifiersAndShift) {
  auto r = asmRun(R"(ps.1.1
    mov r0.rgb, v0_bias
    +mov r0.a, 1-v0
    mov r1, v0_bx2
    add_x2 r1.rgb, r1, -v0_bx2
    +mul_d2 r1.a, v0, v0
    add r0, r0, r1
  )");
  r.input(kV0, {0.75f, 0.25f, 1.0f, 0.5f}).execute();
  // r0 = (v0 - 0.5, 1 - v0.a) = (0.25, -0.25, 0.5, 0.5)
  // r1.rgb = 2 * (bx2 - bx2) = 0; r1.a = (0.5*0.5)/2 = 0.125
  expectNear(color(r), {0.25f, -0.25f, 0.5f, 0.625f});
}

TEST(ShaderPs1x, Ps14SourceX2AndShiftsClampToEight) {
  auto r = asmRun(R"(ps.1.4
    def c0, 1, 0.5, 0.25, 1
    mov_x8 r1, c0
    add r0, r1, c0_x2
    mul_d8 r2, r1, c0
    mov r0.a, r2.b
  )");
  r.execute();
  // r1 = 8*c0 = (8, 4, 2, 8); r0 = r1 + 2*c0 = (10 → 8, 5, 2.5, 10 → 8)
  // r2 = r1*c0/8 = (1, 0.25, 0.0625, 1); r0.a = r2.b
  expectNear(color(r), {8, 5, 2.5f, 0.0625f});
}

TEST(ShaderPs1x, SaturateAndTheRangeClamp) {
  auto r = asmRun(R"(ps.1.1
    def c0, 1, 1, 1, 1
    def c1, -1, -1, 0.25, 0.5
    add_sat r0, c0, c1
    sub r1, c1, c0
    add r0.a, r1.a, c0
  )");
  r.execute();
  // add_sat = (0, 0, 1.25 → 1, 1.5 → 1); r1 = c1 - c0 = (-2 → -1, ..., -0.5); r0.a = -0.5 + 1
  expectNear(color(r), {0, 0, 1, 0.5f});
}

TEST(ShaderPs1x, UnclampedWhenMaxValueIsLarge) {
  ShaderLoweringOptions o;
  o.pixelShader1xMaxValue = std::numeric_limits<float>::max();
  auto r = asmRun("ps.1.1\ndef c0, 1, 1, 1, 1\nadd r0, c0, c0\nmul r0, r0, c1\n", o);
  r.constant(1, {0.25f, 0.25f, 0.25f, 0.25f}).execute();
  // D3D9 float device: (1 + 1) * 0.25 = 0.5 (a DX8 part would give 0.25)
  expectNear(color(r), {0.5f, 0.5f, 0.5f, 0.5f});
}

TEST(ShaderPs1x, CndPerVersion) {
  // ps_1_1: r0.a > 0.5 selects src1 for all components (0.5 itself is not > 0.5)
  auto a = asmRun(R"(ps.1.1
    def c0, 1, 1, 1, 1
    def c1, 0, 0, 0, 0
    mov r0, v0
    cnd r1, r0.a, c0, c1
    mov r0, r1
  )");
  a.setInput(kV0, 0, {0, 0, 0, 0.75f}).setInput(kV0, 1, {0, 0, 0, 0.5f}).execute();
  expectNear(color(a, 0), {1, 1, 1, 1});
  expectNear(color(a, 1), {0, 0, 0, 0});
  // ps_1_4: per component (s0.c > 0.5)
  auto b = asmRun(R"(ps.1.4
    def c0, 1, 1, 1, 1
    def c1, 0, 0, 0, 0
    cnd r0, v0, c0, c1
  )");
  b.input(kV0, {0.25f, 0.5f, 0.75f, 1}).execute();
  expectNear(color(b), {0, 0, 1, 1});
}

TEST(ShaderPs1x, CmpLrpDp4Ps12) {
  auto r = asmRun(R"(ps.1.2
    def c0, 0.25, 0.25, 0.25, 0.25
    def c1, 1, 0, 1, 0
    cmp r0, v0_bias, c1, c0
    lrp r1, c0, c1, v0
    dp4 r1.a, v0, c1
    add r0, r0, r1
  )");
  r.input(kV0, {0.5f, 0.25f, 1, 0}).execute();
  // cmp: (v0 - 0.5 >= 0) ? c1 : c0 → (1, 0.25, 1, 0.25)
  // lrp: c1*0.25 + v0*0.75 → (0.625, 0.1875, 1, 0); dp4 v0.c1 = 0.5 + 1 = 1.5 → 1
  expectNear(color(r), {1, 0.4375f, 1, 1});
}

TEST(ShaderPs1x, CoIssueReadsTheOldValues) {
  // mov r0.rgb, c1 + mov r0.a, r0.b: the alpha half reads r0.b from before the pair
  auto r = asmRun(R"(ps.1.1
    def c0, 0.1, 0.2, 0.3, 0.4
    def c1, 0.5, 0.6, 0.7, 0.8
    mov r0, c0
    mov r0.rgb, c1
    +mov r0.a, r0.b
  )");
  r.execute();
  expectNear(color(r), {0.5f, 0.6f, 0.7f, 0.3f});  // r0.a = old r0.b = 0.3
  // Each half reads what the other writes: both see the old values.
  auto s = asmRun(R"(ps.1.1
    def c0, 0.1, 0.2, 0.3, 0.4
    mov r0, c0
    mov r1, c0
    add r0.rgb, r0, r1.a
    +add r1.a, r0.b, r1.b
    mov r0.a, r1.a
  )");
  s.execute();
  // r0.rgb = old r0 + old r1.a = (0.5, 0.6, 0.7); r1.a = old r0.b + old r1.b = 0.6
  expectNear(color(s), {0.5f, 0.6f, 0.7f, 0.6f});
}

TEST(ShaderPs1x, TexAndTexcoord) {
  ShaderLoweringOptions o;
  o.projectedTextureStages = 0x4;  // stage 2 has D3DTTFF_PROJECTED
  auto r = asmRun(R"(ps.1.1
    tex t0
    texcoord t1
    tex t2
    mov r0, t0
    mov r1, t1
  )", o);
  r.input(kTC0, {0.25f, 0.5f, 0, 1}).input(kTC0 + 1, {1.5f, -0.5f, 0.25f, 7}).input(kTC0 + 2, {1, 2, 3, 4});
  r.fakes[0].offset = 0.125f;
  r.execute();
  expectNear(color(r), {0.375f, 0.625f, 0.125f, 1});            // coords + 0.125
  expectNear(r.temp(1), {1, 0, 0.25f, 1});  // r1 = texcoord t1: saturated, w = 1
  EXPECT_EQ(r.fakes[0].lastMode, SampleMode::Implicit);
  EXPECT_EQ(r.lowered.samplersUsed, 0x5u);
}

TEST(ShaderPs1x, TexProjectedDividesByW) {
  ShaderLoweringOptions o;
  o.projectedTextureStages = 0x1;
  auto r = asmRun("ps.1.1\ntex t0\nmov r0, t0\n", o);
  r.input(kTC0, {1, 0.5f, 0.25f, 2}).execute();
  // (u/q, v/q, w/q, q)
  expectNear(color(r), {0.5f, 0.25f, 0.125f, 1});
}

TEST(ShaderPs1x, TexkillUsesTheCoordinatesXyz) {
  auto r = asmRun("ps.1.1\ntexkill t0\nmov r0, v0\n");
  r.setInput(kTC0, 0, {0, 0, 0, -1});   // w not tested: kept
  r.setInput(kTC0, 1, {0, -0.1f, 0, 1});  // killed
  r.setInput(kTC0, 2, {0, 0, -1, 1});   // killed
  r.execute();
  EXPECT_TRUE(r.laneLive(0));
  EXPECT_FALSE(r.laneLive(1));
  EXPECT_FALSE(r.laneLive(2));
  EXPECT_TRUE(r.laneLive(3));
  EXPECT_TRUE(r.lowered.kills);
}

TEST(ShaderPs1x, TexbemAndTexbemlUseTheSampledStagesMatrix) {
  auto r = asmRun(R"(ps.1.1
    tex t0
    texbem t1, t0
    texbeml t2, t0
    mov r0, t1
    mov r1, t2
    mov r0.a, r1.a
  )");
  // t0 = TC0 = (du, dv, L) = (0.5, -0.25, 0.5)
  r.input(kTC0, {0.5f, -0.25f, 0.5f, 1}).input(kTC0 + 1, {0.1f, 0.2f, 0, 0}).input(kTC0 + 2, {0.3f, 0.4f, 0, 0});
  // stage 1: M = (m00, m01, m10, m11) = (0.5, 0, 0, 1); stage 2: (0, 1, -1, 0), lscale 4, loffset 0
  r.constant(kConstBumpEnv + 2, {0.5f, 0, 0, 1});
  r.constant(kConstBumpEnv + 4, {0, 1, -1, 0}).constant(kConstBumpEnv + 5, {4, 0, 0, 0});
  r.execute();
  // t1: u' = 0.1 + 0.5*0.5 + 0*(-0.25) = 0.35; v' = 0.2 + 0*0.5 + 1*(-0.25) = -0.05
  const Vec4 c = color(r);
  EXPECT_NEAR(c.x, 0.35f, 1e-5f);
  EXPECT_NEAR(c.y, -0.05f, 1e-5f);
  // t2: u' = 0.3 + 0 + (-1)(-0.25) = 0.55; v' = 0.4 + 1*0.5 + 0 = 0.9; sample (0.55, 0.9, 0, 0)
  // then * (t0.b * 4 + 0) = *2 → (1.1 → 1, 1.8 → 1, 0, 0): alpha = 0
  expectNear(r.temp(1), {1, 1, 0, 0});  // r1 = t2
  EXPECT_NEAR(c.w, 0.0f, 1e-5f);
  EXPECT_EQ(r.lowered.bumpEnvStages, 0x6);
}

TEST(ShaderPs1x, TexbemlLuminanceIsNotSaturated) {
  auto r = asmRun("ps.1.1\ntex t0\ntexbeml t1, t0\nmov r0, t1\n");
  r.input(kTC0, {0, 0, 0.5f, 1}).input(kTC0 + 1, {0.2f, 0.1f, 0.3f, 0.4f});
  r.constant(kConstBumpEnv + 2, {0, 0, 0, 0}).constant(kConstBumpEnv + 3, {4, -0.5f, 0, 0});
  r.execute();
  // L = 0.5*4 - 0.5 = 1.5 (not saturated); t1 = (0.2, 0.1, 0.3, 0.4) * 1.5
  expectNear(color(r), {0.3f, 0.15f, 0.45f, 0.6f});
}

TEST(ShaderPs1x, TexReg2ArGbRgb) {
  auto r = asmRun(R"(ps.1.2
    tex t0
    texreg2ar t1, t0
    texreg2gb t2, t0
    texreg2rgb t3, t0
    mov r0.rg, t1
    mov r1, t2
    mov r0.b, r1.g
    mov r1, t3
    mov r0.a, r1.b
  )");
  r.input(kTC0, {0.1f, 0.2f, 0.3f, 0.4f}).execute();
  // texreg2ar: (a, r) = (0.4, 0.1); texreg2gb: (g, b) → .g of t2 = b = 0.3; texreg2rgb .b = 0.3
  expectNear(color(r), {0.4f, 0.1f, 0.3f, 0.3f});
}

TEST(ShaderPs1x, Texm3x2padTexm3x2tex) {
  auto r = asmRun(R"(ps.1.1
    tex t0
    texm3x2pad t1, t0_bx2
    texm3x2tex t2, t0_bx2
    mov r0, t2
  )");
  // t0 = (0.75, 0.5, 1) → bx2 = (0.5, 0, 1); TC1 = (1, 2, 3) → u' = 0.5 + 3 = 3.5;
  // TC2 = (0.5, 0, 0.25) → v' = 0.25 + 0.25 = 0.5. Sample (3.5, 0.5) → clamp to 1 in r0.
  r.input(kTC0, {0.75f, 0.5f, 1, 1}).input(kTC0 + 1, {1, 2, 3, 0}).input(kTC0 + 2, {0.5f, 0, 0.25f, 0});
  r.fakes[2].offset = -3.0f;  // (0.5, -2.5, …) so both values are inside [-1, 1] after the offset
  r.execute();
  EXPECT_NEAR(color(r).x, 0.5f, 1e-5f);  // 3.5 - 3
  EXPECT_NEAR(color(r).y, -1.0f, 1e-5f);  // 0.5 - 3 = -2.5 → clamp -1
}

TEST(ShaderPs1x, Texm3x2depthReplacesDepth) {
  auto r = asmRun(R"(ps.1.3
    tex t0
    texm3x2pad t1, t0
    texm3x2depth t2, t0
    mov r0, t0
  )");
  // t0 = (1, 0, 0); z = TC1.x = 0.3, w = TC2.x = 0.6 → depth 0.5; lane 1: w = 0 → 1
  r.input(kTC0, {1, 0, 0, 1}).input(kTC0 + 1, {0.3f, 0, 0, 0});
  r.setInput(kTC0 + 2, 0, {0.6f, 0, 0, 0}).setInput(kTC0 + 2, 1, {0, 0, 0, 0});
  r.execute();
  EXPECT_NEAR(r.output(kPixelOutDepth, 0).x, 0.5f, 1e-6f);
  EXPECT_EQ(r.output(kPixelOutDepth, 1).x, 1.0f);
  EXPECT_TRUE(r.lowered.writesDepth);
}

TEST(ShaderPs1x, Texm3x3texAndTexm3x3) {
  auto r = asmRun(R"(ps.1.2
    tex t0
    texm3x3pad t1, t0
    texm3x3pad t2, t0
    texm3x3 t3, t0
    mov r0, t3
  )");
  // t0 = (0.5, 0.25, 0.125); rows TC1..TC3 = (1,0,0), (0,2,0), (0,0,4): (0.5, 0.5, 0.5, 1)
  r.input(kTC0, {0.5f, 0.25f, 0.125f, 1}).input(kTC0 + 1, {1, 0, 0, 0}).input(kTC0 + 2, {0, 2, 0, 0});
  r.input(kTC0 + 3, {0, 0, 4, 0}).execute();
  expectNear(color(r), {0.5f, 0.5f, 0.5f, 1});
  auto t = asmRun(R"(ps.1.1
    tex t0
    texm3x3pad t1, t0
    texm3x3pad t2, t0
    texm3x3tex t3, t0
    mov r0, t3
  )");
  t.input(kTC0, {0.5f, 0.25f, 0.125f, 1}).input(kTC0 + 1, {0, 1, 0, 0}).input(kTC0 + 2, {1, 0, 0, 0});
  t.input(kTC0 + 3, {1, 1, 1, 0}).execute();
  // (N.row1, N.row2, N.row3) = (0.25, 0.5, 0.875) sampled at stage 3 (w is no coordinate)
  const Vec4 c = color(t);
  EXPECT_NEAR(c.x, 0.25f, 1e-6f);
  EXPECT_NEAR(c.y, 0.5f, 1e-6f);
  EXPECT_NEAR(c.z, 0.875f, 1e-6f);
}

TEST(ShaderPs1x, Texm3x3specReflectsAConstantEye) {
  auto r = asmRun(R"(ps.1.1
    tex t0
    texm3x3pad t1, t0
    texm3x3pad t2, t0
    texm3x3spec t3, t0, c0
    mov r0, t3
  )");
  // N = identity rows · t0 = t0 = (0, 0, 0.5); E = c0 = (0.6, 0, 0.8)
  // R = 2 (N.E)/(N.N) N - E = 2 * 0.4 / 0.25 * (0,0,0.5) - E = (0,0,1.6) - (0.6,0,0.8) = (-0.6, 0, 0.8)
  r.input(kTC0, {0, 0, 0.5f, 1}).input(kTC0 + 1, {1, 0, 0, 0}).input(kTC0 + 2, {0, 1, 0, 0});
  r.input(kTC0 + 3, {0, 0, 1, 0}).constant(0, {0.6f, 0, 0.8f, 0}).execute();
  const Vec4 c = color(r);
  EXPECT_NEAR(c.x, -0.6f, 1e-5f);
  EXPECT_NEAR(c.y, 0.0f, 1e-5f);
  EXPECT_NEAR(c.z, 0.8f, 1e-5f);
}

TEST(ShaderPs1x, Texm3x3vspecTakesTheEyeFromQ) {
  auto r = asmRun(R"(ps.1.1
    tex t0
    texm3x3pad t1, t0
    texm3x3pad t2, t0
    texm3x3vspec t3, t0
    mov r0, t3
  )");
  // N = (0, 1, 0); E = (TC1.w, TC2.w, TC3.w) = (0.6, 0.8, 0)
  // R = 2 (0.8)/1 (0,1,0) - (0.6, 0.8, 0) = (-0.6, 0.8, 0)
  r.input(kTC0, {0, 1, 0, 1}).input(kTC0 + 1, {1, 0, 0, 0.6f}).input(kTC0 + 2, {0, 1, 0, 0.8f});
  r.input(kTC0 + 3, {0, 0, 1, 0}).execute();
  const Vec4 c = color(r);
  EXPECT_NEAR(c.x, -0.6f, 1e-5f);
  EXPECT_NEAR(c.y, 0.8f, 1e-5f);
  EXPECT_NEAR(c.z, 0.0f, 1e-5f);
}

TEST(ShaderPs1x, Texdp3AndTexdp3tex) {
  auto r = asmRun(R"(ps.1.2
    tex t0
    texdp3 t1, t0
    texdp3tex t2, t0
    mov r0, t1
    mov r1, t2
    mov r0.a, r1.r
    mov r0.b, r1.g
  )");
  // t0 = (0.5, 0.5, 0.5); TC1 = (0.2, 0.4, 0.6) → 0.6; TC2 = (1, 0, 0) → u' = 0.5, lookup (0.5, 0, 0)
  r.input(kTC0, {0.5f, 0.5f, 0.5f, 1}).input(kTC0 + 1, {0.2f, 0.4f, 0.6f, 0}).input(kTC0 + 2, {1, 0, 0, 9});
  r.execute();
  expectNear(color(r), {0.6f, 0.6f, 0, 0.5f});
}

TEST(ShaderPs14, TexldTexcrdPhaseAndDivides) {
  auto r = asmRun(R"(ps.1.4
    texld r0, t0
    texcrd r1.rgb, t1
    texcrd r2.rg, t2_dw.xyw
    phase
    texld r3, r1_dz
    texld r4, t0.xyw
    add r0.rgb, r3, r2
    +mov r0.a, r4.b
  )");
  r.input(kTC0, {0.5f, 0.25f, 0, 2}).input(kTC0 + 1, {0.5f, 1.0f, 2.0f, 0}).input(kTC0 + 2, {1, 2, 9, 4});
  r.fakes[3].offset = 0;
  r.execute();
  // r2 = (1/4, 2/4); r3 = sample(0.5/2, 1/2) = (0.25, 0.5, 2, 0) (z kept)
  // r4 = sample(t0.xyw) = (0.5, 0.25, 2, 2) → alpha = r4.b = 2
  expectNear(color(r), {0.5f, 1.0f, 2.0f, 2.0f});
  // texcrd keeps values beyond [0, 1] (3.0 stays 3.0 within ±8)
  auto t = asmRun("ps.1.4\ntexcrd r0.rgb, t0\n");
  t.input(kTC0, {3, -2, 0.5f, 0}).execute();
  expectNear(color(t), {3, -2, 0.5f, 0});
}

TEST(ShaderPs14, DivideByZeroGivesOne) {
  auto r = asmRun("ps.1.4\ntexcrd r0.rg, t0_dw.xyw\n");
  r.input(kTC0, {3, 5, 7, 0}).execute();
  // w == 0: quotient 1.0
  EXPECT_EQ(color(r).x, 1.0f);
  EXPECT_EQ(color(r).y, 1.0f);
}

TEST(ShaderPs14, BemAndTexdepthAndTexkill) {
  auto r = asmRun(R"(ps.1.4
    def c0, 0.5, 0.25, 0, 0
    texcrd r1.rgb, t1
    bem r2.rg, c0, r1
    phase
    texcrd r5.rgb, t2
    texkill t3
    texdepth r5
    mov r0, r2
  )");
  // bem with stage 2's matrix (0.5, 0, 0, 2): r2.r = 0.5 + 0.5*1 + 0 = 1 (clamped at 8 anyway),
  // r2.g = 0.25 + 0*1 + 2*0.5 = 1.25
  r.input(kTC0 + 1, {1, 0.5f, 0, 0}).input(kTC0 + 2, {0.25f, 0.5f, 0, 0}).input(kTC0 + 3, {1, 1, 1, 1});
  r.setInput(kTC0 + 3, 1, {1, 1, -1, 1});
  r.constant(kConstBumpEnv + 4, {0.5f, 0, 0, 2}).execute();
  EXPECT_NEAR(color(r).x, 1.0f, 1e-6f);
  EXPECT_NEAR(color(r).y, 1.25f, 1e-6f);
  // texdepth: r5.r / r5.g = 0.5
  EXPECT_NEAR(r.output(kPixelOutDepth).x, 0.5f, 1e-6f);
  EXPECT_TRUE(r.laneLive(0));
  EXPECT_FALSE(r.laneLive(1));
}

// Distinct values of (N.H)^16 computed by four squarings over a ramp of N.H.
int distinctSpecularLevels(Precision precision) {
  ShaderLoweringOptions o;
  o.precision = precision;
  auto r = asmRun(R"(ps.1.1
    dp3 r0, v0_bx2, v1_bx2
    mul r1, r0, r0
    mul r0, r1, r1
    mul r1, r0, r0
    mul r0, r1, r1
  )", o);
  std::set<float> levels;
  // v0 = N (0, 0, 1) in bx2 encoding; v1 = H with z = 0.8..1 on the 8-bit grid
  for (int k = 0; k < 26; ++k) {
    for (int l = 0; l < kBatchLanes; ++l) {
      const int step = k * kBatchLanes + l;  // 0..415
      const float hz = 0.8f + 0.2f * float(step) / 415.0f;
      r.setInput(kV0, l, {0.5f, 0.5f, 1.0f, 1});
      r.setInput(kV1, l, {0.5f, 0.5f, (hz + 1) * 0.5f, 1});
    }
    r.execute();
    for (int l = 0; l < kBatchLanes; ++l) levels.insert(r.output(0, l).x);
  }
  return int(levels.size());
}

TEST(ShaderPs1x, HardwarePrecisionQuantisesAndBands) {
  // 0.8^16 = 0.028 … 1: 8 fractional bits leave at most 1/256 steps of N.H and the
  // fourth power of a 1/256 grid, far fewer levels than fp32.
  const int exact = distinctSpecularLevels(Precision::Exact);
  const int hardware = distinctSpecularLevels(Precision::Hardware);
  EXPECT_GT(exact, 200);
  EXPECT_LT(hardware, 60);
  // Every result lies on the 1/256 grid.
  ShaderLoweringOptions o;
  o.precision = Precision::Hardware;
  auto r = asmRun("ps.1.1\nmul r0, v0, v1\n", o);
  r.input(kV0, {0.3f, 0.7f, 0.9f, 0.1f}).input(kV1, {0.3f, 0.7f, 0.9f, 0.1f}).execute();
  const Vec4 c = color(r);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(c[k] * 256.0f, std::nearbyint(c[k] * 256.0f)) << k;
  // round(0.3*256)/256 = 77/256, squared = 0.0904 → round(23.16)/256 = 23/256
  EXPECT_FLOAT_EQ(c.x, 23.0f / 256.0f);
}

}  // namespace
