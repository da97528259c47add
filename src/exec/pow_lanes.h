// D3D pow for the lanes of a batch (powLanes, lane_math.h), as a template over the
// vector width: lane_math.cpp instantiates it with four doubles per register (AVX2),
// pow_lanes_avx512.cpp with eight. Each lane goes through the same IEEE operations in
// the same order at either width, so both give the same bits.
//
// |x|^y = 2^(y · log2|x|), evaluated in double precision and rounded once to float:
// the evaluation's relative error is about 2^-46, so the result is the correctly
// rounded power except where the exact one lies that close to a midpoint between two
// floats. Only the basic operations and fused multiply-adds are used (no libm but
// std::fma in a build without FMA), with
// AVX2's lack of 64-bit integer ⇄ double conversions worked around by magic numbers.
#pragma once
#include <cmath>
#include <cstdint>
#include <cstring>

#include <immintrin.h>

// In an unnamed namespace: each translation unit keeps its own copy, so code compiled
// with AVX-512 flags cannot stand in for the AVX2 unit's inline functions.
namespace refx::exec::detail::pow_lanes {
namespace {

template <int W>
struct Vectors {
  typedef double D __attribute__((vector_size(8 * W)));
  typedef int64_t L __attribute__((vector_size(8 * W)));
  typedef uint64_t U __attribute__((vector_size(8 * W)));
  typedef float F __attribute__((vector_size(4 * W)));
  typedef int32_t I __attribute__((vector_size(4 * W)));
};

// float ⇄ double lanes by the instructions made for it (the compiler's generic vector
// conversion goes through memory in halves). AVX-512's in their zero-masked form with
// every lane set, the same instruction: GCC 12 warns of the plain form's undefined
// source operand. A build without AVX (the fuzz targets') takes the generic forms:
// the same values.
template <int W>
inline typename Vectors<W>::D toDouble(typename Vectors<W>::F x) {
  if constexpr (W == 8) return typename Vectors<W>::D(_mm512_maskz_cvtps_pd(0xff, __m256(x)));
#if defined(__AVX__)
  else return typename Vectors<W>::D(_mm256_cvtps_pd(__m128(x)));
#else
  else return __builtin_convertvector(x, typename Vectors<W>::D);
#endif
}
template <int W>
inline typename Vectors<W>::F toFloat(typename Vectors<W>::D x) {
  if constexpr (W == 8) return typename Vectors<W>::F(_mm512_maskz_cvtpd_ps(0xff, __m512d(x)));
#if defined(__AVX__)
  else return typename Vectors<W>::F(_mm256_cvtpd_ps(__m256d(x)));
#else
  else return __builtin_convertvector(x, typename Vectors<W>::F);
#endif
}

// a · b + c rounded once: the same result at either width, and from std::fma in a
// build without FMA.
template <class D>
inline D fma(D a, D b, D c) {
  if constexpr (sizeof(D) == 64) return D(_mm512_fmadd_pd(__m512d(a), __m512d(b), __m512d(c)));
#if defined(__FMA__)
  else return D(_mm256_fmadd_pd(__m256d(a), __m256d(b), __m256d(c)));
#else
  else {
    D r;
    for (size_t i = 0; i < sizeof(D) / sizeof(double); ++i) r[i] = std::fma(a[i], b[i], c[i]);
    return r;
  }
#endif
}
template <class D>
inline D fma(D a, double b, double c) { return fma(a, D{} + b, D{} + c); }

// The series below are summed by Estrin's scheme, written out (loops over coefficient
// arrays stay loops): pairs of terms, then pairs of pairs with x², x⁴, x⁸, so that the
// products run side by side rather than as one chain of dependent multiply-adds
// (Horner's), whose latency would be the cost.

// Σ z^k/(2k + 1), k = 0 … 8: ln m = 2s times this in z = s² ≤ 0.0295 (the next term,
// z⁹/19, is below 2^-49).
template <class D>
inline D logSeries(D z) {
  const D z2 = z * z, z4 = z2 * z2, z8 = z4 * z4;
  const D p01 = fma(z, 1.0 / 3, 1.0), p23 = fma(z, 1.0 / 7, 1.0 / 5), p45 = fma(z, 1.0 / 11, 1.0 / 9),
          p67 = fma(z, 1.0 / 15, 1.0 / 13);
  const D p03 = fma(p23, z2, p01), p47 = fma(p67, z2, p45);
  return fma(z8, D{} + 1.0 / 17, fma(p47, z4, p03));
}

// e^g = Σ g^k/k!, k = 0 … 11, for |g| ≤ 0.347 (the next term is below 2^-47).
template <class D>
inline D expSeries(D g) {
  const D g2 = g * g, g4 = g2 * g2, g8 = g4 * g4;
  const D p01 = g + 1.0, p23 = fma(g, 1.0 / 6, 1.0 / 2), p45 = fma(g, 1.0 / 120, 1.0 / 24),
          p67 = fma(g, 1.0 / 5040, 1.0 / 720), p89 = fma(g, 1.0 / 362880, 1.0 / 40320),
          pab = fma(g, 1.0 / 39916800, 1.0 / 3628800);
  const D p03 = fma(p23, g2, p01), p47 = fma(p67, g2, p45), p8b = fma(pab, g2, p89);
  return fma(p8b, g8, fma(p47, g4, p03));
}

// x^y for finite x > 0 and finite y (other lanes get some value).
template <int W>
inline typename Vectors<W>::F powFinite(typename Vectors<W>::F x, typename Vectors<W>::F y) {
  using D = typename Vectors<W>::D;
  using L = typename Vectors<W>::L;
  using U = typename Vectors<W>::U;
  const D xd = toDouble<W>(x), yd = toDouble<W>(y);
  // log2 x = e + l: x = 2^e · m with m in [√½, √2) (every float is a normal double),
  // ln m = 2s(1 + s²/3 + … + s¹⁶/17) with s = (m - 1)/(m + 1), |s| ≤ 0.1716 (logSeries).
  // The exponent field becomes a double as the low bits of 2^52 + field.
  const U bits = U(xd);
  const D field = D((bits >> 52) | 0x4330000000000000ULL) - 4503599627370496.0;  // exact
  D m = D((bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL);              // [1, 2)
  const L high = L(m > 1.4142135623730951);                                     // -1 where true
  m = high ? m * 0.5 : m;
  const D e = field - (high ? D{} + 1022.0 : D{} + 1023.0);
  const D s = (m - 1.0) / (m + 1.0);
  const D l = (s + s) * logSeries(s * s) * 1.4426950408889634;  // ln m / ln 2
  // y · log2 x = y·e + y·l with y·e exact (24 by 11 significant bits). The fraction is
  // the exact part minus the nearest whole number n, plus y·l, so the whole part does
  // not cost the fraction its low bits.
  const D ye = yd * e, yl = yd * l;
  D t = ye + yl;
  const L huge = L(t > 200.0) | L(t < -200.0);  // beyond float's range either way
  t = t > 200.0 ? D{} + 200.0 : t;
  t = t < -200.0 ? D{} + -200.0 : t;
  // t + 1.5 · 2^52 rounds t to a whole number (ties to even) and holds it in its low
  // bits, two's complement.
  const D shifted = t + 6755399441055744.0;
  const D n = shifted - 6755399441055744.0;
  const D f = huge ? D{} : (ye - n) + yl;  // |f| ≤ ½
  // 2^n · e^(f ln 2), |f ln 2| ≤ 0.347 (expSeries).
  const U scale = (U(shifted) << 52) + (1023ULL << 52);
  return toFloat<W>(expSeries(f * 0.6931471805599453) * D(scale));
}

// r[l] = |a[l]|^b[l] for l < count (a multiple of W). C's special cases by selects:
// where powFinite does not apply (|a| zero or infinite, b infinite) the power is +inf
// or +0 by whether |a| < 1 agrees with b < 0; a NaN operand gives |a| + b; b = ±0 or
// |a| = 1 give 1, NaN or not.
template <int W>
inline void powLanes(const float* a, const float* b, float* r, int count) {
  using F = typename Vectors<W>::F;
  using I = typename Vectors<W>::I;
  for (int l = 0; l < count; l += W) {
    F x, y;
    std::memcpy(&x, a + l, sizeof x);
    std::memcpy(&y, b + l, sizeof y);
    x = F(I(x) & 0x7fffffff);  // |a|
    const I general = (x > 0.0f) & (x < INFINITY) & (y - y == 0.0f) & (y != 0.0f) & (x != 1.0f);
    uint64_t words[W / 2];  // general's lanes, two per word
    std::memcpy(words, &general, sizeof words);
    uint64_t all = ~uint64_t(0), any = 0;
    for (uint64_t w : words) all &= w, any |= w;
    // (a group without a general lane, as where saturated dot products are 0, skips
    // the evaluation)
    F p = any ? powFinite<W>(x, y) : F{};
    if (all != ~uint64_t(0)) {
      p = general ? p : ((x < 1.0f) == (y < 0.0f) ? F{} + INFINITY : F{});
      p = ((x != x) | (y != y)) ? x + y : p;
      p = ((y == 0.0f) | (x == 1.0f)) ? F{} + 1.0f : p;
    }
    std::memcpy(r + l, &p, sizeof p);
  }
}

}  // namespace
}  // namespace refx::exec::detail::pow_lanes
