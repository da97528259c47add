// Pieces shared by the mesh operations (adjacency, normals, tangent frames).
#pragma once
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "refx/core/math.h"
#include "refx/d3dx/mesh.h"

namespace refx::d3dx::detail {

inline Vec3 load3(const uint8_t* p) {
  float f[3];
  std::memcpy(f, p, sizeof f);
  return {f[0], f[1], f[2]};
}
inline void store3(uint8_t* p, Vec3 v) {
  float f[3] = {v.x, v.y, v.z};
  std::memcpy(p, f, sizeof f);
}

inline bool isFinite(Vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Element `offset` (3 floats) of every vertex.
std::vector<Vec3> loadVec3s(const Mesh& mesh, int offset);

// Throws refx::Error naming `fn` when the mesh has no position or an index names a
// missing vertex.
void checkTriangles(const Mesh& mesh, const char* fn);

// Face normal and per-corner weights of triangle p[0..2]:
//   normal  = normalize(cross(p1 - p0, p2 - p0)), negated with TANGENT_WIND_CW;
//   weight  = angle at the corner (radians), or the face area (TANGENT_WEIGHT_BY_AREA),
//             or 1 (TANGENT_WEIGHT_EQUAL).
// Returns false (weights 0) for a face without a direction: collinear or repeated
// positions, or positions that are not finite.
bool faceNormalAndWeights(const Vec3 p[3], uint32_t options, Vec3& normal, float weight[3]);

}  // namespace refx::d3dx::detail
