// The triangle walk of coverBlocks (raster_coverage.h), written once with GCC/Clang
// vector extensions and compiled by each variant's file with its own flags: 16 int32
// lanes are two ymm registers with AVX2, one zmm with AVX-512. Everything here has internal
// linkage, so no variant can end up calling another's copy.
#pragma once
#include <cstdint>
#include <cstring>
#if defined(__AVX__)
#include <immintrin.h>
#endif

#include "raster_coverage.h"

namespace refx::pipeline {
namespace {

// Vectors of the variant's native width (a wider vector type would be split by the
// compiler through memory): 8 int64 or 16 int32 lanes with AVX-512, 4 or 8 with AVX2.
#if defined(__AVX512F__)
constexpr int kVectorBytes = 64;
#else
constexpr int kVectorBytes = 32;
#endif
typedef int64_t vl __attribute__((vector_size(kVectorBytes)));
typedef int32_t vi __attribute__((vector_size(kVectorBytes)));
constexpr int kLongLanes = kVectorBytes / 8, kIntLanes = kVectorBytes / 4;
constexpr int kBlockGroups = 16 / kLongLanes;          // a row's 16 blocks
constexpr int kLaneGroups64 = kBatchLanes / kLongLanes;  // a block's lanes in int64
constexpr int kLaneGroups32 = kBatchLanes / kIntLanes;   // and in int32
constexpr uint32_t kLongLaneBits = (1u << kLongLanes) - 1;

// Bit j set where lane j of a comparison result is all ones.
inline uint32_t laneBits(vl m) {
#if defined(__AVX512DQ__)
  __m512i x;
  std::memcpy(&x, &m, sizeof x);
  return _mm512_movepi64_mask(x);
#elif defined(__AVX__)
  __m256d x;
  std::memcpy(&x, &m, sizeof x);
  return uint32_t(_mm256_movemask_pd(x));
#else
  uint32_t bits = 0;
  for (int j = 0; j < kLongLanes; ++j) bits |= uint32_t(m[j] & 1) << j;
  return bits;
#endif
}
inline uint32_t laneBits(vi m) {
#if defined(__AVX512DQ__)
  __m512i x;
  std::memcpy(&x, &m, sizeof x);
  return _mm512_movepi32_mask(x);
#elif defined(__AVX__)
  __m256 x;
  std::memcpy(&x, &m, sizeof x);
  return uint32_t(_mm256_movemask_ps(x));
#else
  uint32_t bits = 0;
  for (int j = 0; j < kIntLanes; ++j) bits |= uint32_t(m[j] & 1) << j;
  return bits;
#endif
}

// Bits of the lanes where a + b > 0 (a comparison straight into a mask with AVX-512).
inline uint32_t positiveBits(vl a, int64_t b) {
#if defined(__AVX512F__)
  __m512i x;
  std::memcpy(&x, &a, sizeof x);
  return _mm512_cmpgt_epi64_mask(_mm512_add_epi64(x, _mm512_set1_epi64(b)), _mm512_setzero_si512());
#else
  return laneBits(vl(a + b > 0));  // (clang's comparison type converts to vl and vi alike)
#endif
}
// The 16 lanes where a + b0 > 0, c + b1 > 0 and e + b2 > 0 (a, c, e: kLaneGroups32
// vectors each).
inline uint32_t positiveBits3(const vi* a, int32_t b0, const vi* c, int32_t b1, const vi* e, int32_t b2) {
#if defined(__AVX512F__)
  __m512i x[3];
  std::memcpy(&x[0], a, sizeof x[0]);
  std::memcpy(&x[1], c, sizeof x[1]);
  std::memcpy(&x[2], e, sizeof x[2]);
  const __m512i zero = _mm512_setzero_si512();
  __mmask16 m = _mm512_cmpgt_epi32_mask(_mm512_add_epi32(x[0], _mm512_set1_epi32(b0)), zero);
  m = _mm512_mask_cmpgt_epi32_mask(m, _mm512_add_epi32(x[1], _mm512_set1_epi32(b1)), zero);
  return _mm512_mask_cmpgt_epi32_mask(m, _mm512_add_epi32(x[2], _mm512_set1_epi32(b2)), zero);
#else
  uint32_t bits = 0;
  for (int g = 0; g < kLaneGroups32; ++g)
    bits |= laneBits(vi((a[g] + b0 > 0) & (c[g] + b1 > 0) & (e[g] + b2 > 0))) << (kIntLanes * g);
  return bits;
#endif
}

// Lane bits of a block's pixel columns x >= c and x <= c, and rows likewise
// (kLaneX/kLaneY of output_merger.h: column 0 is lanes 0, 2, 8, 10; row 0 lanes 0, 1, 4, 5).
constexpr uint32_t kColumnsFrom[4] = {0xffff, 0xfafa, 0xf0f0, 0xa0a0};
constexpr uint32_t kColumnsUpTo[4] = {0x0505, 0x0f0f, 0x5f5f, 0xffff};
constexpr uint32_t kRowsFrom[4] = {0xffff, 0xffcc, 0xff00, 0xcc00};
constexpr uint32_t kRowsUpTo[4] = {0x0033, 0x00ff, 0x33ff, 0xffff};

// The lanes of a block whose pixels lie in [lo, hi] along one axis, from the block's
// first coordinate b (lo - b <= 3, hi - b >= 0).
inline uint32_t lanesWithin(const uint32_t (&from)[4], const uint32_t (&upTo)[4], int b, int lo, int hi) {
  return from[lo - b > 0 ? lo - b : 0] & upTo[hi - b < 3 ? hi - b : 3];
}

constexpr int64_t kSubPixel = int64_t(1) << kSubPixelBits;

// A lane's E minus its block's in int32 is exact when |A| + |B| times 3 pixels stays
// within 2^29 subpixel units; the block's E, clamped to +-2^30, then gives every lane's
// sign of E + offset without overflow (beyond 2^30 no offset can change the sign).
constexpr int64_t kMaxLaneOffset32 = int64_t(1) << 29;
constexpr int64_t kClampBlock32 = int64_t(1) << 30;
// The clamp of a row's block values as one vector pass needs AVX-512's int64 min, max
// and narrowing; without them each block's values are clamped on their own.
#if defined(__AVX512F__)
constexpr bool kVectorClamp = true;
typedef int32_t v8i32 __attribute__((vector_size(32)));  // a vl narrowed
#else
constexpr bool kVectorClamp = false;
#endif

// p's triangle: the covered blocks of the rectangle, row by row. Per row the blocks
// entirely outside an edge (E + max offset <= 0) are found for up to 16 blocks at once
// in int64, and the others tested lane by lane: small edges with the row's block E
// clamped to int32 (a broadcast, an add and a compare per edge, also for blocks inside
// all three), large ones in int64 unless the row's test found them inside all three.
int walkTriangle(const Primitive& p, int minX, int minY, int maxX, int maxY, CoveredBlock* out) {
  if (minX > maxX || minY > maxY) return 0;
  const int blocksX = (maxX - minX) / 4 + 1;  // 1..16
  const int groups = (blocksX + kLongLanes - 1) / kLongLanes;
  const uint32_t rowBlocks = (1u << blocksX) - 1;
  vl blockIndex;
  for (int j = 0; j < kLongLanes; ++j) blockIndex[j] = j;
  int64_t eRow[3], stepX[3], stepY[3], lo[3], hi[3];
  vl blockOffset[3][kBlockGroups];
  bool small = true;
  for (int k = 0; k < 3; ++k) {
    const int64_t a = p.edgeA[k], b = p.edgeB[k];
    const int64_t ax = a * 3 * kSubPixel, by3 = b * 3 * kSubPixel;
    lo[k] = (ax < 0 ? ax : 0) + (by3 < 0 ? by3 : 0);
    hi[k] = (ax > 0 ? ax : 0) + (by3 > 0 ? by3 : 0);
    stepX[k] = a * 4 * kSubPixel;
    stepY[k] = b * 4 * kSubPixel;
    eRow[k] = a * (minX * kSubPixel) + b * (minY * kSubPixel) + p.edgeC[k] + p.edgeBias[k];
    blockOffset[k][0] = blockIndex * stepX[k];
    for (int h = 1; h < kBlockGroups; ++h) blockOffset[k][h] = blockOffset[k][h - 1] + kLongLanes * stepX[k];
    small &= hi[k] - lo[k] <= kMaxLaneOffset32;
  }
  // Each lane's E minus its block's: int32 for small edges, else int64. Lane
  // positions: kLaneX/kLaneY.
  constexpr int8_t laneX[kBatchLanes] = {0, 1, 0, 1, 2, 3, 2, 3, 0, 1, 0, 1, 2, 3, 2, 3};
  constexpr int8_t laneY[kBatchLanes] = {0, 0, 1, 1, 0, 0, 1, 1, 2, 2, 3, 3, 2, 2, 3, 3};
  vi laneOffset32[3][kLaneGroups32];
  vl laneOffset64[3][kLaneGroups64];
  for (int k = 0; k < 3; ++k) {
    if (small) {
      for (int g = 0; g < kLaneGroups32; ++g) {
        vi x, y;
        for (int j = 0; j < kIntLanes; ++j) x[j] = laneX[kIntLanes * g + j], y[j] = laneY[kIntLanes * g + j];
        laneOffset32[k][g] = int32_t(p.edgeA[k] * kSubPixel) * x + int32_t(p.edgeB[k] * kSubPixel) * y;
      }
    } else {
      for (int l = 0; l < kBatchLanes; ++l)
        laneOffset64[k][l / kLongLanes][l % kLongLanes] =
            p.edgeA[k] * kSubPixel * laneX[l] + p.edgeB[k] * kSubPixel * laneY[l];
    }
  }
  int count = 0;
  for (int by = minY; by <= maxY; by += 4) {
    uint32_t outside = 0, inside = rowBlocks;
    alignas(64) int32_t blockE32[3][16];
    for (int h = 0; h < groups; ++h) {
      uint32_t in = kLongLaneBits;
      for (int k = 0; k < 3; ++k) {
        const vl e = eRow[k] + blockOffset[k][h];
        outside |= (~positiveBits(e, hi[k]) & kLongLaneBits) << (kLongLanes * h);
        if (!small) {
          in &= positiveBits(e, lo[k]);
        } else {
#if defined(__AVX512F__)
          vl c = e < -kClampBlock32 ? -kClampBlock32 : e;
          c = c > kClampBlock32 ? kClampBlock32 : c;
          const v8i32 c32 = __builtin_convertvector(c, v8i32);
          std::memcpy(&blockE32[k][kLongLanes * h], &c32, sizeof c32);
#endif
        }
      }
      inside &= ~(kLongLaneBits << (kLongLanes * h)) | in << (kLongLanes * h);
    }
    uint32_t left = rowBlocks & ~outside;
    const uint32_t rows = by < p.minY || by + 3 > p.maxY ? lanesWithin(kRowsFrom, kRowsUpTo, by, p.minY, p.maxY)
                                                         : 0xffff;
    while (left) {
      const int i = __builtin_ctz(left);
      left &= left - 1;
      const int bx = minX + 4 * i;
      uint32_t mask = 0xffff;
      if (small) {  // a block inside all three edges gets all 16 lanes here too
        if constexpr (!kVectorClamp)
          for (int k = 0; k < 3; ++k) {
            const int64_t e = eRow[k] + i * stepX[k];
            blockE32[k][i] = int32_t(e < -kClampBlock32 ? -kClampBlock32 : e > kClampBlock32 ? kClampBlock32 : e);
          }
        mask = positiveBits3(laneOffset32[0], blockE32[0][i], laneOffset32[1], blockE32[1][i], laneOffset32[2],
                             blockE32[2][i]);
      } else if (!(inside >> i & 1)) {
        mask = 0;
        for (int g = 0; g < kLaneGroups64; ++g) {
          vl lanes = vl{} - 1;
          for (int k = 0; k < 3; ++k) lanes &= eRow[k] + i * stepX[k] + laneOffset64[k][g] > 0;
          mask |= laneBits(lanes) << (kLongLanes * g);
        }
      }
      mask &= rows;
      if (bx < p.minX || bx + 3 > p.maxX) mask &= lanesWithin(kColumnsFrom, kColumnsUpTo, bx, p.minX, p.maxX);
      if (mask) out[count++] = {bx, by, mask};
    }
    for (int k = 0; k < 3; ++k) eRow[k] += stepY[k];
  }
  return count;
}

}  // namespace
}  // namespace refx::pipeline
