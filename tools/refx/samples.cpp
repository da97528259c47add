// The built-in samples that are not effects: the two multi-pass blends later used by
// RacorX10/11 on a simple scene, and the D3DX shapes with fixed-function lighting. The
// seeds' examples themselves are effect files (samples_effects.cpp), whose techniques
// are chosen by validation.
#include "samples.h"

#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "refx/d3dx/mesh.h"
#include "refx/d3dx/sample_assets.h"
#include "refx/d3dx/teapot.h"
#include "refx/d3dx/texture_fill.h"

namespace refx::samples {

namespace {

using namespace d3d;

constexpr float kPi = 3.14159265358979f;

// Assets are made once per process and shared by the samples.
struct Assets {
  TexturePtr brick = d3dx::brick(256, 0);
  TexturePtr attenuation = makeAttenuationMap(64);

  // RacorX10's 2D attenuation map: 1 - (x^2 + y^2) over [-1,1]^2, clamped.
  static TexturePtr makeAttenuationMap(int size) {
    auto t = Texture::create2D(Format::A8R8G8B8, size, size, 1);
    d3dx::fillTexture(*t, [](Vec2 p, Vec2) {
      const float x = 2 * p.x - 1, y = 2 * p.y - 1;
      const float a = std::max(0.0f, 1.0f - (x * x + y * y));
      return Vec4(a, a, a, 1);
    });
    return t;
  }
};

const Assets& assets() {
  static const Assets a;
  return a;
}

void drawMesh(Device& dev, const d3dx::Mesh& m) {
  dev.drawIndexedPrimitive(PT_TRIANGLELIST, 0, 0, m.vertexCount(), 0, m.faceCount());
}

void linearSampling(Device& dev, int sampler, bool mips) {
  dev.setSamplerState(sampler, SAMP_MINFILTER, 2);
  dev.setSamplerState(sampler, SAMP_MAGFILTER, 2);
  dev.setSamplerState(sampler, SAMP_MIPFILTER, mips ? 2 : 0);
}

std::string describe(const ValidationResult& v) {
  return v.ok ? fmt::format("valid ({} pass{})", v.passes, v.passes == 1 ? "" : "es") : v.reason;
}

// Direction toward the light, world space.
const Vec3 kLightDir = normalize(Vec3{-0.6f, 0.5f, -0.7f});

// ---------------------------------------------------------------- multi-pass blends
// A brick floor seen in perspective, lit by a point light through RacorX10's
// attenuation map: pass 1 lays down the base texture, pass 2 multiplies the
// attenuation in (SRCBLEND ZERO / DESTBLEND SRCCOLOR); the ONE/ONE sample adds a
// coloured highlight pass on top.
struct FloorVertex {
  float x, y, z;
  float u0, v0;  // base texture
  float u1, v1;  // attenuation / light-map coordinates
};

SampleResult renderMultipass(Device& dev, bool additive) {
  SampleResult r;
  const Assets& a = assets();
  const Texture& rt = *dev.renderTarget();
  dev.setTransform(TS_VIEW, matrixLookAtLH({0, 2.2f, -3.2f}, {0, 0, 0.4f}, {0, 1, 0}));
  dev.setTransform(TS_PROJECTION,
                   matrixPerspectiveFovLH(kPi / 4, float(rt.width()) / float(rt.height()), 0.1f, 100.0f));
  dev.setRenderState(RS_LIGHTING, 0);
  dev.setRenderState(RS_CULLMODE, CULL_NONE);
  // Floor: 8x8 grid over [-2,2]^2 at y = 0; light above (0.3, ., 0.2) with radius 1.6.
  const int n = 8;
  const float lightX = 0.3f, lightZ = 0.2f, radius = 1.6f;
  std::vector<FloorVertex> v;
  std::vector<uint16_t> idx;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const float x = -2 + 4.0f * i / n, z = -2 + 4.0f * j / n;
      v.push_back({x, 0, z, x, z, 0.5f + (x - lightX) / (2 * radius), 0.5f - (z - lightZ) / (2 * radius)});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint16_t p = uint16_t(j * (n + 1) + i), q = uint16_t(p + n + 1);
      idx.insert(idx.end(), {p, q, uint16_t(p + 1), uint16_t(p + 1), q, uint16_t(q + 1)});
    }
  dev.setFVF(d3d::FVF_XYZ | d3d::fvfTex(2));
  auto draw = [&] {
    dev.drawIndexedPrimitiveUP(PT_TRIANGLELIST, 0, uint32_t(v.size()), uint32_t(idx.size() / 3),
                               idx.data(), false, v.data(), sizeof(FloorVertex));
  };
  // Pass 1: base texture.
  dev.setTexture(0, a.brick);
  dev.setTextureStageState(0, TSS_COLOROP, TOP_SELECTARG1);
  dev.setTextureStageState(0, TSS_COLORARG1, TA_TEXTURE);
  dev.setTextureStageState(0, TSS_TEXCOORDINDEX, 0);
  dev.setSamplerState(0, SAMP_ADDRESSU, 1);
  dev.setSamplerState(0, SAMP_ADDRESSV, 1);
  linearSampling(dev, 0, true);
  r.notes.push_back("pass 1 (base): " + describe(dev.validate()));
  draw();
  // Pass 2: attenuation, dest = dest * src.
  dev.setTexture(0, a.attenuation);
  dev.setTextureStageState(0, TSS_TEXCOORDINDEX, 1);
  dev.setSamplerState(0, SAMP_ADDRESSU, 3);  // CLAMP: no light beyond the radius
  dev.setSamplerState(0, SAMP_ADDRESSV, 3);
  dev.setRenderState(RS_ALPHABLENDENABLE, 1);
  dev.setRenderState(RS_SRCBLEND, BLEND_ZERO);
  dev.setRenderState(RS_DESTBLEND, BLEND_SRCCOLOR);
  r.notes.push_back("pass 2 (attenuation, ZERO/SRCCOLOR): " + describe(dev.validate()));
  draw();
  r.technique = "2 passes: base texture, then attenuation map with SRCBLEND ZERO / DESTBLEND SRCCOLOR";
  if (additive) {
    // Pass 3: warm highlight added with ONE/ONE.
    dev.setTextureStageState(0, TSS_COLOROP, TOP_MODULATE);
    dev.setTextureStageState(0, TSS_COLORARG1, TA_TEXTURE);
    dev.setTextureStageState(0, TSS_COLORARG2, TA_TFACTOR);
    dev.setRenderState(RS_TEXTUREFACTOR, 0xff704020);
    dev.setRenderState(RS_SRCBLEND, BLEND_ONE);
    dev.setRenderState(RS_DESTBLEND, BLEND_ONE);
    r.notes.push_back("pass 3 (highlight, ONE/ONE): " + describe(dev.validate()));
    draw();
    r.technique = "3 passes: base, attenuation (ZERO/SRCCOLOR), then a highlight added with ONE/ONE";
  }
  r.validation = r.notes.back();
  return r;
}

// ---------------------------------------------------------------- D3DX shapes
// The D3DX shape generators lit by the fixed-function pipeline: one directional
// light with specular, a different material per shape.
SampleResult renderShapes(Device& dev) {
  SampleResult r;
  const Texture& rt = *dev.renderTarget();
  dev.setTransform(TS_VIEW, matrixLookAtLH({0, 0.6f, -6.0f}, {0, 0, 0}, {0, 1, 0}));
  dev.setTransform(TS_PROJECTION,
                   matrixPerspectiveFovLH(kPi / 4, float(rt.width()) / float(rt.height()), 0.1f, 100.0f));
  dev.setRenderState(RS_ZENABLE, ZB_TRUE);
  dev.setRenderState(RS_SPECULARENABLE, 1);
  dev.setRenderState(RS_NORMALIZENORMALS, 1);
  dev.setRenderState(RS_AMBIENT, 0xff303030);
  Light l;
  l.type = LIGHT_DIRECTIONAL;
  l.diffuse = {1, 1, 1, 1};
  l.specular = {1, 1, 1, 1};
  l.direction = -kLightDir;
  dev.setLight(0, l);
  dev.lightEnable(0, true);
  dev.setTextureStageState(0, TSS_COLOROP, TOP_SELECTARG1);
  dev.setTextureStageState(0, TSS_COLORARG1, TA_DIFFUSE);
  struct Item {
    d3dx::Mesh mesh;
    Matrix world;
    Color4 color;
  };
  const Matrix tilt = matrixRotationX(-0.5f) * matrixRotationY(0.6f);
  const Item items[] = {
      {d3dx::createTeapot(6), matrixScaling(0.45f, 0.45f, 0.45f) * matrixRotationY(0.5f) * matrixTranslation(-1.5f, 0.9f, 0),
       {0.9f, 0.9f, 0.95f, 1}},
      {d3dx::createSphere(0.7f, 24, 12), matrixTranslation(0.5f, 0.9f, 0), {0.9f, 0.3f, 0.2f, 1}},
      {d3dx::createBox(1.0f, 1.0f, 1.0f), tilt * matrixTranslation(2.0f, 0.9f, 0), {0.3f, 0.7f, 0.3f, 1}},
      {d3dx::createCylinder(0.45f, 0.3f, 1.2f, 20, 3), matrixRotationX(kPi / 2 + 0.3f) * matrixTranslation(-0.9f, -1.0f, 0),
       {0.3f, 0.5f, 0.9f, 1}},
      {d3dx::createTorus(0.2f, 0.6f, 16, 32), matrixRotationX(-0.9f) * matrixTranslation(1.1f, -1.0f, 0),
       {0.9f, 0.7f, 0.2f, 1}},
  };
  for (const Item& it : items) {
    Material m;
    m.diffuse = it.color;
    m.ambient = it.color;
    m.specular = {0.6f, 0.6f, 0.6f, 1};
    m.power = 24;
    dev.setMaterial(m);
    dev.setTransform(TS_WORLD, it.world);
    scene::bindMesh(dev, it.mesh);
    drawMesh(dev, it.mesh);
  }
  r.technique = "fixed-function lighting: directional light, specular (power 24)";
  r.validation = describe(dev.validate());
  r.notes.push_back("teapot (Newell's 32 patches), D3DXCreateSphere, Box, Cylinder, Torus");
  return r;
}

}  // namespace


const std::vector<Sample>& allSamples() {
  static const std::vector<Sample> samples = {
      {"multipass-modulate", "Two passes: SRCBLEND ZERO / DESTBLEND SRCCOLOR (attenuation map)",
       "the RacorX10 blend on a simple scene", [](Device& d) { return renderMultipass(d, false); }},
      {"multipass-add", "Three passes adding a highlight with ONE/ONE",
       "the RacorX11 blend on a simple scene", [](Device& d) { return renderMultipass(d, true); }},
      {"d3dx-shapes", "D3DX shapes: teapot, sphere, box, cylinder, torus with vertex lighting",
       "the D3DX helpers of the seeds (D3DXCreate*, the Utah teapot)", renderShapes},
  };
  static const std::vector<Sample> all = [] {
    std::vector<Sample> v = samples;
    const auto& effects = effectSamples();
    v.insert(v.end(), effects.begin(), effects.end());
    return v;
  }();
  return all;
}

}  // namespace refx::samples
