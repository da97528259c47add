// The instruction-set variants of the 2D kernels (AVX2: two 8-lane halves, AVX-512: 16
// lanes at once) agree bit for bit with each other and with the scalar reference, on
// random and special coordinates, every addressing pair, both filters, every lane mask.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "refx/core/cpu_features.h"
#include "refx/resource/sampler.h"
#include "resource/sampler_internal.h"
#include "resource/sampler_kernels.h"

namespace refx {
namespace {

using namespace resource;

constexpr int N = kBatchLanes;
constexpr TextureAddress kModes[] = {TextureAddress::Wrap, TextureAddress::Mirror,
                                     TextureAddress::Clamp, TextureAddress::MirrorOnce};

TexturePtr randomTexture(int w, int h, int levels, uint32_t seed) {
  auto tex = Texture::create2D(Format::A8R8G8B8, w, h, levels);
  std::mt19937 rng(seed);
  for (int l = 0; l < tex->levelCount(); ++l) {
    uint8_t* p = tex->data(0, l);
    for (size_t i = 0; i < tex->dataSize(0, l); ++i) p[i] = uint8_t(rng());
  }
  tex->markDirty();
  return tex;
}

// Coordinates of one batch, by kind: anywhere in [-4, 4]; a small screen-like block (the
// common case, whose 2x2 texels are adjacent in memory); texel centres and edges; values
// at and beyond the limits (NaN, infinities, huge, tiny, -0).
void fillCoords(std::mt19937& rng, int kind, int w, int h, float* u, float* v) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const float inf = std::numeric_limits<float>::infinity();
  const float special[] = {std::numeric_limits<float>::quiet_NaN(), inf, -inf, 1e30f, -1e30f,
                           4194304.0f, -4194305.0f, -0.0f, 0.0f, 1.0f, -1.0f, 1e-30f, -1e-30f,
                           0.99999994f, 2.0f, -2.5f};
  const float u0 = unit(rng) * 8 - 4, v0 = unit(rng) * 8 - 4;
  const float step = std::exp2(unit(rng) * 8 - 6) / float(w);
  for (int l = 0; l < N; ++l) {
    switch (kind) {
      case 0:
        u[l] = unit(rng) * 8 - 4, v[l] = unit(rng) * 8 - 4;
        break;
      case 1:
        u[l] = u0 + step * float((l >> 2 & 1) * 2 + (l & 1));
        v[l] = v0 + step * float((l >> 3) * 2 + (l >> 1 & 1));
        break;
      case 2:  // centres (k + 0.5)/W and edges k/W of texels, k in [-W, 2W]
        u[l] = (float(int(rng() % (3 * w)) - w) + (rng() % 2 ? 0.5f : 0.0f)) / float(w);
        v[l] = (float(int(rng() % (3 * h)) - h) + (rng() % 2 ? 0.5f : 0.0f)) / float(h);
        break;
      default:
        u[l] = special[rng() % 16], v[l] = rng() % 2 ? special[rng() % 16] : unit(rng);
        break;
    }
  }
}

TEST(SamplerIsaVariants, KernelsAgreeWithEachOtherAndTheReference) {
  const bool avx512 = detectedIsa() == CpuIsa::Avx512;
  std::mt19937 rng(2026);
  const int sizes[][2] = {{1, 1}, {3, 5}, {64, 32}, {7, 1}, {1, 9}, {256, 256}};
  int compared = 0;
  for (const auto& size : sizes) {
    const auto tex = randomTexture(size[0], size[1], 1, uint32_t(size[0] * 31 + size[1]));
    const SampleLevel& lv = tex->sampleLevel(0, 0);
    for (TextureAddress au : kModes)
      for (TextureAddress av : kModes)
        for (bool linear : {false, true}) {
          const Kernel2D avx2Kernel = selectKernel2D(au, av, linear, CpuIsa::Avx2);
          const Kernel2D avx512Kernel =
              avx512 ? selectKernel2D(au, av, linear, CpuIsa::Avx512) : nullptr;
          SamplerState s;
          s.addressU = au, s.addressV = av;
          s.magFilter = s.minFilter = linear ? TextureFilter::Linear : TextureFilter::Point;
          for (int iter = 0; iter < 64; ++iter) {
            alignas(64) float u[N], v[N];
            fillCoords(rng, iter % 4, size[0], size[1], u, v);
            float a[4][N], b[4][N], ref[4][N];
            avx2Kernel(lv, u, v, a);
            SampleRequest req;
            req.u = u, req.v = v;
            sampleTextureReference(*tex, s, req, ref);
            ASSERT_EQ(std::memcmp(a, ref, sizeof a), 0)
                << "avx2 " << size[0] << "x" << size[1] << " " << int(au) << "/" << int(av)
                << " linear " << linear << " iter " << iter;
            if (avx512Kernel) {
              avx512Kernel(lv, u, v, b);
              ASSERT_EQ(std::memcmp(a, b, sizeof a), 0)
                  << "avx512 " << size[0] << "x" << size[1] << " " << int(au) << "/"
                  << int(av) << " linear " << linear << " iter " << iter;
            }
            ++compared;
          }
        }
  }
  EXPECT_EQ(compared, 6 * 16 * 2 * 64);
  if (!avx512) GTEST_SKIP() << "no AVX-512 on this CPU: the AVX2 variant checked alone";
}

// What sampleTexture and a PreparedSampler give does not depend on the active variant,
// for every lane mask (lanes outside it read 0).
TEST(SamplerIsaVariants, SamplingAgreesAcrossVariantsForEveryLaneMask) {
  if (detectedIsa() != CpuIsa::Avx512) GTEST_SKIP() << "no AVX-512 on this CPU";
  const auto tex = randomTexture(64, 64, 0, 5);
  std::mt19937 rng(17);
  SamplerState s;
  s.addressU = TextureAddress::Wrap, s.addressV = TextureAddress::Mirror;
  s.magFilter = TextureFilter::Point, s.minFilter = TextureFilter::Linear;
  s.mipFilter = TextureFilter::Point;
  const CpuIsa previous = activeIsa();
  setActiveIsa(CpuIsa::Avx2);
  const PreparedSampler avx2Prepared(*tex, s);
  setActiveIsa(CpuIsa::Avx512);
  const PreparedSampler avx512Prepared(*tex, s);
  for (uint32_t mask = 0; mask <= 0xffff; ++mask) {
    alignas(64) float u[N], v[N];
    fillCoords(rng, mask % 3 == 0 ? 0 : 1, 64, 64, u, v);
    SampleRequest req;
    req.u = u, req.v = v, req.laneMask = uint16_t(mask);
    float a[4][N], b[4][N], c[4][N], d[4][N];
    setActiveIsa(CpuIsa::Avx2);
    sampleTexture(*tex, s, req, a);
    setActiveIsa(CpuIsa::Avx512);
    sampleTexture(*tex, s, req, b);
    avx2Prepared.sampleImplicit(u, v, nullptr, uint16_t(mask), c);
    avx512Prepared.sampleImplicit(u, v, nullptr, uint16_t(mask), d);
    ASSERT_EQ(std::memcmp(a, b, sizeof a), 0) << "mask " << mask;
    ASSERT_EQ(std::memcmp(a, c, sizeof a), 0) << "mask " << mask;
    ASSERT_EQ(std::memcmp(a, d, sizeof a), 0) << "mask " << mask;
    for (int l = 0; l < N; ++l) {
      if (!(mask >> l & 1)) {
        ASSERT_EQ(a[0][l], 0.0f) << "mask " << mask << " lane " << l;
      }
    }
  }
  setActiveIsa(previous);
}

// Batches whose quads choose different levels (or filters) are sampled level by level
// on the fast paths: each quad's footprint is t texels per pixel with t from a list
// whose log2 stays 0.24 or more away from the rounding points of POINT mip selection,
// so quad q's level is round(log2 t + bias), clamped to [0, last] (λ <= 0: MAGFILTER,
// level 0), bias 0 or 0.1 (which takes the path that evaluates log2).
// Both variants, sampleTexture and a PreparedSampler give the reference's result, and
// most batches mix levels.
TEST(SamplerIsaVariants, BatchesMixingLevelsMatchTheReference) {
  const auto tex = randomTexture(64, 64, 0, 9);
  std::mt19937 rng(41);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const float texelsPerPixel[] = {0.3f, 0.6f, 1.2f, 2.4f, 4.8f, 9.6f, 19.2f};
  const CpuIsa previous = activeIsa();
  const bool avx512 = detectedIsa() == CpuIsa::Avx512;
  int mixedBatches = 0;
  for (int iter = 0; iter < 4000; ++iter) {
    SamplerState s;
    s.addressU = kModes[rng() % 4], s.addressV = kModes[rng() % 4];
    s.magFilter = rng() % 2 ? TextureFilter::Point : TextureFilter::Linear;
    s.minFilter = rng() % 2 ? TextureFilter::Point : TextureFilter::Linear;
    s.mipFilter = rng() % 4 ? TextureFilter::Point : TextureFilter::None;
    s.mipLodBias = iter % 4 == 1 ? 0.1f : 0.0f;
    alignas(64) float u[N], v[N];
    int level[4];
    for (int q = 0; q < 4; ++q) {
      const int pick = int(rng() % 7);
      const float step = texelsPerPixel[pick] / 64.0f, u0 = unit(rng) * 4 - 2, v0 = unit(rng) * 4 - 2;
      level[q] = std::max(pick - 2, 0);  // round(log2 t): -2, -1, 0, 1, 2, 3, 4
      for (int k = 0; k < 4; ++k)
        u[4 * q + k] = u0 + step * float(k & 1), v[4 * q + k] = v0 + step * float(k >> 1);
    }
    mixedBatches += s.mipFilter == TextureFilter::Point &&
                    (level[0] != level[1] || level[0] != level[2] || level[0] != level[3]);
    SampleRequest req;
    req.u = u, req.v = v;
    req.laneMask = iter % 3 == 0 ? uint16_t(rng()) : uint16_t(0xffff);
    float expected[4][N];
    sampleTextureReference(*tex, s, req, expected);
    for (CpuIsa isa : {CpuIsa::Avx2, CpuIsa::Avx512}) {
      if (isa == CpuIsa::Avx512 && !avx512) continue;
      setActiveIsa(isa);
      const PreparedSampler prepared(*tex, s);
      float a[4][N], b[4][N];
      sampleTexture(*tex, s, req, a);
      prepared.sampleImplicit(u, v, nullptr, req.laneMask, b);
      ASSERT_EQ(std::memcmp(expected, a, sizeof a), 0) << "iter " << iter << " isa " << int(isa);
      ASSERT_EQ(std::memcmp(expected, b, sizeof b), 0) << "iter " << iter << " isa " << int(isa);
    }
  }
  setActiveIsa(previous);
  EXPECT_GT(mixedBatches, 2000);
}

// Batches whose four quads share one level, for every level of a 64x64 texture (and
// beyond its last, clamped): the batch kernels find the level by counting up to it, so
// each level is checked against the reference on its own, in both variants, through
// sampleImplicit and through the ImplicitKernel entry. t texels per pixel as in
// BatchesMixingLevelsMatchTheReference (level round(log2 t), clamped to [0, 6]).
TEST(SamplerIsaVariants, BatchesOfOneLevelMatchTheReferenceOnEveryLevel) {
  const auto tex = randomTexture(64, 64, 0, 23);
  ASSERT_EQ(tex->levelCount(), 7);
  std::mt19937 rng(57);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const float texelsPerPixel[] = {0.6f, 1.2f, 2.4f, 4.8f, 9.6f, 19.2f, 38.4f, 76.8f, 153.6f};
  const CpuIsa previous = activeIsa();
  const bool avx512 = detectedIsa() == CpuIsa::Avx512;
  int throughKernel = 0;
  for (int iter = 0; iter < 900; ++iter) {
    SamplerState s;
    s.addressU = kModes[rng() % 4], s.addressV = kModes[rng() % 4];
    s.magFilter = rng() % 2 ? TextureFilter::Point : TextureFilter::Linear;
    s.minFilter = rng() % 2 ? TextureFilter::Point : TextureFilter::Linear;
    s.mipFilter = TextureFilter::Point;
    const float step = texelsPerPixel[iter % 9] / 64.0f;
    alignas(64) float u[N], v[N];
    for (int q = 0; q < 4; ++q) {
      const float u0 = unit(rng) * 4 - 2, v0 = unit(rng) * 4 - 2;
      for (int k = 0; k < 4; ++k)
        u[4 * q + k] = u0 + step * float(k & 1), v[4 * q + k] = v0 + step * float(k >> 1);
    }
    const uint16_t mask = iter % 5 == 0 ? uint16_t(rng()) : uint16_t(0xffff);
    SampleRequest req;
    req.u = u, req.v = v, req.laneMask = mask;
    float expected[4][N];
    sampleTextureReference(*tex, s, req, expected);
    for (CpuIsa isa : {CpuIsa::Avx2, CpuIsa::Avx512}) {
      if (isa == CpuIsa::Avx512 && !avx512) continue;
      setActiveIsa(isa);
      const PreparedSampler prepared(*tex, s);
      float a[4][N], b[4][N];
      prepared.sampleImplicit(u, v, nullptr, mask, a);
      ASSERT_EQ(std::memcmp(expected, a, sizeof a), 0) << "iter " << iter << " isa " << int(isa);
      if (const auto& kernel = prepared.implicitKernel(); kernel.fn) {
        kernel.fn(kernel.context, u, v, nullptr, mask, b);
        ASSERT_EQ(std::memcmp(expected, b, sizeof b), 0) << "iter " << iter << " isa " << int(isa);
        ++throughKernel;
      }
    }
  }
  setActiveIsa(previous);
  EXPECT_EQ(throughKernel, avx512 ? 1800 : 900);
}

// PreparedSampler::implicitKernel: there for every 2D texture without anisotropic
// filtering, in both variants; it gives what the reference gives for every kind of
// coordinates, lane mask and state (mip filters, LOD bias), the batches the AVX-512
// batch kernel declines included. Cube and volume textures and MAXANISOTROPY > 1 take
// the general path and get none.
TEST(SamplerIsaVariants, ImplicitKernelMatchesTheReference) {
  const CpuIsa previous = activeIsa();
  const bool avx512 = detectedIsa() == CpuIsa::Avx512;
  std::mt19937 rng(91);
  const int sizes[][2] = {{1, 1}, {2, 2}, {17, 5}, {64, 64}};
  int withKernel = 0, withoutKernel = 0;
  for (const auto& size : sizes) {
    const auto tex = randomTexture(size[0], size[1], 0, uint32_t(size[0] + 7 * size[1]));
    for (int iter = 0; iter < 400; ++iter) {
      SamplerState s;
      s.addressU = kModes[rng() % 4], s.addressV = kModes[rng() % 4];
      s.magFilter = rng() % 2 ? TextureFilter::Point : TextureFilter::Linear;
      s.minFilter = rng() % 2 ? TextureFilter::Point : TextureFilter::Linear;
      s.mipFilter = TextureFilter(rng() % 3);  // NONE, POINT, LINEAR
      s.mipLodBias = iter % 7 == 3 ? 0.25f : 0.0f;
      const bool anisotropic = iter % 11 == 5;
      if (anisotropic) s.minFilter = TextureFilter::Anisotropic, s.maxAnisotropy = 4;
      setActiveIsa(iter % 9 == 4 || !avx512 ? CpuIsa::Avx2 : CpuIsa::Avx512);
      const PreparedSampler prepared(*tex, s);
      const auto& kernel = prepared.implicitKernel();
      ASSERT_EQ(kernel.fn != nullptr, !anisotropic) << "iter " << iter;
      if (!kernel.fn) {
        ++withoutKernel;
        continue;
      }
      alignas(64) float u[N], v[N];
      fillCoords(rng, iter % 4, size[0], size[1], u, v);
      const uint16_t mask = iter % 3 == 0 ? uint16_t(rng()) : uint16_t(0xffff);
      SampleRequest req;
      req.u = u, req.v = v, req.laneMask = mask;
      float expected[4][N], got[4][N];
      sampleTextureReference(*tex, s, req, expected);
      kernel.fn(kernel.context, u, v, nullptr, mask, got);
      ASSERT_EQ(std::memcmp(expected, got, sizeof got), 0)
          << size[0] << "x" << size[1] << " iter " << iter;
      ++withKernel;
    }
  }
  setActiveIsa(previous);
  EXPECT_GT(withKernel, 1200);
  EXPECT_GT(withoutKernel, 100);
  // A cube map has no one-level 2D path.
  const auto cube = Texture::createCube(Format::A8R8G8B8, 8, 1);
  EXPECT_EQ(PreparedSampler(*cube, SamplerState{}).implicitKernel().fn, nullptr);
}

// PreparedSampler::implicitPair: two samplers' lookups in one call give what the
// reference gives for each, where they share coordinates (the same rows, or equal ones)
// and sizes (when the addresses are computed once) and where they do not: other
// coordinates, other sizes, other filters or mip filters, masks, batches of mixed or
// declined levels. It exists where the AVX-512 batch kernel does, the same function for
// the same addressing pair.
TEST(SamplerIsaVariants, ImplicitPairGivesWhatEachSamplerGives) {
  const CpuIsa previous = activeIsa();
  if (detectedIsa() != CpuIsa::Avx512) GTEST_SKIP() << "the pair exists in the AVX-512 kernel only";
  setActiveIsa(CpuIsa::Avx512);
  std::mt19937 rng(23);
  const int sizes[][2] = {{1, 1}, {17, 5}, {64, 64}, {256, 128}};
  int shared = 0, apart = 0;
  for (const auto& sa : sizes) {
    for (const auto& sb : sizes) {
      const auto texA = randomTexture(sa[0], sa[1], 0, uint32_t(sa[0] * 5 + sa[1]));
      const auto texB = randomTexture(sb[0], sb[1], 0, uint32_t(sb[0] * 11 + sb[1] + 1));
      for (int iter = 0; iter < 300; ++iter) {
        SamplerState a;
        a.addressU = kModes[rng() % 4], a.addressV = kModes[rng() % 4];
        a.magFilter = rng() % 2 ? TextureFilter::Point : TextureFilter::Linear;
        a.minFilter = rng() % 2 ? TextureFilter::Point : TextureFilter::Linear;
        a.mipFilter = TextureFilter(rng() % 2);  // NONE, POINT: the batch kernel's
        SamplerState b = a;
        if (iter % 5 == 1) b.magFilter = rng() % 2 ? TextureFilter::Point : TextureFilter::Linear;
        if (iter % 7 == 2) b.mipFilter = TextureFilter(rng() % 2);
        const PreparedSampler pa(*texA, a), pb(*texB, b);
        // none where one level and filter serve every λ (no batch kernel needed)
        if (!pa.implicitPair() || !pb.implicitPair()) continue;
        ASSERT_EQ(pa.implicitPair(), pb.implicitPair());
        alignas(64) float ca[3][N] = {}, cb[3][N] = {};
        fillCoords(rng, iter % 4, sa[0], sa[1], ca[0], ca[1]);
        // b at the same rows, at equal rows elsewhere, or at other coordinates
        const int where = iter % 3;
        if (where == 1) std::memcpy(cb, ca, sizeof cb);
        if (where == 2) fillCoords(rng, iter % 4, sb[0], sb[1], cb[0], cb[1]);
        const float (*coordsB)[N] = where == 0 ? ca : cb;
        const uint16_t mask = iter % 3 == 0 ? uint16_t(rng()) : uint16_t(0xffff);
        float expectedA[4][N], expectedB[4][N], gotA[4][N], gotB[4][N];
        SampleRequest req;
        req.laneMask = mask;
        req.u = ca[0], req.v = ca[1];
        sampleTextureReference(*texA, a, req, expectedA);
        req.u = coordsB[0], req.v = coordsB[1];
        sampleTextureReference(*texB, b, req, expectedB);
        std::memset(gotA, 0xcd, sizeof gotA), std::memset(gotB, 0xcd, sizeof gotB);
        pa.implicitPair()(pa.implicitKernel().context, pb.implicitKernel().context, ca, coordsB, mask, gotA,
                          gotB);
        ASSERT_EQ(std::memcmp(expectedA, gotA, sizeof gotA), 0)
            << sa[0] << "x" << sa[1] << " and " << sb[0] << "x" << sb[1] << " iter " << iter;
        ASSERT_EQ(std::memcmp(expectedB, gotB, sizeof gotB), 0)
            << sa[0] << "x" << sa[1] << " and " << sb[0] << "x" << sb[1] << " iter " << iter;
        (where < 2 && sa[0] == sb[0] && sa[1] == sb[1] ? shared : apart) += 1;
      }
    }
  }
  setActiveIsa(previous);
  EXPECT_GT(shared, 500);
  EXPECT_GT(apart, 2400);
}

// The group lookups give for every batch what the reference gives (float results) or
// what sampleImplicitArgb8 gives alone (bytes): groups of 1 to kMaxSampleGroup batches
// mixing screen-like footprints (the phases' case) with random, edge and special
// coordinates, one or two textures of the same size or not, shared coordinates or
// not, lane masks.
TEST(SamplerIsaVariants, GroupLookupsGiveWhatEachBatchGives) {
  const CpuIsa previous = activeIsa();
  const bool avx512 = detectedIsa() == CpuIsa::Avx512;
  std::mt19937 rng(77);
  const int sizes[][2] = {{17, 5}, {64, 64}, {256, 128}};
  int groups = 0;
  for (const auto& sa : sizes) {
    for (const auto& sb : sizes) {
      const auto texA = randomTexture(sa[0], sa[1], 0, uint32_t(sa[0] * 7 + sa[1]));
      const auto texB = randomTexture(sb[0], sb[1], 0, uint32_t(sb[0] * 13 + sb[1] + 2));
      for (int iter = 0; iter < 150; ++iter) {
        setActiveIsa(iter % 10 == 3 || !avx512 ? CpuIsa::Avx2 : CpuIsa::Avx512);
        SamplerState a;
        a.addressU = kModes[rng() % 4], a.addressV = kModes[rng() % 4];
        a.magFilter = iter % 6 == 0 ? TextureFilter::Point : TextureFilter::Linear;
        a.minFilter = iter % 8 == 0 ? TextureFilter::Point : TextureFilter::Linear;
        a.mipFilter = TextureFilter(rng() % 3);  // NONE, POINT, LINEAR
        SamplerState b = a;
        if (iter % 5 == 1) b.mipFilter = TextureFilter(rng() % 3);
        const PreparedSampler pa(*texA, a), pb(*texB, b);
        const int count = 1 + int(rng() % kMaxSampleGroup);
        alignas(64) float ca[kMaxSampleGroup][3][N] = {}, cb[kMaxSampleGroup][3][N] = {};
        alignas(64) float outA[kMaxSampleGroup][4][N], outB[kMaxSampleGroup][4][N];
        alignas(64) uint32_t colors[kMaxSampleGroup][N];
        uint16_t masks[kMaxSampleGroup];
        SampleBatch batchesA[kMaxSampleGroup], batchesB[kMaxSampleGroup];
        const float* us[kMaxSampleGroup];
        const float* vs[kMaxSampleGroup];
        uint32_t* colorOut[kMaxSampleGroup];
        for (int g = 0; g < count; ++g) {
          fillCoords(rng, rng() % 4 ? 1 : int(rng() % 4), sa[0], sa[1], ca[g][0], ca[g][1]);
          if (rng() % 4 == 0) fillCoords(rng, 1, sb[0], sb[1], cb[g][0], cb[g][1]);
          else std::memcpy(cb[g], ca[g], sizeof cb[g]);
          masks[g] = rng() % 3 == 0 ? uint16_t(rng()) : uint16_t(0xffff);
          batchesA[g] = {ca[g], outA[g]}, batchesB[g] = {cb[g], outB[g]};
          us[g] = ca[g][0], vs[g] = ca[g][1], colorOut[g] = colors[g];
        }
        std::memset(outA, 0xcd, sizeof outA), std::memset(outB, 0xcd, sizeof outB);
        const bool pair = iter % 2 == 0;
        if (pair)
          PreparedSampler::sampleImplicitPairGroup(pa, pb, count, masks, batchesA, batchesB);
        else
          pa.sampleImplicitGroup(count, masks, batchesA);
        const uint32_t written = pa.sampleImplicitArgb8Group(count, us, vs, masks, colorOut);
        for (int g = 0; g < count; ++g) {
          float expected[4][N];
          SampleRequest req;
          req.laneMask = masks[g];
          req.u = ca[g][0], req.v = ca[g][1];
          sampleTextureReference(*texA, a, req, expected);
          ASSERT_EQ(std::memcmp(expected, outA[g], sizeof expected), 0) << "iter " << iter << " batch " << g;
          if (pair) {
            req.u = cb[g][0], req.v = cb[g][1];
            sampleTextureReference(*texB, b, req, expected);
            ASSERT_EQ(std::memcmp(expected, outB[g], sizeof expected), 0) << "iter " << iter << " batch " << g;
          }
          alignas(64) uint32_t alone[N];
          const bool wrote = pa.sampleImplicitArgb8(ca[g][0], ca[g][1], masks[g], alone);
          ASSERT_EQ(bool(written >> g & 1), wrote) << "iter " << iter << " batch " << g;
          for (int l = 0; l < N; ++l) {
            if (wrote && masks[g] >> l & 1) {
              ASSERT_EQ(colors[g][l], alone[l]) << "iter " << iter << " batch " << g;
            }
          }
        }
        ++groups;
      }
    }
  }
  setActiveIsa(previous);
  EXPECT_EQ(groups, 9 * 150);
}

// sampleImplicitArgb8 gives the 8-bit unorms of sampleImplicit's channels as D3DCOLORs
// (unorm8 of core/color.h: what the output merger stores), on every lane in the mask,
// wherever it samples at all (the AVX-512 batch kernel's states: mip filter NONE or
// POINT, no LOD bias; batches of one level or of mixed levels).
TEST(SamplerIsaVariants, ColorsAreTheUnorm8OfTheImplicitSample) {
  const CpuIsa previous = activeIsa();
  if (detectedIsa() != CpuIsa::Avx512) GTEST_SKIP() << "the byte output exists in the AVX-512 kernel only";
  setActiveIsa(CpuIsa::Avx512);
  std::mt19937 rng(5);
  const int sizes[][2] = {{1, 1}, {3, 2}, {17, 5}, {64, 64}, {256, 128}};
  int sampled = 0, declined = 0;
  for (const auto& size : sizes) {
    const auto tex = randomTexture(size[0], size[1], 0, uint32_t(size[0] * 3 + size[1]));
    for (int iter = 0; iter < 600; ++iter) {
      SamplerState s;
      s.addressU = kModes[rng() % 4], s.addressV = kModes[rng() % 4];
      s.magFilter = rng() % 2 ? TextureFilter::Point : TextureFilter::Linear;
      s.minFilter = rng() % 2 ? TextureFilter::Point : TextureFilter::Linear;
      s.mipFilter = TextureFilter(rng() % 3);  // NONE, POINT, LINEAR
      const PreparedSampler prepared(*tex, s);
      alignas(64) float u[N], v[N];
      fillCoords(rng, iter % 4, size[0], size[1], u, v);
      const uint16_t mask = iter % 3 == 0 ? uint16_t(rng()) : uint16_t(0xffff);
      alignas(64) float rgba[4][N];
      alignas(64) uint32_t colors[N];
      prepared.sampleImplicit(u, v, nullptr, mask, rgba);
      if (!prepared.sampleImplicitArgb8(u, v, mask, colors)) {
        ++declined;
        continue;
      }
      ++sampled;
      for (int l = 0; l < N; ++l) {
        if (!(mask >> l & 1)) continue;
        const uint32_t want = uint32_t(unorm8(rgba[3][l])) << 24 | uint32_t(unorm8(rgba[0][l])) << 16 |
                              uint32_t(unorm8(rgba[1][l])) << 8 | uint32_t(unorm8(rgba[2][l]));
        ASSERT_EQ(colors[l], want) << size[0] << "x" << size[1] << " iter " << iter << " lane " << l;
      }
    }
  }
  setActiveIsa(previous);
  EXPECT_GT(sampled, 800);   // the kernel's states, most batches
  EXPECT_GT(declined, 800);  // mip LINEAR, declined batches
}

// Screen-like batches (4x4 pixels in quad order, 0.5, 1 or 1.33 texels per pixel, the
// common case of the batch kernels, whose 2x2 texels are adjacent in memory) at every
// half-texel offset around and across the edges of small levels (widths and heights
// 1, 2, 4, 8, 16, 17), every addressing pair, both filters and several lane masks: the
// kernels of both variants and the prepared paths agree with the reference bit for bit,
// where the footprints wrap, mirror or clamp and where they do not.
TEST(SamplerIsaVariants, ScreenFootprintsAroundLevelEdgesMatchTheReference) {
  const bool avx512 = detectedIsa() == CpuIsa::Avx512;
  const CpuIsa previous = activeIsa();
  const int sides[] = {1, 2, 4, 8, 16, 17};
  const float steps[] = {0.5f, 1.0f, 1.33f};
  const uint16_t masks[] = {0xffff, 0x0ff0, 0x8001, 0x0000};
  std::mt19937 rng(3);
  long compared = 0;
  for (int w : sides)
    for (int h : sides) {
      if ((w + h) % 3 == 1) continue;  // a spread of the 36 shapes keeps the test short
      const auto tex = randomTexture(w, h, 1, uint32_t(w * 100 + h));
      const SampleLevel& lv = tex->sampleLevel(0, 0);
      for (TextureAddress au : kModes)
        for (TextureAddress av : kModes)
          for (bool linear : {false, true}) {
            SamplerState s;
            s.addressU = au, s.addressV = av;
            s.magFilter = s.minFilter = linear ? TextureFilter::Linear : TextureFilter::Point;
            const Kernel2D kernels[2] = {
                selectKernel2D(au, av, linear, CpuIsa::Avx2),
                avx512 ? selectKernel2D(au, av, linear, CpuIsa::Avx512) : nullptr};
            for (int ox = -6; ox <= 2 * w + 4; ox += 1 + w / 8)
              for (int oy = -6; oy <= 2 * h + 4; oy += 1 + h / 8) {
                const float step = steps[(ox + oy + 12) % 3];
                alignas(64) float u[N], v[N];
                for (int l = 0; l < N; ++l) {
                  const int q = l >> 2, px = (q & 1) * 2 + (l & 1), py = (q >> 1) * 2 + (l >> 1 & 1);
                  u[l] = (0.5f * float(ox) + step * float(px)) / float(w);
                  v[l] = (0.5f * float(oy) + step * float(py)) / float(h);
                }
                const uint16_t mask = masks[rng() % 4];
                SampleRequest req;
                req.u = u, req.v = v;
                float whole[4][N], ref[4][N], got[4][N];
                sampleTextureReference(*tex, s, req, whole);
                req.laneMask = mask;
                sampleTextureReference(*tex, s, req, ref);
                for (const Kernel2D kernel : kernels) {
                  if (!kernel) continue;
                  kernel(lv, u, v, got);
                  ASSERT_EQ(std::memcmp(whole, got, sizeof got), 0)
                      << w << "x" << h << " " << int(au) << "/" << int(av) << " linear " << linear
                      << " at " << ox << "," << oy << " step " << step;
                }
                // MIPFILTER NONE takes the one-kernel path, POINT (one level here, the
                // same texels) the batch classification in front of the kernel.
                for (CpuIsa isa : {CpuIsa::Avx2, CpuIsa::Avx512})
                  for (TextureFilter mip : {TextureFilter::None, TextureFilter::Point}) {
                    if (isa == CpuIsa::Avx512 && !avx512) continue;
                    setActiveIsa(isa);
                    SamplerState sm = s;
                    sm.mipFilter = mip;
                    const PreparedSampler prepared(*tex, sm);
                    prepared.sampleImplicit(u, v, nullptr, mask, got);
                    ASSERT_EQ(std::memcmp(ref, got, sizeof got), 0)
                        << w << "x" << h << " " << int(au) << "/" << int(av) << " linear "
                        << linear << " at " << ox << "," << oy << " mask " << mask << " isa "
                        << int(isa) << " mip " << int(mip);
                  }
                ++compared;
              }
          }
    }
  setActiveIsa(previous);
  EXPECT_GT(compared, 20000);
}

}  // namespace
}  // namespace refx
