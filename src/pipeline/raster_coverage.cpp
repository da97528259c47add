// The scalar coverage reference and the AVX2 variant of the block walk
// (raster_coverage.h).
#include "raster_coverage.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "output_merger.h"
#include "raster_coverage_walk.h"
#include "refx/core/cpu_features.h"

namespace refx::pipeline {

namespace {

constexpr int N = kBatchLanes;
constexpr int64_t kOne = int64_t(1) << kSubPixelBits;

// Four int64 lanes (GCC/Clang vector extensions: vpaddq, vpcmpgtq).
typedef int64_t v4l __attribute__((vector_size(32)));

// A triangle's edge functions stepped from block to block: E at a block's top-left
// pixel centre and the extremes over its 4x4 pixel centres relative to it.
struct EdgeWalk {
  int64_t lo[3], hi[3];  // offsets of the block's minimum and maximum
  // Triangles: E at each lane's pixel centre minus E at the block's top-left one, in
  // lane order (four lanes to a v4l).
  v4l laneOffset[3][N / 4];

  explicit EdgeWalk(const Primitive& p) {
    for (int k = 0; k < 3; ++k) {
      const int64_t ax = p.edgeA[k] * 3 * kOne, by3 = p.edgeB[k] * 3 * kOne;
      lo[k] = std::min<int64_t>(ax, 0) + std::min<int64_t>(by3, 0);
      hi[k] = std::max<int64_t>(ax, 0) + std::max<int64_t>(by3, 0);
      if (p.kind != PrimKind::Triangle) continue;
      for (int l = 0; l < N; ++l)
        laneOffset[k][l / 4][l % 4] = p.edgeA[k] * kOne * kLaneX[l] + p.edgeB[k] * kOne * kLaneY[l];
    }
  }
  static void at(const Primitive& p, int bx, int by, int64_t e[3]) {
    for (int k = 0; k < 3; ++k)
      e[k] = p.edgeA[k] * (bx * kOne) + p.edgeB[k] * (by * kOne) + p.edgeC[k] + p.edgeBias[k];
  }
};

// Bit j set where lane j of m is all ones (m holds comparison results).
inline uint32_t laneBits4(v4l m) {
#if defined(__AVX__)
  __m256d d;
  std::memcpy(&d, &m, sizeof d);
  return uint32_t(_mm256_movemask_pd(d));  // the sign bits
#else
  uint32_t bits = 0;
  for (int j = 0; j < 4; ++j) bits |= uint32_t(m[j] & 1) << j;
  return bits;
#endif
}

// Coverage of a 4x4 batch at (bx, by) by primitive p; for triangles e0 holds the
// edge functions at (bx, by) (EdgeWalk::at).
uint16_t coverage(const Primitive& p, const EdgeWalk& walk, const int64_t* e0, int bx, int by) {
  uint16_t mask = 0;
  if (p.kind == PrimKind::Triangle) {
    bool inside = true;
    for (int k = 0; k < 3; ++k) {
      if (e0[k] + walk.hi[k] <= 0) return 0;  // whole block outside this edge
      inside &= e0[k] + walk.lo[k] > 0;
    }
    if (inside) {
      mask = 0xffff;
    } else {
      // Per lane, in int64: E(lane) = E(block) + the lane's offset, exact (every term is
      // below 2^53: subpixel coordinates stay within the guard band).
      v4l in[4];
      for (int g = 0; g < 4; ++g) in[g] = v4l{} - 1;
      for (int k = 0; k < 3; ++k) {
        const v4l e = v4l{} + e0[k];
        for (int g = 0; g < 4; ++g) in[g] &= (e + walk.laneOffset[k][g]) > 0;
      }
      for (int g = 0; g < 4; ++g) mask |= uint16_t(laneBits4(in[g]) << (4 * g));
    }
  } else if (p.kind == PrimKind::Line) {
    // One pixel per step along the major axis: the pixel whose centre is nearest
    // the line (ties toward the smaller coordinate).
    for (int l = 0; l < N; ++l) {
      const int x = bx + kLaneX[l], y = by + kLaneY[l];
      const int major = p.xMajor ? x : y, minor = p.xMajor ? y : x;
      const float m = p.lineM * float(major) + p.lineQ;
      const bool in = minor == int(std::ceil(m - 0.5f));
      mask |= uint16_t(in) << l;
    }
  } else {
    mask = 0xffff;  // points: the bounding box is the point's footprint
  }
  // Clip to the primitive's scissor/viewport bounds (only blocks on the border).
  if (bx < p.minX || by < p.minY || bx + 3 > p.maxX || by + 3 > p.maxY) {
    for (int l = 0; l < N; ++l) {
      const int x = bx + kLaneX[l], y = by + kLaneY[l];
      if (x < p.minX || x > p.maxX || y < p.minY || y > p.maxY) mask &= uint16_t(~(1u << l));
    }
  }
  return mask;
}

}  // namespace

uint16_t referenceCoverage(const Primitive& p, int bx, int by) {
  const EdgeWalk walk(p);
  int64_t e[3] = {};
  if (p.kind == PrimKind::Triangle) EdgeWalk::at(p, bx, by, e);
  return coverage(p, walk, e, bx, by);
}

int coverBlocksAvx2(const Primitive& p, int minX, int minY, int maxX, int maxY, CoveredBlock* out) {
  if (p.kind == PrimKind::Triangle) return walkTriangle(p, minX, minY, maxX, maxY, out);
  // Lines and points: block by block (no edge functions).
  const EdgeWalk walk(p);
  const int64_t e[3] = {};
  int count = 0;
  for (int by = minY; by <= maxY; by += 4)
    for (int bx = minX; bx <= maxX; bx += 4)
      if (const uint16_t mask = coverage(p, walk, e, bx, by)) out[count++] = {bx, by, mask};
  return count;
}

CoverBlocksFn chooseCoverBlocks() {
  return activeIsa() == CpuIsa::Avx512 ? coverBlocksAvx512 : coverBlocksAvx2;
}

}  // namespace refx::pipeline
