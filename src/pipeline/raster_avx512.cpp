// The AVX-512 variants of raster.cpp's input interpolation and opaque block store: the
// 16 lanes of a batch in one register instead of two halves of eight, the same IEEE
// operations in the same order (no contraction: -ffp-contract=off), so the values are
// identical. Compiled with AVX-512 flags (CMakeLists.txt: sources named *_avx512.cpp)
// and called only where the CPU has them (chooseInterpolateInputs, rasterize); they use
// no function shared with other translation units, so none of them can end up with an
// AVX-512 copy.
#include "refx/core/avx512_intrinsics.h"

#include <cstring>

#include "raster_interpolate.h"
#include "raster_store.h"

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
    if (targets[i].sameAs != -1) {
      if (targets[i].sameAs >= 0) store16(targets[i].lanes, load16(targets[targets[i].sameAs].lanes));
      continue;
    }
    v16f r = bcast16(planes[0]) + bcast16(planes[1]) * fx + bcast16(planes[2]) * fy;
    if (!targets[i].flat && !unitW) r = r * wv;
    store16(targets[i].lanes, r);
  }
}

void storeOpaqueBlockAvx512(uint8_t* topLeft, int pitch, bool hasAlpha, uint16_t mask,
                            const float (*color)[kBatchLanes], const uint32_t* under) {
  // toUnorm8x8 per channel: vmaxps/vminps with 0 and 1 second (NaN and -0 give 0),
  // then v * 255 + 0.5 truncated.
  __m512i q[4];
  for (int c = 0; c < 4; ++c) {
    __m512 v = _mm512_loadu_ps(color[c]);
    v = _mm512_min_ps(_mm512_max_ps(v, _mm512_setzero_ps()), _mm512_set1_ps(1.0f));
    v = _mm512_add_ps(_mm512_mul_ps(v, _mm512_set1_ps(255.0f)), _mm512_set1_ps(0.5f));
    q[c] = _mm512_cvttps_epi32(v);
  }
  const __m512i alpha = hasAlpha ? _mm512_slli_epi32(q[3], 24) : _mm512_set1_epi32(int(0xff000000u));
  // alpha | r << 16 | g << 8 | b, as two three-way ORs.
  const __m512i rg = _mm512_or_si512(_mm512_slli_epi32(q[0], 16), _mm512_slli_epi32(q[1], 8));
  __m512i packed = _mm512_ternarylogic_epi32(alpha, rg, q[2], 0xfe);
  // Quad-major lanes (core/batch.h) to rows: row r is lanes 0,1,4,5 / 2,3,6,7 / 8,9,12,13
  // / 10,11,14,15.
  const __m512i rows = _mm512_setr_epi32(0, 1, 4, 5, 2, 3, 6, 7, 8, 9, 12, 13, 10, 11, 14, 15);
  packed = _mm512_permutexvar_epi32(rows, packed);
  // The mask's bits in row order, as the lanes above.
  const __m512i bit = _mm512_permutexvar_epi32(rows, _mm512_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024,
                                                                        2048, 4096, 8192, 16384, 32768));
  const __mmask16 rowMask = _mm512_test_epi32_mask(bit, _mm512_set1_epi32(mask));
  if (under) packed = _mm512_mask_blend_epi32(rowMask, _mm512_set1_epi32(int(*under)), packed);
  const __m128i part[4] = {_mm512_castsi512_si128(packed), _mm512_extracti32x4_epi32(packed, 1),
                           _mm512_extracti32x4_epi32(packed, 2), _mm512_extracti32x4_epi32(packed, 3)};
  const bool whole = under || rowMask == 0xffff;
  for (int r = 0; r < 4; ++r) {
    uint8_t* dst = topLeft + size_t(r) * size_t(pitch);
    if (whole)
      _mm_storeu_si128(reinterpret_cast<__m128i*>(dst), part[r]);
    else  // EVEX masked stores: one µop, unlike vpmaskmovd
      _mm_mask_storeu_epi32(dst, __mmask8(rowMask >> (4 * r) & 0xf), part[r]);
  }
}

}  // namespace refx::pipeline
