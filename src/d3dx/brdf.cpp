// Homomorphic BRDF factorization into cube maps, and Ward's anisotropic BRDF.
#include "refx/d3dx/brdf.h"

#include <algorithm>
#include <cmath>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/texture_fill.h"

namespace refx::d3dx {

namespace {

constexpr double kPi = 3.14159265358979323846;

// splitmix64: a small, fully specified generator, so the samples are the same on
// every platform (std:: distributions are not).
struct Random {
  uint64_t state;
  uint64_t next() {
    uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double uniform() { return double(next() >> 11) * (1.0 / 9007199254740992.0); }  // [0, 1)
  // Uniform over the solid angle of the upper hemisphere: z uniform in (0, 1].
  Vec3 hemisphere() {
    double z = 1.0 - uniform(), phi = 2 * kPi * uniform(), r = std::sqrt(std::max(0.0, 1 - z * z));
    return {float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)};
  }
};

Vec3 halfVector(Vec3 wi, Vec3 wo) { return normalize(wi + wo); }

// Texels of a cube map of size S: face * S² + y * S + x.
struct CubeTexels {
  int size;
  int count() const { return 6 * size * size; }
  Vec3 direction(int index) const {
    int face = index / (size * size), rest = index % (size * size);
    return normalize(cubeTexelDirection(face, float(rest % size), float(rest / size), size));
  }
};

}  // namespace

float WardBrdf::operator()(Vec3 wi, Vec3 wo) const {
  if (wi.z <= 0 || wo.z <= 0) return 0;
  Vec3 h = halfVector(wi, wo);
  float ax = alphaX, ay = alphaY;
  float e = ((h.x / ax) * (h.x / ax) + (h.y / ay) * (h.y / ay)) / (h.z * h.z);
  float spec = specular * std::exp(-e) / (4 * float(kPi) * ax * ay * std::sqrt(wi.z * wo.z));
  return diffuse / float(kPi) + spec;
}

int cubeTexelIndex(Vec3 d, int size) {
  float ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
  int face;
  float sc, tc, ma;
  if (az >= ay && az >= ax) {  // ties resolve z, then y, then x
    face = d.z >= 0 ? 4 : 5, sc = d.z >= 0 ? d.x : -d.x, tc = -d.y, ma = az;
  } else if (ay >= ax) {
    face = d.y >= 0 ? 2 : 3, sc = d.x, tc = d.y >= 0 ? d.z : -d.z, ma = ay;
  } else {
    face = d.x >= 0 ? 0 : 1, sc = d.x >= 0 ? -d.z : d.z, tc = -d.y, ma = ax;
  }
  if (!(ma > 0)) return 4 * size * size + (size / 2) * size + size / 2;  // no direction: +Z centre
  float u = (sc / ma + 1) / 2, v = (tc / ma + 1) / 2;
  int x = std::clamp(int(std::floor(u * float(size))), 0, size - 1);
  int y = std::clamp(int(std::floor(v * float(size))), 0, size - 1);
  return (face * size + y) * size + x;
}

float BrdfFactorization::evaluate(Vec3 wi, Vec3 wo) const {
  if (logP.empty()) return 0;
  Vec3 h = halfVector(wi, wo);
  return std::exp(logP[size_t(cubeTexelIndex(wi, cubeSize))] + logQ[size_t(cubeTexelIndex(h, cubeSize))] +
                  logP[size_t(cubeTexelIndex(wo, cubeSize))]);
}

float BrdfFactorization::evaluateTextures(Vec3 wi, Vec3 wo) const {
  if (!p || !pCos || !q) return 0;
  auto texel = [&](const Texture& t, Vec3 d) {
    int i = cubeTexelIndex(d, cubeSize), n = cubeSize * cubeSize;
    return t.texel(i / n, 0, i % cubeSize, (i % n) / cubeSize).r;
  };
  return scale * texel(*p, wo) * texel(*pCos, wi) * texel(*q, halfVector(wi, wo));
}

BrdfFactorization computeBrdfFactorization(const Brdf& f, const BrdfFactorizationOptions& o) {
  if (o.cubeSize < 2 || o.cubeSize > 256)
    fail("computeBrdfFactorization: cube size must be between 2 and 256, not {}", o.cubeSize);
  if (o.samples < 1000 || o.samples > (1 << 24))
    fail("computeBrdfFactorization: samples must be between 1000 and {}, not {}", 1 << 24, o.samples);
  if (o.iterations < 1 || o.iterations > 10000)
    fail("computeBrdfFactorization: iterations must be between 1 and 10000, not {}", o.iterations);
  if (!(o.smoothness >= 0) || !std::isfinite(o.smoothness))
    fail("computeBrdfFactorization: smoothness must be a finite value >= 0, not {}", o.smoothness);
  if (!f) fail("computeBrdfFactorization: no BRDF given");

  const CubeTexels cube{o.cubeSize};
  const int n = cube.count();
  // Unknowns x = [P (n texels), Q (n texels)]; each sample is one equation
  // P[i] + P[o] + Q[h] = log f(wi, wo).
  struct Sample {
    uint32_t i, o, h;
    float value;
  };
  std::vector<Sample> samples(static_cast<size_t>(o.samples));
  Random rng{o.seed};
  float largest = 0;
  for (Sample& s : samples) {
    Vec3 wi = rng.hemisphere(), wo = rng.hemisphere();
    float v = f(wi, wo);
    s = {uint32_t(cubeTexelIndex(wi, cube.size)), uint32_t(cubeTexelIndex(wo, cube.size)),
         uint32_t(n + cubeTexelIndex(halfVector(wi, wo), cube.size)), std::isfinite(v) ? v : 0.0f};
    largest = std::max(largest, s.value);
  }
  if (!(largest > 0)) fail("computeBrdfFactorization: the BRDF is not positive anywhere on the hemisphere");
  const float floorValue = 1e-6f * largest;
  for (Sample& s : samples) s.value = std::max(s.value, floorValue);

  // Neighbouring texels (across face edges too): each texel's four neighbours, found
  // by stepping one texel past its face and looking the direction up again.
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  edges.reserve(size_t(4 * n));
  for (int t = 0; t < n; ++t) {
    int face = t / (cube.size * cube.size), rest = t % (cube.size * cube.size);
    int x = rest % cube.size, y = rest / cube.size;
    const int step[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (const auto& s : step) {
      Vec3 d = cubeTexelDirection(face, float(x + s[0]), float(y + s[1]), cube.size);
      int u = cubeTexelIndex(d, cube.size);
      if (u != t) edges.emplace_back(uint32_t(t), uint32_t(u));
    }
  }
  // Each undirected edge appears about twice; half the weight each.
  const double lambda = 0.5 * double(o.smoothness), ridge = 1e-6;

  // Normal equations (AᵀA + λL + εI) x = Aᵀy, solved by conjugate gradients with a
  // Jacobi preconditioner.
  const size_t unknowns = size_t(2 * n);
  std::vector<double> b(unknowns, 0.0), diag(unknowns, ridge);
  std::vector<uint32_t> uses(unknowns, 0);
  for (const Sample& s : samples) {
    double y = std::log(double(s.value));
    b[s.i] += y, b[s.o] += y, b[s.h] += y;
    ++uses[s.i], ++uses[s.o], ++uses[s.h];
    // Diagonal of AᵀA: sum over rows of the squared coefficient (2² when i == o).
    if (s.i == s.o) diag[s.i] += 4, diag[s.h] += 1;
    else diag[s.i] += 1, diag[s.o] += 1, diag[s.h] += 1;
  }
  for (const auto& [a, c] : edges)
    for (uint32_t block : {0u, uint32_t(n)}) diag[a + block] += lambda, diag[c + block] += lambda;

  auto apply = [&](const std::vector<double>& x, std::vector<double>& out) {
    std::fill(out.begin(), out.end(), 0.0);
    for (const Sample& s : samples) {
      double r = x[s.i] + x[s.o] + x[s.h];
      out[s.i] += r, out[s.o] += r, out[s.h] += r;
    }
    for (const auto& [a, c] : edges)
      for (uint32_t block : {0u, uint32_t(n)}) {
        double d = lambda * (x[a + block] - x[c + block]);
        out[a + block] += d, out[c + block] -= d;
      }
    for (size_t k = 0; k < unknowns; ++k) out[k] += ridge * x[k];
  };
  auto dotv = [](const std::vector<double>& a, const std::vector<double>& c) {
    double s = 0;
    for (size_t k = 0; k < a.size(); ++k) s += a[k] * c[k];
    return s;
  };
  std::vector<double> x(unknowns, 0.0), r = b, z(unknowns), dir(unknowns), ad(unknowns);
  for (size_t k = 0; k < unknowns; ++k) z[k] = r[k] / diag[k];
  dir = z;
  double rz = dotv(r, z);
  const double stop = 1e-20 * dotv(b, b);
  for (int it = 0; it < o.iterations && dotv(r, r) > stop; ++it) {
    apply(dir, ad);
    double denom = dotv(dir, ad);
    if (!(denom > 0)) break;
    double alpha = rz / denom;
    for (size_t k = 0; k < unknowns; ++k) x[k] += alpha * dir[k], r[k] -= alpha * ad[k];
    for (size_t k = 0; k < unknowns; ++k) z[k] = r[k] / diag[k];
    double rzNext = dotv(r, z), beta = rzNext / rz;
    rz = rzNext;
    for (size_t k = 0; k < unknowns; ++k) dir[k] = z[k] + beta * dir[k];
  }

  BrdfFactorization result;
  result.cubeSize = cube.size;
  result.logP.resize(size_t(n));
  result.logQ.resize(size_t(n));
  for (int t = 0; t < n; ++t) {
    result.logP[size_t(t)] = float(x[size_t(t)]);
    result.logQ[size_t(t)] = float(x[size_t(n + t)]);
  }
  double err = 0;
  for (const Sample& s : samples) {
    double model = std::exp(x[s.i] + x[s.o] + x[s.h]), rel = (model - s.value) / s.value;
    err += rel * rel;
  }
  result.trainingError = float(std::sqrt(err / double(samples.size())));

  // Texel values and their scales: the largest value among the texels the fit
  // reached maps to 1 (texels no sample touched only clamp).
  const size_t count = static_cast<size_t>(n);
  std::vector<float> pv(count), pcv(count), qv(count);
  float pMax = 0, pcMax = 0, qMax = 0;
  for (int t = 0; t < n; ++t) {
    pv[size_t(t)] = std::exp(result.logP[size_t(t)]);
    pcv[size_t(t)] = pv[size_t(t)] * std::max(cube.direction(t).z, 0.0f);
    qv[size_t(t)] = std::exp(result.logQ[size_t(t)]);
    if (uses[size_t(t)]) pMax = std::max(pMax, pv[size_t(t)]), pcMax = std::max(pcMax, pcv[size_t(t)]);
    if (uses[size_t(n + t)]) qMax = std::max(qMax, qv[size_t(t)]);
  }
  result.pScale = pMax > 0 ? pMax : 1;
  result.pCosScale = pcMax > 0 ? pcMax : 1;
  result.qScale = qMax > 0 ? qMax : 1;
  result.scale = result.pScale * result.pCosScale * result.qScale;
  auto makeCube = [&](const std::vector<float>& values, float scale) {
    TexturePtr t = Texture::createCube(Format::A8R8G8B8, cube.size, 1);
    std::vector<Color4> row(static_cast<size_t>(cube.size));
    for (int face = 0; face < 6; ++face)
      for (int y = 0; y < cube.size; ++y) {
        for (int xx = 0; xx < cube.size; ++xx) {
          float v = std::clamp(values[size_t((face * cube.size + y) * cube.size + xx)] / scale, 0.0f, 1.0f);
          row[size_t(xx)] = {v, v, v, 1};
        }
        encodeRow(Format::A8R8G8B8, row.data(), cube.size, t->data(face, 0) + size_t(y) * t->rowPitch(0));
      }
    t->markDirty();
    return t;
  };
  result.p = makeCube(pv, result.pScale);
  result.pCos = makeCube(pcv, result.pCosScale);
  result.q = makeCube(qv, result.qScale);
  return result;
}

}  // namespace refx::d3dx
