// ps_2_0 – ps_3_0: texld variants, texkill, dp2add/cmp, dsx/dsy from the 2x2 quads,
// vPos/vFace, oDepth/oC#, ps_3_0 inputs by semantic.
#include "shader_probe.h"

using namespace probe;

namespace {

constexpr int kV0 = kPixelInDiffuse, kTC0 = kPixelInTex0, kPosition = kPixelInPosition;

TEST(ShaderPs2, TexldVariantsPassTheirMode) {
  auto r = asmRun(R"(ps_2_0
    dcl t0
    dcl t1
    dcl_2d s0
    dcl_cube s1
    dcl_volume s2
    texld r0, t0, s0
    texldp r1, t1, s1
    texldb r2, t0, s2
    add r0, r0, r1
    mov oC0, r0
    mov oC1, r2
  )");
  r.input(kTC0, {0.25f, 0.5f, 0.75f, 1}).input(kTC0 + 1, {1, 2, 3, 4}).execute();
  // texld: (0.25, 0.5, 0.75, 1); texldp: (1/4, 2/4, 3/4, 4)
  expectNear(r.output(0), {0.5f, 1.0f, 1.5f, 5});
  expectNear(r.output(1), {0.25f, 0.5f, 0.75f, 1});
  EXPECT_EQ(r.fakes[2].lastMode, SampleMode::Bias);
  EXPECT_EQ(r.lowered.samplersUsed, 0x7u);
  EXPECT_EQ(r.lowered.samplerTypes[1], sh::TextureType::Cube);
  EXPECT_EQ(r.lowered.samplerTypes[2], sh::TextureType::Volume);
}

TEST(ShaderPs2, Ps30SamplerSwizzleAndTexldd) {
  auto r = asmRun(R"(ps_3_0
    dcl_texcoord0 v0
    dcl_2d s3
    texld r0, v0, s3.wzyx
    texldd r1, v0, s3, c0, c1
    mov oC0, r0
    mov oC1, r1
  )");
  r.input(kTC0, {0.1f, 0.2f, 0.3f, 0.4f}).execute();
  expectNear(r.output(0), {0.4f, 0.3f, 0.2f, 0.1f});  // swizzle applied to the result
  expectNear(r.output(1), {0.1f, 0.2f, 0.3f, 0.4f});
  EXPECT_EQ(r.fakes[3].lastMode, SampleMode::Grad);
}

TEST(ShaderPs2, TexkillTestsEveryMaskedComponent) {
  auto r = asmRun("ps_2_0\ndcl t0\ntexkill t0\nmov oC0, c0\n");
  r.setInput(kTC0, 0, {1, 1, 1, -1});  // w tested in ps_2_0: killed
  r.setInput(kTC0, 1, {1, 1, 1, 1});
  r.execute();
  EXPECT_FALSE(r.laneLive(0));
  EXPECT_TRUE(r.laneLive(1));
}

TEST(ShaderPs2, Dp2addCmpAndColorClamp) {
  auto r = asmRun(R"(ps_2_0
    dcl v0
    def c0, 2, 3, 0.5, -1
    dp2add r0, v0, c0, c0.z
    cmp r1, c0.w, c0.x, v0
    mov r0.y, r1.x
    mov oC0, r0
  )");
  r.input(kV0, {0.5f, 2.0f, 0, 0}).execute();
  // v0 read saturated: (0.5, 1): 0.5*2 + 1*3 + 0.5 = 4.5; cmp(-1 >= 0) → v0.x = 0.5
  expectNear(r.output(0), {4.5f, 0.5f, 4.5f, 4.5f});
}

TEST(ShaderPs2, DerivativesFromTheQuad) {
  auto r = asmRun(R"(ps_2_x
    dcl t0
    dsx r0, t0
    dsy r1, t0
    mov r0.y, r1.x
    mov oC0, r0
  )");
  // lane = quad*4 + (y&1)*2 + (x&1); quads at (0,0) (2,0) (0,2) (2,2); value = 3x + 5y²
  for (int l = 0; l < kBatchLanes; ++l) {
    const int q = l / 4, x = (q & 1) * 2 + (l & 1), y = (q >> 1) * 2 + ((l >> 1) & 1);
    r.setInput(kTC0, l, {float(3 * x + 5 * y * y), 0, 0, 0});
  }
  r.execute();
  for (int l = 0; l < kBatchLanes; ++l) {
    const int q = l / 4, y0 = (q >> 1) * 2;
    // d/dx = 3; d/dy within the quad = 5 (y0+1)² - 5 y0²
    EXPECT_FLOAT_EQ(r.output(0, l).x, 3.0f) << l;
    EXPECT_FLOAT_EQ(r.output(0, l).y, float(5 * (y0 + 1) * (y0 + 1) - 5 * y0 * y0)) << l;
  }
}

TEST(ShaderPs3, InputsBySemanticPositionFaceAndDepth) {
  auto r = asmRun(R"(ps_3_0
    dcl_color0 v0
    dcl_texcoord2 v1.xy
    dcl_texcoord3 v1.zw
    dcl vPos.xy
    dcl vFace
    add r0, v0, v1
    if_lt vFace, c0.x
      mov r0.x, vPos.x
    endif
    mov oC0, r0
    mov oDepth, c1.w
  )");
  // v0: color without clamp in ps_3_0; v1.xy = texcoord2.xy, v1.zw = texcoord3.zw
  r.input(kV0, {2, 0, 0, 0}).input(kTC0 + 2, {0.5f, 0.25f, 9, 9}).input(kTC0 + 3, {9, 9, 1, 2});
  r.setInput(kPosition, 0, {7, 8, 0, 1}).setInput(kPixelInFace, 0, {-1, 0, 0, 0});
  r.setInput(kPosition, 1, {3, 4, 0, 1}).setInput(kPixelInFace, 1, {1, 0, 0, 0});
  r.constant(1, {0, 0, 0, 0.75f}).execute();
  expectNear(r.output(0, 0), {7, 0.25f, 1, 2});    // back face: x = vPos.x
  expectNear(r.output(0, 1), {2.5f, 0.25f, 1, 2});  // front face: 2 + 0.5
  EXPECT_FLOAT_EQ(r.output(kPixelOutDepth, 0).x, 0.75f);
  EXPECT_TRUE(r.lowered.writesDepth);
}

TEST(ShaderPs3, RelativeInputsWithAL) {
  auto r = asmRun(R"(ps_3_0
    dcl_texcoord0 v0
    dcl_texcoord1 v1
    dcl_texcoord2 v2
    defi i0, 3, 0, 1, 0
    mov r0, c0
    loop aL, i0
      add r0, r0, v[aL]
    endloop
    mov oC0, r0
  )");
  r.input(kTC0, {1, 0, 0, 0}).input(kTC0 + 1, {0, 1, 0, 0}).input(kTC0 + 2, {0, 0, 1, 0}).execute();
  expectNear(r.output(0), {1, 1, 1, 0});
}

TEST(ShaderPs3, UnsupportedSemanticIsAnError) {
  EXPECT_THROW(asmRun("ps_3_0\ndcl_normal v0\nmov oC0, v0\n"), refx::Error);
}

}  // namespace
