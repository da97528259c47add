// Specular power tables (the samples' LightEval callbacks), RacorX10's attenuation
// maps, the wood noise volume and per-vertex hemisphere visibility. Expected texels
// are the callbacks' formulas evaluated by hand at texel centres, rounded to 8 bits
// (round(255 v)).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/lighting_maps.h"
#include "refx/d3dx/teapot.h"

using namespace refx;
using namespace refx::d3dx;

namespace {

// A8R8G8B8 texel bytes (memory order B, G, R, A) of level 0.
struct Bgra {
  int b, g, r, a;
};
Bgra bytesAt(const Texture& t, int x, int y, int z = 0) {
  const uint8_t* p = t.data(0, 0) + size_t(z) * t.slicePitch(0) + size_t(y) * t.rowPitch(0) + size_t(x) * 4;
  return {p[0], p[1], p[2], p[3]};
}

void expectBytes(Bgra got, int r, int g, int b, int a) {
  EXPECT_EQ(got.r, r);
  EXPECT_EQ(got.g, g);
  EXPECT_EQ(got.b, b);
  EXPECT_EQ(got.a, a);
}

// Triangle soup with per-vertex copies and face normals (clockwise front faces:
// normal = normalize(cross(p1 - p0, p2 - p0))).
struct Soup {
  std::vector<Vec3> p;
  void tri(Vec3 a, Vec3 b, Vec3 c) { p.insert(p.end(), {a, b, c}); }
  // Quad a b c d in order around its edge.
  void quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    tri(a, b, c);
    tri(a, c, d);
  }
  Mesh mesh() const {
    Mesh m(d3d::FVF_XYZ | d3d::FVF_NORMAL, uint32_t(p.size()), uint32_t(p.size() / 3));
    for (uint32_t i = 0; i < p.size(); ++i) {
      uint32_t f = i / 3 * 3;
      m.setPosition(i, p[i]);
      m.setNormal(i, normalize(cross(p[f + 1] - p[f], p[f + 2] - p[f])));
      m.indices[i] = i;
    }
    return m;
  }
};

}  // namespace

TEST(SpecularPowerMap, RacorX8Pow16) {
  // LightEval: RGB = pow(v, 16), A = 1, v = (y + 0.5) / 256.
  TexturePtr t = specularPowerMap(256, 256, 16);
  EXPECT_EQ(t->format(), Format::A8R8G8B8);
  EXPECT_EQ(t->levelCount(), 9);  // D3DXCreateTexture(..., 0 levels): 256 .. 1
  // y = 255: (255.5/256)^16 = 0.998046875^16 = 0.96920 -> 247.15 -> 247
  expectBytes(bytesAt(*t, 0, 255), 247, 247, 247, 255);
  // y = 223: (223.5/256)^16 = 0.873046875^16 = 0.11392 -> 29.05 -> 29 (any x)
  expectBytes(bytesAt(*t, 17, 223), 29, 29, 29, 255);
  expectBytes(bytesAt(*t, 200, 223), 29, 29, 29, 255);
  // y = 191: 0.748046875^16 = 0.0096130 -> 2.45 -> 2
  expectBytes(bytesAt(*t, 100, 191), 2, 2, 2, 255);
  // y = 128: 0.501953125^16 = 1.6e-5 -> 0
  expectBytes(bytesAt(*t, 5, 128), 0, 0, 0, 255);
  // Level 1 (128x128) is filled by the callback at its own texel centres:
  // y = 127: (127.5/128)^16 = 0.99609375^16 = 0.93933 -> 239.53 -> 240
  const uint8_t* p = t->data(0, 1) + 127 * t->rowPitch(1);
  EXPECT_EQ(p[2], 240);
}

TEST(SpecularPowerMap, EffectPaperPow100WithUInAlpha) {
  // LightEval of the effect paper: RGB = pow(v, 100), A = u.
  TexturePtr t = specularPowerMap(256, 256, 100, SpecularAlpha::U, 1);
  // y = 255: 0.998046875^100 = 0.82242 -> 209.72 -> 210; x = 63: u = 63.5/256 =
  // 0.248046875 -> 63.25 -> 63
  expectBytes(bytesAt(*t, 63, 255), 210, 210, 210, 63);
  // y = 250: (250.5/256)^100 = 0.11397 -> 29.06 -> 29; x = 255: u = 0.998046875 -> 254.5
  // -> 255 (254.50 + 0.5 truncated)
  expectBytes(bytesAt(*t, 255, 250), 29, 29, 29, 255);
  // y = 240: (240.5/256)^100 = 0.0019387 -> 0.49 -> 0; x = 0: u = 0.5/256 -> 0.498 -> 0
  expectBytes(bytesAt(*t, 0, 240), 0, 0, 0, 0);
}

TEST(SpecularPowerTable, RacorX12AlphaTable) {
  // LightEval of RacorX12: RGB = 0, A = pow(u, 16), u = (x + 0.5) / 2048; 2048x1.
  TexturePtr t = specularPowerTable();
  EXPECT_EQ(t->width(), 2048);
  EXPECT_EQ(t->height(), 1);
  // x = 2047: (2047.5/2048)^16 = 0.99610 -> 254.01 -> 254
  expectBytes(bytesAt(*t, 2047, 0), 0, 0, 0, 254);
  // x = 1983: (1983.5/2048)^16 = 0.59929 -> 152.82 -> 153
  expectBytes(bytesAt(*t, 1983, 0), 0, 0, 0, 153);
  // x = 1791: (1791.5/2048)^16 = 0.11754 -> 29.97 -> 30
  expectBytes(bytesAt(*t, 1791, 0), 0, 0, 0, 30);
  EXPECT_THROW(specularPowerTable(0, 16), Error);
  EXPECT_THROW(specularPowerTable(16, -1), Error);
}

TEST(AttenuationMap, RacorX10PointLightTexture) {
  // x = 2u - 1, y = 2v - 1 at texel centres u = (i + 0.5)/256.
  TexturePtr t = attenuationMap2D(256);
  // Centre texel (128,128): x = y = 2 * 128.5/256 - 1 = 0.00390625, x² + y² = 3.1e-5
  // -> 0: the light is at full strength (1 - 0).
  expectBytes(bytesAt(*t, 128, 128), 0, 0, 0, 0);
  // Edge texel (0,128): x = 0.5/128 - 1 = -0.99609375, x² = 0.99220 (+ y² 1.5e-5)
  // -> 253.01 -> 253 in RGB and in A.
  expectBytes(bytesAt(*t, 0, 128), 253, 253, 253, 253);
  // (64,128): x = 64.5/128 - 1 = -0.49609375, x² = 0.24611 -> 62.76 -> 63.
  expectBytes(bytesAt(*t, 64, 128), 63, 63, 63, 63);
  // (128,64): y² = 0.24611 -> RGB 63, x² = 1.5e-5 -> A 0.
  expectBytes(bytesAt(*t, 128, 64), 63, 63, 63, 0);
  // Corner (0,0): x² + y² = 1.98 clamps to 1 -> 255; A = x² -> 253.
  expectBytes(bytesAt(*t, 0, 0), 255, 255, 255, 253);
  // The shader's 1 - t0 - t1.a at (x, y, z) = (-0.496, 0, 0): 1 - 63/255 - 0 = 0.753.
}

TEST(AttenuationMap, OneDimensionalZSquared) {
  TexturePtr t = attenuationMap1D(256);
  EXPECT_EQ(t->height(), 1);
  // Texel 0: z = -0.99609375, z² = 0.99220 -> 253.
  expectBytes(bytesAt(*t, 0, 0), 253, 253, 253, 253);
  // Texel 192: z = 192.5/128 - 1 = 0.50390625, z² = 0.25392 -> 64.75 -> 65.
  expectBytes(bytesAt(*t, 192, 0), 65, 65, 65, 65);
  // Texel 128: z = 0.0039, z² = 1.5e-5 -> 0.
  expectBytes(bytesAt(*t, 128, 0), 0, 0, 0, 0);
}

TEST(WoodNoiseVolume, DeterministicTileableAndCentredOnHalf) {
  TexturePtr a = woodNoiseVolume(32), b = woodNoiseVolume(32);
  ASSERT_EQ(a->type(), TextureType::Volume);
  EXPECT_EQ(a->depth(), 32);
  ASSERT_EQ(a->dataSize(0, 0), size_t(32 * 32 * 32 * 4));
  EXPECT_EQ(std::memcmp(a->data(0, 0), b->data(0, 0), a->dataSize(0, 0)), 0);
  TexturePtr other = woodNoiseVolume(32, 1, kWoodNoiseSeed + 1);
  EXPECT_NE(std::memcmp(a->data(0, 0), other->data(0, 0), a->dataSize(0, 0)), 0);

  // Each channel: mean near 0.5 (gradient noise averages 0), a real spread.
  double sum[4] = {}, lo[4] = {1, 1, 1, 1}, hi[4] = {};
  const uint8_t* p = a->data(0, 0);
  const size_t n = 32 * 32 * 32;
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 4; ++c) {
      double v = p[4 * i + c] / 255.0;
      sum[c] += v;
      lo[c] = std::min(lo[c], v);
      hi[c] = std::max(hi[c], v);
    }
  for (int c = 0; c < 4; ++c) {
    EXPECT_NEAR(sum[c] / n, 0.5, 0.08) << "channel " << c;
    EXPECT_LT(lo[c], 0.3) << "channel " << c;
    EXPECT_GT(hi[c], 0.7) << "channel " << c;
  }
  // The channels are different fields.
  EXPECT_NE(bytesAt(*a, 3, 5, 7).r, bytesAt(*a, 3, 5, 7).g);

  // Tiling: across the wrap seam (x = 31 next to x = 0) neighbours differ no more
  // than neighbours inside the volume do.
  auto maxStep = [&](int x0, int x1) {
    int m = 0;
    for (int z = 0; z < 32; ++z)
      for (int y = 0; y < 32; ++y) m = std::max(m, std::abs(bytesAt(*a, x0, y, z).r - bytesAt(*a, x1, y, z).r));
    return m;
  };
  int inside = 0;
  for (int x = 0; x + 1 < 32; ++x) inside = std::max(inside, maxStep(x, x + 1));
  EXPECT_LE(maxStep(31, 0), inside);
  EXPECT_LT(inside, 80);  // smooth: far from white noise's 255
}

TEST(HemisphereVisibility, RayDirectionsCoverTheHemisphere) {
  // Uniform over solid angle: the mean of z is 1/2; cosine weighted: 2/3.
  for (bool cosine : {false, true}) {
    auto dirs = hemisphereRayDirections(1024, cosine);
    double mz = 0;
    for (Vec3 d : dirs) {
      EXPECT_NEAR(length(d), 1.0f, 1e-5f);
      EXPECT_GT(d.z, 0.0f);
      mz += d.z;
    }
    EXPECT_NEAR(mz / 1024, cosine ? 2.0 / 3.0 : 0.5, 2e-3);
  }
}

TEST(HemisphereVisibility, OpenPlaneAndClosedBox) {
  Soup s;
  // A floor quad at y = 0 facing up (clockwise seen from above: cross points +y).
  s.quad({-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1});
  // A closed box around (0, 10, 0), 2 units wide, its faces outward, and a small
  // triangle on the inside of its floor facing up.
  const float c = 10;
  Vec3 v[8];
  for (int i = 0; i < 8; ++i) v[i] = {i & 1 ? 1.0f : -1.0f, c + (i & 2 ? 1.0f : -1.0f), i & 4 ? 1.0f : -1.0f};
  s.quad(v[0], v[1], v[3], v[2]);  // z = -1
  s.quad(v[4], v[6], v[7], v[5]);  // z = +1
  s.quad(v[0], v[2], v[6], v[4]);  // x = -1
  s.quad(v[1], v[5], v[7], v[3]);  // x = +1
  s.quad(v[0], v[4], v[5], v[1]);  // y = c - 1
  s.quad(v[2], v[3], v[7], v[6]);  // y = c + 1
  s.tri({-0.1f, c - 0.99f, -0.1f}, {-0.1f, c - 0.99f, 0.1f}, {0.1f, c - 0.99f, 0.1f});
  Mesh m = s.mesh();
  ASSERT_GT(m.normal(0).y, 0.99f);   // floor faces up
  ASSERT_GT(m.normal(42).y, 0.99f);  // inner triangle faces up
  std::vector<float> vis = computeHemisphereVisibility(m);
  ASSERT_EQ(vis.size(), m.vertexCount());
  // Floor corners: nothing above them but the box far overhead (which covers a
  // cone of about atan(1/10) around the vertical seen from (±1, 0, ±1), under 1% of
  // the hemisphere): visibility ~1.
  for (int i = 0; i < 6; ++i) EXPECT_GT(vis[i], 0.97f) << "floor vertex " << i;
  // Inside the closed box every ray hits a wall: 0.
  for (int i = 42; i < 45; ++i) EXPECT_EQ(vis[i], 0.0f) << "inner vertex " << i;
}

TEST(HemisphereVisibility, HalfBlockedByAWall) {
  // A vertex on a floor at the foot of a huge wall (x = 0 plane): rays with
  // direction x < 0 hit it, x > 0 escape. Uniform and cosine weighted both give 1/2.
  Soup s;
  s.quad({0, 0, -1000}, {0, 1000, -1000}, {0, 1000, 1000}, {0, 0, 1000});
  s.tri({0.001f, 0, 0}, {0.001f, 0, 0.01f}, {0.011f, 0, 0.01f});
  Mesh m = s.mesh();
  ASSERT_GT(m.normal(6).y, 0.99f);
  for (bool cosine : {false, true}) {
    OcclusionOptions o;
    o.rays = 512;
    o.cosineWeighted = cosine;
    EXPECT_NEAR(computeHemisphereVisibility(m, o)[6], 0.5f, 0.02f) << (cosine ? "cosine" : "uniform");
  }
}

TEST(HemisphereVisibility, RoundHoleInACeiling) {
  // A ceiling at height 1 over the vertex with a round hole of radius 1 around the
  // vertical: the open directions are the cone of half-angle a = 45°.
  //   uniform over solid angle: 1 - cos a = 1 - 0.70711 = 0.29289
  //   cosine weighted:          sin² a = 0.5
  // The ceiling reaches radius 2000, so only rays within 0.03° of the horizon pass
  // under its edge. The hole is a 256-gon (area within 0.01% of the circle's).
  Soup s;
  const int n = 256;
  const float pi = 3.14159265f, inner = 1, outer = 2000, h = 1;
  for (int k = 0; k < n; ++k) {
    float a0 = 2 * pi * k / n, a1 = 2 * pi * (k + 1) / n;
    Vec3 i0{inner * std::cos(a0), h, inner * std::sin(a0)}, i1{inner * std::cos(a1), h, inner * std::sin(a1)};
    Vec3 o0{outer * std::cos(a0), h, outer * std::sin(a0)}, o1{outer * std::cos(a1), h, outer * std::sin(a1)};
    s.quad(i0, o0, o1, i1);
  }
  size_t probe = s.p.size();
  s.tri({0, 0, 0}, {0, 0, 0.001f}, {0.001f, 0, 0.001f});
  Mesh m = s.mesh();
  ASSERT_GT(m.normal(uint32_t(probe)).y, 0.99f);
  OcclusionOptions o;
  o.rays = 1024;
  EXPECT_NEAR(computeHemisphereVisibility(m, o)[probe], 0.29289f, 0.01f);
  o.cosineWeighted = true;
  EXPECT_NEAR(computeHemisphereVisibility(m, o)[probe], 0.5f, 0.01f);
  // maxDistance shorter than the ceiling (distance >= 1) lets every ray escape.
  o.maxDistance = 0.9f;
  EXPECT_EQ(computeHemisphereVisibility(m, o)[probe], 1.0f);
}

TEST(HemisphereVisibility, TeapotIsPartlyOccluded) {
  // 10 x 10 quads per patch: 6400 triangles, 3872 vertices.
  Mesh m = createTeapot(10);
  auto start = std::chrono::steady_clock::now();
  std::vector<float> vis = computeHemisphereVisibility(m);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("teapot: %u triangles, %u vertices, 128 rays each: %.3f s\n", m.faceCount(), m.vertexCount(), seconds);
  const uint32_t per = 11 * 11;
  // The knob's top (patch 20, row 0; normal +y): nothing above it.
  EXPECT_EQ(vis[20 * per], 1.0f);
  // The bottom's centre (patch 28, row 0; normal -y): nothing below it.
  EXPECT_EQ(vis[28 * per], 1.0f);
  // The rim's inner edge (patch 0, row 0, at radius 1.4) looks down into the pot
  // and across it: mostly enclosed.
  EXPECT_LT(vis[0], 0.5f);
  for (float v : vis) {
    EXPECT_GE(v, 0.0f);
    EXPECT_LE(v, 1.0f);
  }
}

TEST(HemisphereVisibility, MeshWithoutNormalsUsesFaceNormals) {
  Soup s;
  s.quad({-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1});
  s.quad({-1, 1, -1}, {1, 1, -1}, {1, 1, 1}, {-1, 1, 1});  // ceiling, facing down
  Mesh withNormals = s.mesh();
  Mesh m(d3d::FVF_XYZ, withNormals.vertexCount(), withNormals.faceCount());
  for (uint32_t i = 0; i < m.vertexCount(); ++i) m.setPosition(i, withNormals.position(i));
  m.indices = withNormals.indices;
  std::vector<float> a = computeHemisphereVisibility(m), b = computeHemisphereVisibility(withNormals);
  EXPECT_EQ(a, b);
  // The floor corner (-1, 0, -1) sees the 2x2 ceiling 1 unit up over the quadrant
  // x, z > -1 only: partly covered, less than a quarter of the sky.
  EXPECT_LT(a[0], 0.95f);
  EXPECT_GT(a[0], 0.75f);
}
