#include "clip.h"

#include <algorithm>
#include <cmath>

#include "ff_vertex.h"

namespace refx::pipeline {

using namespace d3d;

float ClipPlanes::distance(const Vec4& p, int plane) const {
  const float g = guardBand;
  switch (plane) {
    case 0: return p.z;             // near: z >= 0
    case 1: return p.w - p.z;       // far: z <= w
    case 2: return g * p.w - p.x;   // right
    case 3: return g * p.w + p.x;   // left
    case 4: return g * p.w - p.y;   // top
    case 5: return g * p.w + p.y;   // bottom
    default: return dot(user[plane - 6], p);
  }
}

bool ClipPlanes::insideUser(const Vec4& p) const {
  for (int i = 0; i < userCount; ++i)
    if (dot(user[i], p) < 0) return false;
  return true;
}

bool ClipPlanes::outsideVolume(const Vec4& p) const {
  return p.z < 0 || p.z > p.w || std::fabs(p.x) > guardBand * p.w || std::fabs(p.y) > guardBand * p.w;
}

void userClipPlanes(const DeviceState& st, bool vertexShader, ClipPlanes& planes) {
  planes.userCount = 0;
  const uint32_t enabled = st.rs(RS_CLIPPLANEENABLE);
  if (!enabled || !st.rs(RS_CLIPPING)) return;
  Matrix toClip;  // world-space plane -> clip-space plane
  if (!vertexShader) {
    Matrix inv;
    // A singular view·projection leaves no volume to clip; its planes keep everything.
    if (inverse(st.view * st.projection, inv)) toClip = transpose(inv);
  }
  for (int i = 0; i < kMaxUserClipPlanes; ++i) {
    if (!(enabled & (1u << i))) continue;
    const Vec4& p = st.clipPlanes[size_t(i)];
    planes.user[planes.userCount++] = vertexShader ? p : p * toClip;
  }
}

namespace {

ClipVertex lerp(const ClipVertex& a, const ClipVertex& b, float t) {
  ClipVertex c;
  for (int k = 0; k < kVaryingCount; ++k)
    for (int j = 0; j < 4; ++j) c.v[k][j] = a.v[k][j] + (b.v[k][j] - a.v[k][j]) * t;
  return c;
}

}  // namespace

void clipPolygon(std::vector<ClipVertex>& poly, const ClipPlanes& planes) {
  std::vector<ClipVertex> out;
  for (int plane = 0; plane < planes.count() && !poly.empty(); ++plane) {
    out.clear();
    const size_t n = poly.size();
    for (size_t i = 0; i < n; ++i) {
      const ClipVertex& a = poly[i];
      const ClipVertex& b = poly[(i + 1) % n];
      const float da = planes.distance(a.v[0], plane), db = planes.distance(b.v[0], plane);
      if (da >= 0) out.push_back(a);
      if ((da >= 0) != (db >= 0)) out.push_back(lerp(a, b, da / (da - db)));
    }
    poly.swap(out);
  }
}

bool clipSegment(const Vec4* a, const Vec4* b, const ClipPlanes& planes, ClipVertex& ca,
                 ClipVertex& cb) {
  float t0 = 0, t1 = 1;
  for (int plane = 0; plane < planes.count(); ++plane) {
    const float da = planes.distance(a[0], plane), db = planes.distance(b[0], plane);
    if (da < 0 && db < 0) return false;
    if (da < 0) t0 = std::max(t0, da / (da - db));
    if (db < 0) t1 = std::min(t1, da / (da - db));
  }
  if (t0 >= t1) return false;
  ClipVertex va, vb;
  std::copy(a, a + kVaryingCount, va.v);
  std::copy(b, b + kVaryingCount, vb.v);
  ca = lerp(va, vb, t0);
  cb = lerp(va, vb, t1);
  return true;
}

void pointCorners(const Vec4* out, float halfX, float halfY, bool sprite, ClipVertex (&corners)[4]) {
  // Clip-space y points up, screen y down: the top corners have the larger y.
  constexpr float kSide[4][2] = {{-1, 1}, {1, 1}, {1, -1}, {-1, -1}};
  constexpr float kUV[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int k = 0; k < 4; ++k) {
    ClipVertex& c = corners[k];
    std::copy(out, out + kVaryingCount, c.v);
    c.v[0].x += kSide[k][0] * halfX;
    c.v[0].y += kSide[k][1] * halfY;
    if (!sprite) continue;
    for (int t = 0; t < 8; ++t) {
      c.v[kVertexOutTex0 + t].x = kUV[k][0];
      c.v[kVertexOutTex0 + t].y = kUV[k][1];
    }
  }
}

}  // namespace refx::pipeline
