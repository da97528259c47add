#include "raster_fill.h"

#include <algorithm>
#include <cstring>

#include "merge_kernels.h"

namespace refx::pipeline {

using namespace d3d;

LazyFill lazyFillFor(const RasterDraw& d) {
  LazyFill lazy;
  const RasterDraw::Fill& f = d.fill;
  lazy.now = f;
  lazy.later = RasterDraw::Fill{};
  lazy.later.rect = f.rect;
  lazy.later.colorValue = f.colorValue;
  lazy.later.z = f.z;
  const ColorTarget& t = d.targets[0];
  bool opaque = t.data && t.data == f.colorTargets[0].data && !t.isFloat && t.writeMask == 0xf &&
                !d.blend.enable && !d.alphaTest && !d.stencil && !d.srgbWrite && !d.dither &&
                (!d.depthTest || d.earlyDepth);
  for (size_t i = 1; i < d.targets.size(); ++i) opaque &= !d.targets[i].data;
  if (f.color && opaque) {
    lazy.parts |= kFillColor0;
    lazy.later.color = true;
    lazy.later.colorTargets[0] = f.colorTargets[0];
    lazy.now.colorTargets[0] = ColorTarget{};
  }
  if (d.depth && f.depth && d.earlyDepth && d.depthWrite) {
    lazy.parts |= kFillDepth;
    lazy.later.depth = true;
    lazy.now.depth = false;
  }
  return lazy;
}

void beginTileFill(const RasterDraw& d, const LazyFill& lazy, int x0, int y0, int x1, int y1,
                   PendingBlocks& pending) {
  pending.x0 = x0;
  pending.y0 = y0;
  std::fill(std::begin(pending.rows), std::end(pending.rows), uint16_t(0));
  const Rect& r = d.fill.rect;
  const int rx0 = std::max(x0, r.left), ry0 = std::max(y0, r.top);
  const int rx1 = std::min(x1, r.right), ry1 = std::min(y1, r.bottom);
  if (rx0 >= rx1 || ry0 >= ry1) return;
  if (!lazy.parts) {
    applyFill(d.fill, d.depth, rx0, ry0, rx1, ry1);
    return;
  }
  applyFill(lazy.now, d.depth, rx0, ry0, rx1, ry1);
  // The whole blocks inside the rect (and so inside the target: the rect is).
  const int ix0 = (rx0 + 3) & ~3, iy0 = (ry0 + 3) & ~3, ix1 = rx1 & ~3, iy1 = ry1 & ~3;
  if (ix0 >= ix1 || iy0 >= iy1) {
    applyFill(lazy.later, d.depth, rx0, ry0, rx1, ry1);
    return;
  }
  applyFill(lazy.later, d.depth, rx0, ry0, rx1, iy0);  // above the blocks
  applyFill(lazy.later, d.depth, rx0, iy1, rx1, ry1);  // below
  applyFill(lazy.later, d.depth, rx0, iy0, ix0, iy1);  // left
  applyFill(lazy.later, d.depth, ix1, iy0, rx1, iy1);  // right
  const uint32_t bits = ((1u << ((ix1 - x0) >> 2)) - 1) & ~((1u << ((ix0 - x0) >> 2)) - 1);
  for (int y = iy0; y < iy1; y += 4) pending.rows[(y - y0) >> 2] = uint16_t(bits);
}

void finishTileFill(const RasterDraw& d, const LazyFill& lazy, PendingBlocks& pending) {
  for (int r = 0; r < kTileSize / 4; ++r) {
    uint32_t bits = pending.rows[r];
    pending.rows[r] = 0;
    const int y = pending.y0 + 4 * r;
    while (bits) {  // each run of pending blocks as one rectangle
      const int c0 = __builtin_ctz(bits);
      const int c1 = c0 + __builtin_ctz(~(bits >> c0));
      applyFill(lazy.later, d.depth, pending.x0 + 4 * c0, y, pending.x0 + 4 * c1, y + 4);
      bits &= ~((1u << c1) - 1);
    }
  }
}

void fillBlock(const RasterDraw& d, int bx, int by, uint32_t parts) {
  const RasterDraw::Fill& f = d.fill;
  if (parts & kFillColor0) {
    const ColorTarget& t = f.colorTargets[0];
    const uint32_t v[4] = {f.colorValue, f.colorValue, f.colorValue, f.colorValue};
    for (int y = by; y < by + 4; ++y) std::memcpy(t.data + size_t(y) * t.pitch + size_t(bx) * 4, v, sizeof v);
  }
  if (parts & kFillDepth) {
    const float v[4] = {f.z, f.z, f.z, f.z};
    for (int y = by; y < by + 4; ++y) std::memcpy(d.depth->depth.data() + size_t(y) * d.width + bx, v, sizeof v);
  }
}

uint16_t depthTestOverFill(const RasterDraw& d, int bx, int by, uint16_t mask, const float* z) {
  const float under = d.fill.z;
  switch (d.depthFunc) {
    case CMP_NEVER: return depthRowsOver(d, bx, by, mask, z, under, [](v8f a, v8f b) { return compareDepths<CMP_NEVER>(a, b); });
    case CMP_LESS: return depthRowsOver(d, bx, by, mask, z, under, [](v8f a, v8f b) { return compareDepths<CMP_LESS>(a, b); });
    case CMP_EQUAL: return depthRowsOver(d, bx, by, mask, z, under, [](v8f a, v8f b) { return compareDepths<CMP_EQUAL>(a, b); });
    case CMP_LESSEQUAL:
      return depthRowsOver(d, bx, by, mask, z, under, [](v8f a, v8f b) { return compareDepths<CMP_LESSEQUAL>(a, b); });
    case CMP_GREATER:
      return depthRowsOver(d, bx, by, mask, z, under, [](v8f a, v8f b) { return compareDepths<CMP_GREATER>(a, b); });
    case CMP_NOTEQUAL:
      return depthRowsOver(d, bx, by, mask, z, under, [](v8f a, v8f b) { return compareDepths<CMP_NOTEQUAL>(a, b); });
    case CMP_GREATEREQUAL:
      return depthRowsOver(d, bx, by, mask, z, under, [](v8f a, v8f b) { return compareDepths<CMP_GREATEREQUAL>(a, b); });
    default: return depthRowsOver(d, bx, by, mask, z, under, [](v8f a, v8f b) { return compareDepths<CMP_ALWAYS>(a, b); });
  }
}

bool overwritesPendingClear(const RasterDraw::Fill& pending, uint32_t flags, const Rect& r) {
  if (pending.color || (!pending.depth && !pending.stencil)) return false;
  if ((pending.depth && !(flags & CLEAR_ZBUFFER)) || (pending.stencil && !(flags & CLEAR_STENCIL))) return false;
  const Rect& p = pending.rect;
  return r.left <= p.left && r.top <= p.top && r.right >= p.right && r.bottom >= p.bottom;
}

void keepUntouchedDepthClear(RasterDraw& d, RasterDraw::Fill& pending) {
  if (d.depthTest || d.stencil || (!d.fill.depth && !d.fill.stencil)) return;
  pending = RasterDraw::Fill{};
  pending.rect = d.fill.rect;
  pending.depth = d.fill.depth;
  pending.stencil = d.fill.stencil;
  pending.z = d.fill.z;
  pending.stencilValue = d.fill.stencilValue;
  d.fill.depth = d.fill.stencil = false;
}

}  // namespace refx::pipeline
