// A primitive's level of detail proven once for many quads: the binary exponent of ρ²
// that the samplers' quad classification would find for every quad of a region,
// derived from the primitive's planes with bounds on every rounding in between.
#pragma once

#include "refx/resource/sampler.h"

namespace refx::pipeline {

// The interpolation of one texture coordinate (RasterDraw::planes): value/w planes
// (base, d/dx, d/dy) unless flat, where the plane holds the value itself.
struct CoordinatePlane {
  const float* plane;
  bool flat;
};

// For the 2x2 quads of the lanes at pixels [x0, x1] x [y0, y1] (whole quads) of a
// primitive whose planes are taken from (originX, originY), with 1/w from `invW` and
// the coordinates u and v: the range of every quad's ρ² = max(|du/dx|² + |dv/dx|²,
// |du/dy|² + |dv/dy|²) as the sampler computes it, from the interpolated lanes'
// differences scaled by (width, height), as binary exponents (ProvenRho). It is proven
// from bounds on the exact differences over the region and on every rounding of the
// interpolation and of the sampler's arithmetic; low == kUnprovenExponent where no
// bound is found (1/w not positive over the region, ρ² not a normal float).
ProvenRho provenQuadRho(const float* invW, CoordinatePlane u, CoordinatePlane v, float originX, float originY, int x0,
                        int y0, int x1, int y1, float width, float height);

}  // namespace refx::pipeline
