// Ward's BRDF, cube texel lookup, and the homomorphic factorization into the BRDF
// effect's cube maps: a product-form BRDF is recovered almost exactly, Ward's model
// within the error the product form and the cube resolution allow.
#include <gtest/gtest.h>

#include <cmath>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/brdf.h"
#include "refx/d3dx/texture_fill.h"

using namespace refx;
using namespace refx::d3dx;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Held-out directions from a generator unrelated to the fit's own (a 64-bit LCG).
struct Lcg {
  uint64_t s;
  double next() {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return double(s >> 11) / 9007199254740992.0;
  }
  // Uniform over solid angle (z uniform) or cosine weighted (z² uniform).
  Vec3 hemisphere(bool cosine) {
    double a = next(), b = next();
    double z = cosine ? std::sqrt(1 - a) : 1 - a, r = std::sqrt(std::max(0.0, 1 - z * z));
    return {float(r * std::cos(2 * kPi * b)), float(r * std::sin(2 * kPi * b)), float(z)};
  }
};

// Relative RMS error of `model` against `target` over n held-out pairs.
template <class Model, class Target>
double heldOutError(Model model, Target target, bool cosine, int n = 20000) {
  Lcg rng{0x1234567};
  double sum = 0;
  for (int k = 0; k < n; ++k) {
    Vec3 wi = rng.hemisphere(cosine), wo = rng.hemisphere(cosine);
    double t = target(wi, wo), e = (model(wi, wo) - t) / t;
    sum += e * e;
  }
  return std::sqrt(sum / n);
}

// A BRDF of exactly the product form a(wi) b(wh) a(wo), smooth and positive.
float sepA(Vec3 w) { return 0.3f + 0.7f * w.z * w.z + 0.2f * w.x; }
float sepB(Vec3 h) { return 0.5f + std::exp(-((h.x / 0.4f) * (h.x / 0.4f) + (h.y / 0.6f) * (h.y / 0.6f))); }
float separable(Vec3 wi, Vec3 wo) { return sepA(wi) * sepB(normalize(wi + wo)) * sepA(wo); }

}  // namespace

TEST(WardBrdf, HandValues) {
  WardBrdf ward;  // ρd 0.15, ρs 0.25, αx 0.12, αy 0.3
  // Normal incidence and view: h = n, exponent 0, cosines 1:
  // 0.15/π + 0.25/(4π 0.12 0.3) = 0.047746 + 0.552621 = 0.600368
  EXPECT_NEAR(ward({0, 0, 1}, {0, 0, 1}), 0.600368f, 1e-5f);
  // Mirror pair at 36.87° (cos 0.8): h = n, the specular term grows by 1/sqrt(0.8 * 0.8):
  // 0.047746 + 0.552621 / 0.8 = 0.738523
  EXPECT_NEAR(ward({0.6f, 0, 0.8f}, {-0.6f, 0, 0.8f}), 0.738523f, 1e-5f);
  // wi = n, wo = (0.6, 0, 0.8): h = (0.6, 0, 1.8)/sqrt(3.6) = (0.316228, 0, 0.948683);
  // exponent (hx/αx)²/hz² = 7.716049, 0.047746 + 0.25 e^-7.716 / (4π 0.036 sqrt(0.8)) = 0.048022
  EXPECT_NEAR(ward({0, 0, 1}, {0.6f, 0, 0.8f}), 0.048022f, 1e-5f);
  // The same tilt along the binormal meets αy = 0.3: exponent 1.234568 -> 0.227516.
  EXPECT_NEAR(ward({0, 0, 1}, {0, 0.6f, 0.8f}), 0.227516f, 1e-5f);
  EXPECT_EQ(ward({0, 0, -1}, {0, 0, 1}), 0.0f);  // light below the surface
  Vec3 a = normalize({0.3f, -0.5f, 0.7f}), b = normalize({-0.2f, 0.1f, 0.9f});
  EXPECT_FLOAT_EQ(ward(a, b), ward(b, a));  // reciprocity
}

TEST(CubeTexelIndex, FaceSelectionAndCoordinates) {
  // Size 4, +Z face centre: u = v = 1/2 -> texel (2, 2): 4*16 + 2*4 + 2 = 74.
  EXPECT_EQ(cubeTexelIndex({0, 0, 1}, 4), 74);
  // (1, 1, 0): tie between x and y resolves to +Y (face 2): sc = x = 1, tc = z = 0,
  // u = 1 -> x clamps to 3, v = 1/2 -> y = 2: 2*16 + 2*4 + 3 = 43.
  EXPECT_EQ(cubeTexelIndex({1, 1, 0}, 4), 43);
  // -X face (1): sc = z, tc = -y; (-1, 0.5, -0.5): u = (-0.5 + 1)/2 = 0.25 -> x = 1,
  // v = (-0.5 + 1)/2 = 0.25 -> y = 1: 16 + 4 + 1 = 21.
  EXPECT_EQ(cubeTexelIndex({-1, 0.5f, -0.5f}, 4), 21);
  // Every texel centre direction (D3DXFillCubeTexture's) finds its own texel.
  for (int face = 0; face < 6; ++face)
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x)
        EXPECT_EQ(cubeTexelIndex(cubeTexelDirection(face, float(x), float(y), 8) * 3.0f, 8),
                  (face * 8 + y) * 8 + x);
}

TEST(BrdfFactorization, RecoversAProductFormBrdf) {
  BrdfFactorization fit = computeBrdfFactorization(separable);
  // The model can represent f exactly up to the nearest-texel steps of a and b: with
  // 32 texels per face (about 3.6° at a face centre) log a changes by at most
  // |d log a / dθ| ~ 1.3 per radian times half a texel (0.031 rad) ~ 0.04 at worst,
  // a fraction of that on average.
  double err = heldOutError([&](Vec3 wi, Vec3 wo) { return fit.evaluate(wi, wo); }, separable, false);
  std::printf("product-form BRDF: held-out relative RMS error %.4f (training %.4f)\n", err, fit.trainingError);
  EXPECT_LT(err, 0.05);
  EXPECT_LT(fit.trainingError, 0.05f);
  // Up to the gauge (P + c/2, Q - c), P is log a and Q is log b at the texels:
  // P - log a is the same constant everywhere the samples reach.
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int t = 0; t < 6 * 32 * 32; ++t) {
    int face = t / 1024, rest = t % 1024;
    Vec3 d = normalize(cubeTexelDirection(face, float(rest % 32), float(rest / 32), 32));
    if (d.z < 0.2f) continue;
    double diff = fit.logP[size_t(t)] - std::log(sepA(d));
    sum += diff, sum2 += diff * diff, ++n;
  }
  double mean = sum / n, spread = std::sqrt(std::max(0.0, sum2 / n - mean * mean));
  EXPECT_LT(spread, 0.02);
}

TEST(BrdfFactorization, WardFitsWithinTheProductFormsError) {
  WardBrdf ward;
  BrdfFactorization fit = computeBrdfFactorization(ward);
  // Ward's specular lobe alone is of the product form (p = 1/sqrt(cos θ), q = the
  // lobe of h); the sum with the diffuse term is not, so the factorization cannot be
  // exact where both matter. The bound allows for that and for the nearest-texel
  // steps across the lobe (αx = 0.12 rad is about two texels of h at size 32).
  double fitErr = heldOutError([&](Vec3 wi, Vec3 wo) { return fit.evaluate(wi, wo); }, ward, false);
  // Through the 8-bit textures the effect multiplies, f cos θi. The cosine is stored
  // per texel, so its relative error grows without bound toward the horizon; light
  // arriving there contributes little, and cosine-weighted pairs weigh it so.
  auto target = [&](Vec3 wi, Vec3 wo) { return double(ward(wi, wo)) * wi.z; };
  double texErr = heldOutError([&](Vec3 wi, Vec3 wo) { return fit.evaluateTextures(wi, wo); }, target, true);
  std::printf("Ward BRDF: held-out relative RMS error %.4f (fit), %.4f (textures, f cos θi); scale %g\n",
              fitErr, texErr, fit.scale);
  EXPECT_LT(fitErr, 0.2);
  EXPECT_LT(texErr, 0.25);
  // Far better than the best constant (a constant misses the lobe by a factor of 10).
  EXPECT_LT(fitErr, 0.5 * heldOutError([](Vec3, Vec3) { return 0.1; }, ward, false));
}

TEST(BrdfFactorization, TexturesAreTheEffectsCubeMaps) {
  BrdfFactorizationOptions o;
  o.cubeSize = 16;
  o.samples = 1 << 15;
  BrdfFactorization fit = computeBrdfFactorization(WardBrdf{}, o);
  for (const TexturePtr& t : {fit.p, fit.pCos, fit.q}) {
    ASSERT_TRUE(t);
    EXPECT_EQ(t->type(), TextureType::Cube);
    EXPECT_EQ(t->format(), Format::A8R8G8B8);
    EXPECT_EQ(t->width(), 16);
    EXPECT_EQ(t->levelCount(), 1);
  }
  EXPECT_FLOAT_EQ(fit.scale, fit.pScale * fit.pCosScale * fit.qScale);
  // The largest value maps to 255 somewhere on the +Z face (the upper hemisphere's
  // heart); pCos is 0 on the -Z face (cos θ < 0).
  int maxP = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      maxP = std::max(maxP, int(fit.p->data(4, 0)[y * fit.p->rowPitch(0) + x * 4 + 2]));
      EXPECT_EQ(fit.pCos->data(5, 0)[y * fit.pCos->rowPitch(0) + x * 4 + 2], 0);
    }
  EXPECT_GT(maxP, 200);
  // The texture product is the fitted model times the texel's cosine, to 8-bit
  // precision. For wi = wo = n the +Z texel (8, 8) is read, centre direction
  // (0.0625, -0.0625, 1) with cos θ = 1/sqrt(1 + 2 * 0.0625²) = 0.9961; each of the
  // three texels rounds by at most half a step, 0.5/255 of its range (about 1% of a
  // value a fifth of the largest).
  Vec3 n{0, 0, 1};
  float viaTextures = fit.evaluateTextures(n, n), viaModel = fit.evaluate(n, n);
  EXPECT_NEAR(viaTextures / viaModel, 0.9961f, 0.04f);
}

TEST(BrdfFactorization, RejectsBadInput) {
  BrdfFactorizationOptions o;
  o.cubeSize = 1;
  EXPECT_THROW(computeBrdfFactorization(WardBrdf{}, o), Error);
  o = {};
  o.samples = 10;
  EXPECT_THROW(computeBrdfFactorization(WardBrdf{}, o), Error);
  o = {};
  o.cubeSize = 8;
  EXPECT_THROW(computeBrdfFactorization([](Vec3, Vec3) { return 0.0f; }, o), Error);
  EXPECT_THROW(computeBrdfFactorization(Brdf{}, o), Error);
}
