#include "exec/lane_math.h"

#include <cmath>

#include "exec/pow_lanes.h"
#include "refx/core/batch.h"
#include "refx/core/cpu_features.h"

namespace refx::exec::detail {

namespace {
constexpr int N = kBatchLanes;
}

void exp2Lanes(const float* a, const float*, const float*, float* r, uint32_t) {
  for (int l = 0; l < N; ++l) r[l] = exp2Lane(a[l]);
}

void log2Lanes(const float* a, const float*, const float*, float* r, uint32_t) {
  for (int l = 0; l < N; ++l) r[l] = log2Lane(a[l]);
}

void powLanesAvx2(const float* a, const float* b, float* r) { pow_lanes::powLanes<4>(a, b, r, N); }

namespace {

// |a|^n for the whole exponents 2, 3 and 4, as products in double precision: x² is
// exact (24 by 24 significant bits), x³ and x⁴ are rounded once, then once more to
// float. The correctly rounded power but where the double product falls exactly on a
// midpoint between two floats (about one in 2^29), also where |a|^n itself is a
// midpoint (rounded to even).
template <int Exponent>
void powWhole(const float* a, float* r) {
  for (int l = 0; l < N; ++l) {
    const double x = std::fabs(double(a[l])), x2 = x * x;
    r[l] = float(Exponent == 2 ? x2 : Exponent == 3 ? x2 * x : x2 * x2);
  }
}

}  // namespace

void powLanes(const float* a, const float* b, const float*, float* r, uint32_t) {
  // One exponent for all lanes that is 2, 3 or 4 (HLSL's pow(x, 3), say): products.
  bool same = true;
  for (int l = 1; l < N; ++l) same &= b[l] == b[0];
  if (same && b[0] == 2.0f) return powWhole<2>(a, r);
  if (same && b[0] == 3.0f) return powWhole<3>(a, r);
  if (same && b[0] == 4.0f) return powWhole<4>(a, r);
  if (activeIsa() == CpuIsa::Avx512) powLanesAvx512(a, b, r);
  else powLanesAvx2(a, b, r);
}

void litLanes(const float* x, const float* y, const float* w, float* r, uint32_t mask) {
  for (int c = 0; c < 4; ++c)
    if (mask >> c & 1)
      for (int l = 0; l < N; ++l) r[c * N + l] = litLane(c, x[l], y[l], w[l]);
}

void expPLanes(const float* v, const float*, const float*, float* r, uint32_t mask) {
  for (int c = 0; c < 4; ++c)
    if (mask >> c & 1)
      for (int l = 0; l < N; ++l) r[c * N + l] = expPLane(c, v[l]);
}

// One loop per component, as the interpreter computes them.
void sinCosLanes(const float* v, const float*, const float*, float* r, uint32_t mask) {
  for (int c = 0; c < 2; ++c)
    if (mask >> c & 1)
      for (int l = 0; l < N; ++l) r[c * N + l] = sinCosLane(c, v[l]);
}

}  // namespace refx::exec::detail
