#include "exec/lane_math.h"

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

void powLanes(const float* a, const float* b, const float*, float* r, uint32_t) {
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
