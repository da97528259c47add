// Texture sampler throughput in samples per second (items_per_second).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <algorithm>
#include <array>
#include <random>
#include <vector>

#include "refx/resource/sampler.h"

namespace {

using namespace refx;

// A 256x256 A8R8G8B8 texture with noise texels.
TexturePtr makeTexture(int levels) {
  auto tex = Texture::create2D(Format::A8R8G8B8, 256, 256, levels);
  std::mt19937 rng(7);
  for (int l = 0; l < tex->levelCount(); ++l) {
    uint8_t* p = tex->data(0, l);
    for (size_t i = 0; i < tex->dataSize(0, l); ++i) p[i] = uint8_t(rng());
  }
  tex->markDirty();
  return tex;
}

// Coordinates of a 256x256-pixel screen area textured with `step` texels per pixel
// (rotated a little so rows do not line up with texel rows), as the rasterizer hands
// them over: 4x4 blocks of four 2x2 quads, lane = quad*4 + (y&1)*2 + (x&1).
struct Coords {
  std::vector<float> u, v;
  // stretch: x (across) covers `stretch` times as many texels as y (an anisotropic
  // footprint of stretch:1).
  Coords(float step, bool scattered, float stretch = 1.0f) {
    const int blocks = 64 * 64;
    u.resize(blocks * kBatchLanes), v.resize(blocks * kBatchLanes);
    const float c = std::cos(0.3f) * step / 256.0f, s = std::sin(0.3f) * step / 256.0f;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> pos(-2.0f, 2.0f);
    for (int b = 0; b < blocks; ++b) {
      // scattered: every block somewhere else on the texture (cache-unfriendly)
      const float u0 = scattered ? pos(rng) : 0.0f, v0 = scattered ? pos(rng) : 0.0f;
      for (int lane = 0; lane < kBatchLanes; ++lane) {
        const int q = lane / 4;
        const int x = (b % 64) * 4 + (q & 1) * 2 + (lane & 1);
        const int y = (b / 64) * 4 + (q >> 1) * 2 + ((lane >> 1) & 1);
        const float px = (scattered ? float(x % 4) : float(x)) * stretch;
        const float py = scattered ? float(y % 4) : float(y);
        u[b * kBatchLanes + lane] = u0 + px * c - py * s;
        v[b * kBatchLanes + lane] = v0 + px * s + py * c;
      }
    }
  }
  int batches() const { return int(u.size()) / kBatchLanes; }
};

// Samples batch after batch with sample(req, out) (sampleTexture or a prepared sampler).
template <class Sample>
void runWith(benchmark::State& state, float step, bool scattered, Sample sample,
             float stretch = 1.0f) {
  Coords c(step, scattered, stretch);
  float out[4][kBatchLanes];
  int64_t samples = 0;
  int b = 0;
  for (auto _ : state) {
    SampleRequest req;
    req.u = &c.u[b * kBatchLanes];
    req.v = &c.v[b * kBatchLanes];
    sample(req, out);
    benchmark::DoNotOptimize(out);
    benchmark::ClobberMemory();
    b = b + 1 == c.batches() ? 0 : b + 1;
    samples += kBatchLanes;
  }
  state.SetItemsProcessed(samples);
}

void run(benchmark::State& state, const Texture& tex, const SamplerState& ss, float step,
         bool scattered = false) {
  runWith(state, step, scattered,
          [&](const SampleRequest& req, float (*out)[kBatchLanes]) { sampleTexture(tex, ss, req, out); });
}

void BM_BilinearRGBA8(benchmark::State& state) {
  auto tex = makeTexture(1);
  SamplerState ss;
  ss.magFilter = ss.minFilter = TextureFilter::Linear;
  run(state, *tex, ss, 1.0f);
}
BENCHMARK(BM_BilinearRGBA8);

void BM_BilinearRGBA8Clamp(benchmark::State& state) {
  auto tex = makeTexture(1);
  SamplerState ss;
  ss.magFilter = ss.minFilter = TextureFilter::Linear;
  ss.addressU = ss.addressV = TextureAddress::Clamp;
  run(state, *tex, ss, 1.0f);
}
BENCHMARK(BM_BilinearRGBA8Clamp);

// Every 4x4 block at a random place: texel fetches mostly miss the L1 cache.
void BM_BilinearRGBA8Scattered(benchmark::State& state) {
  auto tex = makeTexture(1);
  SamplerState ss;
  ss.magFilter = ss.minFilter = TextureFilter::Linear;
  run(state, *tex, ss, 1.0f, true);
}
BENCHMARK(BM_BilinearRGBA8Scattered);

// LINEAR_MIPMAP_NEAREST, as the benchmark scenes sample: λ per quad picks one level
// for the batch (here level 0, 1.3 texels per pixel as on the 1024x768 quad).
void BM_BilinearMipNearestRGBA8(benchmark::State& state) {
  auto tex = makeTexture(0);
  SamplerState ss;
  ss.magFilter = ss.minFilter = TextureFilter::Linear;
  ss.mipFilter = TextureFilter::Point;
  const PreparedSampler prepared(*tex, ss);
  runWith(state, 1.3f, false,
          [&](const SampleRequest& req, float (*out)[kBatchLanes]) { prepared.sample(req, out); });
}
BENCHMARK(BM_BilinearMipNearestRGBA8);

void BM_PointRGBA8(benchmark::State& state) {
  auto tex = makeTexture(1);
  SamplerState ss;
  run(state, *tex, ss, 1.0f);
}
BENCHMARK(BM_PointRGBA8);

// Trilinear: 1.5 texels per pixel, so every lane blends levels 0 and 1.
void BM_TrilinearRGBA8(benchmark::State& state) {
  auto tex = makeTexture(0);
  SamplerState ss;
  ss.magFilter = ss.minFilter = ss.mipFilter = TextureFilter::Linear;
  run(state, *tex, ss, 1.5f);
}
BENCHMARK(BM_TrilinearRGBA8);

// The scalar path: BORDER addressing is not handled by the vectorised kernel.
void BM_BilinearRGBA8Border(benchmark::State& state) {
  auto tex = makeTexture(1);
  SamplerState ss;
  ss.magFilter = ss.minFilter = TextureFilter::Linear;
  ss.addressU = ss.addressV = TextureAddress::Border;
  run(state, *tex, ss, 1.0f);
}
BENCHMARK(BM_BilinearRGBA8Border);

// ANISOTROPIC, MAXANISOTROPY 4, trilinear probes: a 4:1 footprint (4 texels across,
// 1 down) gives N = 4 probes per sample at λ = log2(4/4) = 0 (levels 0 and 1 blended
// where rounding leaves λ above 0).
void BM_AnisotropicRGBA8(benchmark::State& state) {
  auto tex = makeTexture(0);
  SamplerState ss;
  ss.magFilter = ss.minFilter = TextureFilter::Anisotropic;
  ss.mipFilter = TextureFilter::Linear;
  ss.maxAnisotropy = 4;
  runWith(state, 1.0f, false,
          [&](const SampleRequest& req, float (*out)[kBatchLanes]) { sampleTexture(*tex, ss, req, out); },
          4.0f);
}
BENCHMARK(BM_AnisotropicRGBA8);

// The same footprint through LINEAR (one trilinear sample at λ = 2), for comparison.
void BM_TrilinearRGBA8Stretched(benchmark::State& state) {
  auto tex = makeTexture(0);
  SamplerState ss;
  ss.magFilter = ss.minFilter = ss.mipFilter = TextureFilter::Linear;
  runWith(state, 1.0f, false,
          [&](const SampleRequest& req, float (*out)[kBatchLanes]) { sampleTexture(*tex, ss, req, out); },
          4.0f);
}
BENCHMARK(BM_TrilinearRGBA8Stretched);

// LINEAR_MIPMAP_NEAREST as BM_BilinearMipNearestRGBA8, looked up kMaxSampleGroup
// batches at a time (PreparedSampler::sampleImplicitGroup), and for two textures at the same
// coordinates (sampleImplicitPairGroup, counted as two samples a lane).
void runGroups(benchmark::State& state, bool pair) {
  auto texA = makeTexture(0), texB = makeTexture(0);
  SamplerState ss;
  ss.magFilter = ss.minFilter = TextureFilter::Linear;
  ss.mipFilter = TextureFilter::Point;
  const PreparedSampler a(*texA, ss), b(*texB, ss);
  Coords c(1.3f, false);
  std::vector<float> w(c.u.size(), 0.0f);
  // The coordinate rows u, v, w of each batch side by side, as registers hold them.
  std::vector<std::array<float, 3 * kBatchLanes>> rows(size_t(c.batches()));
  for (int i = 0; i < c.batches(); ++i)
    for (int l = 0; l < kBatchLanes; ++l)
      rows[size_t(i)][size_t(l)] = c.u[size_t(i * kBatchLanes + l)],
      rows[size_t(i)][size_t(kBatchLanes + l)] = c.v[size_t(i * kBatchLanes + l)];
  alignas(64) float outA[kMaxSampleGroup][4][kBatchLanes], outB[kMaxSampleGroup][4][kBatchLanes];
  uint16_t masks[kMaxSampleGroup];
  std::fill_n(masks, kMaxSampleGroup, uint16_t(0xffff));
  int64_t samples = 0;
  int first = 0;
  for (auto _ : state) {
    SampleBatch batchesA[kMaxSampleGroup], batchesB[kMaxSampleGroup];
    for (int g = 0; g < kMaxSampleGroup; ++g) {
      const auto* co = reinterpret_cast<const float(*)[kBatchLanes]>(rows[size_t(first + g)].data());
      batchesA[g] = {co, outA[g]}, batchesB[g] = {co, outB[g]};
    }
    if (pair)
      PreparedSampler::sampleImplicitPairGroup(a, b, kMaxSampleGroup, masks, batchesA, batchesB);
    else
      a.sampleImplicitGroup(kMaxSampleGroup, masks, batchesA);
    benchmark::DoNotOptimize(outA);
    benchmark::DoNotOptimize(outB);
    benchmark::ClobberMemory();
    first = first + 2 * kMaxSampleGroup > c.batches() ? 0 : first + kMaxSampleGroup;
    samples += kMaxSampleGroup * kBatchLanes * (pair ? 2 : 1);
  }
  state.SetItemsProcessed(samples);
}
void BM_BilinearMipNearestGroupRGBA8(benchmark::State& state) { runGroups(state, false); }
BENCHMARK(BM_BilinearMipNearestGroupRGBA8);
void BM_BilinearMipNearestPairGroupRGBA8(benchmark::State& state) { runGroups(state, true); }
BENCHMARK(BM_BilinearMipNearestPairGroupRGBA8);

}  // namespace
