// The batch input interpolation (pipeline/raster_interpolate.h) against its formula,
// evaluated lane by lane in scalar floats: both instruction-set variants must give the
// formula's values bit for bit.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "pipeline/raster_interpolate.h"
#include "refx/core/cpu_features.h"

namespace refx::pipeline {
namespace {

struct Case {
  std::vector<float> planes;  // 3 per input
  std::vector<bool> flat;
  float ox, oy;
  float invW[kBatchLanes];
};

Case randomCase(std::mt19937& rng, int inputs) {
  std::uniform_real_distribution<float> value(-300.0f, 300.0f), offset(-70.0f, 70.0f), rhw(0.01f, 2.0f);
  Case c;
  for (int i = 0; i < 3 * inputs; ++i) c.planes.push_back(value(rng) / float(1 + i % 3 * 97));
  for (int i = 0; i < inputs; ++i) c.flat.push_back(i % 3 == 2);
  c.ox = offset(rng) + 0.5f;
  c.oy = offset(rng) - 0.25f;
  for (float& v : c.invW) v = rhw(rng);
  return c;
}

// A batch's lanes: four 2x2 quads, top-left, top-right, bottom-left, bottom-right, each
// in reading order.
constexpr int kLaneX[kBatchLanes] = {0, 1, 0, 1, 2, 3, 2, 3, 0, 1, 0, 1, 2, 3, 2, 3};
constexpr int kLaneY[kBatchLanes] = {0, 0, 1, 1, 0, 0, 1, 1, 2, 2, 3, 3, 2, 2, 3, 3};

// value = base + dx*(ox + laneX) + dy*(oy + laneY), left to right, times 1/invW unless flat.
// copyLast: the last input is marked as the same as the first (InputTarget::sameAs) and
// its plane is garbage: it must get the first one's values.
void checkVariant(InterpolateInputsFn fn, const Case& c, bool copyLast = false) {
  const size_t n = c.flat.size();
  std::vector<std::array<float, kBatchLanes>> out(n);
  std::vector<InputTarget> targets;
  for (size_t i = 0; i < n; ++i) targets.push_back({out[i].data(), bool(c.flat[i])});
  std::vector<float> planes = c.planes;
  if (copyLast && n > 1) {
    targets.back().sameAs = 0;
    for (int k = 0; k < 3; ++k) planes[3 * (n - 1) + size_t(k)] = 1e30f;
  }
  alignas(64) float w[kBatchLanes];
  fn(planes.data(), targets.data(), n, c.ox, c.oy, c.invW, w);
  for (int l = 0; l < kBatchLanes; ++l) {
    const float fx = c.ox + float(kLaneX[l]), fy = c.oy + float(kLaneY[l]);
    const float wl = 1.0f / c.invW[l];
    EXPECT_EQ(std::memcmp(&w[l], &wl, 4), 0) << "w lane " << l;
    for (size_t i = 0; i < n; ++i) {
      const size_t from = copyLast && n > 1 && i == n - 1 ? 0 : i;
      const float* p = &c.planes[3 * from];
      float v = p[0] + p[1] * fx;
      v = v + p[2] * fy;
      if (!c.flat[from]) v = v * wl;
      EXPECT_EQ(std::memcmp(&out[i][l], &v, 4), 0) << "input " << i << " lane " << l << ": " << out[i][l] << " vs " << v;
    }
  }
}

// checkVariant on case c with the AVX2 variant, then with the AVX-512 one where the CPU
// has it.
void checkBothVariants(const Case& c, bool copyLast = false) {
  const CpuIsa saved = activeIsa();
  setActiveIsa(CpuIsa::Avx2);
  checkVariant(chooseInterpolateInputs(), c, copyLast);
  if (detectedIsa() == CpuIsa::Avx512) {
    setActiveIsa(CpuIsa::Avx512);
    ASSERT_EQ(chooseInterpolateInputs(), &interpolateInputsAvx512);
    checkVariant(chooseInterpolateInputs(), c, copyLast);
  }
  setActiveIsa(saved);
}

TEST(RasterInterpolate, BothVariantsGiveTheFormulasValues) {
  std::mt19937 rng(7);
  for (int round = 0; round < 50; ++round) checkBothVariants(randomCase(rng, 1 + round % 9));
}

// invW = 1 in every lane (an affine primitive with w = 1): w = 1 and the values are the
// planes' own (x * 1 = x), whichever way a variant gets there.
TEST(RasterInterpolate, UnitWGivesThePlanesValues) {
  std::mt19937 rng(9);
  for (int round = 0; round < 20; ++round) {
    Case c = randomCase(rng, 1 + round % 7);
    for (float& v : c.invW) v = 1.0f;
    if (round % 2) c.invW[round % kBatchLanes] = 0.5f;  // one lane off: the general path
    checkBothVariants(c);
  }
}

// A target marked sameAs another gets that one's values, not its own plane's.
TEST(RasterInterpolate, CopiedInputsGetTheirSourcesValues) {
  std::mt19937 rng(11);
  for (int round = 0; round < 20; ++round) checkBothVariants(randomCase(rng, 2 + round % 6), true);
}

}  // namespace
}  // namespace refx::pipeline
