// D3DX shapes: counts and layouts from the D3DX definitions, unit outward normals,
// and clockwise front faces seen from outside (what D3D's default CULL_CCW keeps).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/mesh.h"
#include "refx/resource/vertex_format.h"

using namespace refx;
using namespace refx::d3dx;

namespace {

constexpr float kPi = 3.14159265358979323846f;

void expectVec(Vec3 v, float x, float y, float z, float eps = 1e-5f) {
  EXPECT_NEAR(v.x, x, eps);
  EXPECT_NEAR(v.y, y, eps);
  EXPECT_NEAR(v.z, z, eps);
}

void expectUnitNormals(const Mesh& m) {
  for (uint32_t i = 0; i < m.vertexCount(); ++i)
    ASSERT_NEAR(length(m.normal(i)), 1.0f, 1e-5f) << "vertex " << i;
}

// outward(i): a direction pointing out of the surface at vertex i, worked out from
// the shape's geometry independently of the stored normal.
void expectOutwardNormals(const Mesh& m, const std::function<Vec3(Vec3)>& outward) {
  for (uint32_t i = 0; i < m.vertexCount(); ++i) {
    Vec3 p = m.position(i);
    ASSERT_GT(dot(m.normal(i), outward(p)), 0.0f) << "vertex " << i;
  }
}

// Each triangle is looked at from outside (camera on the side its vertex normals
// point to, LookAtLH + PerspectiveFovLH), projected to the screen (x right, y down),
// and its signed area (b-a) x (c-a) must be positive: clockwise on screen.
void expectClockwiseFromOutside(const Mesh& m) {
  Matrix proj = matrixPerspectiveFovLH(kPi / 4, 1.0f, 0.01f, 100.0f);
  for (uint32_t f = 0; f < m.faceCount(); ++f) {
    uint32_t i[3] = {m.indices[3 * f], m.indices[3 * f + 1], m.indices[3 * f + 2]};
    Vec3 p[3] = {m.position(i[0]), m.position(i[1]), m.position(i[2])};
    Vec3 centroid = (p[0] + p[1] + p[2]) * (1.0f / 3.0f);
    Vec3 out = normalize(m.normal(i[0]) + m.normal(i[1]) + m.normal(i[2]));
    Vec3 eye = centroid + out * 3.0f;
    Vec3 up = std::fabs(out.y) < 0.9f ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
    Matrix viewProj = matrixLookAtLH(eye, centroid, up) * proj;
    float sx[3], sy[3];
    for (int k = 0; k < 3; ++k) {
      Vec3 c = transformCoord(p[k], viewProj);
      sx[k] = c.x;
      sy[k] = -c.y;  // screen y grows downward
    }
    float area = (sx[1] - sx[0]) * (sy[2] - sy[0]) - (sy[1] - sy[0]) * (sx[2] - sx[0]);
    ASSERT_GT(area, 0.0f) << "face " << f << " (" << i[0] << ", " << i[1] << ", " << i[2]
                          << ") is counter-clockwise seen from outside";
  }
}

void expectIndicesInRange(const Mesh& m) {
  for (uint32_t idx : m.indices) ASSERT_LT(idx, m.vertexCount());
}

}  // namespace

TEST(MeshLayout, FVFStrides) {
  // XYZ 12 + NORMAL 12 = 24 bytes (the D3DX shape layout).
  EXPECT_EQ(fvfStride(d3d::FVF_XYZ | d3d::FVF_NORMAL), 24u);
  // XYZ 12 + NORMAL 12 + float2 8 + float3 12 = 44.
  uint32_t tex = d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(2) | d3d::fvfTexCoordSize(3, 1);
  EXPECT_EQ(fvfStride(tex), 44u);
  // XYZ 12 + DIFFUSE 4 + float2 8 = 24; texcoord 0 at 16.
  FVFLayout l = FVFLayout::of(d3d::FVF_XYZ | d3d::FVF_DIFFUSE | d3d::fvfTex(1));
  EXPECT_EQ(l.stride, 24u);
  EXPECT_EQ(l.diffuse, 12);
  EXPECT_EQ(l.texCoord[0], 16);
  EXPECT_EQ(l.normal, -1);
  // D3DFVF_TEXCOORDSIZE3(1) = 1 << 18, TEXCOORDSIZE1(0) = 3 << 16.
  EXPECT_EQ(d3d::fvfTexCoordSize(3, 1), 0x40000u);
  EXPECT_EQ(d3d::fvfTexCoordSize(1, 0), 0x30000u);
  EXPECT_THROW(fvfStride(d3d::FVF_XYZ | d3d::fvfTex(9)), Error);
}

TEST(MeshLayout, SameLayoutAsTheDeviceDeclaration) {
  for (uint32_t code : {d3d::FVF_XYZ | d3d::FVF_NORMAL, d3d::FVF_XYZ | d3d::FVF_DIFFUSE | d3d::fvfTex(1),
                        d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(2) | d3d::fvfTexCoordSize(3, 1),
                        d3d::FVF_XYZRHW | d3d::FVF_DIFFUSE | d3d::FVF_SPECULAR | d3d::fvfTex(1)}) {
    FVFLayout l = FVFLayout::of(code);
    VertexDeclaration d = VertexDeclaration::fromFVF(code);
    EXPECT_EQ(d.streamStride(0), l.stride) << std::hex << code;
    if (l.normal >= 0) {
      ASSERT_NE(d.find(d3d::DECLUSAGE_NORMAL, 0), nullptr);
      EXPECT_EQ(d.find(d3d::DECLUSAGE_NORMAL, 0)->offset, l.normal);
    }
    for (int s = 0; s < d3d::fvfTexCount(code); ++s) {
      ASSERT_NE(d.find(d3d::DECLUSAGE_TEXCOORD, uint8_t(s)), nullptr);
      EXPECT_EQ(d.find(d3d::DECLUSAGE_TEXCOORD, uint8_t(s))->offset, l.texCoord[s]);
    }
  }
}

TEST(MeshLayout, ElementAccessAndClone) {
  Mesh m(d3d::FVF_XYZ | d3d::FVF_DIFFUSE | d3d::fvfTex(1), 3, 1);
  EXPECT_EQ(m.vertexCount(), 3u);
  EXPECT_EQ(m.faceCount(), 1u);
  m.setPosition(2, {1, 2, 3});
  m.setDiffuse(2, 0x80ff0010u);
  m.setTexCoord(2, 0, 0.25f, 0.75f);
  expectVec(m.position(2), 1, 2, 3, 0);
  EXPECT_EQ(m.diffuse(2), 0x80ff0010u);
  EXPECT_EQ(m.texCoord(2, 0), Vec4(0.25f, 0.75f, 0, 0));  // float2: z, w read 0
  EXPECT_THROW(m.normal(0), Error);      // no NORMAL in the FVF
  EXPECT_THROW(m.position(3), Error);    // vertex 3 of 3
  EXPECT_THROW(m.texCoord(0, 1), Error);  // one set only

  Mesh c = cloneMeshFVF(m, d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(1));
  EXPECT_EQ(c.stride, 32u);  // 12 + 12 + 8
  expectVec(c.position(2), 1, 2, 3, 0);
  expectVec(c.normal(2), 0, 0, 0, 0);
  EXPECT_EQ(c.texCoord(2, 0), Vec4(0.25f, 0.75f, 0, 0));
  EXPECT_EQ(c.indices, m.indices);
}

TEST(Shapes, SphereLayout) {
  // slices 4, stacks 2: 2 + 4*(2-1) = 6 vertices, 2*4*(2-1) = 8 faces.
  Mesh m = createSphere(1.0f, 4, 2);
  EXPECT_EQ(m.fvf, d3d::FVF_XYZ | d3d::FVF_NORMAL);
  EXPECT_EQ(m.stride, 24u);
  ASSERT_EQ(m.vertexCount(), 6u);
  EXPECT_EQ(m.faceCount(), 8u);
  // Axis z: the +z pole first; the ring at theta = pi/2 starts at phi = pi/2 and
  // steps by -2pi/4: (0,1,0), (1,0,0), (0,-1,0), (-1,0,0); then the -z pole.
  expectVec(m.position(0), 0, 0, 1);
  expectVec(m.position(1), 0, 1, 0);
  expectVec(m.position(2), 1, 0, 0);
  expectVec(m.position(3), 0, -1, 0);
  expectVec(m.position(4), -1, 0, 0);
  expectVec(m.position(5), 0, 0, -1);
}

TEST(Shapes, Sphere) {
  const float r = 2.5f;
  Mesh m = createSphere(r, 12, 7);
  // 2 + 12*6 = 74 vertices, 2*12*6 = 144 faces.
  EXPECT_EQ(m.vertexCount(), 74u);
  EXPECT_EQ(m.faceCount(), 144u);
  expectIndicesInRange(m);
  expectUnitNormals(m);
  for (uint32_t i = 0; i < m.vertexCount(); ++i) {
    Vec3 p = m.position(i), n = m.normal(i);
    EXPECT_NEAR(length(p), r, 1e-5f);
    expectVec(n, p.x / r, p.y / r, p.z / r);  // smooth normal = position / radius
  }
  expectOutwardNormals(m, [](Vec3 p) { return p; });
  expectClockwiseFromOutside(m);
  EXPECT_THROW(createSphere(1, 1, 4), Error);
  EXPECT_THROW(createSphere(-1, 8, 4), Error);
}

TEST(Shapes, TexturedSphere) {
  const float r = 1.5f;
  const uint32_t slices = 16, stacks = 8;
  Mesh m = createTexturedSphere(r, slices, stacks);
  EXPECT_EQ(m.fvf, d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(2) | d3d::fvfTexCoordSize(3, 1));
  EXPECT_EQ(m.stride, 44u);
  // (16+1) * (8+1) = 153 vertices; 2*16*(8-1) = 224 faces (one per quad at the poles).
  EXPECT_EQ(m.vertexCount(), 153u);
  EXPECT_EQ(m.faceCount(), 224u);
  expectIndicesInRange(m);
  expectUnitNormals(m);
  expectOutwardNormals(m, [](Vec3 p) { return p; });
  expectClockwiseFromOutside(m);

  const uint32_t cols = slices + 1;
  for (uint32_t s = 0; s <= stacks; ++s)
    for (uint32_t k = 0; k <= slices; ++k) {
      uint32_t i = s * cols + k;
      Vec4 uv = m.texCoord(i, 0);
      EXPECT_NEAR(uv.x, float(k) / slices, 1e-6f);  // u = slice / slices
      EXPECT_NEAR(uv.y, float(s) / stacks, 1e-6f);  // v = stack / stacks from the north
      Vec3 t = m.texCoord(i, 1).xyz(), n = m.normal(i), p = m.position(i);
      EXPECT_NEAR(length(t), 1.0f, 1e-5f);
      EXPECT_NEAR(dot(t, n), 0.0f, 1e-5f) << "tangent not perpendicular at " << i;
      // Along +u: the next vertex of the row lies ahead of the tangent (not at poles).
      if (s > 0 && s < stacks && k < slices) {
        Vec3 ahead = m.position(i + 1) - p;
        EXPECT_GT(dot(t, ahead), 0.0f) << "vertex " << i;
      }
    }
  // Seam duplicated: column `slices` has the positions of column 0.
  for (uint32_t s = 0; s <= stacks; ++s) {
    Vec3 a = m.position(s * cols), b = m.position(s * cols + slices);
    expectVec(a, b.x, b.y, b.z, 1e-6f);
  }
  // North pole at +y (v = 0), south pole at -y (v = 1).
  expectVec(m.position(0), 0, r, 0);
  expectVec(m.position(stacks * cols), 0, -r, 0);
  // u = 0.5 on the equator (v = 0.5) faces a camera at -z: position (0, 0, -r), and
  // east (+u) is to that camera's right, +x: tangent (-cos pi, 0, -sin pi) = (1, 0, 0).
  uint32_t front = (stacks / 2) * cols + slices / 2;
  expectVec(m.position(front), 0, 0, -r);
  expectVec(m.texCoord(front, 1).xyz(), 1, 0, 0);
}

TEST(Shapes, Box) {
  Mesh m = createBox(2, 4, 6);
  ASSERT_EQ(m.vertexCount(), 24u);
  EXPECT_EQ(m.faceCount(), 12u);
  EXPECT_EQ(m.fvf, d3d::FVF_XYZ | d3d::FVF_NORMAL);
  // D3DX order: the -x face first, its first corner (-w/2, -h/2, -d/2).
  expectVec(m.position(0), -1, -2, -3);
  expectVec(m.normal(0), -1, 0, 0);
  // Flat faces: the 4 vertices of a face share the normal and lie in the plane
  // dot(n, p) = half the extent along n.
  for (uint32_t i = 0; i < 24; ++i) {
    Vec3 n = m.normal(i), p = m.position(i);
    EXPECT_EQ(n, m.normal(i / 4 * 4));
    float half = std::fabs(n.x) * 1 + std::fabs(n.y) * 2 + std::fabs(n.z) * 3;
    EXPECT_NEAR(dot(n, p), half, 1e-6f);
  }
  expectIndicesInRange(m);
  expectUnitNormals(m);
  expectOutwardNormals(m, [](Vec3 p) { return p; });
  expectClockwiseFromOutside(m);
}

TEST(Shapes, Cylinder) {
  const float r1 = 1.0f, r2 = 0.5f, len = 2.0f;
  Mesh m = createCylinder(r1, r2, len, 8, 3);
  // 2 + 8*(3+3) = 50 vertices; 2*8 caps + 3*2*8 sides = 64 faces.
  ASSERT_EQ(m.vertexCount(), 50u);
  EXPECT_EQ(m.faceCount(), 64u);
  expectVec(m.position(0), 0, 0, -1);  // -z cap centre at -length/2
  expectVec(m.normal(0), 0, 0, -1);
  expectVec(m.position(49), 0, 0, 1);  // +z cap centre last
  expectVec(m.normal(49), 0, 0, 1);
  // First side vertex (index 1 + 8): phi = pi/2, radius1, z = -1; cone normal
  // (0, 1, (r1-r2)/len = 0.25) / sqrt(1.0625) = (0, 0.970143, 0.242536).
  expectVec(m.position(9), 0, 1, -1);
  expectVec(m.normal(9), 0, 0.970143f, 0.242536f);
  // Last side ring (index 1 + 8*4): radius2 at z = +1.
  expectVec(m.position(33), 0, 0.5f, 1);
  expectIndicesInRange(m);
  expectUnitNormals(m);
  // Convex around the origin: p itself points outward at every vertex (caps and sides).
  expectOutwardNormals(m, [](Vec3 p) { return p; });
  expectClockwiseFromOutside(m);
}

TEST(Shapes, Torus) {
  const float tube = 0.25f, ring = 1.0f;
  Mesh m = createTorus(tube, ring, 8, 16);
  // sides*rings = 128 vertices, 2*128 faces.
  ASSERT_EQ(m.vertexCount(), 128u);
  EXPECT_EQ(m.faceCount(), 256u);
  // Vertex 0: theta 0, phi pi/2 -> top of the tube at (ring, 0, tube), normal +z.
  expectVec(m.position(0), 1, 0, 0.25f);
  expectVec(m.normal(0), 0, 0, 1);
  expectIndicesInRange(m);
  expectUnitNormals(m);
  // Outward from the tube centre ring*(cos t, sin t, 0): p - c = tube * n exactly.
  for (uint32_t i = 0; i < m.vertexCount(); ++i) {
    Vec3 p = m.position(i);
    float d = std::hypot(p.x, p.y);
    Vec3 c{p.x / d * ring, p.y / d * ring, 0};
    Vec3 n = m.normal(i), e = (p - c) * (1.0f / tube);
    expectVec(n, e.x, e.y, e.z);
  }
  expectClockwiseFromOutside(m);
}
