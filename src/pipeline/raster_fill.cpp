#include "raster_fill.h"

#include <algorithm>
#include <cstring>
#if defined(__AVX__)
#include <immintrin.h>
#endif

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

namespace {
typedef float v8f __attribute__((vector_size(32)));
typedef int32_t v8i __attribute__((vector_size(32)));

template <class Cmp>
uint16_t passingLanes(uint16_t mask, const float* z, float ref, Cmp cmp) {
  uint32_t bits = 0;
  const v8f r = v8f{} + ref;
  for (int h = 0; h < 2; ++h) {
    v8f v;
    std::memcpy(&v, z + 8 * h, sizeof v);
    const v8i pass = cmp(v, r);
#if defined(__AVX__)
    __m256 f;
    std::memcpy(&f, &pass, sizeof f);
    bits |= uint32_t(_mm256_movemask_ps(f)) << (8 * h);
#else
    for (int l = 0; l < 8; ++l) bits |= uint32_t(pass[l] & 1) << (8 * h + l);
#endif
  }
  return uint16_t(mask & bits);
}
}  // namespace

uint16_t depthPassAgainst(uint32_t func, uint16_t mask, const float* z, float ref) {
  switch (func) {
    case CMP_NEVER: return 0;
    case CMP_LESS: return passingLanes(mask, z, ref, [](v8f a, v8f b) { return a < b; });
    case CMP_EQUAL: return passingLanes(mask, z, ref, [](v8f a, v8f b) { return a == b; });
    case CMP_LESSEQUAL: return passingLanes(mask, z, ref, [](v8f a, v8f b) { return a <= b; });
    case CMP_GREATER: return passingLanes(mask, z, ref, [](v8f a, v8f b) { return a > b; });
    case CMP_NOTEQUAL: return passingLanes(mask, z, ref, [](v8f a, v8f b) { return a != b; });
    case CMP_GREATEREQUAL: return passingLanes(mask, z, ref, [](v8f a, v8f b) { return a >= b; });
    default: return mask;
  }
}

void storeBlockDepthOver(const RasterDraw& d, int bx, int by, uint16_t mask, const float* z, float under) {
  // Lanes 8h..8h+7 are rows 2h and 2h+1 as r0[0] r0[1] r1[0] r1[1] r0[2] r0[3] r1[2]
  // r1[3] (quad-major, see core/batch.h).
  const v8i laneBit{1, 2, 4, 8, 16, 32, 64, 128};
  const v8f keep = v8f{} + under;
  typedef float v4f __attribute__((vector_size(16)));
  for (int h = 0; h < 2; ++h) {
    v8f v;
    std::memcpy(&v, z + 8 * h, sizeof v);
    v = (laneBit & ((mask >> (8 * h)) & 0xff)) != 0 ? v : keep;
    float* row0 = d.depth->depth.data() + size_t(by + 2 * h) * d.width + bx;
    const v4f r0 = __builtin_shufflevector(v, v, 0, 1, 4, 5);
    const v4f r1 = __builtin_shufflevector(v, v, 2, 3, 6, 7);
    std::memcpy(row0, &r0, sizeof r0);
    std::memcpy(row0 + d.width, &r1, sizeof r1);
  }
}

}  // namespace refx::pipeline
