// Which pixels of a tile's 4x4 blocks a primitive covers (raster.cpp's tile loop): a
// scalar reference, block by block as the rasterizer defines coverage, and the fast
// walk over one primitive's blocks in a tile, in an AVX2 variant (raster_coverage.cpp)
// and an AVX-512 one (raster_coverage_avx512.cpp) chosen by activeIsa(). Edge
// functions are exact integers, so every variant gives the reference's masks.
#pragma once
#include <cstdint>

#include "raster.h"

namespace refx::pipeline {

// The coverage of the 4x4 block whose top-left pixel is (bx, by) by p, lane l being
// pixel (bx + kLaneX[l], by + kLaneY[l]) (output_merger.h): for triangles the pixel
// centres inside the edge functions (top-left rule: E + bias > 0), for lines the pixel
// nearest the line on each step along the major axis, for points the bounding box;
// limited to p's bounds. The definition the fast walks are tested against.
uint16_t referenceCoverage(const Primitive& p, int bx, int by);

// A block a primitive covers at least one pixel of, and which.
struct CoveredBlock {
  int32_t bx, by;  // top-left pixel
  uint32_t mask;   // lane bits (kBatchLanes)
};

// The most blocks coverBlocks writes: one tile's.
constexpr int kMaxTileBlocks = (kTileSize / 4) * (kTileSize / 4);

// Writes to `out`, row by row and left to right, the blocks with top-left pixel
// (minX + 4i, minY + 4j) inside [minX, maxX] x [minY, maxY] that p covers, with their
// masks (referenceCoverage's), and returns how many. minX and minY are multiples of 4,
// the rectangle lies inside one tile (at most kTileSize pixels a side).
using CoverBlocksFn = int (*)(const Primitive& p, int minX, int minY, int maxX, int maxY,
                              CoveredBlock* out);

// The variant for refx's active instruction set.
CoverBlocksFn chooseCoverBlocks();

// The AVX2 variant (any primitive) and the AVX-512 one (raster_coverage_avx512.cpp:
// triangles; it hands lines and points to the AVX2 variant). Call the latter only
// where the CPU has AVX-512.
int coverBlocksAvx2(const Primitive& p, int minX, int minY, int maxX, int maxY, CoveredBlock* out);
int coverBlocksAvx512(const Primitive& p, int minX, int minY, int maxX, int maxY, CoveredBlock* out);

}  // namespace refx::pipeline
