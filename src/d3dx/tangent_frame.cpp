// D3DXComputeTangentFrame(Ex) and D3DXComputeTangent: per-face partial
// derivatives of the position with respect to the texture coordinates, summed per
// vertex and handedness, made orthonormal to the normal, with degenerate bases
// repaired (no zero or NaN vectors come out).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/mesh_ops.h"
#include "mesh_ops_internal.h"

namespace refx::d3dx {

namespace {

using detail::isFinite;
constexpr uint32_t kNone = 0xffffffffu;

// Corners of one handedness at one vertex.
struct Side {
  Vec3 t, b, g;         // weighted sums of dP/du, dP/dv and of the unit face normals
  float weight = 0;     // sum of the corner weights
  float tScale = 0, bScale = 0;  // sums of weight * |partial|: the longest the sums can be
  uint32_t corners = 0;
};

bool usable(Vec3 v, float scale) {
  float len = length(v);
  return std::isfinite(len) && len > 0 && len > 1e-4f * scale;
}

// v normalized, or ok = false when it has no usable direction.
Vec3 unit(Vec3 v, bool& ok) {
  float len = length(v);
  ok = std::isfinite(len) && len > 1e-30f;
  return ok ? v * (1 / len) : v;
}

// Unit vector perpendicular to the unit vector n: the axis least aligned with n,
// its n component removed.
Vec3 perpendicular(Vec3 n) {
  float ax = std::fabs(n.x), ay = std::fabs(n.y), az = std::fabs(n.z);
  Vec3 axis = ax <= ay && ax <= az ? Vec3{1, 0, 0} : ay <= az ? Vec3{0, 1, 0} : Vec3{0, 0, 1};
  return normalize(axis - n * dot(n, axis));
}

// v made perpendicular to the unit n and normalized. When most of v was along n
// the rounding left in the remainder is removed by a second pass.
Vec3 orthonormal(Vec3 v, Vec3 n) {
  Vec3 r = v - n * dot(n, v);
  if (dot(r, r) < 0.25f * dot(v, v)) r = r - n * dot(n, r);
  bool ok;
  r = unit(r, ok);
  return ok ? r : perpendicular(n);
}

// Unit h * cross(a, b), or the fallback when a and b are parallel.
template <typename Fallback>
Vec3 unitCross(Vec3 a, Vec3 b, float h, Fallback fallback) {
  bool ok;
  Vec3 v = unit(cross(a, b) * h, ok);
  return ok ? v : fallback();
}

struct Frame {
  Vec3 t, b, n;
  float h = 1;               // b = h * cross(n, t) for an orthonormal frame
  bool normalFixed = false;  // the stored normal was unusable and n replaces it
};

// side: the corners used; extra: corners without partials (their normals help
// only when the vertex has no usable normal); sign: +1 / -1 the handedness of the
// side's faces in texture space (sign of s1 t2 - s2 t1), 0 when it has none.
Frame solveFrame(const Side& side, const Side& extra, int sign, Vec3 stored, bool hasStored,
                 uint32_t flags) {
  Frame f;
  float wind = (flags & TANGENT_WIND_CW) ? -1.0f : 1.0f;
  bool handednessFromPartials = false;
  f.n = stored;
  if (!(hasStored && usable(stored, 0))) {
    f.normalFixed = hasStored;
    Vec3 g = side.g + extra.g;
    if (usable(g, side.weight + extra.weight)) {
      f.n = g;
    } else if (usable(side.t, side.tScale) && usable(side.b, side.bScale) &&
               usable(cross(normalize(side.t), normalize(side.b)), 1.0f)) {
      f.n = cross(side.t, side.b);  // then (t, b, n) is right-handed: h = +1
      handednessFromPartials = true;
    } else if (usable(side.t, side.tScale)) {
      f.n = perpendicular(normalize(side.t));
    } else if (usable(side.b, side.bScale)) {
      f.n = perpendicular(normalize(side.b));
    } else {
      f.n = {0, 0, 1};
    }
  }
  f.n = normalize(f.n);
  // cross(dP/du, dP/dv) = cross(e1, e2) / (s1 t2 - s2 t1): for a positive
  // determinant the partials turn the same way as the raw face normal, which is
  // wind * the accumulated g. Relative to the n in use that gives b = h cross(n, t).
  if (sign != 0 && !handednessFromPartials) {
    f.h = float(sign) * wind;
    if (dot(f.n, side.g) < 0) f.h = -f.h;
  }
  float h = f.h;
  bool ortho = !(flags & TANGENT_DONT_ORTHOGONALIZE);
  Vec3 t = side.t, b = side.b;
  if (ortho) {
    t = t - f.n * dot(f.n, t);
    b = b - f.n * dot(f.n, b);
  }
  bool tOk = usable(t, side.tScale), bOk = usable(b, side.bScale);
  float tLen = tOk && side.weight > 0 ? length(t) / side.weight : 1;
  float bLen = bOk && side.weight > 0 ? length(b) / side.weight : 1;
  auto anyT = [&] { return perpendicular(f.n); };
  if (!tOk && !bOk) {
    t = anyT();
    b = cross(f.n, t) * h;
  } else if (!tOk) {
    b = ortho ? orthonormal(b, f.n) : normalize(b);
    t = unitCross(b, f.n, h, anyT);
  } else if (!bOk) {
    t = ortho ? orthonormal(t, f.n) : normalize(t);
    b = unitCross(f.n, t, h, [&] { return cross(f.n, anyT()) * h; });
  } else if (!ortho) {
    t = normalize(t);
    b = normalize(b);
  } else if (flags & TANGENT_ORTHOGONALIZE_FROM_U) {
    t = orthonormal(t, f.n);
    b = cross(f.n, t) * h;
  } else if (flags & TANGENT_ORTHOGONALIZE_FROM_V) {
    b = orthonormal(b, f.n);
    t = cross(b, f.n) * h;
  } else {
    // Both partials count: the tangent is the bisector of dP/du and of the
    // tangent that dP/dv implies (h cross(b, n)), so a shear is shared evenly.
    Vec3 tu = orthonormal(t, f.n), tv = cross(orthonormal(b, f.n), f.n) * h;
    bool ok;
    Vec3 mid = unit(tu + tv, ok);
    t = ok ? orthonormal(mid, f.n) : tu;
    b = cross(f.n, t) * h;
  }
  if (flags & TANGENT_DONT_NORMALIZE_PARTIALS) {
    t = t * tLen;
    b = b * bLen;
  }
  f.t = t;
  f.b = b;
  return f;
}

void checkSet(const char* fn, const char* what, int set, bool allowNone) {
  if (allowNone && set == -1) return;
  if (set < 0 || set >= 8)
    fail("{}: {} texture coordinate set {} does not exist (sets 0 to 7{})", fn, what, set,
         allowNone ? ", or -1 for none" : "");
}

// The FVF with the normal and the 3-float output sets the computation needs.
uint32_t frameFvf(const char* fn, uint32_t fvfCode, int texIn, int tOut, int bOut, bool addNormal) {
  int count = d3d::fvfTexCount(fvfCode);
  if (texIn >= count)
    fail("{}: the mesh (FVF 0x{:x}) has {} texture coordinate sets, no set {} to read (u, v) from",
         fn, fvfCode, count, texIn);
  if (d3d::fvfTexCoordDims(fvfCode, texIn) < 2)
    fail("{}: texture coordinate set {} has 1 float; (u, v) needs 2", fn, texIn);
  uint32_t out = fvfCode;
  if (addNormal) out |= d3d::FVF_NORMAL;
  int newCount = std::max({count, tOut + 1, bOut + 1});
  for (int s = count; s < 8; ++s) out &= ~(3u << (16 + 2 * s));  // unused size bits
  for (int s : {tOut, bOut}) {
    if (s < 0) continue;
    if (s < count) {
      if (d3d::fvfTexCoordDims(fvfCode, s) < 3)
        fail("{}: texture coordinate set {} has {} floats; the output needs 3", fn, s,
             d3d::fvfTexCoordDims(fvfCode, s));
    } else {
      out |= d3d::fvfTexCoordSize(3, s);
    }
  }
  return (out & ~d3d::FVF_TEXCOUNT_MASK) | d3d::fvfTex(newCount);
}

std::vector<uint32_t> tangentFrame(const char* fn, Mesh& mesh, int texIn, int tOut, int bOut,
                                   uint32_t flags, std::span<const uint32_t> adjacency) {
  checkSet(fn, "input", texIn, false);
  checkSet(fn, "tangent output", tOut, true);
  checkSet(fn, "binormal output", bOut, true);
  if (tOut < 0 && bOut < 0) fail("{}: neither a tangent nor a binormal output set is given", fn);
  if (tOut == bOut) fail("{}: tangent and binormal both go to texture coordinate set {}", fn, tOut);
  if (tOut == texIn || bOut == texIn)
    fail("{}: texture coordinate set {} is both the input and an output", fn, texIn);
  if ((flags & TANGENT_ORTHOGONALIZE_FROM_U) && (flags & TANGENT_ORTHOGONALIZE_FROM_V))
    fail("{}: TANGENT_ORTHOGONALIZE_FROM_U and _FROM_V exclude each other", fn);
  if ((flags & TANGENT_WEIGHT_BY_AREA) && (flags & TANGENT_WEIGHT_EQUAL))
    fail("{}: TANGENT_WEIGHT_BY_AREA and TANGENT_WEIGHT_EQUAL exclude each other", fn);
  detail::checkTriangles(mesh, fn);
  bool calculateNormals = flags & TANGENT_CALCULATE_NORMALS;
  uint32_t newFvf = frameFvf(fn, mesh.fvf, texIn, tOut, bOut, calculateNormals);
  if (newFvf != mesh.fvf) mesh = cloneMeshFVF(mesh, newFvf);
  if (calculateNormals)
    computeNormals(mesh, adjacency, flags & (TANGENT_WEIGHT_BY_AREA | TANGENT_WEIGHT_EQUAL | TANGENT_WIND_CW));

  const FVFLayout l = mesh.layout();
  const uint32_t n = mesh.vertexCount();
  const std::vector<Vec3> pos = detail::loadVec3s(mesh, l.position);
  const bool hasNormal = l.normal >= 0;
  std::vector<Vec3> normal;
  if (hasNormal) normal = detail::loadVec3s(mesh, l.normal);
  std::vector<Vec2> uv(n);
  for (uint32_t i = 0; i < n; ++i)
    std::memcpy(&uv[i], mesh.vertices.data() + size_t(i) * mesh.stride + l.texCoord[texIn], 8);

  // Per-face partials, summed into the side (handedness) of each corner's vertex.
  std::vector<Side> sides(2 * size_t(n)), unsided(n);
  const uint32_t faces = mesh.faceCount();
  std::vector<int8_t> faceSign(faces, 0);
  std::vector<uint8_t> used(n, 0);
  auto wrap = [](float d) { return d - std::floor(d + 0.5f); };
  const bool normalizePartials = !(flags & TANGENT_DONT_NORMALIZE_PARTIALS);
  for (uint32_t f = 0; f < faces; ++f) {
    const uint32_t* v = &mesh.indices[3 * size_t(f)];
    Vec3 p[3] = {pos[v[0]], pos[v[1]], pos[v[2]]};
    Vec3 faceNormal;
    float w[3];
    bool valid = detail::faceNormalAndWeights(p, flags, faceNormal, w);
    for (int k = 0; k < 3; ++k) used[v[k]] = 1;
    if (!valid) continue;
    Vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
    float s1 = uv[v[1]].x - uv[v[0]].x, t1 = uv[v[1]].y - uv[v[0]].y;
    float s2 = uv[v[2]].x - uv[v[0]].x, t2 = uv[v[2]].y - uv[v[0]].y;
    if (flags & TANGENT_WRAP_U) s1 = wrap(s1), s2 = wrap(s2);
    if (flags & TANGENT_WRAP_V) t1 = wrap(t1), t2 = wrap(t2);
    float det = s1 * t2 - s2 * t1;
    Vec3 dPdu, dPdv;
    bool mapped = std::fabs(det) > 1e-6f * (std::fabs(s1 * t2) + std::fabs(s2 * t1));
    if (mapped) {
      float r = 1 / det;
      dPdu = (e1 * t2 - e2 * t1) * r;
      dPdv = (e2 * s1 - e1 * s2) * r;
      mapped = isFinite(dPdu) && isFinite(dPdv) && length(dPdu) > 0 && length(dPdv) > 0;
    }
    if (!mapped) {  // zero area in texture space: a normal, no partials
      for (int k = 0; k < 3; ++k) {
        unsided[v[k]].g = unsided[v[k]].g + faceNormal * w[k];
        unsided[v[k]].weight += w[k];
      }
      continue;
    }
    float lu = length(dPdu), lv = length(dPdv);
    if (normalizePartials) dPdu = dPdu * (1 / lu), dPdv = dPdv * (1 / lv), lu = lv = 1;
    int side = det > 0 ? 0 : 1;
    faceSign[f] = int8_t(det > 0 ? 1 : -1);
    for (int k = 0; k < 3; ++k) {
      Side& s = sides[2 * size_t(v[k]) + side];
      s.t = s.t + dPdu * w[k];
      s.b = s.b + dPdv * w[k];
      s.g = s.g + faceNormal * w[k];
      s.weight += w[k];
      s.tScale += w[k] * lu;
      s.bScale += w[k] * lv;
      s.corners++;
    }
  }

  // The side with more weight stays on the vertex; the other one gets a copy of the
  // vertex (or, in place, is dropped).
  const bool split = !(flags & TANGENT_GENERATE_IN_PLACE);
  std::vector<uint8_t> dominant(n, 0);
  std::vector<uint32_t> copyOf(n, kNone), mapping(n);
  for (uint32_t i = 0; i < n; ++i) {
    mapping[i] = i;
    const Side &plus = sides[2 * size_t(i)], &minus = sides[2 * size_t(i) + 1];
    dominant[i] = plus.corners && minus.corners ? (plus.weight >= minus.weight ? 0 : 1) : minus.corners ? 1 : 0;
    if (split && plus.corners && minus.corners) {
      copyOf[i] = uint32_t(mapping.size());
      mapping.push_back(i);
    }
  }
  if (mapping.size() > n) {
    for (uint32_t f = 0; f < faces; ++f) {
      if (!faceSign[f]) continue;
      uint8_t side = faceSign[f] > 0 ? 0 : 1;
      for (int k = 0; k < 3; ++k) {
        uint32_t& v = mesh.indices[3 * size_t(f) + k];
        if (copyOf[v] != kNone && dominant[v] != side) v = copyOf[v];
      }
    }
    mesh.vertices.resize(mapping.size() * mesh.stride);
    for (size_t i = n; i < mapping.size(); ++i)
      std::memcpy(mesh.vertices.data() + i * mesh.stride,
                  mesh.vertices.data() + size_t(mapping[i]) * mesh.stride, mesh.stride);
  }

  auto write = [&](size_t vertex, int set, Vec3 value, float h) {
    if (set < 0) return;
    uint8_t* p = mesh.vertices.data() + vertex * mesh.stride + l.texCoord[set];
    detail::store3(p, value);
    if (l.texDims[set] == 4) std::memcpy(p + 12, &h, 4);  // handedness in w
  };
  for (size_t i = 0; i < mapping.size(); ++i) {
    uint32_t src = mapping[i];
    if (!used[src]) continue;
    int side = i < n ? dominant[src] : 1 - dominant[src];
    const Side& s = sides[2 * size_t(src) + side];
    int sign = s.corners ? (side == 0 ? 1 : -1) : 0;
    Frame fr = solveFrame(s, unsided[src], sign, hasNormal ? normal[src] : Vec3{}, hasNormal, flags);
    write(i, tOut, fr.t, fr.h);
    write(i, bOut, fr.b, fr.h);
    if (fr.normalFixed) detail::store3(mesh.vertices.data() + i * mesh.stride + l.normal, fr.n);
  }
  return mapping;
}

}  // namespace

std::vector<uint32_t> computeTangentFrame(Mesh& mesh, const TangentFrameOptions& options) {
  if (!(options.flags & TANGENT_CALCULATE_NORMALS) && mesh.layout().normal < 0)
    fail("computeTangentFrame: the mesh (FVF 0x{:x}) has no normals; add D3DFVF_NORMAL or "
         "pass TANGENT_CALCULATE_NORMALS", mesh.fvf);
  return tangentFrame("computeTangentFrame", mesh, options.texIn, options.tangentOut,
                      options.binormalOut, options.flags, options.adjacency);
}

void computeTangent(Mesh& mesh, int texStage, int tangentIndex, int binormalIndex, bool wrap) {
  uint32_t flags = TANGENT_GENERATE_IN_PLACE | (wrap ? TANGENT_WRAP_UV : 0u);
  if (mesh.layout().normal < 0) flags |= TANGENT_DONT_ORTHOGONALIZE;
  tangentFrame("computeTangent", mesh, texStage, tangentIndex, binormalIndex, flags, {});
}

}  // namespace refx::d3dx
