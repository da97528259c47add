// D3D's libm-based shader ops, one lane at a time: the interpreter and the native
// code's lane helpers compute each op through these functions, so both give the
// same bits (same libm call, same special cases, same order).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace refx::exec::detail {

inline float exp2Lane(float x) { return std::exp2(x); }
// D3D log: log2 |x| (log(0) = -inf).
inline float log2Lane(float x) { return std::log2(std::fabs(x)); }

// Component c of D3D lit of (x = N.L, y = N.H, w = power).
inline float litLane(int c, float x, float y, float w) {
  // The power is limited to the 8.8 fixed-point range of the era's hardware.
  w = std::min(std::max(w, -127.9961f), 127.9961f);
  return c == 0 || c == 3 ? 1.0f : c == 1 ? (x > 0 ? x : 0.0f) : (x > 0 && y > 0 ? std::pow(y, w) : 0.0f);
}

// Component c of vs_1_1 expp of v: (2^floor(v), v - floor(v), 2^v, 1).
inline float expPLane(int c, float v) {
  const float f = std::floor(v);
  return c == 0 ? std::exp2(f) : c == 1 ? v - f : c == 2 ? std::exp2(v) : 1.0f;
}

// sincos: x = cos(v), y = sin(v).
inline float sinCosLane(int c, float v) { return c == 0 ? std::cos(v) : std::sin(v); }

// Lane helpers called by native code on the 16 lanes of a batch: per-component ops
// read a and b and write r[16]; the others read the components they name and write
// the components of `mask` in r[4][16].
using LaneHelper = void (*)(const float* a, const float* b, const float* c, float* r, uint32_t mask);
void exp2Lanes(const float* a, const float* b, const float* c, float* r, uint32_t mask);
void log2Lanes(const float* a, const float* b, const float* c, float* r, uint32_t mask);
// D3D pow, |a|^b (pow(0, 0) = 1), of the 16 lanes: exp2(b · log2|a|) evaluated in
// double precision and rounded once to float, so nearly always the correctly rounded
// power (pow_lanes.h); where every lane's exponent is the same 2, 3 or 4, products in
// double precision. The interpreter calls this too, so native code and interpreter
// share one definition. C's special cases: pow(x, ±0) = 1 and pow(1, y) = 1 even for
// NaN, pow(+0, y < 0) = +inf, |a|^±inf by whether |a| is above or below 1; other NaNs
// propagate.
void powLanes(const float* a, const float* b, const float* c, float* r, uint32_t mask);
// powLanes at each width (pow_lanes.h): the same bits; Avx512 only where the CPU has it.
void powLanesAvx2(const float* a, const float* b, float* r);
void powLanesAvx512(const float* a, const float* b, float* r);
void litLanes(const float* x, const float* y, const float* w, float* r, uint32_t mask);
void expPLanes(const float* v, const float* b, const float* c, float* r, uint32_t mask);
void sinCosLanes(const float* v, const float* b, const float* c, float* r, uint32_t mask);

}  // namespace refx::exec::detail
