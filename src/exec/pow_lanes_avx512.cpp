// powLanes with eight doubles per register (pow_lanes.h); compiled with AVX-512 flags
// and called only where the CPU has them (lane_math.cpp).
#include "exec/pow_lanes.h"

#include "refx/core/batch.h"

namespace refx::exec::detail {

void powLanesAvx512(const float* a, const float* b, float* r) { pow_lanes::powLanes<8>(a, b, r, kBatchLanes); }

}  // namespace refx::exec::detail
