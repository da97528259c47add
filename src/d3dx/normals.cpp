// D3DXComputeNormals: angle-weighted (by default) sums of unit face normals.
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/mesh_ops.h"
#include "mesh_ops_internal.h"

namespace refx::d3dx {

void computeNormals(Mesh& mesh, std::span<const uint32_t> adjacency, uint32_t options) {
  const char* fn = "computeNormals";
  FVFLayout l = mesh.layout();
  if (l.normal < 0)
    fail("{}: the mesh (FVF 0x{:x}) has no NORMAL element to write; clone it with D3DFVF_NORMAL",
         fn, mesh.fvf);
  detail::checkTriangles(mesh, fn);
  if ((options & TANGENT_WEIGHT_BY_AREA) && (options & TANGENT_WEIGHT_EQUAL))
    fail("{}: TANGENT_WEIGHT_BY_AREA and TANGENT_WEIGHT_EQUAL exclude each other", fn);
  uint32_t n = mesh.vertexCount();
  std::vector<uint32_t> rep;
  if (!adjacency.empty()) rep = convertAdjacencyToPointReps(mesh, adjacency);
  auto group = [&](uint32_t v) { return rep.empty() ? v : rep[v]; };

  std::vector<Vec3> pos = detail::loadVec3s(mesh, l.position);
  std::vector<Vec3> sum(n);
  std::vector<uint8_t> used(n, 0);
  const std::vector<uint32_t>& idx = mesh.indices;
  for (size_t f = 0; f < idx.size(); f += 3) {
    uint32_t v[3] = {idx[f], idx[f + 1], idx[f + 2]};
    Vec3 p[3] = {pos[v[0]], pos[v[1]], pos[v[2]]};
    Vec3 normal;
    float w[3];
    bool valid = detail::faceNormalAndWeights(p, options, normal, w);
    for (int k = 0; k < 3; ++k) {
      used[v[k]] = 1;
      if (valid) sum[group(v[k])] = sum[group(v[k])] + normal * w[k];
    }
  }
  uint8_t* base = mesh.vertices.data() + l.normal;
  for (uint32_t i = 0; i < n; ++i) {
    if (!used[i]) continue;
    Vec3 s = sum[group(i)];
    float len = length(s);
    // Zero when the faces have no direction or cancel out (a double-sided sheet).
    detail::store3(base + size_t(i) * mesh.stride, len > 0 && std::isfinite(len) ? s * (1 / len) : Vec3{});
  }
}

}  // namespace refx::d3dx
