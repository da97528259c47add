// Bicubic Bézier patches and the Utah teapot (D3DXCreateTeapot) built from Martin
// Newell's 32 patches.
#pragma once
#include <cstdint>

#include "refx/core/math.h"
#include "refx/d3dx/mesh.h"

namespace refx::d3dx {

// Point and partial derivatives of a bicubic Bézier patch at (u, v) in [0,1]²:
// P(u, v) = sum_i sum_j B_i(v) B_j(u) controlPoints[4i + j] with the Bernstein
// polynomials B_k, so u runs along each row of four control points and v across rows.
struct BezierPoint {
  Vec3 position, dPdu, dPdv;
};
BezierPoint evaluateBezierPatch(const Vec3 controlPoints[16], float u, float v);

// Unit normal dP/du x dP/dv. Where the patch collapses to a point (a row or column
// of equal control points, as at the teapot's lid and bottom poles) the derivatives'
// cross product vanishes; the normal is then taken just inside the patch, which is
// its limit at the pole.
Vec3 bezierPatchNormal(const Vec3 controlPoints[16], float u, float v);

// One patch as tessellation x tessellation quads: (t+1)² vertices, vertex (i, j) at
// u = j/t, v = i/t with index i(t+1) + j, texture coordinates (u, v), normals from
// bezierPatchNormal; 2t² triangles, clockwise seen from the side the normal points to.
// FVF XYZ | NORMAL | TEX1. tessellation >= 1.
Mesh createBezierPatch(const Vec3 controlPoints[16], uint32_t tessellation);

// The Utah teapot from Newell's 32 patches (306 control points), each patch
// tessellated as createBezierPatch (32(t+1)² vertices, 64t² triangles, the patches
// one after another in the data set's order: rim 0-3, body 4-11, handle 12-15,
// spout 16-19, lid 20-27, bottom 28-31). Texture coordinates are (u, v) of each patch.
// Left-handed with y up: the data set's (x, y, z) with z up becomes (x, z - 1.575, -y),
// so the teapot is centred vertically (y in [-1.575, 1.575]), the spout points to +x
// and the handle to -x. Normals point out of the surface and triangles are clockwise
// seen from outside. The patches near the poles of the lid and bottom contain
// zero-area triangles (kept so the counts stay as above). tessellation >= 1.
Mesh createTeapot(uint32_t tessellation = 8);

inline constexpr int kTeapotPatchCount = 32;
inline constexpr int kTeapotControlPointCount = 306;
// The data set as published: the control point numbers (1-based) of each patch, and
// control points with z up.
extern const uint16_t kTeapotPatches[kTeapotPatchCount][16];
extern const float kTeapotControlPoints[kTeapotControlPointCount][3];

}  // namespace refx::d3dx
