// Fixed-function vertex programs run through the interpreter and compared with
// values worked out by hand from the D3D9 transform / lighting / fog formulas.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "ff_vertex_program.h"
#include "pipeline/ff_vertex.h"
#include "refx/exec/interpreter.h"

using namespace refx;
using namespace refx::exec;
using namespace refx::pipeline;
using namespace refx::d3d;

namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr float kTol = 1e-4f;

struct Vertex {
  Vec4 pos{0, 0, 0, 1};
  Vec4 normal{0, 0, 0, 1};
  Vec4 diffuse{1, 1, 1, 1};
  Vec4 specular{0, 0, 0, 0};
  float psize = 0;
  std::array<Vec4, 8> tex{};
};

struct Result {
  std::array<Vec4, kVertexOutputCount> o;
  Vec4 pos() const { return o[kVertexOutPosition]; }
  Vec4 diffuse() const { return o[kVertexOutDiffuse]; }
  Vec4 specular() const { return o[kVertexOutSpecular]; }
  Vec4 tex(int stage) const { return o[kVertexOutTex0 + stage]; }
  float fog() const { return o[kVertexOutFog].x; }
  float psize() const { return o[kVertexOutPSize].x; }
};

// Vertex i goes to lane kLanes[i]; the other lanes hold an unrelated vertex, so a
// program that mixes lanes shows up as a wrong value.
constexpr int kLanes[] = {5, 0, 15, 9, 2, 12, 7, 3};

using refx::test::BuiltProgram;
using refx::test::build;

std::vector<Result> run(const BuiltProgram& built, const std::vector<Vertex>& verts) {
  const Program& p = built.program;
  EXPECT_EQ(p.inputCount, kVertexInputCount);
  EXPECT_EQ(p.outputCount, kVertexOutputCount);
  BatchRegisters regs;
  regs.resize(p);
  Vertex noise;
  noise.pos = {-7, 3, 11, 1};
  noise.normal = {0.3f, -0.9f, 0.2f, 1};
  noise.diffuse = {0.2f, 0.9f, 0.1f, 0.4f};
  noise.specular = {0.7f, 0.1f, 0.5f, 0.9f};
  noise.psize = 9;
  for (auto& t : noise.tex) t = {0.9f, -0.4f, 3, 5};
  auto put = [&](int lane, const Vertex& v) {
    auto set = [&](int r, Vec4 x) {
      for (int c = 0; c < 4; ++c) regs.inputs[r].c[c][lane] = x[c];
    };
    set(kVertexInPosition, v.pos);
    set(kVertexInNormal, v.normal);
    set(kVertexInDiffuse, v.diffuse);
    set(kVertexInSpecular, v.specular);
    set(kVertexInPSize, {v.psize, 0, 0, 1});
    for (int t = 0; t < 8; ++t) set(kVertexInTex0 + t, v.tex[t]);
  };
  for (int l = 0; l < kBatchLanes; ++l) put(l, noise);
  for (size_t i = 0; i < verts.size(); ++i) put(kLanes[i], verts[i]);
  ExecContext ctx;
  ctx.constants = built.constants.data();
  ctx.constantCount = int(built.constants.size());
  execute(p, ctx, regs);
  std::vector<Result> out(verts.size());
  for (size_t i = 0; i < verts.size(); ++i)
    for (int r = 0; r < kVertexOutputCount; ++r)
      for (int c = 0; c < 4; ++c) out[i].o[r][c] = regs.outputs[r].c[c][kLanes[i]];
  return out;
}

Vertex at(Vec3 p, Vec3 n = {0, 0, -1}) {
  Vertex v;
  v.pos = Vec4(p, 1);
  v.normal = Vec4(n, 1);
  return v;
}

#define EXPECT_VEC4(actual, ex, ey, ez, ew, tol)  \
  do {                                            \
    Vec4 a_ = (actual);                           \
    EXPECT_NEAR(a_.x, (ex), (tol)) << "x";        \
    EXPECT_NEAR(a_.y, (ey), (tol)) << "y";        \
    EXPECT_NEAR(a_.z, (ez), (tol)) << "z";        \
    EXPECT_NEAR(a_.w, (ew), (tol)) << "w";        \
  } while (0)
#define EXPECT_RGB(actual, er, eg, eb, tol) \
  do {                                      \
    Vec4 a_ = (actual);                     \
    EXPECT_NEAR(a_.x, (er), (tol)) << "r";  \
    EXPECT_NEAR(a_.y, (eg), (tol)) << "g";  \
    EXPECT_NEAR(a_.z, (eb), (tol)) << "b";  \
  } while (0)

// A lit state with no lights, white material diffuse and nothing else.
DeviceState litState() {
  DeviceState s;
  s.material.diffuse = {1, 1, 1, 1};
  return s;
}

FixedFunctionVertexConfig withNormal() {
  FixedFunctionVertexConfig c;
  c.hasNormal = true;
  return c;
}

Light directional(Vec3 dir, Color4 diffuse = {1, 1, 1, 0}) {
  Light l;
  l.type = LIGHT_DIRECTIONAL;
  l.direction = dir;
  l.diffuse = diffuse;
  return l;
}

Light point(Vec3 pos, float a0, float a1, float a2, float range) {
  Light l;
  l.type = LIGHT_POINT;
  l.position = pos;
  l.attenuation0 = a0;
  l.attenuation1 = a1;
  l.attenuation2 = a2;
  l.range = range;
  return l;
}

void setFloat(DeviceState& s, RenderState rs, float v) { s.renderStates[rs] = floatBits(v); }

TEST(FFVertex, WorldViewProjectionTransform) {
  DeviceState s;
  s.world = matrixTranslation(1, 2, 3);
  s.view = matrixScaling(2, 2, 2);
  // fovy 90°, aspect 1, zn 1, zf 101: xs = ys = 1, _33 = 101/100 = 1.01, _34 = 1, _43 = -1.01
  s.projection = matrixPerspectiveFovLH(kPi / 2, 1, 1, 101);
  s.renderStates[RS_LIGHTING] = 0;
  auto r = run(build(s, {}), {at({0, 0, 0}), at({1, -1, 2})});
  // (0,0,0) -> world (1,2,3) -> view (2,4,6) -> clip (2, 4, 6*1.01 - 1.01, 6)
  EXPECT_VEC4(r[0].pos(), 2, 4, 5.05f, 6, kTol);
  // (1,-1,2) -> world (2,1,5) -> view (4,2,10) -> clip (4, 2, 10*1.01 - 1.01, 10)
  EXPECT_VEC4(r[1].pos(), 4, 2, 9.09f, 10, kTol);
}

TEST(FFVertex, DirectionalDiffuseIsNdotLTimesMaterial) {
  DeviceState s = litState();
  s.material.diffuse = {0.8f, 0.6f, 0.4f, 0.5f};
  // Ldir = -Direction = (sin 60°, 0, -cos 60°); with N = (0,0,-1): N·L = cos 60° = 0.5
  s.lights[0] = directional({-std::sin(kPi / 3), 0, 0.5f});
  s.lightEnabled[0] = true;
  auto r = run(build(s, withNormal()),
               {at({0, 0, 5}, {0, 0, -1}), at({1, 1, 5}, {0, 0, 1}), at({0, 0, 5}, {1, 0, 0})});
  // 0.5 * (0.8, 0.6, 0.4); alpha = material diffuse alpha
  EXPECT_VEC4(r[0].diffuse(), 0.4f, 0.3f, 0.2f, 0.5f, kTol);
  // facing away: N·L = -0.5 -> max(.,0) = 0
  EXPECT_VEC4(r[1].diffuse(), 0, 0, 0, 0.5f, kTol);
  // N = (1,0,0): N·L = sin 60° = 0.8660
  const float c = std::sin(kPi / 3);
  EXPECT_VEC4(r[2].diffuse(), 0.8f * c, 0.6f * c, 0.4f * c, 0.5f, kTol);
  // Specular is 0 without SPECULARENABLE.
  EXPECT_RGB(r[0].specular(), 0, 0, 0, kTol);
}

TEST(FFVertex, LightAndNormalGoToCameraSpace) {
  // The same world-space configuration seen through a rotated camera lights the same.
  DeviceState s = litState();
  s.lights[0] = directional({-std::sin(kPi / 3), 0, 0.5f});
  s.lightEnabled[0] = true;
  s.view = matrixRotationY(1.1f) * matrixTranslation(0.5f, -2, 7);
  s.world = matrixRotationX(0.0f);
  auto r = run(build(s, withNormal()), {at({0, 0, 5}, {0, 0, -1})});
  // N·L = cos 60° = 0.5 regardless of the view
  EXPECT_RGB(r[0].diffuse(), 0.5f, 0.5f, 0.5f, kTol);
}

TEST(FFVertex, PointLightAttenuationAndRange) {
  DeviceState s = litState();
  s.lights[0] = point({0, 0, 0}, 1, 0.5f, 0, 3);
  s.lights[0].diffuse = {1, 1, 1, 0};
  s.lightEnabled[0] = true;
  // Light at the origin, vertices on +z facing it: Ldir = (0,0,-1), N·L = 1.
  auto r = run(build(s, withNormal()),
               {at({0, 0, 2}), at({0, 0, 1}), at({0, 0, 4}), at({0, 0, 3})});
  // d = 2: 1/(1 + 0.5*2) = 1/2
  EXPECT_RGB(r[0].diffuse(), 0.5f, 0.5f, 0.5f, kTol);
  // d = 1: 1/(1 + 0.5) = 2/3
  EXPECT_RGB(r[1].diffuse(), 2 / 3.0f, 2 / 3.0f, 2 / 3.0f, kTol);
  // d = 4 > Range 3: no contribution
  EXPECT_RGB(r[2].diffuse(), 0, 0, 0, kTol);
  // d = 3 = Range: still lit (attenuation is not zero at Range): 1/(1 + 1.5) = 0.4
  EXPECT_RGB(r[3].diffuse(), 0.4f, 0.4f, 0.4f, kTol);

  // Quadratic term: a0 = 1, a2 = 0.25 at d = 2: 1/(1 + 0.25*4) = 1/2
  s.lights[0] = point({0, 0, 0}, 1, 0, 0.25f, 100);
  s.lights[0].diffuse = {1, 1, 1, 0};
  // Position in camera space: the view moves the light too (world light at z=-3, view +3).
  s.lights[0].position = {0, 0, -3};
  s.view = matrixTranslation(0, 0, 3);
  r = run(build(s, withNormal()), {at({0, 0, -1})});
  EXPECT_RGB(r[0].diffuse(), 0.5f, 0.5f, 0.5f, kTol);
}

TEST(FFVertex, SpotConeAndFalloff) {
  DeviceState s = litState();
  Light l = point({0, 0, 0}, 1, 0, 0, 100);
  l.type = LIGHT_SPOT;
  l.direction = {0, 0, 1};
  l.diffuse = {1, 1, 1, 0};
  l.theta = kPi / 3;  // cos(Theta/2) = cos 30° = 0.866025
  l.phi = kPi / 2;    // cos(Phi/2)   = cos 45° = 0.707107
  l.falloff = 1;
  s.lights[0] = l;
  s.lightEnabled[0] = true;
  // Normals point back at the light so N·L = 1 and only the spot factor varies.
  auto towardLight = [](Vec3 p) { return at(p, normalize(-p)); };
  std::vector<Vertex> v = {towardLight({0, 0, 2}), towardLight({1.5f, 0, 2}),
                           towardLight({3, 0, 2})};
  auto r = run(build(s, withNormal()), v);
  const float cosT = std::cos(kPi / 6), cosP = std::cos(kPi / 4);
  // on the axis: rho = 1 > cos(Theta/2) -> 1
  EXPECT_RGB(r[0].diffuse(), 1, 1, 1, kTol);
  // (1.5,0,2): rho = 2/2.5 = 0.8, in the band: (0.8 - cosP)/(cosT - cosP) = 0.5845
  const float band = (0.8f - cosP) / (cosT - cosP);
  EXPECT_RGB(r[1].diffuse(), band, band, band, kTol);
  // (3,0,2): rho = 2/sqrt(13) = 0.5547 <= cos(Phi/2) -> 0
  EXPECT_RGB(r[2].diffuse(), 0, 0, 0, kTol);

  s.lights[0].falloff = 2;  // band factor squared: 0.5845² = 0.3417
  r = run(build(s, withNormal()), v);
  EXPECT_RGB(r[0].diffuse(), 1, 1, 1, kTol);
  EXPECT_RGB(r[1].diffuse(), band * band, band * band, band * band, kTol);
  EXPECT_RGB(r[2].diffuse(), 0, 0, 0, kTol);

  s.lights[0].falloff = 0;  // outside Phi stays dark even though x^0 = 1
  r = run(build(s, withNormal()), v);
  EXPECT_RGB(r[1].diffuse(), 1, 1, 1, kTol);
  EXPECT_RGB(r[2].diffuse(), 0, 0, 0, kTol);
}

TEST(FFVertex, AmbientGlobalAndPerLight) {
  DeviceState s = litState();
  s.material.diffuse = {0, 0, 0, 1};
  s.material.ambient = {1, 0.5f, 0.25f, 1};
  s.renderStates[RS_AMBIENT] = 0xFF404040;  // Ga = 64/255 = 0.250980
  Light d = directional({0, 0, 1}, {0, 0, 0, 0});
  d.ambient = {0.1f, 0.1f, 0.1f, 0};
  Light p = point({0, 0, 0}, 2, 0, 0, 100);  // atten = 1/2
  p.ambient = {0.4f, 0.4f, 0.4f, 0};
  s.lights[0] = d;
  s.lights[3] = p;
  s.lightEnabled[0] = s.lightEnabled[3] = true;
  auto r = run(build(s, withNormal()), {at({0, 0, 2})});
  // Ambient_m * (Ga + 0.1 + 0.4*0.5) = (1, 0.5, 0.25) * 0.550980
  const float a = 64 / 255.0f + 0.1f + 0.2f;
  EXPECT_VEC4(r[0].diffuse(), a, 0.5f * a, 0.25f * a, 1, kTol);

  // A point light out of range contributes no ambient either.
  s.lights[3].range = 1;
  r = run(build(s, withNormal()), {at({0, 0, 2})});
  const float b = 64 / 255.0f + 0.1f;
  EXPECT_RGB(r[0].diffuse(), b, 0.5f * b, 0.25f * b, kTol);
}

TEST(FFVertex, EmissiveAndMaterialColorSources) {
  DeviceState s = litState();
  s.material.diffuse = {0.2f, 0.4f, 0.6f, 0.8f};
  s.material.emissive = {0.1f, 0.2f, 0.3f, 0};
  // N·L = 1 from a light straight ahead.
  s.lights[0] = directional({0, 0, 1});
  s.lightEnabled[0] = true;
  Vertex v = at({0, 0, 5});
  v.diffuse = {0.5f, 0.25f, 0.125f, 0.6f};
  v.specular = {0.3f, 0.3f, 0.3f, 0.7f};

  // DIFFUSEMATERIALSOURCE COLOR1 (default) and the vertex has a diffuse color:
  // emissive + vertex diffuse * 1
  FixedFunctionVertexConfig cfg = withNormal();
  cfg.hasDiffuse = true;
  auto r = run(build(s, cfg), {v});
  EXPECT_VEC4(r[0].diffuse(), 0.1f + 0.5f, 0.2f + 0.25f, 0.3f + 0.125f, 0.6f, kTol);

  // No vertex diffuse: the material member is used.
  cfg.hasDiffuse = false;
  r = run(build(s, cfg), {v});
  EXPECT_VEC4(r[0].diffuse(), 0.1f + 0.2f, 0.2f + 0.4f, 0.3f + 0.6f, 0.8f, kTol);

  // Source MATERIAL ignores the vertex color.
  cfg.hasDiffuse = true;
  s.renderStates[RS_DIFFUSEMATERIALSOURCE] = MCS_MATERIAL;
  r = run(build(s, cfg), {v});
  EXPECT_VEC4(r[0].diffuse(), 0.3f, 0.6f, 0.9f, 0.8f, kTol);

  // COLORVERTEX FALSE: material even with COLOR1.
  s.renderStates[RS_DIFFUSEMATERIALSOURCE] = MCS_COLOR1;
  s.renderStates[RS_COLORVERTEX] = 0;
  r = run(build(s, cfg), {v});
  EXPECT_VEC4(r[0].diffuse(), 0.3f, 0.6f, 0.9f, 0.8f, kTol);

  // Emissive from COLOR2 (vertex specular), diffuse from COLOR1.
  s.renderStates[RS_COLORVERTEX] = 1;
  s.renderStates[RS_EMISSIVEMATERIALSOURCE] = MCS_COLOR2;
  cfg.hasSpecular = true;
  r = run(build(s, cfg), {v});
  EXPECT_RGB(r[0].diffuse(), 0.3f + 0.5f, 0.3f + 0.25f, 0.3f + 0.125f, kTol);

  // Results are clamped to [0,1]: emissive 0.9 + diffuse 0.5 -> 1.
  s.renderStates[RS_EMISSIVEMATERIALSOURCE] = MCS_MATERIAL;
  s.material.emissive = {0.9f, 0.9f, 0.9f, 0};
  r = run(build(s, cfg), {v});
  EXPECT_RGB(r[0].diffuse(), 1, 1, 1, kTol);
}

TEST(FFVertex, SpecularLocalAndNonLocalViewer) {
  DeviceState s = litState();
  s.material.specular = {1, 0.5f, 1, 1};
  s.material.power = 10;
  Light l = directional({0, 0, 1});  // Ldir = (0,0,-1)
  l.specular = {1, 1, 1, 0};
  s.lights[0] = l;
  s.lightEnabled[0] = true;
  s.renderStates[RS_SPECULARENABLE] = 1;
  // Vertex at (5,0,5) facing the camera, N = (0,0,-1), N·L = 1.
  std::vector<Vertex> v = {at({5, 0, 5})};

  // LOCALVIEWER TRUE: V = normalize(-P) = (-0.7071, 0, -0.7071);
  // H = normalize(V + L) = (-0.38268, 0, -0.92388); N·H = cos 22.5°; spec = cos(22.5°)^10 = 0.4531
  s.renderStates[RS_LOCALVIEWER] = 1;
  auto r = run(build(s, withNormal()), v);
  const float sp = std::pow(std::cos(kPi / 8), 10.0f);
  EXPECT_RGB(r[0].specular(), sp, 0.5f * sp, sp, kTol);

  // LOCALVIEWER FALSE: V = (0,0,-1); H = (0,0,-1); N·H = 1 -> spec = 1 * material specular
  s.renderStates[RS_LOCALVIEWER] = 0;
  r = run(build(s, withNormal()), v);
  EXPECT_RGB(r[0].specular(), 1, 0.5f, 1, kTol);

  // A point light on the same line: same H, atten 1 -> the same local-viewer highlight.
  s.renderStates[RS_LOCALVIEWER] = 1;
  Light p = point({5, 0, 0}, 1, 0, 0, 100);
  p.specular = {1, 1, 1, 0};
  s.lights[0] = p;
  r = run(build(s, withNormal()), v);
  EXPECT_RGB(r[0].specular(), sp, 0.5f * sp, sp, kTol);

  // SPECULARENABLE FALSE: no specular at all.
  s.renderStates[RS_SPECULARENABLE] = 0;
  r = run(build(s, withNormal()), v);
  EXPECT_RGB(r[0].specular(), 0, 0, 0, kTol);
}

TEST(FFVertex, NoSpecularFromLightBehindSurface) {
  DeviceState s = litState();
  s.material.specular = {1, 1, 1, 1};
  s.material.power = 1;
  s.renderStates[RS_SPECULARENABLE] = 1;
  s.renderStates[RS_LOCALVIEWER] = 0;
  // Ldir = normalize(1, 0, 0.2): N·L = -0.196 < 0 although N·H = 0.63 > 0.
  Light l = directional({-1, 0, -0.2f});
  l.specular = {1, 1, 1, 0};
  s.lights[0] = l;
  s.lightEnabled[0] = true;
  auto r = run(build(s, withNormal()), {at({0, 0, 5})});
  EXPECT_RGB(r[0].specular(), 0, 0, 0, kTol);
  EXPECT_RGB(r[0].diffuse(), 0, 0, 0, kTol);
}

TEST(FFVertex, NormalizeNormalsWithScaledWorld) {
  DeviceState s = litState();
  s.world = matrixScaling(2, 2, 2);
  s.lights[0] = directional({0, 0, 1});
  s.lightEnabled[0] = true;
  // Inverse transpose of 2I is I/2: N = (0,0,-0.5), N·L = 0.5
  auto r = run(build(s, withNormal()), {at({0, 0, 5})});
  EXPECT_RGB(r[0].diffuse(), 0.5f, 0.5f, 0.5f, kTol);
  // NORMALIZENORMALS: |N| = 1, N·L = 1
  s.renderStates[RS_NORMALIZENORMALS] = 1;
  r = run(build(s, withNormal()), {at({0, 0, 5})});
  EXPECT_RGB(r[0].diffuse(), 1, 1, 1, kTol);
  // Non-uniform scale: world scaling (1, 1, 4), N = (0,0,-1) -> (0,0,-0.25), normalized back to 1.
  s.world = matrixScaling(1, 1, 4);
  s.renderStates[RS_NORMALIZENORMALS] = 0;
  r = run(build(s, withNormal()), {at({0, 0, 1})});
  EXPECT_RGB(r[0].diffuse(), 0.25f, 0.25f, 0.25f, kTol);
}

TEST(FFVertex, LightingFalsePassesVertexColors) {
  DeviceState s = litState();
  s.renderStates[RS_LIGHTING] = 0;
  s.lights[0] = directional({0, 0, 1});
  s.lightEnabled[0] = true;
  FixedFunctionVertexConfig cfg;
  cfg.hasDiffuse = cfg.hasSpecular = true;
  Vertex v = at({0, 0, 5});
  v.diffuse = {0.1f, 0.2f, 0.3f, 0.4f};
  v.specular = {0.5f, 0.6f, 0.7f, 0.8f};
  Vertex w = at({1, 0, 5});  // absent colors as the fetcher fills them
  auto r = run(build(s, cfg), {v, w});
  EXPECT_VEC4(r[0].diffuse(), 0.1f, 0.2f, 0.3f, 0.4f, kTol);
  EXPECT_VEC4(r[0].specular(), 0.5f, 0.6f, 0.7f, 0.8f, kTol);
  // fog disabled: the fog output is the specular alpha
  EXPECT_NEAR(r[0].fog(), 0.8f, kTol);
  EXPECT_VEC4(r[1].diffuse(), 1, 1, 1, 1, kTol);
  EXPECT_VEC4(r[1].specular(), 0, 0, 0, 0, kTol);
}

TEST(FFVertex, VertexFogModes) {
  DeviceState s;
  s.renderStates[RS_LIGHTING] = 0;
  s.renderStates[RS_FOGENABLE] = 1;
  s.view = matrixTranslation(0, 0, 1);  // camera-space z = world z + 1
  setFloat(s, RS_FOGSTART, 2);
  setFloat(s, RS_FOGEND, 10);
  setFloat(s, RS_FOGDENSITY, 0.5f);
  FixedFunctionVertexConfig cfg;
  cfg.hasSpecular = true;
  std::vector<Vertex> v = {at({0, 0, 3}), at({0, 0, 11}), at({0, 0, 0}), at({3, 0, 3})};
  for (auto& x : v) x.specular = {0.2f, 0.2f, 0.2f, 0.3f};

  s.renderStates[RS_FOGVERTEXMODE] = FOG_LINEAR;
  auto r = run(build(s, cfg), v);
  // (end - d)/(end - start): z = 4 -> 6/8 = 0.75; z = 12 -> -0.25 -> 0; z = 1 -> 1.125 -> 1
  EXPECT_NEAR(r[0].fog(), 0.75f, kTol);
  EXPECT_NEAR(r[0].specular().w, 0.75f, kTol);
  EXPECT_RGB(r[0].specular(), 0.2f, 0.2f, 0.2f, kTol);
  EXPECT_NEAR(r[1].fog(), 0, kTol);
  EXPECT_NEAR(r[2].fog(), 1, kTol);
  // without RANGEFOG only z counts: (3,0,4) -> d = 4 -> 0.75
  EXPECT_NEAR(r[3].fog(), 0.75f, kTol);

  s.renderStates[RS_RANGEFOGENABLE] = 1;
  r = run(build(s, cfg), v);
  // |(3,0,4)| = 5 -> (10 - 5)/8 = 0.625
  EXPECT_NEAR(r[3].fog(), 0.625f, kTol);
  EXPECT_NEAR(r[3].specular().w, 0.625f, kTol);
  s.renderStates[RS_RANGEFOGENABLE] = 0;

  s.renderStates[RS_FOGVERTEXMODE] = FOG_EXP;
  r = run(build(s, cfg), v);
  // e^-(d*density): d = 4 -> e^-2 = 0.135335
  EXPECT_NEAR(r[0].fog(), std::exp(-2.0f), kTol);

  s.renderStates[RS_FOGVERTEXMODE] = FOG_EXP2;
  r = run(build(s, cfg), v);
  // e^-((d*density)²): d = 4 -> e^-4 = 0.018316
  EXPECT_NEAR(r[0].fog(), std::exp(-4.0f), kTol);
  EXPECT_NEAR(r[0].specular().w, std::exp(-4.0f), kTol);

  // Table fog selected: no vertex fog; f stays the vertex specular alpha.
  s.renderStates[RS_FOGTABLEMODE] = FOG_LINEAR;
  r = run(build(s, cfg), v);
  EXPECT_NEAR(r[0].fog(), 0.3f, kTol);
  EXPECT_NEAR(r[0].specular().w, 0.3f, kTol);

  // FOGVERTEXMODE NONE: f from the specular alpha as well.
  s.renderStates[RS_FOGTABLEMODE] = FOG_NONE;
  s.renderStates[RS_FOGVERTEXMODE] = FOG_NONE;
  r = run(build(s, cfg), v);
  EXPECT_NEAR(r[0].fog(), 0.3f, kTol);
}

TEST(FFVertex, VertexFogWithLightingKeepsLitSpecularColor) {
  DeviceState s = litState();
  s.renderStates[RS_FOGENABLE] = 1;
  s.renderStates[RS_FOGVERTEXMODE] = FOG_LINEAR;
  setFloat(s, RS_FOGSTART, 0);
  setFloat(s, RS_FOGEND, 8);
  auto r = run(build(s, withNormal()), {at({0, 0, 2})});
  // (8 - 2)/8 = 0.75
  EXPECT_NEAR(r[0].specular().w, 0.75f, kTol);
  EXPECT_NEAR(r[0].fog(), 0.75f, kTol);
}

TEST(FFVertex, TexCoordGenerationCameraSpace) {
  DeviceState s;
  s.renderStates[RS_LIGHTING] = 0;
  s.view = matrixTranslation(0, 0, 5);
  s.stageStates[0][TSS_TEXCOORDINDEX] = TCI_CAMERASPACENORMAL;
  s.stageStates[1][TSS_TEXCOORDINDEX] = TCI_CAMERASPACEPOSITION;
  s.stageStates[2][TSS_TEXCOORDINDEX] = TCI_CAMERASPACEREFLECTIONVECTOR;
  s.stageStates[3][TSS_TEXCOORDINDEX] = TCI_SPHEREMAP;
  s.stageStates[4][TSS_TEXCOORDINDEX] = 1;  // pass-through of set 1
  FixedFunctionVertexConfig cfg = withNormal();
  cfg.texCoordDims = {2, 2};
  Vertex a = at({0, 0, 0});  // camera (0,0,5)
  Vertex b = at({3, 0, -1});  // camera (3,0,4)
  b.tex[1] = {0.25f, 0.75f, 0, 1};
  auto r = run(build(s, cfg), {a, b});
  EXPECT_VEC4(r[0].tex(0), 0, 0, -1, 0, kTol);
  EXPECT_VEC4(r[0].tex(1), 0, 0, 5, 0, kTol);
  EXPECT_VEC4(r[1].tex(1), 3, 0, 4, 0, kTol);
  // a: E = (0,0,1), N·E = -1, R = E - 2(N·E)N = (0,0,1) + 2(0,0,-1) = (0,0,-1)
  EXPECT_VEC4(r[0].tex(2), 0, 0, -1, 0, kTol);
  // b: E = (0.6,0,0.8), N·E = -0.8, R = E + 1.6 N = (0.6, 0, -0.8)
  EXPECT_VEC4(r[1].tex(2), 0.6f, 0, -0.8f, 0, kTol);
  // sphere map of R = (0.6,0,-0.8): m = 2*sqrt(0.36 + 0.04) = 1.264911;
  // u = 0.6/m + 0.5 = 0.974342, v = 0/m + 0.5
  EXPECT_VEC4(r[1].tex(3), 0.6f / (2 * std::sqrt(0.4f)) + 0.5f, 0.5f, 0, 0, kTol);
  // pass-through: the set's two components, unused components 0 (the fetched w = 1 is dropped)
  EXPECT_VEC4(r[1].tex(4), 0.25f, 0.75f, 0, 0, kTol);

  // The camera-space normal follows a rotated view: N=(1,0,0) * RotationY(90°) = (0,0,-1)
  s.view = matrixRotationY(kPi / 2);
  r = run(build(s, cfg), {at({0, 0, 0}, {1, 0, 0})});
  EXPECT_VEC4(r[0].tex(0), 0, 0, -1, 0, kTol);
}

TEST(FFVertex, TextureTransformCount2TranslationInRow3) {
  DeviceState s;
  s.renderStates[RS_LIGHTING] = 0;
  Matrix m = Matrix::identity();
  m.m[2][0] = 0.25f;  // _31
  m.m[2][1] = 0.5f;   // _32
  s.textureTransforms[0] = m;
  s.stageStates[0][TSS_TEXTURETRANSFORMFLAGS] = TTFF_COUNT2;
  // 3-component set on stage 1: (u,v,w,1) picks up row 4 (_41,_42,_43)
  s.stageStates[1][TSS_TEXTURETRANSFORMFLAGS] = TTFF_COUNT3;
  s.textureTransforms[1] = matrixTranslation(1, 2, 3);
  // 1-component set on stage 2: (u,1,0,0) picks up row 2 (_21)
  Matrix m2 = Matrix::identity();
  m2.m[1][0] = 0.5f;
  s.textureTransforms[2] = m2;
  s.stageStates[2][TSS_TEXTURETRANSFORMFLAGS] = TTFF_COUNT1;
  FixedFunctionVertexConfig cfg;
  cfg.texCoordDims = {2, 3, 1};
  Vertex v = at({0, 0, 1});
  v.tex[0] = {0.1f, 0.2f, 0, 1};
  v.tex[1] = {0.1f, 0.2f, 0.3f, 1};
  v.tex[2] = {0.1f, 0, 0, 1};
  auto r = run(build(s, cfg), {v});
  // (0.1, 0.2, 1, 0) * M = (0.1 + 0.25, 0.2 + 0.5); COUNT2 keeps two, the rest 0
  EXPECT_VEC4(r[0].tex(0), 0.35f, 0.7f, 0, 0, kTol);
  // (0.1, 0.2, 0.3, 1) * T(1,2,3) = (1.1, 2.2, 3.3)
  EXPECT_VEC4(r[0].tex(1), 1.1f, 2.2f, 3.3f, 0, kTol);
  // (0.1, 1, 0, 0) * M2 = (0.1 + 0.5, 1, 0); COUNT1 keeps 0.6
  EXPECT_VEC4(r[0].tex(2), 0.6f, 0, 0, 0, kTol);
}

TEST(FFVertex, ProjectedDivisorInW) {
  DeviceState s;
  s.renderStates[RS_LIGHTING] = 0;
  s.stageStates[0][TSS_TEXCOORDINDEX] = TCI_CAMERASPACEPOSITION;
  s.stageStates[0][TSS_TEXTURETRANSFORMFLAGS] = TTFF_COUNT3 | TTFF_PROJECTED;
  s.textureTransforms[0] = matrixScaling(0.5f, 0.5f, 1);
  s.stageStates[1][TSS_TEXTURETRANSFORMFLAGS] = TTFF_COUNT4 | TTFF_PROJECTED;
  FixedFunctionVertexConfig cfg;
  cfg.texCoordDims = {0, 4};
  Vertex v = at({1, 2, 4});
  v.tex[1] = {1, 2, 3, 4};
  auto r = run(build(s, cfg), {v});
  // (1,2,4,1) * S(0.5,0.5,1) = (0.5, 1, 4); divisor = component 3 (z) -> w
  EXPECT_VEC4(r[0].tex(0), 0.5f, 1, 4, 4, kTol);
  // COUNT4: the fourth component is already w
  EXPECT_VEC4(r[0].tex(1), 1, 2, 3, 4, kTol);
}

TEST(FFVertex, PretransformedPassThrough) {
  DeviceState s = litState();
  s.world = matrixTranslation(5, 5, 5);
  s.projection = matrixScaling(3, 3, 3);
  s.lights[0] = directional({0, 0, 1});
  s.lightEnabled[0] = true;
  s.renderStates[RS_FOGENABLE] = 1;
  s.renderStates[RS_FOGVERTEXMODE] = FOG_LINEAR;
  s.stageStates[0][TSS_TEXCOORDINDEX] = 1 | TCI_CAMERASPACEPOSITION;
  FixedFunctionVertexConfig cfg;
  cfg.pretransformed = true;
  cfg.hasDiffuse = cfg.hasSpecular = true;
  cfg.texCoordDims = {2, 2};
  Vertex v;
  v.pos = {100, 50, 0.5f, 0.25f};
  v.diffuse = {0.1f, 0.2f, 0.3f, 0.4f};
  v.specular = {0.5f, 0.6f, 0.7f, 0.8f};
  v.tex[1] = {0.25f, 0.5f, 0, 1};
  auto r = run(build(s, cfg), {v});
  EXPECT_VEC4(r[0].pos(), 100, 50, 0.5f, 0.25f, 0);
  EXPECT_VEC4(r[0].diffuse(), 0.1f, 0.2f, 0.3f, 0.4f, kTol);
  EXPECT_VEC4(r[0].specular(), 0.5f, 0.6f, 0.7f, 0.8f, kTol);
  // f comes from the vertex's specular alpha
  EXPECT_NEAR(r[0].fog(), 0.8f, kTol);
  // set 1 as given; no generation for pretransformed vertices
  EXPECT_VEC4(r[0].tex(0), 0.25f, 0.5f, 0, 0, kTol);
}

TEST(FFVertex, PointSizeAndScale) {
  DeviceState s;
  s.renderStates[RS_LIGHTING] = 0;
  setFloat(s, RS_POINTSIZE, 4);
  auto r = run(build(s, {}), {at({0, 0, 5})});
  EXPECT_NEAR(r[0].psize(), 4, kTol);
  // POINTSCALE: Si * Vh * sqrt(1/(A + B De + C De²)); Si = 0.1, Vh = 100, C = 1, De = 5 -> 2
  setFloat(s, RS_POINTSIZE, 0.1f);
  setFloat(s, RS_POINTSCALE_A, 0);
  setFloat(s, RS_POINTSCALE_C, 1);
  s.renderStates[RS_POINTSCALEENABLE] = 1;
  s.viewport.height = 100;
  r = run(build(s, {}), {at({3, 0, 4})});
  EXPECT_NEAR(r[0].psize(), 2, kTol);
  // Vertex PSIZE 3 with A = 1: 3 * 100 * 1 = 300 -> clamped to POINTSIZE_MAX 64
  setFloat(s, RS_POINTSCALE_A, 1);
  setFloat(s, RS_POINTSCALE_C, 0);
  FixedFunctionVertexConfig cfg;
  cfg.hasPSize = true;
  Vertex v = at({0, 0, 5});
  v.psize = 3;
  r = run(build(s, cfg), {v});
  EXPECT_NEAR(r[0].psize(), 64, kTol);
}

TEST(FFVertex, NoLightsGivesEmissivePlusAmbient) {
  DeviceState s = litState();
  s.material.emissive = {0.25f, 0, 0, 0};
  s.material.ambient = {0, 1, 0, 0};
  s.renderStates[RS_AMBIENT] = 0xFF808080;  // 128/255
  auto r = run(build(s, {}), {at({0, 0, 5})});
  // emissive + ambient_m * Ga = (0.25, 128/255, 0); material diffuse alpha 1
  EXPECT_VEC4(r[0].diffuse(), 0.25f, 128 / 255.0f, 0, 1, kTol);
}

}  // namespace
