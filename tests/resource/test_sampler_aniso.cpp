// ANISOTROPIC filtering: the batched path against the lane-by-lane reference on random
// footprints, textures and states (bit for bit), MAXANISOTROPY 1 against LINEAR, and
// hand-derived probe averages and level choices (2D and cube).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "refx/resource/sampler.h"
#include "resource/sampler_internal.h"

namespace refx {
namespace {

using namespace resource;

constexpr int N = kBatchLanes;

void fillRandom(Texture& tex, std::mt19937& rng) {
  const bool isFloat = tex.format() == Format::A32B32G32R32F;
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int f = 0; f < tex.faceCount(); ++f)
    for (int l = 0; l < tex.levelCount(); ++l) {
      uint8_t* p = tex.data(f, l);
      const size_t n = tex.dataSize(f, l);
      if (isFloat) {  // finite values in [0, 1]: no NaN texels to compare
        for (size_t i = 0; i + 4 <= n; i += 4) {
          const float v = unit(rng);
          std::memcpy(p + i, &v, 4);
        }
      } else {
        for (size_t i = 0; i < n; ++i) p[i] = uint8_t(rng());
      }
    }
  tex.markDirty();
}

// Equal bits, or both NaN.
bool sameValue(float a, float b) {
  return std::memcmp(&a, &b, 4) == 0 || (std::isnan(a) && std::isnan(b));
}

TEST(SamplerAnisotropic, BatchedMatchesReference) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const TextureAddress modes[] = {TextureAddress::Wrap, TextureAddress::Mirror,
                                  TextureAddress::Clamp, TextureAddress::MirrorOnce,
                                  TextureAddress::Border};
  const TexturePtr textures[] = {Texture::create2D(Format::A8R8G8B8, 64, 32, 0),
                                 Texture::create2D(Format::A8R8G8B8, 20, 12, 0),
                                 Texture::create2D(Format::A8R8G8B8, 16, 16, 1),
                                 Texture::createCube(Format::A8R8G8B8, 16, 0),
                                 Texture::create2D(Format::A32B32G32R32F, 16, 8, 0),
                                 Texture::createCube(Format::A32B32G32R32F, 8, 0)};
  for (const auto& tex : textures) fillRandom(*tex, rng);
  const TextureFilter filters[] = {TextureFilter::Point, TextureFilter::Linear,
                                   TextureFilter::Anisotropic};
  int compared = 0, anisoBatches = 0;
  for (int iter = 0; iter < 6000; ++iter) {
    const Texture& tex = *textures[iter % 6];
    const bool cube = tex.type() == TextureType::Cube;
    SamplerState s;
    s.addressU = modes[rng() % 5];
    s.addressV = modes[rng() % 5];
    s.borderColor = {0.25f, 0.5f, 0.75f, 1.0f};
    s.minFilter = filters[rng() % 3];
    s.magFilter = filters[rng() % 3];
    if (rng() % 2) s.minFilter = TextureFilter::Anisotropic;
    s.mipFilter = TextureFilter(rng() % 3);
    s.maxMipLevel = rng() % 3;
    s.maxAnisotropy = rng() % 20;  // 0 and 17..19 are clamped to [1, 16]
    s.mipLodBias = rng() % 2 ? 0.0f : unit(rng) * 4 - 2;
    s.srgb = rng() % 6 == 0;
    anisoBatches += s.minFilter == TextureFilter::Anisotropic ||
                    s.magFilter == TextureFilter::Anisotropic;

    // Each quad: a random centre and two random derivative vectors, lengths 2^-5 .. 2^7
    // texels of a 16-texel level, in any directions (stretched, sheared, degenerate).
    alignas(64) float c[3][N], lod[N], ddx[3][N], ddy[3][N];
    for (int q = 0; q < N / 4; ++q) {
      float centre[3], dx[3], dy[3];
      for (int k = 0; k < 3; ++k) centre[k] = unit(rng) * 4 - 2;
      if (cube) centre[rng() % 3] = rng() % 2 ? 1.0f : -1.0f;
      const float lx = std::exp2(unit(rng) * 12 - 5) / 16.0f;
      const float ly = rng() % 8 == 0 ? 0.0f : std::exp2(unit(rng) * 12 - 5) / 16.0f;
      for (int k = 0; k < 3; ++k) {
        dx[k] = (unit(rng) * 2 - 1) * lx;
        dy[k] = (unit(rng) * 2 - 1) * ly;
      }
      if (!cube) dx[2] = dy[2] = 0;
      for (int k4 = 0; k4 < 4; ++k4) {
        const int l = q * 4 + k4;
        const float fx = float(k4 & 1), fy = float(k4 >> 1);
        for (int k = 0; k < 3; ++k) {
          c[k][l] = centre[k] + fx * dx[k] + fy * dy[k];
          ddx[k][l] = dx[k] * (0.5f + unit(rng));
          ddy[k][l] = dy[k] * (0.5f + unit(rng));
        }
        lod[l] = unit(rng) * 6 - 2;
      }
    }
    SampleRequest req;
    req.u = c[0], req.v = c[1], req.w = c[2], req.lod = lod;
    for (int k = 0; k < 3; ++k) req.ddx[k] = ddx[k], req.ddy[k] = ddy[k];
    req.lodMode = LodMode(rng() % 4);
    req.laneMask = iter % 5 == 0 ? uint16_t(rng()) : uint16_t(0xffff);
    float fast[4][N], ref[4][N], prep[4][N];
    sampleTexture(tex, s, req, fast);
    sampleTextureReference(tex, s, req, ref);
    PreparedSampler(tex, s).sample(req, prep);
    for (int ch = 0; ch < 4; ++ch)
      for (int l = 0; l < N; ++l) {
        ASSERT_TRUE(sameValue(fast[ch][l], ref[ch][l]))
            << "iter " << iter << " ch " << ch << " lane " << l << ": " << fast[ch][l]
            << " != " << ref[ch][l];
        ASSERT_TRUE(sameValue(fast[ch][l], prep[ch][l])) << "iter " << iter;
        ++compared;
      }
  }
  EXPECT_EQ(compared, 6000 * 4 * N);
  EXPECT_GT(anisoBatches, 3000);
}

// MAXANISOTROPY 1 (and 0, clamped to 1): one probe at the sample point and λ unchanged,
// so the reference's anisotropic path gives what LINEAR gives.
TEST(SamplerAnisotropic, MaxAnisotropyOneIsLinear) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  auto tex = Texture::create2D(Format::A8R8G8B8, 32, 32, 0);
  auto cubeTex = Texture::createCube(Format::A8R8G8B8, 8, 0);
  fillRandom(*tex, rng);
  fillRandom(*cubeTex, rng);
  for (int iter = 0; iter < 1000; ++iter) {
    const Texture& t = iter % 2 ? *cubeTex : *tex;
    SamplerState aniso, linear;
    linear.minFilter = linear.magFilter = TextureFilter::Linear;
    linear.mipFilter = aniso.mipFilter = TextureFilter(rng() % 3);
    aniso.minFilter = aniso.magFilter = TextureFilter::Anisotropic;
    aniso.maxAnisotropy = iter % 3 == 0 ? 0 : 1;
    alignas(64) float c[3][N];
    const float step = std::exp2(unit(rng) * 10 - 6);
    for (int l = 0; l < N; ++l) {
      c[0][l] = unit(rng) * 2 - 1 + step * float(l & 1);
      c[1][l] = unit(rng) * 2 - 1 + step * 4 * float((l >> 1) & 1);
      c[2][l] = 1;
    }
    SampleRequest req;
    req.u = c[0], req.v = c[1], req.w = c[2];
    float a[4][N], b[4][N];
    sampleTextureReference(t, aniso, req, a);
    sampleTexture(t, linear, req, b);
    ASSERT_EQ(std::memcmp(a, b, sizeof a), 0) << "iter " << iter;
  }
}

// A 16x1 texture, MIPFILTER NONE, CLAMP. The quad's u changes by 4 texels per pixel
// across (du = 4/16) and v by 1 texel down (dv = 1/1): Pmax = 4, Pmin = 1, so with
// MAXANISOTROPY 4, N = ceil(4/1) = 4 probes at offsets (i + 0.5)/4 - 0.5 = -3/8, -1/8,
// 1/8, 3/8 of the major axis, i.e. -1.5, -0.5, 0.5, 1.5 texels. Lane 0 sits at texel
// position u·16 = 8, so the probes land on the centres 6.5, 7.5, 8.5, 9.5 of texels
// 6..9: bilinear weight 0, each probe is its texel, and the result is their mean.
TEST(SamplerAnisotropic, ProbesAverageAlongTheMajorAxis) {
  auto tex = Texture::create2D(Format::A8R8G8B8, 16, 1, 1);
  uint8_t* p = tex->data(0, 0);
  std::memset(p, 0, tex->dataSize(0, 0));
  const uint8_t red[4] = {10, 50, 90, 250};  // texels 6..9; byte 2 of B8G8R8A8 is red
  for (int i = 0; i < 4; ++i) p[(6 + i) * 4 + 2] = red[i];
  tex->markDirty();
  SamplerState s;
  s.addressU = s.addressV = TextureAddress::Clamp;
  s.minFilter = s.magFilter = TextureFilter::Anisotropic;
  alignas(64) float u[N], v[N];
  for (int l = 0; l < N; ++l) {
    u[l] = 0.5f + 0.25f * float(l & 1);
    v[l] = 0.5f + 1.0f * float((l >> 1) & 1);
  }
  SampleRequest req;
  req.u = u, req.v = v;
  float out[4][N];
  for (uint32_t maxAniso : {4u, 16u}) {
    s.maxAnisotropy = maxAniso;  // 16: N = min(4, 16) = 4 as well
    sampleTexture(*tex, s, req, out);
    // (10 + 50 + 90 + 250)/4 = 100.
    EXPECT_NEAR(out[0][0], 100.0f / 255.0f, 1e-6f) << maxAniso;
    EXPECT_EQ(out[1][0], 0.0f);
  }
  // MAXANISOTROPY 2: N = 2 probes at -1/4, 1/4 of the axis = -1, +1 texel: positions 7
  // and 9, halfway between texel centres: (10 + 50)/2 = 30 and (90 + 250)/2 = 170,
  // mean 100 again (the same four texels, equally weighted).
  s.maxAnisotropy = 2;
  sampleTexture(*tex, s, req, out);
  EXPECT_NEAR(out[0][0], 100.0f / 255.0f, 1e-6f);
  // LINEAR: one sample at position 8, halfway between the centres of texels 7 and 8:
  // (50 + 90)/2 = 70.
  s.minFilter = s.magFilter = TextureFilter::Linear;
  sampleTexture(*tex, s, req, out);
  EXPECT_NEAR(out[0][0], (50.0f + 90.0f) / 2.0f / 255.0f, 1e-6f);
}

// A 16x16 cube map with mip colors (level i: red = 40·(i + 1)), MIPFILTER POINT,
// sampled by texldd around +Z (direction (0, 0, 1): u = (x/z + 1)/2, v = (-y/z + 1)/2,
// du/dx_dir = 1/2 there). ddx = (0.5, 0, 0): du = 0.25 = 4 texels of 16;
// ddy = (0, 0.125, 0): dv = -0.0625 = 1 texel. Pmax = 4, Pmin = 1:
//   LINEAR: λ = log2 4 = 2 -> level 2
//   ANISOTROPIC, MAXANISOTROPY 4: N = 4, λ = log2(4/4) = 0 -> level 0
//   ANISOTROPIC, MAXANISOTROPY 2: N = 2, λ = log2(4/2) = 1 -> level 1
// The probes stay on +Z (x offsets up to 3/8 · 0.5 < 1), and every level is solid.
TEST(SamplerAnisotropic, CubeLevelFromTheFootprint) {
  auto tex = Texture::createCube(Format::A8R8G8B8, 16, 0);
  for (int f = 0; f < 6; ++f)
    for (int l = 0; l < tex->levelCount(); ++l) {
      uint8_t* p = tex->data(f, l);
      for (size_t i = 0; i < tex->dataSize(f, l); i += 4) p[i + 2] = uint8_t(40 * (l + 1));
    }
  tex->markDirty();
  alignas(64) float x[N], y[N], z[N], dx0[N], dy1[N], zero[N] = {};
  for (int l = 0; l < N; ++l) x[l] = y[l] = 0, z[l] = 1, dx0[l] = 0.5f, dy1[l] = 0.125f;
  SampleRequest req;
  req.u = x, req.v = y, req.w = z;
  req.lodMode = LodMode::Gradients;
  req.ddx[0] = dx0, req.ddx[1] = zero, req.ddx[2] = zero;
  req.ddy[0] = zero, req.ddy[1] = dy1, req.ddy[2] = zero;
  SamplerState s;
  s.mipFilter = TextureFilter::Point;
  const struct {
    TextureFilter filter;
    uint32_t maxAniso;
    int level;
  } cases[] = {{TextureFilter::Linear, 1, 2},
               {TextureFilter::Anisotropic, 4, 0},
               {TextureFilter::Anisotropic, 2, 1},
               {TextureFilter::Anisotropic, 1, 2}};
  for (const auto& k : cases) {
    s.minFilter = s.magFilter = k.filter;
    s.maxAnisotropy = k.maxAniso;
    float out[4][N], ref[4][N];
    sampleTexture(*tex, s, req, out);
    sampleTextureReference(*tex, s, req, ref);
    for (int l = 0; l < N; ++l) {
      EXPECT_EQ(out[0][l], float(40 * (k.level + 1)) / 255.0f) << k.maxAniso << " lane " << l;
      EXPECT_EQ(out[0][l], ref[0][l]);
    }
  }
}

// Volume textures do not claim anisotropic filtering (no VolumeTextureFilterCaps bit):
// ANISOTROPIC samples them as LINEAR, whatever MAXANISOTROPY.
TEST(SamplerAnisotropic, VolumeTexturesFilterAsLinear) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  auto tex = Texture::createVolume(Format::A8R8G8B8, 16, 8, 4, 0);
  fillRandom(*tex, rng);
  for (int iter = 0; iter < 200; ++iter) {
    SamplerState aniso, linear;
    linear.minFilter = linear.magFilter = TextureFilter::Linear;
    aniso.minFilter = aniso.magFilter = TextureFilter::Anisotropic;
    aniso.maxAnisotropy = 16;
    aniso.mipFilter = linear.mipFilter = TextureFilter(rng() % 3);
    alignas(64) float c[3][N];
    for (int l = 0; l < N; ++l) {  // 8:1 stretched quads
      c[0][l] = unit(rng) + 0.5f * float(l & 1);
      c[1][l] = unit(rng) + 0.0625f * float((l >> 1) & 1);
      c[2][l] = unit(rng);
    }
    SampleRequest req;
    req.u = c[0], req.v = c[1], req.w = c[2];
    float a[4][N], b[4][N], r[4][N];
    sampleTexture(*tex, aniso, req, a);
    sampleTexture(*tex, linear, req, b);
    sampleTextureReference(*tex, aniso, req, r);
    ASSERT_EQ(std::memcmp(a, b, sizeof a), 0) << "iter " << iter;
    ASSERT_EQ(std::memcmp(r, b, sizeof r), 0) << "iter " << iter;
  }
}

}  // namespace
}  // namespace refx
