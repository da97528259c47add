// Homogeneous clipping of clip-space primitives: the view volume's near and far
// planes, a guard band that keeps screen coordinates inside the rasterizer's fixed
// point range, and the user clip planes of SetClipPlane / D3DRS_CLIPPLANEENABLE.
#pragma once
#include <vector>

#include "raster.h"
#include "refx/core/math.h"
#include "refx/pipeline/state.h"

namespace refx::pipeline {

struct ClipVertex {
  Vec4 v[kVaryingCount];  // v[0]: clip-space position
};

struct ClipPlanes {
  float guardBand = 1;  // |x|, |y| <= guardBand * w
  int userCount = 0;
  Vec4 user[kMaxUserClipPlanes];  // clip space: a vertex is kept when dot(plane, p) >= 0

  int count() const { return 6 + userCount; }
  // Signed distance of clip-space position p to plane i (>= 0: inside).
  float distance(const Vec4& p, int plane) const;
  // Whether p is on the inside of every user plane.
  bool insideUser(const Vec4& p) const;
  // Whether p is outside near/far or the guard band (user planes not considered).
  bool outsideVolume(const Vec4& p) const;
  // Whether p needs clipping against any plane.
  bool outside(const Vec4& p) const { return outsideVolume(p) || !insideUser(p); }
};

// The enabled user planes of `st` in clip space. D3D9 gives them in world space for
// fixed-function vertex processing (transformed here by the inverse transpose of
// view·projection, clip = world·view·projection in row-vector form) and in clip space
// when a vertex shader runs. None when D3DRS_CLIPPING is FALSE.
void userClipPlanes(const DeviceState& st, bool vertexShader, ClipPlanes& planes);

// Sutherland-Hodgman against every plane; all vertex outputs are interpolated.
void clipPolygon(std::vector<ClipVertex>& poly, const ClipPlanes& planes);

// Parametric clip of the segment a-b; false when nothing is left.
bool clipSegment(const Vec4* a, const Vec4* b, const ClipPlanes& planes, ClipVertex& ca,
                 ClipVertex& cb);

// The clip-space corners of a point's square, in screen order top-left, top-right,
// bottom-right, bottom-left: the vertex `out` moved by halfX, halfY in clip units (half
// the side in pixels times 2w over the viewport's width or height). With `sprite` the
// u, v of every texture coordinate set are (0,0) at the top-left corner to (1,1).
void pointCorners(const Vec4* out, float halfX, float halfY, bool sprite, ClipVertex (&corners)[4]);

}  // namespace refx::pipeline
