// A Clear deferred to a draw (RasterDraw::Fill), written block by block. Each 4x4 block
// of a tile inside the fill rect is "pending" until the draw's first batch on it: when
// the draw's depth test and merge allow, that batch tests against the fill's values
// and writes the whole block at once, its live lanes with the batch's results and the
// others with the fill's (so the block is written once instead of filled, then
// overwritten); otherwise the block is filled first. At the tile's end every block
// still pending is filled. Every pixel ends as if the tile had been filled first.
#pragma once
#include <cstdint>

#include "raster.h"

namespace refx::pipeline {

// The parts of a block a deferred Clear writes.
enum FillPart : uint32_t {
  kFillColor0 = 1,       // render target 0
  kFillOtherColors = 2,  // render targets 1-3
  kFillDepth = 4,
  kFillStencil = 8,
};

// What a draw's batches may do with its deferred Clear, decided once per draw.
struct LazyFill {
  bool enabled = false;  // blocks wait for the batches (else tiles are filled first)
  // The draw's merge stores the live lanes of a batch into target 0 as they are (an
  // opaque merge into the one 8-bit target the Clear fills: no blend, alpha test,
  // stencil, sRGB, dither or write mask; the depth tested early or not at all).
  bool overwritesColor = false;
  uint32_t parts = 0;  // FillParts the Clear writes
};

LazyFill lazyFillFor(const RasterDraw& d);

// The blocks of one tile whose fill is pending: bit c of rows[r] is the block at
// (x0 + 4c, y0 + 4r).
struct PendingBlocks {
  int x0 = 0, y0 = 0;
  uint16_t rows[kTileSize / 4] = {};

  // Whether block (bx, by) of the tile is pending; it is not any more.
  bool take(int bx, int by) {
    uint16_t& row = rows[(by - y0) >> 2];
    const uint16_t bit = uint16_t(1u << ((bx - x0) >> 2));
    const bool was = (row & bit) != 0;
    row = uint16_t(row & ~bit);
    return was;
  }
};

// Starts tile [x0, x1) x [y0, y1): with `lazy` enabled, the blocks wholly inside the
// fill rect become pending and the rest of the rect in the tile is filled now;
// otherwise all of it is filled now.
void beginTileFill(const RasterDraw& d, const LazyFill& lazy, int x0, int y0, int x1, int y1,
                   PendingBlocks& pending);

// Fills every block of the tile still pending.
void finishTileFill(const RasterDraw& d, PendingBlocks& pending);

// Writes `parts` of the fill to block (bx, by), which lies inside the fill rect.
void fillBlock(const RasterDraw& d, int bx, int by, uint32_t parts);

// The lanes of `mask` whose z passes depth function `func` against the stored `ref`.
uint16_t depthPassAgainst(uint32_t func, uint16_t mask, const float* z, float ref);

// Stores block (bx, by) of the depth buffer: z (batch order) in the lanes of `mask`,
// `under` in the others.
void storeBlockDepthOver(const RasterDraw& d, int bx, int by, uint16_t mask, const float* z, float under);

}  // namespace refx::pipeline
