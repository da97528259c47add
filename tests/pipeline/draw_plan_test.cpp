// The device's DrawPlan cache: which state changes reuse a plan and which build a new
// one, and fixed-function values (TFACTOR, fog, material) read from constants, so a
// cached plan draws each draw's values.
//
// The key holds every render state except the values listed in draw_plan.cpp
// (TEXTUREFACTOR, FOG{COLOR,START,END,DENSITY}, AMBIENT, TWEENFACTOR, POINTSIZE*,
// POINTSCALE_*, ALPHAREF, STENCIL{REF,MASK,WRITEMASK}, BLENDFACTOR, DEPTHBIAS,
// SLOPESCALEDEPTHBIAS, CULLMODE, FILLMODE, SCISSORTESTENABLE, CLIPPLANEENABLE, CLIPPING,
// POINTSPRITEENABLE) plus whether FOGSTART = FOGEND; every texture stage state except
// BUMPENVMAT*, BUMPENVL* and CONSTANT; every sampler state; per sampler whether a
// texture is bound and its type; the shaders; per light whether it is on, its type,
// which colours are black and whether its falloff is 1; whether the projection is
// perspective; the vertex declaration; the render targets' formats and whether a depth
// buffer is bound. With a vertex shader the states only fixed-function T&L reads
// (LIGHTING, VERTEXBLEND, material sources, TEXCOORDINDEX, the lights ...) are left out,
// with a pixel shader the texture stages' ops and arguments. Never in it: constants,
// transforms, material and light values, viewport, the textures themselves and the
// vertices.
#include <gtest/gtest.h>

#include <cstdlib>
#include <functional>
#include <string>

#include "device_helpers.h"
#include "pipeline/draw_plan.h"
#include "refx/shader/assembler.h"

using namespace refx;
using namespace refx::test;
using namespace refx::d3d;

namespace {

// A 4x4 target covered by two pretransformed triangles at depth z.
void quad(Device& dev, uint32_t diffuse, float z = 0.5f) {
  drawTL(dev, PT_TRIANGLESTRIP,
         {{0, 0, z, 1, diffuse, 0, 0}, {4, 0, z, 1, diffuse, 1, 0}, {0, 4, z, 1, diffuse, 0, 1},
          {4, 4, z, 1, diffuse, 1, 1}});
}

struct Counts {
  uint64_t hits, misses;
};
Counts counts(const Device& dev) { return {dev.stats().planCacheHits, dev.stats().planCacheMisses}; }

TEST(DrawPlanCache, HitWhenOnlyValuesChange) {
  auto dev = makeDevice(4, 4);
  dev->setTextureStageState(0, TSS_COLOROP, TOP_MODULATE);
  dev->setTextureStageState(0, TSS_COLORARG1, TA_TEXTURE);
  dev->setTextureStageState(0, TSS_COLORARG2, TA_TFACTOR);
  dev->setTexture(0, texel(0xff808080));
  dev->resetStats();
  quad(*dev, 0xffffffff);
  EXPECT_EQ(counts(*dev).misses, 1u);
  EXPECT_EQ(counts(*dev).hits, 0u);

  const float c[4] = {1, 2, 3, 4};
  std::vector<std::function<void()>> valueChanges = {
      [&] { dev->setVertexShaderConstantF(0, c, 1); },
      [&] { dev->setPixelShaderConstantF(3, c, 1); },
      [&] { dev->setTransform(TS_WORLD, matrixTranslation(1, 2, 3)); },
      [&] { dev->setTransform(TS_VIEW, matrixTranslation(0, 0, 5)); },
      [&] { dev->setTransform(TS_TEXTURE0, matrixTranslation(0.5f, 0, 0)); },
      [&] { dev->setTexture(0, texel(0xff00ff00)); },  // another texture of the same type
      [&] { dev->setRenderState(RS_TEXTUREFACTOR, 0x11223344); },
      [&] { dev->setRenderState(RS_FOGCOLOR, 0x00ff0000); },
      [&] { dev->setRenderState(RS_AMBIENT, 0x00404040); },
      [&] { dev->setRenderState(RS_BLENDFACTOR, 0x80808080); },
      [&] { dev->setRenderState(RS_ALPHAREF, 0x40); },
      [&] { dev->setTextureStageState(0, TSS_CONSTANT, 0xff00ff00); },
      [&] { dev->setTextureStageState(0, TSS_BUMPENVMAT00, floatBits(0.5f)); },
      [&] {
        Material m;
        m.diffuse = {0.5f, 0.5f, 0.5f, 1};
        dev->setMaterial(m);
      },
      [&] { dev->setViewport(Viewport{0, 0, 2, 2, 0, 1}); },
  };
  for (size_t i = 0; i < valueChanges.size(); ++i) {
    valueChanges[i]();
    quad(*dev, 0xffffffff);
    EXPECT_EQ(counts(*dev).misses, 1u) << "change " << i;
    EXPECT_EQ(counts(*dev).hits, i + 1) << "change " << i;
  }
}

TEST(DrawPlanCache, MissWhenBlendOrStageOpChanges) {
  auto dev = makeDevice(4, 4);
  useDiffuseOnly(*dev);
  dev->resetStats();
  quad(*dev, 0xffffffff);
  dev->setRenderState(RS_ALPHABLENDENABLE, 1);
  quad(*dev, 0xffffffff);
  EXPECT_EQ(counts(*dev).misses, 2u);
  dev->setRenderState(RS_SRCBLEND, BLEND_SRCALPHA);  // D3D9's default is ONE
  quad(*dev, 0xffffffff);
  EXPECT_EQ(counts(*dev).misses, 3u);
  dev->setTextureStageState(0, TSS_COLOROP, TOP_SELECTARG2);
  quad(*dev, 0xffffffff);
  EXPECT_EQ(counts(*dev).misses, 4u);
  EXPECT_EQ(counts(*dev).hits, 0u);
  // Back to a state drawn before: its plan is still cached.
  dev->setRenderState(RS_ALPHABLENDENABLE, 0);
  dev->setRenderState(RS_SRCBLEND, BLEND_ONE);
  dev->setTextureStageState(0, TSS_COLOROP, TOP_SELECTARG1);
  quad(*dev, 0xffffffff);
  EXPECT_EQ(counts(*dev).misses, 4u);
  EXPECT_EQ(counts(*dev).hits, 1u);
}

// Binding a texture where none was (or a cube where a 2D was) changes the programs.
TEST(DrawPlanCache, MissWhenATextureIsBoundOrUnbound) {
  auto dev = makeDevice(4, 4);
  dev->resetStats();
  quad(*dev, 0xffffffff);
  dev->setTexture(0, texel(0xff808080));
  quad(*dev, 0xffffffff);
  dev->setTexture(0, nullptr);
  quad(*dev, 0xffffffff);
  EXPECT_EQ(counts(*dev).misses, 2u);
  EXPECT_EQ(counts(*dev).hits, 1u);
}

// With shaders bound, the states only fixed function reads do not make a new plan.
TEST(DrawPlanCache, FixedFunctionStatesOutOfTheKeyOfShaders) {
  auto dev = makeDevice(4, 4);
  dev->setRenderState(RS_CULLMODE, CULL_NONE);
  dev->setVertexShader(dev->createVertexShader(shader::assembleTokens(
      "vs_1_1\ndcl_position v0\ndcl_color v1\nmov oPos, v0\nmov oD0, v1\n", "vs")));
  dev->setPixelShader(dev->createPixelShader(shader::assembleTokens("ps_1_1\nmov r0, v0\n", "ps")));
  dev->setFVF(kColorVertexFVF);
  const std::vector<ColorVertex> v = {
      {-1, 1, 0.5f, 0xff336699}, {1, 1, 0.5f, 0xff336699}, {-1, -1, 0.5f, 0xff336699}, {1, -1, 0.5f, 0xff336699}};
  auto draw = [&] { dev->drawPrimitiveUP(PT_TRIANGLESTRIP, 2, v.data(), sizeof(ColorVertex)); };
  dev->resetStats();
  draw();
  dev->setRenderState(RS_LIGHTING, 0);
  dev->setRenderState(RS_NORMALIZENORMALS, 1);
  dev->setTextureStageState(0, TSS_TEXCOORDINDEX, 1);
  dev->setTextureStageState(0, TSS_COLOROP, TOP_ADD);
  dev->setTextureStageState(0, TSS_ALPHAARG1, TA_TFACTOR);
  dev->lightEnable(0, true);
  draw();
  EXPECT_EQ(pixel(*dev, 1, 1), 0xff336699u);  // the pixel shader's v0, as before
  EXPECT_EQ(counts(*dev).misses, 1u);
  EXPECT_EQ(counts(*dev).hits, 1u);
  // Without the vertex shader T&L is fixed function again: LIGHTING counts.
  dev->setVertexShader(nullptr);
  draw();
  dev->setRenderState(RS_LIGHTING, 1);
  draw();
  EXPECT_EQ(counts(*dev).misses, 3u);
}

TEST(DrawPlanCache, TextureFactorOfEachDraw) {
  auto dev = makeDevice(4, 4);
  // CURRENT = TFACTOR * DIFFUSE, alpha = DIFFUSE.
  dev->setTextureStageState(0, TSS_COLOROP, TOP_MODULATE);
  dev->setTextureStageState(0, TSS_COLORARG1, TA_TFACTOR);
  dev->setTextureStageState(0, TSS_COLORARG2, TA_DIFFUSE);
  dev->setTextureStageState(0, TSS_ALPHAOP, TOP_SELECTARG1);
  dev->setTextureStageState(0, TSS_ALPHAARG1, TA_DIFFUSE);
  dev->resetStats();
  dev->setRenderState(RS_TEXTUREFACTOR, 0xffff0000);
  quad(*dev, 0xff808080);
  // (1, 0, 0) * 128/255 = (128, 0, 0)
  EXPECT_EQ(pixel(*dev, 1, 2), 0xff800000u);
  dev->setRenderState(RS_TEXTUREFACTOR, 0xff00ff40);
  quad(*dev, 0xff808080);
  // green 1 * 128/255 -> 128; blue 64/255 * 128/255 * 255 = 32.13 -> 32
  EXPECT_EQ(pixel(*dev, 1, 2), 0xff008020u);
  EXPECT_EQ(counts(*dev).misses, 1u);
  EXPECT_EQ(counts(*dev).hits, 1u);
}

TEST(DrawPlanCache, FogValuesOfEachDraw) {
  auto dev = makeDevice(4, 4);
  useDiffuseOnly(*dev);
  // Pixel fog, linear on z (the projection is not perspective): f = (end - z)/(end - start),
  // colour = f * C + (1 - f) * FOGCOLOR; alpha unchanged.
  dev->setRenderState(RS_FOGENABLE, 1);
  dev->setRenderState(RS_FOGTABLEMODE, FOG_LINEAR);
  dev->setRenderState(RS_FOGCOLOR, 0x00000000);
  dev->setRenderState(RS_FOGSTART, floatBits(0.0f));
  dev->setRenderState(RS_FOGEND, floatBits(1.0f));
  dev->resetStats();
  quad(*dev, 0xffffffff, 0.5f);
  // f = (1 - 0.5)/1 = 0.5: 0.5 * 255 = 127.5 -> 128
  EXPECT_EQ(pixel(*dev, 2, 1), 0xff808080u);
  dev->setRenderState(RS_FOGEND, floatBits(2.0f));
  quad(*dev, 0xffffffff, 0.5f);
  // f = (2 - 0.5)/2 = 0.75: 191.25 -> 191
  EXPECT_EQ(pixel(*dev, 2, 1), 0xffbfbfbfu);
  dev->setRenderState(RS_FOGCOLOR, 0x00ff0000);
  quad(*dev, 0xffffffff, 0.5f);
  // red 0.75 * 1 + 0.25 * 1 = 1 -> 255; green, blue 0.75 -> 191
  EXPECT_EQ(pixel(*dev, 2, 1), 0xffffbfbfu);
  EXPECT_EQ(counts(*dev).misses, 1u);
  EXPECT_EQ(counts(*dev).hits, 2u);
}

TEST(DrawPlanCache, MaterialOfEachDraw) {
  auto dev = makeDevice(4, 4);
  useDiffuseOnly(*dev);
  dev->setRenderState(RS_CULLMODE, CULL_NONE);
  dev->setRenderState(RS_LIGHTING, 1);
  dev->setRenderState(RS_AMBIENT, 0xff808080);
  // No normal and no light: diffuse.rgb = Emissive + Ambient_material * AMBIENT, alpha =
  // the vertex's diffuse alpha (DIFFUSEMATERIALSOURCE = COLOR1).
  const std::vector<ColorVertex> v = {
      {-1, 1, 0.5f, 0xff000000}, {1, 1, 0.5f, 0xff000000}, {-1, -1, 0.5f, 0xff000000}, {1, -1, 0.5f, 0xff000000}};
  dev->setFVF(kColorVertexFVF);
  Material m;
  m.ambient = {1, 0.5f, 0, 1};
  m.emissive = {0, 0, 0.25f, 0};
  dev->setMaterial(m);
  dev->resetStats();
  dev->drawPrimitiveUP(PT_TRIANGLESTRIP, 2, v.data(), sizeof(ColorVertex));
  // r = 1 * 128/255 -> 128; g = 0.5 * 128/255 * 255 = 64 -> 64; b = 0.25 * 255 = 63.75 -> 64
  EXPECT_EQ(pixel(*dev, 1, 1), 0xff804040u);
  m.ambient = {0, 0, 0, 0};
  m.emissive = {0.5f, 0, 1, 0};
  dev->setMaterial(m);
  dev->drawPrimitiveUP(PT_TRIANGLESTRIP, 2, v.data(), sizeof(ColorVertex));
  // r = 0.5 -> 128 (127.5 rounds up), g = 0, b = 1 -> 255
  EXPECT_EQ(pixel(*dev, 1, 1), 0xff8000ffu);
  EXPECT_EQ(counts(*dev).misses, 1u);
  EXPECT_EQ(counts(*dev).hits, 1u);
}

}  // namespace

namespace {

// The cache keeps at most its capacity, dropping the plan used longest ago.
TEST(DrawPlanCache, BoundedLeastRecentlyUsed) {
  using refx::pipeline::DrawPlan;
  using refx::pipeline::DrawPlanCache;
  using refx::pipeline::DrawPlanKey;
  auto key = [](uint32_t n) { return DrawPlanKey{{n, 7}, size_t(n % 3)}; };  // colliding hashes
  DrawPlanCache cache(3);
  for (uint32_t n = 0; n < 3; ++n) cache.insert(key(n), std::make_shared<DrawPlan>());
  ASSERT_NE(cache.find(key(0)), nullptr);  // 0 is now the most recently used
  cache.insert(key(3), std::make_shared<DrawPlan>());
  EXPECT_EQ(cache.size(), 3u);
  EXPECT_EQ(cache.find(key(1)), nullptr);  // the least recently used went
  EXPECT_NE(cache.find(key(0)), nullptr);
  EXPECT_NE(cache.find(key(2)), nullptr);
  EXPECT_NE(cache.find(key(3)), nullptr);
  for (uint32_t n = 10; n < 100; ++n) cache.insert(key(n), std::make_shared<DrawPlan>());
  EXPECT_EQ(cache.size(), 3u);
  EXPECT_NE(cache.find(key(99)), nullptr);
  // Inserting a cached key again replaces its plan.
  auto replacement = std::make_shared<DrawPlan>();
  cache.insert(key(99), replacement);
  EXPECT_EQ(cache.size(), 3u);
  EXPECT_EQ(cache.find(key(99)), replacement);
  EXPECT_NE(cache.find(key(98)), nullptr);
}

}  // namespace

// A new plan records what runs its two programs; a cached plan records nothing.
// DeviceOptions::jit = false leaves both to the interpreter, with no compile time.
TEST(DrawPlanCache, RecordsWhatRunsANewPlansPrograms) {
  for (const bool jit : {true, false}) {
    DeviceOptions options;
    options.jit = jit;
    Device dev(CapsProfile{}, options);
    dev.setRenderTarget(Texture::create2D(Format::A8R8G8B8, 4, 4));
    quad(dev, 0xffffffff);
    quad(dev, 0xff00ff00);
    const auto& builds = dev.stats().programBuilds;
    ASSERT_EQ(builds.size(), 2u) << "jit " << jit;
    EXPECT_EQ(builds[0].name, "ff_vertex_pretransformed");
    EXPECT_EQ(builds[1].name, "fixed-function pixel");
    for (const auto& b : builds) {
      EXPECT_GT(b.instructions, 0) << b.name;
      if (!jit) {
        EXPECT_EQ(b.backend, "interpreter") << b.name;
        EXPECT_EQ(b.microseconds, 0.0) << b.name;
      } else {
        // Native code where the CPU has AVX2 (any x86-64-v3 machine refx is built for)
        // unless REFX_JIT=0 is set for the whole process.
        const char* env = std::getenv("REFX_JIT");
        if (!env || std::string(env) != "0") {
          EXPECT_EQ(b.backend.rfind("jit-", 0), 0u) << b.backend;
        }
      }
    }
  }
}

// DrawStats::stageMicroseconds: every draw adds the wall time of its stages (each of
// them takes some time, so every sum grows), an empty draw adds nothing, resetStats()
// clears them.
TEST(DrawStatsStageTimes, EachDrawAddsItsStagesTime) {
  auto dev = makeDevice(4, 4);
  dev->resetStats();
  const DrawStats::StageTimes& t = dev->stats().stageMicroseconds;
  EXPECT_EQ(t.plan + t.vertex + t.setup + t.raster, 0.0);
  quad(*dev, 0xffffffff);
  const DrawStats::StageTimes first = t;
  EXPECT_GT(first.plan, 0.0);
  EXPECT_GT(first.vertex, 0.0);
  EXPECT_GT(first.setup, 0.0);
  EXPECT_GT(first.raster, 0.0);
  quad(*dev, 0xff00ff00);
  EXPECT_GT(t.plan, first.plan);
  EXPECT_GT(t.vertex, first.vertex);
  EXPECT_GT(t.setup, first.setup);
  EXPECT_GT(t.raster, first.raster);
  const DrawStats::StageTimes second = t;
  dev->drawPrimitive(PT_TRIANGLELIST, 0, 0);  // no primitives: no stage runs
  EXPECT_EQ(t.vertex, second.vertex);
  EXPECT_EQ(t.raster, second.raster);
  dev->resetStats();
  EXPECT_EQ(t.plan + t.vertex + t.setup + t.raster, 0.0);
}
