// Probes of the seed effects RacorX10, the point light effect (RacorX11-14), per-pixel
// specular and hemisphere lighting: each technique draws a flat quad facing the camera
// and the pixel in its middle is compared with the articles' formulas worked out by hand.
//
// The quad: world = world*view*projection = identity, so its corners (+-1, +-1, 0.5)
// are in clip space and in world space at once. Normal (0, 0, -1), tangent U = (1, 0, 0);
// the seeds' vertex shaders build the binormal V = W x U = (0, -1, 0), so a world vector
// (x, y, z) is (x, -y, -z) in tangent space.
// Textures are 1x1 where the article's map is a plain color (the color map, the normal
// map) and the article's own maps where the value comes from a formula (attenuation,
// specular tables, the illumination map, the normalization cube map).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>

#include "pipeline/device_helpers.h"
#include "refx/d3dx/lighting_maps.h"
#include "refx/d3dx/texture_fill.h"
#include "refx/effect/effect.h"

using namespace refx;
using namespace refx::effect;
using namespace refx::d3d;

namespace {

const std::string kEffects = std::string(REFX_DATA_DIR) + "/effects/";

using test::texel;

// XYZ | NORMAL | TEX2, set 0 three floats (u, v and the occlusion the hemisphere vertex
// shader reads from v7.z), set 1 three floats (the tangent, v8).
struct QuadVertex {
  float x, y, z, nx, ny, nz, u, v, occlusion, tx, ty, tz;
};

void drawQuad(Device& dev, float occlusion = 0) {
  const QuadVertex quad[4] = {{-1, 1, 0.5f, 0, 0, -1, 0, 0, occlusion, 1, 0, 0},
                              {1, 1, 0.5f, 0, 0, -1, 1, 0, occlusion, 1, 0, 0},
                              {-1, -1, 0.5f, 0, 0, -1, 0, 1, occlusion, 1, 0, 0},
                              {1, -1, 0.5f, 0, 0, -1, 1, 1, occlusion, 1, 0, 0}};
  dev.setFVF(FVF_XYZ | FVF_NORMAL | (2u << FVF_TEXCOUNT_SHIFT) | fvfTexCoordSize(3, 0) | fvfTexCoordSize(3, 1));
  dev.drawPrimitiveUP(PT_TRIANGLESTRIP, 2, quad, sizeof(QuadVertex));
}

// Runs every pass of `technique` over the quad on an 8x8 target cleared to `clear`
// (black: the point light passes add into the frame buffer) and returns the middle
// pixel; the pass count must be `passes`.
uint32_t drawTechnique(Effect& fx, const std::string& technique, int passes, float occlusion = 0,
                       const std::function<void(Device&)>& deviceSetup = {}, uint32_t clear = 0xff000000) {
  const Handle t = fx.techniqueByName(technique);
  EXPECT_GE(t, 0) << technique;
  fx.setTechnique(t);
  auto dev = test::makeDevice(8, 8, clear);
  if (deviceSetup) deviceSetup(*dev);
  EXPECT_EQ(fx.begin(*dev, 0), passes) << technique;
  for (int i = 0; i < passes; ++i) {
    fx.beginPass(i);
    drawQuad(*dev, occlusion);
    fx.endPass();
  }
  fx.end();
  return test::pixel(*dev, 4, 4);
}

void expectRGB(uint32_t p, int r, int g, int b, int tolerance = 2) {
  EXPECT_NEAR(int((p >> 16) & 0xff), r, tolerance) << std::hex << p;
  EXPECT_NEAR(int((p >> 8) & 0xff), g, tolerance) << std::hex << p;
  EXPECT_NEAR(int(p & 0xff), b, tolerance) << std::hex << p;
}

// RacorX10's illumination map as the article describes diffspec.dds: the diffuse value
// N.L in RGB and the specular value (N.H)^16 in alpha, indexed by (u, v) = (N.L, N.H).
TexturePtr illuminationMap() {
  auto t = Texture::create2D(Format::A8R8G8B8, 256, 256, 1);
  d3dx::fillTexture(*t, [](Vec2 p, Vec2) { return Vec4(p.x, p.x, p.x, std::pow(p.y, 16.0f)); });
  return t;
}

// ---------------------------------------------------------------- RacorX10-14
// The point light and the eye 100 units in front of the quad, on its axis: at the middle
// pixel the light vector and the half vector are (0, 0, -1) in world space, (0, 0, 1) in
// tangent space, and over the whole quad they stay within 0.01 of it.
//   Attenuation (PerPixelPointLight.vsh, range r = 200): the texture coordinates are
//   0.5 * (position - light) / r + 0.5 = (0.5, 0.5) in t0 and 0.75 in t1.x (z = 100/200).
//   The point light texture (RGB = x² + y², A = x² with x = 2u - 1): RGB at the middle is
//   ~0, A at u = 0.75 is 0.25 (bilinear between the 8-bit texels 0.2461 -> 63 and 0.2539 ->
//   65: 64/255 = 0.2510), so 1 - (x² + y² + z²) = 1 - 0.2510 = 0.7490 (191/255): "1 - d*d".
//   Normal map (128, 128, 255): N = 2*texel - 1 = (0.0039, 0.0039, 1), so N.L = N.H = 1.
//   Color map (0x40, 0x60, 0x20) = (0.2510, 0.3765, 0.1255), gloss alpha 0x40 = 0.2510.
//   Specular: the article's tables read at N.H = 1, clamped to their last texel:
//     illumination map (256 texels, (N.H)^16): v = 255.5/256 = 0.99805, ^16 = 0.9692 -> 247
//     -> 0.9686; its RGB (N.L): 0.99805;
//     RacorX12's 2048x1 table (u^16): (2047.5/2048)^16 = 0.99610 -> 254 -> 0.99608.
//   Diffuse: the cube map texel of L = (0, 0, 1) is (0.5, 0.5, 1) -> bx2 (0, 0, 1), N.L = 1.
constexpr float kAttenuation = 191.0f / 255.0f;
constexpr float kColor[3] = {0x40 / 255.0f, 0x60 / 255.0f, 0x20 / 255.0f};
constexpr float kGloss = 0x40 / 255.0f;

std::unique_ptr<Effect> pointLightEffect(const std::string& file) {
  auto fx = Effect::fromFile(kEffects + file);
  for (const auto& d : fx->diagnostics()) ADD_FAILURE() << d.str();
  fx->setMatrix(fx->parameterByName("mWorld"), Matrix::identity());
  fx->setMatrix(fx->parameterByName("mWVP"), Matrix::identity());
  fx->setVector(fx->parameterByName("vEye"), Vec4(0, 0, -99.5f, 1));
  fx->setVector(fx->parameterByName("vLightPos"), Vec4(0, 0, -99.5f, 1));
  fx->setFloat(fx->parameterByName("fRange"), 200);
  fx->setTexture(fx->parameterByName("ColorMap"), texel(0x40406020));
  fx->setTexture(fx->parameterByName("NormalMap"), texel(0xff8080ff));
  fx->setTexture(fx->parameterByName("PointLight"), d3dx::attenuationMap2D(256));
  return fx;
}

// (color * diffuse + gloss * specular) * attenuation, as 8-bit channels.
void expectPointLight(uint32_t p, float diffuse, float specular) {
  int c[3];
  for (int i = 0; i < 3; ++i) c[i] = int(std::lround((kColor[i] * diffuse + kGloss * specular) * kAttenuation * 255));
  expectRGB(p, c[0], c[1], c[2]);
}

// RacorX10: pass 1 writes the attenuation 0.7490; pass 2 (ZERO / SRCCOLOR) multiplies in
// t3.rgb * color + t0.a * t3.a with t3 = illumination map at (N.L, N.H) = (1, 1):
// (0.99805 * (0.2510, 0.3765, 0.1255) + 0.2510 * 0.9686) * 0.7490
// = (0.4936, 0.6189, 0.3684) * 0.7490 -> (94.3, 118.2, 70.4).
TEST(SeedEffectProbe, RacorX10AttenuationTimesIlluminationMap) {
  auto fx = pointLightEffect("racorx10.fx");
  fx->setTexture(fx->parameterByName("IllumMap"), illuminationMap());
  const uint32_t p = drawTechnique(*fx, "PS11", 2);
  expectPointLight(p, 0.99805f, 247.0f / 255);
  expectRGB(p, 94, 118, 70);
}

// RacorX11: color * N.L (ONE / ONE onto black) + gloss * (N.H)^16 from the illumination
// map (ONE / ONE), then * attenuation (ZERO / SRCCOLOR):
// ((0.2510, 0.3765, 0.1255) + 0.2510 * 0.9686) * 0.7490 -> (94.4, 118.4, 70.4).
// RacorX12-14: the same with the 2048x1 table, 0.2510 * 0.99608 = 0.2500:
// (0.5010, 0.6265, 0.3755) * 0.7490 -> (95.7, 119.7, 71.7).
TEST(SeedEffectProbe, PointLightEveryVersionComputesTheSameLight) {
  auto fx = pointLightEffect("racorx_point_light.fx");
  fx->setTexture(fx->parameterByName("IllumMap"), illuminationMap());
  fx->setTexture(fx->parameterByName("CubeMap"), d3dx::createNormalizationCubeMap(64));
  fx->setTexture(fx->parameterByName("SpecularTable"), d3dx::specularPowerTable(2048, 16, 1));
  fx->setTexture(fx->parameterByName("PointLightZ"), d3dx::attenuationMap1D(256));
  {
    SCOPED_TRACE("PS11 (RacorX11, 3 passes)");
    const uint32_t p = drawTechnique(*fx, "PS11", 3);
    expectPointLight(p, 1, 247.0f / 255);
    expectRGB(p, 94, 118, 70);
  }
  {
    SCOPED_TRACE("PS12 (RacorX12, 2 passes)");
    const uint32_t p = drawTechnique(*fx, "PS12", 2);
    expectPointLight(p, 1, 254.0f / 255);
    expectRGB(p, 96, 120, 72);
  }
  for (const char* t : {"PS14_13", "PS14_14a", "PS14_14b", "PS14"}) {
    SCOPED_TRACE(t);
    const uint32_t p = drawTechnique(*fx, t, 1);
    expectPointLight(p, 1, 254.0f / 255);
    expectRGB(p, 96, 120, 72);
  }
}

// Out of the light's range every version draws black: the attenuation multiplies. The
// light at (100, 0, -99.5), range 50: (position - light) / range = (-2, 0, 2) at the middle,
// so the coordinates 0.5 * that + 0.5 clamp to the maps' edge texels: x² + y² = 0.992 in
// RGB (x = -0.996) and z² = 0.992 in alpha, and 1 - 0.992 - 0.992 < 0 saturates to 0.
TEST(SeedEffectProbe, PointLightOutOfRangeIsDark) {
  auto fx = pointLightEffect("racorx_point_light.fx");
  fx->setVector(fx->parameterByName("vLightPos"), Vec4(100, 0, -99.5f, 1));
  fx->setFloat(fx->parameterByName("fRange"), 50);
  fx->setTexture(fx->parameterByName("IllumMap"), illuminationMap());
  fx->setTexture(fx->parameterByName("CubeMap"), d3dx::createNormalizationCubeMap(64));
  fx->setTexture(fx->parameterByName("SpecularTable"), d3dx::specularPowerTable(2048, 16, 1));
  fx->setTexture(fx->parameterByName("PointLightZ"), d3dx::attenuationMap1D(256));
  // A grey background: what is black was drawn black.
  expectRGB(drawTechnique(*fx, "PS11", 3, 0, {}, 0xff808080), 0, 0, 0);
  expectRGB(drawTechnique(*fx, "PS14", 1, 0, {}, 0xff808080), 0, 0, 0);
}

// ---------------------------------------------------------------- per-pixel specular
// The column's vertex shaders (c4 total matrix, c16 the light's direction, c24 camera):
// H = normalize(normalize(eye - position) - c16), in tangent space (T.H, B.H, N.H) with
// their binormal N x T = (0, -1, 0). Color map (0x66, 0x99, 0xcc) = (0.4, 0.6, 0.8).
std::unique_ptr<Effect> specularEffect(Vec4 lightDir) {
  auto fx = Effect::fromFile(kEffects + "paper_specular.fx");
  for (const auto& d : fx->diagnostics()) ADD_FAILURE() << d.str();
  fx->setMatrix(fx->parameterByName("mWorld"), Matrix::identity());
  fx->setMatrix(fx->parameterByName("mWVP"), Matrix::identity());
  fx->setVector(fx->parameterByName("vEye"), Vec4(0, 0, -99.5f, 1));
  fx->setVector(fx->parameterByName("vLightDir"), lightDir);
  fx->setTexture(fx->parameterByName("ColorMap"), texel(0xff6699cc));
  fx->setTexture(fx->parameterByName("NormalMap"), texel(0xff8080ff));
  fx->setTexture(fx->parameterByName("LightMap100"), d3dx::specularPowerMap(256, 256, 100, d3dx::SpecularAlpha::U, 1));
  fx->setTexture(fx->parameterByName("PowerTable"), d3dx::specularPowerTable(2048, 100, 1));
  return fx;
}

// Light along the view (travelling +z): H = (0, 0, -1), (0, 0, 1) in tangent space, and
// N.H = 1 with the flat normal. The tables hold pow(x, 100) at texel centres and the
// lookups clamp to the last texel:
//   PS12, 2048x1:  (2047.5/2048)^100 = 0.97588 -> 249 -> 0.97647; * (0.4, 0.6, 0.8)
//                  = (0.3906, 0.5859, 0.7812) -> (99.6, 149.4, 199.2)
//   PS11, 256x256: (255.5/256)^100 = 0.82243 -> 210 -> 0.82353; * (0.4, 0.6, 0.8)
//                  = (0.3294, 0.4941, 0.6588) -> (84.0, 126.0, 168.0)
// (the 256-texel table's last texel is 0.2% short of N.H = 1, which power 100 turns into
// 18%: the 2048-texel table is the finer lookup).
TEST(SeedEffectProbe, SpecularTablesAtTheHighlight) {
  auto fx = specularEffect(Vec4(0, 0, 1, 0));
  expectRGB(drawTechnique(*fx, "PS12", 1), 100, 149, 199);
  expectRGB(drawTechnique(*fx, "PS11", 1), 84, 126, 168);
}

// Multiply-based exponent, light travelling d = (0, -0.6, 0.8): toward the light
// (0, 0.6, -0.8), toward the eye (0, 0, -1), H = normalize(0, 0.6, -1.8) =
// (0, 0.31623, -0.94868), in tangent space (0, -0.31623, 0.94868), sent biased in oD1.
// N.H = 0.0039216 * -0.31623 + 0.94868 = 0.94744; ^16 = e^(16 ln 0.94744) = 0.42154;
// * (0.4, 0.6, 0.8) = (0.16862, 0.25293, 0.33723) -> (43.0, 64.5, 86.0).
TEST(SeedEffectProbe, SpecularByMultipliesIsTheSixteenthPower) {
  auto fx = specularEffect(Vec4(0, -0.6f, 0.8f, 0));
  expectRGB(drawTechnique(*fx, "PS11Mul", 1), 43, 64, 86);
}

// ---------------------------------------------------------------- hemisphere lighting
// Sky axis s = (0, 0.6, -0.8) (tilted toward the viewer so the quad is lit mostly by the
// sky), directional light travelling d = (0, -0.6, 0.8) (toward it: (0, 0.6, -0.8)).
// Sky (0.55, 0.7, 1.0), ground (0.35, 0.25, 0.15), light color (0.55, 0.5, 0.4).
// Per pixel: the axis in tangent space is (0, -0.6, 0.8), N = (0.0039216, 0.0039216, 1):
//   dp3_d2_sat: (-0.0023529 + 0.8) / 2 = 0.39882; + 0.5: a = 0.89882;
//   lrp: ground + a (sky - ground) = (0.52976, 0.65447, 0.91400)          (2-term)
//   * normal map alpha 0x80 = 0.50196: (0.26592, 0.32852, 0.45879)       (3-term)
//   + dp3_sat(L, N) = 0.79765 * light color (0.43871, 0.39882, 0.31906):
//     (0.70463, 0.72734, 0.77785)                                        (3-term + light)
//   * base texture 0xcc = 0.8:
//     Pixel (108.1, 133.5, 186.5), Pixel3Term (54.2, 67.0, 93.6), PixelSun (143.7, 148.4, 158.7).
// Per vertex (hemisphere.vsh): N.s = 0.8, a = 0.5 * 0.8 + 0.5 = 0.9,
//   lerp: (0.53, 0.655, 0.915) -> Vertex2Term (135.2, 167.0, 233.3);
//   * (1 - occlusion 0.25): (0.3975, 0.49125, 0.68625) -> Vertex (101.4, 125.3, 175.0);
//   + max(N.toward light, 0) = 0.8 * (0.55, 0.5, 0.4): (0.8375, 0.89125, 1.00625), oD0
//   clamped to 1 -> VertexSun (213.6, 227.3, 255).
std::unique_ptr<Effect> hemisphereEffect() {
  auto fx = Effect::fromFile(kEffects + "hemisphere.fx");
  for (const auto& d : fx->diagnostics()) ADD_FAILURE() << d.str();
  fx->setMatrix(fx->parameterByName("mWorld"), Matrix::identity());
  fx->setMatrix(fx->parameterByName("mWVP"), Matrix::identity());
  fx->setVector(fx->parameterByName("vSkyAxis"), Vec4(0, 0.6f, -0.8f, 0));
  fx->setVector(fx->parameterByName("vLightDir"), Vec4(0, -0.6f, 0.8f, 0));
  fx->setTexture(fx->parameterByName("NormalMap"), texel(0x808080ff));
  fx->setTexture(fx->parameterByName("ColorMap"), texel(0xffcccccc));
  return fx;
}

TEST(SeedEffectProbe, HemispherePerPixelTwoAndThreeTermsAndTheLight) {
  auto fx = hemisphereEffect();
  expectRGB(drawTechnique(*fx, "Pixel", 1), 108, 134, 187);
  expectRGB(drawTechnique(*fx, "Pixel3Term", 1), 54, 67, 94);
  expectRGB(drawTechnique(*fx, "PixelSun", 1), 144, 148, 159);
}

TEST(SeedEffectProbe, HemispherePerVertexTwoAndThreeTermsAndTheLight) {
  auto fx = hemisphereEffect();
  expectRGB(drawTechnique(*fx, "Vertex2Term", 1, 0.25f), 135, 167, 233);
  expectRGB(drawTechnique(*fx, "Vertex", 1, 0.25f), 101, 125, 175);
  expectRGB(drawTechnique(*fx, "VertexSun", 1, 0.25f), 214, 227, 255);
}

// DirectX 7: the cube map holds the article's exact integral for a sky along +y,
// a = 1 - 0.5 sin(q) (q < 90°), 0.5 sin(q) (q > 90°). The camera-space normal (0, 0, -1)
// (view = identity) goes through the inverse view rotation: with the view rotated by -60°
// about x the inverse is D3DXMatrixRotationX(60°), (0, 0, -1) -> (0, sin 60°, -cos 60°) =
// (0, 0.866, -0.5): q = 30°, a = 1 - 0.5 * 0.5 = 0.75, color = 0.75 sky + 0.25 ground =
// (0.5, 0.5875, 0.7875), * color map 0.8 = (0.4, 0.47, 0.63) -> (102.0, 119.9, 160.7).
// The inverse view's translation (the eye at (0, 0, -3)) must not move the direction.
TEST(SeedEffectProbe, HemisphereIntegralLooksUpTheWorldNormal) {
  auto fx = hemisphereEffect();
  auto cube = Texture::createCube(Format::A8R8G8B8, 64, 1);
  d3dx::fillCubeTexture(*cube, [](Vec3 d, Vec3) {
    const Vec3 n = normalize(d);
    const float sinQ = std::sqrt(std::max(0.0f, 1 - n.y * n.y));
    const float a = n.y >= 0 ? 1 - 0.5f * sinQ : 0.5f * sinQ;
    return Vec4(0.35f + 0.2f * a, 0.25f + 0.45f * a, 0.15f + 0.85f * a, 1);
  });
  fx->setTexture(fx->parameterByName("IntegralMap"), cube);
  Matrix viewInverse = matrixRotationX(60.0f * 3.14159265f / 180.0f);
  viewInverse.m[3][2] = -3;
  fx->setMatrix(fx->parameterByName("mViewInv"), viewInverse);
  const uint32_t p = drawTechnique(*fx, "Integral", 1, 0, [](Device& dev) {
    dev.setTransform(TS_WORLD, Matrix::identity());
    dev.setTransform(TS_VIEW, Matrix::identity());
    dev.setTransform(TS_PROJECTION, Matrix::identity());
  });
  expectRGB(p, 102, 120, 161);
}

}  // namespace
