// Alpha test, stencil, depth test/write, blending and color write for one batch.
#pragma once
#include <cstdint>

#include "raster.h"

namespace refx::pipeline {

// Lane positions inside a 4x4 batch (quad-major, see core/batch.h).
inline constexpr int kLaneX[kBatchLanes] = {0, 1, 0, 1, 2, 3, 2, 3, 0, 1, 0, 1, 2, 3, 2, 3};
inline constexpr int kLaneY[kBatchLanes] = {0, 0, 1, 1, 0, 0, 1, 1, 2, 2, 3, 3, 2, 2, 3, 3};

bool compare(uint32_t func, float a, float b);

// Depth test only (early depth); returns the lanes that pass. Writes depth for them
// when writeDepth is set.
uint16_t earlyDepthTest(const RasterDraw& d, int bx, int by, uint16_t mask, const float* z,
                        bool writeDepth);

// Full merge of shaded lanes: color[c][lane] in float, z per lane.
void mergeBatch(const RasterDraw& d, int bx, int by, uint16_t mask, const float (*color)[kBatchLanes],
                const float* z, bool depthAlreadyTested, bool counterClockwise);

}  // namespace refx::pipeline
