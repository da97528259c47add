// FVF vertex layouts and element access for D3DX meshes.
#include <algorithm>
#include <cstring>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/mesh.h"

namespace refx::d3dx {

Mesh::Mesh(uint32_t fvf_, uint32_t vertexCount, uint32_t faceCount)
    : fvf(fvf_), stride(fvfStride(fvf_)) {
  vertices.assign(size_t(vertexCount) * stride, 0);
  indices.assign(size_t(faceCount) * 3, 0);
}

uint8_t* Mesh::element(uint32_t i, int offset, const char* what) {
  return const_cast<uint8_t*>(static_cast<const Mesh*>(this)->element(i, offset, what));
}

const uint8_t* Mesh::element(uint32_t i, int offset, const char* what) const {
  if (offset < 0) fail("mesh: FVF 0x{:x} has no {}", fvf, what);
  if (i >= vertexCount()) fail("mesh: vertex {} does not exist ({} vertices)", i, vertexCount());
  return vertices.data() + size_t(i) * stride + size_t(offset);
}

namespace {
Vec3 load3(const uint8_t* p) {
  float f[3];
  std::memcpy(f, p, sizeof f);
  return {f[0], f[1], f[2]};
}
void store3(uint8_t* p, Vec3 v) {
  float f[3] = {v.x, v.y, v.z};
  std::memcpy(p, f, sizeof f);
}
}  // namespace

Vec3 Mesh::position(uint32_t i) const { return load3(element(i, layout().position, "position")); }
void Mesh::setPosition(uint32_t i, Vec3 p) { store3(element(i, layout().position, "position"), p); }
Vec3 Mesh::normal(uint32_t i) const { return load3(element(i, layout().normal, "normal")); }
void Mesh::setNormal(uint32_t i, Vec3 n) { store3(element(i, layout().normal, "normal"), n); }

D3DColor Mesh::diffuse(uint32_t i) const {
  D3DColor c;
  std::memcpy(&c, element(i, layout().diffuse, "diffuse color"), 4);
  return c;
}
void Mesh::setDiffuse(uint32_t i, D3DColor c) {
  std::memcpy(element(i, layout().diffuse, "diffuse color"), &c, 4);
}

Vec4 Mesh::texCoord(uint32_t i, int set) const {
  FVFLayout l = layout();
  if (set < 0 || set >= 8) fail("mesh: texture coordinate set {} does not exist", set);
  float f[4] = {0, 0, 0, 0};
  std::memcpy(f, element(i, l.texCoord[set], "such texture coordinate set"),
              size_t(l.texDims[set]) * 4);
  return {f[0], f[1], f[2], f[3]};
}
void Mesh::setTexCoord(uint32_t i, int set, Vec4 t) {
  FVFLayout l = layout();
  if (set < 0 || set >= 8) fail("mesh: texture coordinate set {} does not exist", set);
  float f[4] = {t.x, t.y, t.z, t.w};
  std::memcpy(element(i, l.texCoord[set], "such texture coordinate set"), f,
              size_t(l.texDims[set]) * 4);
}

Mesh cloneMeshFVF(const Mesh& mesh, uint32_t newFvf) {
  FVFLayout from = mesh.layout(), to = FVFLayout::of(newFvf);
  uint32_t n = mesh.vertexCount();
  Mesh out(newFvf, n, 0);
  out.indices = mesh.indices;
  out.attributes = mesh.attributes;
  out.materials = mesh.materials;
  auto copy = [&](int src, int dst, int bytes) {
    if (src < 0 || dst < 0) return;
    for (uint32_t i = 0; i < n; ++i)
      std::memcpy(out.vertices.data() + size_t(i) * out.stride + dst,
                  mesh.vertices.data() + size_t(i) * mesh.stride + src, size_t(bytes));
  };
  // Position: the x, y, z common to every position type (w / rhw not carried); the blend
  // weights both layouts have, and the matrix indices.
  copy(from.position, to.position, 12);
  copy(from.blendWeights, to.blendWeights, 4 * std::min(from.blendWeightCount, to.blendWeightCount));
  copy(from.blendIndices, to.blendIndices, 4);
  copy(from.normal, to.normal, 12);
  copy(from.psize, to.psize, 4);
  copy(from.diffuse, to.diffuse, 4);
  copy(from.specular, to.specular, 4);
  for (int s = 0; s < 8; ++s)
    copy(from.texCoord[s], to.texCoord[s], 4 * std::min(from.texDims[s], to.texDims[s]));
  return out;
}

std::vector<uint8_t> Mesh::indexBufferData(bool index32) const {
  std::vector<uint8_t> out(indices.size() * (index32 ? 4 : 2));
  for (size_t i = 0; i < indices.size(); ++i) {
    const uint32_t v = indices[i];
    if (index32) {
      std::memcpy(out.data() + 4 * i, &v, 4);
    } else {
      if (v > 0xffff) fail("index {} ({}) does not fit a 16-bit index buffer", i, v);
      const uint16_t s = uint16_t(v);
      std::memcpy(out.data() + 2 * i, &s, 2);
    }
  }
  return out;
}

std::vector<Mesh::AttributeRange> Mesh::attributeTable() const {
  std::vector<AttributeRange> table;
  for (uint32_t f = 0; f < faceCount(); ++f) {
    const uint32_t a = attribute(f);
    if (table.empty() || table.back().attribId != a || table.back().faceStart + table.back().faceCount != f)
      table.push_back({a, f, 0, UINT32_MAX, 0});
    AttributeRange& r = table.back();
    ++r.faceCount;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = indices[3 * f + k];
      const uint32_t end = r.vertexCount ? r.vertexStart + r.vertexCount : 0;
      const uint32_t lo = std::min(r.vertexStart, v), hi = std::max(end, v + 1);
      r.vertexStart = lo;
      r.vertexCount = hi - lo;
    }
  }
  return table;
}

void Mesh::sortFacesByAttribute() {
  if (attributes.empty()) return;
  std::vector<uint32_t> order(faceCount());
  for (uint32_t f = 0; f < order.size(); ++f) order[f] = f;
  std::stable_sort(order.begin(), order.end(),
                   [&](uint32_t a, uint32_t b) { return attribute(a) < attribute(b); });
  std::vector<uint32_t> idx(indices.size()), attr(order.size());
  for (size_t i = 0; i < order.size(); ++i) {
    for (int k = 0; k < 3; ++k) idx[3 * i + k] = indices[3 * order[i] + k];
    attr[i] = attribute(order[i]);
  }
  indices.swap(idx);
  attributes.swap(attr);
}

}  // namespace refx::d3dx
