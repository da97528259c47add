// Vertex shader instructions, probed one at a time. Each expected value is worked out
// from reference/instructions.md (formula next to it).
#include <limits>

#include "shader_probe.h"

using namespace probe;

namespace {

constexpr int kPos = kVertexOutPosition, kD0 = kVertexOutDiffuse, kD1 = kVertexOutSpecular, kT0 = kVertexOutTex0,
              kFog = kVertexOutFog, kPSize = kVertexOutPSize;
const float kInf = std::numeric_limits<float>::infinity();

TEST(ShaderVs, BasicArithmeticWithSwizzleAndNegate) {
  auto r = asmRun(R"(vs_1_1
    add oPos, v0, -v1.wzyx
    sub oD0, v0, v1
    mul oD1, v0.x, v1
    mad oT0, v0, v1, c0.yyyy
    min oT1, v0, v1
    max oT2, v0, v1
    slt oT3, v0, v1
    sge oT4, v0, v1
  )");
  r.input(0, {1, 2, 3, 4}).input(1, {4, 2, 1, 0.5f}).constant(0, {0, 10, 0, 0}).execute();
  expectNear(r.output(kPos), {1 - 0.5f, 2 - 1, 3 - 2, 4 - 4});  // v0 - v1.wzyx
  expectNear(r.output(kD0), {-3, 0, 2, 3.5f});                  // v0 - v1
  expectNear(r.output(kD1), {4, 2, 1, 0.5f});                   // v0.x * v1 = 1 * v1
  expectNear(r.output(kT0), {14, 14, 13, 12});                  // v0*v1 + 10
  expectNear(r.output(kT0 + 1), {1, 2, 1, 0.5f});               // min
  expectNear(r.output(kT0 + 2), {4, 2, 3, 4});                  // max
  expectNear(r.output(kT0 + 3), {1, 0, 0, 0});                  // v0 < v1
  expectNear(r.output(kT0 + 4), {0, 1, 1, 1});                  // v0 >= v1
}

TEST(ShaderVs, ScalarOpsReplicateTheFirstSelectedComponent) {
  auto r = asmRun(R"(vs_1_1
    rcp oPos, v0.y
    rsq oD0, v0.w
    exp oD1, v0.z
    log oT0, v1.x
    logp oT1, v1.y
    rcp oT2, v1.w
    rcp oT3, v1.z
    log oT4, v1.w
  )");
  r.input(0, {9, 4, 3, -4}).input(1, {-8, 8, 1, 0}).execute();
  expectNear(r.output(kPos), {0.25f, 0.25f, 0.25f, 0.25f});  // 1/4
  expectNear(r.output(kD0), {0.5f, 0.5f, 0.5f, 0.5f});       // 1/sqrt(|-4|)
  expectNear(r.output(kD1), {8, 8, 8, 8});                   // 2^3
  expectNear(r.output(kT0), {3, 3, 3, 3});                   // log2|-8|
  expectNear(r.output(kT0 + 1), {3, 3, 3, 3});               // logp 8 = 3 (D3D9)
  expectNear(r.output(kT0 + 2), {kInf, kInf, kInf, kInf});   // rcp(0) = +inf
  EXPECT_EQ(r.output(kT0 + 3).x, 1.0f);                      // rcp(1) exactly 1
  expectNear(r.output(kT0 + 4), {-kInf, -kInf, -kInf, -kInf});  // log(0) = -inf
}

TEST(ShaderVs, ExppPerVersion) {
  // vs_1_1: v = 2.5 → (2^floor(v), v - floor(v), 2^v, 1) = (4, 0.5, 5.656854, 1)
  auto a = asmRun("vs_1_1\nexpp oPos, v0.x\n");
  a.input(0, {2.5f, 0, 0, 0}).execute();
  expectNear(a.output(kPos), {4, 0.5f, 5.656854f, 1}, 1e-4f);
  // vs_2_0: scalar 2^v replicated
  auto b = asmRun("vs_2_0\ndcl_position v0\nexpp r0, v0.x\nmov oPos, r0\n");
  b.input(0, {2.5f, 0, 0, 0}).execute();
  expectNear(b.output(kPos), {5.656854f, 5.656854f, 5.656854f, 5.656854f}, 1e-4f);
}

TEST(ShaderVs, FrcIsFloorBased) {
  auto r = asmRun("vs_1_1\nmov oPos, c1\nfrc oPos.xy, v0\n");
  r.input(0, {-0.25f, 2.75f, 0, 0}).constant(1, {7, 7, 7, 7}).execute();
  // frc(-0.25) = 0.75, frc(2.75) = 0.75, z/w untouched
  expectNear(r.output(kPos), {0.75f, 0.75f, 7, 7});
}

TEST(ShaderVs, LitAllBranches) {
  auto r = asmRun(R"(vs_1_1
    lit oPos, v0
    lit oD0, v1
    lit oD1, v2
    lit oT0, v3
  )");
  r.input(0, {0.5f, 0.8f, 0, 2});   // (1, 0.5, 0.8^2 = 0.64, 1)
  r.input(1, {-0.2f, 0.8f, 0, 2});  // x <= 0: (1, 0, 0, 1)
  r.input(2, {0.3f, -0.5f, 0, 2});  // y <= 0: (1, 0.3, 0, 1)
  r.input(3, {1, 0.99f, 0, 200});   // power clamped to 127.9961: 0.99^127.9961 = 0.276
  r.execute();
  expectNear(r.output(kPos), {1, 0.5f, 0.64f, 1});
  expectNear(r.output(kD0), {1, 0, 0, 1});
  expectNear(r.output(kD1), {1, 0.3f, 0, 1});
  expectNear(r.output(kT0), {1, 1, std::pow(0.99f, 127.9961f), 1}, 1e-4f);
}

TEST(ShaderVs, DstBuildsTheAttenuationVector) {
  auto r = asmRun("vs_1_1\ndst oPos, v0, v1\n");
  // s0 = (?, d², d², ?) with d = 4, s1 = (?, 1/d, ?, 1/d): (1, d, d², 1/d)
  r.input(0, {9, 16, 16, 9}).input(1, {9, 0.25f, 9, 0.25f}).execute();
  expectNear(r.output(kPos), {1, 4, 16, 0.25f});
}

TEST(ShaderVs, DotProductsAndMatrixMacros) {
  auto r = asmRun(R"(vs_1_1
    dp3 oPos, v0, v1
    dp4 oD0, v0, v1
    m3x2 r0.xy, v0, c0
    m4x3 r1.xyz, v0, c0
    m3x4 r2, v0, c0
    mov oT0, r0
    mov oT1, r1
    mov oT2, r2
  )");
  r.input(0, {1, 2, 3, 4}).input(1, {1, 1, 1, 1});
  r.constant(0, {1, 0, 0, 1}).constant(1, {0, 1, 0, 1}).constant(2, {0, 0, 1, 1}).constant(3, {1, 1, 1, 1});
  r.execute();
  expectNear(r.output(kPos), {6, 6, 6, 6});     // 1+2+3
  expectNear(r.output(kD0), {10, 10, 10, 10});  // 1+2+3+4
  // m3x2: (dp3(v0,c0), dp3(v0,c1)) = (1, 2)
  EXPECT_FLOAT_EQ(r.output(kT0).x, 1);
  EXPECT_FLOAT_EQ(r.output(kT0).y, 2);
  // m4x3: dp4 with c0..c2 = (1+4, 2+4, 3+4)
  expectNear(r.output(kT0 + 1), {5, 6, 7, 0});
  // m3x4: dp3 with c0..c3 = (1, 2, 3, 6)
  expectNear(r.output(kT0 + 2), {1, 2, 3, 6});
}

TEST(ShaderVs, AddressRegisterFloorsInVs11AndRoundsWithMova) {
  // vs_1_1 mov a0.x, -0.5 → floor = -1, so c[a0.x + 3] = c2
  auto a = asmRun("vs_1_1\nmov a0.x, v0.x\nmov oPos, c[a0.x + 3]\n");
  a.input(0, {-0.5f, 0, 0, 0}).constant(2, {2, 2, 2, 2}).constant(3, {3, 3, 3, 3}).execute();
  expectNear(a.output(kPos), {2, 2, 2, 2});
  // vs_2_0 mova a0.x, 1.6 → round = 2: c[a0.x + 1] = c3; 1.4 → 1: c2
  auto b = asmRun("vs_2_0\ndcl_position v0\nmova a0.xy, v0\nmov oPos, c[a0.x + 1]\nmov oD0, c[a0.y + 1]\n");
  b.input(0, {1.6f, 1.4f, 0, 0}).constant(2, {2, 2, 2, 2}).constant(3, {3, 3, 3, 3}).execute();
  expectNear(b.output(kPos), {3, 3, 3, 3});
  expectNear(b.output(kD0), {2, 2, 2, 2});
}

TEST(ShaderVs, RelativeReadsPerLaneAndOutOfRange) {
  auto r = asmRun("vs_1_1\ndef c5, 5, 5, 5, 5\nmov a0.x, v0.x\nmov oPos, c[a0.x + 1]\n");
  r.constant(1, {1, 1, 1, 1}).constant(2, {2, 2, 2, 2});
  r.setInput(0, 0, {0, 0, 0, 0});     // c1
  r.setInput(0, 1, {1, 0, 0, 0});     // c2
  r.setInput(0, 2, {4, 0, 0, 0});     // c5: the local def wins in relative reads too
  r.setInput(0, 3, {1000, 0, 0, 0});  // out of range → 0
  r.setInput(0, 4, {-5, 0, 0, 0});    // negative → 0
  r.execute();
  expectNear(r.output(kPos, 0), {1, 1, 1, 1});
  expectNear(r.output(kPos, 1), {2, 2, 2, 2});
  expectNear(r.output(kPos, 2), {5, 5, 5, 5});
  expectNear(r.output(kPos, 3), {0, 0, 0, 0});
  expectNear(r.output(kPos, 4), {0, 0, 0, 0});
  EXPECT_EQ(r.lowered.floatConstantsRead, 256);  // relative: the whole file
}

TEST(ShaderVs, Sm2Arithmetic) {
  auto r = asmRun(R"(vs_2_x
    dcl_position v0
    dcl_normal v1
    sgn r0, v0, r1, r2
    mov oPos, r0
    crs r3.xyz, v1, v2
    mov r3.w, c0.w
    mov oD0, r3
    nrm r4, v3
    mov oD1, r4
    pow r5, v4.x, v4.y
    mov oT0, r5
    abs oT1, v0
    lrp oT2, v5, v1, v2
    nrm r6, c1
    mov oT3, r6
    pow r7, c1.x, c1.x
    mov oT4, r7
  )");
  r.input(0, {-3, 0, 2, -0.0f}).input(1, {1, 0, 0, 0}).input(2, {0, 1, 0, 0}).input(3, {3, 4, 0, 2});
  r.input(4, {-2, 3, 0, 0}).input(5, {0.25f, 0.25f, 0.25f, 0.25f}).constant(0, {0, 0, 0, 9});
  r.constant(1, {0, 0, 0, 1});
  r.execute();
  expectNear(r.output(kPos), {-1, 0, 1, 0});               // sgn
  expectNear(r.output(kD0), {0, 0, 1, 9});                 // x × y = z; w from c0
  expectNear(r.output(kD1), {0.6f, 0.8f, 0, 0.4f});        // (3,4,0,2)/5, w scaled too
  expectNear(r.output(kT0), {8, 8, 8, 8});                 // |-2|^3
  expectNear(r.output(kT0 + 1), {3, 0, 2, 0});             // abs
  expectNear(r.output(kT0 + 2), {0.25f, 0.75f, 0, 0});     // v2 + 0.25 (v1 - v2)
  expectNear(r.output(kT0 + 3), {0, 0, 0, 1});             // nrm of a zero vector: (0,0,0,w)
  expectNear(r.output(kT0 + 4), {1, 1, 1, 1});             // pow(0, 0) = 1
}

TEST(ShaderVs, SinCosSm2AndSm3) {
  // SM2 carries the two constant operands; the result is the same.
  auto a = asmRun(R"(vs_2_0
    dcl_position v0
    def c0, -1.5500992e-006, -2.1701389e-005, 0.0026041667, 0.00026041668
    def c1, -0.020833334, -0.12500000, 1.0, 0.50000000
    mov r0, c2
    sincos r0.xy, v0.x, c0, c1
    mov oPos, r0
  )");
  a.input(0, {1.0f, 0, 0, 0}).constant(2, {5, 5, 5, 5}).execute();
  // (cos 1, sin 1, z, w untouched)
  expectNear(a.output(kPos), {std::cos(1.0f), std::sin(1.0f), 5, 5}, 1e-5f);
  auto b = asmRun("vs_3_0\ndcl_position v0\ndcl_position o0\nmov r0, c2\nsincos r0.y, v0.x\nmov o0, r0\n");
  b.input(0, {0.5f, 0, 0, 0}).constant(2, {5, 5, 5, 5}).execute();
  // .y only: sin(0.5); x untouched in SM3
  expectNear(b.output(kPos), {5, std::sin(0.5f), 5, 5}, 1e-5f);
}

TEST(ShaderVs, ScalarOutputsAndVertexInputs) {
  auto r = asmRun(R"(vs_2_0
    dcl_position v0
    dcl_texcoord1 v3
    mov oFog, v0.w
    mov oPts, v0.z
    mov oPos, v0
  )");
  r.input(0, {1, 2, 3, 4}).execute();
  EXPECT_FLOAT_EQ(r.output(kFog).x, 4);    // oFog = v0.w (scalar: .x)
  EXPECT_FLOAT_EQ(r.output(kPSize).x, 3);  // oPts = v0.z
  ASSERT_EQ(r.lowered.vertexInputs.size(), 2u);
  EXPECT_EQ(r.lowered.vertexInputs[1].reg, 3);
  EXPECT_EQ(r.lowered.vertexInputs[1].usage, sh::DeclUsage::TexCoord);
  EXPECT_EQ(r.lowered.vertexInputs[1].usageIndex, 1);
}

TEST(ShaderVs, Vs11WithoutDclLeavesInputBindingsEmpty) {
  auto r = asmRun("vs.1.1\nmov oPos, v0\n");
  EXPECT_TRUE(r.lowered.vertexInputs.empty());
}

TEST(ShaderVs, Vs30OutputsMappedBySemantic) {
  // o3.xy = texcoord0, o3.zw = texcoord1 (component positions kept), o1 = fog
  auto r = asmRun(R"(vs_3_0
    dcl_position v0
    dcl_position o0
    dcl_fog o1.x
    dcl_color0 o2
    dcl_texcoord0 o3.xy
    dcl_texcoord1 o3.zw
    mov o0, v0
    mov o1.x, v0.y
    mov o2, c0
    mov o3, v0.wzyx
  )");
  r.input(0, {1, 2, 3, 4}).constant(0, {0.5f, 0.5f, 0.5f, 1}).execute();
  expectNear(r.output(kPos), {1, 2, 3, 4});
  EXPECT_FLOAT_EQ(r.output(kFog).x, 2);
  expectNear(r.output(kD0), {0.5f, 0.5f, 0.5f, 1});
  EXPECT_FLOAT_EQ(r.output(kT0).x, 4);
  EXPECT_FLOAT_EQ(r.output(kT0).y, 3);
  EXPECT_FLOAT_EQ(r.output(kT0 + 1).z, 2);
  EXPECT_FLOAT_EQ(r.output(kT0 + 1).w, 1);
}

TEST(ShaderVs, Vs30TexldlSamplesWithExplicitLod) {
  auto r = asmRun(R"(vs_3_0
    dcl_position v0
    dcl_position o0
    dcl_2d s1
    texldl r0, v0, s1
    mov o0, r0
  )");
  r.fakes[1].offset = 100;
  r.input(0, {0.25f, 0.5f, 0, 2}).execute();
  // fake sampler: coords + 100; LOD mode
  expectNear(r.output(kPos), {100.25f, 100.5f, 100, 102});
  EXPECT_EQ(r.fakes[1].lastMode, SampleMode::Lod);
  EXPECT_EQ(r.lowered.samplersUsed, 0x2u);
  EXPECT_EQ(r.lowered.samplerTypes[1], sh::TextureType::Tex2D);
}

}  // namespace
