// The specialised 2D kernels against the scalar reference on coherent screen-like
// coordinates (whole batches on one mip level, paired-texel loads across row ends,
// every addressing pair), and PreparedSampler against sampleTexture.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "refx/resource/sampler.h"
#include "resource/sampler_internal.h"

namespace refx {
namespace {

using namespace resource;

constexpr int N = kBatchLanes;

TEST(SamplerFastPaths, CoherentBatchesMatchReference) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const TextureAddress modes[] = {TextureAddress::Wrap, TextureAddress::Mirror,
                                  TextureAddress::Clamp, TextureAddress::MirrorOnce};
  auto tex = Texture::create2D(Format::A8R8G8B8, 64, 32, 0);
  for (int l = 0; l < tex->levelCount(); ++l) {
    uint8_t* p = tex->data(0, l);
    for (size_t i = 0; i < tex->dataSize(0, l); ++i) p[i] = uint8_t(rng());
  }
  tex->markDirty();
  int compared = 0;
  for (int iter = 0; iter < 4000; ++iter) {
    SamplerState s;
    s.addressU = modes[iter % 4];
    s.addressV = modes[(iter / 4) % 4];
    s.magFilter = TextureFilter(1 + rng() % 2);
    s.minFilter = TextureFilter(1 + rng() % 2);
    s.mipFilter = TextureFilter(rng() % 2 ? 1 : 0);
    s.maxMipLevel = rng() % 2;
    // A 4x4 block with 2^-6 .. 2^8 texels per pixel somewhere around [-2, 2]: λ from
    // -6 to 8 (levels 0..6 and beyond), one level for the block most of the time.
    const float step = std::exp2(unit(rng) * 14 - 6) / 64.0f, rot = unit(rng) * 6.3f;
    const float u0 = unit(rng) * 4 - 2, v0 = unit(rng) * 4 - 2;
    alignas(64) float u[N], v[N], w[N] = {};
    for (int l = 0; l < N; ++l) {
      const int q = l / 4;
      const float x = float((q & 1) * 2 + (l & 1)), y = float((q >> 1) * 2 + ((l >> 1) & 1));
      u[l] = u0 + step * (x * std::cos(rot) - y * std::sin(rot));
      v[l] = v0 + step * (x * std::sin(rot) + y * std::cos(rot));
    }
    SampleRequest req;
    req.u = u, req.v = v, req.w = w;
    req.laneMask = iter % 5 == 0 ? uint16_t(rng()) : uint16_t(0xffff);
    float fast[4][N], ref[4][N];
    sampleTexture(*tex, s, req, fast);
    sampleTextureReference(*tex, s, req, ref);
    for (int ch = 0; ch < 4; ++ch)
      for (int l = 0; l < N; ++l) {
        ASSERT_EQ(fast[ch][l], ref[ch][l]) << "iter " << iter << " ch " << ch << " lane " << l;
        ++compared;
      }
  }
  EXPECT_EQ(compared, 4000 * 4 * N);
}

// WRAP at the ends of the period: u = -tiny reduces to u - floor(u) = 1.0f, so POINT
// reads texel floor(1·W) = W -> wraps to 0 and LINEAR texels W - 1 and W -> 0 with
// weight round((W - 0.5 - (W - 1))·256)/256 = 128/256.
TEST(SamplerFastPaths, WrapAtThePeriodEnds) {
  auto tex = Texture::create2D(Format::A8R8G8B8, 4, 3, 1);
  uint8_t* p = tex->data(0, 0);
  for (size_t i = 0; i < tex->dataSize(0, 0); ++i) p[i] = uint8_t(37 * i + 11);
  tex->markDirty();
  const float ends[] = {-1e-9f, -1e-30f, -0.0f, 0.0f, 1.0f, -1.0f, 1e-9f, 0.99999994f};
  alignas(64) float u[N], v[N];
  for (int l = 0; l < N; ++l) u[l] = ends[l % 8], v[l] = ends[(l + 3) % 8];
  for (TextureFilter f : {TextureFilter::Point, TextureFilter::Linear}) {
    SamplerState s;
    s.magFilter = s.minFilter = f;
    SampleRequest req;
    req.u = u, req.v = v;
    float fast[4][N], ref[4][N];
    sampleTexture(*tex, s, req, fast);
    sampleTextureReference(*tex, s, req, ref);
    for (int ch = 0; ch < 4; ++ch)
      for (int l = 0; l < N; ++l) ASSERT_EQ(fast[ch][l], ref[ch][l]) << "ch " << ch << " lane " << l;
    // lane 0: u = v = -1e-9 (v from ends[3] = 0 here: row 0). POINT: texel (0, 0) red.
    if (f == TextureFilter::Point) {
      EXPECT_EQ(fast[0][0], float(p[2]) / 255.0f);
    }
    // LINEAR, lane 0: x between texels 3 and 0 at weight 1/2, y = 0·3 - 0.5: rows 2 and 0
    // at 1/2: red = (p(3,0) + p(0,0) + p(3,2) + p(0,2))·1/4.
    if (f == TextureFilter::Linear) {
      auto red = [&](int x, int y) { return float(p[(y * 4 + x) * 4 + 2]); };
      const float sum = red(3, 0) + red(0, 0) + red(3, 2) + red(0, 2);  // exact, ·16384 = S
      EXPECT_EQ(fast[0][0], sum * 16384.0f / (255.0f * 65536.0f));
    }
  }
}

// A PreparedSampler gives what sampleTexture gives, for every kind of request.
TEST(SamplerFastPaths, PreparedSamplerMatchesSampleTexture) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const TextureAddress modes[] = {TextureAddress::Wrap, TextureAddress::Mirror,
                                  TextureAddress::Clamp, TextureAddress::MirrorOnce,
                                  TextureAddress::Border};
  const TexturePtr textures[] = {Texture::create2D(Format::A8R8G8B8, 64, 32, 0),
                                 Texture::create2D(Format::A8R8G8B8, 16, 16, 1),
                                 Texture::createCube(Format::A8R8G8B8, 8, 0),
                                 Texture::create2D(Format::A32B32G32R32F, 8, 8, 0)};
  for (const auto& tex : textures) {
    for (int f = 0; f < tex->faceCount(); ++f)
      for (int l = 0; l < tex->levelCount(); ++l) {
        uint8_t* p = tex->data(f, l);
        for (size_t i = 0; i < tex->dataSize(f, l); ++i) p[i] = uint8_t(rng());
      }
    tex->markDirty();
  }
  int compared = 0, implicitCompared = 0;
  for (int iter = 0; iter < 2000; ++iter) {
    const Texture& tex = *textures[iter % 4];
    SamplerState s;
    s.addressU = modes[rng() % 5];
    s.addressV = modes[rng() % 5];
    s.magFilter = TextureFilter(rng() % 3);
    s.minFilter = TextureFilter(rng() % 3);
    s.mipFilter = TextureFilter(rng() % 3);
    s.maxMipLevel = rng() % 3;
    s.mipLodBias = rng() % 2 ? 0.0f : unit(rng) * 2 - 1;
    const PreparedSampler prepared(tex, s);
    const float step = std::exp2(unit(rng) * 14 - 6) / 64.0f, u0 = unit(rng) * 4 - 2;
    alignas(64) float u[N], v[N], w[N], lod[N];
    for (int l = 0; l < N; ++l) {
      const int q = l / 4;
      u[l] = u0 + step * float((q & 1) * 2 + (l & 1)) + (iter % 3 == 0 ? unit(rng) : 0.0f);
      v[l] = u0 + step * float((q >> 1) * 2 + ((l >> 1) & 1));
      w[l] = unit(rng) * 2 - 1;
      lod[l] = unit(rng) * 6 - 2;
    }
    SampleRequest req;
    req.u = u, req.v = v, req.w = w, req.lod = lod;
    req.lodMode = LodMode(rng() % 3);
    req.laneMask = iter % 5 == 0 ? uint16_t(rng()) : uint16_t(0xffff);
    float a[4][N], b[4][N];
    sampleTexture(tex, s, req, a);
    prepared.sample(req, b);
    for (int ch = 0; ch < 4; ++ch)
      for (int l = 0; l < N; ++l) {
        ASSERT_EQ(std::memcmp(&a[ch][l], &b[ch][l], 4), 0) << "iter " << iter << " ch " << ch;
        ++compared;
      }
    if (req.lodMode == LodMode::Derivatives) {  // the same request through sampleImplicit
      float c[4][N];
      prepared.sampleImplicit(u, v, w, req.laneMask, c);
      ASSERT_EQ(std::memcmp(a, c, sizeof a), 0) << "iter " << iter;
      ++implicitCompared;
    }
  }
  EXPECT_EQ(compared, 2000 * 4 * N);
  EXPECT_GT(implicitCompared, 500);  // about a third of the requests
}

TEST(SamplerFastPaths, PointSamplingGivesEveryByteOver255) {
  // A 256x1 texture whose texel i holds the byte i in all four channels: POINT at texel
  // centres returns exactly i/255 (D3D's unorm conversion), for every byte value.
  auto tex = Texture::create2D(Format::A8R8G8B8, 256, 1, 1);
  uint8_t* p = tex->data(0, 0);
  for (int i = 0; i < 256; ++i) std::fill_n(p + 4 * i, 4, uint8_t(i));
  tex->markDirty();
  const SamplerState s;  // POINT, WRAP
  for (int first = 0; first < 256; first += N) {
    alignas(64) float u[N], v[N];
    for (int l = 0; l < N; ++l) u[l] = (float(first + l) + 0.5f) / 256.0f, v[l] = 0.5f;
    SampleRequest req;
    req.u = u, req.v = v;
    float out[4][N];
    sampleTexture(*tex, s, req, out);
    for (int ch = 0; ch < 4; ++ch)
      for (int l = 0; l < N; ++l)
        ASSERT_EQ(out[ch][l], float(first + l) / 255.0f) << "byte " << first + l << " ch " << ch;
  }
}

TEST(SamplerFastPaths, PreparedSamplerFollowsLevelChangesBetweenBatches) {
  // One prepared sampler over many batches whose footprint, and so level and filter,
  // changes from batch to batch in a pattern (2, 2, 1, 3, ... texels per pixel and
  // magnification): each batch must give what sampleTexture gives, whatever level
  // the batches before it used.
  auto tex = Texture::create2D(Format::A8R8G8B8, 64, 64, 0);
  std::mt19937 rng(3);
  for (int l = 0; l < tex->levelCount(); ++l) {
    uint8_t* p = tex->data(0, l);
    for (size_t i = 0; i < tex->dataSize(0, l); ++i) p[i] = uint8_t(rng());
  }
  tex->markDirty();
  SamplerState s;
  s.magFilter = TextureFilter::Point;  // magnified batches switch filter as well as level
  s.minFilter = TextureFilter::Linear;
  s.mipFilter = TextureFilter::Point;
  const PreparedSampler prepared(*tex, s);
  const float texelsPerPixel[] = {2, 2, 1, 4, 4, 0.5f, 8, 2, 1, 1, 16, 0.25f};
  int mismatches = 0;
  for (int batch = 0; batch < 240; ++batch) {
    const float step = texelsPerPixel[batch % 12] / 64.0f, u0 = float(batch % 7) * 0.1f;
    alignas(64) float u[N], v[N];
    for (int l = 0; l < N; ++l) {
      const int q = l / 4;
      u[l] = u0 + step * float((q & 1) * 2 + (l & 1));
      v[l] = u0 + step * float((q >> 1) * 2 + ((l >> 1) & 1));
    }
    SampleRequest req;
    req.u = u, req.v = v;
    req.lodMode = LodMode::Derivatives;
    float a[4][N], b[4][N];
    sampleTexture(*tex, s, req, a);
    prepared.sample(req, b);
    mismatches += std::memcmp(a, b, sizeof a) != 0;
  }
  EXPECT_EQ(mismatches, 0);
}

}  // namespace
}  // namespace refx
