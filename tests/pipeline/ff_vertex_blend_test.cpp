// Vertex blending in the fixed-function vertex program, run through the interpreter
// with a different vertex in each lane, against values worked out by hand:
// P = Σ w_i * p * World_i * View, N = Σ w_i * n * inverse transpose(World_i * View).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "ff_vertex_program.h"
#include "pipeline/ff_vertex.h"
#include "refx/exec/interpreter.h"

using namespace refx;
using namespace refx::exec;
using namespace refx::pipeline;
using namespace refx::d3d;

namespace {

constexpr float kTol = 1e-4f;

struct BlendVertex {
  Vec4 pos{0, 0, 0, 1};
  Vec4 normal{0, 0, -1, 1};
  Vec4 weights{0, 0, 0, 1};
  Vec4 indices{0, 0, 0, 1};
  Vec4 pos1{0, 0, 0, 1};
  Vec4 normal1{0, 0, -1, 1};
};

using refx::test::BuiltProgram;
using refx::test::build;

// Outputs of each vertex; vertex i runs in lane 3*i + 1 of a batch whose other lanes
// hold an unrelated vertex.
std::vector<std::array<Vec4, kVertexOutputCount>> run(const BuiltProgram& built,
                                                        const std::vector<BlendVertex>& verts) {
  const Program& p = built.program;
  BatchRegisters regs;
  regs.resize(p);
  auto put = [&](int lane, const BlendVertex& v) {
    auto set = [&](int r, Vec4 x) {
      for (int c = 0; c < 4; ++c) regs.inputs[r].c[c][lane] = x[c];
    };
    set(kVertexInPosition, v.pos);
    set(kVertexInNormal, v.normal);
    set(kVertexInBlendWeight, v.weights);
    set(kVertexInBlendIndices, v.indices);
    set(kVertexInPosition1, v.pos1);
    set(kVertexInNormal1, v.normal1);
    set(kVertexInDiffuse, {1, 1, 1, 1});
    set(kVertexInSpecular, {0, 0, 0, 0});
  };
  BlendVertex noise{{9, -4, 7, 1}, {0.6f, 0.8f, 0, 1}, {0.3f, 0.3f, 0.3f, 1}, {40, 41, 42, 43},
                    {-3, 2, 5, 1}, {1, 0, 0, 1}};
  for (int l = 0; l < kBatchLanes; ++l) put(l, noise);
  for (size_t i = 0; i < verts.size(); ++i) put(int(3 * i + 1), verts[i]);
  ExecContext ctx;
  ctx.constants = built.constants.data();
  ctx.constantCount = int(built.constants.size());
  execute(p, ctx, regs);
  std::vector<std::array<Vec4, kVertexOutputCount>> out(verts.size());
  for (size_t i = 0; i < verts.size(); ++i)
    for (int r = 0; r < kVertexOutputCount; ++r)
      for (int c = 0; c < 4; ++c) out[i][r][c] = regs.outputs[r].c[c][3 * i + 1];
  return out;
}

#define EXPECT_VEC4(actual, ex, ey, ez, ew)    \
  do {                                         \
    Vec4 a_ = (actual);                        \
    EXPECT_NEAR(a_.x, (ex), kTol) << "x";      \
    EXPECT_NEAR(a_.y, (ey), kTol) << "y";      \
    EXPECT_NEAR(a_.z, (ez), kTol) << "z";      \
    EXPECT_NEAR(a_.w, (ew), kTol) << "w";      \
  } while (0)

Matrix translation(float x, float y, float z) {
  Matrix m = Matrix::identity();
  m.m[3][0] = x, m.m[3][1] = y, m.m[3][2] = z;
  return m;
}
Matrix scaling(float x, float y, float z) {
  Matrix m = Matrix::identity();
  m.m[0][0] = x, m.m[1][1] = y, m.m[2][2] = z;
  return m;
}

// Unlit; stage 0 generates CAMERASPACEPOSITION, stage 1 CAMERASPACENORMAL (camera-space
// values copied to the texture coordinates, so the blended P and N can be read).
DeviceState texgenState(uint32_t vertexBlend) {
  DeviceState s;
  s.renderStates[RS_LIGHTING] = 0;
  s.renderStates[RS_VERTEXBLEND] = vertexBlend;
  s.stageStates[0][TSS_TEXCOORDINDEX] = TCI_CAMERASPACEPOSITION;
  s.stageStates[1][TSS_TEXCOORDINDEX] = TCI_CAMERASPACENORMAL | 1;
  return s;
}

FixedFunctionVertexConfig blendConfig(int weights, int indicesType = -1) {
  FixedFunctionVertexConfig c;
  c.hasNormal = true;
  c.blendWeightCount = weights;
  c.blendIndicesType = indicesType;
  return c;
}

TEST(FixedFunctionVertexBlend, TwoWeightsPerVertexWithView) {
  // World0 = translate(1, 0, 0), World1 = scale(2, 2, 2), World2 = translate(0, 0, 3);
  // View = translate(0, 0, 1). p = (1, 1, 1):
  //   p*W0*V = (2, 1, 2), p*W1*V = (2, 2, 3), p*W2*V = (1, 1, 5).
  // Vertex A, weights (0.5, 0.25) -> w2 = 0.25: (1 + 0.5 + 0.25, 0.5 + 0.5 + 0.25,
  //   1 + 0.75 + 1.25) = (1.75, 1.25, 3).
  // Vertex B, weights (0, 1) -> w2 = 0: (2, 2, 3).
  // Vertex C, weights (0.25, 0.25) -> w2 = 0.5: (0.5 + 0.5 + 0.5, 0.25 + 0.5 + 0.5,
  //   0.5 + 0.75 + 2.5) = (1.5, 1.25, 3.75).
  // Normals n = (0, 0, -1): translations keep it, the scale's inverse transpose halves it:
  //   A: 0.5*(0,0,-1) + 0.25*(0,0,-0.5) + 0.25*(0,0,-1) = (0, 0, -0.875)
  //   B: (0, 0, -0.5);  C: (0, 0, -0.25 - 0.125 - 0.5) = (0, 0, -0.875)
  DeviceState s = texgenState(VBF_2WEIGHTS);
  s.world = translation(1, 0, 0);
  s.worldMatrix(1) = scaling(2, 2, 2);
  s.worldMatrix(2) = translation(0, 0, 3);
  s.view = translation(0, 0, 1);
  s.projection = scaling(1, 1, 0.5f);
  BlendVertex a, b, c;
  a.pos = b.pos = c.pos = {1, 1, 1, 1};
  a.weights = {0.5f, 0.25f, 0, 1};
  b.weights = {0, 1, 0, 1};
  c.weights = {0.25f, 0.25f, 0, 1};
  auto r = run(build(s, blendConfig(2)), {a, b, c});
  EXPECT_VEC4(r[0][kVertexOutTex0], 1.75f, 1.25f, 3, 0);
  EXPECT_VEC4(r[1][kVertexOutTex0], 2, 2, 3, 0);
  EXPECT_VEC4(r[2][kVertexOutTex0], 1.5f, 1.25f, 3.75f, 0);
  EXPECT_VEC4(r[0][kVertexOutTex0 + 1], 0, 0, -0.875f, 0);
  EXPECT_VEC4(r[1][kVertexOutTex0 + 1], 0, 0, -0.5f, 0);
  EXPECT_VEC4(r[2][kVertexOutTex0 + 1], 0, 0, -0.875f, 0);
  // Clip position = blended camera position * Projection (z halved, w = 1).
  EXPECT_VEC4(r[0][kVertexOutPosition], 1.75f, 1.25f, 1.5f, 1);
  EXPECT_VEC4(r[2][kVertexOutPosition], 1.5f, 1.25f, 1.875f, 1);
}

TEST(FixedFunctionVertexBlend, IndexedUbyte4AndD3DColorPerVertex) {
  // D3DVBF_1WEIGHTS indexed: World(index0) * w0 + World(index1) * (1 - w0).
  // World(k) = translate(k, 0, 0) for the indices used; p = (0, 0, 0); View identity.
  //   A: UBYTE4 indices (4, 250), w0 = 0.25: x = 0.25*4 + 0.75*250 = 188.5
  //   B: UBYTE4 indices (17, 0), w0 = 1: x = 17
  // D3DCOLOR indices arrive as byte/255 in (r, g, b, a) order: (4/255, 250/255) reads
  // indices 4 and 250 just the same.
  DeviceState s = texgenState(VBF_1WEIGHTS);
  s.renderStates[RS_INDEXEDVERTEXBLENDENABLE] = 1;
  for (int k : {0, 4, 17, 250}) s.worldMatrix(k) = translation(float(k), 0, 0);
  BlendVertex a, b;
  a.weights = {0.25f, 0, 0, 1};
  a.indices = {4, 250, 0, 0};
  b.weights = {1, 0, 0, 1};
  b.indices = {17, 0, 0, 0};
  auto r = run(build(s, blendConfig(1, DECLTYPE_UBYTE4)), {a, b});
  EXPECT_VEC4(r[0][kVertexOutTex0], 188.5f, 0, 0, 0);
  EXPECT_VEC4(r[1][kVertexOutTex0], 17, 0, 0, 0);
  a.indices = {4 / 255.0f, 250 / 255.0f, 0, 1};
  b.indices = {17 / 255.0f, 0, 0, 1};
  r = run(build(s, blendConfig(1, DECLTYPE_D3DCOLOR)), {a, b});
  EXPECT_VEC4(r[0][kVertexOutTex0], 188.5f, 0, 0, 0);
  EXPECT_VEC4(r[1][kVertexOutTex0], 17, 0, 0, 0);
}

TEST(FixedFunctionVertexBlend, IndexedNormalsUseEachMatrixInverseTranspose) {
  // D3DVBF_3WEIGHTS indexed, indices (3, 5, 7, 9), weights (0.5, 0.25, 0.125) and 0.125.
  // World3 = scale(2, 1, 1), World5 = scale(1, 4, 1), World7 = World9 = identity.
  // n = (1, 1, 0): inverse transposes give (0.5, 1, 0), (1, 0.25, 0), (1, 1, 0), (1, 1, 0):
  // N = 0.5*(0.5, 1) + 0.25*(1, 0.25) + 0.25*(1, 1) = (0.75, 0.8125, 0).
  // With NORMALIZENORMALS: |N| = sqrt(0.5625 + 0.66015625) = 1.105695...
  DeviceState s = texgenState(VBF_3WEIGHTS);
  s.renderStates[RS_INDEXEDVERTEXBLENDENABLE] = 1;
  s.worldMatrix(3) = scaling(2, 1, 1);
  s.worldMatrix(5) = scaling(1, 4, 1);
  s.world = translation(100, 0, 0);  // matrix 0: not indexed here
  BlendVertex v;
  v.normal = {1, 1, 0, 1};
  v.weights = {0.5f, 0.25f, 0.125f, 1};
  v.indices = {3, 5, 7, 9};
  auto r = run(build(s, blendConfig(3, DECLTYPE_UBYTE4)), {v});
  EXPECT_VEC4(r[0][kVertexOutTex0 + 1], 0.75f, 0.8125f, 0, 0);
  s.renderStates[RS_NORMALIZENORMALS] = 1;
  r = run(build(s, blendConfig(3, DECLTYPE_UBYTE4)), {v});
  const float len = std::sqrt(0.75f * 0.75f + 0.8125f * 0.8125f);
  EXPECT_VEC4(r[0][kVertexOutTex0 + 1], 0.75f / len, 0.8125f / len, 0, 0);
}

TEST(FixedFunctionVertexBlend, ZeroWeightsIndexedUsesIndexZero) {
  // D3DVBF_0WEIGHTS: one matrix of weight 1, World(index0) when indexed, World(0) when
  // not. World(6) = translate(0, 6, 0), World(0) = translate(0, 0, 2); p = (1, 0, 0).
  DeviceState s = texgenState(VBF_0WEIGHTS);
  s.world = translation(0, 0, 2);
  s.worldMatrix(6) = translation(0, 6, 0);
  BlendVertex v;
  v.pos = {1, 0, 0, 1};
  v.indices = {6, 0, 0, 0};
  auto r = run(build(s, blendConfig(0, DECLTYPE_UBYTE4)), {v});
  EXPECT_VEC4(r[0][kVertexOutTex0], 1, 0, 2, 0);
  s.renderStates[RS_INDEXEDVERTEXBLENDENABLE] = 1;
  r = run(build(s, blendConfig(0, DECLTYPE_UBYTE4)), {v});
  EXPECT_VEC4(r[0][kVertexOutTex0], 1, 6, 0, 0);
}

TEST(FixedFunctionVertexBlend, TweeningBlendsPositionAndNormal) {
  // POSITION = POSITION0*(1 - t) + POSITION1*t, t = 0.25, then World0 * View:
  // p0 = (0, 0, 0), p1 = (4, 8, 0) -> (1, 2, 0); World0 = translate(0, 0, 1) -> (1, 2, 1).
  // Normals (0, 0, -1) and (0, -1, 0): (0, -0.25, -0.75).
  DeviceState s = texgenState(VBF_TWEENING);
  s.renderStates[RS_TWEENFACTOR] = floatBits(0.25f);
  s.world = translation(0, 0, 1);
  BlendVertex v;
  v.pos1 = {4, 8, 0, 1};
  v.normal1 = {0, -1, 0, 1};
  FixedFunctionVertexConfig c = blendConfig(0);
  c.hasPosition1 = c.hasNormal1 = true;
  auto r = run(build(s, c), {v});
  EXPECT_VEC4(r[0][kVertexOutTex0], 1, 2, 1, 0);
  EXPECT_VEC4(r[0][kVertexOutTex0 + 1], 0, -0.25f, -0.75f, 0);
  // Without POSITION1/NORMAL1 in the declaration there is nothing to tween toward.
  auto r0 = run(build(s, blendConfig(0)), {v});
  EXPECT_VEC4(r0[0][kVertexOutTex0], 0, 0, 1, 0);
  EXPECT_VEC4(r0[0][kVertexOutTex0 + 1], 0, 0, -1, 0);
}

TEST(FixedFunctionVertexBlend, PointLightAndSpecularUseBlendedPosition) {
  // D3DVBF_1WEIGHTS, w0 = 0.5: World0 = translate(0, 0, 2), World1 = translate(0, 0, 4):
  // p = (0, 0, 0) -> P = (0, 0, 3), n = (0, 0, -1) (translations keep it).
  // Point light at (0, 0, 1), range 10, attenuation 1/(0 + 0.5 d): d = 2 -> atten = 1.
  // Ldir = (0, 0, -1), N.L = 1: diffuse = 1. Local viewer: V = normalize(-P) = (0, 0, -1),
  // H = normalize(V + L) = (0, 0, -1), N.H = 1: specular = 1^Power = 1.
  DeviceState s;
  s.renderStates[RS_VERTEXBLEND] = VBF_1WEIGHTS;
  s.renderStates[RS_SPECULARENABLE] = 1;
  s.world = translation(0, 0, 2);
  s.worldMatrix(1) = translation(0, 0, 4);
  s.material.diffuse = {0.25f, 0.25f, 0.25f, 1};
  s.material.specular = {0.25f, 0.25f, 0.25f, 1};
  s.material.power = 4;
  Light l;
  l.type = LIGHT_POINT;
  l.position = {0, 0, 1};
  l.range = 10;
  l.attenuation1 = 0.5f;
  l.diffuse = {1, 1, 1, 1};
  l.specular = {1, 1, 1, 1};
  s.lights[0] = l;
  s.lightEnabled[0] = true;
  s.renderStates[RS_DIFFUSEMATERIALSOURCE] = MCS_MATERIAL;
  s.renderStates[RS_SPECULARMATERIALSOURCE] = MCS_MATERIAL;
  BlendVertex v;
  v.weights = {0.5f, 0, 0, 1};
  auto r = run(build(s, blendConfig(1)), {v});
  // diffuse = Md * atten * N.L = 0.25; specular = Ms * atten = 0.25
  // (the unblended distance 1 would give atten 2: 0.5 and 0.5).
  EXPECT_NEAR(r[0][kVertexOutDiffuse].x, 0.25f, kTol);
  EXPECT_NEAR(r[0][kVertexOutSpecular].x, 0.25f, kTol);
}

}  // namespace
