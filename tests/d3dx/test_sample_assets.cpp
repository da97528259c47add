// Procedural sample textures: deterministic, and land / ocean where the continent
// layout (kEarthContinents) puts them by construction.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/sample_assets.h"
#include "refx/d3dx/texture_fill.h"

using namespace refx;
using namespace refx::d3dx;

namespace {

constexpr float kPi = 3.14159265358979323846f;
constexpr int W = 256, H = 128;

bool sameBytes(const Texture& a, const Texture& b) {
  if (a.format() != b.format() || a.levelCount() != b.levelCount()) return false;
  for (int l = 0; l < a.levelCount(); ++l)
    if (a.dataSize(0, l) != b.dataSize(0, l) ||
        std::memcmp(a.data(0, l), b.data(0, l), a.dataSize(0, l)) != 0)
      return false;
  return true;
}

// The unit-sphere point of map position (u, v) on createTexturedSphere:
// theta = pi v from +y, phi = 2 pi u, p = (-sin(theta) sin(phi), cos(theta), sin(theta) cos(phi)).
Vec3 sphere(float u, float v) {
  float t = kPi * v, p = 2 * kPi * u;
  return {-std::sin(t) * std::sin(p), std::cos(t), std::sin(t) * std::cos(p)};
}

// How far (chord) outside every continent's radius the point is; < 0 inside one.
float continentMargin(float u, float v) {
  float m = 10;
  for (const EarthContinent& c : kEarthContinents)
    m = std::min(m, length(sphere(u, v) - sphere(c.u, c.v)) - c.radius);
  return m;
}

struct Texel {
  int x, y;
};
Texel texelAt(float u, float v) { return {int(u * W), int(v * H)}; }

// Open-ocean positions: elevation <= -0.45 + 0.4 < 0 wherever no continent reaches,
// i.e. farther than radius + kEarthWarp from every centre. The extra 0.03 covers the
// texel and its neighbours (a 256-wide texel spans 2 pi / 256 = 0.025).
const float kOcean[][2] = {{0.05f, 0.60f}, {0.62f, 0.70f}, {0.68f, 0.70f}, {0.12f, 0.50f}};

// Continent centres away from the polar ice (|y| < 0.9): land, elevation >= 0.15.
std::vector<std::pair<float, float>> landCentres() {
  std::vector<std::pair<float, float>> out;
  for (const EarthContinent& c : kEarthContinents)
    if (std::fabs(sphere(c.u, c.v).y) < 0.85f) out.push_back({c.u, c.v});
  return out;
}

}  // namespace

TEST(SampleAssets, OceanPositionsAreFarFromEveryContinent) {
  for (const auto& o : kOcean)
    EXPECT_GT(continentMargin(o[0], o[1]), kEarthWarp + 0.03f) << o[0] << "," << o[1];
  // Land is guaranteed at a centre while the warp stays inside its plateau.
  for (const EarthContinent& c : kEarthContinents) EXPECT_GE(c.radius / 2, kEarthWarp);
  EXPECT_GE(landCentres().size(), 9u);
}

TEST(SampleAssets, Deterministic) {
  EXPECT_TRUE(sameBytes(*earthColorMap(W, H), *earthColorMap(W, H)));
  EXPECT_TRUE(sameBytes(*earthHeightMap(W, H), *earthHeightMap(W, H)));
  EXPECT_TRUE(sameBytes(*earthBumpMap(W, H), *earthBumpMap(W, H)));
  EXPECT_TRUE(sameBytes(*earthBumpMapLuminance(W, H), *earthBumpMapLuminance(W, H)));
  EXPECT_TRUE(sameBytes(*earthNormalMap(W, H), *earthNormalMap(W, H)));
  EXPECT_TRUE(sameBytes(*cloudMap(W, H), *cloudMap(W, H)));
  EXPECT_TRUE(sameBytes(*environmentMap(64), *environmentMap(64)));
  EXPECT_TRUE(sameBytes(*brick(64, 0), *brick(64, 0)));
}

TEST(SampleAssets, EarthGlossAndHeight) {
  TexturePtr color = earthColorMap(W, H), height = earthHeightMap(W, H);
  ASSERT_EQ(color->format(), Format::A8R8G8B8);
  ASSERT_EQ(height->format(), Format::L8);
  for (const auto& o : kOcean) {
    Texel t = texelAt(o[0], o[1]);
    Color4 c = color->texel(0, 0, t.x, t.y);
    EXPECT_EQ(c.a, 1.0f) << "ocean gloss 255 at " << o[0] << "," << o[1];
    EXPECT_GT(c.b, c.r);  // blue water
    EXPECT_GT(c.b, c.g);
    EXPECT_EQ(height->texel(0, 0, t.x, t.y).r, 0.0f);  // water height 0
  }
  for (auto [u, v] : landCentres()) {
    Texel t = texelAt(u, v);
    EXPECT_EQ(color->texel(0, 0, t.x, t.y).a, 0.0f) << "land gloss 0 at " << u << "," << v;
    EXPECT_GT(height->texel(0, 0, t.x, t.y).r, 0.0f);
  }
  // Polar ice: the rows at the poles are white and not glossy.
  Color4 pole = color->texel(0, 0, 10, 0);
  EXPECT_GT(pole.r, 0.85f);
  EXPECT_EQ(pole.a, 0.0f);
}

TEST(SampleAssets, SeamIsContinuous) {
  // u = 0 and u = 1 are the same meridian: the same sphere points, the same terrain.
  for (float v : {0.2f, 0.4f, 0.5f, 0.65f, 0.8f})
    EXPECT_NEAR(earthElevation(earthDirection(0.0f, v)), earthElevation(earthDirection(1.0f, v)), 1e-4f);
  // earthDirection is createTexturedSphere's mapping.
  Vec3 p = earthDirection(0.5f, 0.5f);  // (0, 0, -1) facing a camera at -z
  EXPECT_NEAR(p.x, 0, 1e-6f);
  EXPECT_NEAR(p.y, 0, 1e-6f);
  EXPECT_NEAR(p.z, -1, 1e-6f);
}

TEST(SampleAssets, BumpMapsAreHeightDifferences) {
  TexturePtr height = earthHeightMap(W, H), bump = earthBumpMap(W, H),
             lum = earthBumpMapLuminance(W, H);
  ASSERT_EQ(bump->format(), Format::V8U8);
  ASSERT_EQ(lum->format(), Format::X8L8V8U8);
  auto h8 = [&](int x, int y) {  // wrap in u, clamp in v
    x = (x + W) % W;
    y = std::clamp(y, 0, H - 1);
    return int(std::lround(height->texel(0, 0, x, y).r * 255));
  };
  // Flat water: du = dv = 0; luminance 127/255 over water.
  for (const auto& o : kOcean) {
    Texel t = texelAt(o[0], o[1]);
    Color4 b = bump->texel(0, 0, t.x, t.y);
    EXPECT_EQ(b.r, 0.0f);
    EXPECT_EQ(b.g, 0.0f);
    Color4 l = lum->texel(0, 0, t.x, t.y);
    EXPECT_EQ(l.r, 0.0f);
    EXPECT_NEAR(l.b, 127.0f / 255.0f, 1e-6f);
  }
  // du = (h(x-1) - h(x+1)) / 127, dv = (h(y-1) - h(y+1)) / 127 in 8-bit steps
  // (clamped to [-1, 1] by the signed byte). Checked on a stretch of land.
  int checked = 0;
  for (auto [u, v] : landCentres()) {
    Texel c = texelAt(u, v);
    for (int dx = -3; dx <= 3; ++dx) {
      int x = (c.x + dx + W) % W, y = c.y;
      float du = std::clamp((h8(x - 1, y) - h8(x + 1, y)) / 127.0f, -1.0f, 1.0f);
      float dv = std::clamp((h8(x, y - 1) - h8(x, y + 1)) / 127.0f, -1.0f, 1.0f);
      Color4 b = bump->texel(0, 0, x, y);
      EXPECT_NEAR(b.r, du, 1e-6f);
      EXPECT_NEAR(b.g, dv, 1e-6f);
      EXPECT_NEAR(lum->texel(0, 0, x, y).b, h8(x, y) > 0 ? 63.0f / 255.0f : 127.0f / 255.0f, 1e-6f);
      ++checked;
    }
  }
  EXPECT_GT(checked, 0);
}

TEST(SampleAssets, EarthNormalMap) {
  TexturePtr n = earthNormalMap(W, H);
  ASSERT_EQ(n->format(), Format::A8R8G8B8);
  // Flat water: n = (0, 0, 1) -> (0.5, 0.5, 1) = (128, 128, 255).
  for (const auto& o : kOcean) {
    Texel t = texelAt(o[0], o[1]);
    Color4 c = n->texel(0, 0, t.x, t.y);
    EXPECT_NEAR(c.r, 128.0f / 255.0f, 1e-6f);
    EXPECT_NEAR(c.g, 128.0f / 255.0f, 1e-6f);
    EXPECT_NEAR(c.b, 1.0f, 1e-6f);
  }
  // Mips on request: a full chain of 256x128 has 9 levels.
  EXPECT_EQ(earthNormalMap(W, H, 0)->levelCount(), 9);
}

TEST(SampleAssets, SimpleMaps) {
  // checker(8, 2): 4x4-texel cells, the top-left white.
  TexturePtr c = checker(8, 2);
  EXPECT_EQ(c->texel(0, 0, 0, 0).r, 1.0f);
  EXPECT_EQ(c->texel(0, 0, 3, 3).g, 1.0f);
  EXPECT_EQ(c->texel(0, 0, 4, 0).r, 0.0f);
  EXPECT_EQ(c->texel(0, 0, 0, 4).b, 0.0f);
  EXPECT_EQ(c->texel(0, 0, 7, 7).r, 1.0f);
  EXPECT_THROW(checker(8, 0), Error);

  // Environment map: bright sun in the middle, dark blue in the corner.
  TexturePtr e = environmentMap(64);
  Color4 mid = e->texel(0, 0, 32, 32), corner = e->texel(0, 0, 0, 0);
  EXPECT_GT(mid.r, 0.95f);
  EXPECT_GT(mid.g, 0.95f);
  EXPECT_LT(corner.r, 0.1f);
  EXPECT_GT(corner.b, corner.r);
  EXPECT_GT(corner.b, corner.g);

  // Bricks, 256 texels, 8 courses: row 0 has v = 0.5/256 * 8 = 0.0156 into its
  // course, inside the mortar joint (< 0.06) -> mortar (0.78, 0.76, 0.72).
  TexturePtr b = brick(256);
  Color4 m = b->texel(0, 0, 100, 0);
  EXPECT_NEAR(m.r, 0.78f, 1.0f / 255);
  EXPECT_NEAR(m.g, 0.76f, 1.0f / 255);
  EXPECT_NEAR(m.b, 0.72f, 1.0f / 255);
  // Texel (32, 16): 0.516 down course 0 and 0.508 across its first brick, away
  // from every joint: red brick, r >= 0.55 - 0.05 and b <= 0.20 + 0.05.
  Color4 r = b->texel(0, 0, 32, 16);
  EXPECT_GT(r.r, r.b + 0.2f);

  // Clouds: white, some cover somewhere and clear sky somewhere.
  TexturePtr cl = cloudMap(W, H);
  float lo = 1, hi = 0;
  for (int y = 0; y < H; y += 4)
    for (int x = 0; x < W; x += 4) {
      Color4 t = cl->texel(0, 0, x, y);
      EXPECT_EQ(t.r, 1.0f);
      lo = std::min(lo, t.a), hi = std::max(hi, t.a);
    }
  EXPECT_EQ(lo, 0.0f);
  EXPECT_GT(hi, 0.9f);
}

TEST(SampleAssets, BadSizesAreErrors) {
  EXPECT_THROW(earthColorMap(0, 16), Error);
  EXPECT_THROW(environmentMap(-4), Error);
  EXPECT_THROW(brick(1 << 20), Error);
}
