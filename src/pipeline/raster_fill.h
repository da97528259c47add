// A Clear deferred to a draw (RasterDraw::Fill), written block by block where the draw
// overwrites it: each 4x4 block of a tile inside the fill rect is "pending" until the
// draw's first batch on it, which tests against the fill's z and writes the whole
// block at once, its live lanes with the batch's results and the others with the
// fill's values (the block is written once instead of filled, then overwritten). The
// parts of the fill the draw does not overwrite so (other targets, stencil, a depth it
// does not write) are filled when the tile starts; at the tile's end every block still
// pending is filled. Every pixel ends as if the tile had been filled before it was shaded.
#pragma once
#include <cstdint>

#include "raster.h"

namespace refx::pipeline {

// The parts of a block whose fill may wait for the draw's batches.
enum FillPart : uint32_t {
  kFillColor0 = 1,  // render target 0, 8-bit
  kFillDepth = 2,
};

// How a draw's batches deal with its deferred Clear, decided once per draw.
struct LazyFill {
  uint32_t parts = 0;      // FillParts that wait for the batches; 0: none
  RasterDraw::Fill now;    // the rest of the fill, written when a tile starts
  RasterDraw::Fill later;  // the fill of `parts`, for blocks no batch writes
};

// kFillColor0 where the draw's merge stores the live lanes of a batch into target 0 as
// they are (an opaque merge into the one 8-bit target the Clear fills: no blend, alpha
// test, stencil, sRGB, dither or write mask; depth tested early or not at all);
// kFillDepth where the draw tests the depth early and writes it.
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

// Starts tile [x0, x1) x [y0, y1): fills lazy.now, and the rest of the fill rect in the
// tile except the whole blocks inside it, which become pending.
void beginTileFill(const RasterDraw& d, const LazyFill& lazy, int x0, int y0, int x1, int y1,
                   PendingBlocks& pending);

// Fills every block of the tile still pending.
void finishTileFill(const RasterDraw& d, const LazyFill& lazy, PendingBlocks& pending);

// Writes `parts` of the fill to block (bx, by), which lies inside the fill rect.
void fillBlock(const RasterDraw& d, int bx, int by, uint32_t parts);

// The early depth test of a batch on a pending block whose depth is the fill's z:
// returns the lanes of `mask` that pass and writes the whole block's depth (the draw
// writes depth wherever kFillDepth waits), their z in them and the fill's in the others.
uint16_t depthTestOverFill(const RasterDraw& d, int bx, int by, uint16_t mask, const float* z);

// Whether a Clear of `flags` (D3DCLEAR_*) over rect r writes all that `pending`, a Clear
// not written yet, still has to: a depth or stencil clear alone that it covers.
bool overwritesPendingClear(const RasterDraw::Fill& pending, uint32_t flags, const Rect& r);

// Once draw d has taken the pending Clear: where d neither tests nor writes the depth and
// stencil, their part of the fill goes back to `pending`, to be written when something
// looks at them, or never where another Clear overwrites it first.
void keepUntouchedDepthClear(RasterDraw& d, RasterDraw::Fill& pending);

}  // namespace refx::pipeline
