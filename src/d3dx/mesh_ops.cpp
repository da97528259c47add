// D3DXGenerateAdjacency, ConvertAdjacencyToPointReps and D3DXWeldVertices.
// Coincident positions are found through a grid hash and edges through a sorted
// edge list, so everything runs in O(n log n) for meshes whose epsilon is small
// against their size.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <unordered_map>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/mesh_ops.h"
#include "mesh_ops_internal.h"

namespace refx::d3dx {

namespace detail {

std::vector<Vec3> loadVec3s(const Mesh& mesh, int offset) {
  uint32_t n = mesh.vertexCount();
  std::vector<Vec3> out(n);
  const uint8_t* base = mesh.vertices.data() + offset;
  for (uint32_t i = 0; i < n; ++i) out[i] = load3(base + size_t(i) * mesh.stride);
  return out;
}

void checkTriangles(const Mesh& mesh, const char* fn) {
  if (mesh.layout().position < 0) fail("{}: the mesh (FVF 0x{:x}) has no position", fn, mesh.fvf);
  if (mesh.indices.size() % 3)
    fail("{}: {} indices is not a whole number of triangles", fn, mesh.indices.size());
  uint32_t n = mesh.vertexCount();
  for (size_t i = 0; i < mesh.indices.size(); ++i)
    if (mesh.indices[i] >= n)
      fail("{}: face {} uses vertex {}, the mesh has {} vertices", fn, i / 3, mesh.indices[i], n);
}

bool faceNormalAndWeights(const Vec3 p[3], uint32_t options, Vec3& normal, float weight[3]) {
  weight[0] = weight[1] = weight[2] = 0;
  normal = {};
  Vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
  Vec3 g = cross(e1, e2);
  float len = length(g);
  // sin(angle) below 1e-6 is within float rounding of collinear: no direction.
  if (!std::isfinite(len) || !(len > 1e-6f * length(e1) * length(e2))) return false;
  normal = g * ((options & TANGENT_WIND_CW) ? -1.0f / len : 1.0f / len);
  if (options & TANGENT_WEIGHT_EQUAL) {
    weight[0] = weight[1] = weight[2] = 1;
  } else if (options & TANGENT_WEIGHT_BY_AREA) {
    weight[0] = weight[1] = weight[2] = 0.5f * len;
  } else {
    // Corner angles from the edges leaving corners 0 and 1; the three sum to pi.
    Vec3 e12 = p[2] - p[1];
    float l1 = length(e1), l2 = length(e2), l12 = length(e12);
    float c0 = dot(e1, e2) / (l1 * l2), c1 = -dot(e1, e12) / (l1 * l12);
    weight[0] = std::acos(std::clamp(c0, -1.0f, 1.0f));
    weight[1] = std::acos(std::clamp(c1, -1.0f, 1.0f));
    weight[2] = std::max(0.0f, 3.14159265358979f - weight[0] - weight[1]);
  }
  return true;
}

}  // namespace detail

namespace {

using detail::checkTriangles;

// Disjoint sets whose root is always the lowest index of its set.
struct LowestIndexSets {
  std::vector<uint32_t> parent;
  explicit LowestIndexSets(uint32_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  uint32_t find(uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  }
  void unite(uint32_t a, uint32_t b) {
    a = find(a), b = find(b);
    if (a < b) parent[b] = a;
    else if (b < a) parent[a] = b;
  }
  std::vector<uint32_t> roots() {
    std::vector<uint32_t> r(parent.size());
    for (uint32_t v = 0; v < r.size(); ++v) r[v] = find(v);
    return r;
  }
};

void requireEpsilon(const char* fn, float epsilon) {
  if (!(epsilon >= 0) || !std::isfinite(epsilon))
    fail("{}: epsilon must be a finite value >= 0, not {}", fn, epsilon);
}

// For every vertex the lowest index of the vertices whose positions are within
// epsilon of it on each axis (chained). Positions are bucketed in a grid of cells
// no smaller than epsilon, so close points lie in the same or a neighbouring cell.
// The cells are at least 2^-20 of the mesh extent: a cell then holds at most a few
// distinct float positions per axis beyond exact duplicates, which are joined first.
std::vector<uint32_t> coincidentPoints(const std::vector<Vec3>& pos, float epsilon) {
  uint32_t n = uint32_t(pos.size());
  LowestIndexSets sets(n);
  Vec3 lo{std::numeric_limits<float>::max(), std::numeric_limits<float>::max(),
          std::numeric_limits<float>::max()};
  Vec3 hi = lo * -1.0f;
  std::vector<uint32_t> order;
  order.reserve(n);
  for (uint32_t i = 0; i < n; ++i) {
    Vec3 p = pos[i];
    if (!detail::isFinite(p)) continue;  // never the same point as anything
    order.push_back(i);
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  if (order.empty()) return sets.roots();
  double extent = std::max({double(hi.x) - lo.x, double(hi.y) - lo.y, double(hi.z) - lo.z});
  double cell = std::max(double(epsilon), extent * 0x1p-20);
  if (!(cell > 0)) cell = 1;
  constexpr uint64_t kMaxCell = (uint64_t(1) << 21) - 1;
  auto axisCell = [&](float v, float origin) {
    double c = std::floor((double(v) - origin) / cell);
    return uint64_t(std::clamp(c, 0.0, double(kMaxCell)));
  };
  std::vector<uint64_t> key(n, 0);
  for (uint32_t i : order)
    key[i] = axisCell(pos[i].x, lo.x) << 42 | axisCell(pos[i].y, lo.y) << 21 | axisCell(pos[i].z, lo.z);
  auto before = [&](uint32_t a, uint32_t b) {
    if (key[a] != key[b]) return key[a] < key[b];
    Vec3 p = pos[a], q = pos[b];
    if (p.x != q.x) return p.x < q.x;
    if (p.y != q.y) return p.y < q.y;
    if (p.z != q.z) return p.z < q.z;
    return a < b;
  };
  std::sort(order.begin(), order.end(), before);
  // Exact duplicates are neighbours in this order.
  std::vector<uint32_t> distinct;
  for (size_t j = 0; j < order.size(); ++j) {
    if (j && pos[order[j]] == pos[order[j - 1]]) sets.unite(order[j], order[j - 1]);
    else distinct.push_back(order[j]);
  }
  if (epsilon == 0) return sets.roots();
  std::unordered_map<uint64_t, std::pair<uint32_t, uint32_t>> cells;
  cells.reserve(distinct.size());
  for (uint32_t j = 0; j < distinct.size(); ++j) {
    auto [it, fresh] = cells.try_emplace(key[distinct[j]], j, j + 1);
    if (!fresh) it->second.second = j + 1;
  }
  auto close = [&](Vec3 p, Vec3 q) {
    return std::fabs(p.x - q.x) <= epsilon && std::fabs(p.y - q.y) <= epsilon &&
           std::fabs(p.z - q.z) <= epsilon;
  };
  for (uint32_t j = 0; j < distinct.size(); ++j) {
    uint32_t a = distinct[j];
    uint64_t k = key[a];
    int64_t cx = int64_t(k >> 42), cy = int64_t((k >> 21) & kMaxCell), cz = int64_t(k & kMaxCell);
    // Later entries of the own cell, and neighbour cells with a greater key: every
    // pair of cells is visited once.
    for (uint32_t m = j + 1; m < distinct.size() && key[distinct[m]] == k; ++m)
      if (close(pos[a], pos[distinct[m]])) sets.unite(a, distinct[m]);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          int64_t x = cx + dx, y = cy + dy, z = cz + dz;
          if (x < 0 || y < 0 || z < 0 || x > int64_t(kMaxCell) || y > int64_t(kMaxCell) ||
              z > int64_t(kMaxCell))
            continue;
          uint64_t nk = uint64_t(x) << 42 | uint64_t(y) << 21 | uint64_t(z);
          if (nk <= k) continue;
          auto it = cells.find(nk);
          if (it == cells.end()) continue;
          for (uint32_t m = it->second.first; m < it->second.second; ++m)
            if (close(pos[a], pos[distinct[m]])) sets.unite(a, distinct[m]);
        }
  }
  return sets.roots();
}

}  // namespace

std::vector<uint32_t> generateAdjacency(const Mesh& mesh, float epsilon) {
  const char* fn = "generateAdjacency";
  requireEpsilon(fn, epsilon);
  checkTriangles(mesh, fn);
  std::vector<uint32_t> point =
      coincidentPoints(detail::loadVec3s(mesh, mesh.layout().position), epsilon);
  const std::vector<uint32_t>& idx = mesh.indices;
  size_t corners = idx.size();
  auto edgeKey = [&](size_t c, bool reversed) {
    size_t next = c - c % 3 + (c % 3 + 1) % 3;
    uint64_t a = point[idx[c]], b = point[idx[next]];
    return reversed ? (b << 32 | a) : (a << 32 | b);
  };
  // Directed edges sorted by their (from, to) points.
  std::vector<std::pair<uint64_t, uint32_t>> edges(corners);
  for (size_t c = 0; c < corners; ++c) edges[c] = {edgeKey(c, false), uint32_t(c)};
  std::sort(edges.begin(), edges.end());

  std::vector<uint32_t> adjacency(corners, kNoNeighbor);
  // hint[lo]: first entry of the run starting at lo that may still be unpaired.
  std::vector<uint32_t> hint(corners + 1, 0);
  for (size_t c = 0; c < corners; ++c) {
    if (adjacency[c] != kNoNeighbor) continue;
    uint64_t want = edgeKey(c, true);
    if ((want >> 32) == (want & 0xffffffffu)) continue;  // both ends one point
    auto first = std::lower_bound(edges.begin(), edges.end(), std::pair<uint64_t, uint32_t>{want, 0});
    size_t lo = size_t(first - edges.begin());
    uint32_t face = uint32_t(c / 3);
    size_t j = std::max<size_t>(lo, hint[lo]);
    while (j < corners && edges[j].first == want && adjacency[edges[j].second] != kNoNeighbor) ++j;
    hint[lo] = uint32_t(j);
    for (; j < corners && edges[j].first == want; ++j) {
      uint32_t other = edges[j].second;
      if (adjacency[other] != kNoNeighbor || other / 3 == face) continue;
      adjacency[c] = other / 3;
      adjacency[other] = face;
      break;
    }
  }
  return adjacency;
}

std::vector<uint32_t> convertAdjacencyToPointReps(const Mesh& mesh,
                                                  std::span<const uint32_t> adjacency) {
  const char* fn = "convertAdjacencyToPointReps";
  checkTriangles(mesh, fn);
  uint32_t faces = mesh.faceCount();
  if (adjacency.size() != size_t(faces) * 3)
    fail("{}: the adjacency has {} entries, the mesh's {} faces need {}", fn, adjacency.size(),
         faces, size_t(faces) * 3);
  for (size_t i = 0; i < adjacency.size(); ++i)
    if (adjacency[i] != kNoNeighbor && adjacency[i] >= faces)
      fail("{}: adjacency entry {} names face {}, the mesh has {} faces", fn, i, adjacency[i], faces);
  std::vector<Vec3> pos = detail::loadVec3s(mesh, mesh.layout().position);
  const std::vector<uint32_t>& idx = mesh.indices;
  auto at = [&](uint32_t face, int k) { return idx[3 * size_t(face) + size_t(k % 3)]; };
  LowestIndexSets sets(mesh.vertexCount());
  for (uint32_t f = 0; f < faces; ++f)
    for (int k = 0; k < 3; ++k) {
      uint32_t g = adjacency[3 * size_t(f) + k];
      if (g == kNoNeighbor || g == f) continue;
      // The edge of g that runs back along edge k of f: preferably one whose adjacency
      // names f, then the one whose ends are closest to this edge's ends.
      Vec3 a = pos[at(f, k)], b = pos[at(f, k + 1)];
      int best = -1;
      bool bestBack = false;
      float bestDist = 0;
      for (int m = 0; m < 3; ++m) {
        bool back = adjacency[3 * size_t(g) + m] == f;
        Vec3 da = a - pos[at(g, m + 1)], db = b - pos[at(g, m)];
        float dist = dot(da, da) + dot(db, db);
        if (best < 0 || (back && !bestBack) || (back == bestBack && dist < bestDist))
          best = m, bestBack = back, bestDist = dist;
      }
      sets.unite(at(f, k), at(g, best + 1));
      sets.unite(at(f, k + 1), at(g, best));
    }
  return sets.roots();
}

namespace {

// The parts of an FVF vertex compared when welding: runs of floats, and colors
// compared per 8-bit channel in 0..1 units.
struct WeldFields {
  std::vector<std::pair<int, int>> floats;  // byte offset, float count
  std::vector<int> colors;                  // byte offset of a D3DCOLOR
  explicit WeldFields(const FVFLayout& l) {
    int positionEnd = int(l.stride);
    for (int off : {l.normal, l.psize, l.diffuse, l.specular, l.texCoord[0]})
      if (off >= 0) positionEnd = std::min(positionEnd, off);
    if (l.position >= 0) floats.push_back({l.position, positionEnd / 4});
    if (l.normal >= 0) floats.push_back({l.normal, 3});
    if (l.psize >= 0) floats.push_back({l.psize, 1});
    if (l.diffuse >= 0) colors.push_back(l.diffuse);
    if (l.specular >= 0) colors.push_back(l.specular);
    for (int s = 0; s < 8; ++s)
      if (l.texCoord[s] >= 0) floats.push_back({l.texCoord[s], l.texDims[s]});
  }
  bool match(const uint8_t* a, const uint8_t* b, float eps) const {
    for (auto [off, count] : floats)
      for (int i = 0; i < count; ++i) {
        float x, y;
        std::memcpy(&x, a + off + 4 * i, 4);
        std::memcpy(&y, b + off + 4 * i, 4);
        if (!(std::fabs(x - y) <= eps)) return false;
      }
    for (int off : colors)
      for (int i = 0; i < 4; ++i)
        if (!(std::abs(int(a[off + i]) - int(b[off + i])) / 255.0f <= eps)) return false;
    return true;
  }
};

}  // namespace

std::vector<uint32_t> weldVertices(Mesh& mesh, float epsilon, uint32_t flags,
                                   std::span<const uint32_t> adjacency) {
  const char* fn = "weldVertices";
  requireEpsilon(fn, epsilon);
  checkTriangles(mesh, fn);
  std::vector<uint32_t> generated;
  if (adjacency.empty()) {
    generated = generateAdjacency(mesh, epsilon);
    adjacency = generated;
  }
  std::vector<uint32_t> rep = convertAdjacencyToPointReps(mesh, adjacency);
  uint32_t n = mesh.vertexCount();
  WeldFields fields(mesh.layout());
  // Each replica is compared with the distinct vertices kept so far for its point
  // (a short list: the distinct vertices of one point).
  constexpr uint32_t kNone = 0xffffffffu;
  std::vector<uint32_t> target(n), nextKept(n, kNone), lastKept(n, kNone);
  auto vertex = [&](uint32_t v) { return mesh.vertices.data() + size_t(v) * mesh.stride; };
  for (uint32_t v = 0; v < n; ++v) {
    uint32_t r = rep[v];
    target[v] = v;
    if (r != v) {
      if (flags & WELD_ALL) {
        target[v] = r;
        continue;
      }
      uint32_t k = r;
      for (; k != kNone; k = nextKept[k])
        if (fields.match(vertex(k), vertex(v), epsilon)) break;
      if (k != kNone) {
        target[v] = k;
        continue;
      }
      nextKept[lastKept[r]] = v;
    }
    lastKept[r] = v;
  }
  std::vector<uint32_t> newIndex(n);
  if (flags & WELD_DONOTREMOVEVERTICES) {
    newIndex = target;
  } else {
    std::vector<uint8_t> kept;
    kept.reserve(mesh.vertices.size());
    uint32_t count = 0;
    for (uint32_t v = 0; v < n; ++v) {
      if (target[v] != v) continue;
      newIndex[v] = count++;
      kept.insert(kept.end(), vertex(v), vertex(v) + mesh.stride);
    }
    for (uint32_t v = 0; v < n; ++v) newIndex[v] = newIndex[target[v]];
    mesh.vertices = std::move(kept);
  }
  for (uint32_t& i : mesh.indices) i = newIndex[i];
  return newIndex;
}

}  // namespace refx::d3dx
