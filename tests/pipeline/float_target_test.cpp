// A32B32G32R32F render targets: the pixel shader's colour is stored as four floats,
// without the [0, 1] clamp and the 8-bit quantisation of A8R8G8B8; blending works on
// the unclamped values; a Clear's D3DCOLOR becomes c / 255 per channel.
#include <gtest/gtest.h>

#include <cstring>

#include "device_helpers.h"
#include "refx/pipeline/device.h"
#include "refx/shader/assembler.h"

namespace refx {
namespace {

std::array<float, 4> floatPixel(const Device& dev, int x, int y) {
  const Texture& t = *dev.renderTarget();
  std::array<float, 4> v;
  std::memcpy(v.data(), t.data(0, 0) + y * t.rowPitch(0) + x * 16, 16);
  return v;
}

std::unique_ptr<Device> floatDevice() {
  DeviceOptions opt;
  opt.threads = 1;
  auto dev = std::make_unique<Device>(CapsProfile{}, opt);
  dev->setRenderTarget(Texture::create2D(Format::A32B32G32R32F, 8, 8));
  dev->setDepthStencilSurface(std::make_shared<DepthStencilSurface>(8, 8));
  return dev;
}

void drawWith(Device& dev, const char* ps) {
  dev.setPixelShader(dev.createPixelShader(shader::encode(shader::assemble(ps, "ps.psh"))));
  test::drawTL(dev, d3d::PT_TRIANGLESTRIP,
               {{0, 0, 0.5f, 1, 0, 0, 0}, {8, 0, 0.5f, 1, 0, 1, 0}, {0, 8, 0.5f, 1, 0, 0, 1}, {8, 8, 0.5f, 1, 0, 1, 1}});
}

// Clear with 0x80ff4000: (255, 64, 0, 128) / 255 = (1, 0.250980, 0, 0.501961).
TEST(FloatTarget, ClearWritesTheColourDividedBy255) {
  auto dev = floatDevice();
  dev->clear(d3d::CLEAR_TARGET, 0x80ff4000, 1, 0);
  const auto p = floatPixel(*dev, 3, 3);
  EXPECT_FLOAT_EQ(p[0], 1.0f);
  EXPECT_FLOAT_EQ(p[1], 64.0f / 255.0f);
  EXPECT_FLOAT_EQ(p[2], 0.0f);
  EXPECT_FLOAT_EQ(p[3], 128.0f / 255.0f);
}

// The shader writes (2.5, -1, 0.125, 0.5): a float target keeps it exactly.
TEST(FloatTarget, KeepsValuesOutsideZeroToOne) {
  auto dev = floatDevice();
  dev->clear(d3d::CLEAR_TARGET, 0, 1, 0);
  drawWith(*dev, "ps_2_0\ndef c0, 2.5, -1, 0.125, 0.5\nmov oC0, c0\n");
  EXPECT_EQ(floatPixel(*dev, 4, 4), (std::array<float, 4>{2.5f, -1.0f, 0.125f, 0.5f}));
}

// ONE/ONE blending twice over a cleared (0, 0, 0, 0) target: 2 * (2.5, -1, 0.125, 0.5) =
// (5, -2, 0.25, 1), the source not clamped to [0, 1] first. COLORWRITEENABLE red|alpha
// then leaves green and blue as they were.
TEST(FloatTarget, BlendsUnclampedValuesAndHonoursTheWriteMask) {
  auto dev = floatDevice();
  dev->clear(d3d::CLEAR_TARGET, 0, 1, 0);
  dev->setRenderState(d3d::RS_ALPHABLENDENABLE, 1);
  dev->setRenderState(d3d::RS_SRCBLEND, d3d::BLEND_ONE);
  dev->setRenderState(d3d::RS_DESTBLEND, d3d::BLEND_ONE);
  const char* ps = "ps_2_0\ndef c0, 2.5, -1, 0.125, 0.5\nmov oC0, c0\n";
  drawWith(*dev, ps);
  drawWith(*dev, ps);
  EXPECT_EQ(floatPixel(*dev, 4, 4), (std::array<float, 4>{5.0f, -2.0f, 0.25f, 1.0f}));
  dev->setRenderState(d3d::RS_COLORWRITEENABLE, d3d::CW_RED | d3d::CW_ALPHA);
  drawWith(*dev, ps);
  EXPECT_EQ(floatPixel(*dev, 4, 4), (std::array<float, 4>{7.5f, -2.0f, 0.25f, 1.5f}));
}

}  // namespace
}  // namespace refx
