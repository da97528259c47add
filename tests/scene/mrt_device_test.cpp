// Multiple render targets through the Device API (IDirect3DDevice9::SetRenderTarget
// with indices 0-3): what may be bound together, the viewport reset, Clear on every
// target (immediate and deferred) and oCn reaching target n. Expected values follow
// D3D9's "Multiple Render Targets" rules and are worked out by hand.
#include <gtest/gtest.h>

#include "pipeline/error_helpers.h"

#include <cstring>
#include <string>

#include "pipeline/device_helpers.h"
#include "refx/core/diagnostics.h"
#include "refx/hlsl/compiler.h"
#include "refx/pipeline/device.h"
#include "refx/shader/assembler.h"

using namespace refx;
using namespace refx::test;

namespace {


TexturePtr target(int w, int h, Format f = Format::A8R8G8B8) { return Texture::create2D(f, w, h); }

// A device of caps profile `profile` with an 8x8 A8R8G8B8 target 0.
std::unique_ptr<Device> mrtDevice(const std::string& profile = "ref") {
  auto dev = std::make_unique<Device>(loadCapsProfile(profile), DeviceOptions{1});
  dev->setRenderTarget(target(8, 8));
  return dev;
}

uint32_t texel32(const Texture& t, int x, int y) {
  uint32_t v;
  std::memcpy(&v, t.data(0, 0) + y * t.rowPitch(0) + x * 4, 4);
  return v;
}

TEST(MultipleRenderTargets, IndexBeyondNumSimultaneousRTsFails) {
  // ref: NumSimultaneousRTs 4 -> indices 0-3; dx8: 1 -> index 0 only.
  auto ref = mrtDevice("ref");
  EXPECT_EQ(errorOf([&] { ref->setRenderTarget(3, target(8, 8)); }), "(no error)");
  EXPECT_NE(errorOf([&] { ref->setRenderTarget(4, target(8, 8)); }).find("render target index 4 is out of range"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { ref->setRenderTarget(-1, target(8, 8)); }).find("out of range"), std::string::npos);
  auto dx8 = mrtDevice("dx8");
  const std::string e = errorOf([&] { dx8->setRenderTarget(1, target(8, 8)); });
  EXPECT_NE(e.find("caps profile dx8 has NumSimultaneousRTs 1"), std::string::npos) << e;
  EXPECT_EQ(dx8->renderTarget(1), nullptr);
}

TEST(MultipleRenderTargets, TargetZeroCannotBeNullOthersCan) {
  auto dev = mrtDevice();
  const TexturePtr rt0 = dev->renderTarget(0);
  EXPECT_NE(errorOf([&] { dev->setRenderTarget(0, nullptr); }).find("render target 0 cannot be null"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { dev->setRenderTarget(nullptr); }).find("cannot be null"), std::string::npos);
  EXPECT_EQ(dev->renderTarget(0), rt0);  // a failed call changes nothing
  dev->setRenderTarget(2, target(8, 8));
  EXPECT_NE(dev->renderTarget(2), nullptr);
  EXPECT_EQ(errorOf([&] { dev->setRenderTarget(2, nullptr); }), "(no error)");
  EXPECT_EQ(dev->renderTarget(2), nullptr);
  EXPECT_NE(errorOf([&] { dev->renderTarget(4); }).find("out of range"), std::string::npos);
}

TEST(MultipleRenderTargets, AllTargetsHaveTheSameSize) {
  auto dev = mrtDevice();
  const std::string e = errorOf([&] { dev->setRenderTarget(1, target(8, 4)); });
  EXPECT_NE(e.find("render target 1 is 8x4, render target 0 is 8x8"), std::string::npos) << e;
  dev->setRenderTarget(1, target(8, 8));
  // Target 0 of another size while target 1 is bound fails too; unbinding 1 allows it.
  EXPECT_NE(errorOf([&] { dev->setRenderTarget(0, target(16, 16)); }).find("same size"), std::string::npos);
  dev->setRenderTarget(1, nullptr);
  EXPECT_EQ(errorOf([&] { dev->setRenderTarget(0, target(16, 16)); }), "(no error)");
}

TEST(MultipleRenderTargets, FormatsAndBitDepths) {
  // ref has D3DPMISCCAPS_MRTINDEPENDENTBITDEPTHS: a 128-bit float target next to a
  // 32-bit one; dx9 does not: only the same bit depth (A8R8G8B8 with X8R8G8B8).
  auto ref = mrtDevice("ref");
  EXPECT_EQ(errorOf([&] { ref->setRenderTarget(1, target(8, 8, Format::A32B32G32R32F)); }), "(no error)");
  EXPECT_NE(errorOf([&] { ref->setRenderTarget(2, target(8, 8, Format::R5G6B5)); })
                .find("must be a 2D A8R8G8B8, X8R8G8B8 or A32B32G32R32F texture"),
            std::string::npos);
  auto dx9 = mrtDevice("dx9");
  EXPECT_EQ(errorOf([&] { dx9->setRenderTarget(1, target(8, 8, Format::X8R8G8B8)); }), "(no error)");
  const std::string e = errorOf([&] { dx9->setRenderTarget(2, target(8, 8, Format::A32B32G32R32F)); });
  EXPECT_NE(e.find("differ in bit depth"), std::string::npos) << e;
  EXPECT_NE(e.find("MRTINDEPENDENTBITDEPTHS"), std::string::npos) << e;
}

TEST(MultipleRenderTargets, OnlyTargetZeroResetsTheViewport) {
  auto dev = mrtDevice();
  dev->setViewport(Viewport{2, 2, 4, 4, 0, 1});
  dev->setRenderTarget(1, target(8, 8));
  EXPECT_EQ(dev->state().viewport.x, 2);
  EXPECT_EQ(dev->state().viewport.width, 4);
  dev->setRenderTarget(0, target(8, 8));
  EXPECT_EQ(dev->state().viewport.x, 0);
  EXPECT_EQ(dev->state().viewport.width, 8);
  EXPECT_EQ(dev->state().viewport.height, 8);
}

TEST(MultipleRenderTargets, ClearFillsEveryBoundTarget) {
  // Immediate: the test holds references to the targets.
  auto dev = mrtDevice();
  auto rt1 = target(8, 8), rt3 = target(8, 8, Format::A32B32G32R32F);
  dev->setRenderTarget(1, rt1);
  dev->setRenderTarget(3, rt3);
  dev->clear(d3d::CLEAR_TARGET, 0xff336699, 1.0f, 0);
  EXPECT_EQ(texel32(*dev->renderTarget(0), 7, 7), 0xff336699u);
  EXPECT_EQ(texel32(*rt1, 0, 0), 0xff336699u);
  // The float target holds c/255: 0x33 = 51 -> 0.2, 0x66 -> 0.4, 0x99 -> 0.6, 0xff -> 1.
  const Color4 c = rt3->texel(0, 0, 5, 5);
  EXPECT_NEAR(c.r, 0.2f, 1e-6f);
  EXPECT_NEAR(c.g, 0.4f, 1e-6f);
  EXPECT_NEAR(c.b, 0.6f, 1e-6f);
  EXPECT_NEAR(c.a, 1.0f, 1e-6f);
}

TEST(MultipleRenderTargets, DeferredClearFillsEveryBoundTarget) {
  // Only the device holds the targets: the clear is deferred to the next draw (every
  // tile of it) or to an accessor. 200x150 spans several 64x64 tiles.
  for (bool draw : {false, true}) {
    auto dev = std::make_unique<Device>(loadCapsProfile("ref"), DeviceOptions{1});
    dev->setRenderTarget(target(200, 150));
    dev->setRenderTarget(1, target(200, 150));
    dev->setRenderTarget(2, target(200, 150, Format::X8R8G8B8));
    dev->clear(d3d::CLEAR_TARGET, 0x8000ff00, 1.0f, 0);
    if (draw) {
      useDiffuseOnly(*dev);
      drawTL(*dev, d3d::PT_TRIANGLESTRIP,
             {{1.5f, 1.5f, 0.5f, 1, 0xffff0000, 0, 0}, {5.5f, 1.5f, 0.5f, 1, 0xffff0000, 0, 0},
              {1.5f, 5.5f, 0.5f, 1, 0xffff0000, 0, 0}, {5.5f, 5.5f, 0.5f, 1, 0xffff0000, 0, 0}});
      EXPECT_EQ(texel32(*dev->renderTarget(0), 3, 3), 0xffff0000u);
      // Fixed function writes target 0 only: target 1 keeps the clear under the quad.
      EXPECT_EQ(texel32(*dev->renderTarget(1), 3, 3), 0x8000ff00u);
    }
    for (int i = 0; i < 3; ++i) {
      // X8R8G8B8 reads alpha 255 whatever its byte holds.
      const Color4 expected = i == 2 ? Color4{0, 1, 0, 1} : Color4{0, 1, 0, 128 / 255.0f};
      for (auto [x, y] : {std::pair{0, 0}, {199, 149}, {130, 10}}) {
        const Color4 c = dev->renderTarget(i)->texel(0, 0, x, y);
        EXPECT_NEAR(c.r, expected.r, 1e-6f) << "target " << i << " at " << x << "," << y;
        EXPECT_NEAR(c.g, expected.g, 1e-6f) << "target " << i << " at " << x << "," << y;
        EXPECT_NEAR(c.a, expected.a, 1e-6f) << "target " << i << " at " << x << "," << y;
      }
    }
  }
}

TEST(MultipleRenderTargets, ShaderOutputsReachTheirTargets) {
  // ps_2_0: oC0 = (1, 0, 0, 1), oC1 = (0, 1, 0, 1); targets 2 and 3 are bound but oC2
  // and oC3 are not written, so they keep their clear (refx's choice where D3D9 leaves
  // them undefined).
  auto dev = mrtDevice();
  for (int i = 1; i < 4; ++i) dev->setRenderTarget(i, target(8, 8));
  dev->clear(d3d::CLEAR_TARGET, 0xff404040, 1.0f, 0);
  dev->setPixelShader(dev->createPixelShader(shader::assembleTokens(
      "ps_2_0\ndef c0, 1, 0, 0, 1\ndef c1, 0, 1, 0, 1\nmov oC0, c0\nmov oC1, c1\n", "t.psh")));
  drawTL(*dev, d3d::PT_TRIANGLESTRIP,
         {{-0.5f, -0.5f, 0.5f, 1, 0xffffffff, 0, 0}, {7.5f, -0.5f, 0.5f, 1, 0xffffffff, 0, 0},
          {-0.5f, 7.5f, 0.5f, 1, 0xffffffff, 0, 0}, {7.5f, 7.5f, 0.5f, 1, 0xffffffff, 0, 0}});
  EXPECT_EQ(texel32(*dev->renderTarget(0), 4, 4), 0xffff0000u);
  EXPECT_EQ(texel32(*dev->renderTarget(1), 4, 4), 0xff00ff00u);
  EXPECT_EQ(texel32(*dev->renderTarget(2), 4, 4), 0xff404040u);
  EXPECT_EQ(texel32(*dev->renderTarget(3), 4, 4), 0xff404040u);
}

TEST(MultipleRenderTargets, ColorOutputsAreWrittenInOrder) {
  // The ps_2_0 rules: oCn may be written only with oC0 to oC(n-1), so no bound target
  // sits between two written ones.
  auto dev = mrtDevice();
  const std::string e = errorOf([&] {
    dev->createPixelShader(shader::assembleTokens("ps_2_0\ndef c0, 1, 0, 0, 1\nmov oC0, c0\nmov oC3, c0\n", "t.psh"));
  });
  EXPECT_NE(e.find("oC3 is written but oC1 is not"), std::string::npos) << e;
}

TEST(MultipleRenderTargets, HlslColorSemanticsReachTheirTargets) {
  // COLOR0-COLOR2 outputs of an HLSL pixel shader are oC0-oC2, for ps_2_0 and ps_3_0:
  // target n holds (n + 1)/4 in red, 1 - (n + 1)/4 in green: 0.25 -> 63.75 -> 64,
  // 0.75 -> 191.25 -> 191, 0.5 -> 127.5 -> 128 (round to nearest).
  const char* source =
      "struct Out { float4 c0 : COLOR0; float4 c1 : COLOR1; float4 c2 : COLOR2; };\n"
      "Out main() {\n"
      "  Out o;\n"
      "  o.c0 = float4(0.25, 0.75, 0, 1);\n"
      "  o.c1 = float4(0.5, 0.5, 0, 1);\n"
      "  o.c2 = float4(0.75, 0.25, 0, 1);\n"
      "  return o;\n"
      "}\n";
  for (const char* profile : {"ps_2_0", "ps_3_0"}) {
    hlsl::CompileOptions options;
    options.profile = profile;
    const hlsl::CompileResult compiled = hlsl::compile(source, "mrt.hlsl", options);
    ASSERT_TRUE(compiled.ok()) << compiled.messages();
    auto dev = mrtDevice();
    dev->setRenderTarget(1, target(8, 8));
    dev->setRenderTarget(2, target(8, 8));
    dev->clear(d3d::CLEAR_TARGET, 0xff000000, 1.0f, 0);
    dev->setPixelShader(dev->createPixelShader(compiled.tokens));
    // A clip-space quad over the whole target, passed through (ps_3_0 needs a vs_3_0).
    const bool sm3 = std::string(profile) == "ps_3_0";
    dev->setVertexShader(dev->createVertexShader(shader::assembleTokens(
        sm3 ? "vs_3_0\ndcl_position v0\ndcl_position o0\nmov o0, v0\n" : "vs_2_0\ndcl_position v0\nmov oPos, v0\n",
        "t.vsh")));
    const float quad[] = {-1, 1, 0.5f, 1, 1, 1, 0.5f, 1, -1, -1, 0.5f, 1, 1, -1, 0.5f, 1};
    dev->setFVF(d3d::FVF_XYZW);
    dev->setRenderState(d3d::RS_CULLMODE, d3d::CULL_NONE);
    dev->drawPrimitiveUP(d3d::PT_TRIANGLESTRIP, 2, quad, 16);
    EXPECT_EQ(texel32(*dev->renderTarget(0), 4, 4), 0xff40bf00u) << profile;
    EXPECT_EQ(texel32(*dev->renderTarget(1), 4, 4), 0xff808000u) << profile;
    EXPECT_EQ(texel32(*dev->renderTarget(2), 4, 4), 0xffbf4000u) << profile;
  }
}

}  // namespace
