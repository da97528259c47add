// The AVX-512 variant of the 2D rgba8 kernels: kernel2DFor of sampler.cpp with the 16
// lanes of a batch in one register instead of two halves, the same IEEE operations in
// the same order (see the comments there for why each step is exact). Compiled with
// AVX-512 flags (CMakeLists.txt: sources named *_avx512.cpp) and called only where the
// CPU has them (selectKernel2D). Everything but the selector has internal linkage, so
// no other translation unit can end up calling an AVX-512 copy of a shared function.
#include "refx/core/avx512_intrinsics.h"

#include <cstdint>
#include <cstring>
#include <type_traits>

#include "resource/sampler_kernels.h"

namespace refx::resource {

namespace {

using namespace kernels;

constexpr int kLanes = kBatchLanes;

typedef float v16f __attribute__((vector_size(64)));
typedef int v16i __attribute__((vector_size(64)));
typedef uint32_t v16u __attribute__((vector_size(64)));
typedef uint16_t v32h __attribute__((vector_size(64)));

inline v16f splat(float f) { return v16f(_mm512_set1_ps(f)); }
inline v16f toFloat(v16i i) { return __builtin_convertvector(i, v16f); }

// vmaxps/vminps: x > lo ? x : lo (NaN -> lo), then x < hi ? x : hi.
inline v16f clampPosition(v16f x, float lo, float hi) {
  return v16f(_mm512_min_ps(_mm512_max_ps(__m512(x), _mm512_set1_ps(lo)), _mm512_set1_ps(hi)));
}

// float(floor(x)) (vrndscaleps toward -inf).
inline v16f floorFloat(v16f x) {
  return v16f(_mm512_roundscale_ps(__m512(x), _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC));
}

// Rounds to the nearest int by the MXCSR mode (vcvtps2dq).
inline v16i roundInt(v16f x) { return v16i(_mm512_cvtps_epi32(__m512(x))); }

inline v16f fmadd(v16f a, v16f b, v16f c) {
  return v16f(_mm512_fmadd_ps(__m512(a), __m512(b), __m512(c)));
}

template <TextureAddress A>
inline v16i addressLanes(v16i i, int n) {
  const int p = 2 * n;
  if constexpr (A == TextureAddress::Wrap) {
    return i < 0 ? i + n : (i >= n ? i - n : i);
  } else if constexpr (A == TextureAddress::Mirror) {
    v16i m = i < 0 ? i + p : (i >= p ? i - p : i);
    return m < n ? m : (p - 1) - m;
  } else if constexpr (A == TextureAddress::MirrorOnce) {
    v16i m = i < 0 ? -1 - i : i;
    return m < n - 1 ? m : n - 1;
  } else {  // Clamp
    v16i m = i > 0 ? i : 0;
    return m < n - 1 ? m : n - 1;
  }
}

inline v16i minU32(v16i a, v16i b) {
  const v16u ua = v16u(a), ub = v16u(b);
  return v16i(ua < ub ? ua : ub);
}
inline v16i wrapLow(v16i i, int n) { return minU32(i, i + n); }   // i in [-1, n - 1]
inline v16i wrapHigh(v16i i, int n) { return minU32(i, i - n); }  // i in [0, n]

// One axis of all lanes (axis8 of sampler.cpp).
template <TextureAddress A, bool Linear>
inline void axis16(const float* c, float fn, float lo, float hi, int n, v16i& i0, v16i& i1,
                   v16i& X) {
  v16f u;
  std::memcpy(&u, c, sizeof u);
  u = clampPosition(u, -kCoordLimit, kCoordLimit);
  if constexpr (A == TextureAddress::Wrap) u = u - floorFloat(u);
  if constexpr (A == TextureAddress::Mirror) u = u - 2.0f * floorFloat(u * 0.5f);
  if constexpr (Linear) {
    v16f x = u * (fn * kWeightScale) - 0.5f * kWeightScale;
    if constexpr (A != TextureAddress::Wrap)
      x = clampPosition(x, lo * kWeightScale, hi * kWeightScale);
    X = roundInt(x);
    const v16i i = X >> kWeightBits;
    if constexpr (A == TextureAddress::Wrap) {
      i0 = wrapLow(i, n);
      i1 = wrapHigh(i + 1, n);
    } else {
      i0 = addressLanes<A>(i, n);
      i1 = addressLanes<A>(i + 1, n);
    }
  } else {
    v16f x = u * fn;
    if constexpr (A != TextureAddress::Wrap) x = clampPosition(x, lo, hi);
    const v16i i = __builtin_convertvector(floorFloat(x), v16i);
    if constexpr (A == TextureAddress::Wrap)
      i0 = wrapHigh(i, n);
    else
      i0 = addressLanes<A>(i, n);
  }
}

// Whether b - a = d in every lane.
inline bool allDiffer(v16i a, v16i b, int d) {
  return _mm512_cmpeq_epi32_mask(__m512i(b - a), _mm512_set1_epi32(d)) == 0xffff;
}

// Sixteen texels by index: scalar loads inserted four to a 128-bit block, the indices
// read back from memory (load8 of sampler.cpp); faster than vpgatherdd on current cores.
[[gnu::always_inline]] inline v16u load16(const uint32_t* texels, v16i a) {
  alignas(64) int ix[16];
  std::memcpy(ix, &a, sizeof ix);
  asm volatile("" ::: "memory");  // reload the indices as integers, not by lane extraction
  __m128i q[4];
  for (int b = 0; b < 4; ++b) {
    const int* i = ix + 4 * b;
    q[b] = _mm_cvtsi32_si128(int(texels[i[0]]));
    q[b] = _mm_insert_epi32(q[b], int(texels[i[1]]), 1);
    q[b] = _mm_insert_epi32(q[b], int(texels[i[2]]), 2);
    q[b] = _mm_insert_epi32(q[b], int(texels[i[3]]), 3);
  }
  const __m256i lo = _mm256_setr_m128i(q[0], q[1]), hi = _mm256_setr_m128i(q[2], q[3]);
  return v16u(_mm512_inserti64x4(_mm512_castsi256_si512(lo), hi, 1));
}

// Texels a[l] and a[l] + 1 of every lane: two 64-bit gathers of eight lanes each, then
// the first and second texels picked from both.
inline void loadPairs16(const uint32_t* texels, v16i a, v16u& first, v16u& second) {
  const __m512i idx = __m512i(a);
  const __m512i lo = _mm512_i32gather_epi64(_mm512_castsi512_si256(idx), texels, 4);
  const __m512i hi = _mm512_i32gather_epi64(_mm512_extracti64x4_epi64(idx, 1), texels, 4);
  const __m512i even = _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
  const __m512i odd = _mm512_setr_epi32(1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 29, 31);
  first = v16u(_mm512_permutex2var_epi32(lo, even, hi));
  second = v16u(_mm512_permutex2var_epi32(lo, odd, hi));
}

// fn(l, ix[l]) for the 16 lanes' texel indices (not negative), read two per 64-bit
// load: the texel loops are bound by load µops, and a shift is cheaper than a load.
template <class Fn>
[[gnu::always_inline]] inline void forEachIndex(const int (&ix)[16], Fn fn) {
  uint64_t pairs[8];
  std::memcpy(pairs, ix, sizeof pairs);
  for (int k = 0; k < 8; ++k) {
    fn(2 * k, size_t(uint32_t(pairs[k])));
    fn(2 * k + 1, size_t(pairs[k] >> 32));
  }
}

// q[l] = t00 t10 t01 t11 of lane l as the texel vectors p00 p10 p01 p11: lanes l, l + 4,
// l + 8, l + 12 share a register (one per 128-bit block), then a 4x4 transpose within
// each block.
inline void transposeQuads(const __m128i (&q)[16], v16u (&p)[4]) {
  __m512i r[4];
  for (int l = 0; l < 4; ++l) {
    const __m256i lo = _mm256_setr_m128i(q[l], q[l + 4]), hi = _mm256_setr_m128i(q[l + 8], q[l + 12]);
    r[l] = _mm512_inserti64x4(_mm512_castsi256_si512(lo), hi, 1);
  }
  const __m512i a01 = _mm512_unpacklo_epi32(r[0], r[1]), b01 = _mm512_unpackhi_epi32(r[0], r[1]);
  const __m512i a23 = _mm512_unpacklo_epi32(r[2], r[3]), b23 = _mm512_unpackhi_epi32(r[2], r[3]);
  p[0] = v16u(_mm512_unpacklo_epi64(a01, a23));
  p[1] = v16u(_mm512_unpackhi_epi64(a01, a23));
  p[2] = v16u(_mm512_unpacklo_epi64(b01, b23));
  p[3] = v16u(_mm512_unpackhi_epi64(b01, b23));
}

// Texel pairs a[l], a[l] + 1 (top row) and a[l] + w, a[l] + w + 1 (bottom row) of every
// lane, in each of T textures of one size (p[t]: p00 p10 p01 p11 of texture t): scalar
// 64-bit loads, each lane's index read back from memory once for all T textures, then
// a transpose (loadQuads8 of sampler.cpp, 16 lanes). Faster than vpgatherdq on current
// cores.
template <int T>
[[gnu::always_inline]] inline void loadQuadsOf(const uint32_t* const (&texels)[T], v16i a, int w,
                                               v16u (&p)[T][4]) {
  alignas(64) int ix[16];
  std::memcpy(ix, &a, sizeof ix);
  asm volatile("" ::: "memory");  // reload the indices as integers, not by lane extraction
  // The bottom row from its own base register: both loads of a lane take its index as
  // is, with no address arithmetic per lane (the compiler would otherwise add w to it).
  const uint32_t* top[T];
  const uint32_t* below[T];
  for (int t = 0; t < T; ++t) {
    top[t] = texels[t], below[t] = texels[t] + w;
    asm("" : "+r"(below[t]));
  }
  __m128i q[T][16];
  forEachIndex(ix, [&](int l, size_t i) {
    for (int t = 0; t < T; ++t) {
      const __m128i row = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(top[t] + i));
      q[t][l] = _mm_castpd_si128(_mm_loadh_pd(_mm_castsi128_pd(row), reinterpret_cast<const double*>(below[t] + i)));
    }
  });
  for (int t = 0; t < T; ++t) transposeQuads(q[t], p[t]);
}

inline void loadQuads16(const uint32_t* texels, v16i a, int w, v16u& p00, v16u& p10, v16u& p01,
                        v16u& p11) {
  const uint32_t* const one[1] = {texels};
  v16u p[1][4];
  loadQuadsOf<1>(one, a, w, p);
  p00 = p[0][0], p10 = p[0][1], p01 = p[0][2], p11 = p[0][3];
}

inline v16f channel(v16u p, int shift) { return toFloat(v16i((p >> shift) & 255u)); }

// b/255 for integer b in 0..255, correctly rounded (byteOver255 of sampler.cpp).
inline v16f byteOver255(v16f b) { return fmadd(b, splat(kInv255Hi), b * kInv255Lo); }

// Row lerp in 16-bit lanes, two channels per 32-bit lane (rowLerp of sampler.cpp).
inline v32h rowLerp(v16u t0, v16u t1, v32h wx) {
  const v32h a = v32h(t0), b = v32h(t1);
  return (a << 8) + (b - a) * wx;
}

// x = top + (bottom - top)·wy of one channel from the low (shift 0) or high (shift 16)
// halves of two row results: S/256 exactly, S the channel's filter sum.
template <int Shift>
inline v16f columnSum(v32h top, v32h bottom, v16f wy) {
  const v16u mask = v16u{} + (Shift ? 0xffffffffu : 0xffffu);
  const v16f t = toFloat(v16i((v16u(top) >> Shift) & mask));
  const v16f b = toFloat(v16i((v16u(bottom) >> Shift) & mask));
  return fmadd(b - t, wy, t);
}

// columnSum divided by 65280 (columnLerp of sampler.cpp).
template <int Shift>
inline v16f columnLerp(v32h top, v32h bottom, v16f wy) {
  const v16f x = columnSum<Shift>(top, bottom, wy);
  return fmadd(x, splat(kInv65280Hi), x * kInv65280Lo);
}

// Lanes outside `mask` store 0 (clearLanes of sampler.cpp), or with Merge keep what
// the row held.
template <bool Merge>
inline void store(float* p, v16f v, __mmask16 mask) {
  if constexpr (Merge)
    _mm512_mask_storeu_ps(p, mask, __m512(v));
  else
    _mm512_storeu_ps(p, _mm512_maskz_mov_ps(mask, __m512(v)));
}

// The D3DCOLORs of a batch (Argb8 output) stored as `store` stores a channel.
template <bool Merge>
inline void storeColors(uint32_t* p, v16u v, __mmask16 mask) {
  if constexpr (Merge)
    _mm512_mask_storeu_epi32(p, mask, __m512i(v));
  else
    _mm512_storeu_si512(p, _mm512_maskz_mov_epi32(mask, __m512i(v)));
}

// A texel's bytes r, g, b, a (memory order) as the D3DCOLOR a << 24 | r << 16 | g << 8 | b.
inline v16u texelColors(v16u p) {
  const __m512i order = _mm512_set4_epi32(0x0f0c0d0e, 0x0b08090a, 0x07040506, 0x03000102);
  return v16u(_mm512_shuffle_epi8(__m512i(p), order));
}

// The 8-bit unorm of one bilinear channel (Argb8 output): columnSum's x = top +
// (bottom - top)·wy is S/256 exactly (S the filter sum, below 2^24), the float result
// S/65280/256 correctly rounded, and its unorm8 (round(v·255)) is floor(S/65536 + 1/2)
// for every S (checked exhaustively in tests/resource/test_filter_quotient.cpp):
// x/256 + 1/2 is exact in float (24 bits), truncated to an integer.
template <int Shift>
inline v16i columnByte(v32h top, v32h bottom, v16f wy) {
  const v16f x = columnSum<Shift>(top, bottom, wy);
  return v16i(_mm512_cvttps_epi32(__m512(fmadd(x, splat(1.0f / 256.0f), splat(0.5f)))));
}

// LINEAR's weights: the horizontal one (low byte of fixedX) in both 16-bit halves of
// each lane (rowLerp's wx), by one vpshufb, and the vertical one as a float.
inline void linearWeights(v16i fixedX, v16i fixedY, v32h& wx2, v16f& fy) {
  const __m512i weightBytes = _mm512_set4_epi32(0xff0cff0c, 0xff08ff08, 0xff04ff04, 0xff00ff00);
  wx2 = v32h(_mm512_shuffle_epi8(__m512i(fixedX), weightBytes));
  fy = toFloat(fixedY & ((1 << kWeightBits) - 1)) * kWeightUnit;
}

// The bilinear result of 2x2 texels (p00 p10 the top row, p01 p11 the bottom one) with
// linearWeights' wx2 and fy, stored into `out` (Out: see filterLevels).
template <bool Merge, class Out>
[[gnu::always_inline]] inline void blendTexels(v16u p00, v16u p10, v16u p01, v16u p11, v32h wx2, v16f fy,
                                               __mmask16 mask, Out out, uint8_t channels = 0xF) {
  const v16u m = v16u{} + 0x00ff00ffu;
  // (p >> 8) & 0x00ff00ff is the 16-bit halves shifted right by 8 (one vpsrlw).
  const auto highBytes = [](v16u p) { return v16u(v32h(p) >> 8); };
  const v32h topRB = rowLerp(p00 & m, p10 & m, wx2);
  const v32h topGA = rowLerp(highBytes(p00), highBytes(p10), wx2);
  const v32h bottomRB = rowLerp(p01 & m, p11 & m, wx2);
  const v32h bottomGA = rowLerp(highBytes(p01), highBytes(p11), wx2);
  if constexpr (std::is_same_v<Out, uint32_t*>) {
    const v16i r = columnByte<0>(topRB, bottomRB, fy), g = columnByte<0>(topGA, bottomGA, fy);
    const v16i b = columnByte<16>(topRB, bottomRB, fy), a = columnByte<16>(topGA, bottomGA, fy);
    storeColors<Merge>(out, v16u((a << 24) | (r << 16) | (g << 8) | b), mask);
  } else {
    // Channels nobody reads are not written (the same for every batch of a draw).
    if (channels & 1) store<Merge>(out[0], columnLerp<0>(topRB, bottomRB, fy), mask);
    if (channels & 2) store<Merge>(out[1], columnLerp<0>(topGA, bottomGA, fy), mask);
    if (channels & 4) store<Merge>(out[2], columnLerp<16>(topRB, bottomRB, fy), mask);
    if (channels & 8) store<Merge>(out[3], columnLerp<16>(topGA, bottomGA, fy), mask);
  }
}

// The texels of `count` levels of one size at the same positions, addresses and
// weights computed once: level k's result into out[k]. Out: float (*)[kLanes] (the
// channels as the shader sees them) or uint32_t* (their 8-bit unorms as D3DCOLORs,
// PreparedSampler::sampleImplicitArgb8).
template <TextureAddress AU, TextureAddress AV, bool Linear, bool Merge, class Out, int Count>
[[gnu::always_inline]] inline void filterLevels(const SampleLevel* const (&levels)[Count], const float* u,
                                                const float* v, __mmask16 mask, Out const (&out)[Count]) {
  constexpr bool colors = std::is_same_v<Out, uint32_t*>;
  const int w = levels[0]->width, h = levels[0]->height;
  float loU, hiU, loV, hiV;
  positionRange(AU, w, loU, hiU);
  positionRange(AV, h, loV, hiV);
  v16i x0, x1, y0, y1, fixedX, fixedY;
  axis16<AU, Linear>(u, float(w), loU, hiU, w, x0, x1, fixedX);
  axis16<AV, Linear>(v, float(h), loV, hiV, h, y0, y1, fixedY);
  const v16i r0 = y0 * w;
  if constexpr (!Linear) {
    for (int k = 0; k < Count; ++k) {
      const v16u p = load16(levels[k]->rgba8.data(), r0 + x0);
      if constexpr (colors)
        storeColors<Merge>(out[k], texelColors(p), mask);  // unorm8(b/255) = b
      else
        for (int ch = 0; ch < 4; ++ch) store<Merge>(out[k][ch], byteOver255(channel(p, 8 * ch)), mask);
    }
  } else {
    v16u p00[Count], p10[Count], p01[Count], p11[Count];
    const bool pairs = allDiffer(x0, x1, 1);
    // y1 = y0 + 1 is r1 = r0 + w (a level has fewer than 2^31 texels: no product wraps):
    // the 2x2 texels are a block in memory, and r1 is not needed.
    if (pairs && allDiffer(y0, y1, 1)) {
      for (int k = 0; k < Count; ++k) loadQuads16(levels[k]->rgba8.data(), r0 + x0, w, p00[k], p10[k], p01[k], p11[k]);
    } else {
      const v16i r1 = y1 * w;
      for (int k = 0; k < Count; ++k) {
        const uint32_t* texels = levels[k]->rgba8.data();
        if (!pairs) {
          p00[k] = load16(texels, r0 + x0), p10[k] = load16(texels, r0 + x1);
          p01[k] = load16(texels, r1 + x0), p11[k] = load16(texels, r1 + x1);
        } else {
          loadPairs16(texels, r0 + x0, p00[k], p10[k]);
          loadPairs16(texels, r1 + x0, p01[k], p11[k]);
        }
      }
    }
    v32h wx2;
    v16f fy;
    linearWeights(fixedX, fixedY, wx2, fy);
    for (int k = 0; k < Count; ++k) blendTexels<Merge>(p00[k], p10[k], p01[k], p11[k], wx2, fy, mask, out[k]);
  }
}

// One level (filterLevels). Out of line: its callers reach it by a jump, and the batch
// classification in front of it keeps a frame without stack realignment (this one's
// 64-byte index buffers).
template <TextureAddress AU, TextureAddress AV, bool Linear, bool Merge = false, class Out = float (*)[kLanes]>
[[gnu::noinline]] void filter16(const SampleLevel& lv, const float* u, const float* v,
                                __mmask16 mask, Out out) {
  const SampleLevel* const levels[1] = {&lv};
  const Out outs[1] = {out};
  filterLevels<AU, AV, Linear, Merge, Out, 1>(levels, u, v, mask, outs);
}

// Two levels of one size at the same coordinates (filterLevels): the texel fetches of
// both are independent of each other and overlap.
template <TextureAddress AU, TextureAddress AV, bool Linear>
[[gnu::noinline]] void filterPair16(const SampleLevel& a, const SampleLevel& b, const float* u,
                                    const float* v, __mmask16 mask, float (*outA)[kLanes],
                                    float (*outB)[kLanes]) {
  const SampleLevel* const levels[2] = {&a, &b};
  float (*const outs[2])[kLanes] = {outA, outB};
  filterLevels<AU, AV, Linear, false, float (*)[kLanes], 2>(levels, u, v, mask, outs);
}

template <TextureAddress AU, TextureAddress AV, bool Linear>
void kernel2D16(const SampleLevel& lv, const float* u, const float* v, float out[4][kLanes]) {
  filter16<AU, AV, Linear>(lv, u, v, 0xffff, out);
}

// A batch whose quads chose different levels or filters: each (level, filter) of the
// four quads samples its quads' lanes, `k` holding (level << 1) | linear of quad q in
// its lane q.
// Every lane belongs to one quad, so every lane in `mask` is written once; the others
// read 0. Lanes are independent in the kernel, so this is what a batch of one key gives
// on those lanes. False (nothing written) when a level is not for the kernels, after
// plan.rest with Rest (float output only).
template <TextureAddress AU, TextureAddress AV, bool Rest, class Out = float (*)[kLanes]>
[[gnu::noinline]] bool mixedLevels16(const UniformPlan& plan, const float* u, const float* v,
                                     const float* w, uint32_t mask, __m128i k, Out out) {
  int keys[4];
  _mm_storeu_si128(reinterpret_cast<__m128i*>(keys), k);
  for (int q = 0; q < 4; ++q) {
    if (!plan.levels[keys[q] >> 1]) {
      if constexpr (Rest) plan.rest(plan.owner, u, v, w, uint16_t(mask), out);
      return false;
    }
  }
  if constexpr (std::is_same_v<Out, uint32_t*>)
    _mm512_storeu_si512(out, _mm512_setzero_si512());
  else
    for (int ch = 0; ch < 4; ++ch) _mm512_storeu_ps(out[ch], _mm512_setzero_ps());
  uint32_t done = 0;  // quads sampled
  for (int q = 0; q < 4; ++q) {
    if (done >> q & 1) continue;
    uint32_t lanes = 0;
    for (int r = q; r < 4; ++r)
      if (keys[r] == keys[q]) done |= 1u << r, lanes |= 0xfu << (4 * r);
    const SampleLevel& lv = *plan.levels[keys[q] >> 1];
    if (keys[q] & 1)
      filter16<AU, AV, true, true, Out>(lv, u, v, __mmask16(lanes & mask), out);
    else
      filter16<AU, AV, false, true, Out>(lv, u, v, __mmask16(lanes & mask), out);
  }
  return true;
}

// What classifyBatch16 returns besides a key.
constexpr int kDeclined = -2;  // some quad's ρ² is not of the form the classification reads
constexpr int kMixed = -1;     // the quads' keys differ (they are in `keys`)

// sample2DUniform's classification of the four quads at once (see there): ρ² of each
// quad with the same operations in the same order, one lane per quad; the exponent
// gives λ's side of 0 and the nearest level when the mantissa keeps log2 away from an
// integer. The batch's key (level << 1 | LINEAR) when all four quads agree.
[[gnu::always_inline]] inline int classifyBatch16(const UniformPlan& plan, const float* u, const float* v,
                                                  __m128i& keys) {
  typedef float v4f __attribute__((vector_size(16)));
  typedef int v4i __attribute__((vector_size(16)));
  typedef uint32_t v4u __attribute__((vector_size(16)));
  const __m512 x = _mm512_loadu_ps(u), y = _mm512_loadu_ps(v);
  // Quad q's lanes tl, tr, bl are 4q, 4q + 1, 4q + 2: the differences of the quads' u
  // and v as one register, (tr - tl of quads 0..3, bl - tl of quads 0..3) for u, then
  // for v, scaled by the level-0 size; the rest works on one value per quad.
  const __m512i far = _mm512_setr_epi32(1, 5, 9, 13, 2, 6, 10, 14, 17, 21, 25, 29, 18, 22, 26, 30);
  const __m512i near = _mm512_setr_epi32(0, 4, 8, 12, 0, 4, 8, 12, 16, 20, 24, 28, 16, 20, 24, 28);
  const v16f size = v16f(_mm512_mask_broadcastss_ps(_mm512_set1_ps(plan.size[0]), 0xff00,
                                                    _mm_set_ss(plan.size[1])));
  const v16f d = (v16f(_mm512_permutex2var_ps(x, far, y)) - v16f(_mm512_permutex2var_ps(x, near, y))) * size;
  const v16f d2 = d * d;
  // du·du + dv·dv for the vectors a (tr - tl) and b (bl - tl) of each quad.
  typedef float v8f __attribute__((vector_size(32)));
  const v8f sq = v8f(_mm512_castps512_ps256(__m512(d2))) + v8f(_mm512_extractf32x8_ps(__m512(d2), 1));
  const v4f la = v4f(_mm256_castps256_ps128(__m256(sq))), lb = v4f(_mm256_extractf128_ps(__m256(sq), 1));
  const v4f ms = la < lb ? lb : la;  // std::max(la, lb)
  // Normal, positive and finite, mantissa in [0x1000, 0x7ff000): as two unsigned
  // range checks, independent of each other.
  const v4i bits = v4i(ms), mant = bits & 0x7fffff;
  const __mmask8 normal = _mm_cmplt_epu32_mask(__m128i(bits - 0x00800000), _mm_set1_epi32(0x7f000000));
  const __mmask8 inside = _mm_cmplt_epu32_mask(__m128i(mant - 0x1000), _mm_set1_epi32(0x7ff000 - 0x1000));
  if (__mmask8(normal & inside) != 0xf) return kDeclined;
  const v4i e = v4i(v4u(bits) >> 23) - 127;
  const v4i linear = e >= 0 ? v4i{} + plan.minLinear : v4i{} + plan.magLinear;
  v4i level = (e + 1) >> 1;
  level = level < plan.first ? v4i{} + plan.first : level;
  level = level > plan.last ? v4i{} + plan.last : level;
  if (plan.mipNone) level = v4i{};
  const v4i k = (level << 1) | linear;  // per quad
  keys = __m128i(k);
  const int key = k[0];
  return _mm_cmpeq_epi32_mask(__m128i(k), _mm_set1_epi32(key)) == 0xf ? key : kMixed;
}

// The key classifyBatch16 gives a quad whose ρ² has binary exponent e (and a mantissa
// it reads), as the same steps in scalar arithmetic.
inline int keyOfExponent(const UniformPlan& plan, int e) {
  const int linear = e >= 0 ? plan.minLinear : plan.magLinear;
  int level = (e + 1) >> 1;
  level = level < plan.first ? plan.first : level;
  level = level > plan.last ? plan.last : level;
  if (plan.mipNone) level = 0;
  return (level << 1) | linear;
}

// The key of every quad whose ρ² lies in range r, where it is one: the keys of the
// binades at both ends agree (keys grow with the exponent), and an end near a binade's
// edge, where classifyBatch16 declines, has the same key across that edge (there the
// exact λ is near a whole level, or near 0 with one filter for both sides). -1: none.
inline int keyOfRange(const UniformPlan& plan, const ProvenRho& r) {
  if (r.low == kUnprovenExponent) return -1;
  const int key = keyOfExponent(plan, r.low);
  if (keyOfExponent(plan, r.high) != key) return -1;
  if (r.lowNearEdge && keyOfExponent(plan, r.low - 1) != key) return -1;
  if (r.highNearEdge && keyOfExponent(plan, r.high + 1) != key) return -1;
  return key;
}

// The batch sampled at the level and with the filter classifyBatch16 finds. With Rest,
// a batch it declines goes on to plan.rest, as a tail call (the common path then calls
// nothing and keeps nothing across a call). Out as filter16's.
template <TextureAddress AU, TextureAddress AV, bool Rest, class Out = float (*)[kLanes]>
[[gnu::always_inline]] inline bool uniformBatch16(const UniformPlan& plan, const float* u,
                                                  const float* v, const float* w,
                                                  uint32_t mask, Out out) {
  const auto decline = [&] {
    if constexpr (Rest) plan.rest(plan.owner, u, v, w, uint16_t(mask), out);
    return false;
  };
  __m128i keys;
  const int key = classifyBatch16(plan, u, v, keys);
  if (key == kDeclined) return decline();
  if (key == kMixed) return mixedLevels16<AU, AV, Rest, Out>(plan, u, v, w, mask, keys, out);
  const SampleLevel* lv = levelByCount(plan.levels, key >> 1);  // 0 <= key >> 1 <= last
  if (!lv) return decline();
  if (key & 1)
    filter16<AU, AV, true, false, Out>(*lv, u, v, __mmask16(mask), out);
  else
    filter16<AU, AV, false, false, Out>(*lv, u, v, __mmask16(mask), out);
  return true;
}

template <TextureAddress AU, TextureAddress AV>
bool uniform16(const UniformPlan& plan, const float* u, const float* v, uint32_t mask,
               float out[4][kLanes]) {
  return uniformBatch16<AU, AV, false>(plan, u, v, nullptr, mask, out);
}

template <TextureAddress AU, TextureAddress AV>
bool uniformColors16(const UniformPlan& plan, const float* u, const float* v, uint32_t mask,
                     uint32_t out[kLanes]) {
  return uniformBatch16<AU, AV, false, uint32_t*>(plan, u, v, nullptr, mask, out);
}

template <TextureAddress AU, TextureAddress AV>
void implicit16(const void* context, const float* u, const float* v, const float* w,
                uint16_t laneMask, float (*out)[kLanes]) {
  uniformBatch16<AU, AV, true>(*static_cast<const UniformPlan*>(context), u, v, w, laneMask, out);
}

// Whether two batches of coordinates are the same, bit for bit.
inline bool sameCoordinates(const float (*a)[kLanes], const float (*b)[kLanes]) {
  if (a == b) return true;
  const __mmask16 u = _mm512_cmpeq_epi32_mask(_mm512_loadu_si512(a[0]), _mm512_loadu_si512(b[0]));
  const __mmask16 v = _mm512_cmpeq_epi32_mask(_mm512_loadu_si512(a[1]), _mm512_loadu_si512(b[1]));
  return __mmask16(u & v) == 0xffff;
}

// Whether classifyBatch16 gives both plans the same key for every batch.
inline bool sameClassification(const UniformPlan& a, const UniformPlan& b) {
  return a.size[0] == b.size[0] && a.size[1] == b.size[1] && a.first == b.first && a.last == b.last &&
         a.minLinear == b.minLinear && a.magLinear == b.magLinear && a.mipNone == b.mipNone;
}

// Two implicit16 calls in one (ImplicitPair2D): where both read the same coordinates
// and classify them alike, and the level has one size in both textures, filterPair16
// samples both; otherwise each plan samples on its own.
template <TextureAddress AU, TextureAddress AV>
void implicitPair16(const void* contextA, const void* contextB, const float (*coordsA)[kLanes],
                    const float (*coordsB)[kLanes], uint16_t laneMask, float (*outA)[kLanes],
                    float (*outB)[kLanes]) {
  const UniformPlan& a = *static_cast<const UniformPlan*>(contextA);
  const UniformPlan& b = *static_cast<const UniformPlan*>(contextB);
  if (sameCoordinates(coordsA, coordsB) && sameClassification(a, b)) {
    const float *u = coordsA[0], *v = coordsA[1];
    __m128i keys;
    const int key = classifyBatch16(a, u, v, keys);
    if (key >= 0) {
      const SampleLevel* la = levelByCount(a.levels, key >> 1);
      const SampleLevel* lb = levelByCount(b.levels, key >> 1);
      if (la && lb && la->width == lb->width && la->height == lb->height) {
        if (key & 1)
          filterPair16<AU, AV, true>(*la, *lb, u, v, __mmask16(laneMask), outA, outB);
        else
          filterPair16<AU, AV, false>(*la, *lb, u, v, __mmask16(laneMask), outA, outB);
        return;
      }
    }
  }
  implicit16<AU, AV>(&a, coordsA[0], coordsA[1], coordsA[2], laneMask, outA);
  implicit16<AU, AV>(&b, coordsB[0], coordsB[1], coordsB[2], laneMask, outB);
}

// A batch of a group (sampleGroup16): its coordinate rows and where its result goes.
template <class Out>
struct GroupBatch {
  const float *u, *v, *w;
  Out out;
  uint8_t channels = 0xF;  // SampleBatch::channels (float output only)
};
// A batch's u and v rows: a GroupBatch's, or a SampleBatch's coordinates.
template <class Out>
inline const float* coordinateU(const GroupBatch<Out>& b) { return b.u; }
template <class Out>
inline const float* coordinateV(const GroupBatch<Out>& b) { return b.v; }
inline const float* coordinateU(const SampleBatch& b) { return b.coords[0]; }
inline const float* coordinateV(const SampleBatch& b) { return b.coords[1]; }

// Up to kMaxSampleGroup batches of LINEAR footprints sampled phase by phase rather than
// one after the other: the classification of all, then their addresses and weights,
// their texel fetches, their filtering. Each batch's work is a long dependency chain;
// side by side, the chains of different batches overlap. The operations per batch are
// filterLevels' own, in the same order. With T = 2 both plans' textures are sampled at
// the first one's coordinates (the caller made sure each batch has the same ones for
// both, and that the plans classify alike). Returns the batches sampled (bit g: batch
// g); the others (declined or mixed classification, POINT, a footprint whose 2x2
// texels are not a block in memory, levels of different sizes) are left untouched.
template <TextureAddress AU, TextureAddress AV, int T, class Batch>
[[gnu::noinline]] uint32_t sampleGroup16(const UniformPlan* const (&plans)[T], int count, const uint16_t* masks,
                                         const Batch* const (&batches)[T], ProvenRho proven) {
  int slot[kMaxSampleGroup];  // the batches still in the group
  const SampleLevel* levels[kMaxSampleGroup][T];
  int n = 0;
  const int provenKey = keyOfRange(*plans[0], proven);
  for (int g = 0; g < count; ++g) {
    __m128i keys;
    const int key = provenKey >= 0 ? provenKey : classifyBatch16(*plans[0], coordinateU(batches[0][g]), coordinateV(batches[0][g]), keys);
    if (key < 0 || !(key & 1)) continue;
    bool ok = true;
    for (int t = 0; t < T; ++t) {
      levels[n][t] = levelByCount(plans[t]->levels, key >> 1);
      ok = ok && levels[n][t] && levels[n][t]->width == levels[n][0]->width &&
           levels[n][t]->height == levels[n][0]->height;
    }
    if (ok) slot[n++] = g;
  }
  v16i index[kMaxSampleGroup];
  v32h wx2[kMaxSampleGroup];
  v16f fy[kMaxSampleGroup];
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const int g = slot[i];
    const int w = levels[i][0]->width, h = levels[i][0]->height;
    float loU, hiU, loV, hiV;
    positionRange(AU, w, loU, hiU);
    positionRange(AV, h, loV, hiV);
    v16i x0, x1, y0, y1, fixedX, fixedY;
    axis16<AU, true>(coordinateU(batches[0][g]), float(w), loU, hiU, w, x0, x1, fixedX);
    axis16<AV, true>(coordinateV(batches[0][g]), float(h), loV, hiV, h, y0, y1, fixedY);
    if (!allDiffer(x0, x1, 1) || !allDiffer(y0, y1, 1)) continue;
    index[m] = y0 * w + x0;
    linearWeights(fixedX, fixedY, wx2[m], fy[m]);
    slot[m] = g;
    for (int t = 0; t < T; ++t) levels[m][t] = levels[i][t];
    ++m;
  }
  v16u texels[kMaxSampleGroup][T][4];
  for (int i = 0; i < m; ++i) {
    const uint32_t* data[T];
    for (int t = 0; t < T; ++t) data[t] = levels[i][t]->rgba8.data();
    loadQuadsOf<T>(data, index[i], levels[i][0]->width, texels[i]);  // the levels have one size (above)
  }
  uint32_t done = 0;
  for (int i = 0; i < m; ++i) {
    const int g = slot[i];
    for (int t = 0; t < T; ++t)
      blendTexels<false>(texels[i][t][0], texels[i][t][1], texels[i][t][2], texels[i][t][3], wx2[i], fy[i],
                         __mmask16(masks[g]), batches[t][g].out, batches[t][g].channels);
    done |= 1u << g;
  }
  return done;
}

// PreparedSampler::ImplicitGroupFn: sampleGroup16, and implicit16 for what it leaves.
template <TextureAddress AU, TextureAddress AV>
void implicitGroup16(const void* context, int count, const uint16_t* laneMasks, const SampleBatch* batches,
                     ProvenRho proven) {
  const UniformPlan& plan = *static_cast<const UniformPlan*>(context);
  const UniformPlan* const plans[1] = {&plan};
  const SampleBatch* const sets[1] = {batches};
  const uint32_t done = sampleGroup16<AU, AV, 1>(plans, count, laneMasks, sets, proven);
  for (int g = 0; g < count; ++g)
    if (!(done >> g & 1)) {
      const float(*c)[kLanes] = batches[g].coords;
      implicit16<AU, AV>(&plan, c[0], c[1], c[2], laneMasks[g], batches[g].out);
    }
}

// PreparedSampler::ImplicitPairGroupFn: sampleGroup16 of both plans for the batches
// whose coordinates are the same for both (the batches as given where every one reads
// a single array for both), implicitPair16 for the others.
template <TextureAddress AU, TextureAddress AV>
void implicitPairGroup16(const void* contextA, const void* contextB, int count, const uint16_t* laneMasks,
                         const SampleBatch* batchesA, const SampleBatch* batchesB, ProvenRho proven) {
  const UniformPlan& a = *static_cast<const UniformPlan*>(contextA);
  const UniformPlan& b = *static_cast<const UniformPlan*>(contextB);
  GroupBatch<float (*)[kLanes]> groupA[kMaxSampleGroup], groupB[kMaxSampleGroup];
  uint16_t masks[kMaxSampleGroup] = {};
  int at[kMaxSampleGroup];
  int n = 0;
  uint32_t done = 0;
  if (sameClassification(a, b)) {
    bool shared = true;
    for (int g = 0; g < count && shared; ++g) shared = batchesA[g].coords == batchesB[g].coords;
    if (shared) {
      // Both lookups read one coordinate array (RasterDraw's shared coordinates): the
      // batches as they are.
      const UniformPlan* const plans[2] = {&a, &b};
      const SampleBatch* const sets[2] = {batchesA, batchesB};
      done = sampleGroup16<AU, AV, 2>(plans, count, laneMasks, sets, proven);
    } else {
      for (int g = 0; g < count; ++g) {
        if (!sameCoordinates(batchesA[g].coords, batchesB[g].coords)) continue;
        const float(*c)[kLanes] = batchesA[g].coords;
        groupA[n] = {c[0], c[1], c[2], batchesA[g].out, batchesA[g].channels};
        groupB[n] = {c[0], c[1], c[2], batchesB[g].out, batchesB[g].channels};
        masks[n] = laneMasks[g];
        at[n++] = g;
      }
      const UniformPlan* const plans[2] = {&a, &b};
      const GroupBatch<float (*)[kLanes]>* const sets[2] = {groupA, groupB};
      const uint32_t sampled = sampleGroup16<AU, AV, 2>(plans, n, masks, sets, proven);
      for (int i = 0; i < n; ++i)
        if (sampled >> i & 1) done |= 1u << at[i];
    }
  }
  for (int g = 0; g < count; ++g)
    if (!(done >> g & 1))
      implicitPair16<AU, AV>(&a, &b, batchesA[g].coords, batchesB[g].coords, laneMasks[g], batchesA[g].out,
                             batchesB[g].out);
}

// UniformColors2D for a group (UniformColorsGroup2D): sampleGroup16 with byte output,
// then uniformColors16 for the batches it leaves. Returns the batches written.
template <TextureAddress AU, TextureAddress AV>
uint32_t uniformColorsGroup16(const UniformPlan& plan, int count, const float* const* u, const float* const* v,
                              const uint16_t* laneMasks, uint32_t* const* out, ProvenRho proven) {
  GroupBatch<uint32_t*> group[kMaxSampleGroup];
  for (int g = 0; g < count; ++g) group[g] = {u[g], v[g], nullptr, out[g]};
  const UniformPlan* const plans[1] = {&plan};
  const GroupBatch<uint32_t*>* const sets[1] = {group};
  uint32_t done = sampleGroup16<AU, AV, 1>(plans, count, laneMasks, sets, proven);
  for (int g = 0; g < count; ++g)
    if (!(done >> g & 1) && uniformColors16<AU, AV>(plan, u[g], v[g], laneMasks[g], out[g])) done |= 1u << g;
  return done;
}

// The kernels of each addressing pair, one entry per kind (Entry<AU, AV>::get(args)
// gives the instance), and the run-time choice among them.
template <TextureAddress AU, TextureAddress AV>
struct UniformEntry {
  static constexpr Uniform2D get() { return uniform16<AU, AV>; }
};
template <TextureAddress AU, TextureAddress AV>
struct UniformColorsEntry {
  static constexpr UniformColors2D get() { return uniformColors16<AU, AV>; }
};
template <TextureAddress AU, TextureAddress AV>
struct ImplicitEntry {
  static constexpr Implicit2D get() { return implicit16<AU, AV>; }
};
template <TextureAddress AU, TextureAddress AV>
struct ImplicitPairEntry {
  static constexpr ImplicitPair2D get() { return implicitPair16<AU, AV>; }
};
template <TextureAddress AU, TextureAddress AV>
struct ImplicitGroupEntry {
  static constexpr ImplicitGroup2D get() { return implicitGroup16<AU, AV>; }
};
template <TextureAddress AU, TextureAddress AV>
struct ImplicitPairGroupEntry {
  static constexpr ImplicitPairGroup2D get() { return implicitPairGroup16<AU, AV>; }
};
template <TextureAddress AU, TextureAddress AV>
struct UniformColorsGroupEntry {
  static constexpr UniformColorsGroup2D get() { return uniformColorsGroup16<AU, AV>; }
};
template <TextureAddress AU, TextureAddress AV>
struct KernelEntry {
  static constexpr Kernel2D get(bool linear) {
    return linear ? kernel2D16<AU, AV, true> : kernel2D16<AU, AV, false>;
  }
};

template <template <TextureAddress, TextureAddress> class Entry, TextureAddress AU, class... Args>
constexpr auto forAddressV(TextureAddress av, Args... args) {
  switch (av) {
    case TextureAddress::Wrap: return Entry<AU, TextureAddress::Wrap>::get(args...);
    case TextureAddress::Mirror: return Entry<AU, TextureAddress::Mirror>::get(args...);
    case TextureAddress::MirrorOnce: return Entry<AU, TextureAddress::MirrorOnce>::get(args...);
    default: return Entry<AU, TextureAddress::Clamp>::get(args...);
  }
}

// BORDER never reaches the kernels; any other value is CLAMP (validAddress of sampler.cpp).
template <template <TextureAddress, TextureAddress> class Entry, class... Args>
constexpr auto forAddressing(TextureAddress au, TextureAddress av, Args... args) {
  switch (au) {
    case TextureAddress::Wrap: return forAddressV<Entry, TextureAddress::Wrap>(av, args...);
    case TextureAddress::Mirror: return forAddressV<Entry, TextureAddress::Mirror>(av, args...);
    case TextureAddress::MirrorOnce: return forAddressV<Entry, TextureAddress::MirrorOnce>(av, args...);
    default: return forAddressV<Entry, TextureAddress::Clamp>(av, args...);
  }
}

}  // namespace

Uniform2D selectUniform2DAvx512(TextureAddress au, TextureAddress av) {
  return forAddressing<UniformEntry>(au, av);
}

UniformColors2D selectUniformColors2DAvx512(TextureAddress au, TextureAddress av) {
  return forAddressing<UniformColorsEntry>(au, av);
}

Implicit2D selectImplicit2DAvx512(TextureAddress au, TextureAddress av) {
  return forAddressing<ImplicitEntry>(au, av);
}

ImplicitPair2D selectImplicitPair2DAvx512(TextureAddress au, TextureAddress av) {
  return forAddressing<ImplicitPairEntry>(au, av);
}

ImplicitGroup2D selectImplicitGroup2DAvx512(TextureAddress au, TextureAddress av) {
  return forAddressing<ImplicitGroupEntry>(au, av);
}

ImplicitPairGroup2D selectImplicitPairGroup2DAvx512(TextureAddress au, TextureAddress av) {
  return forAddressing<ImplicitPairGroupEntry>(au, av);
}

UniformColorsGroup2D selectUniformColorsGroup2DAvx512(TextureAddress au, TextureAddress av) {
  return forAddressing<UniformColorsGroupEntry>(au, av);
}

Kernel2D selectKernel2DAvx512(TextureAddress au, TextureAddress av, bool linear) {
  return forAddressing<KernelEntry>(au, av, linear);
}

}  // namespace refx::resource
