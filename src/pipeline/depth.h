// Depth values beyond the interpolated z: D3DRS_DEPTHBIAS / SLOPESCALEDEPTHBIAS and
// w-buffering (D3DRS_ZENABLE = D3DZB_USEW).
#pragma once
#include <algorithm>
#include <cmath>

#include "refx/core/math.h"

namespace refx::pipeline {

// The w of a point on the far plane (z_clip = w_clip) of a projection matrix in D3D's
// row-vector form: with w = _34·z + _44 and z_clip = _33·z + _43, the far plane is at
// z = (_44 - _43) / (_33 - _34), so w_far = _34·(_44 - _43) / (_33 - _34) + _44
// (the zf of a W-friendly perspective matrix, 1 for the identity). A w-buffer stores
// w / w_far. Returns 1 where the matrix has no positive finite w_far.
float projectionFarW(const Matrix& projection);

// D3D9's depth offset of a triangle: DepthBias + SlopeScale · max(|dz/dx|, |dz/dy|),
// the slopes in depth units per pixel.
inline float depthOffset(float depthBias, float slopeScale, float dzdx, float dzdy) {
  const float m = std::max(std::fabs(dzdx), std::fabs(dzdy));
  return depthBias + (slopeScale != 0 ? slopeScale * m : 0.0f);
}

}  // namespace refx::pipeline
