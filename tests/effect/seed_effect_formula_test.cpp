// Probes of the seed effects BRDF, BumpEarth, the per-pixel diffuse column with its
// fallbacks and RacorX7-9: each technique draws a flat quad facing the camera and the
// pixel in its middle is compared with the articles' formulas worked out by hand.
//
// The quad: world = world*view*projection = identity, so its corners (+-1, +-1, 0.5) are
// in clip space and in world space at once; the middle pixel (4, 4) of the 8x8 target is
// the quad's centre (D3D9 pixel centres sit on integer coordinates). Normal (0, 0, -1),
// tangent U = (1, 0, 0); the seeds' vertex shaders build the binormal V = (0, -1, 0), so a
// world vector (x, y, z) is (x, -y, -z) in tangent space.
// The tilted light used below travels d = (0, -0.6, 0.8): toward it (0, 0.6, -0.8), in
// tangent space L = (0, -0.6, 0.8). The flat normal map texel (128, 128, 255) gives
// N = 2 * texel - 1 = (0.0039216, 0.0039216, 1), so
//   N.L = -0.6 * 0.0039216 + 0.8 = 0.797647.
// With the eye 100 units in front (0, 0, -99.5), toward the eye is (0, 0, -1) and
// H = normalize((0, 0, -1) + (0, 0.6, -0.8)) = normalize(0, 0.6, -1.8) = (0, 0.31623, -0.94868),
// in tangent space (0, -0.31623, 0.94868):
//   N.H = -0.31623 * 0.0039216 + 0.94868 = 0.94744;
//   (N.H)^16 = e^(16 ln 0.94744) = e^(16 * -0.0539916) = e^-0.863866 = 0.42153.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>

#include "pipeline/device_helpers.h"
#include "refx/effect/effect.h"

using namespace refx;
using namespace refx::effect;
using namespace refx::d3d;

namespace {

const std::string kEffects = std::string(REFX_DATA_DIR) + "/effects/";

using test::texel;

// A 1x1 cube map, one color per face (+X, -X, +Y, -Y, +Z, -Z).
TexturePtr cubeFaces(const uint32_t (&argb)[6]) {
  auto t = Texture::createCube(Format::A8R8G8B8, 1, 1);
  for (int f = 0; f < 6; ++f) std::memcpy(t->data(f, 0), &argb[f], 4);
  t->markDirty();
  return t;
}

// A 256 x 256 gray table whose texel row y holds round(255 * f((y + 0.5) / 256)).
TexturePtr rowTable(const std::function<double(double)>& f) {
  auto t = Texture::create2D(Format::A8R8G8B8, 256, 256, 1);
  for (int y = 0; y < 256; ++y) {
    const uint32_t g = uint32_t(std::lround(255 * f((y + 0.5) / 256)));
    const uint32_t argb = 0xff000000u | g << 16 | g << 8 | g;
    for (int x = 0; x < 256; ++x) std::memcpy(t->data(0, 0) + y * t->rowPitch(0) + x * 4, &argb, 4);
  }
  t->markDirty();
  return t;
}

// XYZ | NORMAL | TEX2, set 0 three floats (u, v, w), set 1 three floats (the tangent, v8).
// 48 bytes: also the layout of brdf.fx's declaration (v0 position, v3 normal, v7 three
// texture coordinates, v8 tangent), which its pass sets itself.
struct QuadVertex {
  float x, y, z, nx, ny, nz, u, v, w, tx, ty, tz;
};

void drawQuad(Device& dev, float w, bool setFvf) {
  const QuadVertex quad[4] = {{-1, 1, 0.5f, 0, 0, -1, 0, 0, w, 1, 0, 0},
                              {1, 1, 0.5f, 0, 0, -1, 1, 0, w, 1, 0, 0},
                              {-1, -1, 0.5f, 0, 0, -1, 0, 1, w, 1, 0, 0},
                              {1, -1, 0.5f, 0, 0, -1, 1, 1, w, 1, 0, 0}};
  if (setFvf)
    dev.setFVF(FVF_XYZ | FVF_NORMAL | (2u << FVF_TEXCOUNT_SHIFT) | fvfTexCoordSize(3, 0) | fvfTexCoordSize(3, 1));
  dev.drawPrimitiveUP(PT_TRIANGLESTRIP, 2, quad, sizeof(QuadVertex));
}

struct DrawOptions {
  int passes = 1;
  float w = 1;          // third texture coordinate of set 0
  bool setFvf = true;   // false: the pass sets a declaration
  bool fixedFunctionTransforms = false;  // identity world / view / projection
};

// Runs every pass of `technique` over the quad on an 8x8 target cleared to black and
// returns the middle pixel.
uint32_t drawTechnique(Effect& fx, const std::string& technique, const DrawOptions& o = {}) {
  const Handle t = fx.techniqueByName(technique);
  EXPECT_GE(t, 0) << technique;
  fx.setTechnique(t);
  auto dev = test::makeDevice(8, 8, 0xff000000);
  if (o.fixedFunctionTransforms) {
    dev->setTransform(TS_WORLD, Matrix::identity());
    dev->setTransform(TS_VIEW, Matrix::identity());
    dev->setTransform(TS_PROJECTION, Matrix::identity());
  }
  EXPECT_EQ(fx.begin(*dev, 0), o.passes) << technique;
  for (int i = 0; i < o.passes; ++i) {
    fx.beginPass(i);
    drawQuad(*dev, o.w, o.setFvf);
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

std::unique_ptr<Effect> loadEffect(const std::string& file) {
  auto fx = Effect::fromFile(kEffects + file);
  for (const auto& d : fx->diagnostics()) ADD_FAILURE() << d.str();
  return fx;
}

// ---------------------------------------------------------------- BRDF (seeds/000)
// r0 = t0 * t1 * t2 * t3 * v0: the three BRDF factor maps, the detail texture and the
// material color (oD0 = c9). t0, t2 (view, half vector) and t3 are 1x1 2D maps, so only
// the light lookup t1 depends on the coordinates: a cube map, +Z face white, +X face
// (0x40, 0x40, 0x40), the others black. lhtR = c16 = (-0.6, 0, 0.8): toward the light
// -c16 = (0.6, 0, -0.8), in tangent space (T.-c16, B.-c16, N.-c16) = (0.6, 0, 0.8).
// t0 = t2 = white, detail (0xff, 0x80, 0x40), MaterialColor (1, 0.5, 1, 1).
std::unique_ptr<Effect> brdfEffect(const std::string& file) {
  auto fx = loadEffect(file);
  fx->setMatrix(fx->parameterByName("mWld"), Matrix::identity());
  fx->setMatrix(fx->parameterByName("mTot"), Matrix::identity());
  fx->setVector(fx->parameterByName("lhtR"), Vec4(-0.6f, 0, 0.8f, 0));
  fx->setVector(fx->parameterByName("MaterialColor"), Vec4(1, 0.5f, 1, 1));
  fx->setTexture(fx->parameterByName("BRDFTexture1"), texel(0xffffffff));
  fx->setTexture(fx->parameterByName("BRDFTexture2"),
                 cubeFaces({0xff404040, 0xff000000, 0xff000000, 0xff000000, 0xffffffff, 0xff000000}));
  fx->setTexture(fx->parameterByName("BRDFTexture3"), texel(0xffffffff));
  fx->setTexture(fx->parameterByName("ObjectTexture"), texel(0xffff8040));
  return fx;
}

// brdf_fixed.fx writes oT1 = (0.6, 0, 0.8): major axis +z, the white face.
// (1, 1, 1) * (1, 0.50196, 0.25098) * (1, 0.5, 1) = (1, 0.25098, 0.25098) -> (255, 64, 64).
TEST(SeedEffectFormula, BrdfFixedReadsTheLightAlongItsMajorAxis) {
  auto fx = brdfEffect("brdf_fixed.fx");
  fx->setVector(fx->parameterByName("vEye"), Vec4(0, 0, -99.5f, 1));
  expectRGB(drawTechnique(*fx, "tec0", {.setFvf = false}), 255, 64, 64);
}

// brdf.fx as printed: `dp3 oT2.z,-c16,r0` leaves oT1.z unwritten (0), so t1 looks up
// (0.6, 0, 0): the +X face (0x40 = 0.25098), "reads the horizon".
// 0.25098 * (1, 0.50196, 0.25098) * (1, 0.5, 1) = (0.25098, 0.06299, 0.06299) -> (64, 16, 16).
TEST(SeedEffectFormula, BrdfAsPrintedLosesTheLightsZ) {
  auto fx = brdfEffect("brdf.fx");
  expectRGB(drawTechnique(*fx, "tec0", {.setFvf = false}), 64, 16, 16);
}

// ---------------------------------------------------------------- BumpEarth (seeds/000)
// Fixed-function light, travelling (0, -0.6, 0.8); camera-space normal (0, 0, -1):
//   diffuse = ambient 0x20/255 + N.(-d) = 0.12549 + 0.8 = 0.92549.
// Earth texel (0x80, 0x40, 0x20): earth * diffuse = (0.50196, 0.25098, 0.12549) * 0.92549
//   = (0.46456, 0.23228, 0.11614) -> (118.5, 59.2, 29.6).
// Environment map: 16 x 16, columns 0-10 A = (0, 0, 0x40), columns 11-15 B = (0x40, 0x20, 0).
// Its coordinates: (n.x, n.y, n.z, 1) x mEnvMap = (0.5 + 0.5 n.x, 0.5 - 0.5 n.y) = (0.5, 0.5):
//   unbumped u = 0.5 -> texel coordinate 0.5 * 16 - 0.5 = 7.5, between columns 7 and 8: A.
// Bump texel V8U8 du = 64/127 = 0.50394, dv = 0; with BUMPENVMAT 0.5 / 0 / 0 / 0.5:
//   u' = 0.5 + 0.5 * 0.50394 = 0.75197 -> texel coordinate 11.53, columns 11 and 12: B.
TexturePtr envMap() {
  auto t = Texture::create2D(Format::A8R8G8B8, 16, 16, 1);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const uint32_t c = x <= 10 ? 0xff000040u : 0xff402000u;
      std::memcpy(t->data(0, 0) + y * t->rowPitch(0) + x * 4, &c, 4);
    }
  t->markDirty();
  return t;
}

std::unique_ptr<Effect> bumpEarthEffect() {
  auto fx = loadEffect("bump_earth.fx");
  fx->setVector(fx->parameterByName("vLightDir"), Vec4(0, -0.6f, 0.8f, 0));
  fx->setTexture(fx->parameterByName("EarthTexture"), texel(0xff804020));
  auto bump = Texture::create2D(Format::V8U8, 1, 1, 1);
  const uint16_t dudv = 0x0040;  // V = 0, U = 64
  std::memcpy(bump->data(0, 0), &dudv, 2);
  bump->markDirty();
  fx->setTexture(fx->parameterByName("BumpMap"), bump);
  fx->setTexture(fx->parameterByName("EnvMapTexture"), envMap());
  return fx;
}

// MODULATE(earth, diffuse) / BUMPENVMAP / ADD(env(u'), current):
// (118.5, 59.2, 29.6) + B (64, 32, 0) = (182.5, 91.2, 29.6).
TEST(SeedEffectFormula, BumpEarthBumpEnvMapShiftsTheEnvironmentLookup) {
  auto fx = bumpEarthEffect();
  expectRGB(drawTechnique(*fx, "BumpEnvMap", {.fixedFunctionTransforms = true}), 182, 91, 30);
}

// MODULATE(earth, diffuse) / ADD(env(u), current): (118.5, 59.2, 29.6) + A (0, 0, 64)
// = (118.5, 59.2, 93.6).
TEST(SeedEffectFormula, BumpEarthNoBumpAddsTheEnvironmentUnbumped) {
  auto fx = bumpEarthEffect();
  expectRGB(drawTechnique(*fx, "NoBump", {.fixedFunctionTransforms = true}), 118, 59, 94);
}

// ---------------------------------------------------------------- per-pixel diffuse (seeds/000)
// Color map (0xff, 0x80, 0x40) = (1, 0.50196, 0.25098), light travelling (0, -0.6, 0.8).
std::unique_ptr<Effect> paperDiffuseEffect() {
  auto fx = loadEffect("paper_diffuse.fx");
  fx->setMatrix(fx->parameterByName("mWorld"), Matrix::identity());
  fx->setMatrix(fx->parameterByName("mWorldInv"), Matrix::identity());
  fx->setMatrix(fx->parameterByName("mWVP"), Matrix::identity());
  fx->setVector(fx->parameterByName("vLightDir"), Vec4(0, -0.6f, 0.8f, 0));
  fx->setTexture(fx->parameterByName("ColorMap"), texel(0xffff8040));
  fx->setTexture(fx->parameterByName("NormalMap"), texel(0xff8080ff));
  return fx;
}

// PS11: oD0 = 0.5 L + 0.5 = (0.5, 0.2, 0.9); dp3_sat(N, L) = 0.797647;
// color * 0.797647 = (0.797647, 0.400389, 0.200195) -> (203.4, 102.1, 51.0).
// DOT3_VS: DOTPRODUCT3(normal texel, oD0) = 4 ((0.50196 - 0.5) * 0 + (0.50196 - 0.5) * (0.2 - 0.5)
//   + (1 - 0.5) (0.9 - 0.5)) = 4 (-0.000588 + 0.2) = 0.797647, then MODULATE(color): the same.
TEST(SeedEffectFormula, PaperDiffusePixelShaderAndDot3StagesAgree) {
  auto fx = paperDiffuseEffect();
  expectRGB(drawTechnique(*fx, "PS11"), 203, 102, 51);
  expectRGB(drawTechnique(*fx, "DOT3_VS"), 203, 102, 51);
}

// DOT3 (fixed-function T&L): vTangentLight (-0.55, -0.45, 0.64) -> TFACTOR 0.5 l + 0.5 =
// (0.225, 0.275, 0.82) -> (57.4, 70.1, 209.1) -> (57, 70, 209) = (0.223529, 0.274510, 0.819608).
// DOTPRODUCT3(normal texel, TFACTOR) = 4 (0.0019608 (-0.276471 - 0.225490) + 0.5 * 0.319608)
//   = 4 (-0.000984 + 0.159804) = 0.635279;
// * color map * vertex diffuse (ambient 0.12549 + N.L 0.8 = 0.92549):
//   (1, 0.50196, 0.25098) * 0.635279 * 0.92549 = (0.587945, 0.295126, 0.147563) -> (149.9, 75.3, 37.6).
TEST(SeedEffectFormula, PaperDiffuseFixedFunctionDot3) {
  auto fx = paperDiffuseEffect();
  const float tangentLight[3] = {-0.55f, -0.45f, 0.64f};
  fx->setFloatArray(fx->parameterByName("vTangentLight"), tangentLight, 3);
  expectRGB(drawTechnique(*fx, "DOT3", {.fixedFunctionTransforms = true}), 150, 75, 38);
}

// Emboss: a 256-row height map rising with v (row j = (j + 0.5) / 256, so h(v) = v under
// linear filtering) and color map (0x80, 0x40, 0x20) = (0.50196, 0.25098, 0.12549).
// Pass 1: SELECTARG1(h(v)), ADDSIGNED(1 - h(v'), current) = h(v) - h(v') + 0.5.
// Pass 2: color * diffuse, blended DESTCOLOR / SRCCOLOR: 2 * src * dst.
std::unique_ptr<Effect> embossEffect() {
  auto fx = paperDiffuseEffect();
  fx->setTexture(fx->parameterByName("ColorMap"), texel(0xff804020));
  fx->setTexture(fx->parameterByName("HeightMap"), rowTable([](double v) { return v; }));
  const float offset[2] = {0, 0.5f};
  fx->setFloatArray(fx->parameterByName("vEmbossOffset"), offset, 2);
  return fx;
}

// Emboss_VS (paper_emboss.vsh): c12 = toward the light (0, 0.6, -0.8); its binormal
// T x N = (1, 0, 0) x (0, 0, -1) = (0, 1, 0), so r6.xy = (T.c12, B.c12) = (0, 0.6) and
// oT1 = (u, v) + r6.xy * -c24.xy = (u, v - 0.6 * 0.5) = (u, v - 0.3).
// Pass 1: v - (v - 0.3) + 0.5 = 0.8. oD0 = N.c12 = (0, 0, -1).(0, 0.6, -0.8) = 0.8.
// Pass 2: 2 * (color * 0.8) * 0.8 = (0.642510, 0.321255, 0.160627) -> (163.8, 81.9, 41.0).
TEST(SeedEffectFormula, PaperDiffuseEmbossVertexShader) {
  auto fx = embossEffect();
  expectRGB(drawTechnique(*fx, "Emboss_VS", {.passes = 2}), 164, 82, 41);
}

// Emboss (fixed-function T&L): (u, v, 1) x TextureTransform[1] = (u + 0 * lx, v + 0.5 * ly);
// vTangentLight.y = -0.6 -> v - 0.3, pass 1 = 0.8 as above. The diffuse color is the
// fixed-function light: ambient 0.12549 + N.L 0.8 = 0.92549.
// Pass 2: 2 * (color * 0.92549) * 0.8 = (0.743306, 0.371653, 0.185827) -> (189.5, 94.8, 47.4).
TEST(SeedEffectFormula, PaperDiffuseFixedFunctionEmboss) {
  auto fx = embossEffect();
  const float tangentLight[3] = {0, -0.6f, 0.8f};
  fx->setFloatArray(fx->parameterByName("vTangentLight"), tangentLight, 3);
  expectRGB(drawTechnique(*fx, "Emboss", {.passes = 2, .fixedFunctionTransforms = true}), 189, 95, 47);
}

// ---------------------------------------------------------------- RacorX7-9 (seeds/003)
std::unique_ptr<Effect> racorEffect(const std::string& file, Vec4 lightDir) {
  auto fx = loadEffect(file);
  fx->setMatrix(fx->parameterByName("mWorld"), Matrix::identity());
  fx->setMatrix(fx->parameterByName("mWVP"), Matrix::identity());
  fx->setVector(fx->parameterByName("vEye"), Vec4(0, 0, -99.5f, 1));
  fx->setVector(fx->parameterByName("vLightDir"), lightDir);
  fx->setTexture(fx->parameterByName("NormalMap"), texel(0xff8080ff));
  return fx;
}

// RacorX7: color * (N.H)^16 (four squarings), tilted light, H biased in oD1.
// Color (0xff, 0x80, 0x40): (1, 0.50196, 0.25098) * 0.42153 = (0.42153, 0.21159, 0.10580)
// -> (107.5, 54.0, 27.0).
TEST(SeedEffectFormula, RacorX7SixteenthPowerByMultiplies) {
  auto fx = racorEffect("racorx7.fx", Vec4(0, -0.6f, 0.8f, 0));
  fx->setTexture(fx->parameterByName("ColorMap"), texel(0xffff8040));
  for (const char* t : {"PS14", "PS11"}) {
    SCOPED_TRACE(t);
    expectRGB(drawTechnique(*fx, t), 107, 54, 27);
  }
}

// RacorX8: the table lookup at (N.H, N.H) into LightEval = pow(v, 16) (rows), times the
// color map. Tilted light: N.H = 0.94744 -> row coordinate 0.94744 * 256 - 0.5 = 242.04,
// rows 242 (0.947266^16 = 0.42030 -> 107) and 243 (0.951172^16 = 0.44889 -> 114):
// 107 + 0.04 * 7 = 107.3 -> 0.4208 (the table gives (N.H)^16 = 0.4215 within a texel).
// Color (0xff, 0x80, 0x40): (0.4208, 0.2112, 0.1056) -> (107.3, 53.9, 26.9).
TEST(SeedEffectFormula, RacorX8SpecularTableLookup) {
  auto fx = racorEffect("racorx8.fx", Vec4(0, -0.6f, 0.8f, 0));
  fx->setTexture(fx->parameterByName("ColorMap"), texel(0xffff8040));
  fx->setTexture(fx->parameterByName("LightMap16"), rowTable([](double v) { return std::pow(v, 16); }));
  for (const char* t : {"PS14", "PS11"}) {
    SCOPED_TRACE(t);
    expectRGB(drawTechnique(*fx, t), 107, 54, 27);
  }
}

// RacorX9, tilted light, color (0x80, 0x40, 0x20) = (0.50196, 0.25098, 0.12549):
// color * N.L = (0.400389, 0.200195, 0.100097).
// PS11 (and PS14Mul): + (N.H)^16 0.42153 = (0.821919, 0.621725, 0.521627) -> (209.6, 158.5, 133.0).
// PS14: + the specular value read from the normal map's alpha at (N.H, N.H); the 1x1 normal
// map's alpha 0x40 = 0.25098: (0.651369, 0.451175, 0.351077) -> (166.1, 115.0, 89.5).
TEST(SeedEffectFormula, RacorX9DiffusePlusSpecular) {
  auto fx = racorEffect("racorx9.fx", Vec4(0, -0.6f, 0.8f, 0));
  fx->setTexture(fx->parameterByName("ColorMap"), texel(0xff804020));
  fx->setTexture(fx->parameterByName("NormalMapSpecular"), texel(0x408080ff));
  {
    SCOPED_TRACE("PS11");
    expectRGB(drawTechnique(*fx, "PS11"), 210, 158, 133);
  }
  {
    SCOPED_TRACE("PS14Mul");
    expectRGB(drawTechnique(*fx, "PS14Mul"), 210, 158, 133);
  }
  {
    SCOPED_TRACE("PS14");
    expectRGB(drawTechnique(*fx, "PS14"), 166, 115, 90);
  }
}

}  // namespace
