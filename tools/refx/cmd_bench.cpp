// `refx bench`: Mpixels/s of the device on the workloads llvmpipe is measured on
// (../shared/anchors/llvmpipe_bench): a full-screen quad and a lit sphere, textured by
// the anchor's ps.1.1 `tex t0; mov r0, t0` (`texture`), or shaded by RacorX6's ps.1.1
// diffuse bump shader
// (`racorx6`, llvmpipe's `diffuse`), RacorX9's ps.1.1 diffuse + specular shader
// (`racorx9`, llvmpipe's `specular`) or the HLSL point light of data/hlsl compiled by
// refx (`phong`, llvmpipe's `phong`), with the same textures, geometry and lights; and
// RacorX10 / RacorX11's multi-pass frames (`racorx10`, `racorx11`, no llvmpipe
// counterpart) on the same geometry; `fftexture` is the fixed-function MODULATE of the
// texture and the lit diffuse colour (no llvmpipe counterpart). Each row also gives the cycles per pixel the cores
// spent and the cycles the workload's FP32 arithmetic needs at the core's peak.
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <sstream>

#include <fmt/format.h>

#include "bench_cycles.h"
#include "commands.h"
#include "effect_scene.h"
#include "refx/core/diagnostics.h"
#include "refx/core/statistics.h"
#include "refx/d3dx/mesh.h"
#include "refx/effect/effect.h"
#include "refx/hlsl/compiler.h"
#include "refx/pipeline/device.h"
#include "refx/resource/image_io.h"
#include "refx/resource/sampler.h"
#include "refx/shader/assembler.h"
#include "refx/shader/constant_table.h"
#include "refx/scene/racorx_scene.h"
#include "samples.h"

namespace refx::cli {

namespace {

using namespace d3d;

struct BenchOptions {
  std::string workloads = "texture";
  std::string geoms = "quad,sphere";
  std::string threads = "1,2";
  std::string sizes = "1024x768,1920x1080";
  double minTime = 2.0;
  int frames = 0;  // > 0: exactly this many measured frames, whatever the time
  std::string png;
  bool hardware = false;
  bool verbose = false;
};

// FP32 FLOPs per shaded pixel, counted as the llvmpipe anchor's RESULTS.md counts them:
// FMA = 2, mul/add = 1, rsq = 4, a ps.1.x modifier (_bx2, 1-x) 2 or 1 per component;
// perspective-correct interpolation 5 per component the pixel stage reads + 5 for 1/w;
// bilinear filtering of an RGBA8 texel quad as float math 50 per sample (a cube map
// sample as one bilinear sample). Blending into the target counts its arithmetic.
struct Workload {
  const char* name;
  int flopsPerPixel;
};
constexpr Workload kWorkloads[] = {
    // texture: tex t0; mov r0, t0: interpolation of uv (2) = 2 x 5 + 5 = 15; one
    // sample 50.                                                              15 + 50 = 65
    {"texture", 65},
    // racorx6: dp3 r1, t1_bx2, v0_bx2 = 2 x 3 x 2 (bx2) + 5 (dp3); mul r0 4 = 21;
    // t0.xy t1.xy v0.xyz = 7 x 5 + 5 = 40; two samples 100.               21 + 40 + 100 = 161
    {"racorx6", 161},
    // racorx9: dp3 with two bx2 = 17; four vec4 muls (N.H^16) = 16; dp3 with two bx2 = 17;
    // mad r0 vec4 = 8 → 58; t0.xy t1.xy v0.xyz v1.xyz = 10 x 5 + 5 = 55; two samples 100.
    //                                                                    58 + 55 + 100 = 213
    {"racorx9", 213},
    // phong (point_light.hlsl PS): bumpNormal 2*(t-0.5) 3 mad = 6; normalize(Light),
    // normalize(View) 2 x (dp3 5 + rsq 4 + mul 3) = 24; saturate(dot(N, L)) 5;
    // saturate(4*diff) 1; Reflect = normalize(2*diff*N - L) 1 + 6 + 12 = 19;
    // min(pow(saturate(dot(R, V)), 3), a) 5 + 2 + 1 = 8; dot(Att, Att) 5;
    // (color * (shadow*diff + 0.2) + shadow*spec) * (1 - att) 1 + 1 + 4 + 1 + 4 + 1 + 4 = 16
    // → 84; Tex.xy Light.xyz View.xyz Att.xyz = 11 x 5 + 5 = 60; two samples 100.
    //                                                                    84 + 60 + 100 = 244
    {"phong", 244},
    // racorx10, per pixel of each of its two passes (both cover the same pixels):
    //   Attenuation: add r0, 1-t0, -t1.a = 4 + 4 = 8; t0.xy t1.x = 3 x 5 + 5 = 20;
    //     two samples 100                                                       = 128
    //   Illumination: texm3x2pad/texm3x2tex 2 x (bx2 6 + dp3 5) = 22; mul r1.rgb 3,
    //     mul r1.a 1, add r0 4 = 8; t0.xy t1.xy t2.xyz t3.xyz = 10 x 5 + 5 = 55;
    //     three samples 150; blend dest x src 4                                 = 239
    //   mean (128 + 239) / 2                                                    = 184
    {"racorx10", 184},
    // racorx11 (racorx_point_light.fx PS11), per pixel of each of its three passes:
    //   Diffuse: dp3 r1, t2_bx2, t1_bx2 = 17, mul r0 4 = 21; t0.xy t1.xy t2.xyz = 40;
    //     three samples (the cube map's as one) 150; blend add 4                = 215
    //   Specular: texm3x2pad/tex 22, mul r0 4 = 26; 10 components 55; three samples
    //     150; blend add 4                                                      = 235
    //   Attenuation: as RacorX10's 128, blend dest x src 4                      = 132
    //   mean (215 + 235 + 132) / 3                                              = 194
    {"racorx11", 194},
    // fftexture: MODULATE texture x diffuse: 4 mul = 4; interpolation of uv (2) and the
    // diffuse color (4) = 6 x 5 + 5 = 35; one sample 50.                   4 + 35 + 50 = 89
    {"fftexture", 89},
};

const Workload* findWorkload(const std::string& name) {
  for (const Workload& w : kWorkloads)
    if (name == w.name) return &w;
  return nullptr;
}

std::string workloadNames() {
  std::string r;
  for (const Workload& w : kWorkloads) r += (r.empty() ? "" : ", ") + std::string(w.name);
  return r;
}

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> r;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) r.push_back(item);
  return r;
}

// The llvmpipe anchor's colour map: 64-texel checker cells, alpha = x ^ y.
TexturePtr checkerTexture(int size) {
  auto t = Texture::create2D(Format::A8R8G8B8, size, size, 0);
  uint8_t* p = t->data(0, 0);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const bool on = ((x >> 6) ^ (y >> 6)) & 1;
      uint8_t* q = p + (size_t(y) * size + x) * 4;  // B G R A
      q[2] = on ? 230 : 40;
      q[1] = on ? 200 : 90;
      q[0] = on ? 120 : 160;
      q[3] = uint8_t((x ^ y) & 0xff);
    }
  t->markDirty();
  t->generateMips();
  return t;
}

// The anchor's normal map: a sum-of-sines height field's normals, n * 0.5 + 0.5.
TexturePtr bumpNormalTexture(int size) {
  auto t = Texture::create2D(Format::A8R8G8B8, size, size, 0);
  uint8_t* p = t->data(0, 0);
  const double k = 2.0 * 3.14159265358979 * 16.0 / size;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const double dhdx = 0.6 * std::cos(k * x) * std::cos(0.5 * k * y);
      const double dhdy = -0.3 * std::sin(k * x) * std::sin(0.5 * k * y) + 0.4 * std::cos(k * y * 1.3);
      const double nx = -dhdx, ny = -dhdy, nz = 1.0;
      const double inv = 1.0 / std::sqrt(nx * nx + ny * ny + nz * nz);
      uint8_t* q = p + (size_t(y) * size + x) * 4;  // B G R A
      q[2] = uint8_t(std::lround((nx * inv * 0.5 + 0.5) * 255.0));
      q[1] = uint8_t(std::lround((ny * inv * 0.5 + 0.5) * 255.0));
      q[0] = uint8_t(std::lround((nz * inv * 0.5 + 0.5) * 255.0));
      q[3] = 255;
    }
  t->markDirty();
  t->generateMips();
  return t;
}

// The anchor's vertex shader for the ps.1.1 workloads: a point light and the eye in
// object space (c4, c5), light and half vectors moved into tangent space, normalized
// and biased into oD0 / oD1 (*0.5 + 0.5), the texture coordinates in oT0 and oT1.
// c0-c3 = world*view*projection (transposed), c6 = 0.5.
constexpr const char* kRacorXBenchVS = R"(vs.1.1
m4x4 oPos, v0, c0
mov r6, v3                      ; N
mov r7, v8                      ; T
mul r8, r6.zxyw, r7.yzxw
mad r8, r6.yzxw, r7.zxyw, -r8   ; B = N x T
add r0, c4, -v0                 ; L = light - position
add r1, c5, -v0                 ; V = eye - position
dp3 r2.x, r7, r0
dp3 r2.y, r8, r0
dp3 r2.z, r6, r0
dp3 r3.x, r7, r1
dp3 r3.y, r8, r1
dp3 r3.z, r6, r1
dp3 r2.w, r2, r2
rsq r2.w, r2.w
mul r2.xyz, r2, r2.w            ; normalize(L)
dp3 r3.w, r3, r3
rsq r3.w, r3.w
mad r3.xyz, r3, r3.w, r2        ; normalize(V) + normalize(L)
dp3 r3.w, r3, r3
rsq r3.w, r3.w
mul r3.xyz, r3, r3.w            ; H
mad oD0.xyz, r2, c6, c6
mad oD1.xyz, r3, c6, c6
mov oT0.xy, v7
mov oT1.xy, v7
)";

struct Scene {
  d3dx::Mesh mesh;
  bool sphere = false;
};

Scene makeScene(const std::string& geom, bool tangents) {
  Scene s;
  if (geom == "quad" && tangents) {
    // The same clip-space quad, facing the viewer (-z), tangent +x.
    s.mesh = d3dx::Mesh(d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(2) | d3d::fvfTexCoordSize(3, 1), 4, 2);
    const float P[4][2] = {{-1, 1}, {1, 1}, {1, -1}, {-1, -1}};
    const float T[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (uint32_t i = 0; i < 4; ++i) {
      s.mesh.setPosition(i, {P[i][0], P[i][1], 0.5f});
      s.mesh.setNormal(i, {0, 0, -1});
      s.mesh.setTexCoord(i, 0, T[i][0], T[i][1]);
      s.mesh.setTexCoord(i, 1, Vec4(1, 0, 0, 0));
    }
    s.mesh.indices = {0, 1, 2, 0, 2, 3};
  } else if (geom == "sphere" && tangents) {
    // createTexturedSphere carries the tangent (v8) in set 1.
    s.mesh = d3dx::createTexturedSphere(1.0f, 64, 32);
    for (uint32_t i = 0; i < s.mesh.vertexCount(); ++i) {
      Vec4 t = s.mesh.texCoord(i, 0);
      s.mesh.setTexCoord(i, 0, t.x * 2.0f, t.y);
    }
    s.sphere = true;
  } else if (geom == "quad") {
    // Clip-space quad with identity transforms, white diffuse, (u,v) 0..1.
    s.mesh = d3dx::Mesh(d3d::FVF_XYZ | d3d::FVF_DIFFUSE | d3d::fvfTex(1), 4, 2);
    const float P[4][2] = {{-1, 1}, {1, 1}, {1, -1}, {-1, -1}};
    const float T[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (uint32_t i = 0; i < 4; ++i) {
      s.mesh.setPosition(i, {P[i][0], P[i][1], 0.5f});
      s.mesh.setDiffuse(i, 0xffffffff);
      s.mesh.setTexCoord(i, 0, T[i][0], T[i][1]);
    }
    s.mesh.indices = {0, 1, 2, 0, 2, 3};  // clockwise on screen
  } else if (geom == "sphere") {
    // 64x32 segments as the anchor; the texture wraps twice around.
    d3dx::Mesh m = d3dx::createTexturedSphere(1.0f, 64, 32);
    s.mesh = d3dx::cloneMeshFVF(m, d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(1));
    for (uint32_t i = 0; i < s.mesh.vertexCount(); ++i) {
      Vec4 t = s.mesh.texCoord(i, 0);
      s.mesh.setTexCoord(i, 0, t.x * 2.0f, t.y);
    }
    s.sphere = true;
  } else {
    fail("--geom: unknown geometry '{}' (expected quad or sphere)", geom);
  }
  return s;
}

// The anchor's sphere camera: projected radius 0.85 x half the screen diagonal; for a
// unit sphere at distance d, r_ndc = cot(fov/2) / sqrt(d^2 - 1).
struct SphereCamera {
  Matrix world, view, projection;
  float distance;
};
SphereCamera sphereCamera(int w, int h, float rotationY) {
  const float aspect = float(w) / float(h), fov = 3.14159265f / 3.0f;
  const float rNdc = 0.85f * std::sqrt(aspect * aspect + 1.0f);
  const float t = rNdc * std::tan(fov / 2);
  SphereCamera c;
  c.distance = std::sqrt(1.0f / (t * t) + 1.0f);
  c.world = matrixRotationY(rotationY);
  c.view = matrixLookAtLH({0, 0, -c.distance}, {0, 0, 0}, {0, 1, 0});
  c.projection = matrixPerspectiveFovLH(fov, aspect, 0.1f, 10.0f);
  return c;
}

// The anchor's texture workload (W1) as it wrote it in ps.1.1.
constexpr const char* kTextureBenchPS = "ps.1.1\ntex t0\nmov r0, t0\n";

// RacorX6 / RacorX9 on the anchor's scene: colour map in stage 0, normal map in stage
// 1, the seeds' ps.1.1 shader (data/shaders), the anchor's vertex shader and lights;
// `texture`: the same with the anchor's W1 pixel shader.
void setupShaderWorkload(Device& dev, const Scene& s, const std::string& workload, const TexturePtr& color,
                         const TexturePtr& normal, int w, int h) {
  for (int st = 0; st < 2; ++st) {
    dev.setTexture(st, st == 0 ? color : normal);
    dev.setSamplerState(st, SAMP_MINFILTER, 2);  // LINEAR
    dev.setSamplerState(st, SAMP_MAGFILTER, 2);
    dev.setSamplerState(st, SAMP_MIPFILTER, 1);  // POINT: GL_LINEAR_MIPMAP_NEAREST
  }
  scene::bindMesh(dev, s.mesh);
  dev.setVertexShader(dev.createVertexShader(shader::assembleTokens(kRacorXBenchVS, "<bench vs>")));
  if (workload == "texture")
    dev.setPixelShader(dev.createPixelShader(shader::assembleTokens(kTextureBenchPS, "<bench ps>")));
  else
    dev.setPixelShader(
        scene::racorx::loadPixelShader(dev, workload == "racorx6" ? "racorx6_ps11.psh" : "racorx9_ps11.psh"));
  Matrix mvp = Matrix::identity();
  Vec3 light{0.3f, 0.4f, -1.0f}, eye{0, 0, -2.0f};  // the anchor's quad light and eye, facing -z
  if (s.sphere) {
    // The anchor rotates by 0.6 and puts the light at (1.5, 1.2, 2.5) from the centre
    // toward the viewer; light and eye go to object space through the inverse world.
    const SphereCamera c = sphereCamera(w, h, 0.6f);
    mvp = c.world * c.view * c.projection;
    Matrix inv;
    if (!inverse(c.world, inv)) inv = Matrix::identity();
    light = transformCoord(Vec3{1.5f, 1.2f, -2.5f}, inv);
    eye = transformCoord(Vec3{0, 0, -c.distance}, inv);
    dev.setRenderState(RS_ZENABLE, ZB_TRUE);
    dev.setRenderState(RS_ZFUNC, CMP_LESS);
  }
  scene::racorx::setMatrix(dev, 0, mvp);
  scene::racorx::setVector(dev, 4, Vec4(light, 1));
  scene::racorx::setVector(dev, 5, Vec4(eye, 1));
  scene::racorx::setVector(dev, 6, Vec4(0.5f, 0.5f, 0.5f, 0.5f));
}

// Sets a vertex shader constant of an HLSL shader by name, where its constant table puts
// it; a matrix the compiler packed by columns (the HLSL default) goes in transposed, as
// ID3DXConstantTable::SetMatrix does.
void setVertexConstant(Device& dev, const shader::ShaderConstantTable& table, const char* name, Matrix m) {
  const shader::ShaderConstant* c = table.find(name);
  if (!c) return;  // optimised away
  if (c->cls == shader::ConstantClass::MatrixColumns) m = transpose(m);
  dev.setVertexShaderConstantF(uint32_t(c->registerIndex), &m.m[0][0], uint32_t(std::min(c->registerCount, 4)));
}
void setVertexConstant(Device& dev, const shader::ShaderConstantTable& table, const char* name, Vec4 v) {
  if (const shader::ShaderConstant* c = table.find(name))
    dev.setVertexShaderConstantF(uint32_t(c->registerIndex), &v.x, 1);
}

hlsl::CompileResult compileOrFail(const std::string& source, const std::string& path, const char* profile,
                                  const char* entry) {
  hlsl::CompileOptions o;
  o.profile = profile;
  o.entry = entry;
  hlsl::CompileResult r = hlsl::compile(source, path, o);
  if (!r.ok()) fail("{}", r.messages());
  return r;
}

// llvmpipe's `phong`: data/hlsl/point_light.hlsl compiled by refx as its header says (VS
// to vs_1_1, PS to ps_2_0) on the anchor's scene, light, eye and attenuation scale
// (uInvRange: 0.35 on the quad, 0.3 on the sphere). The seed fixes the scale in its
// vertex shader (`float LightRange = 1.0;`), so the anchor's value is compiled in its
// place. Colour map on the PS's ColorMapSampler (alpha = the specular mask), normal map
// on BumpMapSampler.
void setupPhongWorkload(Device& dev, const Scene& s, const TexturePtr& color, const TexturePtr& normal, int w,
                        int h) {
  const std::string path = std::string(REFX_DATA_DIR) + "/hlsl/point_light.hlsl";
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: cannot open the shader file", path);
  std::ostringstream text;
  text << in.rdbuf();
  std::string source = text.str();
  const std::string fixedRange = "float LightRange = 1.0;";
  const size_t at = source.find(fixedRange);
  if (at == std::string::npos) fail("{}: no '{}' to put the attenuation scale in", path, fixedRange);
  source.replace(at, fixedRange.size(), fmt::format("float LightRange = {};", s.sphere ? 0.3f : 0.35f));
  const hlsl::CompileResult vs = compileOrFail(source, path, "vs_1_1", "VS");
  const hlsl::CompileResult ps = compileOrFail(source, path, "ps_2_0", "PS");
  const auto vsTable = shader::readConstantTable(vs.shader);
  const auto psTable = shader::readConstantTable(ps.shader);
  if (!vsTable || !psTable) fail("{}: the compiled shaders have no constant table", path);

  scene::bindMesh(dev, s.mesh);
  // The mesh's FVF vertices, declared by semantic: the tangent is texture set 1.
  const FVFLayout layout = s.mesh.layout();
  VertexDeclaration decl;
  auto element = [&](int offset, uint8_t type, uint8_t usage) {
    VertexElement e;
    e.offset = uint16_t(offset);
    e.type = type;
    e.usage = usage;
    decl.elements.push_back(e);
  };
  element(layout.position, d3d::DECLTYPE_FLOAT3, d3d::DECLUSAGE_POSITION);
  element(layout.normal, d3d::DECLTYPE_FLOAT3, d3d::DECLUSAGE_NORMAL);
  element(layout.texCoord[0], d3d::DECLTYPE_FLOAT2, d3d::DECLUSAGE_TEXCOORD);
  element(layout.texCoord[1], d3d::DECLTYPE_FLOAT3, d3d::DECLUSAGE_TANGENT);
  dev.setVertexDeclaration(decl);
  dev.setVertexShader(dev.createVertexShader(vs.tokens));
  dev.setPixelShader(dev.createPixelShader(ps.tokens));

  const std::pair<const char*, const TexturePtr*> samplers[] = {{"ColorMapSampler", &color},
                                                                {"BumpMapSampler", &normal}};
  for (const auto& [name, tex] : samplers) {
    const shader::ShaderConstant* c = psTable->find(name);
    if (!c) fail("{}: the pixel shader has no sampler {}", path, name);
    const int st = c->registerIndex;
    dev.setTexture(st, *tex);
    dev.setSamplerState(st, SAMP_MINFILTER, 2);  // LINEAR
    dev.setSamplerState(st, SAMP_MAGFILTER, 2);
    dev.setSamplerState(st, SAMP_MIPFILTER, 1);  // POINT: GL_LINEAR_MIPMAP_NEAREST
  }
  Matrix world = Matrix::identity(), wvp = Matrix::identity();
  Vec3 light{0.3f, 0.4f, -1.0f}, eye{0, 0, -2.0f};  // the anchor's quad light and eye, facing -z
  if (s.sphere) {
    const SphereCamera c = sphereCamera(w, h, 0.6f);
    world = c.world;
    wvp = c.world * c.view * c.projection;
    light = {1.5f, 1.2f, -2.5f};  // world space: the sphere is at the origin
    eye = {0, 0, -c.distance};
    dev.setRenderState(RS_ZENABLE, ZB_TRUE);
    dev.setRenderState(RS_ZFUNC, CMP_LESS);
  }
  setVertexConstant(dev, *vsTable, "matWorldViewProj", wvp);
  setVertexConstant(dev, *vsTable, "matWorld", world);
  setVertexConstant(dev, *vsTable, "vecLightDir", Vec4(light, 1));
  setVertexConstant(dev, *vsTable, "vecEye", Vec4(eye, 1));
}

// RacorX10 (racorx10.fx) and RacorX11 (racorx_point_light.fx, technique PS11): their
// passes drawn with the bench's mesh, camera and colour / normal maps; the lookup
// textures (illumination map, point light texture, normalization cube map) and the
// light are the effects' own.
std::unique_ptr<effect::Effect> setupMultipassWorkload(Device& dev, const Scene& s, const std::string& workload,
                                                       const TexturePtr& color, const TexturePtr& normal, int w,
                                                       int h) {
  const std::string path =
      std::string(REFX_DATA_DIR) + (workload == "racorx10" ? "/effects/racorx10.fx" : "/effects/racorx_point_light.fx");
  std::unique_ptr<effect::Effect> fx = effect::Effect::fromFile(path);
  const effect::Handle technique = fx->techniqueByName("PS11");
  if (technique < 0) fail("{}: no technique PS11", path);
  const effect::TechniqueValidation v = fx->validateTechnique(technique, dev.caps());
  if (!v.ok) fail("{}: technique PS11: {}", path, v.reason);
  fx->setTechnique(technique);
  EffectScene textures({});
  for (const std::string& warning : textures.prepare(*fx))
    std::fprintf(stderr, "%s: %s\n", path.c_str(), warning.c_str());
  fx->setTexture(fx->parameterByName("ColorMap"), color);
  fx->setTexture(fx->parameterByName("NormalMap"), normal);
  Matrix world = Matrix::identity(), wvp = Matrix::identity();
  Vec3 eye{0, 0, -2.0f};
  if (s.sphere) {
    const SphereCamera c = sphereCamera(w, h, 0.6f);
    world = c.world;
    wvp = c.world * c.view * c.projection;
    eye = {0, 0, -c.distance};
  }
  fx->setMatrix(fx->parameterByName("mWorld"), world);
  fx->setMatrix(fx->parameterByName("mWVP"), wvp);
  fx->setVector(fx->parameterByName("vEye"), Vec4(eye, 1));
  scene::bindMesh(dev, s.mesh);
  return fx;
}

void setupDevice(Device& dev, const Scene& s, const TexturePtr& tex, int w, int h) {
  dev.setTexture(0, tex);
  dev.setSamplerState(0, SAMP_MINFILTER, 2);  // LINEAR
  dev.setSamplerState(0, SAMP_MAGFILTER, 2);
  dev.setSamplerState(0, SAMP_MIPFILTER, 1);  // POINT: GL_LINEAR_MIPMAP_NEAREST
  dev.setTextureStageState(0, TSS_COLOROP, TOP_MODULATE);
  dev.setTextureStageState(0, TSS_COLORARG1, TA_TEXTURE);
  dev.setTextureStageState(0, TSS_COLORARG2, TA_DIFFUSE);
  scene::bindMesh(dev, s.mesh);
  if (!s.sphere) {
    dev.setRenderState(RS_LIGHTING, 0);
    return;
  }
  const SphereCamera c = sphereCamera(w, h, 0.5f);
  dev.setTransform(TS_VIEW, c.view);
  dev.setTransform(TS_PROJECTION, c.projection);
  dev.setTransform(TS_WORLD, c.world);
  Light l;
  l.type = LIGHT_DIRECTIONAL;
  l.diffuse = {1, 1, 1, 1};
  l.direction = normalize(Vec3{-0.5f, -0.5f, 1.0f});
  dev.setLight(0, l);
  dev.lightEnable(0, true);
  Material m;
  m.diffuse = {1, 1, 1, 1};
  m.ambient = {0.25f, 0.25f, 0.25f, 1};
  dev.setMaterial(m);
  dev.setRenderState(RS_AMBIENT, 0xffffffff);
  dev.setRenderState(RS_ZENABLE, ZB_TRUE);
  dev.setRenderState(RS_ZFUNC, CMP_LESS);
}

int runBench(const BenchOptions& o) {
  // Every list is checked before the table starts, so a typo gives only the error.
  std::vector<std::pair<int, int>> sizes;
  for (const auto& size : splitList(o.sizes)) {
    int w = 0, h = 0;
    char rest = 0;
    if (std::sscanf(size.c_str(), "%dx%d%c", &w, &h, &rest) != 2 || w < 16 || h < 16 || w > 8192 || h > 8192)
      fail("--size: expected WxH between 16 and 8192, got '{}'", size);
    sizes.emplace_back(w, h);
  }
  if (sizes.empty()) fail("--size: expected WxH between 16 and 8192, got '{}'", o.sizes);
  const std::vector<std::string> workloads = splitList(o.workloads), geoms = splitList(o.geoms);
  for (const auto& wl : workloads)
    if (!findWorkload(wl)) fail("--workload: unknown workload '{}' (available: {})", wl, workloadNames());
  for (const auto& geom : geoms)
    if (geom != "quad" && geom != "sphere")
      fail("--geom: unknown geometry '{}' (available: quad, sphere)", geom);
  std::vector<int> threadCounts;
  for (const auto& ts : splitList(o.threads)) {
    int n = 0;
    const auto [end, ec] = std::from_chars(ts.data(), ts.data() + ts.size(), n);
    if (ec != std::errc() || end != ts.data() + ts.size() || n < 1 || n > 256)
      fail("--threads: expected counts 1-256, got '{}'", ts);
    threadCounts.push_back(n);
  }
  const bool tty = stderrIsTerminal();
  // Opened before any device, so that every worker thread counts.
  CycleCounter cycles;
  cycles.start();
  const PeakFlops peak = peakFlopsPerCycle();
  const TexturePtr tex = checkerTexture(1024);
  TexturePtr normal;  // made when a shader workload needs it
  std::printf("# cyc/px: cycles of all threads per shaded pixel (%s)\n", cycles.source().c_str());
  std::printf("# flop-cyc/px: FP32 FLOPs per pixel / %.1f FLOPs per cycle (%s FMA throughput, measured)\n",
              peak.perCycle, peak.isa);
  std::printf("%-10s %-7s %-10s %7s %9s %10s %12s %9s %12s\n", "workload", "geom", "res", "threads", "fps",
              "Mpix/s", "px/frame", "cyc/px", "flop-cyc/px");
  for (const auto& wl : workloads) {
    const Workload& workload = *findWorkload(wl);
    const bool shaded = wl != "fftexture";
    const bool multipass = wl == "racorx10" || wl == "racorx11";
    if (shaded && !normal) normal = bumpNormalTexture(1024);
    for (const auto& geom : geoms) {
      const Scene scene = makeScene(geom, shaded);
      for (const auto& [w, h] : sizes) {
        const std::string res = fmt::format("{}x{}", w, h);
        for (const int threads : threadCounts) {
          DeviceOptions opt;
          opt.threads = threads;
          opt.precision = o.hardware ? Precision::Hardware : Precision::Exact;
          // The ps.1.1 workloads run on a DirectX 8 part's profile (values in [-1, 1]),
          // the HLSL one on a DirectX 9 part's.
          Device dev(wl == "phong" ? loadCapsProfile("dx9") : shaded ? loadCapsProfile("dx8") : CapsProfile{}, opt);
          dev.setRenderTarget(Texture::create2D(Format::A8R8G8B8, w, h));
          dev.setDepthStencilSurface(std::make_shared<DepthStencilSurface>(w, h));
          std::unique_ptr<effect::Effect> fx;
          if (multipass)
            fx = setupMultipassWorkload(dev, scene, wl, tex, normal, w, h);
          else if (wl == "phong")
            setupPhongWorkload(dev, scene, tex, normal, w, h);
          else if (shaded)
            setupShaderWorkload(dev, scene, wl, tex, normal, w, h);
          else
            setupDevice(dev, scene, tex, w, h);
          auto draw = [&] {
            dev.drawIndexedPrimitive(PT_TRIANGLELIST, 0, 0, scene.mesh.vertexCount(), 0, scene.mesh.faceCount());
          };
          auto frame = [&] {
            dev.clear(CLEAR_TARGET | CLEAR_ZBUFFER, 0xff000000, 1.0f, 0);
            if (!fx) return draw();
            const int passes = fx->begin(dev, 0);
            for (int p = 0; p < passes; ++p) {
              fx->beginPass(p);
              draw();
              fx->endPass();
            }
            fx->end();
          };
          for (int i = 0; i < 3; ++i) frame();  // warm-up: decoded texture levels, caches
          DrawStats total = dev.stats();          // plans and programs are built here
          dev.resetStats();
          frame();
          const uint64_t pixelsPerFrame = dev.stats().pixelsShaded;
          int frames = 0;
          const auto t0 = std::chrono::steady_clock::now();
          const double c0 = cycles.read();
          double elapsed = 0;
          std::vector<double> frameMicroseconds;  // each timed frame's wall time
          while (o.frames > 0 ? frames < o.frames : elapsed < o.minTime) {
            const auto frameStart = std::chrono::steady_clock::now();
            frame();
            ++frames;
            const auto frameEnd = std::chrono::steady_clock::now();
            frameMicroseconds.push_back(std::chrono::duration<double, std::micro>(frameEnd - frameStart).count());
            elapsed = std::chrono::duration<double>(frameEnd - t0).count();
            if (tty)
              std::fprintf(stderr, "\r%s %s %s %d thr: %d frames, %.1fs", wl.c_str(), geom.c_str(), res.c_str(),
                           threads, frames, elapsed);
          }
          const double spent = cycles.read() - c0;
          if (tty) std::fprintf(stderr, "\r%-70s\r", "");
          const double fps = frames / elapsed;
          const double pixels = double(frames) * double(pixelsPerFrame);
          std::printf("%-10s %-7s %-10s %7d %9.1f %10.1f %12llu %9.1f %12.2f\n", wl.c_str(), geom.c_str(),
                      res.c_str(), threads, fps, fps * double(pixelsPerFrame) / 1e6,
                      static_cast<unsigned long long>(pixelsPerFrame), pixels > 0 ? spent / pixels : 0.0,
                      double(workload.flopsPerPixel) / peak.perCycle);
          if (o.verbose) {
            // Over every frame of the row, warm-up included (where plans are built).
            const DrawStats& run = dev.stats();
            total.planCacheHits += run.planCacheHits;
            total.planCacheMisses += run.planCacheMisses;
            total.draws += run.draws;
            total.samplePassthroughDraws += run.samplePassthroughDraws;
            total.groupedLookupDraws += run.groupedLookupDraws;
            total.programBuilds.insert(total.programBuilds.end(), run.programBuilds.begin(), run.programBuilds.end());
            const uint64_t lookups = total.planCacheHits + total.planCacheMisses;
            std::printf("  plan cache: %llu hits, %llu misses", static_cast<unsigned long long>(total.planCacheHits),
                        static_cast<unsigned long long>(total.planCacheMisses));
            if (lookups) std::printf(", hit rate %.1f%%", 100.0 * double(total.planCacheHits) / double(lookups));
            if (total.samplePassthroughDraws)
              std::printf("; sample passthrough: %llu of %llu draws stored texture samples as bytes",
                          static_cast<unsigned long long>(total.samplePassthroughDraws),
                          static_cast<unsigned long long>(total.draws));
            if (total.groupedLookupDraws)
              std::printf("; grouped lookups: %llu of %llu draws sampled %d blocks at a time",
                          static_cast<unsigned long long>(total.groupedLookupDraws),
                          static_cast<unsigned long long>(total.draws), refx::kMaxSampleGroup);
            // The timed frames and the one before them that counted the pixels (the
            // stats were reset before it).
            const DrawStats::StageTimes& t = run.stageMicroseconds;
            const double counted = double(frames + 1);
            std::printf("\n  per frame: plan %.1f us, vertex %.1f us, setup %.1f us, binning and shading %.1f us"
                        " (frame %.1f us)",
                        t.plan / counted, t.vertex / counted, t.setup / counted, t.raster / counted,
                        1e6 * elapsed / frames);
            // A busy machine shows as a spread between the fast frames and the slow ones.
            std::sort(frameMicroseconds.begin(), frameMicroseconds.end());
            std::printf("\n  frame times: min %.1f us, p10 %.1f us, median %.1f us, p90 %.1f us, max %.1f us",
                        frameMicroseconds.front(), nearestRank(frameMicroseconds, 0.1),
                        nearestRank(frameMicroseconds, 0.5), nearestRank(frameMicroseconds, 0.9),
                        frameMicroseconds.back());
            std::printf("\n  program builds: %zu\n", total.programBuilds.size());
            for (const DrawStats::ProgramBuild& b : total.programBuilds)
              std::printf("    %-32s %5d instructions %10.1f us  %s\n", b.name.c_str(), b.instructions,
                          b.microseconds, b.backend.c_str());
          }
          std::fflush(stdout);
          if (!o.png.empty()) savePNG(*dev.renderTarget(), o.png);
        }
      }
    }
  }
  return 0;
}

}  // namespace

Action addBenchCommand(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "measure Mpixels/s and cycles/pixel on the llvmpipe anchor's workloads");
  cmd->add_option("--workload", o->workloads,
                  "comma-separated workloads: texture, racorx6, racorx9, phong, racorx10, racorx11, fftexture")
      ->capture_default_str();
  cmd->add_option("--geom", o->geoms, "comma-separated geometries: quad, sphere")->capture_default_str();
  cmd->add_option("--threads", o->threads, "comma-separated thread counts")->capture_default_str();
  cmd->add_option("--size", o->sizes, "comma-separated render target sizes WxH")->capture_default_str();
  cmd->add_option("--min-time", o->minTime, "seconds per measurement")->check(CLI::Range(0.01, 600.0))->capture_default_str();
  cmd->add_option("--frames", o->frames, "measure exactly N frames instead of --min-time (for profilers)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--png", o->png, "write the last frame to this PNG");
  cmd->add_flag("--hardware", o->hardware, "shader workloads in the `hardware` precision model");
  cmd->add_flag("-v,--verbose", o->verbose, "after each row: plan-cache hits and misses, every program build");
  return [o] { return runBench(*o); };
}

}  // namespace refx::cli
