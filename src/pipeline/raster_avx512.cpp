// The AVX-512 variant of the input interpolation of raster.cpp: the 16 lanes of a
// batch in one register instead of two halves of eight, the same IEEE operations in
// the same order (no contraction: -ffp-contract=off), so the values are identical.
// Compiled with AVX-512 flags (CMakeLists.txt: sources named *_avx512.cpp) and called
// only where the CPU has them (chooseInterpolateInputs); it uses no function shared
// with other translation units, so none of them can end up with an AVX-512 copy.
#include <immintrin.h>

#include <cstring>

#include "raster_interpolate.h"

namespace refx::pipeline {

namespace {

typedef float v16f __attribute__((vector_size(64)));

// Per-lane pixel offsets inside a batch (kLaneX / kLaneY of output_merger.h).
alignas(64) constexpr float kLaneXf[kBatchLanes] = {0, 1, 0, 1, 2, 3, 2, 3, 0, 1, 0, 1, 2, 3, 2, 3};
alignas(64) constexpr float kLaneYf[kBatchLanes] = {0, 0, 1, 1, 0, 0, 1, 1, 2, 2, 3, 3, 2, 2, 3, 3};

inline v16f load16(const float* p) {
  v16f v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline void store16(float* p, v16f v) { std::memcpy(p, &v, sizeof v); }
// x in every lane (a broadcast: -0 stays -0, unlike 0 + x).
inline v16f bcast16(float x) { return v16f{x, x, x, x, x, x, x, x, x, x, x, x, x, x, x, x}; }

}  // namespace

void interpolateInputsAvx512(const float* planes, const InputTarget* targets, size_t count, float ox,
                             float oy, const float* invW, float* w) {
  const v16f fx = bcast16(ox) + load16(kLaneXf), fy = bcast16(oy) + load16(kLaneYf);
  const v16f one = bcast16(1.0f), iw = load16(invW);
  const bool unitW = _mm512_cmp_ps_mask(__m512(iw), __m512(one), _CMP_EQ_OQ) == 0xffff;
  const v16f wv = unitW ? one : one / iw;
  store16(w, wv);
  for (size_t i = 0; i < count; ++i, planes += 3) {
    if (targets[i].sameAs >= 0) {
      store16(targets[i].lanes, load16(targets[targets[i].sameAs].lanes));
      continue;
    }
    v16f r = bcast16(planes[0]) + bcast16(planes[1]) * fx + bcast16(planes[2]) * fy;
    if (!targets[i].flat && !unitW) r = r * wv;
    store16(targets[i].lanes, r);
  }
}

}  // namespace refx::pipeline
