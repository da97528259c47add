#include "output_merger.h"

#include "merge_kernels.h"

#include <algorithm>
#include <cmath>
#if defined(__SSE__) || defined(__AVX__)
#include <immintrin.h>
#endif

namespace refx::pipeline {

using namespace d3d;

// D3DCMPFUNC on depth (float) or alpha/stencil (8-bit integer) values.
template <typename T>
static bool compareValues(uint32_t func, T a, T b) {
  switch (func) {
    case CMP_NEVER: return false;
    case CMP_LESS: return a < b;
    case CMP_EQUAL: return a == b;
    case CMP_LESSEQUAL: return a <= b;
    case CMP_GREATER: return a > b;
    case CMP_NOTEQUAL: return a != b;
    case CMP_GREATEREQUAL: return a >= b;
    default: return true;
  }
}

bool compare(uint32_t func, float a, float b) { return compareValues(func, a, b); }
static bool compareU(uint32_t func, uint32_t a, uint32_t b) { return compareValues(func, a, b); }

uint16_t earlyDepthTest(const RasterDraw& d, int bx, int by, uint16_t mask, const float* z,
                        bool writeDepth) {
  if (bx + 4 <= d.width && by + 4 <= d.height) {
    switch (d.depthFunc) {
      case CMP_NEVER: return 0;
      case CMP_LESS: return depthRows(d, bx, by, mask, z, writeDepth, [](v8f a, v8f b) { return a < b; });
      case CMP_EQUAL: return depthRows(d, bx, by, mask, z, writeDepth, [](v8f a, v8f b) { return a == b; });
      case CMP_LESSEQUAL: return depthRows(d, bx, by, mask, z, writeDepth, [](v8f a, v8f b) { return a <= b; });
      case CMP_GREATER: return depthRows(d, bx, by, mask, z, writeDepth, [](v8f a, v8f b) { return a > b; });
      case CMP_NOTEQUAL: return depthRows(d, bx, by, mask, z, writeDepth, [](v8f a, v8f b) { return a != b; });
      case CMP_GREATEREQUAL: return depthRows(d, bx, by, mask, z, writeDepth, [](v8f a, v8f b) { return a >= b; });
      default: return depthRows(d, bx, by, mask, z, writeDepth, [](v8f a, v8f) { return (a == a) | (a != a); });
    }
  }
  uint16_t pass = 0;
  for (int l = 0; l < kBatchLanes; ++l) {
    if (!(mask & (1 << l))) continue;
    size_t i = size_t(by + kLaneY[l]) * d.width + (bx + kLaneX[l]);
    if (compare(d.depthFunc, z[l], d.depth->depth[i])) {
      pass |= uint16_t(1u << l);
      if (writeDepth) d.depth->depth[i] = z[l];
    }
  }
  return pass;
}

static uint8_t stencilOp(uint32_t op, uint8_t s, uint8_t ref, uint8_t writeMask) {
  uint8_t r = s;
  switch (op) {
    case STENCILOP_ZERO: r = 0; break;
    case STENCILOP_REPLACE: r = ref; break;
    case STENCILOP_INCRSAT: r = s == 255 ? 255 : uint8_t(s + 1); break;
    case STENCILOP_DECRSAT: r = s == 0 ? 0 : uint8_t(s - 1); break;
    case STENCILOP_INVERT: r = uint8_t(~s); break;
    case STENCILOP_INCR: r = uint8_t(s + 1); break;
    case STENCILOP_DECR: r = uint8_t(s - 1); break;
    default: break;  // KEEP
  }
  return uint8_t((s & ~writeMask) | (r & writeMask));
}

// Blend factor for one channel c (0..3) of (r,g,b,a).
static float blendFactor(uint32_t f, int c, const float* src, const float* dst, Color4 k) {
  const float kc[4] = {k.r, k.g, k.b, k.a};
  switch (f) {
    case BLEND_ZERO: return 0;
    case BLEND_ONE: return 1;
    case BLEND_SRCCOLOR: return src[c];
    case BLEND_INVSRCCOLOR: return 1 - src[c];
    case BLEND_SRCALPHA: return src[3];
    case BLEND_INVSRCALPHA: return 1 - src[3];
    case BLEND_DESTALPHA: return dst[3];
    case BLEND_INVDESTALPHA: return 1 - dst[3];
    case BLEND_DESTCOLOR: return dst[c];
    case BLEND_INVDESTCOLOR: return 1 - dst[c];
    case BLEND_SRCALPHASAT: return c == 3 ? 1.0f : std::min(src[3], 1 - dst[3]);
    case BLEND_BLENDFACTOR: return kc[c];
    case BLEND_INVBLENDFACTOR: return 1 - kc[c];
    default: return 1;
  }
}

static float blendOp(uint32_t op, float s, float fs, float dst, float fd) {
  switch (op) {
    case BLENDOP_SUBTRACT: return s * fs - dst * fd;
    case BLENDOP_REVSUBTRACT: return dst * fd - s * fs;
    case BLENDOP_MIN: return std::min(s, dst);
    case BLENDOP_MAX: return std::max(s, dst);
    default: return s * fs + dst * fd;
  }
}

static inline uint8_t toUnorm8(float v) {
  // NaN and negative go to 0; round to nearest.
  if (!(v > 0.0f)) return 0;
  if (v >= 1.0f) return 255;
  return static_cast<uint8_t>(v * 255.0f + 0.5f);
}

// sRGB encoding of a linear value in [0,1] (IEC 61966-2-1).
static float linearToSrgb(float c) {
  c = std::clamp(c, 0.0f, 1.0f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

// src = blend(src, dst) with the draw's factors and operations; an 8-bit target
// clamps the shader's colour to [0, 1] first, a float target blends it as it is.
static void blendInto(const RasterDraw& d, float* src, const float* dst, bool clampSource) {
  if (clampSource)
    for (int c = 0; c < 4; ++c) src[c] = std::clamp(src[c], 0.0f, 1.0f);
  float out[4];
  uint32_t sf = d.blend.src, df = d.blend.dst;
  if (sf == BLEND_BOTHSRCALPHA) { sf = BLEND_SRCALPHA; df = BLEND_INVSRCALPHA; }
  if (sf == BLEND_BOTHINVSRCALPHA) { sf = BLEND_INVSRCALPHA; df = BLEND_SRCALPHA; }
  for (int c = 0; c < 3; ++c)
    out[c] = blendOp(d.blend.op, src[c], blendFactor(sf, c, src, dst, d.blend.factor), dst[c],
                     blendFactor(df, c, src, dst, d.blend.factor));
  uint32_t sa = d.blend.srcA, da = d.blend.dstA;
  if (sa == BLEND_BOTHSRCALPHA) { sa = BLEND_SRCALPHA; da = BLEND_INVSRCALPHA; }
  if (sa == BLEND_BOTHINVSRCALPHA) { sa = BLEND_INVSRCALPHA; da = BLEND_SRCALPHA; }
  out[3] = blendOp(d.blend.opA, src[3], blendFactor(sa, 3, src, dst, d.blend.factor), dst[3],
                   blendFactor(da, 3, src, dst, d.blend.factor));
  std::copy(out, out + 4, src);
}

// Writes one pixel of target t: blend with what it holds, sRGB encoding and
// quantisation for 8-bit targets, then the channels its write mask enables.
static void writePixel(const RasterDraw& d, const ColorTarget& t, int x, int y, float* src) {
  const uint32_t wm = t.writeMask;
  if (t.isFloat) {  // r, g, b, a floats: no clamp, no quantisation
    float* pf = reinterpret_cast<float*>(t.data + size_t(y) * t.pitch) + size_t(x) * 4;
    if (d.blend.enable) blendInto(d, src, pf, false);
    for (int c = 0; c < 4; ++c)
      if (wm & (1u << c)) pf[c] = src[c];
    return;
  }
  uint8_t* px = t.data + size_t(y) * t.pitch + size_t(x) * 4;  // B G R A
  if (d.blend.enable) {
    const float dst[4] = {px[2] / 255.0f, px[1] / 255.0f, px[0] / 255.0f, t.hasAlpha ? px[3] / 255.0f : 1.0f};
    blendInto(d, src, dst, true);
  }
  if (d.srgbWrite)  // the blended linear value is encoded on write; alpha stays linear
    for (int c = 0; c < 3; ++c) src[c] = linearToSrgb(src[c]);
  // Dithering spreads the colour's quantisation error; alpha rounds to nearest.
  if (wm & CW_RED) px[2] = quantizeUnorm8(src[0], d.dither, x, y);
  if (wm & CW_GREEN) px[1] = quantizeUnorm8(src[1], d.dither, x, y);
  if (wm & CW_BLUE) px[0] = quantizeUnorm8(src[2], d.dither, x, y);
  if (wm & CW_ALPHA) px[3] = t.hasAlpha ? toUnorm8(src[3]) : 255;
}

uint8_t quantizeUnorm8(float v, bool dither, int x, int y) {
  if (!dither) return toUnorm8(v);
  // 4x4 Bayer matrix: each of 0..15 once, neighbours as far apart as possible.
  static constexpr uint8_t kBayer[4][4] = {{0, 8, 2, 10}, {12, 4, 14, 6}, {3, 11, 1, 9}, {15, 7, 13, 5}};
  if (!(v > 0.0f)) return 0;
  if (v >= 1.0f) return 255;
  const float t = (float(kBayer[y & 3][x & 3]) + 0.5f) / 16.0f;
  return static_cast<uint8_t>(std::min(v * 255.0f + t, 255.0f));
}

// Whether target t takes the batch as it is: an 8-bit target, all channels written,
// nothing between the shader and the store.
static bool opaqueStore(const RasterDraw& d, const ColorTarget& t) {
  return !t.data || (!t.isFloat && t.writeMask == 0xf && !d.blend.enable && !d.srgbWrite && !d.dither);
}

void mergeBatch(const RasterDraw& d, int bx, int by, uint16_t mask, const exec::LaneVec4* colors,
                const float* z, bool depthAlreadyTested, bool counterClockwise) {
  if (!d.alphaTest && !d.stencil && (!d.depthTest || depthAlreadyTested) &&
      std::all_of(d.targets.begin(), d.targets.end(), [&](const ColorTarget& t) { return opaqueStore(d, t); })) {
    for (size_t i = 0; i < d.targets.size(); ++i)
      if (d.targets[i].data) storeOpaque(d.targets[i], d.width, d.height, bx, by, mask, colors[i].c);
    return;
  }
  for (int l = 0; l < kBatchLanes; ++l) {
    if (!(mask & (1 << l))) continue;
    const int x = bx + kLaneX[l], y = by + kLaneY[l];
    // Alpha test compares oC0's alpha in 8-bit as hardware does (ALPHAREF is 0..255); a
    // failing pixel is discarded from every target.
    if (d.alphaTest) {
      int a8 = toUnorm8(colors[0].c[3][l]);
      if (!compareU(d.alphaFunc, uint32_t(a8), d.alphaRef)) continue;
    }
    const size_t pi = size_t(y) * d.width + x;
    if (d.stencil && d.depth) {
      uint8_t& s = d.depth->stencil[pi];
      const uint8_t ref = d.stencilRef, rmask = d.stencilMask;
      const uint8_t wmask = d.stencilWriteMask;
      // Two-sided stencil: counter-clockwise primitives use the CCW_ states.
      const std::array<uint32_t, 4>& ops = d.stencilOps[counterClockwise ? 1 : 0];
      if (!compareU(ops[0], ref & rmask, s & rmask)) {
        s = stencilOp(ops[1], s, ref, wmask);
        continue;
      }
      bool zpass = true;
      if (d.depthTest && !depthAlreadyTested) zpass = compare(d.depthFunc, z[l], d.depth->depth[pi]);
      if (!zpass) {
        s = stencilOp(ops[2], s, ref, wmask);
        continue;
      }
      s = stencilOp(ops[3], s, ref, wmask);
      if (d.depthTest && d.depthWrite && !depthAlreadyTested) d.depth->depth[pi] = z[l];
    } else if (d.depthTest && !depthAlreadyTested) {
      if (!compare(d.depthFunc, z[l], d.depth->depth[pi])) continue;
      if (d.depthWrite) d.depth->depth[pi] = z[l];
    }
    for (size_t i = 0; i < d.targets.size(); ++i) {
      if (!d.targets[i].data) continue;
      float src[4] = {colors[i].c[0][l], colors[i].c[1][l], colors[i].c[2][l], colors[i].c[3][l]};
      writePixel(d, d.targets[i], x, y, src);
    }
  }
}

// --- Merges specialised for common states --------------------------------------------

namespace {

// No blending (as a blend factor) or no depth test (as a compare function): neither
// enumeration uses 0.
constexpr uint32_t kOff = 0;

// The lanes of `on` (each all ones or zero) as bits.
inline int laneBits(v8i on) {
#if defined(__AVX__)
  __m256 f;
  __builtin_memcpy(&f, &on, sizeof f);
  return _mm256_movemask_ps(f);
#else
  int bits = 0;
  for (int l = 0; l < 8; ++l) bits |= (on[l] & 1) << l;
  return bits;
#endif
}


// The depth test F of a batch, writing the passing lanes' depth when Write is set.
template <uint32_t F, bool Write>
uint16_t depthTestBatch(const RasterDraw& d, int bx, int by, uint16_t mask, const float* z) {
  if (bx + 4 <= d.width && by + 4 <= d.height)
    return depthRows(d, bx, by, mask, z, Write, [](v8f a, v8f b) { return compareDepths<F>(a, b); });
  for (int l = 0; l < kBatchLanes; ++l) {
    if (!(mask & (1 << l))) continue;
    float& stored = d.depth->depth[size_t(by + kLaneY[l]) * d.width + (bx + kLaneX[l])];
    if (!compareValues(F, z[l], stored)) mask = uint16_t(mask & ~(1u << l));
    else if (Write) stored = z[l];
  }
  return mask;
}

template <uint32_t F, bool Write>
uint16_t earlyDepthSpecialised(const RasterDraw& d, int bx, int by, uint16_t mask, const float* z, bool) {
  return depthTestBatch<F, Write>(d, bx, by, mask, z);
}

// The alpha test (ALPHAFUNC against ALPHAREF on oC0's alpha in 8 bits) of a batch.
uint16_t alphaTestBatch(const RasterDraw& d, uint16_t mask, const float* alpha) {
  uint32_t pass = 0;
  const v8i ref = v8i{} + int32_t(d.alphaRef);
  for (int h = 0; h < 2; ++h) {
    v8f v;
    __builtin_memcpy(&v, alpha + 8 * h, sizeof v);
    const v8i a = toUnorm8x8(v);  // 0..255: signed compares are the unsigned ones
    v8i ok;
    switch (d.alphaFunc) {
      case CMP_NEVER: ok = v8i{}; break;
      case CMP_LESS: ok = a < ref; break;
      case CMP_EQUAL: ok = a == ref; break;
      case CMP_LESSEQUAL: ok = a <= ref; break;
      case CMP_GREATER: ok = a > ref; break;
      case CMP_NOTEQUAL: ok = a != ref; break;
      case CMP_GREATEREQUAL: ok = a >= ref; break;
      default: ok = v8i{} - 1; break;
    }
    pass |= uint32_t(laneBits(ok)) << (8 * h);
  }
  return uint16_t(mask & pass);
}

// blendFactor for factor F and channel c, eight lanes at once.
template <uint32_t F>
inline v8f blendFactorx8(int c, const v8f* src, const v8f* dst) {
  const v8f one = v8f{} + 1.0f;
  if constexpr (F == BLEND_ZERO) return v8f{};
  else if constexpr (F == BLEND_ONE) return one;
  else if constexpr (F == BLEND_SRCCOLOR) return src[c];
  else if constexpr (F == BLEND_INVSRCCOLOR) return one - src[c];
  else if constexpr (F == BLEND_SRCALPHA) return src[3];
  else if constexpr (F == BLEND_INVSRCALPHA) return one - src[3];
  else if constexpr (F == BLEND_DESTALPHA) return dst[3];
  else if constexpr (F == BLEND_INVDESTALPHA) return one - dst[3];
  else if constexpr (F == BLEND_DESTCOLOR) return dst[c];
  else if constexpr (F == BLEND_INVDESTCOLOR) return one - dst[c];
  else static_assert(F == BLEND_ZERO, "blend factor without an eight-lane version");
}

// Eight lanes of an 8-bit target (B G R A in memory) blended with lanes k..k+7 of
// the colour by SF/DF and ADD: blendInto and writePixel's operations in their order.
template <uint32_t SF, uint32_t DF>
inline v8u blendPixels(v8u old, const float (*color)[kBatchLanes], int k, bool hasAlpha) {
  const v8f zero{}, one = zero + 1.0f, k255 = zero + 255.0f;
  v8f src[4], dst[4];
  for (int c = 0; c < 4; ++c) {
    v8f v;
    __builtin_memcpy(&v, color[c] + k, sizeof v);
    v = v < zero ? zero : v;  // std::clamp(v, 0, 1): NaN stays NaN
    src[c] = one < v ? one : v;
  }
  const v8i bytes = v8i(old);
  dst[0] = __builtin_convertvector((bytes >> 16) & 0xff, v8f) / k255;
  dst[1] = __builtin_convertvector((bytes >> 8) & 0xff, v8f) / k255;
  dst[2] = __builtin_convertvector(bytes & 0xff, v8f) / k255;
  dst[3] = hasAlpha ? __builtin_convertvector((bytes >> 24) & 0xff, v8f) / k255 : one;
  v8i q[4];
  for (int c = 0; c < 4; ++c)
    q[c] = toUnorm8x8(src[c] * blendFactorx8<SF>(c, src, dst) + dst[c] * blendFactorx8<DF>(c, src, dst));
  const v8i a = hasAlpha ? q[3] : v8i{} + 255;
  return v8u((a << 24) | (q[0] << 16) | (q[1] << 8) | q[2]);
}

// Blends the live lanes of a batch into target t: inside the surface two rows of 4
// pixels per half, lanes that are not live written back as they were.
template <uint32_t SF, uint32_t DF>
void blendStore(const ColorTarget& t, int width, int height, int bx, int by, uint16_t mask,
                const float (*color)[kBatchLanes]) {
  const v8i laneBit{1, 2, 4, 8, 16, 32, 64, 128};
  if (bx + 4 <= width && by + 4 <= height) {
    for (int h = 0; h < 2; ++h) {
      const int live = (mask >> (8 * h)) & 0xff;
      if (!live) continue;
      uint8_t* row0 = t.data + size_t(by + 2 * h) * t.pitch + size_t(bx) * 4;
      uint8_t* row1 = row0 + t.pitch;
      v4u r0, r1;
      __builtin_memcpy(&r0, row0, sizeof r0);
      __builtin_memcpy(&r1, row1, sizeof r1);
      const v8u old = __builtin_shufflevector(r0, r1, 0, 1, 4, 5, 2, 3, 6, 7);
      const v8u p = (laneBit & live) != 0 ? blendPixels<SF, DF>(old, color, 8 * h, t.hasAlpha) : old;
      r0 = __builtin_shufflevector(p, p, 0, 1, 4, 5);
      r1 = __builtin_shufflevector(p, p, 2, 3, 6, 7);
      __builtin_memcpy(row0, &r0, sizeof r0);
      __builtin_memcpy(row1, &r1, sizeof r1);
    }
    return;
  }
  // At the surface's edge: the live lanes gathered into lane order and back.
  alignas(32) uint32_t px[kBatchLanes] = {};
  auto at = [&](int l) { return t.data + size_t(by + kLaneY[l]) * t.pitch + size_t(bx + kLaneX[l]) * 4; };
  for (int l = 0; l < kBatchLanes; ++l)
    if (mask & (1 << l)) __builtin_memcpy(px + l, at(l), 4);
  for (int k = 0; k < kBatchLanes; k += 8) {
    v8u old;
    __builtin_memcpy(&old, px + k, sizeof old);
    const v8u p = blendPixels<SF, DF>(old, color, k, t.hasAlpha);
    __builtin_memcpy(px + k, &p, sizeof p);
  }
  for (int l = 0; l < kBatchLanes; ++l)
    if (mask & (1 << l)) __builtin_memcpy(at(l), px + l, 4);
}

// mergeBatch for: no stencil, target 0 alone, 8-bit with every channel written, no
// sRGB write or dithering; the alpha test (any function) as the draw says, depth test
// DepthF (kOff: none or already done early), blending SF/DF with ADD (kOff: none).
// The same operations in the same order as the generic path, so the same bytes.
template <uint32_t SF, uint32_t DF, uint32_t DepthF>
void mergeSpecialised(const RasterDraw& d, int bx, int by, uint16_t mask, const exec::LaneVec4* colors,
                      const float* z, bool depthAlreadyTested, bool) {
  const float (*color)[kBatchLanes] = colors[0].c;
  if (d.alphaTest) {
    mask = alphaTestBatch(d, mask, color[3]);
    if (!mask) return;
  }
  if constexpr (DepthF != kOff) {
    if (!depthAlreadyTested) {
      mask = d.depthWrite ? depthTestBatch<DepthF, true>(d, bx, by, mask, z)
                          : depthTestBatch<DepthF, false>(d, bx, by, mask, z);
      if (!mask) return;
    }
  }
  if constexpr (SF == kOff) storeOpaque(d.targets[0], d.width, d.height, bx, by, mask, color);
  else blendStore<SF, DF>(d.targets[0], d.width, d.height, bx, by, mask, color);
}

template <uint32_t SF, uint32_t DF>
MergeBatchFn chooseDepth(uint32_t depthFunc) {
  switch (depthFunc) {
    case kOff: return mergeSpecialised<SF, DF, kOff>;
    case CMP_LESS: return mergeSpecialised<SF, DF, CMP_LESS>;
    case CMP_LESSEQUAL: return mergeSpecialised<SF, DF, CMP_LESSEQUAL>;
    case CMP_GREATER: return mergeSpecialised<SF, DF, CMP_GREATER>;
    case CMP_GREATEREQUAL: return mergeSpecialised<SF, DF, CMP_GREATEREQUAL>;
    case CMP_EQUAL: return mergeSpecialised<SF, DF, CMP_EQUAL>;
    default: return mergeBatch;
  }
}

// The blend factors as blendInto takes them: BOTHSRCALPHA and BOTHINVSRCALPHA stand
// for a source and destination factor together.
void resolveBothFactors(uint32_t& src, uint32_t& dst) {
  if (src == BLEND_BOTHSRCALPHA) { src = BLEND_SRCALPHA; dst = BLEND_INVSRCALPHA; }
  if (src == BLEND_BOTHINVSRCALPHA) { src = BLEND_INVSRCALPHA; dst = BLEND_SRCALPHA; }
}

}  // namespace

MergeBatchFn chooseMerge(const MergeState& m) {
  if (m.stencil || m.srgbWrite || m.dither) return mergeBatch;
  if (m.targets[0] != MergeState::Target::Unorm8Full) return mergeBatch;
  for (size_t i = 1; i < m.targets.size(); ++i)
    if (m.targets[i] != MergeState::Target::None) return mergeBatch;
  // An early depth test leaves the merge nothing to test.
  const uint32_t depth = m.depthTest && !m.earlyDepth ? m.depthFunc : kOff;
  const RasterDraw::Blend& b = m.blend;
  if (!b.enable) return chooseDepth<kOff, kOff>(depth);
  if (b.op != BLENDOP_ADD || b.opA != BLENDOP_ADD) return mergeBatch;
  uint32_t sf = b.src, df = b.dst, sa = b.srcA, da = b.dstA;
  resolveBothFactors(sf, df);
  resolveBothFactors(sa, da);
  if (sa != sf || da != df) return mergeBatch;
  // The pairs the samples draw with: alpha blending, additive passes, modulation (2x).
  if (sf == BLEND_SRCALPHA && df == BLEND_INVSRCALPHA) return chooseDepth<BLEND_SRCALPHA, BLEND_INVSRCALPHA>(depth);
  if (sf == BLEND_ONE && df == BLEND_ONE) return chooseDepth<BLEND_ONE, BLEND_ONE>(depth);
  if (sf == BLEND_ZERO && df == BLEND_SRCCOLOR) return chooseDepth<BLEND_ZERO, BLEND_SRCCOLOR>(depth);
  if (sf == BLEND_DESTCOLOR && df == BLEND_ZERO) return chooseDepth<BLEND_DESTCOLOR, BLEND_ZERO>(depth);
  if (sf == BLEND_SRCALPHA && df == BLEND_ONE) return chooseDepth<BLEND_SRCALPHA, BLEND_ONE>(depth);
  if (sf == BLEND_DESTCOLOR && df == BLEND_SRCCOLOR) return chooseDepth<BLEND_DESTCOLOR, BLEND_SRCCOLOR>(depth);
  return mergeBatch;
}

EarlyDepthFn chooseEarlyDepthTest(uint32_t depthFunc, bool writeDepth) {
  switch (depthFunc) {
    case CMP_LESS: return writeDepth ? earlyDepthSpecialised<CMP_LESS, true> : earlyDepthSpecialised<CMP_LESS, false>;
    case CMP_LESSEQUAL:
      return writeDepth ? earlyDepthSpecialised<CMP_LESSEQUAL, true> : earlyDepthSpecialised<CMP_LESSEQUAL, false>;
    case CMP_GREATER:
      return writeDepth ? earlyDepthSpecialised<CMP_GREATER, true> : earlyDepthSpecialised<CMP_GREATER, false>;
    case CMP_GREATEREQUAL:
      return writeDepth ? earlyDepthSpecialised<CMP_GREATEREQUAL, true>
                        : earlyDepthSpecialised<CMP_GREATEREQUAL, false>;
    case CMP_EQUAL: return writeDepth ? earlyDepthSpecialised<CMP_EQUAL, true> : earlyDepthSpecialised<CMP_EQUAL, false>;
    default: return earlyDepthTest;
  }
}

}  // namespace refx::pipeline
