// D3DXFill*Texture coordinates, cube texel directions, the normalization cube map and
// D3DXComputeNormalMap, checked against values worked out from d3dx-utilities.md §2-3
// and fixed-function.md §10.
#include <gtest/gtest.h>

#include <cmath>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/texture_fill.h"

using namespace refx;
using namespace refx::d3dx;

namespace {

constexpr float kTol8 = 2.0f / 255.0f;

void expectColor(Color4 c, float r, float g, float b, float a, float eps) {
  EXPECT_NEAR(c.r, r, eps);
  EXPECT_NEAR(c.g, g, eps);
  EXPECT_NEAR(c.b, b, eps);
  EXPECT_NEAR(c.a, a, eps);
}

// A8R8G8B8 texel bytes (memory order B, G, R, A).
struct Bgra {
  int b, g, r, a;
};
Bgra bytesAt(const Texture& t, int face, int x, int y) {
  const uint8_t* p = t.data(face, 0) + size_t(y) * t.rowPitch(0) + size_t(x) * 4;
  return {p[0], p[1], p[2], p[3]};
}

// L8 height map from a function of the texel.
template <class F>
TexturePtr heightMap(int w, int h, F value) {
  TexturePtr t = Texture::create2D(Format::L8, w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) t->data(0, 0)[size_t(y) * w + x] = uint8_t(value(x, y));
  t->markDirty();
  return t;
}

}  // namespace

TEST(FillTexture, TexelCentresOfEveryLevel) {
  // 4x2 with the full chain: 4x2, 2x1, 1x1 -> 8 + 2 + 1 = 11 calls.
  TexturePtr t = Texture::create2D(Format::A32B32G32R32F, 4, 2, 0);
  ASSERT_EQ(t->levelCount(), 3);
  int calls = 0;
  fillTexture(*t, [&](Vec2 uv, Vec2 size) {
    ++calls;
    return Vec4(uv.x, uv.y, size.x, size.y);
  });
  EXPECT_EQ(calls, 11);
  for (int level = 0; level < 3; ++level) {
    int w = t->width(level), h = t->height(level);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        // texCoord = ((x + 0.5)/W, (y + 0.5)/H), texelSize = (1/W, 1/H).
        expectColor(t->texel(0, level, x, y), (x + 0.5f) / w, (y + 0.5f) / h, 1.0f / w, 1.0f / h,
                    1e-7f);
  }
  // Level 0, texel (3, 1): (3.5/4, 1.5/2) = (0.875, 0.75).
  expectColor(t->texel(0, 0, 3, 1), 0.875f, 0.75f, 0.25f, 0.5f, 0);
}

TEST(FillTexture, ConvertsAndClampsToTheFormat) {
  TexturePtr t = Texture::create2D(Format::A8R8G8B8, 2, 1);
  fillTexture(*t, [](Vec2 uv, Vec2) { return Vec4(uv.x, 2.0f, -1.0f, 0.5f); });
  // x = 0: u = 0.25 -> R = 0.25*255 + 0.5 = 64.25 -> 64; G clamps to 255; B to 0;
  // A = 0.5*255 + 0.5 = 128.
  Bgra p = bytesAt(*t, 0, 0, 0);
  EXPECT_EQ(p.r, 64);
  EXPECT_EQ(p.g, 255);
  EXPECT_EQ(p.b, 0);
  EXPECT_EQ(p.a, 128);
  // Signed V8U8 keeps negative values: U = round(-0.5 * 127) = -64 -> -64/127.
  TexturePtr s = Texture::create2D(Format::V8U8, 1, 1);
  fillTexture(*s, [](Vec2, Vec2) { return Vec4(-0.5f, 1.0f, 0, 0); });
  expectColor(s->texel(0, 0, 0, 0), -64.0f / 127.0f, 1.0f, 1.0f, 1.0f, 1e-6f);
}

TEST(FillTexture, VolumeCoordinates) {
  TexturePtr t = Texture::createVolume(Format::A32B32G32R32F, 2, 4, 2, 1);
  fillVolumeTexture(*t, [](Vec3 c, Vec3 size) { return Vec4(c.x, c.y, c.z, size.y); });
  // Texel (1, 2, 1): ((1.5)/2, (2.5)/4, (1.5)/2) = (0.75, 0.625, 0.75); 1/H = 0.25.
  expectColor(t->texel(0, 0, 1, 2, 1), 0.75f, 0.625f, 0.75f, 0.25f, 0);
}

TEST(FillTexture, WrongTypeAndCompressedAreErrors) {
  auto cube = Texture::createCube(Format::A8R8G8B8, 4);
  auto flat = Texture::create2D(Format::A8R8G8B8, 4, 4);
  auto dxt = Texture::create2D(Format::DXT1, 4, 4);
  auto fill2 = [](Vec2, Vec2) { return Vec4(); };
  auto fill3 = [](Vec3, Vec3) { return Vec4(); };
  EXPECT_THROW(fillTexture(*cube, fill2), Error);
  EXPECT_THROW(fillCubeTexture(*flat, fill3), Error);
  EXPECT_THROW(fillVolumeTexture(*flat, fill3), Error);
  EXPECT_THROW(fillTexture(*dxt, fill2), Error);
}

TEST(FillCubeTexture, FaceDirections) {
  // Size 2: texel (0, 0) has s = t = 2*0.5/2 - 1 = -0.5.
  TexturePtr t = Texture::createCube(Format::A32B32G32R32F, 2);
  Vec3 sizes[6];
  fillCubeTexture(*t, [&](Vec3 dir, Vec3 size) {
    // The major axis identifies the face; remember the texel size seen there.
    int face = std::fabs(dir.x) == 1 ? (dir.x > 0 ? 0 : 1)
               : std::fabs(dir.y) == 1 ? (dir.y > 0 ? 2 : 3)
                                       : (dir.z > 0 ? 4 : 5);
    sizes[face] = size;
    return Vec4(dir, 0);
  });
  // +X (1, -t, -s) = (1, 0.5, 0.5); -X (-1, -t, s) = (-1, 0.5, -0.5);
  // +Y (s, 1, t) = (-0.5, 1, -0.5); -Y (s, -1, -t) = (-0.5, -1, 0.5);
  // +Z (s, -t, 1) = (-0.5, 0.5, 1); -Z (-s, -t, -1) = (0.5, 0.5, -1).
  const float expect[6][3] = {{1, 0.5f, 0.5f},   {-1, 0.5f, -0.5f}, {-0.5f, 1, -0.5f},
                              {-0.5f, -1, 0.5f}, {-0.5f, 0.5f, 1},  {0.5f, 0.5f, -1}};
  for (int f = 0; f < 6; ++f)
    expectColor(t->texel(f, 0, 0, 0), expect[f][0], expect[f][1], expect[f][2], 0, 0);
  // Texel size 2/S = 1 on the face's two axes, 0 on the major axis.
  EXPECT_EQ(sizes[0], Vec3(0, 1, 1));
  EXPECT_EQ(sizes[3], Vec3(1, 0, 1));
  EXPECT_EQ(sizes[5], Vec3(1, 1, 0));
}

TEST(FillCubeTexture, DirectionsSelectTheirOwnTexel) {
  // fixed-function.md §10 face selection: the direction of texel (x, y) of face f
  // must select face f and land on u = (x+0.5)/S, v = (y+0.5)/S.
  const int S = 8;
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < S; ++y)
      for (int x = 0; x < S; ++x) {
        Vec3 r = cubeTexelDirection(f, float(x), float(y), S);
        float ax = std::fabs(r.x), ay = std::fabs(r.y), az = std::fabs(r.z);
        int face;
        float sc, tc, ma;
        if (az >= ax && az >= ay) {
          face = r.z > 0 ? 4 : 5, sc = r.z > 0 ? r.x : -r.x, tc = -r.y, ma = az;
        } else if (ay >= ax) {
          face = r.y > 0 ? 2 : 3, sc = r.x, tc = r.y > 0 ? r.z : -r.z, ma = ay;
        } else {
          face = r.x > 0 ? 0 : 1, sc = r.x > 0 ? -r.z : r.z, tc = -r.y, ma = ax;
        }
        ASSERT_EQ(face, f) << "texel " << x << "," << y;
        EXPECT_NEAR((sc / ma + 1) / 2, (x + 0.5f) / S, 1e-6f);
        EXPECT_NEAR((tc / ma + 1) / 2, (y + 0.5f) / S, 1e-6f);
      }
}

TEST(NormalizationCubeMap, BiasedDirections) {
  TexturePtr t = createNormalizationCubeMap(3);
  ASSERT_EQ(t->type(), TextureType::Cube);
  // Size 3, centre texel (1, 1): s = t = 0. +X: n = (1, 0, 0) -> 0.5 + 0.5n =
  // (1, 0.5, 0.5) -> (255, 128, 128): 0.5*255 = 127.5 rounds half up to 128.
  Bgra p = bytesAt(*t, 0, 1, 1);
  EXPECT_EQ(p.r, 255);
  EXPECT_EQ(p.g, 128);
  EXPECT_EQ(p.b, 128);
  EXPECT_EQ(p.a, 255);
  // -Y centre: n = (0, -1, 0) -> (128, 0, 128).
  p = bytesAt(*t, 3, 1, 1);
  EXPECT_EQ(p.r, 128);
  EXPECT_EQ(p.g, 0);
  EXPECT_EQ(p.b, 128);
  // -Z centre: n = (0, 0, -1) -> (128, 128, 0).
  p = bytesAt(*t, 5, 1, 1);
  EXPECT_EQ(p.r, 128);
  EXPECT_EQ(p.g, 128);
  EXPECT_EQ(p.b, 0);

  // Size 4, +X texel (0, 0): s = t = -0.75, direction (1, 0.75, 0.75), length
  // sqrt(2.125) = 1.457738 -> n = (0.685994, 0.514496, 0.514496);
  // 0.5 + 0.5n = (0.842997, 0.757248, 0.757248) -> (215, 193, 193).
  TexturePtr t4 = createNormalizationCubeMap(4);
  p = bytesAt(*t4, 0, 0, 0);
  EXPECT_EQ(p.r, 215);
  EXPECT_EQ(p.g, 193);
  EXPECT_EQ(p.b, 193);
}

TEST(NormalizationCubeMap, SignedFormatStoresRawDirection) {
  TexturePtr t = createNormalizationCubeMap(3, Format::Q8W8V8U8);
  // +Y centre: n = (0, 1, 0) -> (U, V, W, Q) = (0, 1, 0, 1).
  expectColor(t->texel(2, 0, 1, 1), 0, 1, 0, 1, 1e-6f);
  // Mips: every level is filled (1x1 level of +Z: s = t = 0 -> (0, 0, 1)).
  TexturePtr m = createNormalizationCubeMap(4, Format::A8R8G8B8, 0);
  ASSERT_EQ(m->levelCount(), 3);
  expectColor(m->texel(4, 2, 0, 0), 0.5f, 0.5f, 1.0f, 1.0f, kTol8);
}

TEST(ComputeNormalMap, RampAlongU) {
  // h(x) = 8x/255 per texel: slope s = 8/255. amplitude a = 4:
  // dx = (h(x+1) - h(x-1)) / 2 * a = s*a = 32/255, dy = 0.
  // n = normalize(-32/255, 0, 1) = (-0.124514, 0, 0.992218);
  // 0.5n + 0.5 = (0.437743, 0.5, 0.996109).
  TexturePtr h = heightMap(16, 4, [](int x, int) { return 8 * x; });
  TexturePtr n = computeNormalMap(*h, CHANNEL_RED, 4.0f);
  ASSERT_EQ(n->format(), Format::A8R8G8B8);
  ASSERT_EQ(n->width(0), 16);
  const float d = 32.0f / 255.0f, len = std::sqrt(d * d + 1);
  for (int y = 0; y < 4; ++y)
    for (int x = 1; x < 15; ++x)  // away from the wrapped edge
      expectColor(n->texel(0, 0, x, y), 0.5f - 0.5f * d / len, 0.5f, 0.5f + 0.5f / len, 1.0f, kTol8);
  expectColor(n->texel(0, 0, 5, 2), 0.437743f, 0.5f, 0.996109f, 1.0f, kTol8);

  // Wrapped at x = 0: h(-1) = h(15) = 120/255, so dx = (8 - 120)/255 / 2 * 4 = -224/255:
  // the normal leans the other way: n = (0.878431, 0, 1) / sqrt(0.878431^2 + 1)
  // = (0.659963, 0, 0.751298).
  expectColor(n->texel(0, 0, 0, 0), 0.5f + 0.5f * 0.659963f, 0.5f, 0.5f + 0.5f * 0.751298f, 1.0f,
              kTol8);
  // MIRROR_U: h(-1) = h(0) = 0, dx = (8/255 - 0) / 2 * 4 = 16/255.
  TexturePtr m = computeNormalMap(*h, CHANNEL_RED, 4.0f, NORMALMAP_MIRROR_U);
  const float dm = 16.0f / 255.0f, lm = std::sqrt(dm * dm + 1);
  expectColor(m->texel(0, 0, 0, 0), 0.5f - 0.5f * dm / lm, 0.5f, 0.5f + 0.5f / lm, 1.0f, kTol8);
  // INVERTSIGN: n = normalize(+dx, 0, 1).
  TexturePtr inv = computeNormalMap(*h, CHANNEL_RED, 4.0f, NORMALMAP_INVERTSIGN);
  expectColor(inv->texel(0, 0, 5, 2), 0.5f + 0.5f * d / len, 0.5f, 0.5f + 0.5f / len, 1.0f, kTol8);
}

TEST(ComputeNormalMap, RampAlongVAndSignedOutput) {
  // h(y) = 16y/255 going down the rows; a = 2: dy = 16/255 * 2 = 32/255,
  // n = normalize(0, -32/255, 1) = (0, -0.124514, 0.992218).
  TexturePtr h = heightMap(4, 16, [](int, int y) { return 16 * y; });
  TexturePtr n = computeNormalMap(*h, CHANNEL_LUMINANCE, 2.0f);
  expectColor(n->texel(0, 0, 2, 7), 0.5f, 0.5f - 0.5f * 0.124514f, 0.5f + 0.5f * 0.992218f, 1.0f,
              kTol8);
  // V8U8 stores raw n: U = 0, V = round(-0.124514 * 127) = round(-15.81) / 127 = -16/127.
  TexturePtr s = computeNormalMap(*h, CHANNEL_LUMINANCE, 2.0f, 0, Format::V8U8);
  expectColor(s->texel(0, 0, 2, 7), 0.0f, -16.0f / 127.0f, 1.0f, 1.0f, 1e-6f);
  // Q8W8V8U8: (U, V, W, Q) = (0, -0.124514, 0.992218, 1), 8-bit signed steps of 1/127.
  TexturePtr q = computeNormalMap(*h, CHANNEL_LUMINANCE, 2.0f, 0, Format::Q8W8V8U8);
  expectColor(q->texel(0, 0, 2, 7), 0.0f, -0.124514f, 0.992218f, 1.0f, 1.0f / 127.0f);
}

TEST(ComputeNormalMap, ChannelSelection) {
  // The ramp lives in green only: CHANNEL_GREEN tilts the normal, CHANNEL_RED sees a
  // flat field, n = (0, 0, 1) -> (0.5, 0.5, 1).
  TexturePtr t = Texture::create2D(Format::A8R8G8B8, 8, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) t->setTexel(0, 0, x, y, 0, {0.25f, x * 16 / 255.0f, 0, 1});
  TexturePtr flat = computeNormalMap(*t, CHANNEL_RED, 10.0f);
  expectColor(flat->texel(0, 0, 3, 3), 0.5f, 0.5f, 1.0f, 1.0f, kTol8);
  // GREEN, a = 1: dx = 16/255 = 0.062745, n = (-0.062745, 0, 1) / 1.001966
  // = (-0.062622, 0, 0.998037).
  TexturePtr green = computeNormalMap(*t, CHANNEL_GREEN, 1.0f);
  expectColor(green->texel(0, 0, 3, 3), 0.5f - 0.5f * 0.062622f, 0.5f, 0.5f + 0.5f * 0.998037f, 1.0f,
              kTol8);
  EXPECT_THROW(computeNormalMap(*t, 0x20, 1.0f), Error);
  EXPECT_THROW(computeNormalMap(*t, CHANNEL_RED, 1.0f, 0x1), Error);
  EXPECT_THROW(computeNormalMap(*Texture::createCube(Format::L8, 4), CHANNEL_RED, 1.0f), Error);
}

TEST(ComputeNormalMap, Occlusion) {
  // Flat field: every direction sees the whole sky, alpha 1.
  TexturePtr flat = heightMap(8, 8, [](int, int) { return 100; });
  TexturePtr a = computeNormalMap(*flat, CHANNEL_RED, 1.0f, NORMALMAP_COMPUTE_OCCLUSION);
  EXPECT_NEAR(a->texel(0, 0, 4, 4).a, 1.0f, kTol8);
  // One texel at 0 in a field at 1 (amplitude 1): the horizon is the neighbour.
  // Axis directions: rise 1 over 1 texel, elevation 45 deg, open 1 - sin 45 = 0.292893;
  // diagonals: rise 1 over sqrt 2, tan = 0.707107, sin = 0.577350, open 0.422650.
  // Alpha = (4*0.292893 + 4*0.422650) / 8 = 0.357771.
  TexturePtr pit = heightMap(8, 8, [](int x, int y) { return x == 4 && y == 4 ? 0 : 255; });
  TexturePtr b = computeNormalMap(*pit, CHANNEL_RED, 1.0f, NORMALMAP_COMPUTE_OCCLUSION);
  EXPECT_NEAR(b->texel(0, 0, 4, 4).a, 0.357771f, kTol8);
  // Without the flag alpha is 1.
  TexturePtr c = computeNormalMap(*pit, CHANNEL_RED, 1.0f);
  EXPECT_NEAR(c->texel(0, 0, 4, 4).a, 1.0f, 0);
}
