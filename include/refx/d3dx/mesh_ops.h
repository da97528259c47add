// D3DX mesh operations: adjacency and point representatives, vertex welding,
// D3DXComputeNormals, D3DXComputeTangent and D3DXComputeTangentFrame(Ex).
//
// Conventions (as D3DX): the face normal of triangle (p0, p1, p2) is
// cross(p1 - p0, p2 - p0), which for D3D's clockwise front faces in its
// left-handed space points toward the viewer (outward); TANGENT_WIND_CW flips it.
// Tangent = dP/du and binormal = dP/dv of the texture mapping, with v growing
// downward in D3D texture space.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "refx/d3dx/mesh.h"

namespace refx::d3dx {

// Adjacency entry for an edge with no neighbouring face (0xffffffff, as D3DX).
constexpr uint32_t kNoNeighbor = 0xffffffffu;

// D3DXGenerateAdjacency: 3 entries per face; entry 3f+k is the face across edge k
// (from corner k to corner k+1 mod 3) of face f, or kNoNeighbor. Positions whose
// x, y and z each differ by at most `epsilon` are the same point; two faces are
// neighbours when they run along the same pair of points in opposite directions
// (consistently wound). Each edge is paired with at most one other edge, and the
// pairing is mutual. Edges whose two ends are the same point have no neighbour.
// Positions are hashed on a grid, so the cost is O(n log n) while epsilon is small
// against the mesh; non-finite positions match nothing. Throws refx::Error for a
// negative or non-finite epsilon and for indices past the vertices.
std::vector<uint32_t> generateAdjacency(const Mesh& mesh, float epsilon);

// ID3DXBaseMesh::ConvertAdjacencyToPointReps: for each vertex, the lowest vertex
// index reachable from it through edges the adjacency pairs up (vertices that are
// replicas of one point). Vertices that no face uses are their own representative.
// Throws refx::Error when the adjacency has the wrong size or names a missing face.
std::vector<uint32_t> convertAdjacencyToPointReps(const Mesh& mesh,
                                                  std::span<const uint32_t> adjacency);

// D3DXWELDEPSILONS_* flags.
enum WeldFlags : uint32_t {
  WELD_ALL = 0x1,                   // weld replicas of a point whatever their other elements
  WELD_DONOTREMOVEVERTICES = 0x8,   // keep welded-away vertices (unused) in the buffer
};

// D3DXWeldVertices with one epsilon for every element (D3DXWELDEPSILONS filled
// with `epsilon`): vertices that are replicas of one point (the point
// representatives of `adjacency`, or of generateAdjacency(mesh, epsilon) when it is
// empty) and whose other elements (normal, point size, colors as 0..1 channels,
// every texture coordinate set) each differ by at most `epsilon` become one vertex;
// the indices are remapped and the vertex buffer compacted (the first vertex of
// each welded group keeps its place in order). Returns, for every old vertex, its
// new index.
std::vector<uint32_t> weldVertices(Mesh& mesh, float epsilon, uint32_t flags = 0,
                                   std::span<const uint32_t> adjacency = {});

// D3DXTANGENT_* option flags.
enum TangentFlags : uint32_t {
  TANGENT_WRAP_U = 0x01,
  TANGENT_WRAP_V = 0x02,
  TANGENT_WRAP_UV = 0x03,
  TANGENT_DONT_NORMALIZE_PARTIALS = 0x04,
  TANGENT_DONT_ORTHOGONALIZE = 0x08,
  TANGENT_ORTHOGONALIZE_FROM_V = 0x10,
  TANGENT_ORTHOGONALIZE_FROM_U = 0x20,
  TANGENT_WEIGHT_BY_AREA = 0x40,
  TANGENT_WEIGHT_EQUAL = 0x80,
  TANGENT_WIND_CW = 0x100,
  TANGENT_CALCULATE_NORMALS = 0x200,
  TANGENT_GENERATE_IN_PLACE = 0x400,
};

// D3DXComputeNormals: each vertex normal becomes the normalized sum of the unit
// normals of the faces around it, each weighted by the angle of the face at that
// corner (options TANGENT_WEIGHT_BY_AREA: by the face area, TANGENT_WEIGHT_EQUAL:
// by 1; TANGENT_WIND_CW flips the face normals). With an adjacency, the replicas of
// a point (convertAdjacencyToPointReps) share one sum; without, each vertex sums
// only the faces that use its index. Vertices whose faces all have zero area get
// (0, 0, 0); vertices no face uses keep their normal. Throws refx::Error when the
// mesh has no NORMAL element.
void computeNormals(Mesh& mesh, std::span<const uint32_t> adjacency = {}, uint32_t options = 0);

// D3DXComputeTangentFrameEx, with the outputs as FVF texture coordinate sets.
struct TangentFrameOptions {
  uint32_t flags = 0;     // TANGENT_*
  int texIn = 0;          // texture coordinate set holding (u, v)
  int tangentOut = 1;     // set receiving dP/du (3 floats); -1: not written
  int binormalOut = -1;   // set receiving dP/dv (3 floats); -1: not written
  // Used to compute the normals with TANGENT_CALCULATE_NORMALS (see computeNormals).
  std::span<const uint32_t> adjacency = {};
};

// Per-vertex tangent frame from the texture mapping of set `texIn`:
//  * per face: e1 = p1 - p0, e2 = p2 - p0, (s1, t1) = uv1 - uv0, (s2, t2) = uv2 - uv0,
//    dP/du = (e1 t2 - e2 t1) / (s1 t2 - s2 t1), dP/dv = (e2 s1 - e1 s2) / (s1 t2 - s2 t1);
//    with TANGENT_WRAP_U (V) a coordinate difference beyond +-0.5 is taken the short
//    way around (d - round(d)), for meshes whose seams are not split;
//  * per vertex: the partials (normalized per face unless DONT_NORMALIZE_PARTIALS,
//    then their weighted mean length is kept) summed with angle / area / equal
//    weights as computeNormals, then made orthonormal to the vertex normal N with
//    b = h cross(N, t), h = +1 or -1 the handedness of the mapping: by default t is
//    the bisector of dP/du and of the tangent dP/dv implies (h cross(dP/dv, N)), both
//    Gram-Schmidt'ed against N, so a shear is shared evenly; ORTHOGONALIZE_FROM_U
//    keeps dP/du, FROM_V keeps dP/dv; DONT_ORTHOGONALIZE only normalizes;
//  * faces whose mapping is mirrored (u or v reversed) are not averaged with the
//    others: a vertex shared by both kinds is split in two (the new vertex is a copy
//    appended to the buffer, the faces of the lighter side use it; equal weights
//    keep the positive side). With TANGENT_GENERATE_IN_PLACE (what
//    D3DXComputeTangentFrame always passes) nothing is split and the vertex keeps
//    the heavier side's frame;
//  * degenerate bases are fixed, never NaN: faces with zero area in texture space
//    or in position give no partials; a vertex left without one partial derives it
//    from the other and N; with neither, the tangent is the axis least aligned with
//    N (x, then y, then z on ties) made perpendicular to it; an unusable normal
//    (zero, not finite) is replaced by the faces' geometric normal (or one
//    perpendicular to the partials) and written.
// The output sets are added (3 floats each, through cloneMeshFVF) when the FVF has
// fewer sets; an existing output set with fewer than 3 floats is an error, one with
// 4 floats receives h in w. With TANGENT_CALCULATE_NORMALS the normals are computed
// first (a NORMAL element is added when missing); otherwise the mesh must have
// normals. Vertices no face uses are left unchanged. Returns, for every vertex of
// the result, the vertex it was made from (identity unless vertices were split).
// Throws refx::Error on bad input.
std::vector<uint32_t> computeTangentFrame(Mesh& mesh, const TangentFrameOptions& options = {});

// D3DXComputeTangent (legacy): tangent (dP/du) into set `tangentIndex`, binormal
// (dP/dv) into set `binormalIndex` (-1: none) from the coordinates of set
// `texStage`; wrap = true is TANGENT_WRAP_UV. Computed in place (no vertex is split,
// TANGENT_GENERATE_IN_PLACE), made orthonormal to the normals when the mesh has
// them, otherwise only normalized (TANGENT_DONT_ORTHOGONALIZE).
void computeTangent(Mesh& mesh, int texStage, int tangentIndex, int binormalIndex, bool wrap);

}  // namespace refx::d3dx
