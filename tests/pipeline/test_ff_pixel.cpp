// Fixed-function texture stages compiled to IR and run on the interpreter. Every
// expected value is worked out from the D3D9 formulas (reference/fixed-function.md)
// in the comment beside it.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pipeline/ff_pixel.h"
#include "refx/exec/interpreter.h"

using namespace refx;
using namespace refx::d3d;
using namespace refx::exec;
using namespace refx::pipeline;

namespace {

// A sampler returning one fixed color and recording the coordinates of lane 0.
struct FakeSampler {
  Vec4 color;
  mutable std::vector<Vec4> calls;
};

void fakeSample(const void* context, SampleMode, const float (*coords)[kBatchLanes], uint16_t,
                float (*out)[kBatchLanes]) {
  const auto* s = static_cast<const FakeSampler*>(context);
  s->calls.push_back({coords[0][0], coords[1][0], coords[2][0], coords[3][0]});
  for (int c = 0; c < 4; ++c)
    for (int l = 0; l < kBatchLanes; ++l) out[c][l] = s->color[c];
}

// Fixed inputs (chosen so sums and products are easy to do by hand):
//   D  = diffuse  (0.2, 0.4, 0.6, 0.8)      S  = specular (0.1, 0.2, 0.3, 0.4)
//   T0 = texture 0 (0.5, 0.25, 0.75, 0.6)   T1 = texture 1 (0.3, 0.9, 0.1, 0.2)
//   F  = TFACTOR 0x66CC3366 = (0.8, 0.2, 0.4, 0.4)   (0xCC = 204/255 = 0.8, 0x33 = 0.2, 0x66 = 0.4)
//   K  = stage CONSTANT 0xCC996633 = (0.6, 0.4, 0.2, 0.8)
class FFPixel : public ::testing::Test {
 protected:
  FFPixel() {
    for (auto& t : tex) t = Texture::create2D(Format::A8R8G8B8, 1, 1);
    samplers[0].color = {0.5f, 0.25f, 0.75f, 0.6f};
    samplers[1].color = {0.3f, 0.9f, 0.1f, 0.2f};
    for (int i = 2; i < 8; ++i) samplers[i].color = {0.1f * i, 0, 0, 1};
    cfg.textures[0] = tex[0].get();
    cfg.textures[1] = tex[1].get();
    state.renderStates[RS_TEXTUREFACTOR] = 0x66CC3366;
    for (int s = 0; s < 8; ++s) {
      state.stageStates[s][TSS_CONSTANT] = 0xCC996633;
      coords[s] = {0.1f * s, 0.05f * s, 0, 1};
    }
  }

  void stage(int s, uint32_t colorOp, uint32_t c1, uint32_t c2, uint32_t alphaOp, uint32_t a1,
             uint32_t a2) {
    auto& t = state.stageStates[s];
    t[TSS_COLOROP] = colorOp;
    t[TSS_COLORARG1] = c1;
    t[TSS_COLORARG2] = c2;
    t[TSS_ALPHAOP] = alphaOp;
    t[TSS_ALPHAARG1] = a1;
    t[TSS_ALPHAARG2] = a2;
  }
  // Same op and arguments for color and alpha.
  void stage(int s, uint32_t op, uint32_t a1, uint32_t a2) { stage(s, op, a1, a2, op, a1, a2); }
  void setFloat(int s, TextureStageState st, float v) { state.stageStates[s][st] = floatBits(v); }
  void setRs(RenderState r, uint32_t v) { state.renderStates[r] = v; }
  void setRsFloat(RenderState r, float v) { state.renderStates[r] = floatBits(v); }

  Vec4 run() {
    program = buildFixedFunctionPixelProgram(state, cfg);
    appendSpecularAndFog(program, state, !cfg.shaderPath);
    return execute(program);
  }
  Vec4 execute(const Program& p) {
    BatchRegisters regs;
    regs.resize(p);
    auto fill = [](LaneVec4& r, Vec4 v) {
      for (int c = 0; c < 4; ++c)
        for (int l = 0; l < kBatchLanes; ++l) r.c[c][l] = v[c];
    };
    fill(regs.inputs[kPixelInDiffuse], diffuse);
    fill(regs.inputs[kPixelInSpecular], specular);
    for (int s = 0; s < 8; ++s) fill(regs.inputs[kPixelInTex0 + s], coords[s]);
    fill(regs.inputs[kPixelInFog], {fog, 0, 0, 0});
    fill(regs.inputs[kPixelInPosition], position);
    fill(regs.outputs[kPixelOutColor], presetOutput);
    SamplerBinding bind[8];
    for (int i = 0; i < 8; ++i) bind[i] = {&samplers[i], fakeSample};
    std::vector<Vec4> constants;
    fixedFunctionPixelConstants(state, constants);
    ExecContext ctx;
    ctx.constants = constants.data();
    ctx.constantCount = int(constants.size());
    ctx.samplers = bind;
    ctx.samplerCount = 8;
    exec::execute(p, ctx, regs);
    const LaneVec4& o = regs.outputs[kPixelOutColor];
    for (int l = 1; l < kBatchLanes; ++l)
      for (int c = 0; c < 4; ++c) EXPECT_EQ(o.c[c][l], o.c[c][0]) << "lanes differ";
    return {o.c[0][0], o.c[1][0], o.c[2][0], o.c[3][0]};
  }
  int count(Op op) const {
    int n = 0;
    for (const Instr& in : program.code) n += in.op == op;
    return n;
  }

  DeviceState state;
  FixedFunctionPixelConfig cfg;
  std::array<TexturePtr, 8> tex;
  FakeSampler samplers[8];
  Vec4 diffuse{0.2f, 0.4f, 0.6f, 0.8f};
  Vec4 specular{0.1f, 0.2f, 0.3f, 0.4f};
  std::array<Vec4, 8> coords{};
  float fog = 1;
  Vec4 position{0, 0, 0.5f, 1};
  Vec4 presetOutput{};
  Program program;
};

constexpr float kTol = 1e-5f;
#define EXPECT_VEC4(v, X, Y, Z, W)        \
  do {                                    \
    Vec4 v_ = (v);                        \
    EXPECT_NEAR(v_.x, (X), kTol) << "r";  \
    EXPECT_NEAR(v_.y, (Y), kTol) << "g";  \
    EXPECT_NEAR(v_.z, (Z), kTol) << "b";  \
    EXPECT_NEAR(v_.w, (W), kTol) << "a";  \
  } while (0)

// ---------------------------------------------------------------- D3DTOP, stage 0
// A1 = TEXTURE = T0 = (0.5, 0.25, 0.75, 0.6), A2 = DIFFUSE = D = (0.2, 0.4, 0.6, 0.8),
// same op for color and alpha.

TEST_F(FFPixel, SelectArg1) {
  stage(0, TOP_SELECTARG1, TA_TEXTURE, TA_DIFFUSE);
  EXPECT_VEC4(run(), 0.5f, 0.25f, 0.75f, 0.6f);  // A1
}

TEST_F(FFPixel, SelectArg2) {
  stage(0, TOP_SELECTARG2, TA_TEXTURE, TA_DIFFUSE);
  EXPECT_VEC4(run(), 0.2f, 0.4f, 0.6f, 0.8f);  // A2
}

TEST_F(FFPixel, Modulate) {
  stage(0, TOP_MODULATE, TA_TEXTURE, TA_DIFFUSE);
  // A1*A2 = (0.5*0.2, 0.25*0.4, 0.75*0.6, 0.6*0.8)
  EXPECT_VEC4(run(), 0.1f, 0.1f, 0.45f, 0.48f);
}

TEST_F(FFPixel, Modulate2x) {
  stage(0, TOP_MODULATE2X, TA_TEXTURE, TA_DIFFUSE);
  // 2*A1*A2 = 2*(0.1, 0.1, 0.45, 0.48)
  EXPECT_VEC4(run(), 0.2f, 0.2f, 0.9f, 0.96f);
}

TEST_F(FFPixel, Modulate4x) {
  stage(0, TOP_MODULATE4X, TA_TEXTURE, TA_DIFFUSE);
  // 4*A1*A2 = (0.4, 0.4, 1.8 -> 1, 1.92 -> 1) saturated
  EXPECT_VEC4(run(), 0.4f, 0.4f, 1.0f, 1.0f);
}

TEST_F(FFPixel, Add) {
  stage(0, TOP_ADD, TA_TEXTURE, TA_DIFFUSE);
  // A1+A2 = (0.7, 0.65, 1.35 -> 1, 1.4 -> 1)
  EXPECT_VEC4(run(), 0.7f, 0.65f, 1.0f, 1.0f);
}

TEST_F(FFPixel, AddSigned) {
  stage(0, TOP_ADDSIGNED, TA_TEXTURE, TA_DIFFUSE);
  // A1+A2-0.5 = (0.2, 0.15, 0.85, 0.9)
  EXPECT_VEC4(run(), 0.2f, 0.15f, 0.85f, 0.9f);
}

TEST_F(FFPixel, AddSigned2x) {
  stage(0, TOP_ADDSIGNED2X, TA_TEXTURE, TA_DIFFUSE);
  // 2*(A1+A2-0.5) = (0.4, 0.3, 1.7 -> 1, 1.8 -> 1)
  EXPECT_VEC4(run(), 0.4f, 0.3f, 1.0f, 1.0f);
}

TEST_F(FFPixel, Subtract) {
  stage(0, TOP_SUBTRACT, TA_TEXTURE, TA_DIFFUSE);
  // A1-A2 = (0.3, -0.15 -> 0, 0.15, -0.2 -> 0)
  EXPECT_VEC4(run(), 0.3f, 0.0f, 0.15f, 0.0f);
}

TEST_F(FFPixel, AddSmooth) {
  stage(0, TOP_ADDSMOOTH, TA_TEXTURE, TA_DIFFUSE);
  // A1+A2-A1*A2 = (0.7-0.1, 0.65-0.1, 1.35-0.45, 1.4-0.48)
  EXPECT_VEC4(run(), 0.6f, 0.55f, 0.9f, 0.92f);
}

TEST_F(FFPixel, BlendDiffuseAlpha) {
  stage(0, TOP_BLENDDIFFUSEALPHA, TA_TEXTURE, TA_DIFFUSE);
  // a = D.a = 0.8: A1*0.8 + A2*0.2 = (0.4+0.04, 0.2+0.08, 0.6+0.12, 0.48+0.16)
  EXPECT_VEC4(run(), 0.44f, 0.28f, 0.72f, 0.64f);
}

TEST_F(FFPixel, BlendTextureAlpha) {
  stage(0, TOP_BLENDTEXTUREALPHA, TA_TEXTURE, TA_DIFFUSE);
  // a = T0.a = 0.6: A1*0.6 + A2*0.4 = (0.3+0.08, 0.15+0.16, 0.45+0.24, 0.36+0.32)
  EXPECT_VEC4(run(), 0.38f, 0.31f, 0.69f, 0.68f);
}

TEST_F(FFPixel, BlendFactorAlpha) {
  stage(0, TOP_BLENDFACTORALPHA, TA_TEXTURE, TA_DIFFUSE);
  // a = F.a = 0.4: A1*0.4 + A2*0.6 = (0.2+0.12, 0.1+0.24, 0.3+0.36, 0.24+0.48)
  EXPECT_VEC4(run(), 0.32f, 0.34f, 0.66f, 0.72f);
}

TEST_F(FFPixel, BlendTextureAlphaPM) {
  stage(0, TOP_BLENDTEXTUREALPHAPM, TA_TEXTURE, TA_DIFFUSE);
  // A1 + A2*(1 - T0.a) = A1 + 0.4*A2 = (0.5+0.08, 0.25+0.16, 0.75+0.24, 0.6+0.32)
  EXPECT_VEC4(run(), 0.58f, 0.41f, 0.99f, 0.92f);
}

TEST_F(FFPixel, BlendCurrentAlpha) {
  // Stage 0: CURRENT = F = (0.8, 0.2, 0.4, 0.4). Stage 1: A1 = T1, A2 = D, a = CURRENT.a = 0.4:
  // T1*0.4 + D*0.6 = (0.12+0.12, 0.36+0.24, 0.04+0.36, 0.08+0.48)
  stage(0, TOP_SELECTARG1, TA_TFACTOR, TA_DIFFUSE);
  stage(1, TOP_BLENDCURRENTALPHA, TA_TEXTURE, TA_DIFFUSE);
  EXPECT_VEC4(run(), 0.24f, 0.6f, 0.4f, 0.56f);
}

TEST_F(FFPixel, PremodulateOutputsArg1) {
  stage(0, TOP_PREMODULATE, TA_TEXTURE, TA_DIFFUSE);
  EXPECT_VEC4(run(), 0.5f, 0.25f, 0.75f, 0.6f);  // output = A1 = T0
}

TEST_F(FFPixel, PremodulateMultipliesNextStageCurrentByItsTexture) {
  stage(0, TOP_PREMODULATE, TA_TEXTURE, TA_DIFFUSE);
  stage(1, TOP_SELECTARG1, TA_CURRENT, TA_DIFFUSE);
  // CURRENT in stage 1 = T0 * T1 = (0.5*0.3, 0.25*0.9, 0.75*0.1, 0.6*0.2)
  EXPECT_VEC4(run(), 0.15f, 0.225f, 0.075f, 0.12f);
}

TEST_F(FFPixel, PremodulateWithoutNextTextureLeavesCurrent) {
  cfg.textures[1] = nullptr;
  stage(0, TOP_PREMODULATE, TA_TEXTURE, TA_DIFFUSE);
  stage(1, TOP_SELECTARG1, TA_CURRENT, TA_DIFFUSE);
  EXPECT_VEC4(run(), 0.5f, 0.25f, 0.75f, 0.6f);  // CURRENT = T0 unchanged
}

// The four color-only ops: A1 = T0, A2 = SPECULAR S = (0.1, 0.2, 0.3, 0.4); alpha op
// SELECTARG2 DIFFUSE -> 0.8.
TEST_F(FFPixel, ModulateAlphaAddColor) {
  stage(0, TOP_MODULATEALPHA_ADDCOLOR, TA_TEXTURE, TA_SPECULAR, TOP_SELECTARG2, TA_TEXTURE,
        TA_DIFFUSE);
  // A1 + A1.a*A2 = T0 + 0.6*S = (0.5+0.06, 0.25+0.12, 0.75+0.18)
  EXPECT_VEC4(run(), 0.56f, 0.37f, 0.93f, 0.8f);
}

TEST_F(FFPixel, ModulateColorAddAlpha) {
  stage(0, TOP_MODULATECOLOR_ADDALPHA, TA_TEXTURE, TA_SPECULAR, TOP_SELECTARG2, TA_TEXTURE,
        TA_DIFFUSE);
  // A1*A2 + A1.a = (0.05+0.6, 0.05+0.6, 0.225+0.6)
  EXPECT_VEC4(run(), 0.65f, 0.65f, 0.825f, 0.8f);
}

TEST_F(FFPixel, ModulateInvAlphaAddColor) {
  stage(0, TOP_MODULATEINVALPHA_ADDCOLOR, TA_TEXTURE, TA_SPECULAR, TOP_SELECTARG2, TA_TEXTURE,
        TA_DIFFUSE);
  // A1 + (1-A1.a)*A2 = T0 + 0.4*S = (0.5+0.04, 0.25+0.08, 0.75+0.12)
  EXPECT_VEC4(run(), 0.54f, 0.33f, 0.87f, 0.8f);
}

TEST_F(FFPixel, ModulateInvColorAddAlpha) {
  stage(0, TOP_MODULATEINVCOLOR_ADDALPHA, TA_TEXTURE, TA_SPECULAR, TOP_SELECTARG2, TA_TEXTURE,
        TA_DIFFUSE);
  // (1-A1)*A2 + A1.a = (0.5*0.1+0.6, 0.75*0.2+0.6, 0.25*0.3+0.6)
  EXPECT_VEC4(run(), 0.65f, 0.75f, 0.675f, 0.8f);
}

TEST_F(FFPixel, DotProduct3OverridesAlphaOp) {
  // Alpha op alone would give T0.a = 0.6.
  stage(0, TOP_DOTPRODUCT3, TA_TEXTURE, TA_DIFFUSE, TOP_SELECTARG1, TA_TEXTURE, TA_DIFFUSE);
  // 4*((0.5-0.5)(0.2-0.5) + (0.25-0.5)(0.4-0.5) + (0.75-0.5)(0.6-0.5))
  //   = 4*(0 + 0.025 + 0.025) = 0.2, replicated to r, g, b and a
  EXPECT_VEC4(run(), 0.2f, 0.2f, 0.2f, 0.2f);
}

TEST_F(FFPixel, DotProduct3Saturates) {
  // A1 = T0, A2 = 1 - D = (0.8, 0.6, 0.4):
  // 4*(0*0.3 + (-0.25)*0.1 + 0.25*(-0.1)) = -0.2 -> 0
  stage(0, TOP_DOTPRODUCT3, TA_TEXTURE, TA_DIFFUSE | TA_COMPLEMENT);
  EXPECT_VEC4(run(), 0.0f, 0.0f, 0.0f, 0.0f);
}

TEST_F(FFPixel, MultiplyAdd) {
  stage(0, TOP_MULTIPLYADD, TA_TEXTURE, TA_DIFFUSE);
  state.stageStates[0][TSS_COLORARG0] = TA_SPECULAR;
  state.stageStates[0][TSS_ALPHAARG0] = TA_SPECULAR;
  // A0 + A1*A2 = S + T0*D = (0.1+0.1, 0.2+0.1, 0.3+0.45, 0.4+0.48)
  EXPECT_VEC4(run(), 0.2f, 0.3f, 0.75f, 0.88f);
}

TEST_F(FFPixel, Lerp) {
  stage(0, TOP_LERP, TA_TEXTURE, TA_DIFFUSE);
  state.stageStates[0][TSS_COLORARG0] = TA_SPECULAR;
  state.stageStates[0][TSS_ALPHAARG0] = TA_SPECULAR;
  // A0*A1 + (1-A0)*A2: r 0.1*0.5+0.9*0.2 = 0.23; g 0.2*0.25+0.8*0.4 = 0.37;
  // b 0.3*0.75+0.7*0.6 = 0.645; a 0.4*0.6+0.6*0.8 = 0.72
  EXPECT_VEC4(run(), 0.23f, 0.37f, 0.645f, 0.72f);
}

// ---------------------------------------------------------------- bump mapping

class FFPixelBump : public FFPixel {
 protected:
  FFPixelBump() {
    // Bump texel (du, dv, L) = (0.5, -0.25, 0.5); matrix M00 0.5, M01 0.25, M10 -0.5, M11 2.
    samplers[0].color = {0.5f, -0.25f, 0.5f, 1.0f};
    setFloat(0, TSS_BUMPENVMAT00, 0.5f);
    setFloat(0, TSS_BUMPENVMAT01, 0.25f);
    setFloat(0, TSS_BUMPENVMAT10, -0.5f);
    setFloat(0, TSS_BUMPENVMAT11, 2.0f);
    coords[0] = {0.7f, 0.8f, 0, 1};
    coords[1] = {0.1f, 0.2f, 0.3f, 1};
    stage(1, TOP_SELECTARG1, TA_TEXTURE, TA_DIFFUSE);
  }
};

TEST_F(FFPixelBump, BumpEnvMapPerturbsNextStageCoordinates) {
  stage(0, TOP_BUMPENVMAP, TA_TEXTURE, TA_CURRENT);
  Vec4 c = run();
  EXPECT_VEC4(c, 0.3f, 0.9f, 0.1f, 0.2f);  // stage 1 selects T1, luminance factor 1
  ASSERT_EQ(samplers[0].calls.size(), 1u);
  EXPECT_NEAR(samplers[0].calls[0].x, 0.7f, kTol);  // bump map read at TC0
  EXPECT_NEAR(samplers[0].calls[0].y, 0.8f, kTol);
  ASSERT_EQ(samplers[1].calls.size(), 1u);
  // u' = 0.1 + du*M00 + dv*M10 = 0.1 + 0.5*0.5 + (-0.25)*(-0.5) = 0.475
  // v' = 0.2 + du*M01 + dv*M11 = 0.2 + 0.5*0.25 + (-0.25)*2 = -0.175
  EXPECT_NEAR(samplers[1].calls[0].x, 0.475f, kTol);
  EXPECT_NEAR(samplers[1].calls[0].y, -0.175f, kTol);
  EXPECT_NEAR(samplers[1].calls[0].z, 0.3f, kTol);  // w coordinate untouched
}

TEST_F(FFPixelBump, BumpEnvMapWithProjectedNextStage) {
  stage(0, TOP_BUMPENVMAP, TA_TEXTURE, TA_CURRENT);
  state.stageStates[1][TSS_TEXTURETRANSFORMFLAGS] = TTFF_COUNT3 | TTFF_PROJECTED;
  coords[1] = {0.2f, 0.4f, 0, 2};
  run();
  ASSERT_EQ(samplers[1].calls.size(), 1u);
  // (u, v) = (0.2, 0.4)/2 = (0.1, 0.2), then perturbed as above: (0.475, -0.175)
  EXPECT_NEAR(samplers[1].calls[0].x, 0.475f, kTol);
  EXPECT_NEAR(samplers[1].calls[0].y, -0.175f, kTol);
}

TEST_F(FFPixelBump, CurrentAfterBumpStageIsStageBefore) {
  // Bump at stage 0: CURRENT in stage 1 = DIFFUSE. T1*D = (0.06, 0.36, 0.06, 0.16)
  stage(0, TOP_BUMPENVMAP, TA_TEXTURE, TA_CURRENT);
  stage(1, TOP_MODULATE, TA_TEXTURE, TA_CURRENT);
  EXPECT_VEC4(run(), 0.06f, 0.36f, 0.06f, 0.16f);
}

TEST_F(FFPixelBump, CurrentAfterBumpStageSkipsBumpStage) {
  // Stage 0 selects F; stage 1 bumps (matrix of stage 1); stage 2 selects CURRENT = F.
  samplers[1].color = {0.5f, -0.25f, 0.5f, 1.0f};
  stage(0, TOP_SELECTARG1, TA_TFACTOR, TA_DIFFUSE);
  stage(1, TOP_BUMPENVMAP, TA_TEXTURE, TA_CURRENT);
  stage(2, TOP_SELECTARG1, TA_CURRENT, TA_DIFFUSE);
  cfg.textures[2] = tex[2].get();
  EXPECT_VEC4(run(), 0.8f, 0.2f, 0.4f, 0.4f);
}

TEST_F(FFPixelBump, BumpEnvMapLuminanceScalesAllChannels) {
  // Lf = saturate(L*LSCALE + LOFFSET) = saturate(0.5*0.5 + 0.25) = 0.5
  // TEXTURE in stage 1 = T1*0.5 = (0.15, 0.45, 0.05, 0.1)
  stage(0, TOP_BUMPENVMAPLUMINANCE, TA_TEXTURE, TA_CURRENT);
  setFloat(0, TSS_BUMPENVLSCALE, 0.5f);
  setFloat(0, TSS_BUMPENVLOFFSET, 0.25f);
  EXPECT_VEC4(run(), 0.15f, 0.45f, 0.05f, 0.1f);
  EXPECT_NEAR(samplers[1].calls.at(0).x, 0.475f, kTol);  // also perturbed
}

TEST_F(FFPixelBump, BumpEnvMapLuminanceSaturatesHigh) {
  // Lf = saturate(0.5*4 + 0) = saturate(2) = 1 -> T1 unchanged
  stage(0, TOP_BUMPENVMAPLUMINANCE, TA_TEXTURE, TA_CURRENT);
  setFloat(0, TSS_BUMPENVLSCALE, 4.0f);
  EXPECT_VEC4(run(), 0.3f, 0.9f, 0.1f, 0.2f);
}

TEST_F(FFPixelBump, BumpEnvMapLuminanceSaturatesLow) {
  // Lf = saturate(0.5*(-1) + 0.25) = saturate(-0.25) = 0 -> (0, 0, 0, 0)
  stage(0, TOP_BUMPENVMAPLUMINANCE, TA_TEXTURE, TA_CURRENT);
  setFloat(0, TSS_BUMPENVLSCALE, -1.0f);
  setFloat(0, TSS_BUMPENVLOFFSET, 0.25f);
  EXPECT_VEC4(run(), 0.0f, 0.0f, 0.0f, 0.0f);
}

// ---------------------------------------------------------------- DISABLE cascade

TEST_F(FFPixel, Stage0DisabledGivesDiffuse) {
  stage(0, TOP_DISABLE, TA_TEXTURE, TA_CURRENT);
  EXPECT_VEC4(run(), 0.2f, 0.4f, 0.6f, 0.8f);
  EXPECT_EQ(count(Op::Tex), 0);
}

TEST_F(FFPixel, CascadeStopsAtFirstDisabledStage) {
  stage(0, TOP_SELECTARG1, TA_TEXTURE, TA_DIFFUSE);
  stage(1, TOP_DISABLE, TA_TEXTURE, TA_CURRENT);
  stage(2, TOP_SELECTARG1, TA_TFACTOR, TA_CURRENT);  // never reached
  EXPECT_VEC4(run(), 0.5f, 0.25f, 0.75f, 0.6f);     // T0 from stage 0
}

TEST_F(FFPixel, AlphaOpDisabledPassesCurrentAlpha) {
  stage(0, TOP_SELECTARG1, TA_TEXTURE, TA_DIFFUSE);
  stage(1, TOP_SELECTARG1, TA_DIFFUSE, TA_CURRENT, TOP_DISABLE, TA_TEXTURE, TA_CURRENT);
  // rgb = D.rgb; alpha = CURRENT.a from stage 0 = T0.a = 0.6
  EXPECT_VEC4(run(), 0.2f, 0.4f, 0.6f, 0.6f);
}

TEST_F(FFPixel, Stage0AlphaOpDisabledPassesDiffuseAlpha) {
  stage(0, TOP_SELECTARG1, TA_TEXTURE, TA_DIFFUSE, TOP_DISABLE, TA_TEXTURE, TA_DIFFUSE);
  EXPECT_VEC4(run(), 0.5f, 0.25f, 0.75f, 0.8f);  // alpha = D.a
}

TEST_F(FFPixel, DefaultStateModulatesTextureAndDiffuse) {
  // Stage 0 defaults: color MODULATE(TEXTURE, CURRENT = D), alpha SELECTARG1(TEXTURE).
  EXPECT_VEC4(run(), 0.1f, 0.1f, 0.45f, 0.6f);
  EXPECT_EQ(count(Op::Tex), 1);
  EXPECT_EQ(program.inputCount, kPixelInputCount);
  EXPECT_EQ(program.outputCount, kPixelOutputCount);
  EXPECT_GT(program.tempCount, 0);
}

// ---------------------------------------------------------------- arguments

TEST_F(FFPixel, ArgDiffuse) {
  stage(0, TOP_SELECTARG1, TA_DIFFUSE, TA_TEXTURE);
  EXPECT_VEC4(run(), 0.2f, 0.4f, 0.6f, 0.8f);
  EXPECT_EQ(count(Op::Tex), 0);  // no TEXTURE read, no sample
  EXPECT_TRUE(samplers[0].calls.empty());
}

TEST_F(FFPixel, ArgCurrentInStage0IsDiffuse) {
  stage(0, TOP_SELECTARG1, TA_CURRENT, TA_TEXTURE);
  EXPECT_VEC4(run(), 0.2f, 0.4f, 0.6f, 0.8f);
}

TEST_F(FFPixel, ArgCurrentIsPreviousStage) {
  stage(0, TOP_SELECTARG1, TA_TFACTOR, TA_DIFFUSE);
  stage(1, TOP_SELECTARG1, TA_CURRENT, TA_DIFFUSE);
  EXPECT_VEC4(run(), 0.8f, 0.2f, 0.4f, 0.4f);  // F
}

TEST_F(FFPixel, ArgTexture) {
  stage(0, TOP_SELECTARG1, TA_DIFFUSE, TA_DIFFUSE);
  stage(1, TOP_SELECTARG1, TA_TEXTURE, TA_DIFFUSE);
  EXPECT_VEC4(run(), 0.3f, 0.9f, 0.1f, 0.2f);  // T1 from sampler 1
  ASSERT_EQ(samplers[1].calls.size(), 1u);
  EXPECT_NEAR(samplers[1].calls[0].x, 0.1f, kTol);  // coordinates of stage 1 (input 3)
  EXPECT_NEAR(samplers[1].calls[0].y, 0.05f, kTol);
}

TEST_F(FFPixel, ArgTextureWithoutTextureReadsCurrent) {
  cfg.textures[1] = nullptr;
  stage(0, TOP_SELECTARG1, TA_TFACTOR, TA_DIFFUSE);
  stage(1, TOP_SELECTARG1, TA_TEXTURE, TA_DIFFUSE);
  EXPECT_VEC4(run(), 0.8f, 0.2f, 0.4f, 0.4f);  // CURRENT = F
  EXPECT_TRUE(samplers[1].calls.empty());
}

TEST_F(FFPixel, ArgTFactor) {
  stage(0, TOP_SELECTARG1, TA_TFACTOR, TA_DIFFUSE);
  EXPECT_VEC4(run(), 0.8f, 0.2f, 0.4f, 0.4f);  // 0x66CC3366 -> (204, 51, 102, 102)/255
}

TEST_F(FFPixel, ArgSpecular) {
  stage(0, TOP_SELECTARG1, TA_SPECULAR, TA_DIFFUSE);
  EXPECT_VEC4(run(), 0.1f, 0.2f, 0.3f, 0.4f);
}

TEST_F(FFPixel, ArgTempStartsAtZero) {
  stage(0, TOP_SELECTARG1, TA_TEMP, TA_DIFFUSE);
  EXPECT_VEC4(run(), 0.0f, 0.0f, 0.0f, 0.0f);
}

TEST_F(FFPixel, ArgConstant) {
  stage(0, TOP_SELECTARG1, TA_CONSTANT, TA_DIFFUSE);
  EXPECT_VEC4(run(), 0.6f, 0.4f, 0.2f, 0.8f);  // 0xCC996633 -> (153, 102, 51, 204)/255
}

TEST_F(FFPixel, ArgConstantIsPerStage) {
  stage(0, TOP_SELECTARG1, TA_CONSTANT, TA_DIFFUSE);
  stage(1, TOP_ADD, TA_CONSTANT, TA_CURRENT);
  state.stageStates[1][TSS_CONSTANT] = 0x33333333;  // 0.2 each
  EXPECT_VEC4(run(), 0.8f, 0.6f, 0.4f, 1.0f);        // K + 0.2, alpha 0.8+0.2
}

TEST_F(FFPixel, ModifierComplement) {
  stage(0, TOP_SELECTARG1, TA_TEXTURE | TA_COMPLEMENT, TA_DIFFUSE);
  EXPECT_VEC4(run(), 0.5f, 0.75f, 0.25f, 0.4f);  // 1 - T0
}

TEST_F(FFPixel, ModifierAlphaReplicate) {
  stage(0, TOP_SELECTARG1, TA_TEXTURE | TA_ALPHAREPLICATE, TA_DIFFUSE);
  EXPECT_VEC4(run(), 0.6f, 0.6f, 0.6f, 0.6f);  // (T0.a, T0.a, T0.a, T0.a)
}

TEST_F(FFPixel, ModifierComplementAndAlphaReplicate) {
  stage(0, TOP_SELECTARG1, TA_TEXTURE | TA_COMPLEMENT | TA_ALPHAREPLICATE, TA_DIFFUSE);
  EXPECT_VEC4(run(), 0.4f, 0.4f, 0.4f, 0.4f);  // 1 - T0.a = 0.4 replicated
}

TEST_F(FFPixel, ComplementInsideModulate) {
  stage(0, TOP_MODULATE, TA_TEXTURE | TA_COMPLEMENT, TA_DIFFUSE);
  // (1-T0)*D = (0.5*0.2, 0.75*0.4, 0.25*0.6, 0.4*0.8)
  EXPECT_VEC4(run(), 0.1f, 0.3f, 0.15f, 0.32f);
}

TEST_F(FFPixel, ComplementInsideAddSigned) {
  stage(0, TOP_ADDSIGNED, TA_TEXTURE, TA_DIFFUSE | TA_COMPLEMENT);
  // T0 + (1-D) - 0.5 = (0.5+0.8-0.5, 0.25+0.6-0.5, 0.75+0.4-0.5, 0.6+0.2-0.5)
  EXPECT_VEC4(run(), 0.8f, 0.35f, 0.65f, 0.3f);
}

TEST_F(FFPixel, ComplementInsideDotProduct3) {
  stage(0, TOP_DOTPRODUCT3, TA_DIFFUSE | TA_COMPLEMENT, TA_TFACTOR);
  // A1 = 1-D = (0.8, 0.6, 0.4), A2 = F = (0.8, 0.2, 0.4):
  // 4*(0.3*0.3 + 0.1*(-0.3) + (-0.1)*(-0.1)) = 4*0.07 = 0.28
  EXPECT_VEC4(run(), 0.28f, 0.28f, 0.28f, 0.28f);
}

TEST_F(FFPixel, ComplementedAlphaInsideModulateInvAlpha) {
  stage(0, TOP_MODULATEINVALPHA_ADDCOLOR, TA_TEXTURE | TA_COMPLEMENT, TA_SPECULAR,
        TOP_SELECTARG2, TA_TEXTURE, TA_DIFFUSE);
  // A1 = 1-T0 = (0.5, 0.75, 0.25, 0.4); A1 + (1-A1.a)*S = A1 + 0.6*S
  //    = (0.5+0.06, 0.75+0.12, 0.25+0.18)
  EXPECT_VEC4(run(), 0.56f, 0.87f, 0.43f, 0.8f);
}

TEST_F(FFPixel, ResultArgTemp) {
  // Stage 0 writes T0 to TEMP, CURRENT stays D; stage 1: TEMP*CURRENT = T0*D.
  stage(0, TOP_SELECTARG1, TA_TEXTURE, TA_DIFFUSE);
  state.stageStates[0][TSS_RESULTARG] = TA_TEMP;
  stage(1, TOP_MODULATE, TA_TEMP, TA_CURRENT);
  EXPECT_VEC4(run(), 0.1f, 0.1f, 0.45f, 0.48f);
}

TEST_F(FFPixel, ResultArgTempOnLastStageLeavesCurrent) {
  stage(0, TOP_SELECTARG1, TA_TEXTURE, TA_DIFFUSE);
  state.stageStates[0][TSS_RESULTARG] = TA_TEMP;
  EXPECT_VEC4(run(), 0.2f, 0.4f, 0.6f, 0.8f);  // final color = CURRENT = D
}

TEST_F(FFPixel, SaturationBetweenStages) {
  // Stage 0: 0.75 + 0.75 = 1.5 -> saturated to 1.0; stage 1: 1.0 - 0.5 = 0.5
  // (without the saturation it would be 1.0).
  diffuse = {0.75f, 0.75f, 0.75f, 0.75f};
  samplers[0].color = {0.75f, 0.75f, 0.75f, 0.75f};
  specular = {0.5f, 0.5f, 0.5f, 0.5f};
  stage(0, TOP_ADD, TA_TEXTURE, TA_DIFFUSE);
  stage(1, TOP_SUBTRACT, TA_CURRENT, TA_SPECULAR);
  EXPECT_VEC4(run(), 0.5f, 0.5f, 0.5f, 0.5f);
}

TEST_F(FFPixel, ProjectedStageDividesByW) {
  state.stageStates[0][TSS_TEXTURETRANSFORMFLAGS] = TTFF_COUNT3 | TTFF_PROJECTED;
  coords[0] = {0.4f, 0.8f, 0.0f, 2.0f};
  stage(0, TOP_SELECTARG1, TA_TEXTURE, TA_DIFFUSE);
  run();
  EXPECT_EQ(count(Op::TexProj), 1);
  ASSERT_EQ(samplers[0].calls.size(), 1u);
  EXPECT_NEAR(samplers[0].calls[0].x, 0.2f, kTol);  // 0.4/2
  EXPECT_NEAR(samplers[0].calls[0].y, 0.4f, kTol);  // 0.8/2
}

// ---------------------------------------------------------------- specular and fog
// Fog color (1, 0, 0.4) = 0x00FF0066; final rgb = f*C + (1-f)*FogColor.

TEST_F(FFPixel, SpecularAdd) {
  stage(0, TOP_SELECTARG1, TA_DIFFUSE, TA_DIFFUSE);
  setRs(RS_SPECULARENABLE, 1);
  // D.rgb + S.rgb = (0.3, 0.6, 0.9); alpha stays D.a
  EXPECT_VEC4(run(), 0.3f, 0.6f, 0.9f, 0.8f);
}

TEST_F(FFPixel, SpecularAddSaturates) {
  stage(0, TOP_SELECTARG1, TA_TFACTOR, TA_TFACTOR);
  specular = {0.3f, 0.3f, 0.3f, 0.3f};
  setRs(RS_SPECULARENABLE, 1);
  // F.rgb + 0.3 = (1.1 -> 1, 0.5, 0.7); alpha F.a = 0.4
  EXPECT_VEC4(run(), 1.0f, 0.5f, 0.7f, 0.4f);
}

TEST_F(FFPixel, FogDisabledLeavesColor) {
  stage(0, TOP_SELECTARG1, TA_DIFFUSE, TA_DIFFUSE);
  setRs(RS_FOGCOLOR, 0x00FF0066);
  fog = 0.25f;
  EXPECT_VEC4(run(), 0.2f, 0.4f, 0.6f, 0.8f);
}

TEST_F(FFPixel, FogTableLinear) {
  stage(0, TOP_SELECTARG1, TA_DIFFUSE, TA_DIFFUSE);
  setRs(RS_FOGENABLE, 1);
  setRs(RS_FOGCOLOR, 0x00FF0066);
  setRs(RS_FOGTABLEMODE, FOG_LINEAR);
  setRsFloat(RS_FOGSTART, 0.2f);
  setRsFloat(RS_FOGEND, 0.8f);
  position = {0, 0, 0.5f, 1};
  // f = (end - z)/(end - start) = (0.8-0.5)/0.6 = 0.5
  // rgb = 0.5*(0.2, 0.4, 0.6) + 0.5*(1, 0, 0.4) = (0.6, 0.2, 0.5); alpha unchanged
  EXPECT_VEC4(run(), 0.6f, 0.2f, 0.5f, 0.8f);
}

TEST_F(FFPixel, FogTableLinearClampsFactor) {
  stage(0, TOP_SELECTARG1, TA_DIFFUSE, TA_DIFFUSE);
  setRs(RS_FOGENABLE, 1);
  setRs(RS_FOGCOLOR, 0x00FF0066);
  setRs(RS_FOGTABLEMODE, FOG_LINEAR);
  setRsFloat(RS_FOGSTART, 0.2f);
  setRsFloat(RS_FOGEND, 0.8f);
  position = {0, 0, 0.1f, 1};
  // f = (0.8-0.1)/0.6 = 1.17 -> 1: no fog
  EXPECT_VEC4(run(), 0.2f, 0.4f, 0.6f, 0.8f);
}

TEST_F(FFPixel, FogTableExp) {
  stage(0, TOP_SELECTARG1, TA_DIFFUSE, TA_DIFFUSE);
  setRs(RS_FOGENABLE, 1);
  setRs(RS_FOGCOLOR, 0x00FF0066);
  setRs(RS_FOGTABLEMODE, FOG_EXP);
  setRsFloat(RS_FOGDENSITY, 2.0f);
  position = {0, 0, 0.5f, 1};
  // f = 1/e^(0.5*2) = e^-1 = 0.367879
  // r = 0.367879*0.2 + 0.632121*1 = 0.705697; g = 0.367879*0.4 = 0.147152;
  // b = 0.367879*0.6 + 0.632121*0.4 = 0.473576
  EXPECT_VEC4(run(), 0.705697f, 0.147152f, 0.473576f, 0.8f);
}

TEST_F(FFPixel, FogTableExp2) {
  stage(0, TOP_SELECTARG1, TA_DIFFUSE, TA_DIFFUSE);
  setRs(RS_FOGENABLE, 1);
  setRs(RS_FOGCOLOR, 0x00FF0066);
  setRs(RS_FOGTABLEMODE, FOG_EXP2);
  setRsFloat(RS_FOGDENSITY, 1.0f);
  position = {0, 0, 0.5f, 1};
  // f = 1/e^((0.5*1)^2) = e^-0.25 = 0.778801
  // r = 0.778801*0.2 + 0.221199 = 0.376959; g = 0.778801*0.4 = 0.311520;
  // b = 0.778801*0.6 + 0.221199*0.4 = 0.555761
  EXPECT_VEC4(run(), 0.376959f, 0.311520f, 0.555761f, 0.8f);
}

TEST_F(FFPixel, FogTableUsesEyeWWithPerspectiveProjection) {
  stage(0, TOP_SELECTARG1, TA_DIFFUSE, TA_DIFFUSE);
  setRs(RS_FOGENABLE, 1);
  setRs(RS_FOGCOLOR, 0x00FF0066);
  setRs(RS_FOGTABLEMODE, FOG_LINEAR);
  setRsFloat(RS_FOGSTART, 0.0f);
  setRsFloat(RS_FOGEND, 10.0f);
  state.projection.m[2][3] = 1;
  state.projection.m[3][3] = 0;
  position = {0, 0, 0.9f, 5.0f};
  // W-fog: f = (10 - 5)/10 = 0.5 (with z it would be 0.91): rgb = (0.6, 0.2, 0.5)
  EXPECT_VEC4(run(), 0.6f, 0.2f, 0.5f, 0.8f);
}

TEST_F(FFPixel, FogVertex) {
  stage(0, TOP_SELECTARG1, TA_DIFFUSE, TA_DIFFUSE);
  setRs(RS_FOGENABLE, 1);
  setRs(RS_FOGCOLOR, 0x00FF0066);
  fog = 0.25f;
  // rgb = 0.25*(0.2, 0.4, 0.6) + 0.75*(1, 0, 0.4) = (0.8, 0.1, 0.45)
  EXPECT_VEC4(run(), 0.8f, 0.1f, 0.45f, 0.8f);
}

TEST_F(FFPixel, FogVertexFactorClamped) {
  stage(0, TOP_SELECTARG1, TA_DIFFUSE, TA_DIFFUSE);
  setRs(RS_FOGENABLE, 1);
  setRs(RS_FOGCOLOR, 0x00FF0066);
  fog = 1.5f;  // f clamped to 1: no fog
  EXPECT_VEC4(run(), 0.2f, 0.4f, 0.6f, 0.8f);
}

TEST_F(FFPixel, SpecularThenFog) {
  stage(0, TOP_SELECTARG1, TA_DIFFUSE, TA_DIFFUSE);
  setRs(RS_SPECULARENABLE, 1);
  setRs(RS_FOGENABLE, 1);
  setRs(RS_FOGCOLOR, 0x00FF0066);
  fog = 0.5f;
  // (D + S).rgb = (0.3, 0.6, 0.9); fog 0.5: (0.15+0.5, 0.3, 0.45+0.2)
  EXPECT_VEC4(run(), 0.65f, 0.3f, 0.65f, 0.8f);
}

TEST_F(FFPixel, ShaderPathFogsOutputWithoutSpecular) {
  cfg.shaderPath = true;
  setRs(RS_SPECULARENABLE, 1);
  setRs(RS_FOGENABLE, 1);
  setRs(RS_FOGCOLOR, 0x00FF0066);
  fog = 0.5f;
  presetOutput = {0.4f, 0.2f, 0.8f, 0.3f};  // color written by the pixel shader
  // No specular add; fog 0.5: (0.2+0.5, 0.1, 0.4+0.2), alpha kept
  EXPECT_VEC4(run(), 0.7f, 0.1f, 0.6f, 0.3f);
  EXPECT_EQ(count(Op::Tex), 0);
}

}  // namespace

namespace {

TEST_F(FFPixel, BuildLeavesSpecularAndFogToCaller) {
  stage(0, TOP_SELECTARG1, TA_DIFFUSE, TA_DIFFUSE);
  setRs(RS_SPECULARENABLE, 1);
  setRs(RS_FOGENABLE, 1);
  setRs(RS_FOGCOLOR, 0x00FF0066);
  fog = 0.5f;
  // The stage program alone yields D; appending gives (D + S) fogged (see SpecularThenFog).
  EXPECT_VEC4(execute(buildFixedFunctionPixelProgram(state, cfg)), 0.2f, 0.4f, 0.6f, 0.8f);
}

}  // namespace
