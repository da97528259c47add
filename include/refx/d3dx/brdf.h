// BRDF factor cube maps for the effect paper's "BRDF Shader" technique: homomorphic
// factorization (McCool, Ang and Ahmad, SIGGRAPH 2001). A reciprocal BRDF is
// approximated by a product of two functions of one direction each,
//   f(wi, wo) ≈ p(wi) q(wh) p(wo),   wh = normalize(wi + wo),
// fitted in log space, log f ≈ P(wi) + Q(wh) + P(wo), by linear least squares over
// many direction pairs. The effect multiplies three cube textures: p looked up with
// the view vector, p again with the light vector and q with the half vector; here
// the cosine of the light's incidence is folded into the second, so the effect's
// product is f(wi, wo) cos θi, the light reflected toward the viewer.
//
// Directions are in tangent space (x = tangent, y = binormal, z = normal), unit
// length, pointing away from the surface; the upper hemisphere is z > 0.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "refx/core/math.h"
#include "refx/resource/texture.h"

namespace refx::d3dx {

using Brdf = std::function<float(Vec3 wi, Vec3 wo)>;

// Ward's anisotropic model (Ward 1992):
//   f = ρd/π + ρs exp(-((hx/αx)² + (hy/αy)²) / hz²) / (4π αx αy sqrt(cos θi cos θo))
// with h = normalize(wi + wo); 0 when either direction is below the surface.
struct WardBrdf {
  float diffuse = 0.15f;   // ρd
  float specular = 0.25f;  // ρs
  float alphaX = 0.12f;    // roughness along the tangent
  float alphaY = 0.30f;    // roughness along the binormal
  float operator()(Vec3 wi, Vec3 wo) const;
};

struct BrdfFactorizationOptions {
  int cubeSize = 32;          // texels along a cube face edge
  int samples = 1 << 18;      // (wi, wo) pairs over the hemisphere, uniform in solid angle
  int iterations = 200;       // conjugate-gradient steps on the normal equations (at most)
  float smoothness = 0.5f;    // weight of (X[a] - X[b])² for neighbouring texels; fills the
                              // texels no sample reaches (the lower hemisphere)
  uint32_t seed = 1;          // of the sample directions
};

struct BrdfFactorization {
  int cubeSize = 0;
  // Fitted P = log p and Q = log q per cube texel (index cubeTexelIndex).
  std::vector<float> logP, logQ;
  // The effect's BRDFTexture1..3: A8R8G8B8 cube maps, one level, RGB = the value
  // divided by its scale (so the largest is 1), A = 1. Point sampling reads exactly
  // the fitted texels.
  TexturePtr p;     // p(w), looked up with the view vector (t0)
  TexturePtr pCos;  // p(w) max(w.z, 0) at the texel centre, looked up with the light vector (t1)
  TexturePtr q;     // q(w), looked up with the half vector (t2)
  float pScale = 1, pCosScale = 1, qScale = 1;
  // f(wi, wo) cos θi ≈ scale * p(wo) * pCos(wi) * q(wh) in texel values:
  // scale = pScale * pCosScale * qScale. An application folds it into the material
  // colour (the effect's oD0) or the light's intensity.
  float scale = 1;
  // Relative RMS error of exp(P(wi) + Q(wh) + P(wo)) against f over the fitted samples.
  float trainingError = 0;

  // p(wi) q(wh) p(wo) from the fitted values (nearest texels): the model of f.
  float evaluate(Vec3 wi, Vec3 wo) const;
  // What the effect computes: scale * the three 8-bit texels, ≈ f cos θi.
  float evaluateTextures(Vec3 wi, Vec3 wo) const;
};

// Throws refx::Error for option values out of range (cube size 2..256, at least 1000
// samples, 1..10000 iterations) and when f gives no positive value at all.
// Values of f below 1e-6 of its largest sample are raised to that floor before the
// logarithm.
BrdfFactorization computeBrdfFactorization(const Brdf& f, const BrdfFactorizationOptions& options = {});

// Index face * size² + y * size + x of the cube texel that point sampling reads for
// direction d: the major axis picks the face (ties z, then y, then x, as D3D9
// hardware), face coordinates as D3D's cube addressing, clamped to the face.
int cubeTexelIndex(Vec3 d, int size);

}  // namespace refx::d3dx
