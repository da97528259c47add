// ComputeTangentFrame / ComputeTangent. Per face, with e1 = p1 - p0, e2 = p2 - p0,
// (s1,t1) = uv1 - uv0, (s2,t2) = uv2 - uv0 and det = s1 t2 - s2 t1:
//   dP/du = (e1 t2 - e2 t1) / det,  dP/dv = (e2 s1 - e1 s2) / det.
// D3D texture space has v growing downward, so on a surface seen upright the
// binormal (dP/dv) points down. The face normal is cross(e1, e2), toward the viewer
// for clockwise front faces.
#include <gtest/gtest.h>

#include <cmath>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/mesh.h"
#include "refx/d3dx/mesh_ops.h"

using namespace refx;
using namespace refx::d3dx;

namespace {

void expectVec(Vec3 v, Vec3 e, float eps = 1e-5f) {
  EXPECT_NEAR(v.x, e.x, eps);
  EXPECT_NEAR(v.y, e.y, eps);
  EXPECT_NEAR(v.z, e.z, eps);
}

Vec3 xyz(Vec4 v) { return {v.x, v.y, v.z}; }

bool finite(Vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

struct V {
  Vec3 p;
  float u, v;
};

Mesh makeMesh(uint32_t fvfCode, const std::vector<V>& verts, const std::vector<uint32_t>& idx) {
  Mesh m(fvfCode, uint32_t(verts.size()), uint32_t(idx.size() / 3));
  for (uint32_t i = 0; i < verts.size(); ++i) {
    m.setPosition(i, verts[i].p);
    m.setTexCoord(i, 0, verts[i].u, verts[i].v);
  }
  m.indices = idx;
  return m;
}

// Unit quad facing a viewer at -z, texture upright: TL (0,1,0) uv (0,0), TR
// (1,1,0) uv (1,0), BL (0,0,0) uv (0,1), BR (1,0,0) uv (1,1); faces TL TR BL, TR BR BL.
Mesh texturedQuad(uint32_t fvfCode) {
  return makeMesh(fvfCode, {{{0, 1, 0}, 0, 0}, {{1, 1, 0}, 1, 0}, {{0, 0, 0}, 0, 1}, {{1, 0, 0}, 1, 1}},
                  {0, 1, 2, 1, 3, 2});
}

// Every used vertex: finite, unit tangent / binormal / normal, mutually orthogonal.
void expectOrthonormal(const Mesh& m, int tSet, int bSet, float eps = 1e-5f) {
  std::vector<bool> used(m.vertexCount());
  for (uint32_t i : m.indices) used[i] = true;
  for (uint32_t i = 0; i < m.vertexCount(); ++i) {
    if (!used[i]) continue;
    Vec3 t = xyz(m.texCoord(i, tSet)), b = xyz(m.texCoord(i, bSet)), n = m.normal(i);
    ASSERT_TRUE(finite(t) && finite(b) && finite(n)) << "vertex " << i;
    EXPECT_NEAR(length(t), 1, eps) << "vertex " << i;
    EXPECT_NEAR(length(b), 1, eps) << "vertex " << i;
    EXPECT_NEAR(length(n), 1, eps) << "vertex " << i;
    EXPECT_NEAR(dot(t, n), 0, eps) << "vertex " << i;
    EXPECT_NEAR(dot(b, n), 0, eps) << "vertex " << i;
    EXPECT_NEAR(dot(t, b), 0, eps) << "vertex " << i;
  }
}

}  // namespace

TEST(TangentFrame, UnitQuad) {
  // Face 0: e1 = (1,0,0), e2 = (0,-1,0), (s1,t1) = (1,0), (s2,t2) = (0,1), det = 1:
  // dP/du = e1*1 - e2*0 = (1,0,0); dP/dv = e2*1 - e1*0 = (0,-1,0) (v grows downward);
  // normal = cross(e1, e2) = (0,0,-1). Face 1: e1 = (0,-1,0), e2 = (-1,-1,0),
  // (s1,t1) = (0,1), (s2,t2) = (-1,1), det = 0*1 - (-1)*1 = 1:
  // dP/du = (0,-1,0) - (-1,-1,0) = (1,0,0); dP/dv = (-1,-1,0)*0 - (0,-1,0)*(-1) = (0,-1,0).
  Mesh m = texturedQuad(d3d::FVF_XYZ | d3d::fvfTex(1));
  TangentFrameOptions o;
  o.flags = TANGENT_CALCULATE_NORMALS;
  o.tangentOut = 1;
  o.binormalOut = 2;
  std::vector<uint32_t> mapping = computeTangentFrame(m, o);
  EXPECT_EQ(mapping, (std::vector<uint32_t>{0, 1, 2, 3}));
  // Normal and the two float3 sets were added.
  EXPECT_EQ(m.fvf, d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(3) | d3d::fvfTexCoordSize(3, 1) |
                       d3d::fvfTexCoordSize(3, 2));
  for (uint32_t i = 0; i < 4; ++i) {
    expectVec(m.normal(i), {0, 0, -1});
    expectVec(xyz(m.texCoord(i, 1)), {1, 0, 0});
    expectVec(xyz(m.texCoord(i, 2)), {0, -1, 0});
    EXPECT_EQ(m.texCoord(i, 0).x, (i & 1) ? 1.0f : 0.0f);  // the input set is kept
  }
  // Handedness: cross(n, t) = cross((0,0,-1), (1,0,0)) = (0,-1,0) = b, so h = +1.
  // Each orthogonalization mode agrees on an orthonormal mapping.
  for (uint32_t flags : {TANGENT_ORTHOGONALIZE_FROM_U, TANGENT_ORTHOGONALIZE_FROM_V,
                         TANGENT_DONT_ORTHOGONALIZE}) {
    Mesh q = texturedQuad(d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(1));
    for (uint32_t i = 0; i < 4; ++i) q.setNormal(i, {0, 0, -1});
    o.flags = flags;
    computeTangentFrame(q, o);
    for (uint32_t i = 0; i < 4; ++i) {
      expectVec(xyz(q.texCoord(i, 1)), {1, 0, 0});
      expectVec(xyz(q.texCoord(i, 2)), {0, -1, 0});
    }
  }
}

TEST(TangentFrame, FourFloatTangentSetReceivesHandedness) {
  Mesh m = texturedQuad(d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(2) | d3d::fvfTexCoordSize(4, 1));
  TangentFrameOptions o;
  o.flags = TANGENT_CALCULATE_NORMALS;
  computeTangentFrame(m, o);
  for (uint32_t i = 0; i < 4; ++i) {
    Vec4 t = m.texCoord(i, 1);
    expectVec(xyz(t), {1, 0, 0});
    EXPECT_EQ(t.w, 1.0f);
  }
}

TEST(TangentFrame, CubeFacesHaveTheirOwnFrames) {
  // Faces as (outward n, right r, down d) seen from outside, r x d = n; each face
  // has its own 4 vertices TL = n-r-d (0,0), TR = n+r-d (1,0), BL = n-r+d (0,1),
  // BR = n+r+d (1,1). With e1 = TR - TL = 2r, e2 = BL - TL = 2d, det = 1:
  // dP/du = 2r, dP/dv = 2d, normal along cross(2r, 2d) = 4n: t = r, b = d, n = n.
  struct Face {
    Vec3 n, r, d;
  } faces[6] = {
      {{1, 0, 0}, {0, 0, 1}, {0, -1, 0}},   {{-1, 0, 0}, {0, 0, -1}, {0, -1, 0}},
      {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},   {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
      {{0, 0, 1}, {-1, 0, 0}, {0, -1, 0}},  {{0, 0, -1}, {1, 0, 0}, {0, -1, 0}},
  };
  std::vector<V> verts;
  std::vector<uint32_t> idx;
  for (const Face& f : faces) {
    uint32_t b = uint32_t(verts.size());
    verts.push_back({f.n - f.r - f.d, 0, 0});
    verts.push_back({f.n + f.r - f.d, 1, 0});
    verts.push_back({f.n - f.r + f.d, 0, 1});
    verts.push_back({f.n + f.r + f.d, 1, 1});
    idx.insert(idx.end(), {b, b + 1, b + 2, b + 1, b + 3, b + 2});
  }
  Mesh m = makeMesh(d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(1), verts, idx);
  TangentFrameOptions o;
  o.flags = TANGENT_CALCULATE_NORMALS;
  o.binormalOut = 2;
  computeTangentFrame(m, o);
  ASSERT_EQ(m.vertexCount(), 24u);
  for (uint32_t f = 0; f < 6; ++f)
    for (uint32_t k = 0; k < 4; ++k) {
      uint32_t i = 4 * f + k;
      expectVec(m.normal(i), faces[f].n);
      expectVec(xyz(m.texCoord(i, 1)), faces[f].r);
      expectVec(xyz(m.texCoord(i, 2)), faces[f].d);
    }
}

TEST(TangentFrame, TexturedSphereTangentsFollowU) {
  // createTexturedSphere puts vertex (row, col) at n = (-sin(theta) sin(phi),
  // cos(theta), sin(theta) cos(phi)), theta = pi row / stacks, phi = 2 pi col / slices,
  // u = col / slices, v = row / stacks. The computed tangent (set 2) must be
  // orthogonal to the stored normal and point east, along dP/du = 2 pi dn/dphi
  // = 2 pi sin(theta) (-cos(phi), 0, -sin(phi)); the binormal (set 3) south, along
  // dP/dv = pi dn/dtheta = pi (-cos(theta) sin(phi), -sin(theta), cos(theta) cos(phi)).
  // Seen from outside with north up, east is right and south down, so
  // b = +cross(n, t) (as on the upright quad): h = +1.
  const uint32_t slices = 32, stacks = 16;
  Mesh m = createTexturedSphere(1.5f, slices, stacks);
  TangentFrameOptions o;
  o.tangentOut = 2;
  o.binormalOut = 3;
  std::vector<uint32_t> mapping = computeTangentFrame(m, o);
  ASSERT_EQ(mapping.size(), m.vertexCount());  // no mirrored faces: nothing split
  expectOrthonormal(m, 2, 3);
  std::vector<bool> used(m.vertexCount());
  for (uint32_t i : m.indices) used[i] = true;
  const float kPi = 3.14159265358979f;
  for (uint32_t i = 0; i < m.vertexCount(); ++i) {
    if (!used[i]) continue;  // the pole vertex of the first / last column
    Vec3 t = xyz(m.texCoord(i, 2)), b = xyz(m.texCoord(i, 3)), n = m.normal(i);
    uint32_t row = i / (slices + 1), col = i % (slices + 1);
    float theta = kPi * float(row) / stacks, phi = 2 * kPi * float(col) / slices;
    Vec3 east{-std::cos(phi), 0, -std::sin(phi)};
    Vec3 south{-std::cos(theta) * std::sin(phi), -std::sin(theta), std::cos(theta) * std::cos(phi)};
    // Within half a slice (5.6 degrees) of the analytic directions.
    EXPECT_GT(dot(t, east), 0.99f) << "vertex " << i;
    EXPECT_GT(dot(b, south), 0.99f) << "vertex " << i;
    EXPECT_GT(dot(cross(n, t), b), 0.999f) << "vertex " << i;
  }
}

TEST(TangentFrame, LegacyComputeTangentMatches) {
  Mesh m = createTexturedSphere(1, 24, 12);
  Mesh framed = m;
  TangentFrameOptions o;
  o.tangentOut = 1;
  computeTangentFrame(framed, o);
  computeTangent(m, 0, 1, -1, false);
  for (uint32_t i = 0; i < m.vertexCount(); ++i)
    expectVec(xyz(m.texCoord(i, 1)), xyz(framed.texCoord(i, 1)));
  EXPECT_THROW(computeTangent(m, 0, -1, -1, false), Error);
  EXPECT_THROW(computeTangent(m, 0, 1, 1, false), Error);
}

TEST(TangentFrame, WrapTakesTheShortWayAcrossTheSeam) {
  // The quad's u runs 0.9 -> 0.1 left to right: across the u = 1 seam when wrapped.
  // Face 0: s1 = 0.1 - 0.9 = -0.8, or with WRAP_U -0.8 + 1 = 0.2; t1 = 0, (s2,t2) = (0,1).
  // Unwrapped: det = -0.8, dP/du = (1,0,0) / -0.8 -> t = (-1,0,0);
  // wrapped:   det = 0.2,  dP/du = (1,0,0) / 0.2  -> t = (1,0,0).
  std::vector<V> verts = {{{0, 1, 0}, 0.9f, 0}, {{1, 1, 0}, 0.1f, 0}, {{0, 0, 0}, 0.9f, 1}, {{1, 0, 0}, 0.1f, 1}};
  Mesh plain = makeMesh(d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(2) | d3d::fvfTexCoordSize(3, 1), verts, {0, 1, 2, 1, 3, 2});
  for (uint32_t i = 0; i < 4; ++i) plain.setNormal(i, {0, 0, -1});
  Mesh wrapped = plain;
  computeTangent(plain, 0, 1, -1, false);
  computeTangent(wrapped, 0, 1, -1, true);
  for (uint32_t i = 0; i < 4; ++i) {
    expectVec(xyz(plain.texCoord(i, 1)), {-1, 0, 0});
    expectVec(xyz(wrapped.texCoord(i, 1)), {1, 0, 0});
  }
}

TEST(TangentFrame, MirroredHalvesAreSplitNotAveraged) {
  // Two quads side by side sharing the middle column (x = 1): u runs 0 -> 1 on the
  // left and back 1 -> 0 on the right (a mirrored texture), v down as usual.
  // Left faces: t = (1,0,0), b = (0,-1,0), h = +1 as the unit quad. Right faces:
  // dP/du = (-1,0,0) with det < 0, b = (0,-1,0) = h cross((0,0,-1), (-1,0,0))
  // = h (0,1,0) so h = -1. Averaging the middle vertices would give t = 0.
  // With equal weights the heavier side of a middle vertex is the one with more
  // triangles there: vertex 1 is in 2 left and 1 right triangle (it stays left, the
  // right faces get copy 6), vertex 4 in 1 left and 2 right (it stays right, the
  // left face gets copy 7).
  std::vector<V> verts = {{{0, 1, 0}, 0, 0}, {{1, 1, 0}, 1, 0}, {{2, 1, 0}, 0, 0},
                          {{0, 0, 0}, 0, 1}, {{1, 0, 0}, 1, 1}, {{2, 0, 0}, 0, 1}};
  std::vector<uint32_t> idx = {0, 1, 3, 1, 4, 3,   // left quad
                               1, 2, 4, 2, 5, 4};  // right quad
  uint32_t f = d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(3) | d3d::fvfTexCoordSize(4, 1) | d3d::fvfTexCoordSize(3, 2);
  Mesh m = makeMesh(f, verts, idx);
  TangentFrameOptions o;
  o.flags = TANGENT_CALCULATE_NORMALS | TANGENT_WEIGHT_EQUAL;
  o.binormalOut = 2;
  std::vector<uint32_t> mapping = computeTangentFrame(m, o);
  EXPECT_EQ(mapping, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 1, 4}));
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 3, 1, 7, 3, 6, 2, 4, 2, 5, 4}));
  ASSERT_EQ(m.vertexCount(), 8u);
  for (uint32_t i : {0u, 1u, 3u, 7u}) {
    expectVec(xyz(m.texCoord(i, 1)), {1, 0, 0});
    EXPECT_EQ(m.texCoord(i, 1).w, 1.0f);
  }
  for (uint32_t i : {2u, 4u, 5u, 6u}) {
    expectVec(xyz(m.texCoord(i, 1)), {-1, 0, 0});
    EXPECT_EQ(m.texCoord(i, 1).w, -1.0f);
  }
  for (uint32_t i = 0; i < 8; ++i) {
    expectVec(xyz(m.texCoord(i, 2)), {0, -1, 0});
    expectVec(m.normal(i), {0, 0, -1});
  }
  expectVec(m.position(6), {1, 1, 0});
  expectVec(m.position(7), {1, 0, 0});

  // In place nothing is split: each middle vertex keeps its heavier side's frame.
  Mesh inPlace = makeMesh(f, verts, idx);
  o.flags = TANGENT_CALCULATE_NORMALS | TANGENT_WEIGHT_EQUAL | TANGENT_GENERATE_IN_PLACE;
  mapping = computeTangentFrame(inPlace, o);
  EXPECT_EQ(mapping.size(), 6u);
  EXPECT_EQ(inPlace.indices, idx);
  expectVec(xyz(inPlace.texCoord(1, 1)), {1, 0, 0});
  expectVec(xyz(inPlace.texCoord(4, 1)), {-1, 0, 0});
  expectVec(xyz(inPlace.texCoord(2, 1)), {-1, 0, 0});
  expectOrthonormal(inPlace, 1, 2);
}

TEST(TangentFrame, MirroredTriangleInAQuad) {
  // The unit quad with BR at u = -1: face 1 (TR BR BL) has e1 = (0,-1,0),
  // e2 = (-1,-1,0), (s1,t1) = (-2,1), (s2,t2) = (-1,1), det = -2 + 1 = -1 (mirrored),
  // dP/du = ((0,-1,0) - (-1,-1,0)) / -1 = (-1,0,0). TR and BL are shared by both
  // faces with 45 degrees each (equal: the positive side keeps them): they are split.
  // ORTHOGONALIZE_FROM_U keeps dP/du as it is.
  Mesh m = makeMesh(d3d::FVF_XYZ | d3d::fvfTex(1),
                    {{{0, 1, 0}, 0, 0}, {{1, 1, 0}, 1, 0}, {{0, 0, 0}, 0, 1}, {{1, 0, 0}, -1, 1}},
                    {0, 1, 2, 1, 3, 2});
  TangentFrameOptions o;
  o.flags = TANGENT_CALCULATE_NORMALS | TANGENT_ORTHOGONALIZE_FROM_U;
  o.binormalOut = 2;
  std::vector<uint32_t> mapping = computeTangentFrame(m, o);
  EXPECT_EQ(mapping, (std::vector<uint32_t>{0, 1, 2, 3, 1, 2}));
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 4, 3, 5}));
  expectOrthonormal(m, 1, 2);
  for (uint32_t i : {0u, 1u, 2u}) expectVec(xyz(m.texCoord(i, 1)), {1, 0, 0});
  for (uint32_t i : {3u, 4u, 5u}) expectVec(xyz(m.texCoord(i, 1)), {-1, 0, 0});
}

TEST(TangentFrame, DegenerateBasesAreFixed) {
  TangentFrameOptions o;
  o.flags = TANGENT_CALCULATE_NORMALS;
  o.binormalOut = 2;
  // Zero area in texture space (every vertex at uv (0.5, 0.5)): no partials. The
  // tangent is the axis least aligned with n = (0,0,-1) (x, the first of x and y),
  // b = cross(n, t) = cross((0,0,-1), (1,0,0)) = (0,-1,0).
  Mesh flat = makeMesh(d3d::FVF_XYZ | d3d::fvfTex(1),
                       {{{0, 1, 0}, 0.5f, 0.5f}, {{1, 1, 0}, 0.5f, 0.5f}, {{0, 0, 0}, 0.5f, 0.5f},
                        {{1, 0, 0}, 0.5f, 0.5f}},
                       {0, 1, 2, 1, 3, 2});
  computeTangentFrame(flat, o);
  expectOrthonormal(flat, 1, 2);
  for (uint32_t i = 0; i < 4; ++i) {
    expectVec(flat.normal(i), {0, 0, -1});
    expectVec(xyz(flat.texCoord(i, 1)), {1, 0, 0});
    expectVec(xyz(flat.texCoord(i, 2)), {0, -1, 0});
  }
  // Collinear positions: no normal, no partials. Still a unit orthonormal frame.
  Mesh line = makeMesh(d3d::FVF_XYZ | d3d::fvfTex(1), {{{0, 0, 0}, 0, 0}, {{1, 0, 0}, 1, 0}, {{2, 0, 0}, 0, 1}},
                       {0, 1, 2});
  computeTangentFrame(line, o);
  expectOrthonormal(line, 1, 2);
  // Repeated vertex and non-finite data next to a good face: finite everywhere,
  // the good face unharmed.
  Mesh mixed = makeMesh(d3d::FVF_XYZ | d3d::fvfTex(1),
                        {{{0, 1, 0}, 0, 0}, {{1, 1, 0}, 1, 0}, {{0, 0, 0}, 0, 1}, {{NAN, 0, 0}, 1, 1},
                         {{3, 3, 3}, INFINITY, 0}},
                        {0, 1, 2, 1, 3, 2, 0, 0, 1, 2, 4, 0});
  computeTangentFrame(mixed, o);
  for (uint32_t i = 0; i < mixed.vertexCount(); ++i) {
    EXPECT_TRUE(finite(xyz(mixed.texCoord(i, 1)))) << "vertex " << i;
    EXPECT_TRUE(finite(xyz(mixed.texCoord(i, 2)))) << "vertex " << i;
    EXPECT_NEAR(length(xyz(mixed.texCoord(i, 1))), 1, 1e-5f) << "vertex " << i;
  }
  expectVec(xyz(mixed.texCoord(1, 1)), {1, 0, 0});
  // A stored normal along dP/dv = (0,-1,0): b has nothing left after Gram-Schmidt
  // and is rebuilt from n and t = (1,0,0).
  Mesh tilted = texturedQuad(d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(1));
  for (uint32_t i = 0; i < 4; ++i) tilted.setNormal(i, {0, -1, 0});
  o.flags = 0;
  computeTangentFrame(tilted, o);
  expectOrthonormal(tilted, 1, 2);
  for (uint32_t i = 0; i < 4; ++i) expectVec(xyz(tilted.texCoord(i, 1)), {1, 0, 0});
  // A zero stored normal is replaced by the faces' normal.
  Mesh zero = texturedQuad(d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(1));
  computeTangentFrame(zero, o);
  for (uint32_t i = 0; i < 4; ++i) expectVec(zero.normal(i), {0, 0, -1});
}

TEST(TangentFrame, OrthogonalizationOfAShearedMapping) {
  // One face with uv (0,0), (1,0), (1,1) on TL, TR, BL: (s1,t1) = (1,0),
  // (s2,t2) = (1,1), det = 1; dP/du = e1 = (1,0,0); dP/dv = e2*1 - e1*1 = (-1,-1,0).
  Mesh base = makeMesh(d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(1),
                       {{{0, 1, 0}, 0, 0}, {{1, 1, 0}, 1, 0}, {{0, 0, 0}, 1, 1}}, {0, 1, 2});
  for (uint32_t i = 0; i < 3; ++i) base.setNormal(i, {0, 0, -1});
  TangentFrameOptions o;
  o.binormalOut = 2;
  float r = 1 / std::sqrt(2.0f);
  // FROM_U keeps t = (1,0,0); b = cross(n, t) = (0,-1,0).
  Mesh m = base;
  o.flags = TANGENT_ORTHOGONALIZE_FROM_U;
  computeTangentFrame(m, o);
  expectVec(xyz(m.texCoord(0, 1)), {1, 0, 0});
  expectVec(xyz(m.texCoord(0, 2)), {0, -1, 0});
  // FROM_V keeps b = (-1,-1,0)/sqrt2; t = cross(b, n) = ((-1)(-1) - 0, 0 - (-1)(-1), 0)/sqrt2
  // = (1,-1,0)/sqrt2.
  m = base;
  o.flags = TANGENT_ORTHOGONALIZE_FROM_V;
  computeTangentFrame(m, o);
  expectVec(xyz(m.texCoord(0, 1)), {r, -r, 0});
  expectVec(xyz(m.texCoord(0, 2)), {-r, -r, 0});
  // Both: t bisects (1,0,0) and the tangent implied by b, (1,-1,0)/sqrt2: 22.5
  // degrees below x, t = (cos 22.5, -sin 22.5, 0); b = cross(n, t) = (-sin 22.5, -cos 22.5, 0).
  m = base;
  o.flags = 0;
  computeTangentFrame(m, o);
  float c = std::cos(3.14159265f / 8), s = std::sin(3.14159265f / 8);
  expectVec(xyz(m.texCoord(0, 1)), {c, -s, 0});
  expectVec(xyz(m.texCoord(0, 2)), {-s, -c, 0});
  // Without orthogonalization both partials only get normalized.
  m = base;
  o.flags = TANGENT_DONT_ORTHOGONALIZE;
  computeTangentFrame(m, o);
  expectVec(xyz(m.texCoord(0, 1)), {1, 0, 0});
  expectVec(xyz(m.texCoord(0, 2)), {-r, -r, 0});
}

TEST(TangentFrame, UnnormalizedPartialsKeepTheStretch) {
  // The quad stretched to x in [0, 2] with u still in [0, 1]: |dP/du| = 2, |dP/dv| = 1.
  Mesh m = makeMesh(d3d::FVF_XYZ | d3d::fvfTex(1),
                    {{{0, 1, 0}, 0, 0}, {{2, 1, 0}, 1, 0}, {{0, 0, 0}, 0, 1}, {{2, 0, 0}, 1, 1}},
                    {0, 1, 2, 1, 3, 2});
  TangentFrameOptions o;
  o.flags = TANGENT_CALCULATE_NORMALS | TANGENT_DONT_NORMALIZE_PARTIALS;
  o.binormalOut = 2;
  computeTangentFrame(m, o);
  for (uint32_t i = 0; i < 4; ++i) {
    expectVec(xyz(m.texCoord(i, 1)), {2, 0, 0});
    expectVec(xyz(m.texCoord(i, 2)), {0, -1, 0});
  }
}

TEST(TangentFrame, BadInputIsReported) {
  Mesh noNormal = texturedQuad(d3d::FVF_XYZ | d3d::fvfTex(1));
  EXPECT_THROW(computeTangentFrame(noNormal), Error);
  Mesh m = texturedQuad(d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(2));  // set 1 has 2 floats
  EXPECT_THROW(computeTangentFrame(m), Error);
  TangentFrameOptions o;
  o.texIn = 3;
  o.tangentOut = 4;
  EXPECT_THROW(computeTangentFrame(m, o), Error);
  o = {};
  o.tangentOut = 9;
  EXPECT_THROW(computeTangentFrame(m, o), Error);
  o = {};
  o.tangentOut = 0;
  EXPECT_THROW(computeTangentFrame(m, o), Error);
  o = {};
  o.tangentOut = 3;
  o.flags = TANGENT_ORTHOGONALIZE_FROM_U | TANGENT_ORTHOGONALIZE_FROM_V;
  EXPECT_THROW(computeTangentFrame(m, o), Error);
  o.flags = 0;
  m.indices[5] = 17;
  EXPECT_THROW(computeTangentFrame(m, o), Error);
}
