// Texture sampler throughput in samples per second (items_per_second).
#include <benchmark/benchmark.h>

#include <cstdint>
#include <random>
#include <vector>

#include "refx/resource/sampler.h"

namespace {

using namespace refx;

constexpr int kBatches = 1024;

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

// Batches of four 2x2 quads at random places, each quad stepping `step` texels per pixel.
struct Coords {
  std::vector<float> u, v;
  explicit Coords(float step) : u(kBatches * kBatchLanes), v(kBatches * kBatchLanes) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> pos(-2.0f, 2.0f);
    const float d = step / 256.0f;
    for (int b = 0; b < kBatches; ++b)
      for (int q = 0; q < 4; ++q) {
        float u0 = pos(rng), v0 = pos(rng);
        for (int k = 0; k < 4; ++k) {
          u[b * kBatchLanes + q * 4 + k] = u0 + d * float(k & 1);
          v[b * kBatchLanes + q * 4 + k] = v0 + d * float(k >> 1);
        }
      }
  }
};

void run(benchmark::State& state, const Texture& tex, const SamplerState& ss, float step) {
  Coords c(step);
  float out[4][kBatchLanes];
  int64_t samples = 0;
  int b = 0;
  for (auto _ : state) {
    SampleRequest req;
    req.u = &c.u[b * kBatchLanes];
    req.v = &c.v[b * kBatchLanes];
    sampleTexture(tex, ss, req, out);
    benchmark::DoNotOptimize(out);
    benchmark::ClobberMemory();
    b = (b + 1) % kBatches;
    samples += kBatchLanes;
  }
  state.SetItemsProcessed(samples);
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

void BM_PointRGBA8(benchmark::State& state) {
  auto tex = makeTexture(1);
  SamplerState ss;
  run(state, *tex, ss, 1.0f);
}
BENCHMARK(BM_PointRGBA8);

// Trilinear: quads step 1.5 texels, so every lane blends levels 0 and 1.
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

}  // namespace
