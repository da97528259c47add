// A draw gives the same pixels whichever instruction-set variant of the kernels runs
// (refx/core/cpu_features.h): textured triangles in perspective with every addressing
// mode and filter the vectorised sampler handles, compared pixel for pixel.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "device_helpers.h"
#include "refx/core/cpu_features.h"

namespace refx {
namespace {

using namespace refx::d3d;
using test::TLVertex;

std::vector<uint8_t> drawFrame(const TexturePtr& tex, uint32_t address, uint32_t filter,
                               uint32_t mipFilter) {
  auto dev = test::makeDevice(96, 80, 0xff102030);
  dev->setTexture(0, tex);
  dev->setSamplerState(0, SAMP_ADDRESSU, address);
  dev->setSamplerState(0, SAMP_ADDRESSV, address == 1 ? 2 : address);
  dev->setSamplerState(0, SAMP_MAGFILTER, filter);
  dev->setSamplerState(0, SAMP_MINFILTER, filter);
  dev->setSamplerState(0, SAMP_MIPFILTER, mipFilter);
  dev->setTextureStageState(0, TSS_COLOROP, TOP_MODULATE);
  dev->setTextureStageState(0, TSS_COLORARG1, TA_TEXTURE);
  dev->setTextureStageState(0, TSS_COLORARG2, TA_DIFFUSE);
  // A floor receding into the distance (rhw from 1 to 1/8, texture repeated 6 times
  // across, so the far rows minify and pick smaller levels) and a triangle crossing it.
  const std::vector<TLVertex> floor = {
      {2, 78, 0.1f, 1.0f, 0xffffffff, -3.0f, 3.0f},
      {94, 78, 0.1f, 1.0f, 0xffff8040, 3.0f, 3.0f},
      {40, 4, 0.9f, 0.125f, 0xff40ff80, -0.4f, -3.0f},
      {94, 78, 0.1f, 1.0f, 0xffff8040, 3.0f, 3.0f},
      {60, 4, 0.9f, 0.125f, 0xff8080ff, 0.4f, -3.0f},
      {40, 4, 0.9f, 0.125f, 0xff40ff80, -0.4f, -3.0f},
      {-5, 30, 0.05f, 0.5f, 0xffffffff, -1.3f, 0.2f},
      {70, 10, 0.05f, 0.9f, 0xffffffff, 1.7f, -0.6f},
      {50, 85, 0.05f, 0.3f, 0xffffffff, 0.1f, 2.9f},
  };
  test::drawTL(*dev, PT_TRIANGLELIST, floor);
  const Texture& t = *dev->renderTarget();
  return std::vector<uint8_t>(t.data(0, 0), t.data(0, 0) + t.dataSize(0, 0));
}

TEST(IsaVariants, DrawsGiveTheSamePixels) {
  if (detectedIsa() != CpuIsa::Avx512) GTEST_SKIP() << "no AVX-512 on this CPU";
  auto tex = Texture::create2D(Format::A8R8G8B8, 64, 32, 0);
  std::mt19937 rng(41);
  for (int l = 0; l < tex->levelCount(); ++l) {
    uint8_t* p = tex->data(0, l);
    for (size_t i = 0; i < tex->dataSize(0, l); ++i) p[i] = uint8_t(rng());
  }
  tex->markDirty();
  const CpuIsa previous = activeIsa();
  int frames = 0;
  for (uint32_t address : {1u, 2u, 3u, 5u})          // WRAP (V: MIRROR), MIRROR, CLAMP, MIRRORONCE
    for (uint32_t filter : {1u, 2u})                // POINT, LINEAR
      for (uint32_t mipFilter : {0u, 1u}) {         // NONE, POINT
        setActiveIsa(CpuIsa::Avx2);
        const auto avx2 = drawFrame(tex, address, filter, mipFilter);
        setActiveIsa(CpuIsa::Avx512);
        const auto avx512 = drawFrame(tex, address, filter, mipFilter);
        ASSERT_EQ(avx2, avx512) << "address " << address << " filter " << filter << " mip "
                                << mipFilter;
        // The frame is textured: its pixels are not all the clear colour.
        uint32_t first;
        std::memcpy(&first, avx2.data() + (40 * 96 + 48) * 4, 4);
        EXPECT_NE(first, 0xff102030u);
        ++frames;
      }
  setActiveIsa(previous);
  EXPECT_EQ(frames, 16);
}

}  // namespace
}  // namespace refx
