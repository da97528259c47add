// The numeric limits of the reference profile (data/caps/ref.caps) hold: textures as
// large as MaxTextureWidth/Height/MaxVolumeExtent validate and one texel more does
// not, texture coordinates wrap correctly up to MaxTextureRepeat, and vertex data
// comes from all MaxStreams streams.
#include <gtest/gtest.h>

#include <cstring>

#include "device_helpers.h"
#include "refx/core/color.h"
#include "refx/pipeline/caps.h"
#include "refx/pipeline/device.h"

using namespace refx;
using namespace refx::d3d;
using namespace refx::test;

namespace {

std::string reason(const DeviceState& s, const CapsProfile& caps) {
  ValidationResult r = validateDeviceState(s, caps);
  return r.ok ? "ok" : r.reason;
}

}  // namespace

TEST(CapsLimits, TextureSizesUpToTheLimits) {
  const CapsProfile ref = loadCapsProfile("ref");
  ASSERT_EQ(ref.maxTextureWidth, 8192u);
  ASSERT_EQ(ref.maxTextureHeight, 8192u);
  ASSERT_EQ(ref.maxVolumeExtent, 2048u);
  DeviceState s;  // stage 0 samples sampler 0
  s.textures[0] = Texture::create2D(Format::A8R8G8B8, 8192, 1);
  EXPECT_EQ(reason(s, ref), "ok");
  s.textures[0] = Texture::create2D(Format::A8R8G8B8, 8193, 1);
  EXPECT_EQ(reason(s, ref), "sampler 0 texture is 8193x1 but ref has MaxTextureWidth 8192");
  s.textures[0] = Texture::create2D(Format::A8R8G8B8, 1, 8192);
  EXPECT_EQ(reason(s, ref), "ok");
  s.textures[0] = Texture::create2D(Format::A8R8G8B8, 1, 8193);
  EXPECT_EQ(reason(s, ref), "sampler 0 texture is 1x8193 but ref has MaxTextureHeight 8192");
  s.textures[0] = Texture::createVolume(Format::A8R8G8B8, 1, 1, 2048);
  EXPECT_EQ(reason(s, ref), "ok");
  s.textures[0] = Texture::createVolume(Format::A8R8G8B8, 1, 1, 2049);
  EXPECT_EQ(reason(s, ref), "sampler 0 volume texture is 1x1x2049 but ref has MaxVolumeExtent 2048");
}

TEST(CapsLimits, TextureRepeatsAcrossTheWholeRange) {
  // MaxTextureRepeat 32768: coordinates up to 32768 repeats wrap like their fraction.
  // A 4x1 texture red, green, blue, white, POINT and WRAP (the defaults): texel
  // floor(frac(u) * 4). u = 32767.375: frac 0.375 -> 1.5 -> texel 1, green;
  // u = -32767.125: frac 0.875 -> 3.5 -> texel 3, white.
  ASSERT_EQ(loadCapsProfile("ref").maxTextureRepeat, 32768u);
  auto dev = makeDevice(4, 2);
  TexturePtr tex = Texture::create2D(Format::A8R8G8B8, 4, 1);
  const uint32_t colors[4] = {0xffff0000, 0xff00ff00, 0xff0000ff, 0xffffffff};
  for (int x = 0; x < 4; ++x) tex->setTexel(0, 0, x, 0, 0, colorFromD3D(colors[x]));
  dev->setTexture(0, tex);
  dev->setRenderState(RS_CULLMODE, CULL_NONE);
  auto row = [&](float y0, float u) {
    drawTL(*dev, PT_TRIANGLESTRIP, {{-0.5f, y0, 0.5f, 1, 0xffffffff, u, 0.5f},
                                    {3.5f, y0, 0.5f, 1, 0xffffffff, u, 0.5f},
                                    {-0.5f, y0 + 1, 0.5f, 1, 0xffffffff, u, 0.5f},
                                    {3.5f, y0 + 1, 0.5f, 1, 0xffffffff, u, 0.5f}});
  };
  row(-0.5f, 32767.375f);
  row(0.5f, -32767.125f);
  for (int x = 0; x < 4; ++x) {
    EXPECT_EQ(pixel(*dev, x, 0), 0xff00ff00u) << x;
    EXPECT_EQ(pixel(*dev, x, 1), 0xffffffffu) << x;
  }
}

TEST(CapsLimits, SixteenStreams) {
  // MaxStreams 16: position from stream 0, diffuse from stream 15 (the last).
  ASSERT_EQ(loadCapsProfile("ref").maxStreams, 16u);
  auto dev = makeDevice(2, 2);
  useDiffuseOnly(*dev);
  dev->setRenderState(RS_CULLMODE, CULL_NONE);
  VertexDeclaration decl;
  decl.elements.push_back(VertexElement{0, 0, DECLTYPE_FLOAT4, 0, DECLUSAGE_POSITIONT, 0});
  decl.elements.push_back(VertexElement{15, 0, DECLTYPE_D3DCOLOR, 0, DECLUSAGE_COLOR, 0});
  dev->setVertexDeclaration(decl);
  const float pos[4][4] = {{-0.5f, -0.5f, 0.5f, 1}, {1.5f, -0.5f, 0.5f, 1},
                           {-0.5f, 1.5f, 0.5f, 1}, {1.5f, 1.5f, 0.5f, 1}};
  const uint32_t color[4] = {0xff336699, 0xff336699, 0xff336699, 0xff336699};
  auto positions = std::make_shared<VertexBuffer>();
  positions->data.resize(sizeof pos);
  std::memcpy(positions->data.data(), pos, sizeof pos);
  auto colors = std::make_shared<VertexBuffer>();
  colors->data.resize(sizeof color);
  std::memcpy(colors->data.data(), color, sizeof color);
  dev->setStreamSource(0, positions, 0, 16);
  dev->setStreamSource(15, colors, 0, 4);
  dev->drawPrimitive(PT_TRIANGLESTRIP, 0, 2);
  // Every pixel takes the stream-15 diffuse color.
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) EXPECT_EQ(pixel(*dev, x, y), 0xff336699u) << x << "," << y;
}
