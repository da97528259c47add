// Adjacency, point representatives, welding and ComputeNormals. Expected values
// are worked out from the D3DX definitions: neighbours run along the same two
// points in opposite directions; the face normal is cross(p1 - p0, p2 - p0)
// (toward the viewer for D3D's clockwise front faces); vertex normals are
// angle-weighted sums of unit face normals.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <map>
#include <set>
#include <tuple>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/mesh.h"
#include "refx/d3dx/mesh_ops.h"

using namespace refx;
using namespace refx::d3dx;

namespace {

constexpr uint32_t X = kNoNeighbor;

void expectVec(Vec3 v, Vec3 e, float eps = 1e-5f) {
  EXPECT_NEAR(v.x, e.x, eps);
  EXPECT_NEAR(v.y, e.y, eps);
  EXPECT_NEAR(v.z, e.z, eps);
}

Mesh makeMesh(uint32_t fvfCode, const std::vector<Vec3>& pos, const std::vector<uint32_t>& idx) {
  Mesh m(fvfCode, uint32_t(pos.size()), uint32_t(idx.size() / 3));
  for (uint32_t i = 0; i < pos.size(); ++i) m.setPosition(i, pos[i]);
  m.indices = idx;
  return m;
}

// Unit quad in the XY plane facing a viewer at -z (D3D's default camera looks
// along +z): top-left (0,1), top-right (1,1), bottom-left (0,0), bottom-right
// (1,0); triangles TL TR BL and TR BR BL, clockwise on screen.
Mesh quad(uint32_t fvfCode) {
  return makeMesh(fvfCode, {{0, 1, 0}, {1, 1, 0}, {0, 0, 0}, {1, 0, 0}}, {0, 1, 2, 1, 3, 2});
}

// The faces of the cube [-1,1]^3 as (outward n, right r, down d) seen from outside
// with r x d = n, so that the corners TL = n-r-d, TR = n+r-d, BL = n-r+d, BR = n+r+d
// give triangles TL TR BL and TR BR BL with cross(e1, e2) = 4 r x d = 4 n: outward,
// clockwise seen from outside.
struct CubeFace {
  Vec3 n, r, d;
};
const CubeFace kCubeFaces[6] = {
    {{1, 0, 0}, {0, 0, 1}, {0, -1, 0}},    // (0,0,1) x (0,-1,0) = (1,0,0)
    {{-1, 0, 0}, {0, 0, -1}, {0, -1, 0}},  // (0,0,-1) x (0,-1,0) = (-1,0,0)
    {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},    // (1,0,0) x (0,0,-1) = (0,1,0)
    {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},    // (1,0,0) x (0,0,1) = (0,-1,0)
    {{0, 0, 1}, {-1, 0, 0}, {0, -1, 0}},   // (-1,0,0) x (0,-1,0) = (0,0,1)
    {{0, 0, -1}, {1, 0, 0}, {0, -1, 0}},   // (1,0,0) x (0,-1,0) = (0,0,-1)
};

// The cube with 8 shared corner vertices (shared = true) or 4 vertices per face.
Mesh cube(uint32_t fvfCode, bool shared) {
  std::vector<Vec3> pos;
  std::vector<uint32_t> idx;
  std::map<std::tuple<float, float, float>, uint32_t> corner;
  auto vertex = [&](Vec3 p) {
    if (shared) {
      auto [it, fresh] = corner.try_emplace({p.x, p.y, p.z}, uint32_t(pos.size()));
      if (!fresh) return it->second;
    }
    pos.push_back(p);
    return uint32_t(pos.size() - 1);
  };
  for (const CubeFace& f : kCubeFaces) {
    uint32_t tl = vertex(f.n - f.r - f.d), tr = vertex(f.n + f.r - f.d);
    uint32_t bl = vertex(f.n - f.r + f.d), br = vertex(f.n + f.r + f.d);
    idx.insert(idx.end(), {tl, tr, bl, tr, br, bl});
  }
  return makeMesh(fvfCode, pos, idx);
}

uint32_t vertexAt(const Mesh& m, Vec3 p) {
  for (uint32_t i = 0; i < m.vertexCount(); ++i)
    if (m.position(i) == p) return i;
  ADD_FAILURE() << "no vertex at " << p.x << "," << p.y << "," << p.z;
  return 0;
}

void expectMutual(const Mesh& m, const std::vector<uint32_t>& adj) {
  for (uint32_t f = 0; f < m.faceCount(); ++f)
    for (int k = 0; k < 3; ++k) {
      uint32_t g = adj[3 * f + k];
      if (g == X) continue;
      ASSERT_LT(g, m.faceCount());
      int back = 0;
      for (int j = 0; j < 3; ++j) back += adj[3 * g + j] == f;
      EXPECT_GE(back, 1) << "face " << g << " does not name face " << f << " back";
    }
}

}  // namespace

TEST(Adjacency, TwoTrianglesSharingAnEdge) {
  Mesh m = quad(d3d::FVF_XYZ);
  // Face 0 (0,1,2): edge 1 runs 1->2; face 1 (1,3,2): edge 2 runs 2->1, the same
  // points the other way. The other four edges are on the border.
  std::vector<uint32_t> expected = {X, 1, X, X, X, 0};
  EXPECT_EQ(generateAdjacency(m, 0.0f), expected);
}

TEST(Adjacency, EdgesInTheSameDirectionAreNotNeighbours) {
  // Face 1 (1,2,3) runs 1->2 like face 0 (0,1,2): inconsistent winding.
  Mesh m = makeMesh(d3d::FVF_XYZ, {{0, 1, 0}, {1, 1, 0}, {0, 0, 0}, {1, 0, 0}}, {0, 1, 2, 1, 2, 3});
  std::vector<uint32_t> expected(6, X);
  EXPECT_EQ(generateAdjacency(m, 0.0f), expected);
}

TEST(Adjacency, SplitVerticesMatchWithinEpsilon) {
  // Second triangle has its own copies of the shared edge's points, 1e-4 away.
  Mesh m = makeMesh(d3d::FVF_XYZ,
                    {{0, 1, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1.0001f, 0}, {1, 0, 0}, {0.0001f, 0, 0}},
                    {0, 1, 2, 3, 4, 5});
  // Face 1 edge 2 runs 5->3 = (0,0)->(1,1), face 0 edge 1 runs (1,1)->(0,0).
  EXPECT_EQ(generateAdjacency(m, 0.0f), std::vector<uint32_t>(6, X));
  EXPECT_EQ(generateAdjacency(m, 1e-5f), std::vector<uint32_t>(6, X));
  EXPECT_EQ(generateAdjacency(m, 1e-3f), (std::vector<uint32_t>{X, 1, X, X, X, 0}));
}

TEST(Adjacency, ClosedBoxHasANeighbourOnEveryEdge) {
  for (bool shared : {true, false}) {
    Mesh m = cube(d3d::FVF_XYZ, shared);
    std::vector<uint32_t> adj = generateAdjacency(m, 0.0f);
    ASSERT_EQ(adj.size(), 36u);
    for (uint32_t a : adj) EXPECT_NE(a, X);
    expectMutual(m, adj);
    // Face 0 (+x: TL TR BL) edge 1 (TR -> BL) is the diagonal: its neighbour is face 1.
    EXPECT_EQ(adj[1], 1u);
  }
  Mesh box = createBox(1, 2, 3);
  std::vector<uint32_t> adj = generateAdjacency(box, 0.0f);
  for (uint32_t a : adj) EXPECT_NE(a, X);
  expectMutual(box, adj);
}

TEST(Adjacency, ErrorsAreReported) {
  Mesh m = quad(d3d::FVF_XYZ);
  EXPECT_THROW(generateAdjacency(m, -1.0f), Error);
  EXPECT_THROW(generateAdjacency(m, NAN), Error);
  m.indices[4] = 9;
  EXPECT_THROW(generateAdjacency(m, 0.0f), Error);
  Mesh ok = quad(d3d::FVF_XYZ);
  EXPECT_THROW(convertAdjacencyToPointReps(ok, std::vector<uint32_t>{X, X, X}), Error);
  EXPECT_THROW(convertAdjacencyToPointReps(ok, std::vector<uint32_t>{X, 7, X, X, X, 0}), Error);
}

TEST(Adjacency, NonFinitePositionsMatchNothing) {
  Mesh m = makeMesh(d3d::FVF_XYZ, {{0, 1, 0}, {1, 1, 0}, {NAN, 0, 0}, {1, 0, 0}}, {0, 1, 2, 1, 3, 2});
  std::vector<uint32_t> adj = generateAdjacency(m, 0.01f);
  // Shared index 2 still pairs the diagonal: points are per index first.
  EXPECT_EQ(adj, (std::vector<uint32_t>{X, 1, X, X, X, 0}));
}

TEST(PointReps, ReplicasAcrossAnEdgeShareTheLowestIndex) {
  // v3 = v1 and v5 = v2 as copies; face 1 (3,4,5) edge 2 runs 5->3 against face 0's 1->2.
  Mesh m = makeMesh(d3d::FVF_XYZ, {{0, 1, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 0, 0}},
                    {0, 1, 2, 3, 4, 5});
  std::vector<uint32_t> adj = generateAdjacency(m, 0.0f);
  EXPECT_EQ(adj, (std::vector<uint32_t>{X, 1, X, X, X, 0}));
  EXPECT_EQ(convertAdjacencyToPointReps(m, adj), (std::vector<uint32_t>{0, 1, 2, 1, 4, 2}));
  // Without adjacency nothing is a replica.
  EXPECT_EQ(convertAdjacencyToPointReps(m, std::vector<uint32_t>(6, X)),
            (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
}

TEST(Weld, BoxWithSplitCornersBecomesEightVertices) {
  Mesh m = cube(d3d::FVF_XYZ, false);
  ASSERT_EQ(m.vertexCount(), 24u);
  Mesh before = m;
  std::vector<uint32_t> remap = weldVertices(m, 0.0f);
  EXPECT_EQ(m.vertexCount(), 8u);
  EXPECT_EQ(m.faceCount(), 12u);
  ASSERT_EQ(remap.size(), 24u);
  std::set<std::tuple<float, float, float>> corners;
  for (uint32_t i = 0; i < 8; ++i) corners.insert({m.position(i).x, m.position(i).y, m.position(i).z});
  EXPECT_EQ(corners.size(), 8u);  // the 8 distinct corners of the cube
  for (size_t c = 0; c < m.indices.size(); ++c) {
    EXPECT_EQ(m.position(m.indices[c]), before.position(before.indices[c])) << "corner " << c;
    EXPECT_EQ(m.indices[c], remap[before.indices[c]]);
  }
}

TEST(Weld, DifferentNormalsStayApartUnlessWeldAll) {
  Mesh box = createBox(2, 2, 2);  // flat normals: the replicas of a corner differ by 1
  Mesh m = box;
  weldVertices(m, 1e-6f);
  EXPECT_EQ(m.vertexCount(), 24u);
  m = box;
  weldVertices(m, 1e-6f, WELD_ALL);
  EXPECT_EQ(m.vertexCount(), 8u);
}

TEST(Weld, OtherElementsCompareWithinEpsilon) {
  // Two triangles sharing an edge through copies whose texture coordinates differ by 1e-4.
  Mesh m(d3d::FVF_XYZ | d3d::fvfTex(1), 6, 2);
  Vec3 p[6] = {{0, 1, 0}, {1, 1, 0}, {0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 0, 0}};
  for (uint32_t i = 0; i < 6; ++i) m.setPosition(i, p[i]), m.setTexCoord(i, 0, p[i].x, 1 - p[i].y);
  m.setTexCoord(3, 0, 1.0001f, 0.0f);
  m.indices = {0, 1, 2, 3, 4, 5};
  Mesh a = m;
  weldVertices(a, 1e-5f);
  EXPECT_EQ(a.vertexCount(), 5u);  // 5 -> 2 welds (equal), 3 -> 1 does not (1e-4 > 1e-5)
  EXPECT_EQ(a.indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 2}));
  Mesh b = m;
  std::vector<uint32_t> remap = weldVertices(b, 1e-3f);
  EXPECT_EQ(b.vertexCount(), 4u);
  EXPECT_EQ(b.indices, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2}));
  EXPECT_EQ(remap, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2}));
  Mesh c = m;
  weldVertices(c, 1e-3f, WELD_DONOTREMOVEVERTICES);
  EXPECT_EQ(c.vertexCount(), 6u);
  EXPECT_EQ(c.indices, (std::vector<uint32_t>{0, 1, 2, 1, 4, 2}));
}

TEST(ComputeNormals, QuadNormalFacesTheViewer) {
  // Face 0: e1 = (1,1,0)-(0,1,0) = (1,0,0), e2 = (0,0,0)-(0,1,0) = (0,-1,0);
  // cross(e1, e2) = (0*0 - 0*(-1), 0*0 - 1*0, 1*(-1) - 0*0) = (0,0,-1): toward the
  // viewer at -z. Face 1 is in the same plane, same winding.
  Mesh m = quad(d3d::FVF_XYZ | d3d::FVF_NORMAL);
  computeNormals(m);
  for (uint32_t i = 0; i < 4; ++i) expectVec(m.normal(i), {0, 0, -1});
  computeNormals(m, {}, TANGENT_WIND_CW);
  for (uint32_t i = 0; i < 4; ++i) expectVec(m.normal(i), {0, 0, 1});
}

TEST(ComputeNormals, SharedCubeCorner) {
  Mesh m = cube(d3d::FVF_XYZ | d3d::FVF_NORMAL, true);
  ASSERT_EQ(m.vertexCount(), 8u);
  uint32_t v = vertexAt(m, {1, 1, 1});
  // Angle weights: each of the three faces meets the corner with a right angle in
  // total (90 in one triangle, or 45 + 45 across the diagonal), so the sum is
  // (pi/2)(1,0,0) + (pi/2)(0,1,0) + (pi/2)(0,0,1) -> normalize(1,1,1).
  computeNormals(m);
  float s = 1 / std::sqrt(3.0f);
  expectVec(m.normal(v), {s, s, s});
  // Equal weights count triangles: (1,1,1) is TR (two triangles) of the +x face
  // (n + r - d = (1,0,0) + (0,0,1) + (0,1,0)) and of +y ((0,1,0) + (1,0,0) + (0,0,1)),
  // TL (one triangle) of +z ((0,0,1) + (1,0,0) + (0,1,0)): normalize(2,2,1) = (2,2,1)/3.
  computeNormals(m, {}, TANGENT_WEIGHT_EQUAL);
  expectVec(m.normal(v), {2.0f / 3, 2.0f / 3, 1.0f / 3});
  // Area weights: every triangle has area |cross(2r, 2d)|/2 = 2, so the same ratio.
  computeNormals(m, {}, TANGENT_WEIGHT_BY_AREA);
  expectVec(m.normal(v), {2.0f / 3, 2.0f / 3, 1.0f / 3});
  EXPECT_THROW(computeNormals(m, {}, TANGENT_WEIGHT_BY_AREA | TANGENT_WEIGHT_EQUAL), Error);
}

TEST(ComputeNormals, SplitCubeSmoothsOnlyThroughAdjacency) {
  Mesh m = cube(d3d::FVF_XYZ | d3d::FVF_NORMAL, false);
  // Without adjacency each vertex sums only its own face: the flat face normal.
  computeNormals(m);
  for (uint32_t f = 0; f < 6; ++f)
    for (int k = 0; k < 6; ++k) expectVec(m.normal(m.indices[6 * f + k]), kCubeFaces[f].n);
  // With adjacency the three replicas of a corner share one sum: corner / sqrt(3).
  std::vector<uint32_t> adj = generateAdjacency(m, 0.0f);
  computeNormals(m, adj);
  float s = 1 / std::sqrt(3.0f);
  for (uint32_t i = 0; i < m.vertexCount(); ++i) expectVec(m.normal(i), m.position(i) * s);
}

TEST(ComputeNormals, ReproducesTheShapesOutwardNormals) {
  // createBox stores flat outward normals for clockwise-from-outside faces: the
  // same as cross(e1, e2) per face.
  Mesh box = createBox(1, 2, 3), computed = box;
  computeNormals(computed);
  for (uint32_t i = 0; i < box.vertexCount(); ++i) expectVec(computed.normal(i), box.normal(i));
  // Sphere: the stored normal is position / radius; the weighted face normals
  // average to nearly it (exactly at the poles by symmetry).
  Mesh sphere = createSphere(2, 24, 12);
  computed = sphere;
  computeNormals(computed);
  for (uint32_t i = 0; i < sphere.vertexCount(); ++i) {
    EXPECT_NEAR(length(computed.normal(i)), 1.0f, 1e-5f);
    EXPECT_GT(dot(computed.normal(i), sphere.normal(i)), 0.999f) << "vertex " << i;
  }
  expectVec(computed.normal(0), {0, 0, 1});
}

TEST(ComputeNormals, NeedsANormalElementAndSurvivesDegenerateFaces) {
  Mesh noNormal = quad(d3d::FVF_XYZ);
  EXPECT_THROW(computeNormals(noNormal), Error);
  // Collinear positions have no direction: zero, never NaN. An unused vertex keeps
  // its normal.
  Mesh m = makeMesh(d3d::FVF_XYZ | d3d::FVF_NORMAL, {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {5, 5, 5}}, {0, 1, 2});
  m.setNormal(3, {0, 1, 0});
  computeNormals(m);
  for (uint32_t i = 0; i < 3; ++i) expectVec(m.normal(i), {0, 0, 0});
  expectVec(m.normal(3), {0, 1, 0});
  Mesh q = quad(d3d::FVF_XYZ | d3d::FVF_NORMAL);
  EXPECT_THROW(computeNormals(q, std::vector<uint32_t>{X, X}), Error);
}

TEST(Adjacency, TexturedSphereIsClosedAndEpsilonFindsJitteredReplicas) {
  // The seam column repeats column 0 and each pole row repeats one point, so with
  // replicas matched the sphere has no border edge.
  Mesh m = createTexturedSphere(1, 16, 8);
  std::vector<uint32_t> exact = generateAdjacency(m, 0.0f);
  for (uint32_t a : exact) EXPECT_NE(a, X);
  expectMutual(m, exact);
  EXPECT_EQ(generateAdjacency(m, 1e-5f), exact);
  // Replicas moved apart by up to 4e-6 per axis (across grid cells of 1e-5): an
  // epsilon of 1e-5 still joins them, 1e-7 does not.
  Mesh jittered = m;
  for (uint32_t i = 0; i < m.vertexCount(); ++i) {
    float d = float(int(i * 7919 % 9) - 4) * 1e-6f;
    Vec3 p = m.position(i);
    jittered.setPosition(i, {p.x + d, p.y - d, p.z + 0.5f * d});
  }
  EXPECT_EQ(generateAdjacency(jittered, 1e-5f), exact);
  std::vector<uint32_t> tight = generateAdjacency(jittered, 1e-7f);
  EXPECT_NE(std::count(tight.begin(), tight.end(), X), 0);
}

TEST(Weld, TexturedSphereReplicas) {
  // 17 x 9 = 153 vertices; distinct points: 2 poles + 16 * 7 rings = 114. The
  // replicas differ in u, so only WELD_ALL joins them. The pole vertices of the
  // first and last column belong to no face, so no edge makes them replicas: 116.
  Mesh m = createTexturedSphere(1, 16, 8);
  ASSERT_EQ(m.vertexCount(), 153u);
  Mesh all = m;
  weldVertices(all, 1e-6f);
  EXPECT_EQ(all.vertexCount(), 153u);
  weldVertices(all, 1e-6f, WELD_ALL);
  EXPECT_EQ(all.vertexCount(), 116u);
  // Normals smoothed across the seam through adjacency stay close to the analytic ones.
  Mesh smooth = m;
  computeNormals(smooth, generateAdjacency(smooth, 0.0f));
  for (uint32_t i = 1; i + 1 < m.vertexCount(); ++i)
    EXPECT_GT(dot(smooth.normal(i), m.normal(i)), 0.995f) << "vertex " << i;
}
