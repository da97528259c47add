// Primitive assembly, clipping (clip.cpp) and setup: screen-space triangles, lines
// and points become fixed-point edge functions and interpolation planes (raster.h).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "clip.h"
#include "depth.h"
#include "draw_plan.h"

namespace refx::pipeline {

void setTriangleEdges(const int64_t (&X)[3], const int64_t (&Y)[3], bool counterClockwise, Primitive& p) {
  int order[3] = {0, 1, 2};
  if (counterClockwise) std::swap(order[1], order[2]);
  p.kind = PrimKind::Triangle;
  p.counterClockwise = counterClockwise;
  for (int k = 0; k < 3; ++k) {
    const int a = order[k], b = order[(k + 1) % 3];
    const int64_t dx = X[b] - X[a], dy = Y[b] - Y[a];
    // E(P) = (P.y - a.y)*dx - (P.x - a.x)*dy, positive inside a clockwise triangle.
    p.edgeA[k] = -dy;
    p.edgeB[k] = dx;
    p.edgeC[k] = -Y[a] * dx + X[a] * dy;
    const bool topLeft = (dy == 0 && dx > 0) || dy < 0;
    p.edgeBias[k] = topLeft ? 1 : 0;
  }
}

using namespace d3d;

namespace {

struct SetupVertex {
  float x, y, z, invW;
  const Vec4* varyings;
  float wDepthOffset = 0;  // w-buffering: the depth bias of the triangle a line or point outlines
};

// Where setup appends primitives and their planes (RasterDraw::prims / planes, or a
// range of the draw's primitives set up by another thread).
struct PrimitiveList {
  std::vector<Primitive>& prims;
  std::vector<float>& planes;
};

void addPlane(std::vector<float>& planes, double a0, double a1, double a2, double x1, double y1,
              double x2, double y2, double det) {
  // Plane through (0,0,a0), (x1,y1,a1), (x2,y2,a2) relative to vertex 0.
  const double dx = ((a1 - a0) * y2 - (a2 - a0) * y1) / det;
  const double dy = ((a2 - a0) * x1 - (a1 - a0) * x2) / det;
  planes.push_back(float(a0));
  planes.push_back(float(dx));
  planes.push_back(float(dy));
}

// D3DRS_WRAPn: a wrapped coordinate takes the shorter way around the unit cylinder,
// e.g. 0.9 -> 0.1 interpolates through 1.0 (0.9 -> 1.1), not back through 0.5.
void wrapTowards(double base, double& v) {
  const double shift = std::round(v - base);
  v -= shift;
}

// std::llround (halves away from zero) inline: the libm call was a good part of
// triangle setup. x - trunc(x) is exact for every double. The step away from zero is
// added without a branch: whether a coordinate's fraction reaches one half is as good
// as random, and a mispredicted branch per coordinate cost more than the arithmetic.
inline int64_t roundHalfAway(double x) {
  if (!(std::fabs(x) < 0x1p52)) return std::llround(x);  // huge or NaN: libm decides
  const double t = std::trunc(x);
  const int64_t away = std::fabs(x - t) >= 0.5;
  return int64_t(t) + (x < 0 ? -away : away);
}

// The value the depth buffer holds for a vertex: z, or w / w_far when w-buffering.
double bufferDepth(const RasterDraw& d, const SetupVertex& v) {
  return d.wBuffer ? double(d.invFarW) / double(v.invW) : double(v.z);
}

// `biased`: D3DRS_DEPTHBIAS/SLOPESCALEDEPTHBIAS apply (not to the pieces of a point).
void setupTriangle(const RasterDraw& d, PrimitiveList out, const SetupVertex (&sv)[3], uint32_t cull,
                   const Rect& bounds, bool flat, bool biased = true) {
  constexpr double one = double(1 << kSubPixelBits);
  // Positions that are not numbers or lie far beyond any guard band (pretransformed
  // vertices are not clipped) would overflow the fixed-point edge functions: such a
  // triangle is not drawn.
  constexpr float kMaxScreenCoordinate = float(1 << 18);
  for (const SetupVertex& v : sv)
    if (!(std::fabs(v.x) <= kMaxScreenCoordinate && std::fabs(v.y) <= kMaxScreenCoordinate)) return;
  int64_t X[3], Y[3];
  for (int i = 0; i < 3; ++i) {
    X[i] = roundHalfAway(double(sv[i].x) * one);
    Y[i] = roundHalfAway(double(sv[i].y) * one);
  }
  const int64_t area = (X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]);
  if (area == 0) return;
  const bool ccw = area < 0;  // y points down: positive area is clockwise on screen
  if ((cull == CULL_CCW && ccw) || (cull == CULL_CW && !ccw)) return;
  Primitive p{};
  setTriangleEdges(X, Y, ccw, p);
  const double minx = std::min({X[0], X[1], X[2]}) / one, maxx = std::max({X[0], X[1], X[2]}) / one;
  const double miny = std::min({Y[0], Y[1], Y[2]}) / one, maxy = std::max({Y[0], Y[1], Y[2]}) / one;
  p.minX = std::max(bounds.left, int(std::ceil(minx)));
  p.maxX = std::min(bounds.right - 1, int(std::floor(maxx)));
  p.minY = std::max(bounds.top, int(std::ceil(miny)));
  p.maxY = std::min(bounds.bottom - 1, int(std::floor(maxy)));
  if (p.minX > p.maxX || p.minY > p.maxY) return;
  // Interpolation planes relative to vertex 0 (snapped positions).
  const double x0 = X[0] / one, y0 = Y[0] / one;
  const double x1 = X[1] / one - x0, y1 = Y[1] / one - y0, x2 = X[2] / one - x0, y2 = Y[2] / one - y0;
  const double det = x1 * y2 - x2 * y1;
  p.originX = float(x0);
  p.originY = float(y0);
  p.planeOffset = uint32_t(out.planes.size());
  addPlane(out.planes, sv[0].invW, sv[1].invW, sv[2].invW, x1, y1, x2, y2, det);
  addPlane(out.planes, sv[0].z, sv[1].z, sv[2].z, x1, y1, x2, y2, det);
  if (biased && (d.depthBias != 0 || d.slopeScaleDepthBias != 0)) {
    float* z = &out.planes[out.planes.size() - 3];  // base, dz/dx, dz/dy
    float slopeX = z[1], slopeY = z[2];
    if (d.wBuffer) {
      // The slopes of the stored w / w_far across the vertices.
      const double w0 = bufferDepth(d, sv[0]), w1 = bufferDepth(d, sv[1]) - w0, w2 = bufferDepth(d, sv[2]) - w0;
      slopeX = float((w1 * y2 - w2 * y1) / det);
      slopeY = float((w2 * x1 - w1 * x2) / det);
    }
    const float offset = depthOffset(d.depthBias, d.slopeScaleDepthBias, slopeX, slopeY);
    if (d.wBuffer) p.wDepthOffset = offset;
    else z[0] += offset;
  }
  for (const InterpolatedInput& in : d.inputs) {
    if (in.flat) {
      out.planes.push_back(sv[0].varyings[in.varying][in.component]);
      out.planes.push_back(0);
      out.planes.push_back(0);
      continue;
    }
    double a[3];
    for (int i = 0; i < 3; ++i) a[i] = sv[i].varyings[in.varying][in.component];
    if (in.wrap) {
      wrapTowards(a[0], a[1]);
      wrapTowards(a[0], a[2]);
    }
    for (int i = 0; i < 3; ++i) a[i] *= sv[i].invW;
    addPlane(out.planes, a[0], a[1], a[2], x1, y1, x2, y2, det);
  }
  out.prims.push_back(p);
}

void setupLine(const RasterDraw& d, PrimitiveList out, const SetupVertex& a, const SetupVertex& b, const Rect& bounds,
               bool flat) {
  const float dx = b.x - a.x, dy = b.y - a.y;
  if (dx == 0 && dy == 0) return;
  Primitive p{};
  p.kind = PrimKind::Line;
  p.xMajor = std::fabs(dx) >= std::fabs(dy);
  const float amaj = p.xMajor ? a.x : a.y, bmaj = p.xMajor ? b.x : b.y;
  const float amin = p.xMajor ? a.y : a.x, bmin = p.xMajor ? b.y : b.x;
  p.lineM = (bmin - amin) / (bmaj - amaj);
  p.lineQ = amin - p.lineM * amaj;
  const int lo = int(std::floor(std::min(amaj, bmaj) + 0.5f)), hi = int(std::floor(std::max(amaj, bmaj) + 0.5f));
  const int mlo = int(std::floor(std::min(amin, bmin) - 1)), mhi = int(std::ceil(std::max(amin, bmin) + 1));
  p.minX = std::max(bounds.left, p.xMajor ? lo : mlo);
  p.maxX = std::min(bounds.right - 1, p.xMajor ? hi : mhi);
  p.minY = std::max(bounds.top, p.xMajor ? mlo : lo);
  p.maxY = std::min(bounds.bottom - 1, p.xMajor ? mhi : hi);
  if (p.minX > p.maxX || p.minY > p.maxY) return;
  p.originX = a.x;
  p.originY = a.y;
  p.planeOffset = uint32_t(out.planes.size());
  p.wDepthOffset = a.wDepthOffset;
  const float len = bmaj - amaj;
  auto plane = [&](double va, double vb) {
    out.planes.push_back(float(va));
    const float g = float((vb - va) / len);
    out.planes.push_back(p.xMajor ? g : 0.0f);
    out.planes.push_back(p.xMajor ? 0.0f : g);
  };
  plane(a.invW, b.invW);
  plane(a.z, b.z);
  for (const InterpolatedInput& in : d.inputs) {
    if (in.flat) {
      plane(a.varyings[in.varying][in.component], a.varyings[in.varying][in.component]);
      continue;
    }
    double va = a.varyings[in.varying][in.component], vb = b.varyings[in.varying][in.component];
    if (in.wrap) wrapTowards(va, vb);
    plane(va * a.invW, vb * b.invW);
  }
  out.prims.push_back(p);
}

// A point is a screen-aligned square of side `size` centred on the vertex; it covers
// the pixels whose centres lie in [x - size/2, x + size/2) x [y - size/2, y + size/2)
// (the top-left rule of two triangles covering the square). With `sprite`
// (D3DRS_POINTSPRITEENABLE) texture coordinates u, v of every set run across the
// square, (0,0) at its top-left corner to (1,1) at its bottom-right; otherwise all
// inputs keep the vertex's values.
void setupPoint(const RasterDraw& d, PrimitiveList out, const SetupVertex& a, float size, const Rect& bounds,
                bool sprite) {
  if (!std::isfinite(a.x) || !std::isfinite(a.y)) return;
  Primitive p{};
  p.kind = PrimKind::Point;
  size = size >= 1.0f ? size : 1.0f;  // NaN too
  const float h = size * 0.5f;
  // Clamped as floats: far-away (guard band) or huge points stay in int range.
  auto clampTo = [](float v, int lo, int hi) { return v <= float(lo) ? lo : v >= float(hi) ? hi : int(v); };
  p.minX = clampTo(std::ceil(a.x - h), bounds.left, bounds.right);
  p.maxX = clampTo(std::ceil(a.x + h) - 1, bounds.left - 1, bounds.right - 1);
  p.minY = clampTo(std::ceil(a.y - h), bounds.top, bounds.bottom);
  p.maxY = clampTo(std::ceil(a.y + h) - 1, bounds.top - 1, bounds.bottom - 1);
  if (p.minX > p.maxX || p.minY > p.maxY) return;
  p.originX = a.x;
  p.originY = a.y;
  p.planeOffset = uint32_t(out.planes.size());
  p.wDepthOffset = a.wDepthOffset;
  auto plane = [&](float v, float dx, float dy) {
    out.planes.push_back(v);
    out.planes.push_back(dx);
    out.planes.push_back(dy);
  };
  plane(a.invW, 0, 0);
  plane(a.z, 0, 0);
  for (const InterpolatedInput& in : d.inputs) {
    const float scale = in.flat ? 1.0f : a.invW;  // non-flat planes hold value/w
    const bool texCoord = in.varying >= kVertexOutTex0 && in.varying < kVertexOutTex0 + 8;
    if (sprite && texCoord && in.component < 2) {
      // At the centre 0.5, one unit across the side.
      const float step = scale / size;
      plane(0.5f * scale, in.component == 0 ? step : 0.0f, in.component == 1 ? step : 0.0f);
      continue;
    }
    plane(a.varyings[in.varying][in.component] * scale, 0, 0);
  }
  out.prims.push_back(p);
}


}  // namespace

Rect activeRect(const DeviceState& s, int w, int h) {
  Rect r{std::max(0, s.viewport.x), std::max(0, s.viewport.y),
         std::min(w, s.viewport.x + s.viewport.width), std::min(h, s.viewport.y + s.viewport.height)};
  if (s.rs(RS_SCISSORTESTENABLE)) {
    r.left = std::max(r.left, s.scissor.left);
    r.top = std::max(r.top, s.scissor.top);
    r.right = std::min(r.right, s.scissor.right);
    r.bottom = std::min(r.bottom, s.scissor.bottom);
  }
  return r;
}

namespace {

// RasterDraw::inputCopies: inputs that receive the same value at every vertex (a vertex
// shader's mov oT0.xy, v7 and mov oT1.xy, v7) get the same planes, as clipping and setup
// treat every varying alike; point sprites replace texture coordinates, so none there.
void findInputCopies(RasterDraw& d, const std::vector<ShadedVertex>& verts, bool sprites) {
  d.inputCopies.assign(d.inputs.size(), -1);
  if (sprites) return;
  for (size_t k = 1; k < d.inputs.size(); ++k) {
    const InterpolatedInput& b = d.inputs[k];
    for (size_t j = 0; j < k && d.inputCopies[k] < 0; ++j) {
      const InterpolatedInput& a = d.inputs[j];
      if (d.inputCopies[j] >= 0 || a.flat != b.flat || a.wrap != b.wrap) continue;
      bool same = true;
      for (const ShadedVertex& v : verts) {
        const float x = v.out[a.varying][a.component], y = v.out[b.varying][b.component];
        if (std::memcmp(&x, &y, sizeof x) != 0) {
          same = false;
          break;
        }
      }
      if (same) d.inputCopies[k] = int(j);
    }
  }
}

}  // namespace

// Draws with fewer primitives are set up by one thread.
constexpr uint32_t kParallelSetupPrimitives = 512;
// The most primitives a draw's (or a range's) lists are reserved for up front.
constexpr size_t kReservedPrimitives = size_t(1) << 16;

void setupPrimitives(const DrawPlan& plan, const DeviceState& st, float maxPointSize,
                     PrimitiveType type, uint32_t primitiveCount, const DrawIndices& indices,
                     const std::vector<ShadedVertex>& verts, RasterDraw& d, ThreadPool& pool) {
  const std::vector<uint32_t>& idx = indices.idx;
  const uint32_t lo = indices.lo;
  const FixedFunctionVertexConfig& vcfg = plan.vertexConfig;
  const bool flat = plan.flat;
  const Rect bounds = activeRect(st, d.width, d.height);
  const Viewport& vp = st.viewport;
  const float gb = std::max(1.0f, 16384.0f / float(std::max({vp.width, vp.height, 1})));
  const uint32_t cull = st.rs(RS_CULLMODE);
  const uint32_t fill = st.rs(RS_FILLMODE);
  // Point size: D3DRS_POINTSIZE clamped to POINTSIZE_MIN/MAX, or the vertex's own
  // size (fixed-function T&L computes and clamps it, with POINTSCALEENABLE; a vertex
  // shader's oPts is clamped here), finally limited to the caps' MaxPointSize.
  const float sizeMin = st.rsFloat(RS_POINTSIZE_MIN);
  const float sizeMax = std::max(sizeMin, st.rsFloat(RS_POINTSIZE_MAX));
  const float deviceMaxPointSize = std::max(maxPointSize, 1.0f);
  const float renderStatePointSize = std::clamp(st.rsFloat(RS_POINTSIZE), sizeMin, sizeMax);
  const bool vertexPointSize = plan.vertexPointSize;
  auto pointSizeOf = [&](const Vec4* out) {
    const float size = vertexPointSize ? std::clamp(out[kVertexOutPSize].x, sizeMin, sizeMax)
                                       : renderStatePointSize;
    return size >= 1.0f ? std::min(size, deviceMaxPointSize) : 1.0f;  // NaN: 1
  };
  const bool pointSprite = st.rs(RS_POINTSPRITEENABLE) != 0;
  findInputCopies(d, verts, pointSprite);
  // Room for the primitives before clipping (a triangle's invW, z and input planes), up
  // to a bound: the lists of most draws grow without copies, and a huge draw, culled
  // mostly, does not reserve for all its primitives.
  const auto reserveFor = [&](uint32_t count, std::vector<Primitive>& prims, std::vector<float>& planes) {
    const size_t n = std::min<size_t>(count, kReservedPrimitives);
    prims.reserve(prims.size() + n);
    planes.reserve(planes.size() + n * 3 * (2 + d.inputs.size()));
  };
  reserveFor(primitiveCount, d.prims, d.planes);  // all of them end in the draw's lists

  auto toScreen = [&](const Vec4* out, SetupVertex& s) {
    const Vec4& p = out[0];
    if (vcfg.pretransformed) {
      // XYZRHW: already in screen space; rhw is 1/w for perspective interpolation.
      s.x = p.x;
      s.y = p.y;
      s.z = p.z;
      s.invW = p.w != 0 ? p.w : 1.0f;
    } else {
      const float iw = 1.0f / p.w;
      s.x = float(vp.x) + (1.0f + p.x * iw) * 0.5f * float(vp.width);
      s.y = float(vp.y) + (1.0f - p.y * iw) * 0.5f * float(vp.height);
      s.z = vp.minZ + p.z * iw * (vp.maxZ - vp.minZ);
      s.invW = iw;
    }
    s.varyings = out;
  };
  auto vertexOut = [&](uint32_t i) -> const Vec4* { return verts[i - lo].out; };
  // Near/far, the guard band and the user clip planes. Pretransformed vertices are
  // not clipped (they have no clip space; D3DPMISCCAPS_CLIPTLVERTS concerns the
  // viewport, which the rasterizer's bounds already enforce).
  ClipPlanes clip;
  clip.guardBand = gb;
  if (!vcfg.pretransformed) userClipPlanes(st, plan.vertexShader != nullptr, clip);

  // Triangles share vertices: each one's screen position and whether it needs clipping,
  // once per vertex.
  const bool triangles = type == PT_TRIANGLELIST || type == PT_TRIANGLESTRIP || type == PT_TRIANGLEFAN;
  std::vector<SetupVertex> screen(triangles ? verts.size() : 0);
  std::vector<uint8_t> needsClip(screen.size(), 0);
  for (size_t i = 0; i < screen.size(); ++i) {
    toScreen(verts[i].out, screen[i]);
    needsClip[i] = !vcfg.pretransformed && clip.outside(verts[i].out[0]);
  }

  // The primitives [begin, end) into `out`, with `poly` to clip in.
  auto setupRange = [&](uint32_t begin, uint32_t end, PrimitiveList out, std::vector<ClipVertex>& poly) {
    auto triangle = [&](uint32_t i0, uint32_t i1, uint32_t i2) {
      auto emitScreen = [&](SetupVertex (&sv)[3]) {
        const Vec4* a = sv[0].varyings;
        const Vec4* b = sv[1].varyings;
        const Vec4* c = sv[2].varyings;
        if (fill == FILL_SOLID) {
          setupTriangle(d, out, sv, cull, bounds, flat);
          return;
        }
        // Wireframe/point fill: cull first, then draw edges or vertices.
        const double area = double(sv[1].x - sv[0].x) * (sv[2].y - sv[0].y) -
                            double(sv[2].x - sv[0].x) * (sv[1].y - sv[0].y);
        if (area == 0 || (cull == CULL_CCW && area < 0) || (cull == CULL_CW && area > 0)) return;
        if (d.depthBias != 0 || d.slopeScaleDepthBias != 0) {
          // The triangle's depth offset applies to its edges and vertices as well.
          const double x1 = sv[1].x - sv[0].x, y1 = sv[1].y - sv[0].y;
          const double x2 = sv[2].x - sv[0].x, y2 = sv[2].y - sv[0].y;
          const double z0 = bufferDepth(d, sv[0]);
          const double z1 = bufferDepth(d, sv[1]) - z0, z2 = bufferDepth(d, sv[2]) - z0;
          const float offset = depthOffset(d.depthBias, d.slopeScaleDepthBias,
                                           float((z1 * y2 - z2 * y1) / area), float((z2 * x1 - z1 * x2) / area));
          for (SetupVertex& v : sv) (d.wBuffer ? v.wDepthOffset : v.z) += offset;
        }
        if (fill == FILL_WIREFRAME) {
          setupLine(d, out, sv[0], sv[1], bounds, flat);
          setupLine(d, out, sv[1], sv[2], bounds, flat);
          setupLine(d, out, sv[2], sv[0], bounds, flat);
        } else {
          const Vec4* outs[3] = {a, b, c};
          for (int k = 0; k < 3; ++k) setupPoint(d, out, sv[k], pointSizeOf(outs[k]), bounds, pointSprite);
        }
      };
      auto emit = [&](const Vec4* a, const Vec4* b, const Vec4* c) {
        SetupVertex sv[3];
        toScreen(a, sv[0]);
        toScreen(b, sv[1]);
        toScreen(c, sv[2]);
        emitScreen(sv);
      };
      const uint32_t v0 = i0 - lo, v1 = i1 - lo, v2 = i2 - lo;
      if (!needsClip[v0] && !needsClip[v1] && !needsClip[v2]) {
        SetupVertex sv[3] = {screen[v0], screen[v1], screen[v2]};
        emitScreen(sv);
        return;
      }
      const Vec4* o[3] = {vertexOut(i0), vertexOut(i1), vertexOut(i2)};
      poly.assign(3, {});
      for (int k = 0; k < 3; ++k) std::memcpy(poly[k].v, o[k], sizeof(poly[k].v));
      clipPolygon(poly, clip);
      for (size_t k = 2; k < poly.size(); ++k) {
        // Clipped vertices keep the provoking (first) vertex's flat colors.
        emit(poly[0].v, poly[k - 1].v, poly[k].v);
      }
    };
    auto line = [&](uint32_t i0, uint32_t i1) {
      const Vec4* a = vertexOut(i0);
      const Vec4* b = vertexOut(i1);
      SetupVertex sa, sb;
      ClipVertex ca, cb;  // outlive the setup: SetupVertex points at their varyings
      if (!vcfg.pretransformed && (clip.outside(a[0]) || clip.outside(b[0]))) {
        if (!clipSegment(a, b, clip, ca, cb)) return;
        toScreen(ca.v, sa);
        toScreen(cb.v, sb);
      } else {
        toScreen(a, sa);
        toScreen(b, sb);
      }
      setupLine(d, out, sa, sb, bounds, flat);
    };
    auto point = [&](uint32_t i) {
      const Vec4* a = vertexOut(i);
      // A point whose centre is outside the view volume is culled whole.
      if (!vcfg.pretransformed && clip.outsideVolume(a[0])) return;
      const float size = pointSizeOf(a);
      if (!vcfg.pretransformed && clip.userCount) {
        // User planes clip the point's square like a polygon
        // (D3DPMISCCAPS_CLIPPLANESCALEDPOINTS): the corners, then two triangles per
        // clipped piece, with the same coverage rule and constant (or sprite) values.
        const float side = std::max(size, 1.0f) * a[0].w;  // half side * 2w
        ClipVertex corners[4];
        pointCorners(a, side / float(vp.width), side / float(vp.height), pointSprite, corners);
        bool inside = true;
        for (const ClipVertex& c : corners) inside &= clip.insideUser(c.v[0]);
        if (!inside) {
          poly.assign(corners, corners + 4);
          clipPolygon(poly, clip);
          for (size_t k = 2; k < poly.size(); ++k) {
            SetupVertex sv[3];
            toScreen(poly[0].v, sv[0]);
            toScreen(poly[k - 1].v, sv[1]);
            toScreen(poly[k].v, sv[2]);
            setupTriangle(d, out, sv, CULL_NONE, bounds, flat, false);
          }
          return;
        }
      }
      SetupVertex s;
      toScreen(a, s);
      setupPoint(d, out, s, size, bounds, pointSprite);
    };

    switch (type) {
      case PT_POINTLIST:
        for (uint32_t i = begin; i < end; ++i) point(idx[i]);
        break;
      case PT_LINELIST:
        for (uint32_t i = begin; i < end; ++i) line(idx[2 * i], idx[2 * i + 1]);
        break;
      case PT_LINESTRIP:
        for (uint32_t i = begin; i < end; ++i) line(idx[i], idx[i + 1]);
        break;
      case PT_TRIANGLELIST:
        for (uint32_t i = begin; i < end; ++i) triangle(idx[3 * i], idx[3 * i + 1], idx[3 * i + 2]);
        break;
      case PT_TRIANGLESTRIP:
        // Odd triangles swap two vertices to keep the winding consistent.
        for (uint32_t i = begin; i < end; ++i) {
          if (i & 1) triangle(idx[i + 1], idx[i], idx[i + 2]);
          else triangle(idx[i], idx[i + 1], idx[i + 2]);
        }
        break;
      case PT_TRIANGLEFAN:
        // D3D's provoking vertex for flat shading in a fan is the second vertex of each
        // triangle (v[i+1]); start the triangle there.
        for (uint32_t i = begin; i < end; ++i) triangle(idx[i + 1], idx[i + 2], idx[0]);
        break;
    }
  };
  const int threads = pool.threadCount();
  if (threads < 2 || primitiveCount < kParallelSetupPrimitives) {
    std::vector<ClipVertex> poly;
    setupRange(0, primitiveCount, {d.prims, d.planes}, poly);
    return;
  }
  // Consecutive ranges, one per thread: the first into the draw's lists, the others
  // into their own, appended in order after (their plane offsets moved by the planes
  // before them), so the draw's lists are those of one thread.
  std::vector<std::vector<Primitive>> prims(size_t(threads - 1));
  std::vector<std::vector<float>> planes(size_t(threads - 1));
  pool.parallelFor(size_t(threads), [&](size_t c, int) {
    const uint32_t begin = uint32_t(uint64_t(primitiveCount) * c / size_t(threads));
    const uint32_t end = uint32_t(uint64_t(primitiveCount) * (c + 1) / size_t(threads));
    std::vector<ClipVertex> poly;
    if (c == 0) {
      setupRange(begin, end, {d.prims, d.planes}, poly);
      return;
    }
    reserveFor(end - begin, prims[c - 1], planes[c - 1]);
    setupRange(begin, end, {prims[c - 1], planes[c - 1]}, poly);
  });
  for (size_t c = 0; c + 1 < size_t(threads); ++c) {
    const uint32_t offset = uint32_t(d.planes.size());
    for (Primitive& p : prims[c]) p.planeOffset += offset;
    d.prims.insert(d.prims.end(), prims[c].begin(), prims[c].end());
    d.planes.insert(d.planes.end(), planes[c].begin(), planes[c].end());
  }
}

}  // namespace refx::pipeline
