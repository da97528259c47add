// D3DX shape generators. Vertex order and triangle order follow D3DX (as Wine's
// d3dx9 reproduces it); front faces are clockwise seen from outside, so D3D's
// default CULL_CCW keeps the outside visible.
#include <cmath>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/mesh.h"

namespace refx::d3dx {

namespace {

constexpr float kPi = 3.14159265358979323846f;
constexpr uint32_t kPosNormal = d3d::FVF_XYZ | d3d::FVF_NORMAL;

// sin/cos of start + i*step, i < n (D3DX builds the same tables).
struct SinCos {
  std::vector<float> s, c;
  SinCos(float start, float step, uint32_t n) : s(n), c(n) {
    for (uint32_t i = 0; i < n; ++i) {
      float a = start + float(i) * step;
      s[i] = std::sin(a);
      c[i] = std::cos(a);
    }
  }
};

void requireAtLeast(const char* fn, const char* what, uint32_t v, uint32_t min) {
  if (v < min) fail("{}: {} must be at least {}, not {}", fn, what, min, v);
}
void requireNonNegative(const char* fn, const char* what, float v) {
  if (!(v >= 0.0f) || !std::isfinite(v)) fail("{}: {} must be a finite value >= 0, not {}", fn, what, v);
}
// Keeps the vertex count within 32-bit indices and sane memory.
void requireVertexCount(const char* fn, uint64_t n) {
  if (n > (uint64_t(1) << 24))
    fail("{}: {} vertices exceeds the limit of {}", fn, n, uint64_t(1) << 24);
}

struct Builder {
  Mesh& m;
  uint32_t v = 0, f = 0;
  void vertex(Vec3 p, Vec3 n) {
    m.setPosition(v, p);
    m.setNormal(v, n);
    ++v;
  }
  void face(uint32_t a, uint32_t b, uint32_t c) {
    m.indices[3 * f] = a, m.indices[3 * f + 1] = b, m.indices[3 * f + 2] = c;
    ++f;
  }
};

}  // namespace

Mesh createSphere(float radius, uint32_t slices, uint32_t stacks) {
  requireNonNegative("createSphere", "radius", radius);
  requireAtLeast("createSphere", "slices", slices, 2);
  requireAtLeast("createSphere", "stacks", stacks, 2);
  requireVertexCount("createSphere", 2 + uint64_t(slices) * (stacks - 1));
  uint32_t nv = 2 + slices * (stacks - 1);
  Mesh mesh(kPosNormal, nv, 2 * slices * (stacks - 1));
  Builder b{mesh};
  // phi: angle in the xy plane from +x, starting at +y and stepping clockwise
  // seen from +z; theta: angle from +z.
  SinCos phi(kPi / 2, -2.0f * kPi / float(slices), slices);
  float thetaStep = kPi / float(stacks), theta = thetaStep;
  auto vi = [&](uint32_t slice, uint32_t stack) { return stack * slices + slice + 1; };

  b.vertex({0, 0, radius}, {0, 0, 1});
  uint32_t stack = 0, slice = 0;
  for (stack = 0; stack < stacks - 1; ++stack) {
    float st = std::sin(theta), ct = std::cos(theta);
    for (slice = 0; slice < slices; ++slice) {
      Vec3 n{st * phi.c[slice], st * phi.s[slice], ct};
      b.vertex(n * radius, n);
      if (slice == 0) continue;
      if (stack == 0) {  // top stack: fan around the +z pole
        b.face(0, slice + 1, slice);
      } else {           // quad strip between two rings
        b.face(vi(slice - 1, stack - 1), vi(slice, stack - 1), vi(slice - 1, stack));
        b.face(vi(slice, stack - 1), vi(slice, stack), vi(slice - 1, stack));
      }
    }
    theta += thetaStep;
    if (stack == 0) {
      b.face(0, 1, slice);
    } else {
      b.face(vi(slice - 1, stack - 1), vi(0, stack - 1), vi(slice - 1, stack));
      b.face(vi(0, stack - 1), vi(0, stack), vi(slice - 1, stack));
    }
  }
  uint32_t bottom = b.v;
  b.vertex({0, 0, -radius}, {0, 0, -1});
  // bottom stack: fan around the -z pole
  for (slice = 1; slice < slices; ++slice)
    b.face(vi(slice - 1, stack - 1), vi(slice, stack - 1), bottom);
  b.face(vi(slice - 1, stack - 1), vi(0, stack - 1), bottom);
  return mesh;
}

Mesh createTexturedSphere(float radius, uint32_t slices, uint32_t stacks) {
  requireNonNegative("createTexturedSphere", "radius", radius);
  requireAtLeast("createTexturedSphere", "slices", slices, 3);
  requireAtLeast("createTexturedSphere", "stacks", stacks, 2);
  requireVertexCount("createTexturedSphere", uint64_t(slices + 1) * (stacks + 1));
  const uint32_t cols = slices + 1;
  Mesh mesh(d3d::FVF_XYZ | d3d::FVF_NORMAL | d3d::fvfTex(2) | d3d::fvfTexCoordSize(3, 1), cols * (stacks + 1),
            2 * slices * (stacks - 1));
  for (uint32_t s = 0; s <= stacks; ++s) {
    float v = float(s) / float(stacks);
    float theta = kPi * v;  // from the north pole (+y)
    float st = std::sin(theta), ct = std::cos(theta);
    if (s == 0) st = 0, ct = 1;  // exact poles
    if (s == stacks) st = 0, ct = -1;
    for (uint32_t k = 0; k <= slices; ++k) {
      float u = float(k) / float(slices);
      // Longitude phi = 2*pi*u; u = 0 at +z (the back, seen from a camera at -z),
      // u = 0.5 at -z facing that camera, east toward +x there.
      float phi = 2.0f * kPi * u;
      float sp = std::sin(phi), cp = std::cos(phi);
      if (k == slices) sp = 0, cp = 1;  // the seam column repeats column 0 exactly
      Vec3 n{-st * sp, ct, st * cp};
      uint32_t i = s * cols + k;
      mesh.setPosition(i, n * radius);
      mesh.setNormal(i, n);
      mesh.setTexCoord(i, 0, u, v);
      // dP/du = 2*pi*radius*sin(theta) * (-cos phi, 0, -sin phi); normalized it is
      // defined at the poles too.
      mesh.setTexCoord(i, 1, Vec4(-cp, 0, -sp, 0));
    }
  }
  // Quads (s,k) (s,k+1) / (s+1,k) (s+1,k+1): north-west, north-east, south-west,
  // south-east seen from outside; the pole rows keep one triangle per quad.
  uint32_t f = 0;
  auto face = [&](uint32_t a, uint32_t b, uint32_t c) {
    mesh.indices[3 * f] = a, mesh.indices[3 * f + 1] = b, mesh.indices[3 * f + 2] = c;
    ++f;
  };
  for (uint32_t s = 0; s < stacks; ++s)
    for (uint32_t k = 0; k < slices; ++k) {
      uint32_t nw = s * cols + k, ne = nw + 1, sw = nw + cols, se = sw + 1;
      if (s > 0) face(nw, ne, sw);
      if (s + 1 < stacks) face(ne, se, sw);
    }
  return mesh;
}

Mesh createBox(float width, float height, float depth) {
  requireNonNegative("createBox", "width", width);
  requireNonNegative("createBox", "height", height);
  requireNonNegative("createBox", "depth", depth);
  // Unit box corners, 4 per face, faces -x, +y, +x, -y, +z, -z (D3DX order).
  static const Vec3 kCorners[24] = {
      {-0.5f, -0.5f, -0.5f}, {-0.5f, -0.5f, 0.5f},  {-0.5f, 0.5f, 0.5f},   {-0.5f, 0.5f, -0.5f},
      {-0.5f, 0.5f, -0.5f},  {-0.5f, 0.5f, 0.5f},   {0.5f, 0.5f, 0.5f},    {0.5f, 0.5f, -0.5f},
      {0.5f, 0.5f, -0.5f},   {0.5f, 0.5f, 0.5f},    {0.5f, -0.5f, 0.5f},   {0.5f, -0.5f, -0.5f},
      {-0.5f, -0.5f, 0.5f},  {-0.5f, -0.5f, -0.5f}, {0.5f, -0.5f, -0.5f},  {0.5f, -0.5f, 0.5f},
      {-0.5f, -0.5f, 0.5f},  {0.5f, -0.5f, 0.5f},   {0.5f, 0.5f, 0.5f},    {-0.5f, 0.5f, 0.5f},
      {-0.5f, -0.5f, -0.5f}, {-0.5f, 0.5f, -0.5f},  {0.5f, 0.5f, -0.5f},   {0.5f, -0.5f, -0.5f}};
  static const Vec3 kNormals[6] = {{-1, 0, 0}, {0, 1, 0}, {1, 0, 0},
                                   {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  Mesh mesh(kPosNormal, 24, 12);
  Builder b{mesh};
  for (int i = 0; i < 24; ++i) {
    const Vec3& c = kCorners[i];
    b.vertex({c.x * width, c.y * height, c.z * depth}, kNormals[i / 4]);
  }
  for (uint32_t i = 0; i < 12; ++i) {  // each face a fan (0,1,2), (0,2,3)
    uint32_t base = (i / 2) * 4;
    b.face(base, base + i % 2 + 1, base + i % 2 + 2);
  }
  return mesh;
}

Mesh createCylinder(float radius1, float radius2, float length, uint32_t slices, uint32_t stacks) {
  requireNonNegative("createCylinder", "radius1", radius1);
  requireNonNegative("createCylinder", "radius2", radius2);
  requireNonNegative("createCylinder", "length", length);
  requireAtLeast("createCylinder", "slices", slices, 2);
  requireAtLeast("createCylinder", "stacks", stacks, 1);
  requireVertexCount("createCylinder", 2 + uint64_t(slices) * (3 + stacks));
  uint32_t nv = 2 + slices * (3 + stacks);
  Mesh mesh(kPosNormal, nv, 2 * slices + stacks * 2 * slices);
  Builder b{mesh};
  SinCos theta(kPi / 2, -2.0f * kPi / float(slices), slices);
  auto vi = [&](uint32_t slice, uint32_t stack) { return stack * slices + slice + 1; };
  float zStep = length / float(stacks), radiusStep = (radius1 - radius2) / float(stacks);
  float z = -length / 2, radius = radius1;
  // Side normal of a cone: (cos, sin, (r1 - r2) / length), normalized.
  float zNormal = length > 0 ? (radius1 - radius2) / length : 0.0f;

  b.vertex({0, 0, z}, {0, 0, -1});
  uint32_t slice = 0, stack = 0;
  for (slice = 0; slice < slices; ++slice) {  // -z cap ring
    b.vertex({radius * theta.c[slice], radius * theta.s[slice], z}, {0, 0, -1});
    if (slice > 0) b.face(0, slice, slice + 1);
  }
  b.face(0, slice, 1);

  for (stack = 1; stack <= stacks + 1; ++stack) {  // side rings
    for (slice = 0; slice < slices; ++slice) {
      b.vertex({radius * theta.c[slice], radius * theta.s[slice], z},
               normalize({theta.c[slice], theta.s[slice], zNormal}));
      if (stack > 1 && slice > 0) {
        b.face(vi(slice - 1, stack - 1), vi(slice - 1, stack), vi(slice, stack - 1));
        b.face(vi(slice, stack - 1), vi(slice - 1, stack), vi(slice, stack));
      }
    }
    if (stack > 1) {
      b.face(vi(slice - 1, stack - 1), vi(slice - 1, stack), vi(0, stack - 1));
      b.face(vi(0, stack - 1), vi(slice - 1, stack), vi(0, stack));
    }
    if (stack < stacks + 1) z += zStep, radius -= radiusStep;
  }
  // The last ring is exactly radius2 at +length/2 (no accumulated steps).
  z = length / 2, radius = radius2;
  for (slice = 0; slice < slices; ++slice) {  // +z cap ring
    b.vertex({radius * theta.c[slice], radius * theta.s[slice], z}, {0, 0, 1});
    if (slice > 0) b.face(vi(slice - 1, stack), nv - 1, vi(slice, stack));
  }
  b.vertex({0, 0, z}, {0, 0, 1});
  b.face(vi(slice - 1, stack), nv - 1, vi(0, stack));
  return mesh;
}

Mesh createTorus(float innerRadius, float outerRadius, uint32_t sides, uint32_t rings) {
  requireNonNegative("createTorus", "innerRadius", innerRadius);
  requireNonNegative("createTorus", "outerRadius", outerRadius);
  requireAtLeast("createTorus", "sides", sides, 3);
  requireAtLeast("createTorus", "rings", rings, 3);
  requireVertexCount("createTorus", uint64_t(sides) * rings);
  Mesh mesh(kPosNormal, sides * rings, 2 * sides * rings);
  Builder b{mesh};
  // phi goes around the tube (from the top, +z, outward first), theta around the axis.
  SinCos phi(kPi / 2, -2.0f * kPi / float(sides), sides);
  SinCos theta(0, -2.0f * kPi / float(rings), rings);
  for (uint32_t i = 0; i < rings; ++i)
    for (uint32_t j = 0; j < sides; ++j) {
      float ring = outerRadius + innerRadius * phi.c[j];
      b.vertex({ring * theta.c[i], ring * theta.s[i], innerRadius * phi.s[j]},
               {phi.c[j] * theta.c[i], phi.c[j] * theta.s[i], phi.s[j]});
    }
  for (uint32_t i = 0; i < rings; ++i) {
    uint32_t i1 = (i + 1) % rings;
    for (uint32_t j = 0; j < sides; ++j) {
      uint32_t j1 = (j + 1) % sides;
      b.face(i * sides + j, i1 * sides + j, i * sides + j1);
      b.face(i * sides + j1, i1 * sides + j, i1 * sides + j1);
    }
  }
  return mesh;
}

}  // namespace refx::d3dx
