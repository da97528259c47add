// Per-vertex hemisphere visibility: rays against the mesh's own triangles through a
// bounding-volume hierarchy.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/lighting_maps.h"

namespace refx::d3dx {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

Vec3 vmin(Vec3 a, Vec3 b) { return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)}; }
Vec3 vmax(Vec3 a, Vec3 b) { return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)}; }
float axis(Vec3 v, int a) { return a == 0 ? v.x : a == 1 ? v.y : v.z; }

struct Triangle {
  Vec3 p0, e1, e2;  // corner and the two edges from it
};

struct Node {
  Vec3 lo, hi;
  uint32_t first = 0;  // leaf: first triangle; inner: index of the left child
  uint32_t count = 0;  // leaf: triangle count; 0 for inner nodes (right child = first + 1)
};

class Bvh {
 public:
  explicit Bvh(std::vector<Triangle> tris) : tris_(std::move(tris)) {
    if (tris_.empty()) return;
    std::vector<uint32_t> order(tris_.size());
    std::iota(order.begin(), order.end(), 0u);
    centroids_.resize(tris_.size());
    for (size_t i = 0; i < tris_.size(); ++i) {
      const Triangle& t = tris_[i];
      centroids_[i] = t.p0 + (t.e1 + t.e2) * (1.0f / 3.0f);
    }
    nodes_.reserve(2 * tris_.size());
    nodes_.push_back({});
    build(0, order, 0, uint32_t(order.size()));
    std::vector<Triangle> sorted(tris_.size());
    for (size_t i = 0; i < order.size(); ++i) sorted[i] = tris_[order[i]];
    tris_ = std::move(sorted);
  }

  // True when the ray o + t d, tMin < t < tMax, hits any triangle (either side).
  bool occluded(Vec3 o, Vec3 d, float tMin, float tMax) const {
    if (nodes_.empty()) return false;
    Vec3 inv{1.0f / d.x, 1.0f / d.y, 1.0f / d.z};
    uint32_t stack[64];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = nodes_[stack[--top]];
      if (!hitsBox(n, o, inv, tMin, tMax)) continue;
      if (n.count > 0) {
        for (uint32_t i = n.first; i < n.first + n.count; ++i)
          if (hitsTriangle(tris_[i], o, d, tMin, tMax)) return true;
      } else if (top + 2 <= 64) {
        stack[top++] = n.first + 1;
        stack[top++] = n.first;
      }
    }
    return false;
  }

 private:
  void build(uint32_t index, std::vector<uint32_t>& order, uint32_t begin, uint32_t end) {
    Vec3 lo{kInf, kInf, kInf}, hi = lo * -1.0f, clo = lo, chi = hi;
    for (uint32_t i = begin; i < end; ++i) {
      const Triangle& t = tris_[order[i]];
      Vec3 p1 = t.p0 + t.e1, p2 = t.p0 + t.e2;
      lo = vmin(lo, vmin(t.p0, vmin(p1, p2)));
      hi = vmax(hi, vmax(t.p0, vmax(p1, p2)));
      clo = vmin(clo, centroids_[order[i]]);
      chi = vmax(chi, centroids_[order[i]]);
    }
    nodes_[index].lo = lo;
    nodes_[index].hi = hi;
    Vec3 extent = chi - clo;
    int a = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    if (end - begin <= 4 || axis(extent, a) <= 0) {
      nodes_[index].first = begin;
      nodes_[index].count = end - begin;
      return;
    }
    // Median split on the widest axis of the centroids (ties by index: deterministic).
    uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                     [&](uint32_t x, uint32_t y) {
                       float cx = axis(centroids_[x], a), cy = axis(centroids_[y], a);
                       return cx < cy || (cx == cy && x < y);
                     });
    uint32_t left = uint32_t(nodes_.size());
    nodes_[index].first = left;
    nodes_[index].count = 0;
    nodes_.push_back({});
    nodes_.push_back({});
    build(left, order, begin, mid);
    build(left + 1, order, mid, end);
  }

  static bool hitsBox(const Node& n, Vec3 o, Vec3 inv, float tMin, float tMax) {
    for (int a = 0; a < 3; ++a) {
      float t0 = (axis(n.lo, a) - axis(o, a)) * axis(inv, a);
      float t1 = (axis(n.hi, a) - axis(o, a)) * axis(inv, a);
      if (t0 > t1) std::swap(t0, t1);
      // NaN (0 * inf for a ray in the slab's plane) keeps the interval unchanged.
      if (t0 > tMin) tMin = t0;
      if (t1 < tMax) tMax = t1;
      if (tMin > tMax) return false;
    }
    return true;
  }

  // Möller-Trumbore, two-sided.
  static bool hitsTriangle(const Triangle& t, Vec3 o, Vec3 d, float tMin, float tMax) {
    Vec3 p = cross(d, t.e2);
    float det = dot(t.e1, p);
    if (std::fabs(det) < 1e-20f) return false;
    float inv = 1.0f / det;
    Vec3 s = o - t.p0;
    float u = dot(s, p) * inv;
    if (u < 0 || u > 1) return false;
    Vec3 q = cross(s, t.e1);
    float v = dot(d, q) * inv;
    if (v < 0 || u + v > 1) return false;
    float dist = dot(t.e2, q) * inv;
    return dist > tMin && dist < tMax;
  }

  std::vector<Triangle> tris_;
  std::vector<Vec3> centroids_;
  std::vector<Node> nodes_;
};

// Any unit vector perpendicular to n, chosen without branches on tiny components.
Vec3 perpendicular(Vec3 n) {
  Vec3 helper = std::fabs(n.x) < 0.6f ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  return normalize(cross(helper, n));
}

}  // namespace

std::vector<Vec3> hemisphereRayDirections(int rays, bool cosineWeighted) {
  if (rays < 1 || rays > 65536) fail("hemisphere rays: count must be between 1 and 65536, not {}", rays);
  // Fibonacci spiral: ray k at azimuth k * golden angle; equal-area steps in z
  // (uniform) or in z² (cosine weighted, whose density is 2 z dz).
  const double golden = 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
  std::vector<Vec3> dirs(static_cast<size_t>(rays));
  for (int k = 0; k < rays; ++k) {
    double f = (double(k) + 0.5) / double(rays);
    double z = cosineWeighted ? std::sqrt(1.0 - f) : 1.0 - f;
    double r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = golden * double(k);
    dirs[size_t(k)] = {float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)};
  }
  return dirs;
}

std::vector<float> computeHemisphereVisibility(const Mesh& mesh, const OcclusionOptions& options) {
  const FVFLayout layout = mesh.layout();
  if (layout.position < 0) fail("computeHemisphereVisibility: the mesh has no positions");
  if (!(options.bias >= 0) || !std::isfinite(options.bias))
    fail("computeHemisphereVisibility: bias must be a finite value >= 0, not {}", options.bias);
  if (!(options.maxDistance >= 0)) fail("computeHemisphereVisibility: maxDistance must be >= 0");
  const std::vector<Vec3> dirs = hemisphereRayDirections(options.rays, options.cosineWeighted);
  const uint32_t nv = mesh.vertexCount(), nf = mesh.faceCount();
  for (uint32_t i : mesh.indices)
    if (i >= nv) fail("computeHemisphereVisibility: index {} is past the {} vertices", i, nv);

  std::vector<Vec3> pos(nv);
  for (uint32_t v = 0; v < nv; ++v) {
    pos[v] = mesh.position(v);
    if (!std::isfinite(pos[v].x) || !std::isfinite(pos[v].y) || !std::isfinite(pos[v].z))
      fail("computeHemisphereVisibility: vertex {} has a position that is not finite", v);
  }
  std::vector<Triangle> tris;
  tris.reserve(nf);
  std::vector<Vec3> faceNormalSum(layout.normal < 0 ? nv : 0);
  // Mean length of the edges at each vertex: the scale of the origin offset.
  std::vector<float> edgeSum(nv, 0.0f);
  std::vector<uint32_t> edgeCount(nv, 0);
  for (uint32_t f = 0; f < nf; ++f) {
    const uint32_t* idx = &mesh.indices[3 * f];
    Vec3 a = pos[idx[0]], b = pos[idx[1]], c = pos[idx[2]];
    for (int k = 0; k < 3; ++k) {
      float e = length(pos[idx[(k + 1) % 3]] - pos[idx[k]]);
      edgeSum[idx[k]] += e, edgeSum[idx[(k + 1) % 3]] += e;
      ++edgeCount[idx[k]], ++edgeCount[idx[(k + 1) % 3]];
    }
    Triangle t{a, b - a, c - a};
    Vec3 n = cross(t.e1, t.e2);  // |n| = 2 * area; outward for clockwise front faces
    if (!faceNormalSum.empty())
      for (int k = 0; k < 3; ++k) faceNormalSum[mesh.indices[3 * f + k]] = faceNormalSum[mesh.indices[3 * f + k]] + n;
    if (length(n) > 0) tris.push_back(t);
  }
  const Bvh bvh(std::move(tris));
  const float tMax = options.maxDistance > 0 ? options.maxDistance : kInf;

  std::vector<float> visibility(nv, 1.0f);
  for (uint32_t v = 0; v < nv; ++v) {
    Vec3 n = normalize(layout.normal >= 0 ? mesh.normal(v) : faceNormalSum[v]);
    if (!(length(n) > 0.5f)) continue;  // no direction to look in: leave it open
    Vec3 t = perpendicular(n), b = cross(n, t);
    float lift = edgeCount[v] ? options.bias * edgeSum[v] / float(edgeCount[v]) : 0.0f;
    Vec3 origin = pos[v] + n * lift;
    int open = 0;
    for (const Vec3& d : dirs) {
      Vec3 w = t * d.x + b * d.y + n * d.z;
      if (!bvh.occluded(origin, w, 0.0f, tMax)) ++open;
    }
    visibility[v] = float(open) / float(dirs.size());
  }
  return visibility;
}

}  // namespace refx::d3dx
