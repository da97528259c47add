// The six programs of "Implementing Lighting Models With HLSL", compiled by refx and
// rendered on a unit sphere. Expected colours come from the article's formulas
// evaluated at the sphere point each probed pixel shows.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "refx/d3dx/mesh.h"
#include "refx/hlsl/compiler.h"
#include "refx/pipeline/device.h"
#include "refx/shader/validator.h"

namespace refx {
namespace {

std::string seedPath(const char* name) { return std::string(REFX_DATA_DIR) + "/hlsl/" + name; }

hlsl::CompileResult compileSeed(const char* file, const char* profile, const char* entry) {
  hlsl::CompileOptions o;
  o.profile = profile;
  o.entry = entry;
  return hlsl::compileFile(seedPath(file), o);
}

bool hasError(const hlsl::CompileResult& r) {
  for (const Diagnostic& d : r.diagnostics)
    if (d.severity == Severity::Error) return true;
  return false;
}

// Every program compiles for the profiles the article names, and refx's validator
// accepts the result.
TEST(HlslSeeds, CompileForTheArticlesProfiles) {
  const char* files[] = {"ambient.hlsl", "diffuse.hlsl", "specular.hlsl", "self_shadow.hlsl", "bump.hlsl",
                         "point_light.hlsl"};
  for (const char* f : files) {
    for (auto [profile, entry] : {std::pair{"vs_1_1", "VS"}, {"vs_2_0", "VS"}, {"ps_2_0", "PS"}}) {
      hlsl::CompileResult r = compileSeed(f, profile, entry);
      EXPECT_TRUE(r.ok()) << f << " " << profile << "\n" << r.messages();
      EXPECT_FALSE(hasError(r)) << f << " " << profile;
      if (r.ok()) {
        EXPECT_TRUE(shader::validate(r.shader).empty()) << f << " " << profile;
      }
    }
  }
}

// The pixel shaders that fit the DirectX 8 models compile for ps_1_4 and ps_1_1 (the
// ambient one is one mov of a def, the diffuse one reads both vectors with a texture
// instruction, dp3_sat and mad); the others need normalize, which ps_1_x cannot do.
TEST(HlslSeeds, PixelShadersThatFitPs1x) {
  for (const char* profile : {"ps_1_4", "ps_1_1"}) {
    for (auto [file, slots] : {std::pair{"ambient.hlsl", 1}, {"diffuse.hlsl", 4}}) {
      hlsl::CompileResult r = compileSeed(file, profile, "PS");
      ASSERT_TRUE(r.ok()) << file << " " << profile << "\n" << r.messages();
      EXPECT_TRUE(shader::validate(r.shader).empty()) << file << " " << profile;
      EXPECT_EQ(r.instructionSlots, slots) << file << " " << profile;
    }
    for (const char* file : {"specular.hlsl", "self_shadow.hlsl", "bump.hlsl", "point_light.hlsl"}) {
      hlsl::CompileResult r = compileSeed(file, profile, "PS");
      EXPECT_FALSE(r.ok()) << file << " " << profile;
      bool named = false;
      for (const Diagnostic& d : r.diagnostics)
        named |= d.code == "X4532" && d.message.find("normalize needs rsq") != std::string::npos &&
                 d.message.find(profile) != std::string::npos;
      EXPECT_TRUE(named) << file << " " << profile << "\n" << r.messages();
    }
  }
}

// Reviewed listing: the ambient pixel shader is one def and one mov, the vertex shader
// four dp4 of the position with the columns of matWorldViewProj (column_major: c0..c3
// hold the columns), as fxc compiles them.
TEST(HlslSeeds, AmbientListing) {
  hlsl::CompileResult ps = compileSeed("ambient.hlsl", "ps_2_0", "PS");
  ASSERT_TRUE(ps.ok()) << ps.messages();
  ASSERT_EQ(ps.shader.instructions.size(), 3u);  // CTAB comment, def, mov
  const shader::Instruction& def = ps.shader.instructions[1];
  EXPECT_EQ(def.opcode, shader::Opcode::Def);
  float v[4];
  std::memcpy(v, def.literal.data(), 16);
  EXPECT_FLOAT_EQ(v[0], 0.5f);
  EXPECT_FLOAT_EQ(v[1], 0.075f);
  EXPECT_FLOAT_EQ(v[2], 0.075f);
  EXPECT_FLOAT_EQ(v[3], 1.0f);
  const shader::Instruction& mov = ps.shader.instructions[2];
  EXPECT_EQ(mov.opcode, shader::Opcode::Mov);
  EXPECT_EQ(mov.dst.type, shader::RegType::ColorOut);
  EXPECT_EQ(mov.src[0].type, shader::RegType::Const);

  hlsl::CompileResult vs = compileSeed("ambient.hlsl", "vs_1_1", "VS");
  ASSERT_TRUE(vs.ok()) << vs.messages();
  int dp4 = 0;
  for (const shader::Instruction& in : vs.shader.instructions) {
    if (in.opcode != shader::Opcode::Dp4) continue;
    EXPECT_EQ(in.dst.type, shader::RegType::RastOut);            // oPos
    EXPECT_EQ(in.dst.writeMask, 1u << dp4);                      // .x, .y, .z, .w in turn
    EXPECT_EQ(in.src[1].type, shader::RegType::Const);
    EXPECT_EQ(in.src[1].index, dp4);                             // column dp4 of the matrix
    ++dp4;
  }
  EXPECT_EQ(dp4, 4);
  EXPECT_EQ(vs.instructionSlots, 4);
}

// ---- rendering on a sphere -----------------------------------------------------------------

constexpr int kSize = 64;
constexpr float kExtent = 1.25f;  // the view shows [-1.25, 1.25]²

struct SphereScene {
  std::unique_ptr<Device> dev;
  d3dx::Mesh sphere = d3dx::createSphere(1.0f, 64, 32);

  SphereScene() {
    DeviceOptions opt;
    opt.threads = 1;
    dev = std::make_unique<Device>(CapsProfile{}, opt);
    dev->setRenderTarget(Texture::create2D(Format::A8R8G8B8, kSize, kSize));
    dev->setDepthStencilSurface(std::make_shared<DepthStencilSurface>(kSize, kSize));
    dev->clear(d3d::CLEAR_TARGET | d3d::CLEAR_ZBUFFER, 0xff000000, 1.0f, 0);
    dev->setFVF(sphere.fvf);
    auto vb = std::make_shared<VertexBuffer>();
    vb->data = sphere.vertices;
    dev->setStreamSource(0, vb, 0, sphere.stride);
    auto ib = std::make_shared<IndexBuffer>();
    ib->index32 = true;
    ib->data = sphere.indexBufferData(true);
    dev->setIndices(ib);
    dev->setRenderState(d3d::RS_CULLMODE, d3d::CULL_NONE);
  }

  // matWorldViewProj as an orthographic view: x, y scaled by 1/1.25, z in [0.25, 0.75];
  // uploaded transposed (column_major: register i holds column i).
  void setMatrices(int worldRegister) {
    const float wvp[16] = {1 / kExtent, 0, 0, 0, 0, 1 / kExtent, 0, 0, 0, 0, 0.25f, 0.5f, 0, 0, 0, 1};
    dev->setVertexShaderConstantF(0, wvp, 4);
    const float world[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    if (worldRegister >= 0) dev->setVertexShaderConstantF(uint32_t(worldRegister), world, 4);
  }

  void draw(const hlsl::CompileResult& vs, const hlsl::CompileResult& ps) {
    dev->setVertexShader(dev->createVertexShader(vs.tokens));
    dev->setPixelShader(dev->createPixelShader(ps.tokens));
    dev->drawIndexedPrimitive(d3d::PT_TRIANGLELIST, 0, 0, sphere.vertexCount(), 0, sphere.faceCount());
  }

  Color4 at(int x, int y) const {
    const Texture& t = *dev->renderTarget();
    uint32_t v;
    std::memcpy(&v, t.data(0, 0) + y * t.rowPitch(0) + x * 4, 4);
    return {float((v >> 16) & 255) / 255, float((v >> 8) & 255) / 255, float(v & 255) / 255, float(v >> 24) / 255};
  }

  // The sphere point pixel (x, y) shows (D3D9 pixel centres at integer coordinates).
  static bool surface(int x, int y, Vec3& p) {
    float sx = (float(x) / (kSize / 2) - 1) * kExtent;
    float sy = (1 - float(y) / (kSize / 2)) * kExtent;
    float r2 = sx * sx + sy * sy;
    if (r2 > 1) return false;
    p = Vec3(sx, sy, -std::sqrt(1 - r2));  // the hemisphere facing the camera (looking down +z)
    return true;
  }
};

const std::pair<int, int> kProbes[] = {{32, 32}, {20, 26}, {44, 20}, {36, 44}, {14, 32}, {32, 12}, {48, 40}};

Vec3 normalized(Vec3 v) {
  float l = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
  return Vec3(v.x / l, v.y / l, v.z / l);
}
float dot3(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
float sat(float v) { return std::fmin(std::fmax(v, 0.0f), 1.0f); }

TEST(HlslSeeds, AmbientIsConstantOverTheSphere) {
  auto vs = compileSeed("ambient.hlsl", "vs_1_1", "VS");
  auto ps = compileSeed("ambient.hlsl", "ps_2_0", "PS");
  ASSERT_TRUE(vs.ok() && ps.ok()) << vs.messages() << ps.messages();
  SphereScene s;
  s.setMatrices(-1);
  s.draw(vs, ps);
  int covered = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      Vec3 p;
      Color4 c = s.at(x, y);
      float sx = (float(x) / (kSize / 2) - 1) * kExtent, sy = (1 - float(y) / (kSize / 2)) * kExtent;
      if (sx * sx + sy * sy < 0.95f) {
        // return float4(0.5, 0.075, 0.075, 1.0): exactly that everywhere the sphere covers
        ++covered;
        ASSERT_NEAR(c.r, 0.5f, 1.0f / 255) << x << "," << y;
        ASSERT_NEAR(c.g, 0.075f, 1.0f / 255) << x << "," << y;
        ASSERT_NEAR(c.b, 0.075f, 1.0f / 255) << x << "," << y;
      } else if (sx * sx + sy * sy > 1.05f) {
        ASSERT_EQ(c.r, 0.0f) << "background at " << x << "," << y;
      }
      (void)p;
    }
  EXPECT_GT(covered, 1500);  // pi * (25.6 px)^2 * 0.95 ~ 1950
}

TEST(HlslSeeds, DiffuseIsAmbientPlusNDotL) {
  auto vs = compileSeed("diffuse.hlsl", "vs_1_1", "VS");
  auto ps = compileSeed("diffuse.hlsl", "ps_2_0", "PS");
  ASSERT_TRUE(vs.ok() && ps.ok()) << vs.messages() << ps.messages();
  SphereScene s;
  s.setMatrices(4);  // matWorld follows matWorldViewProj: c4..c7
  const Vec3 L = normalized(Vec3(0.5f, 0.6f, -0.62f));
  const float light[4] = {L.x, L.y, L.z, 0};
  s.dev->setVertexShaderConstantF(8, light, 1);  // vecLightDir: c8
  s.draw(vs, ps);
  for (auto [x, y] : kProbes) {
    Vec3 n;
    ASSERT_TRUE(SphereScene::surface(x, y, n));
    // I = ambient + diffuse * saturate(N.L): red = 0.1 + saturate(N.L), green = blue = 0
    float expected = sat(0.1f + sat(dot3(n, L)));
    Color4 c = s.at(x, y);
    EXPECT_NEAR(c.r, expected, 2.5f / 255) << x << "," << y;
    EXPECT_NEAR(c.g, 0.0f, 1.0f / 255);
    EXPECT_NEAR(c.b, 0.0f, 1.0f / 255);
  }
}

TEST(HlslSeeds, SpecularIsPhongWithExponent8) {
  auto vs = compileSeed("specular.hlsl", "vs_1_1", "VS");
  auto ps = compileSeed("specular.hlsl", "ps_2_0", "PS");
  ASSERT_TRUE(vs.ok() && ps.ok()) << vs.messages() << ps.messages();
  SphereScene s;
  s.setMatrices(4);
  const Vec3 L = normalized(Vec3(-0.3f, 0.4f, -0.85f));
  const Vec3 eye(0, 0, -3);
  const float light[4] = {L.x, L.y, L.z, 0}, eyev[4] = {eye.x, eye.y, eye.z, 1};
  s.dev->setVertexShaderConstantF(8, light, 1);  // vecLightDir: c8
  s.dev->setVertexShaderConstantF(9, eyev, 1);   // vecEye: c9
  s.draw(vs, ps);
  for (auto [x, y] : kProbes) {
    Vec3 p;
    ASSERT_TRUE(SphereScene::surface(x, y, p));
    // VS: PosWorld = normalize(float4(P, 1)) truncated to float3 = P / sqrt(2) on the
    // unit sphere; View = vecEye - PosWorld; Norm = P.
    const float k = 1 / std::sqrt(2.0f);
    Vec3 view(eye.x - p.x * k, eye.y - p.y * k, eye.z - p.z * k);
    Vec3 n = p, l = L, v = normalized(view);
    float diff = sat(dot3(n, l));
    Vec3 r = normalized(Vec3(2 * diff * n.x - l.x, 2 * diff * n.y - l.y, 2 * diff * n.z - l.z));
    float spec = std::pow(sat(dot3(r, v)), 8.0f);
    // I = ambient + diffuse * N.L + (R.V)^8: red 0.1 + diff + spec, green = blue = spec
    Color4 c = s.at(x, y);
    EXPECT_NEAR(c.r, sat(0.1f + diff + spec), 3.0f / 255) << x << "," << y;
    EXPECT_NEAR(c.g, sat(spec), 3.0f / 255) << x << "," << y;
    EXPECT_NEAR(c.b, sat(spec), 3.0f / 255) << x << "," << y;
  }
}

// The ps_1_4 and ps_1_1 versions of the ambient and diffuse pixel shaders at the same
// probes as ps_2_0. ps_1_1 reads the light and normal vectors with texcoord, which
// clamps each coordinate to [0, 1]; ps_1_4's texcrd reads them as they are.
TEST(HlslSeeds, AmbientAndDiffuseInPs1x) {
  for (const char* profile : {"ps_1_4", "ps_1_1"}) {
    SCOPED_TRACE(profile);
    const bool clampedVectors = std::string(profile) == "ps_1_1";
    auto ambientVs = compileSeed("ambient.hlsl", "vs_1_1", "VS");
    auto ambientPs = compileSeed("ambient.hlsl", profile, "PS");
    ASSERT_TRUE(ambientVs.ok() && ambientPs.ok()) << ambientVs.messages() << ambientPs.messages();
    SphereScene a;
    a.setMatrices(-1);
    a.draw(ambientVs, ambientPs);
    for (auto [x, y] : kProbes) {
      Color4 c = a.at(x, y);  // return float4(0.5, 0.075, 0.075, 1.0)
      EXPECT_NEAR(c.r, 0.5f, 1.0f / 255) << x << "," << y;
      EXPECT_NEAR(c.g, 0.075f, 1.0f / 255) << x << "," << y;
      EXPECT_NEAR(c.b, 0.075f, 1.0f / 255) << x << "," << y;
    }

    auto vs = compileSeed("diffuse.hlsl", "vs_1_1", "VS");
    auto ps = compileSeed("diffuse.hlsl", profile, "PS");
    ASSERT_TRUE(vs.ok() && ps.ok()) << vs.messages() << ps.messages();
    SphereScene s;
    s.setMatrices(4);  // matWorld follows matWorldViewProj: c4..c7
    const Vec3 L = normalized(Vec3(0.5f, 0.6f, -0.62f));
    const float light[4] = {L.x, L.y, L.z, 0};
    s.dev->setVertexShaderConstantF(8, light, 1);  // vecLightDir: c8
    s.draw(vs, ps);
    for (auto [x, y] : kProbes) {
      Vec3 n, l = L;
      ASSERT_TRUE(SphereScene::surface(x, y, n));
      if (clampedVectors) {
        n = Vec3(sat(n.x), sat(n.y), sat(n.z));
        l = Vec3(sat(l.x), sat(l.y), sat(l.z));
      }
      // red = 0.1 + saturate(N.L), green = blue = 0
      Color4 c = s.at(x, y);
      EXPECT_NEAR(c.r, sat(0.1f + sat(dot3(n, l))), 2.5f / 255) << x << "," << y;
      EXPECT_NEAR(c.g, 0.0f, 1.0f / 255);
      EXPECT_NEAR(c.b, 0.0f, 1.0f / 255);
    }
  }
}

}  // namespace
}  // namespace refx
