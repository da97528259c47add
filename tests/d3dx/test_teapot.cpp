// Bézier patches and the Utah teapot: counts, planar patches, corners, the data set's
// known extents and outward normals.
#include <gtest/gtest.h>

#include <cmath>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/teapot.h"

using namespace refx;
using namespace refx::d3dx;

namespace {

constexpr float kEps = 1e-5f;

void expectVec(Vec3 v, Vec3 want, float eps) {
  EXPECT_NEAR(v.x, want.x, eps);
  EXPECT_NEAR(v.y, want.y, eps);
  EXPECT_NEAR(v.z, want.z, eps);
}

// Control points o + a*s[j] + b*t[i]: all in the plane through o spanned by a and b,
// unevenly spaced so the parametrisation is not affine.
void planarPatch(Vec3 cp[16], Vec3 o, Vec3 a, Vec3 b) {
  const float s[4] = {0, 0.5f, 2, 3}, t[4] = {0, 1, 1.5f, 3};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) cp[4 * i + j] = o + a * s[j] + b * t[i];
}

}  // namespace

TEST(BezierPatch, CountsAndLayout) {
  Vec3 cp[16];
  planarPatch(cp, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  Mesh m = createBezierPatch(cp, 5);
  EXPECT_EQ(m.fvf, d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(1));
  EXPECT_EQ(m.stride, 32u);            // 3 + 3 + 2 floats
  EXPECT_EQ(m.vertexCount(), 36u);     // (5+1)²
  EXPECT_EQ(m.faceCount(), 50u);       // 2 * 5²
  // Vertex (i, j) = i * 6 + j has (u, v) = (j/5, i/5).
  Vec4 uv = m.texCoord(2 * 6 + 3);
  EXPECT_FLOAT_EQ(uv.x, 0.6f);
  EXPECT_FLOAT_EQ(uv.y, 0.4f);
  EXPECT_THROW(createBezierPatch(cp, 0), Error);
}

TEST(BezierPatch, PlanarControlPointsGivePlanarVerticesAndThePlaneNormal) {
  // Plane spanned by a = (1, 0.5, 0) and b = (0, 1, 1):
  // a x b = (0.5*1 - 0*1, 0*0 - 1*1, 1*1 - 0.5*0) = (0.5, -1, 1), |a x b| = 1.5,
  // n = (1/3, -2/3, 2/3). s and t increase, so dP/du is along +a, dP/dv along +b.
  const Vec3 o{2, -1, 3}, a{1, 0.5f, 0}, b{0, 1, 1}, n{1.0f / 3, -2.0f / 3, 2.0f / 3};
  Vec3 cp[16];
  planarPatch(cp, o, a, b);
  Mesh m = createBezierPatch(cp, 7);
  for (uint32_t v = 0; v < m.vertexCount(); ++v) {
    EXPECT_NEAR(dot(m.position(v) - o, n), 0.0f, 1e-5f) << "vertex " << v;
    expectVec(m.normal(v), n, 1e-5f);
  }
  // Clockwise seen from the normal's side: cross(p1 - p0, p2 - p0) points along n.
  for (uint32_t f = 0; f < m.faceCount(); ++f) {
    Vec3 p0 = m.position(m.indices[3 * f]), p1 = m.position(m.indices[3 * f + 1]),
         p2 = m.position(m.indices[3 * f + 2]);
    EXPECT_GT(dot(cross(p1 - p0, p2 - p0), n), 0.0f) << "face " << f;
  }
}

TEST(BezierPatch, CornersAreTheCornerControlPoints) {
  Vec3 cp[16];
  for (int k = 0; k < 16; ++k)  // a curved patch: z = (i - 1.5)² - (j - 1.5)²
    cp[k] = {float(k % 4), float(k / 4), float((k / 4 - 1.5f) * (k / 4 - 1.5f) - (k % 4 - 1.5f) * (k % 4 - 1.5f))};
  const uint32_t t = 6, row = t + 1;
  Mesh m = createBezierPatch(cp, t);
  expectVec(m.position(0), cp[0], kEps);                 // (u, v) = (0, 0)
  expectVec(m.position(t), cp[3], kEps);                 // (1, 0)
  expectVec(m.position(t * row), cp[12], kEps);          // (0, 1)
  expectVec(m.position(t * row + t), cp[15], kEps);      // (1, 1)
  // Bernstein weights at u = v = 1/2 are (1, 3, 3, 1)/8 on each axis; the centre is
  // sum w_i w_j cp: x = (0*1 + 1*3 + 2*3 + 3*1)/8 = 1.5, likewise y, and
  // z = sum_i w_i (i-1.5)² - sum_j w_j (j-1.5)² = 0.
  BezierPoint c = evaluateBezierPatch(cp, 0.5f, 0.5f);
  expectVec(c.position, {1.5f, 1.5f, 0}, kEps);
}

TEST(BezierPatch, CollapsedEdgeGetsThePoleNormal) {
  // A dome: row 0 is one point (the pole, at the top); the other rows are circles
  // of growing radius going down. At the pole dP/du = 0; the normal must be +z.
  Vec3 cp[16];
  const float r[4] = {0, 0.6f, 1.0f, 1.0f}, z[4] = {1, 1, 0.6f, 0};
  const float kx[4] = {1, 1, -1, -1}, ky[4] = {0, 1.3f, 1.3f, 0};  // a half circle in +y
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) cp[4 * i + j] = {r[i] * kx[j], r[i] * ky[j], z[i]};
  // Orientation: at (u, v) = (0.5, 0.5) dP/du runs toward -x and dP/dv outward and
  // down (+y, -z); (-1,0,0) x (0,1,-1) = (0*(-1) - 0*1, 0*0 - (-1)*(-1), -1*1 - 0) =
  // (0, -1, -1): inward and down. So the pole normal is the limit of that side: -z.
  Mesh m = createBezierPatch(cp, 4);
  for (uint32_t j = 0; j <= 4; ++j) expectVec(m.normal(j), {0, 0, -1}, 1e-2f);
}

TEST(Teapot, CountsAndFormat) {
  for (uint32_t t : {1u, 4u, 8u}) {
    Mesh m = createTeapot(t);
    EXPECT_EQ(m.vertexCount(), 32 * (t + 1) * (t + 1));
    EXPECT_EQ(m.faceCount(), 64 * t * t);
    EXPECT_EQ(m.fvf, d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(1));
  }
  EXPECT_THROW(createTeapot(0), Error);
}

TEST(Teapot, DataSetHas306PointsAndConsistentPatches) {
  // Every patch refers to points 1..306; the four quadrants of the rim, body, lid and
  // bottom are the same patch turned by 90° about the axis, so their points agree.
  for (int p = 0; p < kTeapotPatchCount; ++p)
    for (int k = 0; k < 16; ++k) {
      EXPECT_GE(kTeapotPatches[p][k], 1);
      EXPECT_LE(kTeapotPatches[p][k], 306);
    }
  auto point = [](int p, int k) {
    const float* c = kTeapotControlPoints[kTeapotPatches[p][k] - 1];
    return Vec3{c[0], c[1], c[2]};
  };
  for (int group : {0, 4, 8, 20, 24})
    for (int q = 1; q < 4; ++q)
      for (int k = 0; k < 16; ++k) {
        // Patch group+q is patch group turned by q * -90° about z: (x, y) -> (y, -x).
        Vec3 a = point(group, k);
        for (int i = 0; i < q; ++i) a = {a.y, -a.x, a.z};
        expectVec(point(group + q, k), a, 1e-6f);
      }
}

TEST(Teapot, BoundingBoxIsTheDataSetsExtents) {
  // Data set extents (z up): x from -3.0 (the handle's corner point 136, a patch
  // corner) to the spout lip, y within +-2.0 (body corners at radius 2.0),
  // z from 0 (bottom) to 3.15 (lid knob). The lip's outer edge is the curve with
  // x-control values 3.3, 3.525, 3.45, 3.2; its maximum, 3.434075 at v = 0.41, bounds
  // the tessellated maximum; with t = 10 the vertex at v = 0.4 gives
  // 3.3*0.216 + 3.525*0.432 + 3.45*0.288 + 3.2*0.064 = 3.43404.
  // Turned y-up and centred: y = z - 1.575 in [-1.575, 1.575], z = -y in [-2, 2].
  Mesh m = createTeapot(10);
  Vec3 lo = m.position(0), hi = lo;
  for (uint32_t v = 0; v < m.vertexCount(); ++v) {
    Vec3 p = m.position(v);
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  EXPECT_NEAR(lo.x, -3.0f, kEps);
  EXPECT_NEAR(hi.x, 3.43404f, 1e-4f);
  EXPECT_NEAR(lo.y, -1.575f, kEps);
  EXPECT_NEAR(hi.y, 1.575f, kEps);
  EXPECT_NEAR(lo.z, -2.0f, kEps);
  EXPECT_NEAR(hi.z, 2.0f, kEps);
}

TEST(Teapot, NormalsAreUnitAndOutward) {
  const uint32_t t = 8, per = (t + 1) * (t + 1);
  Mesh m = createTeapot(t);
  double mean = 0;
  for (uint32_t v = 0; v < m.vertexCount(); ++v) {
    Vec3 n = m.normal(v), p = m.position(v);
    EXPECT_NEAR(length(n), 1.0f, 1e-5f) << "vertex " << v;
    mean += dot(n, normalize(p));
  }
  mean /= m.vertexCount();
  EXPECT_GT(mean, 0.5);
  // The body (patches 4-11) is a surface of revolution bulging outward: every normal
  // has a positive radial component.
  for (uint32_t v = 4 * per; v < 12 * per; ++v) {
    Vec3 n = m.normal(v), p = m.position(v);
    EXPECT_GT(n.x * p.x + n.z * p.z, 0.0f) << "vertex " << v;
  }
  // The lid's knob top (patch 20, row 0) and the bottom centre (patch 28, row 0) are
  // poles where the patches collapse to a point: the normals are straight up / down.
  for (uint32_t j = 0; j <= t; ++j) {
    expectVec(m.position(20 * per + j), {0, 1.575f, 0}, kEps);
    expectVec(m.normal(20 * per + j), {0, 1, 0}, 1e-2f);
    expectVec(m.position(28 * per + j), {0, -1.575f, 0}, kEps);
    expectVec(m.normal(28 * per + j), {0, -1, 0}, 1e-2f);
  }
}

TEST(Teapot, FacesAreClockwiseFromOutside) {
  // cross(p1 - p0, p2 - p0) points outward for clockwise front faces (D3D); compare
  // with the vertex normals of each non-degenerate triangle.
  Mesh m = createTeapot(6);
  int degenerate = 0;
  for (uint32_t f = 0; f < m.faceCount(); ++f) {
    uint32_t i0 = m.indices[3 * f], i1 = m.indices[3 * f + 1], i2 = m.indices[3 * f + 2];
    Vec3 fn = cross(m.position(i1) - m.position(i0), m.position(i2) - m.position(i0));
    if (length(fn) < 1e-7f) {
      ++degenerate;
      continue;
    }
    EXPECT_GT(dot(fn, m.normal(i0) + m.normal(i1) + m.normal(i2)), 0.0f) << "face " << f;
  }
  // Only the poles of the lid (4 patches) and bottom (4 patches) collapse: one
  // triangle per quad of row 0, t per patch.
  EXPECT_EQ(degenerate, 8 * 6);
}

TEST(Teapot, BodyPatchesMeetSmoothly) {
  // The body's upper patches (4-7) end where the lower ones (8-11) start: same
  // positions and, the surface being smooth there, the same normals.
  const uint32_t t = 6, row = t + 1, per = row * row;
  Mesh m = createTeapot(t);
  for (uint32_t p = 4; p < 8; ++p)
    for (uint32_t j = 0; j <= t; ++j) {
      uint32_t upper = p * per + t * row + j, lower = (p + 4) * per + j;
      expectVec(m.position(upper), m.position(lower), kEps);
      expectVec(m.normal(upper), m.normal(lower), 1e-3f);
    }
}
