// The opaque store of a shaded batch into an 8-bit target (merge_kernels.h storeOpaque
// and storeOpaqueOver) in an AVX-512 variant (raster_avx512.cpp), for the blocks inside
// the target: the same conversion (toUnorm8x8's operations) on 16 lanes at once.
#pragma once
#include <cstdint>

#include "refx/core/batch.h"

namespace refx::pipeline {

// Stores the live lanes of `mask` of a batch's colours (r, g, b, a rows) as D3DCOLORs
// into the 4x4 block whose top-left pixel is at `topLeft` (rows `pitch` bytes apart):
// with `under`, the other lanes get *under (the block held it in every pixel), else
// they keep what they hold. hasAlpha false: alpha 0xff (X8R8G8B8).
using OpaqueBlockStoreFn = void (*)(uint8_t* topLeft, int pitch, bool hasAlpha, uint16_t mask,
                                    const float (*color)[kBatchLanes], const uint32_t* under);

// The AVX-512 variant: call only where the CPU has AVX-512.
void storeOpaqueBlockAvx512(uint8_t* topLeft, int pitch, bool hasAlpha, uint16_t mask,
                            const float (*color)[kBatchLanes], const uint32_t* under);

}  // namespace refx::pipeline
