// RacorX7 against RacorX8 (seeds/003): "Using the mul instructions to perform the
// specular color leads to visible banding artifacts ... The only way to provide higher
// precision is delivering a texture map with the specular values encoded". In the
// `hardware` precision model the four squarings run on 8-bit fixed point and band;
// the lookup table does not. In `exact` precision both are smooth.
//
// The scenes are the samples' own (include/refx/scene/racorx_scene.h: the same shader files,
// constants and states), on a white color map and a flat normal map so that the only
// variation left in the highlight is the specular term.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "refx/scene/mesh_binding.h"
#include "refx/scene/racorx_scene.h"

namespace refx {
namespace {

using scene::racorx::PSVersion;
using scene::racorx::SpecularTextures;
using scene::racorx::View;

constexpr int kSize = 256;

TexturePtr solid(uint8_t r, uint8_t g, uint8_t b, uint8_t a) {
  auto t = Texture::create2D(Format::A8R8G8B8, 64, 64, 0);
  for (int level = 0; level < t->levelCount(); ++level) {
    uint8_t* p = t->data(0, level);
    for (size_t i = 0; i < t->dataSize(0, level); i += 4) {
      p[i + 0] = b;
      p[i + 1] = g;
      p[i + 2] = r;
      p[i + 3] = a;
    }
  }
  t->markDirty();
  return t;
}

// Red channel of the frame (the specular term is grey: R = G = B).
std::vector<uint8_t> render(bool racorx8, Precision precision) {
  DeviceOptions opt;
  opt.precision = precision;
  Device dev(loadCapsProfile("dx8"), opt);  // ps.1.1, MaxPixelShaderValue 1
  dev.setRenderTarget(Texture::create2D(Format::A8R8G8B8, kSize, kSize));
  dev.setDepthStencilSurface(std::make_shared<DepthStencilSurface>(kSize, kSize));
  dev.clear(d3d::CLEAR_TARGET | d3d::CLEAR_ZBUFFER, 0xff000000, 1.0f, 0);

  static const SpecularTextures textures{solid(255, 255, 255, 255),  // white color map
                                         solid(128, 128, 255, 255),  // flat normal (0, 0, 1)
                                         scene::racorx::racorx8Table()};
  View v = scene::racorx::globeView(dev, Matrix::identity());
  // Light from the upper left behind the viewer: the highlight sits on the visible side.
  v.lightDirection = -normalize(Vec3{0.3f, 0.4f, -1.0f});
  if (racorx8)
    scene::racorx::setupRacorX8(dev, v, textures, PSVersion::PS11);
  else
    scene::racorx::setupRacorX7(dev, v, textures, PSVersion::PS11);
  static const d3dx::Mesh sphere = scene::racorx::globe(64, 32);
  scene::bindMesh(dev, sphere);
  scene::racorx::drawGlobe(dev, sphere);

  const Texture& rt = *dev.renderTarget();
  const uint8_t* p = rt.data(0, 0);
  std::vector<uint8_t> red(size_t(kSize) * kSize);
  for (size_t i = 0; i < red.size(); ++i) red[i] = p[i * 4 + 2];  // B G R A
  return red;
}

// The highlight region: where the accurate picture (RacorX8, exact) has a specular term
// of at least 13/255 ~ 0.05, i.e. N.H >= 0.05^(1/16) = 0.829.
std::vector<bool> highlightMask() {
  const std::vector<uint8_t> reference = render(true, Precision::Exact);
  std::vector<bool> mask(reference.size());
  for (size_t i = 0; i < mask.size(); ++i) mask[i] = reference[i] >= 13;
  return mask;
}

size_t distinctLevels(const std::vector<uint8_t>& image, const std::vector<bool>& mask) {
  std::set<uint8_t> levels;
  for (size_t i = 0; i < image.size(); ++i)
    if (mask[i]) levels.insert(image[i]);
  return levels.size();
}

TEST(RacorXPrecision, MultiplyBasedSpecularBandsInHardwarePrecisionOnly) {
  const std::vector<bool> mask = highlightMask();
  const size_t area = size_t(std::count(mask.begin(), mask.end(), true));
  // The sphere's projected radius is ~109 pixels (cot(22.5 deg) / sqrt(3^2 - 1) x 128);
  // N.H >= 0.829 is a cap of ~34 degrees around the highlight, ~60 pixels across its
  // radius: thousands of pixels, so every level the gradient crosses shows up.
  ASSERT_GT(area, 2000u);

  const size_t x7hw = distinctLevels(render(false, Precision::Hardware), mask);
  const size_t x8hw = distinctLevels(render(true, Precision::Hardware), mask);
  const size_t x7ex = distinctLevels(render(false, Precision::Exact), mask);
  const size_t x8ex = distinctLevels(render(true, Precision::Exact), mask);
  RecordProperty("racorx7_hardware", int(x7hw));
  RecordProperty("racorx8_hardware", int(x8hw));
  RecordProperty("racorx7_exact", int(x7ex));
  RecordProperty("racorx8_exact", int(x8ex));

  // Hardware: v1 arrives as an 8-bit color, so N.H (dp3 of 8-bit values, result on the
  // 8-bit register grid) takes steps of at least 1/255; within the mask N.H lies in
  // [0.829, 1], at most (1 - 0.829) x 255 + 1 = 44 values, and the four rounded
  // squarings cannot make more levels than their input has: <= 44, taken as 50.
  EXPECT_LE(x7hw, 50u);
  // RacorX8's table is addressed by texm3x2pad/texm3x2tex dot products at texture
  // coordinate precision and filtered between its rows (one row step changes v^16 by up
  // to 16 x 1/256 = 16 levels), so its output reaches most of the 243 levels 13..255:
  // visibly more, at least twice RacorX7's.
  EXPECT_GE(x8hw, 2 * x7hw);
  EXPECT_GE(x8hw, 100u);

  // Exact: the squarings run in fp32 on an fp32 interpolated v1, so RacorX7's term is
  // as continuous as the table's; only the 8-bit target quantizes either. Both reach
  // most of the 243 levels: the difference is small (within a quarter).
  EXPECT_GE(x7ex, 100u);
  EXPECT_GE(4 * x7ex, 3 * x8ex);
  EXPECT_GE(4 * x8ex, 3 * x7ex);
}

}  // namespace
}  // namespace refx
