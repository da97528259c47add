// The triangle walk of coverBlocks (raster_coverage.h), written once with GCC/Clang
// vector extensions and compiled by each variant's file with its own flags: 16 lanes
// are two ymm registers with AVX2, one zmm with AVX-512. Everything here has internal
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

typedef int64_t v8l __attribute__((vector_size(64)));
typedef int32_t v16i __attribute__((vector_size(64)));
typedef int32_t v8i32 __attribute__((vector_size(32)));

// Bit j set where lane j of a comparison result is all ones.
inline uint32_t laneBits(v8l m) {
#if defined(__AVX512DQ__)
  __m512i x;
  std::memcpy(&x, &m, sizeof x);
  return _mm512_movepi64_mask(x);
#elif defined(__AVX__)
  __m256d h[2];
  std::memcpy(h, &m, sizeof h);
  return uint32_t(_mm256_movemask_pd(h[0])) | uint32_t(_mm256_movemask_pd(h[1])) << 4;
#else
  uint32_t bits = 0;
  for (int j = 0; j < 8; ++j) bits |= uint32_t(m[j] & 1) << j;
  return bits;
#endif
}
inline uint32_t laneBits(v16i m) {
#if defined(__AVX512DQ__)
  __m512i x;
  std::memcpy(&x, &m, sizeof x);
  return _mm512_movepi32_mask(x);
#elif defined(__AVX__)
  __m256 h[2];
  std::memcpy(h, &m, sizeof h);
  return uint32_t(_mm256_movemask_ps(h[0])) | uint32_t(_mm256_movemask_ps(h[1])) << 8;
#else
  uint32_t bits = 0;
  for (int j = 0; j < 16; ++j) bits |= uint32_t(m[j] & 1) << j;
  return bits;
#endif
}

// Bits of the lanes where a + b > 0 (a comparison straight into a mask with AVX-512).
inline uint32_t positiveBits(v8l a, int64_t b) {
#if defined(__AVX512F__)
  __m512i x;
  std::memcpy(&x, &a, sizeof x);
  return _mm512_cmpgt_epi64_mask(_mm512_add_epi64(x, _mm512_set1_epi64(b)), _mm512_setzero_si512());
#else
  return laneBits(a + b > 0);
#endif
}
// Bits of the lanes where a + b0 > 0, c + b1 > 0 and e + b2 > 0.
inline uint32_t positiveBits3(v16i a, int32_t b0, v16i c, int32_t b1, v16i e, int32_t b2) {
#if defined(__AVX512F__)
  __m512i x[3];
  std::memcpy(&x[0], &a, sizeof a);
  std::memcpy(&x[1], &c, sizeof c);
  std::memcpy(&x[2], &e, sizeof e);
  const __m512i zero = _mm512_setzero_si512();
  __mmask16 m = _mm512_cmpgt_epi32_mask(_mm512_add_epi32(x[0], _mm512_set1_epi32(b0)), zero);
  m = _mm512_mask_cmpgt_epi32_mask(m, _mm512_add_epi32(x[1], _mm512_set1_epi32(b1)), zero);
  return _mm512_mask_cmpgt_epi32_mask(m, _mm512_add_epi32(x[2], _mm512_set1_epi32(b2)), zero);
#else
  return laneBits((a + b0 > 0) & (c + b1 > 0) & (e + b2 > 0));
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

// p's triangle: the covered blocks of the rectangle, row by row. Per row the blocks
// entirely outside an edge (E + max offset <= 0) are found for up to 16 blocks at once
// in int64, and the others tested lane by lane: small edges with the row's block E
// clamped to int32 (a broadcast, an add and a compare per edge, also for blocks inside
// all three), large ones in int64 unless the row's test found them inside all three.
int walkTriangle(const Primitive& p, int minX, int minY, int maxX, int maxY, CoveredBlock* out) {
  if (minX > maxX || minY > maxY) return 0;
  const int blocksX = (maxX - minX) / 4 + 1;  // 1..16
  const int halves = blocksX > 8 ? 2 : 1;
  const uint32_t rowBlocks = (1u << blocksX) - 1;
  const v8l blockIndex = {0, 1, 2, 3, 4, 5, 6, 7};
  int64_t eRow[3], stepX[3], stepY[3], lo[3], hi[3];
  v8l blockOffset[3][2];
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
    blockOffset[k][1] = blockOffset[k][0] + 8 * stepX[k];
    small &= hi[k] - lo[k] <= kMaxLaneOffset32;
  }
  // Each lane's E minus its block's: int32 for small edges, else int64 (two halves).
  // Lane positions: kLaneX/kLaneY.
  const v16i laneX = {0, 1, 0, 1, 2, 3, 2, 3, 0, 1, 0, 1, 2, 3, 2, 3};
  const v16i laneY = {0, 0, 1, 1, 0, 0, 1, 1, 2, 2, 3, 3, 2, 2, 3, 3};
  v16i laneOffset32[3];
  v8l laneOffset64[3][2];
  for (int k = 0; k < 3; ++k) {
    if (small) {
      laneOffset32[k] = int32_t(p.edgeA[k] * kSubPixel) * laneX + int32_t(p.edgeB[k] * kSubPixel) * laneY;
    } else {
      for (int l = 0; l < kBatchLanes; ++l)
        laneOffset64[k][l / 8][l % 8] = p.edgeA[k] * kSubPixel * laneX[l] + p.edgeB[k] * kSubPixel * laneY[l];
    }
  }
  int count = 0;
  for (int by = minY; by <= maxY; by += 4) {
    uint32_t outside = 0, inside = rowBlocks;
    alignas(64) int32_t blockE32[3][16];
    for (int h = 0; h < halves; ++h) {
      uint32_t in = 0xff;
      for (int k = 0; k < 3; ++k) {
        const v8l e = eRow[k] + blockOffset[k][h];
        outside |= (~positiveBits(e, hi[k]) & 0xff) << (8 * h);
        if (small) {
          v8l c = e < -kClampBlock32 ? -kClampBlock32 : e;
          c = c > kClampBlock32 ? kClampBlock32 : c;
          const v8i32 c32 = __builtin_convertvector(c, v8i32);
          std::memcpy(&blockE32[k][8 * h], &c32, sizeof c32);
        } else {
          in &= positiveBits(e, lo[k]);
        }
      }
      inside &= ~(0xffu << (8 * h)) | in << (8 * h);
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
        mask = positiveBits3(laneOffset32[0], blockE32[0][i], laneOffset32[1], blockE32[1][i], laneOffset32[2],
                             blockE32[2][i]);
      } else if (!(inside >> i & 1)) {
        v8l lanes[2] = {v8l{} - 1, v8l{} - 1};
        for (int k = 0; k < 3; ++k) {
          const int64_t e = eRow[k] + i * stepX[k];
          for (int g = 0; g < 2; ++g) lanes[g] &= e + laneOffset64[k][g] > 0;
        }
        mask = laneBits(lanes[0]) | laneBits(lanes[1]) << 8;
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
