// The vectorised kernels of the output merger that the rasterizer's shade paths
// inline too (output_merger.cpp, raster.cpp): conversion to 8 bits, the opaque store
// and the depth test of a batch.
#pragma once
#include <cstdint>
#if defined(__SSE__) || defined(__AVX__)
#include <immintrin.h>
#endif

#include "output_merger.h"

namespace refx::pipeline {

typedef float v4f __attribute__((vector_size(16)));
typedef float v8f __attribute__((vector_size(32)));
typedef int32_t v8i __attribute__((vector_size(32)));

// Eight lanes as one value (GCC/Clang vector extensions), so the conversions below
// are vectorised whatever the compiler's loop heuristics decide.
typedef uint32_t v4u __attribute__((vector_size(16)));
typedef uint32_t v8u __attribute__((vector_size(32)));
// toUnorm8 on eight lanes: NaN and negatives 0, then round to nearest.
inline v8i toUnorm8x8(v8f v) {
  const v8f zero{};
#if defined(__AVX__)
  // vmaxps/vminps return their second operand for NaN and for equal values (±0),
  // so these are exactly v > 0 ? v : 0 and v < 1 ? v : 1 in one instruction each.
  __m256 m;
  __builtin_memcpy(&m, &v, sizeof m);
  m = _mm256_min_ps(_mm256_max_ps(m, _mm256_setzero_ps()), _mm256_set1_ps(1.0f));
  __builtin_memcpy(&v, &m, sizeof v);
#else
  const v8f one = zero + 1.0f;
  v = v > zero ? v : zero;
  v = v < one ? v : one;
#endif
  return __builtin_convertvector(v * (zero + 255.0f) + (zero + 0.5f), v8i);
}

// Lanes k..k+7 of a batch's colours as the opaque merge stores them: 8 bits per
// channel as D3DCOLOR, the alpha 0xff for a target without alpha.
inline v8i packOpaque(const ColorTarget& t, const float (*color)[kBatchLanes], int k) {
  v8i q[4];
  for (int c = 0; c < 4; ++c) {
    v8f v;
    __builtin_memcpy(&v, color[c] + k, sizeof v);
    q[c] = toUnorm8x8(v);
  }
  const v8i alphaOr = v8i{} + int32_t(t.hasAlpha ? 0u : 0xff000000u);
  return ((q[3] << 24) | alphaOr) | (q[0] << 16) | (q[1] << 8) | q[2];
}

// Writes the lanes in `mask` of a batch of D3DCOLORs into 8-bit target t at block
// (bx, by).
inline void storePacked(const ColorTarget& t, int width, int height, int bx, int by, uint16_t mask,
                        const uint32_t packed[kBatchLanes]) {
  const bool inside = bx + 4 <= width && by + 4 <= height;
  const bool whole = mask == 0xffff && inside;
#if defined(__AVX2__)
  // Inside the surface a partly covered batch is stored row by row, blended with the rows.
  const bool masked = inside && !whole;
  const v8i laneBit{1, 2, 4, 8, 16, 32, 64, 128};
#else
  const bool masked = false;
#endif
  if (!whole && !masked) {
    for (int l = 0; l < kBatchLanes; ++l)
      if (mask & (1 << l))
        reinterpret_cast<uint32_t*>(t.data + size_t(by + kLaneY[l]) * t.pitch)[bx + kLaneX[l]] = packed[l];
    return;
  }
  for (int k = 0; k < kBatchLanes; k += 8) {
    v8u p;
    __builtin_memcpy(&p, packed + k, sizeof p);
    // Lanes k..k+7 are rows k/4 and k/4 + 1: lanes 0,1,4,5 and 2,3,6,7 of the half.
    const v4u r0 = __builtin_shufflevector(p, p, 0, 1, 4, 5);
    const v4u r1 = __builtin_shufflevector(p, p, 2, 3, 6, 7);
    uint8_t* row = t.data + size_t(by + k / 4) * t.pitch + size_t(bx) * 4;
    if (whole) {
      __builtin_memcpy(row, &r0, sizeof r0);
      __builtin_memcpy(row + t.pitch, &r1, sizeof r1);
      continue;
    }
#if defined(__AVX2__)
    // The dead lanes keep what the rows hold: whole-row loads and stores, as
    // vpmaskmovd stores cost several cycles each on some cores (Zen 4).
    const int live = (mask >> k) & 0xff;
    const v8i on = (laneBit & live) != 0;
    const v4u m0 = __builtin_shufflevector(v8u(on), v8u(on), 0, 1, 4, 5);
    const v4u m1 = __builtin_shufflevector(v8u(on), v8u(on), 2, 3, 6, 7);
    v4u old0, old1;
    __builtin_memcpy(&old0, row, sizeof old0);
    __builtin_memcpy(&old1, row + t.pitch, sizeof old1);
    const v4u out0 = m0 ? r0 : old0, out1 = m1 ? r1 : old1;
    __builtin_memcpy(row, &out0, sizeof out0);
    __builtin_memcpy(row + t.pitch, &out1, sizeof out1);
#endif
  }
}

// Opaque writes with nothing but an (already done) depth test: convert the whole
// batch to 8 bits at once and store the live lanes.
inline void storeOpaque(const ColorTarget& t, int width, int height, int bx, int by, uint16_t mask,
                        const float (*color)[kBatchLanes]) {
  alignas(64) uint32_t packed[kBatchLanes];
  for (int k = 0; k < kBatchLanes; k += 8) {
    const v8i p = packOpaque(t, color, k);
    __builtin_memcpy(packed + k, &p, sizeof p);
  }
  storePacked(t, width, height, bx, by, mask, packed);
}

// The store of a batch of D3DCOLORs into a whole 4x4 block of 8-bit target t (inside
// it) that holds `under` (a D3DCOLOR) in every pixel: the live lanes of `mask` get
// theirs, the others `under`, all 16 written at once.
inline void storePackedOver(const ColorTarget& t, int bx, int by, uint16_t mask, const uint32_t packed[kBatchLanes],
                            uint32_t under) {
  const v8i laneBit{1, 2, 4, 8, 16, 32, 64, 128};
  const v8i keep = v8i{} + int32_t(under);
  for (int k = 0; k < kBatchLanes; k += 8) {
    v8i p;
    __builtin_memcpy(&p, packed + k, sizeof p);
    const v8i out = (laneBit & ((mask >> k) & 0xff)) != 0 ? p : keep;
    // Lanes k..k+7 are rows k/4 and k/4 + 1: lanes 0,1,4,5 and 2,3,6,7 of the half.
    const v4u r0 = __builtin_shufflevector(v8u(out), v8u(out), 0, 1, 4, 5);
    const v4u r1 = __builtin_shufflevector(v8u(out), v8u(out), 2, 3, 6, 7);
    uint8_t* row = t.data + size_t(by + k / 4) * t.pitch + size_t(bx) * 4;
    __builtin_memcpy(row, &r0, sizeof r0);
    __builtin_memcpy(row + t.pitch, &r1, sizeof r1);
  }
}

// The opaque store of a batch into a whole 4x4 block of 8-bit target t (inside it) that
// holds `under` (a D3DCOLOR) in every pixel: the live lanes of `mask` get the colour as
// the opaque merge converts it, the others `under`, all 16 written at once.
inline void storeOpaqueOver(const ColorTarget& t, int bx, int by, uint16_t mask, const float (*color)[kBatchLanes],
                            uint32_t under) {
  alignas(64) uint32_t packed[kBatchLanes];
  for (int k = 0; k < kBatchLanes; k += 8) {
    const v8i p = packOpaque(t, color, k);
    __builtin_memcpy(packed + k, &p, sizeof p);
  }
  storePackedOver(t, bx, by, mask, packed, under);
}

// The depth test of a batch on a 4x4 block (inside the surface) that holds `under` in
// every pixel, by cmp as depthRows: returns the live lanes of `mask` that pass and
// writes the whole block, their z in them and `under` in the others.
template <class Cmp>
inline uint16_t depthRowsOver(const RasterDraw& d, int bx, int by, uint16_t mask, const float* z, float under,
                              Cmp cmp) {
  uint32_t pass = 0;
  const v8i laneBit{1, 2, 4, 8, 16, 32, 64, 128};
  const v8f old = v8f{} + under;
  for (int h = 0; h < 2; ++h) {
    const int live = (mask >> (8 * h)) & 0xff;
    float* row0 = d.depth->depth.data() + size_t(by + 2 * h) * d.width + bx;
    v8f nz;
    __builtin_memcpy(&nz, z + 8 * h, sizeof nz);
    const v8i ok = cmp(nz, old) & ((laneBit & live) != 0);
#if defined(__AVX__)
    __m256 okf;
    __builtin_memcpy(&okf, &ok, sizeof okf);
    pass |= uint32_t(_mm256_movemask_ps(okf)) << (8 * h);
#else
    for (int l = 0; l < 8; ++l) pass |= uint32_t(ok[l] & 1) << (8 * h + l);
#endif
    const v8f r = ok ? nz : old;
    const v4f r0 = __builtin_shufflevector(r, r, 0, 1, 4, 5);
    const v4f r1 = __builtin_shufflevector(r, r, 2, 3, 6, 7);
    __builtin_memcpy(row0, &r0, sizeof r0);
    __builtin_memcpy(row0 + d.width, &r1, sizeof r1);
  }
  return uint16_t(pass);
}

// D3DCMPFUNC F on eight depths at once.
template <uint32_t F>
inline v8i compareDepths(v8f a, v8f b) {
  using namespace d3d;
  if constexpr (F == CMP_LESS) return a < b;
  else if constexpr (F == CMP_LESSEQUAL) return a <= b;
  else if constexpr (F == CMP_GREATER) return a > b;
  else if constexpr (F == CMP_GREATEREQUAL) return a >= b;
  else if constexpr (F == CMP_EQUAL) return a == b;
  else if constexpr (F == CMP_NOTEQUAL) return a != b;
  else if constexpr (F == CMP_NEVER) return v8i{};
  else return v8i{} - 1;
}

// Depth test of the live lanes of a 4x4 batch inside the surface, two rows at a time:
// lanes 8h..8h+7 are rows 2h and 2h+1 as r0[0] r0[1] r1[0] r1[1] r0[2] r0[3] r1[2] r1[3]
// (quad-major, see core/batch.h), one shuffle away from the two rows' 16-byte loads.
template <class Cmp>
inline uint16_t depthRows(const RasterDraw& d, int bx, int by, uint16_t mask, const float* z,
                          bool writeDepth, Cmp cmp) {
  uint32_t pass = 0;
  const v8i laneBit{1, 2, 4, 8, 16, 32, 64, 128};
  for (int h = 0; h < 2; ++h) {
    // No branches on the coverage: on small triangles they are hard to predict.
    const int live = (mask >> (8 * h)) & 0xff;
    float* row0 = d.depth->depth.data() + size_t(by + 2 * h) * d.width + bx;
    float* row1 = row0 + d.width;
    v4f r0, r1;
    __builtin_memcpy(&r0, row0, sizeof r0);
    __builtin_memcpy(&r1, row1, sizeof r1);
    const v8f old = __builtin_shufflevector(r0, r1, 0, 1, 4, 5, 2, 3, 6, 7);
    v8f nz;
    __builtin_memcpy(&nz, z + 8 * h, sizeof nz);
    const v8i ok = cmp(nz, old) & ((laneBit & live) != 0);
#if defined(__AVX__)
    __m256 okf;
    __builtin_memcpy(&okf, &ok, sizeof okf);
    const int bits = _mm256_movemask_ps(okf);
#else
    int bits = 0;
    for (int l = 0; l < 8; ++l) bits |= (ok[l] & 1) << l;
#endif
    pass |= uint32_t(bits) << (8 * h);
    if (writeDepth) {  // lanes that fail write their old depth back
      const v8f r = ok ? nz : old;
      r0 = __builtin_shufflevector(r, r, 0, 1, 4, 5);
      r1 = __builtin_shufflevector(r, r, 2, 3, 6, 7);
      __builtin_memcpy(row0, &r0, sizeof r0);
      __builtin_memcpy(row1, &r1, sizeof r1);
    }
  }
  return uint16_t(pass);
}

}  // namespace refx::pipeline
