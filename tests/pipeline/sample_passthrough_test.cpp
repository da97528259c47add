// Draws whose pixel program only samples a texture into an opaque 8-bit target
// (DrawPlan::samplePassthrough) store the sample's bytes without running the program.
// They must give exactly the pixels and depths of the same draw with a program that
// computes the same value in a way the pass-through does not recognise (tex, then two
// movs), and a hand-worked case pins the bytes themselves.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "device_helpers.h"
#include "refx/shader/assembler.h"

using namespace refx;
using namespace refx::test;
using namespace refx::d3d;

namespace {

// D3DTEXTUREFILTERTYPE and D3DTEXTUREADDRESS values.
constexpr uint32_t kNone = 0, kPoint = 1, kLinear = 2;
constexpr uint32_t kWrap = 1, kMirror = 2, kClamp = 3;

constexpr const char* kPassthrough = "ps.1.1\ntex t0\nmov r0, t0\n";
// The same value: r1 = t0, r0 = r1 (each in [-1, 1], which keeps the sample as it is).
constexpr const char* kRunsTheProgram = "ps.1.1\ntex t0\nmov r1, t0\nmov r0, r1\n";

struct Config {
  Format target;
  uint32_t minFilter, magFilter, mipFilter, address;
  bool depth;
};

struct Frame : FrameContents {
  uint64_t passthroughDraws;
};

// Two overlapping perspective triangles (rhw varies, texture coordinates beyond 1 and
// below 0) on a 67x45 target cleared to a colour, then a third one half behind them.
Frame render(const Config& c, const char* ps, const TexturePtr& tex) {
  DeviceOptions opt;
  opt.threads = 2;
  Device dev(CapsProfile{}, opt);
  const int w = 67, h = 45;
  auto target = Texture::create2D(c.target, w, h);
  dev.setRenderTarget(target);
  auto ds = std::make_shared<DepthStencilSurface>(w, h);
  dev.setDepthStencilSurface(ds);
  dev.clear(CLEAR_TARGET | CLEAR_ZBUFFER, 0x80402010, 1.0f, 0);
  dev.setRenderState(RS_ZENABLE, c.depth ? ZB_TRUE : ZB_FALSE);
  dev.setRenderState(RS_ZFUNC, CMP_LESS);
  dev.setRenderState(RS_CULLMODE, CULL_NONE);
  dev.setTexture(0, tex);
  setSampler(dev, 0, c.minFilter, c.magFilter, c.mipFilter, c.address);
  dev.setPixelShader(dev.createPixelShader(shader::assembleTokens(ps, "test.psh")));
  dev.resetStats();
  drawTL(dev, PT_TRIANGLELIST,
         {{-3.5f, 1.25f, 0.5f, 1.0f, 0xffffffff, -0.7f, -0.3f},
          {70.0f, 4.0f, 0.25f, 0.2f, 0xffffffff, 3.1f, 0.2f},
          {5.0f, 47.0f, 0.75f, 0.6f, 0xffffffff, 0.4f, 2.6f},
          {60.0f, 44.0f, 0.6f, 1.0f, 0xffffffff, 1.5f, 1.5f},
          {10.0f, 3.0f, 0.6f, 0.5f, 0xffffffff, -0.2f, 0.9f},
          {66.0f, 20.0f, 0.6f, 0.8f, 0xffffffff, 0.3f, -0.8f}});
  Frame f;
  static_cast<FrameContents&>(f) = readFrame(*target, *ds);
  f.passthroughDraws = dev.stats().samplePassthroughDraws;
  return f;
}

TEST(SamplePassthrough, SameBytesAsTheProgram) {
  const TexturePtr tex = noiseTexture(64, 32);
  int configs = 0;
  for (Format target : {Format::A8R8G8B8, Format::X8R8G8B8})
    for (uint32_t filter : {kPoint, kLinear})
      for (uint32_t mip : {kNone, kPoint, kLinear})
        for (uint32_t address : {kWrap, kMirror, kClamp})
          for (bool depth : {false, true}) {
            const Config c{target, filter, kLinear, mip, address, depth};
            const Frame fast = render(c, kPassthrough, tex);
            const Frame program = render(c, kRunsTheProgram, tex);
            SCOPED_TRACE(testing::Message() << "target " << int(target) << " min " << filter << " mip " << mip
                                            << " address " << address << " depth " << depth);
            EXPECT_EQ(fast.passthroughDraws, 1u);
            EXPECT_EQ(program.passthroughDraws, 0u);
            EXPECT_EQ(fast.color, program.color);
            EXPECT_EQ(fast.depth, program.depth);
            ++configs;
          }
  EXPECT_EQ(configs, 72);
}

TEST(SamplePassthrough, TexelsLandAsBytes) {
  // A 2x2 POINT-sampled texture over a 4x4 target, u and v from 0 to 1: pixel (x, y)
  // has its centre at u = (x + 0.5) / 4, the texel floor(u * 2), so each 2x2 pixel
  // block shows one texel's bytes. X8R8G8B8: the alpha byte is written as 0xff.
  auto tex = Texture::create2D(Format::A8R8G8B8, 2, 2, 1);
  const uint32_t texels[4] = {0x11223344, 0x55667788, 0x99aabbcc, 0x00ddeeff};
  for (int i = 0; i < 4; ++i) std::memcpy(tex->data(0, 0) + (i / 2) * tex->rowPitch(0) + (i % 2) * 4, &texels[i], 4);
  tex->markDirty();
  for (Format format : {Format::A8R8G8B8, Format::X8R8G8B8}) {
    Device dev(CapsProfile{});
    dev.setRenderTarget(Texture::create2D(format, 4, 4));
    dev.setTexture(0, tex);
    dev.setSamplerState(0, SAMP_MINFILTER, kPoint);
    dev.setSamplerState(0, SAMP_MAGFILTER, kPoint);
    dev.setPixelShader(dev.createPixelShader(shader::assembleTokens(kPassthrough, "test.psh")));
    dev.resetStats();
    drawTL(dev, PT_TRIANGLESTRIP,
           {{0, 0, 0.5f, 1, 0, 0, 0}, {4, 0, 0.5f, 1, 0, 1, 0}, {0, 4, 0.5f, 1, 0, 0, 1}, {4, 4, 0.5f, 1, 0, 1, 1}});
    EXPECT_EQ(dev.stats().samplePassthroughDraws, 1u);
    const uint32_t alpha = format == Format::X8R8G8B8 ? 0xff000000u : 0;
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 4; ++x)
        EXPECT_EQ(pixel(dev, x, y), texels[(y / 2) * 2 + x / 2] | alpha) << x << "," << y;
  }
}

TEST(SamplePassthrough, OnlyForAnOpaqueStore) {
  // Blending, the alpha test, stencil or a partial colour write mask make the merge more
  // than a store: the program runs.
  const TexturePtr tex = noiseTexture(8, 8);
  const std::vector<std::pair<RenderState, uint32_t>> states = {
      {RS_ALPHABLENDENABLE, 1}, {RS_ALPHATESTENABLE, 1}, {RS_STENCILENABLE, 1}, {RS_COLORWRITEENABLE, 0x7}};
  for (const auto& [state, value] : states) {
    auto dev = makeDevice(8, 8);
    dev->setTexture(0, tex);
    dev->setPixelShader(dev->createPixelShader(shader::assembleTokens(kPassthrough, "test.psh")));
    dev->setRenderState(state, value);
    dev->resetStats();
    drawTL(*dev, PT_TRIANGLESTRIP,
           {{0, 0, 0.5f, 1, 0, 0, 0}, {8, 0, 0.5f, 1, 0, 1, 0}, {0, 8, 0.5f, 1, 0, 0, 1}, {8, 8, 0.5f, 1, 0, 1, 1}});
    EXPECT_EQ(dev->stats().samplePassthroughDraws, 0u) << int(state);
  }
}

}  // namespace
