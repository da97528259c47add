// `refx bench`: Mpixels/s of the device on the workloads llvmpipe is measured on
// (../shared/anchors/llvmpipe_bench): a full-screen quad and a lit sphere.
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
  std::string png;
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

struct Scene {
  d3dx::Mesh mesh;
  bool sphere = false;
};

Scene makeScene(const std::string& geom) {
  Scene s;
  if (geom == "quad") {
    // Clip-space quad with identity transforms, white diffuse, (u,v) 0..1.
    s.mesh = d3dx::Mesh(d3dx::fvf::XYZ | d3dx::fvf::DIFFUSE | d3dx::fvf::tex(1), 4, 2);
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
    s.mesh = d3dx::cloneMeshFVF(m, d3dx::fvf::XYZ | d3dx::fvf::NORMAL | d3dx::fvf::tex(1));
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

void setupDevice(Device& dev, const Scene& s, const TexturePtr& tex, int w, int h) {
  dev.setTexture(0, tex);
  dev.setSamplerState(0, SAMP_MINFILTER, 2);  // LINEAR
  dev.setSamplerState(0, SAMP_MAGFILTER, 2);
  dev.setSamplerState(0, SAMP_MIPFILTER, 1);  // POINT: GL_LINEAR_MIPMAP_NEAREST
  dev.setTextureStageState(0, TSS_COLOROP, TOP_MODULATE);
  dev.setTextureStageState(0, TSS_COLORARG1, TA_TEXTURE);
  dev.setTextureStageState(0, TSS_COLORARG2, TA_DIFFUSE);
  samples::bindMesh(dev, s.mesh);
  if (!s.sphere) {
    dev.setRenderState(RS_LIGHTING, 0);
    return;
  }
  // Projected radius 0.85 x half the screen diagonal, as the anchor: for a unit
  // sphere at distance d, r_ndc = cot(fov/2) / sqrt(d^2 - 1).
  const float aspect = float(w) / float(h), fov = 3.14159265f / 3.0f;
  const float rNdc = 0.85f * std::sqrt(aspect * aspect + 1.0f);
  const float t = rNdc * std::tan(fov / 2);
  const float d = std::sqrt(1.0f / (t * t) + 1.0f);
  dev.setTransform(TS_VIEW, matrixLookAtLH({0, 0, -d}, {0, 0, 0}, {0, 1, 0}));
  dev.setTransform(TS_PROJECTION, matrixPerspectiveFovLH(fov, aspect, 0.1f, 10.0f));
  dev.setTransform(TS_WORLD, matrixRotationY(0.5f));
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
  const bool tty = stderrIsTerminal();
  const TexturePtr tex = checkerTexture(1024);
  std::printf("%-10s %-7s %-10s %7s %9s %10s %12s\n", "workload", "geom", "res", "threads", "fps",
              "Mpix/s", "px/frame");
  for (const auto& wl : splitList(o.workloads)) {
    if (wl != "texture") fail("--workload: unknown workload '{}' (available: texture)", wl);
    for (const auto& geom : splitList(o.geoms)) {
      const Scene scene = makeScene(geom);
      for (const auto& ts : splitList(o.threads)) {
        const int threads = std::atoi(ts.c_str());
        if (threads < 1 || threads > 256) fail("--threads: expected counts 1-256, got '{}'", ts);
        DeviceOptions opt;
        opt.threads = threads;
        Device dev(CapsProfile{}, opt);
        dev.setRenderTarget(Texture::create2D(Format::A8R8G8B8, w, h));
        dev.setDepthStencilSurface(std::make_shared<DepthStencilSurface>(w, h));
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
        while (elapsed < o.minTime) {
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
  cmd->add_option("--workload", o->workloads, "comma-separated workloads: texture")->capture_default_str();
  cmd->add_option("--geom", o->geoms, "comma-separated geometries: quad, sphere")->capture_default_str();
  cmd->add_option("--threads", o->threads, "comma-separated thread counts")->capture_default_str();
  cmd->add_option("--size", o->size, "render target WxH")->capture_default_str();
  cmd->add_option("--min-time", o->minTime, "seconds per measurement")->check(CLI::Range(0.01, 600.0))->capture_default_str();
  cmd->add_option("--png", o->png, "write the last frame to this PNG");
  return [o] { return runBench(*o); };
}

}  // namespace refx::cli
