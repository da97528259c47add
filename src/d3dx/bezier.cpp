// Bicubic Bézier patch evaluation and tessellation.
#include <algorithm>
#include <cmath>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/teapot.h"

namespace refx::d3dx {

namespace {

// Bernstein basis of degree 3 and its derivative at t.
void bernstein(float t, float b[4], float d[4]) {
  float s = 1 - t;
  b[0] = s * s * s;
  b[1] = 3 * t * s * s;
  b[2] = 3 * t * t * s;
  b[3] = t * t * t;
  d[0] = -3 * s * s;
  d[1] = 3 * s * s - 6 * t * s;
  d[2] = 6 * t * s - 3 * t * t;
  d[3] = 3 * t * t;
}

// Largest extent of the control net: the scale for "the cross product vanishes".
float netSize(const Vec3 cp[16]) {
  Vec3 lo = cp[0], hi = cp[0];
  for (int k = 1; k < 16; ++k) {
    lo = {std::min(lo.x, cp[k].x), std::min(lo.y, cp[k].y), std::min(lo.z, cp[k].z)};
    hi = {std::max(hi.x, cp[k].x), std::max(hi.y, cp[k].y), std::max(hi.z, cp[k].z)};
  }
  return std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
}

}  // namespace

BezierPoint evaluateBezierPatch(const Vec3 cp[16], float u, float v) {
  float bu[4], du[4], bv[4], dv[4];
  bernstein(u, bu, du);
  bernstein(v, bv, dv);
  BezierPoint r;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const Vec3& c = cp[4 * i + j];
      r.position = r.position + c * (bv[i] * bu[j]);
      r.dPdu = r.dPdu + c * (bv[i] * du[j]);
      r.dPdv = r.dPdv + c * (dv[i] * bu[j]);
    }
  return r;
}

Vec3 bezierPatchNormal(const Vec3 cp[16], float u, float v) {
  float size = netSize(cp);
  float tiny = 1e-6f * size * size;
  BezierPoint p = evaluateBezierPatch(cp, u, v);
  Vec3 n = cross(p.dPdu, p.dPdv);
  // At a collapsed edge step into the patch; the normal there tends to the pole's
  // normal as the step shrinks (1e-3 tilts it by a small fraction of a degree).
  for (float step : {1e-3f, 1e-2f}) {
    if (length(n) > tiny) break;
    float u2 = u < 0.5f ? u + step : u - step, v2 = v < 0.5f ? v + step : v - step;
    BezierPoint a = evaluateBezierPatch(cp, u, v2), b = evaluateBezierPatch(cp, u2, v);
    n = cross(a.dPdu, a.dPdv);
    if (length(n) <= tiny) n = cross(b.dPdu, b.dPdv);
    if (length(n) <= tiny) {
      BezierPoint c = evaluateBezierPatch(cp, u2, v2);
      n = cross(c.dPdu, c.dPdv);
    }
  }
  return normalize(n);
}

Mesh createBezierPatch(const Vec3 cp[16], uint32_t tessellation) {
  if (tessellation < 1) fail("createBezierPatch: tessellation must be at least 1, not 0");
  if (tessellation > 2048) fail("createBezierPatch: tessellation {} exceeds the limit of 2048", tessellation);
  for (int k = 0; k < 16; ++k)
    if (!std::isfinite(cp[k].x) || !std::isfinite(cp[k].y) || !std::isfinite(cp[k].z))
      fail("createBezierPatch: control point {} is not finite", k);
  const uint32_t t = tessellation, row = t + 1;
  Mesh mesh(d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(1), row * row, 2 * t * t);
  for (uint32_t i = 0; i <= t; ++i)
    for (uint32_t j = 0; j <= t; ++j) {
      float u = float(j) / float(t), v = float(i) / float(t);
      uint32_t k = i * row + j;
      mesh.setPosition(k, evaluateBezierPatch(cp, u, v).position);
      mesh.setNormal(k, bezierPatchNormal(cp, u, v));
      mesh.setTexCoord(k, 0, u, v);
    }
  // Quad a = (i,j), b = (i,j+1), c = (i+1,j), d = (i+1,j+1): b - a runs along dP/du and
  // c - a along dP/dv, so (a, b, c) and (b, d, c) have cross(p1-p0, p2-p0) along the
  // normal: clockwise seen from that side in D3D's left-handed space.
  uint32_t f = 0;
  for (uint32_t i = 0; i < t; ++i)
    for (uint32_t j = 0; j < t; ++j) {
      uint32_t a = i * row + j, b = a + 1, c = a + row, d = c + 1;
      uint32_t* idx = &mesh.indices[6 * f++];
      idx[0] = a, idx[1] = b, idx[2] = c;
      idx[3] = b, idx[4] = d, idx[5] = c;
    }
  return mesh;
}

}  // namespace refx::d3dx
