// Interpolation of a batch's pixel-program inputs from their planes (raster.cpp), in
// an AVX2 variant and an AVX-512 one (raster_avx512.cpp) chosen per draw by
// activeIsa(); both do the same IEEE operations in the same order, lane by lane.
#pragma once
#include <cstddef>

#include "refx/core/batch.h"

namespace refx::pipeline {

// Where an interpolated input goes: its lanes in a worker's registers (set once per
// draw, so a batch does not look up register and component again).
struct InputTarget {
  float* lanes;
  bool flat;  // the plane holds the value itself, not value/w
  // An earlier target whose plane is this one's in every primitive of the draw
  // (RasterDraw::inputCopies): its values are copied, not computed again. -1: none;
  // kUnreadInput: nothing reads the input, it is not interpolated.
  int sameAs = -1;
};
constexpr int kUnreadInput = -2;

// For a batch whose top-left pixel is (ox, oy) from the primitive's plane origin:
// w[l] = 1 / invW[l], then for input i (planes: 3 floats each, base, d/dx, d/dy)
// value[l] = base + dx*(ox + laneX[l]) + dy*(oy + laneY[l]), times w[l] unless flat.
// Where invW is 1 in every lane (an affine primitive with w = 1, such as a clip-space
// quad) w is 1 and the product by it, an identity in IEEE arithmetic, is left out.
using InterpolateInputsFn = void (*)(const float* planes, const InputTarget* targets, size_t count,
                                     float ox, float oy, const float* invW, float* w);

// The variant for refx's active instruction set.
InterpolateInputsFn chooseInterpolateInputs();

// The AVX-512 variant (raster_avx512.cpp): call only where the CPU has AVX-512.
void interpolateInputsAvx512(const float* planes, const InputTarget* targets, size_t count, float ox,
                             float oy, const float* invW, float* w);

}  // namespace refx::pipeline
