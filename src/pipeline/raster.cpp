#include "raster.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "ff_pixel.h"
#include "merge_kernels.h"
#include "output_merger.h"
#include "raster_coverage.h"
#include "raster_fill.h"
#include "raster_interpolate.h"
#include "raster_lod.h"
#include "refx/core/cpu_features.h"
#include "refx/exec/lower.h"

namespace refx::pipeline {

namespace {

constexpr int N = kBatchLanes;

// The primitives of each tile, in draw order: tile t's are entries[start[t],
// start[t + 1]) (a counting sort: no list per tile to allocate).
struct TileBins {
  int tilesX = 0, tilesY = 0;
  std::vector<uint32_t> start;    // tiles + 1
  std::vector<uint32_t> entries;  // primitive indices
  size_t tiles() const { return start.size() - 1; }
};

// Draws with fewer primitives are binned by one thread.
constexpr size_t kParallelBinPrimitives = 1024;

// Calls fn(tile) for every tile that p's rectangle touches.
template <class Fn>
inline void forTilesOf(const Primitive& p, int tilesX, Fn fn) {
  if (p.minX > p.maxX || p.minY > p.maxY) return;
  for (int ty = p.minY / kTileSize; ty <= p.maxY / kTileSize; ++ty)
    for (int tx = p.minX / kTileSize; tx <= p.maxX / kTileSize; ++tx) fn(size_t(ty) * size_t(tilesX) + size_t(tx));
}

// Consecutive ranges of the primitives on the pool's threads: each counts its entries
// per tile, then writes them where the counts of the tiles before and of the ranges
// before in the same tile end, so every tile's entries stay in draw order.
void bin(const RasterDraw& d, TileBins& bins, ThreadPool& pool) {
  bins.tilesX = (d.width + kTileSize - 1) / kTileSize;
  bins.tilesY = (d.height + kTileSize - 1) / kTileSize;
  const size_t tiles = size_t(bins.tilesX) * size_t(bins.tilesY), prims = d.prims.size();
  const size_t parts = prims >= kParallelBinPrimitives ? size_t(pool.threadCount()) : 1;
  std::vector<uint32_t> at(parts * tiles, 0);  // counts, then each range's next entry per tile
  const auto range = [&](size_t part, auto fn) {
    for (size_t i = prims * part / parts, end = prims * (part + 1) / parts; i < end; ++i)
      forTilesOf(d.prims[i], bins.tilesX, [&](size_t t) { fn(uint32_t(i), at[part * tiles + t]); });
  };
  const auto run = [&](auto fn) {
    if (parts == 1) fn(0, 0);
    else pool.parallelFor(parts, fn);
  };
  run([&](size_t part, int) { range(part, [](uint32_t, uint32_t& count) { ++count; }); });
  bins.start.resize(tiles + 1);
  uint32_t total = 0;
  for (size_t t = 0; t < tiles; ++t) {
    bins.start[t] = total;
    for (size_t part = 0; part < parts; ++part) {
      const uint32_t count = at[part * tiles + t];
      at[part * tiles + t] = total;
      total += count;
    }
  }
  bins.start[tiles] = total;
  bins.entries.resize(total);
  run([&](size_t part, int) { range(part, [&](uint32_t i, uint32_t& next) { bins.entries[next++] = i; }); });
}

// Per-lane pixel offsets inside a batch, as floats (interpolation).
alignas(64) constexpr float kLaneXf[N] = {0, 1, 0, 1, 2, 3, 2, 3, 0, 1, 0, 1, 2, 3, 2, 3};
alignas(64) constexpr float kLaneYf[N] = {0, 0, 1, 1, 0, 0, 1, 1, 2, 2, 3, 3, 2, 2, 3, 3};

// One batch of a group (shadeGroup): its registers, depth and pass-through colors.
struct GroupSlot {
  exec::BatchRegisters regs;  // prepared for RasterDraw::pixelRest
  exec::ProgramRunner runRest;  // pixelRest on regs, where it is native code
  std::vector<InputTarget> inputTargets;  // RasterDraw::inputs' destinations in regs
  alignas(64) float z[N];
  alignas(64) float invW[N];
  alignas(64) float passU[N], passV[N];  // RasterDraw::passthroughSampler's coordinates
  alignas(64) uint32_t packed[N];
  InputTarget passTargets[2];
};

// Where a group lookup's coordinates come from, for provenQuadRho: the places of their
// u and v planes in RasterDraw::inputs, whether they are interpolated flat, and the
// texture's level-0 size. uInput < 0: the lookups classify their quads themselves.
struct LodSource {
  int uInput = -1, vInput = -1;
  bool uFlat = false, vFlat = false;
  float width = 0, height = 0;
  int sameAs = -1;  // an earlier source with the same coordinates and size
};

struct TileWorker {
  exec::ProgramRunner runProgram;  // RasterDraw::pixelProgram on regs, where it is native code
  exec::BatchRegisters regs;
  std::vector<InputTarget> inputTargets;  // RasterDraw::inputs' destinations, in order
  InterpolateInputsFn interpolateInputs = nullptr;
  CoverBlocksFn coverBlocks = nullptr;
  CoveredBlock blocks[kMaxTileBlocks];  // one primitive's in the current tile
  LazyFill lazyFill;       // the draw's
  PendingBlocks pending;   // the current tile's
  alignas(64) float z[N];
  alignas(64) float invW[N];
  alignas(64) float w[N];  // 1 / invW
  alignas(64) float passU[N], passV[N];  // RasterDraw::passthroughSampler's coordinates
  InputTarget passTargets[2];
  // Blocks shaded in groups (shadeGroup): the draw has a texture prologue or a
  // pass-through sampler.
  bool grouped = false;
  std::array<GroupSlot, kMaxSampleGroup> group;
  // The draw's group lookups (the pass-through's, or RasterDraw::prologue's in order)
  // and, for the current primitive in the tile, what is proven of each one's ρ².
  const std::vector<LodSource>* lodSources = nullptr;
  std::vector<ProvenRho> provenRho;
};

// Eight lanes as one value (v8f, merge_kernels.h): interpolation is vectorised
// whatever the compiler's loop heuristics decide, with the same IEEE operations.
inline v8f load8(const float* p) {
  v8f v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline void store8(float* p, v8f v) { std::memcpy(p, &v, sizeof v); }
// x in every lane (a broadcast: -0 stays -0, unlike 0 + x).
inline v8f bcast(float x) { return v8f{x, x, x, x, x, x, x, x}; }

// Whether every lane of a comparison's result is true.
inline bool allLanes(v8i m) {
#if defined(__AVX__)
  __m256 f;
  std::memcpy(&f, &m, sizeof f);
  return _mm256_movemask_ps(f) == 0xff;
#else
  for (int l = 0; l < 8; ++l)
    if (!m[l]) return false;
  return true;
#endif
}

// The lanes' pixel offsets from a primitive's origin, (ox, oy) being the block's.
inline void laneOffsets(float ox, float oy, v8f (&fx)[2], v8f (&fy)[2]) {
  for (int h = 0; h < 2; ++h) {
    fx[h] = bcast(ox) + load8(kLaneXf + 8 * h);
    fy[h] = bcast(oy) + load8(kLaneYf + 8 * h);
  }
}

// value[l] = (base + dx*fx[l] + dy*fy[l]) * scale[l]; no scale: the same without the
// multiply by one.
inline void evalPlane(const float* pl, const v8f (&fx)[2], const v8f (&fy)[2],
                      const v8f* scale, float* out) {
  const v8f a = bcast(pl[0]), dx = bcast(pl[1]), dy = bcast(pl[2]);
  for (int h = 0; h < 2; ++h) {
    v8f r = a + dx * fx[h] + dy * fy[h];
    if (scale) r = r * scale[h];
    store8(out + 8 * h, r);
  }
}

void interpolateInputsAvx2(const float* planes, const InputTarget* targets, size_t count, float ox,
                           float oy, const float* invW, float* w) {
  v8f fx[2], fy[2], wv[2];
  laneOffsets(ox, oy, fx, fy);
  bool unitW = true;
  for (int h = 0; h < 2; ++h) {
    const v8f iw = load8(invW + 8 * h);
    unitW = unitW && allLanes(iw == bcast(1.0f));
    wv[h] = iw;
  }
  for (int h = 0; h < 2; ++h) {
    wv[h] = unitW ? bcast(1.0f) : bcast(1.0f) / wv[h];
    store8(w + 8 * h, wv[h]);
  }
  for (size_t i = 0; i < count; ++i, planes += 3) {
    if (targets[i].sameAs != -1) {
      if (targets[i].sameAs < 0) continue;  // kUnreadInput
      const float* from = targets[targets[i].sameAs].lanes;
      for (int h = 0; h < 2; ++h) store8(targets[i].lanes + 8 * h, load8(from + 8 * h));
      continue;
    }
    evalPlane(planes, fx, fy, targets[i].flat || unitW ? nullptr : wv, targets[i].lanes);
  }
}

// What shadeBatch is compiled for: kAnyState reads the draw's state at run time (every
// draw); the others are for draws that read neither vPos nor vFace, take no depth from
// the shader and test the depth early (depth function F, written when Write) or not at
// all (kNoDepth), their merge the opaque store into target 0 (Opaque) or d.merge.
constexpr uint32_t kAnyState = 0xffffffffu, kNoDepth = 0;

// A batch's start: its depth (into z) and the early depth test, with the deferred
// Clear's depth where the block still has it. Returns the lanes to shade; 0: the block
// is finished (its fill written). fillLeft: the FillParts of the block the Clear has
// yet to write (lazyFill: the batch tests against and writes over the fill's values).
template <uint32_t F, bool Write>
[[gnu::always_inline]] inline uint16_t enterBatch(const RasterDraw& d, const Primitive& p, int bx, int by,
                                                  uint16_t mask, TileWorker& w, float* z, float* invW,
                                                  uint32_t& fillLeft) {
  constexpr bool any = F == kAnyState;
  const float* pl = d.planes.data() + p.planeOffset;
  const float ox = float(bx) - p.originX, oy = float(by) - p.originY;
  fillLeft = w.lazyFill.parts && w.pending.take(bx, by) ? w.lazyFill.parts : 0;
  v8f fx[2], fy[2];
  laneOffsets(ox, oy, fx, fy);
  evalPlane(pl, fx, fy, nullptr, invW);
  const v8f zero{}, one = zero + 1.0f;
  if (any ? d.depthTest || d.usesPosition : F != kNoDepth) {  // z is read by the depth test and vPos only
    if (d.wBuffer) {  // w / w_far plus the primitive's depth bias
      for (int h = 0; h < 2; ++h)
        store8(z + 8 * h, bcast(d.invFarW) / load8(invW + 8 * h) + bcast(p.wDepthOffset));
    } else {
      evalPlane(pl + 3, fx, fy, nullptr, z);
    }
    for (int h = 0; h < 2; ++h) {
      // std::min(std::max(z, 0), 1): NaN stays NaN.
      v8f v = load8(z + 8 * h);
      v = v < zero ? zero : v;
      store8(z + 8 * h, one < v ? one : v);
    }
  }
  if (any ? d.earlyDepth : F != kNoDepth) {
    if (fillLeft & kFillDepth) {  // the block's depth is the fill's z in every lane
      if constexpr (any)
        mask = depthTestOverFill(d, bx, by, mask, z);
      else
        mask = depthRowsOver(d, bx, by, mask, z, d.fill.z, [](v8f a, v8f b) { return compareDepths<F>(a, b); });
      fillLeft &= ~kFillDepth;
    } else if (!any && bx + 4 <= d.width && by + 4 <= d.height) {
      mask = depthRows(d, bx, by, mask, z, Write, [](v8f a, v8f b) { return compareDepths<F>(a, b); });
    } else {
      mask = (d.earlyDepthTestFn ? d.earlyDepthTestFn : earlyDepthTest)(d, bx, by, mask, z, d.depthWrite);
    }
    if (!mask && fillLeft) fillBlock(d, bx, by, fillLeft);
  }
  return mask;
}

// A batch's end: its lanes counted and its color written, with the fill where the
// block still has it. packed: the D3DCOLORs of a pass-through; null: the program's
// outputs in `regs`.
template <bool Opaque>
[[gnu::always_inline]] inline void leaveBatch(const RasterDraw& d, const Primitive& p, int bx, int by, uint16_t mask,
                                              const exec::BatchRegisters& regs, const float* z, uint32_t fillLeft,
                                              const uint32_t* packed, uint64_t& shaded) {
  const float (*color)[N] = regs.outputs[0].c;
  shaded += static_cast<uint64_t>(__builtin_popcount(mask));
  if (fillLeft) {  // target 0's fill (the depth's is written by now)
    if (!mask) {
      fillBlock(d, bx, by, fillLeft);
      return;
    }
    const ColorTarget& t = d.targets[0];
    if (packed)
      storePackedOver(t, bx, by, mask, packed, d.fill.colorValue);
    else if (d.opaqueBlockStore)  // the fill's blocks are whole ones inside the target
      d.opaqueBlockStore(t.data + size_t(by) * size_t(t.pitch) + size_t(bx) * 4, t.pitch, t.hasAlpha, mask, color,
                         &d.fill.colorValue);
    else
      storeOpaqueOver(t, bx, by, mask, color, d.fill.colorValue);
    return;
  }
  if (!mask) return;
  if (packed) {
    storePacked(d.targets[0], d.width, d.height, bx, by, mask, packed);
  } else if constexpr (Opaque) {
    const ColorTarget& t = d.targets[0];
    if (d.opaqueBlockStore && bx + 4 <= d.width && by + 4 <= d.height)
      d.opaqueBlockStore(t.data + size_t(by) * size_t(t.pitch) + size_t(bx) * 4, t.pitch, t.hasAlpha, mask, color,
                         nullptr);
    else
      storeOpaque(t, d.width, d.height, bx, by, mask, color);
  } else
    (d.merge ? d.merge : mergeBatch)(d, bx, by, mask, regs.outputs.data(), z, d.earlyDepth, p.counterClockwise);
}

template <uint32_t F, bool Write, bool Opaque>
void shadeBatch(const RasterDraw& d, const Primitive& p, int bx, int by, uint16_t mask,
                TileWorker& w, uint64_t& shaded) {
  constexpr bool any = F == kAnyState;
  const float* pl = d.planes.data() + p.planeOffset;
  const float ox = float(bx) - p.originX, oy = float(by) - p.originY;
  uint32_t fillLeft;
  mask = enterBatch<F, Write>(d, p, bx, by, mask, w, w.z, w.invW, fillLeft);
  if (!mask) return;
  // The program's output 0 as floats, or (passthrough) as the D3DCOLORs to store.
  alignas(64) uint32_t packed[N];
  bool isPacked = false;
  if (Opaque && d.passthroughSampler) {
    // The program only samples a 2D texture: its (u, v) interpolated as for the
    // program, the sample's bytes as the opaque store converts them.
    w.interpolateInputs(pl + 6 + 3 * d.passthroughInput, w.passTargets, 2, ox, oy, w.invW, w.w);
    isPacked = d.passthroughSampler->sampleImplicitArgb8(w.passU, w.passV, mask, packed);
    if (!isPacked) d.passthroughSampler->sampleImplicit(w.passU, w.passV, nullptr, mask, w.regs.outputs[0].c);
    else if (!d.targets[0].hasAlpha)
      for (uint32_t& v : packed) v |= 0xff000000u;
  } else {
    w.interpolateInputs(pl + 6, w.inputTargets.data(), w.inputTargets.size(), ox, oy, w.invW, w.w);
    if (any && d.usesPosition) {
      auto& pos = w.regs.inputs[kPixelInPosition];
      // The position's z is the interpolated z, also when the depth buffer holds w.
      if (d.wBuffer) {
        v8f fx[2], fy[2];
        laneOffsets(ox, oy, fx, fy);
        evalPlane(pl + 3, fx, fy, nullptr, pos.c[2]);
      }
      for (int l = 0; l < N; ++l) {
        pos.c[0][l] = float(bx + kLaneX[l]);
        pos.c[1][l] = float(by + kLaneY[l]);
        if (!d.wBuffer) pos.c[2][l] = w.z[l];
        pos.c[3][l] = w.w[l];
      }
    }
    if (any && d.usesFace) {
      // vFace: > 0 for clockwise (front-facing) triangles, < 0 for counter-clockwise.
      const float face = p.kind == PrimKind::Triangle && p.counterClockwise ? -1.0f : 1.0f;
      auto& f = w.regs.inputs[exec::kPixelInFace];
      for (int c = 0; c < 4; ++c) std::fill_n(f.c[c], N, face);
    }
    w.regs.laneMask = mask;
    if (w.runProgram) w.runProgram();
    else exec::execute(*d.pixelProgram, d.execContext, w.regs);
    mask &= w.regs.laneMask;
    if (any && d.shaderDepth) {
      // The shader's depth replaces the interpolated one, clamped to [0,1].
      const float* z = w.regs.outputs[exec::kPixelOutDepth].c[0];
      for (int l = 0; l < N; ++l) w.z[l] = std::clamp(z[l], 0.0f, 1.0f);
    }
  }
  leaveBatch<Opaque>(d, p, bx, by, mask, w.regs, w.z, fillLeft, isPacked ? packed : nullptr, shaded);
}

// shadeBatch for up to kMaxSampleGroup blocks of one primitive whose texture lookups
// are made for all of them at once (RasterDraw::prologue, or the pass-through's): the
// blocks' depth tests and interpolation, then the lookups, group by group, then the
// rest of the program and the store block by block. The same results as shadeBatch
// for each block: the lookups read only interpolated inputs.
template <uint32_t F, bool Write, bool Opaque>
void shadeGroup(const RasterDraw& d, const Primitive& p, const CoveredBlock* blocks, int count, TileWorker& w,
                uint64_t& shaded) {
  static_assert(F != kAnyState, "groups are for draws whose tile loop is compiled for their state");
  const bool passthrough = Opaque && d.passthroughSampler;
  if (!passthrough && d.prologue.empty()) {
    for (int i = 0; i < count; ++i)
      shadeBatch<F, Write, Opaque>(d, p, blocks[i].bx, blocks[i].by, uint16_t(blocks[i].mask), w, shaded);
    return;
  }
  struct Item {
    int bx, by;
    uint16_t mask;
    uint32_t fillLeft;
  } items[kMaxSampleGroup];
  int n = 0;
  for (int i = 0; i < count; ++i) {
    const int bx = blocks[i].bx, by = blocks[i].by;
    GroupSlot& slot = w.group[size_t(n)];
    uint32_t fillLeft;
    const uint16_t mask =
        enterBatch<F, Write>(d, p, bx, by, uint16_t(blocks[i].mask), w, slot.z, slot.invW, fillLeft);
    if (!mask) continue;
    items[n++] = {bx, by, mask, fillLeft};
  }
  if (!n) return;
  // The blocks' interpolation after all their depth tests, side by side.
  const float* pl = d.planes.data() + p.planeOffset;
  for (int g = 0; g < n; ++g) {
    GroupSlot& slot = w.group[size_t(g)];
    const float ox = float(items[g].bx) - p.originX, oy = float(items[g].by) - p.originY;
    if (passthrough)
      w.interpolateInputs(pl + 6 + 3 * d.passthroughInput, slot.passTargets, 2, ox, oy, slot.invW, w.w);
    else
      w.interpolateInputs(pl + 6, slot.inputTargets.data(), slot.inputTargets.size(), ox, oy, slot.invW, w.w);
  }
  uint16_t lanes[kMaxSampleGroup];
  uint32_t packedDone = 0;
  if (passthrough) {
    const float* u[kMaxSampleGroup];
    const float* v[kMaxSampleGroup];
    uint32_t* out[kMaxSampleGroup];
    for (int g = 0; g < n; ++g) {
      GroupSlot& slot = w.group[size_t(g)];
      u[g] = slot.passU, v[g] = slot.passV, out[g] = slot.packed;
      lanes[g] = items[g].mask;
    }
    packedDone = d.passthroughSampler->sampleImplicitArgb8Group(n, u, v, lanes, out, w.provenRho[0]);
    for (int g = 0; g < n; ++g) {
      GroupSlot& slot = w.group[size_t(g)];
      if (!(packedDone >> g & 1))
        d.passthroughSampler->sampleImplicit(slot.passU, slot.passV, nullptr, lanes[g], slot.regs.outputs[0].c);
      else if (!d.targets[0].hasAlpha)
        for (uint32_t& c : slot.packed) c |= 0xff000000u;
    }
  } else {
    for (int g = 0; g < n; ++g) lanes[g] = exec::quadLanes(items[g].mask);
    const auto batchesOf = [&](const RasterDraw::PrologueLookup& l, SampleBatch* batches) {
      for (int g = 0; g < n; ++g) {
        exec::BatchRegisters& regs = w.group[size_t(g)].regs;
        auto& file = l.file == exec::RegFile::Output ? regs.outputs : regs.temps;
        batches[g] = {regs.inputs[size_t(l.coordinates)].c, file[size_t(l.index)].c, l.channels};
      }
    };
    for (size_t k = 0; k < d.prologue.size(); ++k) {
      const RasterDraw::PrologueLookup& a = d.prologue[k];
      SampleBatch batchesA[kMaxSampleGroup], batchesB[kMaxSampleGroup];
      batchesOf(a, batchesA);
      if (k + 1 < d.prologue.size() &&
          (d.prologue[k + 1].file != a.file || d.prologue[k + 1].index != a.index)) {
        batchesOf(d.prologue[k + 1], batchesB);
        PreparedSampler::sampleImplicitPairGroup(*a.sampler, *d.prologue[k + 1].sampler, n, lanes, batchesA,
                                                 batchesB, w.provenRho[k]);
        ++k;
      } else {
        a.sampler->sampleImplicitGroup(n, lanes, batchesA, w.provenRho[k]);
      }
    }
  }
  // The rest of the program for every block, then the stores: the blocks' programs side
  // by side overlap (each is a chain of dependent operations).
  if (!passthrough)
    for (int g = 0; g < n; ++g) {
      GroupSlot& slot = w.group[size_t(g)];
      slot.regs.laneMask = items[g].mask;
      if (slot.runRest) slot.runRest();
      else exec::execute(*d.pixelRest, d.execContext, slot.regs);
    }
  for (int g = 0; g < n; ++g) {
    GroupSlot& slot = w.group[size_t(g)];
    const uint16_t mask = passthrough ? items[g].mask : uint16_t(items[g].mask & slot.regs.laneMask);
    leaveBatch<Opaque>(d, p, items[g].bx, items[g].by, mask, slot.regs, slot.z, items[g].fillLeft,
                       packedDone >> g & 1 ? slot.packed : nullptr, shaded);
  }
}

// TileWorker::provenRho for primitive p's blocks with lanes in [x0, x1] x [y0, y1].
void proveRho(const RasterDraw& d, const Primitive& p, int x0, int y0, int x1, int y1, TileWorker& w) {
  const std::vector<LodSource>& sources = *w.lodSources;
  const float* pl = d.planes.data() + p.planeOffset;
  for (size_t k = 0; k < sources.size(); ++k) {
    const LodSource& s = sources[k];
    ProvenRho& rho = w.provenRho[k];
    if (s.sameAs >= 0) rho = w.provenRho[size_t(s.sameAs)];
    else if (s.uInput < 0) rho = {};
    else
      rho = provenQuadRho(pl, {pl + 6 + 3 * s.uInput, s.uFlat}, {pl + 6 + 3 * s.vInput, s.vFlat}, p.originX,
                          p.originY, x0, y0, x1, y1, s.width, s.height);
  }
}

// The draw's LodSources: the pass-through's lookup, or each of RasterDraw::prologue's.
std::vector<LodSource> lodSourcesOf(const RasterDraw& d) {
  const auto inputOf = [&](int input, int component) {
    for (size_t i = 0; i < d.inputs.size(); ++i)
      if (d.inputs[i].input == input && d.inputs[i].component == component) return int(i);
    return -1;
  };
  // flat: as the lanes are interpolated (the pass-through's never are, TileWorker::passTargets).
  const auto source = [&](const PreparedSampler& sampler, int u, int v, bool asFlat) {
    LodSource s;
    if (u < 0 || v < 0 || !sampler.levelZeroSize(s.width, s.height)) return s;
    s.uInput = u, s.vInput = v;
    s.uFlat = asFlat && d.inputs[size_t(u)].flat, s.vFlat = asFlat && d.inputs[size_t(v)].flat;
    return s;
  };
  std::vector<LodSource> sources;
  if (d.passthroughSampler) {
    const int u = d.passthroughInput;
    sources.push_back(
        source(*d.passthroughSampler, u, u >= 0 && size_t(u) + 1 < d.inputs.size() ? u + 1 : -1, false));
  } else {
    for (const RasterDraw::PrologueLookup& l : d.prologue)
      sources.push_back(source(*l.sampler, inputOf(l.input, 0), inputOf(l.input, 1), true));
  }
  for (size_t k = 0; k < sources.size(); ++k)
    for (size_t j = 0; j < k && sources[k].sameAs < 0; ++j)
      if (sources[j].sameAs < 0 && sources[j].uInput == sources[k].uInput && sources[j].vInput == sources[k].vInput &&
          sources[j].width == sources[k].width && sources[j].height == sources[k].height)
        sources[k].sameAs = int(j);
  return sources;
}

template <uint32_t F, bool Write, bool Opaque>
void shadeTile(const RasterDraw& d, const TileBins& bins, size_t tile, TileWorker& w,
               uint64_t& shaded) {
  const int tx = int(tile % bins.tilesX), ty = int(tile / bins.tilesX);
  const int x0 = tx * kTileSize, y0 = ty * kTileSize;
  const int x1 = std::min(x0 + kTileSize, d.width) - 1, y1 = std::min(y0 + kTileSize, d.height) - 1;
  uint64_t count = 0;  // local: the per-thread counters share cache lines
  beginTileFill(d, w.lazyFill, x0, y0, x1 + 1, y1 + 1, w.pending);
  for (uint32_t k = bins.start[tile]; k < bins.start[tile + 1]; ++k) {
    const Primitive& p = d.prims[bins.entries[k]];
    const int minX = std::max(p.minX, x0) & ~3, minY = std::max(p.minY, y0) & ~3;
    const int maxX = std::min(p.maxX, x1), maxY = std::min(p.maxY, y1);
    const int blocks = w.coverBlocks(p, minX, minY, maxX, maxY, w.blocks);
    if constexpr (F != kAnyState) {
      if (w.grouped) {
        if (blocks) proveRho(d, p, minX, minY, maxX | 3, maxY | 3, w);
        for (int i = 0; i < blocks; i += kMaxSampleGroup)
          shadeGroup<F, Write, Opaque>(d, p, w.blocks + i, std::min(kMaxSampleGroup, blocks - i), w, count);
        continue;
      }
    }
    for (int i = 0; i < blocks; ++i)
      shadeBatch<F, Write, Opaque>(d, p, w.blocks[i].bx, w.blocks[i].by, uint16_t(w.blocks[i].mask), w, count);
  }
  finishTileFill(d, w.lazyFill, w.pending);
  shaded += count;
}

using ShadeTileFn = void (*)(const RasterDraw& d, const TileBins& bins, size_t tile, TileWorker& w,
                             uint64_t& shaded);

template <bool Opaque>
ShadeTileFn chooseShadeTile(const RasterDraw& d) {
  using namespace d3d;
  if (!d.depthTest) return shadeTile<kNoDepth, false, Opaque>;
  const bool write = d.depthWrite;
  switch (d.depthFunc) {
    case CMP_LESS: return write ? shadeTile<CMP_LESS, true, Opaque> : shadeTile<CMP_LESS, false, Opaque>;
    case CMP_LESSEQUAL:
      return write ? shadeTile<CMP_LESSEQUAL, true, Opaque> : shadeTile<CMP_LESSEQUAL, false, Opaque>;
    case CMP_GREATER: return write ? shadeTile<CMP_GREATER, true, Opaque> : shadeTile<CMP_GREATER, false, Opaque>;
    case CMP_GREATEREQUAL:
      return write ? shadeTile<CMP_GREATEREQUAL, true, Opaque> : shadeTile<CMP_GREATEREQUAL, false, Opaque>;
    case CMP_EQUAL: return write ? shadeTile<CMP_EQUAL, true, Opaque> : shadeTile<CMP_EQUAL, false, Opaque>;
    default: return shadeTile<kAnyState, false, false>;
  }
}

// The tile loop compiled for the draw's state where it is a common one, else the one
// that reads the state at run time.
ShadeTileFn chooseShadeTile(const RasterDraw& d) {
  if (d.usesPosition || d.usesFace || d.shaderDepth || (d.depthTest && !d.earlyDepth))
    return shadeTile<kAnyState, false, false>;
  // The merge is the opaque store into target 0 (mergeBatch's first case, and what
  // chooseMerge picks for this state).
  const ColorTarget& t = d.targets[0];
  bool opaque = t.data && !t.isFloat && t.writeMask == 0xf && !d.blend.enable && !d.alphaTest && !d.stencil &&
                !d.srgbWrite && !d.dither;
  for (size_t i = 1; i < d.targets.size(); ++i) opaque &= !d.targets[i].data;
  return opaque ? chooseShadeTile<true>(d) : chooseShadeTile<false>(d);
}

}  // namespace

InterpolateInputsFn chooseInterpolateInputs() {
  return activeIsa() == CpuIsa::Avx512 ? interpolateInputsAvx512 : interpolateInputsAvx2;
}

void fillColorRow(uint8_t* row, int x0, int x1, uint32_t argb, bool isFloat) {
  if (!isFloat) {
    std::fill_n(reinterpret_cast<uint32_t*>(row) + x0, x1 - x0, argb);
    return;
  }
  const float rgba[4] = {float((argb >> 16) & 0xff) / 255.0f, float((argb >> 8) & 0xff) / 255.0f,
                         float(argb & 0xff) / 255.0f, float(argb >> 24) / 255.0f};
  float* px = reinterpret_cast<float*>(row) + size_t(x0) * 4;
  for (int x = x0; x < x1; ++x, px += 4) std::copy(rgba, rgba + 4, px);
}

void applyFill(const RasterDraw::Fill& fill, DepthStencilSurface* depth, int x0, int y0, int x1,
               int y1) {
  x0 = std::max(x0, fill.rect.left), y0 = std::max(y0, fill.rect.top);
  x1 = std::min(x1, fill.rect.right), y1 = std::min(y1, fill.rect.bottom);
  if (x0 >= x1 || y0 >= y1) return;
  for (int y = y0; y < y1; ++y) {
    if (fill.color)
      for (const ColorTarget& t : fill.colorTargets)
        if (t.data) fillColorRow(t.data + size_t(y) * t.pitch, x0, x1, fill.colorValue, t.isFloat);
    if (!depth) continue;  // a target without a depth-stencil surface
    const size_t row = size_t(y) * depth->width;  // depth: same size as the target
    if (fill.depth) std::fill_n(depth->depth.data() + row + x0, x1 - x0, fill.z);
    if (fill.stencil) std::fill_n(depth->stencil.data() + row + x0, x1 - x0, fill.stencilValue);
  }
}

namespace {

// The interpolation targets' sameAs from the draw's input copies.
void setCopies(const RasterDraw& draw, std::vector<InputTarget>& targets) {
  for (size_t i = 0; i < targets.size(); ++i)
    targets[i].sameAs = i < draw.inputCopies.size() ? draw.inputCopies[i] : -1;
}

// RasterDraw::PrologueLookup::coordinates: a lookup whose input register is interpolated
// as a copy of an earlier lookup's in every component (or, in a component, neither is
// interpolated: zero in both) reads that lookup's coordinates.
void shareCoordinates(RasterDraw& draw) {
  const auto rootOf = [&](int input, int component) {
    for (size_t i = 0; i < draw.inputs.size(); ++i)
      if (draw.inputs[i].input == input && draw.inputs[i].component == component)
        return i < draw.inputCopies.size() && draw.inputCopies[i] >= 0 ? draw.inputCopies[i] : int(i);
    return -1;
  };
  for (size_t k = 0; k < draw.prologue.size(); ++k) {
    RasterDraw::PrologueLookup& l = draw.prologue[k];
    l.coordinates = l.input;
    for (size_t j = 0; j < k; ++j) {
      bool same = true;
      for (int c = 0; c < 4 && same; ++c) same = rootOf(l.input, c) == rootOf(draw.prologue[j].input, c);
      if (same) {
        l.coordinates = draw.prologue[j].coordinates;
        break;
      }
    }
  }
}

// Marks kUnreadInput the group slots' targets of input registers that neither the rest
// of the program nor a lookup's coordinates read (RasterDraw::prologue: a lookup that
// reads another register's copy of its coordinates leaves its own unread), unless a read
// target copies from them.
void skipUnreadInputs(const RasterDraw& draw, std::vector<InputTarget>& targets) {
  if (!draw.pixelRest || draw.passthroughSampler) return;
  std::vector<bool> read(kPixelInputCount, false);
  for (const RasterDraw::PrologueLookup& l : draw.prologue) read[size_t(l.coordinates)] = true;
  for (const exec::Instr& in : draw.pixelRest->code)
    for (int s = 0; s < exec::sourceCount(in.op); ++s) {
      const exec::Src& src = in.src[size_t(s)];
      if (src.file != exec::RegFile::Input) continue;
      if (src.rel != exec::RelMode::None || src.index >= kPixelInputCount) return;  // any of them
      read[src.index] = true;
    }
  std::vector<bool> used(targets.size());
  for (size_t i = 0; i < targets.size(); ++i) used[i] = read[size_t(draw.inputs[i].input)];
  for (size_t i = 0; i < targets.size(); ++i)
    if (used[i] && targets[i].sameAs >= 0) used[size_t(targets[i].sameAs)] = true;
  for (size_t i = 0; i < targets.size(); ++i)
    if (!used[i]) targets[i].sameAs = kUnreadInput;
}

// The registers of a worker's group slots, as the worker's own for the whole program
// (rasterize), prepared for the program without its lookups.
void prepareGroup(const RasterDraw& draw, TileWorker& w, exec::ProgramBuildInfo* build) {
  for (GroupSlot& slot : w.group) {
    const exec::Program& program = draw.pixelRest ? *draw.pixelRest : *draw.pixelProgram;
    slot.regs.resize(program);
    if (int(slot.regs.inputs.size()) < kPixelInputCount) slot.regs.inputs.resize(kPixelInputCount);
    for (auto& in : slot.regs.inputs) std::memset(&in, 0, sizeof(in));
    if (draw.pixelRest) {
      const exec::ProgramBuildInfo info = exec::prepare(program, draw.execContext, slot.regs, draw.prepareOptions);
      if (build && &slot == &w.group[0]) *build = info;
      slot.runRest = exec::runnerFor(program, draw.execContext, slot.regs);
    }
    slot.inputTargets.clear();
    for (const InterpolatedInput& in : draw.inputs)
      slot.inputTargets.push_back({slot.regs.inputs[in.input].c[in.component], in.flat});
    setCopies(draw, slot.inputTargets);
    skipUnreadInputs(draw, slot.inputTargets);
    slot.passTargets[0] = {slot.passU, false};
    slot.passTargets[1] = {slot.passV, false};
  }
}

}  // namespace

void rasterize(RasterDraw& draw, ThreadPool& pool) {
  const bool fill = draw.fill.color || draw.fill.depth || draw.fill.stencil;
  if (draw.prims.empty() && !fill) return;
  TileBins bins;
  bin(draw, bins, pool);
  std::vector<size_t> busy;
  for (size_t t = 0; t < bins.tiles(); ++t)
    if (fill || bins.start[t + 1] > bins.start[t]) busy.push_back(t);
  const int threads = pool.threadCount();
  std::vector<TileWorker> workers(threads);
  for (auto& w : workers) {
    w.regs.resize(*draw.pixelProgram);
    if (int(w.regs.inputs.size()) < kPixelInputCount) w.regs.inputs.resize(kPixelInputCount);
    if (draw.usesFace && int(w.regs.inputs.size()) <= exec::kPixelInFace)
      w.regs.inputs.resize(exec::kPixelInFace + 1);
    if (draw.shaderDepth && int(w.regs.outputs.size()) <= exec::kPixelOutDepth)
      w.regs.outputs.resize(exec::kPixelOutDepth + 1);
    for (auto& in : w.regs.inputs) std::memset(&in, 0, sizeof(in));
    const exec::ProgramBuildInfo info =
        exec::prepare(*draw.pixelProgram, draw.execContext, w.regs, draw.prepareOptions);
    if (draw.pixelBuild && &w == &workers[0]) *draw.pixelBuild = info;
    w.runProgram = exec::runnerFor(*draw.pixelProgram, draw.execContext, w.regs);
    w.interpolateInputs = chooseInterpolateInputs();
    w.coverBlocks = chooseCoverBlocks();
    w.lazyFill = lazyFillFor(draw);
    w.passTargets[0] = {w.passU, false};
    w.passTargets[1] = {w.passV, false};
    for (const InterpolatedInput& in : draw.inputs)
      w.inputTargets.push_back({w.regs.inputs[in.input].c[in.component], in.flat});
    setCopies(draw, w.inputTargets);
  }
  std::vector<uint64_t> shaded(threads, 0);
  draw.opaqueBlockStore = activeIsa() == CpuIsa::Avx512 ? storeOpaqueBlockAvx512 : nullptr;
  const ShadeTileFn tileLoop = chooseShadeTile(draw);
  // Groups are for the tile loops compiled for a state (shadeGroup).
  draw.groupedLookups =
      (draw.pixelRest || draw.passthroughSampler) && tileLoop != shadeTile<kAnyState, false, false>;
  const std::vector<LodSource> lodSources = draw.groupedLookups ? lodSourcesOf(draw) : std::vector<LodSource>{};
  shareCoordinates(draw);
  for (auto& w : workers) {
    w.lodSources = &lodSources;
    w.provenRho.assign(lodSources.size(), ProvenRho{});
    w.grouped = draw.groupedLookups;
    if (w.grouped) prepareGroup(draw, w, &w == &workers[0] ? draw.pixelRestBuild : nullptr);
  }
  pool.parallelFor(busy.size(), [&](size_t i, int thread) {
    tileLoop(draw, bins, busy[i], workers[thread], shaded[thread]);
  });
  if (draw.pixelsShaded)
    for (uint64_t s : shaded) *draw.pixelsShaded += s;
}

}  // namespace refx::pipeline
