// Alpha test, stencil, depth test/write, blending and color write for one batch.
#pragma once
#include <array>
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

// Full merge of shaded lanes: colors[i] is the pixel program's output i (oCi, in float)
// for render target i, z per lane. Alpha test reads oC0; the tests' outcome and the
// blend state apply to every target (D3DPMISCCAPS_MRTPOSTPIXELSHADERBLENDING).
void mergeBatch(const RasterDraw& d, int bx, int by, uint16_t mask, const exec::LaneVec4* colors,
                const float* z, bool depthAlreadyTested, bool counterClockwise);

// Quantises a colour channel to 8 bits: round to nearest, or with D3DRS_DITHERENABLE
// floor(v * 255 + t) where t = (B + 0.5) / 16 and B is the 4x4 Bayer matrix entry of
// pixel (x & 3, y & 3) -- the same value on average, a pattern instead of one step.
uint8_t quantizeUnorm8(float v, bool dither, int x, int y);

// The output-merger state a draw plan fixes, as far as it chooses the merge function.
struct MergeState {
  RasterDraw::Blend blend{};
  bool alphaTest = false, depthTest = false, depthWrite = false, earlyDepth = false;
  bool stencil = false, srgbWrite = false, dither = false;
  uint32_t depthFunc = 4;
  // What target n takes from the program (None: not written).
  enum class Target : uint8_t { None, Unorm8Full, Unorm8Masked, Float };
  std::array<Target, kMaxRenderTargets> targets{};
};

// A merge specialised for `m` (blending off, or ADD of SRCALPHA/INVSRCALPHA, ONE/ONE,
// ZERO/SRCCOLOR, DESTCOLOR/ZERO, DESTCOLOR/SRCCOLOR or SRCALPHA/ONE; depth off, early,
// or LESS, LESSEQUAL, GREATER, GREATEREQUAL or EQUAL with or without write; the alpha
// test; no stencil; an 8-bit target 0 alone with every channel written; no sRGB or
// dithering), vectorised over the batch, or mergeBatch. Either gives the same bytes
// and depths.
MergeBatchFn chooseMerge(const MergeState& m);

// earlyDepthTest specialised for `depthFunc` (LESS, LESSEQUAL, GREATER, GREATEREQUAL,
// EQUAL) and `writeDepth`, or earlyDepthTest itself. Either passes the same lanes and
// writes the same depths.
EarlyDepthFn chooseEarlyDepthTest(uint32_t depthFunc, bool writeDepth);

}  // namespace refx::pipeline
