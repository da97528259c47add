// `refx bench`: Mpixels/s of the device on the workloads llvmpipe is measured on
// (../shared/anchors/llvmpipe_bench): a full-screen quad and a lit sphere, textured
// (`texture`, fixed function), or shaded by RacorX6's ps.1.1 diffuse bump shader
// (`racorx6`, llvmpipe's `diffuse`) or RacorX9's ps.1.1 diffuse + specular shader
// (`racorx9`, llvmpipe's `specular`), with the same textures, geometry and lights.
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

#include <fmt/format.h>

#include "commands.h"
#include "refx/core/diagnostics.h"
#include "refx/d3dx/mesh.h"
#include "refx/pipeline/device.h"
#include "refx/resource/image_io.h"
#include "refx/shader/assembler.h"
#include "refx/scene/racorx_scene.h"
#include "samples.h"

namespace refx::cli {

namespace {

using namespace d3d;

struct BenchOptions {
  std::string workloads = "texture";
  std::string geoms = "quad,sphere";
  std::string threads = "1,2";
  std::string size = "1024x768";
  double minTime = 2.0;
  int frames = 0;  // > 0: exactly this many measured frames, whatever the time
  std::string png;
  bool hardware = false;
};

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

// RacorX6 / RacorX9 on the anchor's scene: colour map in stage 0, normal map in stage
// 1, the seeds' ps.1.1 shader (data/shaders), the anchor's vertex shader and lights.
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
  dev.setPixelShader(scene::racorx::loadPixelShader(dev, workload == "racorx6" ? "racorx6_ps11.psh" : "racorx9_ps11.psh"));
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
  int w = 0, h = 0;
  if (std::sscanf(o.size.c_str(), "%dx%d", &w, &h) != 2 || w < 16 || h < 16 || w > 8192 || h > 8192)
    fail("--size: expected WxH between 16 and 8192, got '{}'", o.size);
  // Every list is checked before the table starts, so a typo gives only the error.
  const std::vector<std::string> workloads = splitList(o.workloads), geoms = splitList(o.geoms);
  for (const auto& wl : workloads)
    if (wl != "texture" && wl != "racorx6" && wl != "racorx9")
      fail("--workload: unknown workload '{}' (available: texture, racorx6, racorx9)", wl);
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
  const TexturePtr tex = checkerTexture(1024);
  TexturePtr normal;  // made when a shader workload needs it
  std::printf("%-10s %-7s %-10s %7s %9s %10s %12s\n", "workload", "geom", "res", "threads", "fps",
              "Mpix/s", "px/frame");
  for (const auto& wl : workloads) {
    const bool shaded = wl != "texture";
    if (shaded && !normal) normal = bumpNormalTexture(1024);
    for (const auto& geom : geoms) {
      const Scene scene = makeScene(geom, shaded);
      for (const int threads : threadCounts) {
        DeviceOptions opt;
        opt.threads = threads;
        opt.precision = o.hardware ? Precision::Hardware : Precision::Exact;
        // The shader workloads run on a DirectX 8 part's profile (ps.1.1, values in [-1, 1]).
        Device dev(shaded ? loadCapsProfile("dx8") : CapsProfile{}, opt);
        dev.setRenderTarget(Texture::create2D(Format::A8R8G8B8, w, h));
        dev.setDepthStencilSurface(std::make_shared<DepthStencilSurface>(w, h));
        if (shaded)
          setupShaderWorkload(dev, scene, wl, tex, normal, w, h);
        else
          setupDevice(dev, scene, tex, w, h);
        auto frame = [&] {
          dev.clear(CLEAR_TARGET | CLEAR_ZBUFFER, 0xff000000, 1.0f, 0);
          dev.drawIndexedPrimitive(PT_TRIANGLELIST, 0, 0, scene.mesh.vertexCount(), 0,
                                   scene.mesh.faceCount());
        };
        for (int i = 0; i < 3; ++i) frame();  // warm-up: decoded texture levels, caches
        dev.resetStats();
        frame();
        const uint64_t pixelsPerFrame = dev.stats().pixelsShaded;
        int frames = 0;
        const auto t0 = std::chrono::steady_clock::now();
        double elapsed = 0;
        while (o.frames > 0 ? frames < o.frames : elapsed < o.minTime) {
          frame();
          ++frames;
          elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          if (tty)
            std::fprintf(stderr, "\r%s %s %d thr: %d frames, %.1fs", wl.c_str(), geom.c_str(),
                         threads, frames, elapsed);
        }
        if (tty) std::fprintf(stderr, "\r%-60s\r", "");
        const double fps = frames / elapsed;
        std::printf("%-10s %-7s %-10s %7d %9.1f %10.1f %12llu\n", wl.c_str(), geom.c_str(),
                    o.size.c_str(), threads, fps, fps * double(pixelsPerFrame) / 1e6,
                    static_cast<unsigned long long>(pixelsPerFrame));
        std::fflush(stdout);
        if (!o.png.empty()) savePNG(*dev.renderTarget(), o.png);
      }
    }
  }
  return 0;
}

}  // namespace

Action addBenchCommand(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "measure Mpixels/s on the llvmpipe anchor's workloads");
  cmd->add_option("--workload", o->workloads, "comma-separated workloads: texture, racorx6, racorx9")
      ->capture_default_str();
  cmd->add_option("--geom", o->geoms, "comma-separated geometries: quad, sphere")->capture_default_str();
  cmd->add_option("--threads", o->threads, "comma-separated thread counts")->capture_default_str();
  cmd->add_option("--size", o->size, "render target WxH")->capture_default_str();
  cmd->add_option("--min-time", o->minTime, "seconds per measurement")->check(CLI::Range(0.01, 600.0))->capture_default_str();
  cmd->add_option("--frames", o->frames, "measure exactly N frames instead of --min-time (for profilers)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--png", o->png, "write the last frame to this PNG");
  cmd->add_flag("--hardware", o->hardware, "shader workloads in the `hardware` precision model");
  return [o] { return runBench(*o); };
}

}  // namespace refx::cli
