// Texture sampling over 16-lane SoA batches: D3D9 addressing, point/linear filtering,
// mip selection, cube faces, border color and sRGB.
//
// Two paths agree bit for bit:
//  * a scalar reference path, lane by lane, for every texture type, format and mode;
//  * a vectorised kernel for the common case (one 2D level or cube face, 8-bit unorm
//    texels, no BORDER addressing, no sRGB), run on all 16 lanes at once.
// 8-bit unorm levels are filtered in byte units (0..255) and divided by 255 at the
// end: point sampling returns exactly byte/255 and constant regions stay constant.
//
// Filter weights have 8 bits of sub-texel precision, as on D3D9-era hardware (D3D10
// later required at least 8): the texel-space position of LINEAR filtering and the
// λ of MIPFILTER LINEAR are rounded to multiples of 1/256 (toFixed8) before they are
// split into a texel (level) index and a weight w/256, w in 0..255. For 8-bit unorm
// texels t_ij a bilinear sample is then exactly
//   S = sum t_ij·wx_i·wy_j  (wx_0 = 256 - wx, wx_1 = wx; likewise y),  0 <= S <= 255·65536,
//   result = S / (255·65536) rounded once to float,
// whichever path computes it: the reference's float lerps are exact on these values
// (byte units: top/bottom rows are multiples of 1/256 below 256, the blend multiples
// of 1/65536 below 256, all within float's 24 bits), and the vectorised kernel
// forms S with integer arithmetic. The mip blend r0 + (m/256)·(r1 - r0) and the
// volume depth blend stay in float; float, signed, sRGB and BORDER samples use the
// same quantised weights with float texels.
#include "refx/resource/sampler.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#if defined(__AVX__)
#include <immintrin.h>
#endif

#include "resource/sampler_internal.h"
#include "resource/sampler_kernels.h"

namespace refx {

using resource::Kernel2D;
using resource::srgbToLinear;
using namespace resource::kernels;

namespace {

constexpr int kLanes = kBatchLanes;
constexpr float kZeros[kLanes] = {};

// ---------------------------------------------------------------- cube faces (§10)

struct CubeFaceAxes {
  int sc, tc, ma;  // direction component giving sc, tc and the major axis
  float scSign, tcSign;
};
// Indexed by D3DCUBEMAP_FACES: +X, -X, +Y, -Y, +Z, -Z.
constexpr CubeFaceAxes kCubeFaces[6] = {
    {2, 1, 0, -1, -1},  // +X: sc = -rz, tc = -ry
    {2, 1, 0, +1, -1},  // -X: sc = +rz, tc = -ry
    {0, 2, 1, +1, +1},  // +Y: sc = +rx, tc = +rz
    {0, 2, 1, +1, -1},  // -Y: sc = +rx, tc = -rz
    {0, 1, 2, +1, -1},  // +Z: sc = +rx, tc = -ry
    {0, 1, 2, -1, -1},  // -Z: sc = -rx, tc = -ry
};

// Major axis; ties go z > y > x as on D3D9 hardware.
int selectCubeFace(float x, float y, float z) {
  float ax = std::fabs(x), ay = std::fabs(y), az = std::fabs(z);
  if (az >= ax && az >= ay) return z < 0 ? 5 : 4;
  if (ay >= ax) return y < 0 ? 3 : 2;
  return x < 0 ? 1 : 0;
}

// u = (sc/|ma| + 1)/2, v = (tc/|ma| + 1)/2.
void faceCoords(int face, const float d[3], float& u, float& v) {
  const CubeFaceAxes& f = kCubeFaces[face];
  float ma = std::fabs(d[f.ma]);
  if (!(ma > 0)) {  // zero (or NaN) direction: the face center
    u = v = 0.5f;
    return;
  }
  u = (f.scSign * d[f.sc] / ma + 1.0f) * 0.5f;
  v = (f.tcSign * d[f.tc] / ma + 1.0f) * 0.5f;
}

// Change of the face coordinates (u,v) for a change dd of the direction d, by the
// quotient rule on u = (sc/|ma| + 1)/2 (d is kept on its own face).
void faceDerivative(int face, const float d[3], const float dd[3], float& du, float& dv) {
  const CubeFaceAxes& f = kCubeFaces[face];
  float ma = std::fabs(d[f.ma]);
  if (!(ma > 0)) {
    du = dv = INFINITY;
    return;
  }
  float dma = d[f.ma] < 0 ? -dd[f.ma] : dd[f.ma];
  float sc = f.scSign * d[f.sc], tc = f.tcSign * d[f.tc];
  float dsc = f.scSign * dd[f.sc], dtc = f.tcSign * dd[f.tc];
  float inv = 0.5f / (ma * ma);
  du = (dsc * ma - sc * dma) * inv;
  dv = (dtc * ma - tc * dma) * inv;
}

// ---------------------------------------------------------------- level of detail

// The screen-space derivatives of the texture coordinates, in texels of level 0.
struct Footprint {
  TextureType type;
  float size[3];  // level 0 width, height, depth (cube: face size)

  explicit Footprint(const Texture& tex)
      : type(tex.type()),
        size{float(tex.width(0)), float(tex.height(0)),
             tex.type() == TextureType::Volume ? float(tex.depth(0)) : 0.0f} {}

  // λ before bias: log2 ρ, ρ = the longer of the two derivative vectors (lane's own
  // coordinates c give the cube face the derivatives are projected on).
  float lod(const float* const c[3], int lane, const float dx[3], const float dy[3]) const {
    float la, lb;
    squaredLengths(c, lane, dx, dy, la, lb);
    return 0.5f * std::log2(std::max(la, lb));  // log2 sqrt(ρ²)
  }

  // The squared lengths, in texels of level 0, of the derivative vectors dx and dy.
  void squaredLengths(const float* const c[3], int lane, const float dx[3], const float dy[3],
                      float& la, float& lb) const {
    float a[3], b[3];
    if (type == TextureType::Cube) {
      const float d[3] = {c[0][lane], c[1][lane], c[2][lane]};
      int face = selectCubeFace(d[0], d[1], d[2]);
      faceDerivative(face, d, dx, a[0], a[1]);
      faceDerivative(face, d, dy, b[0], b[1]);
      a[0] *= size[0], a[1] *= size[0], b[0] *= size[0], b[1] *= size[0];
      a[2] = b[2] = 0;
    } else {  // 2D or volume: a 2D texture's λ ignores the third coordinate (even NaN)
      a[2] = b[2] = 0;
      for (int i = 0; i < (type == TextureType::Volume ? 3 : 2); ++i)
        a[i] = dx[i] * size[i], b[i] = dy[i] * size[i];
    }
    la = a[0] * a[0] + a[1] * a[1] + a[2] * a[2];
    lb = b[0] * b[0] + b[1] * b[1] + b[2] * b[2];
  }
};

// λ per lane. Derivatives/Bias: one value per 2x2 quad from its top-left, top-right
// and bottom-left lanes (masked-off lanes still give coordinates), plus the lane's
// own bias for texldb.
void computeLambda(const Texture& tex, const SamplerState& st, const SampleRequest& req,
                   const float* const c[3], float lam[kLanes]) {
  const float* lod = req.lod ? req.lod : kZeros;
  const Footprint fp(tex);
  switch (req.lodMode) {
    case LodMode::Explicit:
      for (int l = 0; l < kLanes; ++l) lam[l] = lod[l] + st.mipLodBias;
      return;
    case LodMode::Gradients: {
      for (int l = 0; l < kLanes; ++l) {
        float dx[3], dy[3];
        for (int i = 0; i < 3; ++i) {
          dx[i] = req.ddx[i] ? req.ddx[i][l] : 0.0f;
          dy[i] = req.ddy[i] ? req.ddy[i][l] : 0.0f;
        }
        lam[l] = fp.lod(c, l, dx, dy) + st.mipLodBias;
      }
      return;
    }
    case LodMode::Derivatives:
    case LodMode::Bias:
      break;
  }
  const bool perLaneBias = req.lodMode == LodMode::Bias;
  for (int q = 0; q < kLanes / 4; ++q) {
    const int tl = q * 4, tr = tl + 1, bl = tl + 2;
    float dx[3], dy[3];
    for (int i = 0; i < 3; ++i) {
      dx[i] = c[i][tr] - c[i][tl];
      dy[i] = c[i][bl] - c[i][tl];
    }
    float quad = fp.lod(c, tl, dx, dy) + st.mipLodBias;
    for (int k = 0; k < 4; ++k) lam[tl + k] = quad + (perLaneBias ? lod[tl + k] : 0.0f);
  }
}

// NONE samples like POINT; ANISOTROPIC (and the quad filters) like LINEAR.
bool isLinear(TextureFilter f) { return uint32_t(f) >= uint32_t(TextureFilter::Linear); }

// Which level(s) and filter each lane uses.
struct LanePlan {
  int level[2][kLanes];
  float mipFrac[kLanes];  // weight of level[1]; 0: level[0] alone
  int linear[kLanes];     // 1: LINEAR filtering, 0: POINT
};

inline float clampFinite(float x, float lo, float hi) {
  x = x > lo ? x : lo;  // NaN -> lo
  return x < hi ? x : hi;
}

// x rounded to the nearest multiple of 1/256, in units of 1/256: floor(x) = X >> 8 and
// the weight of the next texel (level) (X & 255)/256. Rounds half to even, as the
// vectorised kernel's vcvtps2dq does (both use the MXCSR mode, round-to-nearest).
// |x| <= 2^22 here, so X fits an int.
inline int toFixed8(float x) {
#if defined(__AVX__)
  return _mm_cvtss_si32(_mm_set_ss(x * kWeightScale));  // vcvtss2si: MXCSR rounding, inline
#else
  return int(std::lrint(x * kWeightScale));
#endif
}
inline int fixed8Floor(int X) { return X >> kWeightBits; }
inline int fixed8Weight(int X) { return X & ((1 << kWeightBits) - 1); }

// The level(s) one λ selects (MIPFILTER POINT or LINEAR; NONE is handled by the caller).
struct LevelChoice {
  int level[2];
  float frac;  // weight of level[1]; 0: level[0] alone
};
LevelChoice chooseLevels(const Texture& tex, const SamplerState& st, float lam) {
  const int last = tex.levelCount() - 1;
  // MAXMIPLEVEL: the most detailed level that may be used; λ is clamped to
  // [MAXMIPLEVEL, levels-1].
  const int first = int(std::min<uint32_t>(st.maxMipLevel, uint32_t(last)));
  const float lc = clampFinite(lam, float(first), float(last));
  if (st.mipFilter == TextureFilter::Point) {
    const int nearest = int(std::floor(lc + 0.5f));
    return {{nearest, nearest}, 0.0f};
  }
  // LINEAR: levels floor(λ) and floor(λ)+1, weighted by frac(λ) in 1/256
  const int L = toFixed8(lc);
  const int l0 = fixed8Floor(L);  // lc <= last, so l0 < last or the weight is 0
  return {{l0, std::min(l0 + 1, last)}, float(fixed8Weight(L)) * kWeightUnit};
}

void planLevels(const Texture& tex, const SamplerState& st, const float lam[kLanes],
                LanePlan& p) {
  // λ <= 0: magnification (NaN from degenerate coordinates counts as such).
  const int magLinear = isLinear(st.magFilter), minLinear = isLinear(st.minFilter);
  for (int l = 0; l < kLanes; ++l) p.linear[l] = lam[l] > 0 ? minLinear : magLinear;
  const uint32_t mip = uint32_t(st.mipFilter);
  // MIPFILTER NONE: level 0 whatever λ and MAXMIPLEVEL.
  if (mip == uint32_t(TextureFilter::None)) {
    for (int l = 0; l < kLanes; ++l) p.level[0][l] = p.level[1][l] = 0, p.mipFrac[l] = 0;
    return;
  }
  for (int l = 0; l < kLanes; ++l) {
    const LevelChoice choice = chooseLevels(tex, st, lam[l]);
    p.level[0][l] = choice.level[0], p.level[1][l] = choice.level[1];
    p.mipFrac[l] = choice.frac;
  }
}

// ---------------------------------------------------------------- addressing (§9)

TextureAddress validAddress(TextureAddress a) {
  uint32_t v = uint32_t(a);
  return v >= 1 && v <= 5 ? a : TextureAddress::Wrap;
}

inline float clampPosition(float x, float lo, float hi) { return clampFinite(x, lo, hi); }

// floor(x) as an int, for |x| < 2^31 (the vectorised kernel computes it the same way).
inline int floorInt(float x) {
  int i = int(x);
  return float(i) > x ? i - 1 : i;
}

// The coordinate reduced to one period before scaling (exact in float): WRAP keeps
// frac(u), MIRROR keeps u mod 2. The texel chosen is the same as from u*size taken
// modulo the period, with less rounding for large |u|.
inline float reduceCoord(TextureAddress a, float u) {
  u = clampPosition(u, -kCoordLimit, kCoordLimit);
  if (a == TextureAddress::Wrap) return u - float(floorInt(u));
  if (a == TextureAddress::Mirror) return u - 2.0f * float(floorInt(u * 0.5f));
  return u;
}

// Texel index after addressing; -1 = outside the level (BORDER color).
int addressTexel(TextureAddress a, int i, int n) {
  switch (a) {
    case TextureAddress::Mirror: {
      int p = 2 * n, m = ((i % p) + p) % p;
      return m < n ? m : p - 1 - m;
    }
    case TextureAddress::Clamp:
      return std::clamp(i, 0, n - 1);
    case TextureAddress::Border:
      return i < 0 || i >= n ? -1 : i;
    case TextureAddress::MirrorOnce:
      return std::clamp(i < 0 ? -1 - i : i, 0, n - 1);
    case TextureAddress::Wrap:
      break;
  }
  return ((i % n) + n) % n;
}

// ---------------------------------------------------------------- scalar reference

const std::array<float, 256>& srgbByteTable() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[i] = srgbToLinear(float(i) / 255.0f);
    return t;
  }();
  return table;
}

// One level as the scalar path reads it. Texel values are in "level units": bytes
// (0..255) for 8-bit unorm levels without sRGB, shader values otherwise.
struct LevelReader {
  const SampleLevel& lv;
  bool bytes, srgb;
  Color4 border;

  LevelReader(const SampleLevel& level, const SamplerState& st)
      : lv(level), bytes(level.unorm8 && !st.srgb), srgb(st.srgb), border(st.borderColor) {
    if (bytes) border = {border.r * 255.0f, border.g * 255.0f, border.b * 255.0f,
                         border.a * 255.0f};
  }

  Color4 fetch(int x, int y, int z) const {
    if (x < 0 || y < 0 || z < 0) return border;
    size_t i = (size_t(z) * lv.height + size_t(y)) * lv.width + size_t(x);
    if (lv.unorm8) {
      uint32_t p = lv.rgba8[i];
      int r = p & 255, g = (p >> 8) & 255, b = (p >> 16) & 255, a = p >> 24;
      if (bytes) return {float(r), float(g), float(b), float(a)};
      const auto& lin = srgbByteTable();
      return {lin[r], lin[g], lin[b], float(a) / 255.0f};
    }
    Color4 c = lv.rgbaf[i];
    if (srgb) c = {srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b), c.a};
    return c;
  }

  Color4 finish(Color4 c) const {
    if (bytes) return {c.r / 255.0f, c.g / 255.0f, c.b / 255.0f, c.a / 255.0f};
    return c;
  }
};

inline Color4 lerp(Color4 a, Color4 b, float t) {
  return {a.r + t * (b.r - a.r), a.g + t * (b.g - a.g), a.b + t * (b.b - a.b),
          a.a + t * (b.a - a.a)};
}

Color4 sampleScalar(const LevelReader& rd, const TextureAddress addr[3], bool linear,
                    bool volume, float u, float v, float w) {
  const float coord[3] = {u, v, w};
  const int size[3] = {rd.lv.width, rd.lv.height, rd.lv.depth};
  int i0[3] = {0, 0, 0}, i1[3] = {0, 0, 0};
  float frac[3] = {0, 0, 0};
  for (int a = 0; a < (volume ? 3 : 2); ++a) {
    float lo, hi;
    positionRange(addr[a], size[a], lo, hi);
    // POINT: texel floor(u*W); LINEAR: texels floor(u*W - 0.5) and the next one,
    // with the position rounded to 1/256 texel.
    float x = reduceCoord(addr[a], coord[a]) * float(size[a]);
    if (linear) x = x - 0.5f;
    x = clampPosition(x, lo, hi);
    int i = floorInt(x);
    if (linear) {
      const int X = toFixed8(x);
      i = fixed8Floor(X);
      frac[a] = float(fixed8Weight(X)) * kWeightUnit;
    }
    i0[a] = addressTexel(addr[a], i, size[a]);
    i1[a] = addressTexel(addr[a], i + 1, size[a]);
  }
  if (!linear) return rd.finish(rd.fetch(i0[0], i0[1], i0[2]));
  auto slice = [&](int z) {
    Color4 top = lerp(rd.fetch(i0[0], i0[1], z), rd.fetch(i1[0], i0[1], z), frac[0]);
    Color4 bottom = lerp(rd.fetch(i0[0], i1[1], z), rd.fetch(i1[0], i1[1], z), frac[0]);
    return lerp(top, bottom, frac[1]);
  };
  Color4 c = slice(i0[2]);
  if (volume) c = lerp(c, slice(i1[2]), frac[2]);
  return rd.finish(c);
}

// ---------------------------------------------------------------- vectorised kernel

// Eight lanes as one value (GCC/Clang vector extensions): the kernel is written with
// these so that it is vectorised whatever the compiler's loop heuristics decide.
typedef float v8f __attribute__((vector_size(32)));
typedef int v8i __attribute__((vector_size(32)));

inline v8f splat(float f) { return v8f{f, f, f, f, f, f, f, f}; }
inline v8f toFloat(v8i i) { return __builtin_convertvector(i, v8f); }
inline v8f clampPosition(v8f x, float lo, float hi) {
  const v8f l = splat(lo), h = splat(hi);
#if defined(__AVX__)
  // vmaxps/vminps compute exactly x > l ? x : l and x < h ? x : h (NaN -> l).
  __m256 m;
  std::memcpy(&m, &x, sizeof m);
  __m256 ml, mh;
  std::memcpy(&ml, &l, sizeof ml);
  std::memcpy(&mh, &h, sizeof mh);
  m = _mm256_min_ps(_mm256_max_ps(m, ml), mh);
  std::memcpy(&x, &m, sizeof x);
  return x;
#else
  x = x > l ? x : l;
  return x < h ? x : h;
#endif
}
inline v8i floorInt(v8f x) {
  v8i i = __builtin_convertvector(x, v8i);
  return i + (toFloat(i) > x);  // true is -1
}

// Texel indices (after addressing) and weights of one axis for all lanes: the same
// float operations as sampleScalar. Indices before addressing lie within the position
// range (plus one), so one step of each rule is enough.
template <TextureAddress A>
v8i addressLanes(v8i i, int n) {
  const int p = 2 * n;
  if constexpr (A == TextureAddress::Wrap) {
    return i < 0 ? i + n : (i >= n ? i - n : i);
  } else if constexpr (A == TextureAddress::Mirror) {
    v8i m = i < 0 ? i + p : (i >= p ? i - p : i);
    return m < n ? m : (p - 1) - m;
  } else if constexpr (A == TextureAddress::MirrorOnce) {
    v8i m = i < 0 ? -1 - i : i;
    return m < n - 1 ? m : n - 1;
  } else {  // Clamp
    v8i m = i > 0 ? i : 0;
    return m < n - 1 ? m : n - 1;
  }
}

// Texel loads stay scalar: on current x86 cores they are faster than vpgatherdd.
inline uint32_t scalarLoad(const uint32_t* texels, int i) {
  uint32_t v = texels[i];
#if defined(__GNUC__)
  asm("" : "+r"(v));  // keeps the loop from being turned into a gather
#endif
  return v;
}

// kernel2D with both axes' addressing modes fixed at compile time and the axis
// arithmetic, texel loads and filtering done 8 lanes at a time: the same float
// operations as sampleScalar, in fewer instructions.
typedef uint32_t v8u __attribute__((vector_size(32)));

// Rounds to the nearest int by the MXCSR mode (vcvtps2dq), as lrint does.
inline v8i roundInt(v8f x) {
#if defined(__AVX__)
  __m256 m;
  std::memcpy(&m, &x, sizeof m);
  const __m256i r = _mm256_cvtps_epi32(m);
  v8i X;
  std::memcpy(&X, &r, sizeof X);
  return X;
#else
  v8i X;
  for (int l = 0; l < 8; ++l) X[l] = int(std::lrint(x[l]));
  return X;
#endif
}

// float(floorInt(x)) for |x| <= 2^22 (vroundps toward -inf).
inline v8f floorFloat(v8f x) {
#if defined(__AVX__)
  __m256 m;
  std::memcpy(&m, &x, sizeof m);
  m = _mm256_floor_ps(m);
  std::memcpy(&x, &m, sizeof x);
  return x;
#else
  return toFloat(floorInt(x));
#endif
}

// Unsigned minimum of each lane.
inline v8i minU32(v8i a, v8i b) {
  const v8u ua = v8u(a), ub = v8u(b);
  return v8i(ua < ub ? ua : ub);
}

// WRAP for indices in [-1, n]: as unsigned, the wrong one of i, i + n, i - n is the
// larger (i + n for i = n, i for i = -1, and i - n below n = 0 only for i = n).
inline v8i wrapLow(v8i i, int n) { return minU32(i, i + n); }   // i in [-1, n - 1]
inline v8i wrapHigh(v8i i, int n) { return minU32(i, i - n); }  // i in [0, n]

// One axis of eight lanes: texel indices after addressing and, for LINEAR, the weight
// of the second texel in 1/256 (0..255). LINEAR takes X = toFixed8(u·W - 0.5) as
// u·(256·W) - 128: scaling by 256 commutes with rounding, so it is the same value.
template <TextureAddress A, bool Linear>
inline void axis8(const float* c, float fn, float lo, float hi, int n, v8i& i0, v8i& i1,
                  v8i& X) {
  v8f u;
  std::memcpy(&u, c, sizeof u);
  u = clampPosition(u, -kCoordLimit, kCoordLimit);
  if constexpr (A == TextureAddress::Wrap) u = u - floorFloat(u);
  if constexpr (A == TextureAddress::Mirror) u = u - 2.0f * floorFloat(u * 0.5f);
  // WRAP: u is in [0, 1] here, so x lies inside [lo, hi] already, and POINT's texel
  // in [0, n], LINEAR's in [-1, n - 1].
  if constexpr (Linear) {
    v8f x = u * (fn * kWeightScale) - 0.5f * kWeightScale;
    if constexpr (A != TextureAddress::Wrap)
      x = clampPosition(x, lo * kWeightScale, hi * kWeightScale);
    X = roundInt(x);
    const v8i i = X >> kWeightBits;
    if constexpr (A == TextureAddress::Wrap) {
      i0 = wrapLow(i, n);
      i1 = wrapHigh(i + 1, n);
    } else {
      i0 = addressLanes<A>(i, n);
      i1 = addressLanes<A>(i + 1, n);
    }
  } else {
    v8f x = u * fn;
    if constexpr (A != TextureAddress::Wrap) x = clampPosition(x, lo, hi);
    const v8i i = __builtin_convertvector(floorFloat(x), v8i);
    if constexpr (A == TextureAddress::Wrap)
      i0 = wrapHigh(i, n);
    else
      i0 = addressLanes<A>(i, n);
  }
}

// Eight texels by index. The indices go through memory and the texels are inserted one
// by one: on current x86 cores that beats vpgatherdd.
inline v8u load8(const uint32_t* texels, v8i a) {
#if defined(__AVX2__)
  alignas(32) int ix[8];
  std::memcpy(ix, &a, sizeof ix);
#if defined(__GNUC__)
  asm volatile("" ::: "memory");  // reload the indices as integers, not by lane extraction
#endif
  __m128i lo = _mm_cvtsi32_si128(int(texels[ix[0]])), hi = _mm_cvtsi32_si128(int(texels[ix[4]]));
  lo = _mm_insert_epi32(lo, int(texels[ix[1]]), 1), hi = _mm_insert_epi32(hi, int(texels[ix[5]]), 1);
  lo = _mm_insert_epi32(lo, int(texels[ix[2]]), 2), hi = _mm_insert_epi32(hi, int(texels[ix[6]]), 2);
  lo = _mm_insert_epi32(lo, int(texels[ix[3]]), 3), hi = _mm_insert_epi32(hi, int(texels[ix[7]]), 3);
  const __m256i g = _mm256_setr_m128i(lo, hi);
  v8u p;
  std::memcpy(&p, &g, sizeof p);
  return p;
#else
  v8u p;
  for (int l = 0; l < 8; ++l) p[l] = scalarLoad(texels, a[l]);
  return p;
#endif
}

// Whether b - a = d in every lane.
inline bool allDiffer(v8i a, v8i b, int d) {
  const v8i same = (b - a) == d;
#if defined(__AVX2__)
  __m256i m;
  std::memcpy(&m, &same, sizeof m);
  return _mm256_movemask_epi8(m) == -1;
#else
  const v8i all = v8i{} - 1;
  return __builtin_memcmp(&same, &all, sizeof same) == 0;
#endif
}

// Whether every lane's second column is the next texel in memory (no wrap or clamp
// at the row end), so both columns come from one 64-bit load.
inline bool pairs8(v8i x0, v8i x1) { return allDiffer(x0, x1, 1); }

// Texels a[l] and a[l] + 1 of every lane.
inline void loadPairs8(const uint32_t* texels, v8i a, v8u& first, v8u& second) {
  typedef uint64_t v4q __attribute__((vector_size(32)));
  v4q lo, hi;
  // lo holds the pairs of lanes 0, 1, 4, 5 and hi those of 2, 3, 6, 7, so that one
  // in-lane shuffle (vshufps) per output puts lanes back in order.
#if defined(__AVX2__)
  __m256i idx;
  std::memcpy(&idx, &a, sizeof idx);
  idx = _mm256_permute4x64_epi64(idx, 0xd8);  // a0 a1 a4 a5 | a2 a3 a6 a7
  const auto* base = reinterpret_cast<const long long*>(texels);
  const __m256i g0 = _mm256_i32gather_epi64(base, _mm256_castsi256_si128(idx), 4);
  const __m256i g1 = _mm256_i32gather_epi64(base, _mm256_extracti128_si256(idx, 1), 4);
  std::memcpy(&lo, &g0, sizeof lo);
  std::memcpy(&hi, &g1, sizeof hi);
#else
  const int order[8] = {0, 1, 4, 5, 2, 3, 6, 7};
  // Element addresses of vector types are not portable (clang rejects them): load
  // through scalars.
  for (int l = 0; l < 4; ++l) {
    long long p0, p1;
    std::memcpy(&p0, texels + a[order[l]], 8);
    std::memcpy(&p1, texels + a[order[l + 4]], 8);
    lo[l] = p0;
    hi[l] = p1;
  }
#endif
  v8u l, h;
  std::memcpy(&l, &lo, sizeof l);
  std::memcpy(&h, &hi, sizeof h);
  first = __builtin_shufflevector(l, h, 0, 2, 8, 10, 4, 6, 12, 14);
  second = __builtin_shufflevector(l, h, 1, 3, 9, 11, 5, 7, 13, 15);
}

// Texel pairs a[l], a[l] + 1 (top row) and a[l] + w, a[l] + w + 1 (bottom row) of every
// lane. Scalar 64-bit loads, the indices read back from memory: on current x86 cores
// this beats four vpgatherdq, which contend with the filter arithmetic for the vector
// pipes.
inline void loadQuads8(const uint32_t* texels, v8i a, int w, v8u& p00, v8u& p10, v8u& p01,
                       v8u& p11) {
  alignas(32) int ix[8];
  std::memcpy(ix, &a, sizeof ix);
#if defined(__AVX2__)
#if defined(__GNUC__)
  asm volatile("" ::: "memory");  // reload the indices as integers, not by lane extraction
#endif
  __m128i q[8];
  for (int l = 0; l < 8; ++l) {
    const uint32_t* t = texels + ix[l];
    const __m128i top = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(t));
    q[l] = _mm_castpd_si128(
        _mm_loadh_pd(_mm_castsi128_pd(top), reinterpret_cast<const double*>(t + w)));
  }
  // q[l] = t00 t10 t01 t11 of lane l. Lanes l and l + 4 share a register (one per
  // 128-bit half), then a 4x4 transpose within each half gives the four texel vectors.
  __m256i r[4];
  for (int l = 0; l < 4; ++l) r[l] = _mm256_setr_m128i(q[l], q[l + 4]);
  const __m256i a01 = _mm256_unpacklo_epi32(r[0], r[1]), b01 = _mm256_unpackhi_epi32(r[0], r[1]);
  const __m256i a23 = _mm256_unpacklo_epi32(r[2], r[3]), b23 = _mm256_unpackhi_epi32(r[2], r[3]);
  const __m256i c[4] = {_mm256_unpacklo_epi64(a01, a23), _mm256_unpackhi_epi64(a01, a23),
                        _mm256_unpacklo_epi64(b01, b23), _mm256_unpackhi_epi64(b01, b23)};
  std::memcpy(&p00, &c[0], sizeof p00);
  std::memcpy(&p10, &c[1], sizeof p10);
  std::memcpy(&p01, &c[2], sizeof p01);
  std::memcpy(&p11, &c[3], sizeof p11);
#else
  for (int l = 0; l < 8; ++l) {
    const uint32_t* t = texels + ix[l];
    p00[l] = t[0], p10[l] = t[1], p01[l] = t[w], p11[l] = t[w + 1];
  }
#endif
}

inline v8f channel(v8u p, int shift) { return __builtin_convertvector(v8i((p >> shift) & 255u), v8f); }

// Bilinear filtering of eight lanes in integers: two channels per 32-bit lane (r,b and
// g,a, one byte each in the low half of a 16-bit lane), lerped along x in sixteen
// 16-bit lanes, t0·256 + (t1 - t0)·wx: 0..65280, the row in 1/256 byte units, exact
// (the arithmetic wraps mod 2^16 but the result fits). Along y in float, exact too:
// top + (bottom - top)·wy/256 is a multiple of 1/256 below 65536 (24 bits), = S/256.
typedef uint16_t v16h __attribute__((vector_size(32)));

// The weight (low byte of the fixed-point position) in both 16-bit halves of each lane.
inline v16h weightPairs(v8i X) {
#if defined(__AVX2__)
  __m256i m;
  std::memcpy(&m, &X, sizeof m);
  const __m256i pick = _mm256_setr_epi8(0, -1, 0, -1, 4, -1, 4, -1, 8, -1, 8, -1, 12, -1, 12, -1,
                                        0, -1, 0, -1, 4, -1, 4, -1, 8, -1, 8, -1, 12, -1, 12, -1);
  m = _mm256_shuffle_epi8(m, pick);
  v16h w;
  std::memcpy(&w, &m, sizeof w);
  return w;
#else
  const v8u w = v8u(X) & 255u;
  return v16h(w | (w << 16));
#endif
}

inline v16h rowLerp(v8u t0, v8u t1, v16h wx) {
  const v16h a = v16h(t0), b = v16h(t1);
  return (a << 8) + (b - a) * wx;
}

inline v8f fmadd(v8f a, v8f b, v8f c) {
#if defined(__FMA__)
  __m256 ma, mb, mc;
  std::memcpy(&ma, &a, sizeof ma);
  std::memcpy(&mb, &b, sizeof mb);
  std::memcpy(&mc, &c, sizeof mc);
  const __m256 r = _mm256_fmadd_ps(ma, mb, mc);
  v8f v;
  std::memcpy(&v, &r, sizeof v);
  return v;
#else
  return a * b + c;  // exact here either way
#endif
}

// b/255 for integer b in 0..255, correctly rounded like the division: fma(b, hi, b·lo)
// with the reciprocal split in two floats (exact for all 256 values; tests check every
// one), without vdivps.
inline v8f byteOver255(v8f b) {
#if defined(__FMA__)
  return fmadd(b, v8f{} + kInv255Hi, b * kInv255Lo);
#else
  return b / 255.0f;
#endif
}

// One channel from the low (shift 0) or high (shift 16) halves of two row results:
// S/(255·65536) = (S/256)/65280, one correctly rounded division as in the reference.

template <int Shift>
inline v8f columnLerp(v16h top, v16h bottom, v8f wy) {
  const v8u mask = v8u{} + (Shift ? 0xffffffffu : 0xffffu);
  const v8f t = toFloat(v8i((v8u(top) >> Shift) & mask));
  const v8f b = toFloat(v8i((v8u(bottom) >> Shift) & mask));
  // x / 65280 without a division (whose throughput limits this loop): fma(x, hi, x·lo)
  // with 1/65280 split in two floats is the correctly rounded quotient, checked
  // exhaustively for every x = S/256, S in [0, 255·65536].
  const v8f x = fmadd(b - t, wy, t);
#if defined(__FMA__)
  return fmadd(x, v8f{} + kInv65280Hi, x * kInv65280Lo);
#else
  return x / 65280.0f;  // the split reciprocal needs a fused multiply-add
#endif
}

template <TextureAddress AU, TextureAddress AV, bool Linear>
void kernel2DFor(const SampleLevel& lv, const float* u, const float* v, float out[4][kLanes]) {
  const int w = lv.width, h = lv.height;
  float loU, hiU, loV, hiV;
  positionRange(AU, w, loU, hiU);
  positionRange(AV, h, loV, hiV);
  const uint32_t* texels = lv.rgba8.data();
  struct Fetched {
    v8u p00, p10, p01, p11;
    v8i fixedX, fixedY;
  };
  [[maybe_unused]] Fetched fetched[2];
  for (int k = 0; k < kLanes; k += 8) {
    v8i x0, x1, y0, y1, fixedX, fixedY;
    axis8<AU, Linear>(u + k, float(w), loU, hiU, w, x0, x1, fixedX);
    axis8<AV, Linear>(v + k, float(h), loV, hiV, h, y0, y1, fixedY);
    const v8i r0 = y0 * w;
    if constexpr (!Linear) {
      const v8u p = load8(texels, r0 + x0);
      for (int ch = 0; ch < 4; ++ch) {
        const v8f t = byteOver255(channel(p, 8 * ch));
        std::memcpy(out[ch] + k, &t, sizeof t);
      }
    } else {
      // Both halves' texels are fetched before either is filtered, so that all the
      // loads are in flight together (the filter waits on their latency).
      const v8i r1 = y1 * w;
      v8u p00, p10, p01, p11;
      const bool pairs = pairs8(x0, x1);
      if (pairs && allDiffer(r0, r1, w)) {  // the 2x2 texels are a block in memory
        loadQuads8(texels, r0 + x0, w, p00, p10, p01, p11);
      } else if (!pairs) {
        p00 = load8(texels, r0 + x0), p10 = load8(texels, r0 + x1);
        p01 = load8(texels, r1 + x0), p11 = load8(texels, r1 + x1);
      } else {
        loadPairs8(texels, r0 + x0, p00, p10);
        loadPairs8(texels, r1 + x0, p01, p11);
      }
      fetched[k / 8] = {p00, p10, p01, p11, fixedX, fixedY};
    }
  }
  if constexpr (Linear) {
    for (int k = 0; k < kLanes; k += 8) {
      const Fetched& f = fetched[k / 8];
      const v8u m = v8u{} + 0x00ff00ffu;
      const v16h wx2 = weightPairs(f.fixedX);
      // (p >> 8) & 0x00ff00ff is the 16-bit halves shifted right by 8 (one vpsrlw).
      const auto highBytes = [](v8u p) { return v8u(v16h(p) >> 8); };
      const v16h topRB = rowLerp(f.p00 & m, f.p10 & m, wx2);
      const v16h topGA = rowLerp(highBytes(f.p00), highBytes(f.p10), wx2);
      const v16h bottomRB = rowLerp(f.p01 & m, f.p11 & m, wx2);
      const v16h bottomGA = rowLerp(highBytes(f.p01), highBytes(f.p11), wx2);
      const v8f fy = toFloat(f.fixedY & ((1 << kWeightBits) - 1)) * kWeightUnit;
      const v8f r = columnLerp<0>(topRB, bottomRB, fy), g = columnLerp<0>(topGA, bottomGA, fy);
      const v8f b = columnLerp<16>(topRB, bottomRB, fy), a = columnLerp<16>(topGA, bottomGA, fy);
      std::memcpy(out[0] + k, &r, sizeof r);
      std::memcpy(out[1] + k, &g, sizeof g);
      std::memcpy(out[2] + k, &b, sizeof b);
      std::memcpy(out[3] + k, &a, sizeof a);
    }
  }
}

template <TextureAddress AU, TextureAddress AV>
constexpr Kernel2D kernelPair(bool linear) {
  return linear ? kernel2DFor<AU, AV, true> : kernel2DFor<AU, AV, false>;
}

template <TextureAddress AU>
constexpr Kernel2D kernelForV(TextureAddress av, bool linear) {
  switch (av) {
    case TextureAddress::Wrap: return kernelPair<AU, TextureAddress::Wrap>(linear);
    case TextureAddress::Mirror: return kernelPair<AU, TextureAddress::Mirror>(linear);
    case TextureAddress::MirrorOnce: return kernelPair<AU, TextureAddress::MirrorOnce>(linear);
    default: return kernelPair<AU, TextureAddress::Clamp>(linear);
  }
}

// The specialised kernel for an addressing pair (BORDER excluded: see fastLevel).
Kernel2D selectKernel2DAvx2(TextureAddress au, TextureAddress av, bool linear) {
  switch (au) {
    case TextureAddress::Wrap: return kernelForV<TextureAddress::Wrap>(av, linear);
    case TextureAddress::Mirror: return kernelForV<TextureAddress::Mirror>(av, linear);
    case TextureAddress::MirrorOnce: return kernelForV<TextureAddress::MirrorOnce>(av, linear);
    default: return kernelForV<TextureAddress::Clamp>(av, linear);
  }
}

// The kernel in the variant of the active instruction set.
Kernel2D selectKernel2D(TextureAddress au, TextureAddress av, bool linear) {
  return resource::selectKernel2D(au, av, linear, activeIsa());
}

// One 2D level of packed rgba8 texels, all lanes.
void kernel2D(const SampleLevel& lv, TextureAddress au, TextureAddress av, bool linear,
              const float* u, const float* v, float out[4][kLanes]) {
  selectKernel2D(au, av, linear)(lv, u, v, out);
}

// ---------------------------------------------------------------- driver

// Whether kernel2D can sample this level: 8-bit unorm texels, no sRGB, no BORDER.
bool fastLevel(const SampleLevel& lv, const SamplerState& st, const TextureAddress addr[3]) {
  return lv.unorm8 && !st.srgb && lv.width > 0 && lv.height > 0 &&
         addr[0] != TextureAddress::Border &&
         addr[1] != TextureAddress::Border && lv.depth == 1 &&
         lv.rgba8.size() == size_t(lv.width) * size_t(lv.height);
}

// Lanes not asked for read 0.
void clearLanes(float out[4][kLanes], uint32_t mask) {
  const v8i bit{1, 2, 4, 8, 16, 32, 64, 128};
  for (int k = 0; k < kLanes; k += 8) {
    const v8i live = (bit & int(mask >> k)) != 0;
    for (int ch = 0; ch < 4; ++ch) {
      v8f v;
      std::memcpy(&v, out[ch] + k, sizeof v);
      v = live ? v : v8f{};
      std::memcpy(out[ch] + k, &v, sizeof v);
    }
  }
}

// Samples one pass (level[pass] of each lane in `todo`) into dst; lanes sharing face,
// level and filter are sampled together.
void samplePass(const Texture& tex, const SamplerState& st, const LanePlan& plan, int pass,
                uint32_t todo, const int face[kLanes], const float* cu, const float* cv,
                const float* cw, const TextureAddress addr[3], bool allowFast,
                float dst[4][kLanes]) {
  const TextureType type = tex.type();
  int key[kLanes];
  for (int l = 0; l < kLanes; ++l)
    key[l] = (face[l] << 24) | (plan.level[pass][l] << 1) | plan.linear[l];
  while (todo) {
    const int lead = std::countr_zero(todo);
    const int f = face[lead], level = plan.level[pass][lead];
    const bool linear = plan.linear[lead];
    uint32_t group = 0;
    for (int l = 0; l < kLanes; ++l) group |= uint32_t(key[l] == key[lead]) << l;
    group &= todo;
    todo &= ~group;

    const SampleLevel& lv = tex.sampleLevel(f, level);
    if (lv.width <= 0 || lv.height <= 0 || lv.depth <= 0) continue;
    if (allowFast && type != TextureType::Volume && fastLevel(lv, st, addr)) {
      if (group == 0xffff) {
        kernel2D(lv, addr[0], addr[1], linear, cu, cv, dst);
      } else {
        float tmp[4][kLanes];
        kernel2D(lv, addr[0], addr[1], linear, cu, cv, tmp);
        for (int ch = 0; ch < 4; ++ch)
          for (int l = 0; l < kLanes; ++l)
            if (group >> l & 1) dst[ch][l] = tmp[ch][l];
      }
      continue;
    }
    const LevelReader reader(lv, st);
    for (int l = 0; l < kLanes; ++l) {
      if (!(group >> l & 1)) continue;
      Color4 s = sampleScalar(reader, addr, linear, type == TextureType::Volume, cu[l], cv[l],
                              cw[l]);
      dst[0][l] = s.r, dst[1][l] = s.g, dst[2][l] = s.b, dst[3][l] = s.a;
    }
  }
}

// ---------------------------------------------------------------- anisotropic filtering
//
// MINFILTER / MAGFILTER ANISOTROPIC (docs/anisotropic_filtering.md). The isotropic λ
// (log2 Pmax + bias) decides between MAGFILTER (λ <= 0) and MINFILTER as for the other
// filters. Where the chosen filter is ANISOTROPIC, with Pmax, Pmin the longer and
// shorter derivative vector in texels of level 0:
//   N = min(ceil(Pmax/Pmin), MAXANISOTROPY clamped to [1,16])   (Pmin = 0: the limit)
//   λ' = λ - log2 N  = log2(Pmax/N) + bias, which selects the level(s) by MIPFILTER
//   probe i (0..N-1) at c + ((i + 0.5)/N - 0.5)·d, d the longer derivative vector in
//   coordinate units (cube maps: the direction's derivative, each probe picks its face)
//   result = (sum of the probes, each bilinear and mip-blended as LINEAR would) / N.
// N = 1 is LINEAR exactly. Volume textures filter ANISOTROPIC as LINEAR. λ given
// explicitly (texldl, vertex texture fetch) has no footprint: N = 1.

constexpr uint32_t kMaxAnisotropy = 16;

uint32_t anisotropyLimit(const SamplerState& st) {
  return std::clamp<uint32_t>(st.maxAnisotropy, 1, kMaxAnisotropy);
}

// Whether ANISOTROPIC filtering can differ from LINEAR for this texture and state.
bool anisotropicFootprint(const Texture& tex, const SamplerState& st) {
  return (st.minFilter == TextureFilter::Anisotropic ||
          st.magFilter == TextureFilter::Anisotropic) &&
         tex.type() != TextureType::Volume;
}

// One lane's probes along the major axis of its footprint.
struct AnisoProbes {
  int count = 1;         // N
  float axis[3] = {};    // the longer derivative vector, coordinate units
};

// The derivatives lane `lane` filters with (the 2x2 quad's for Derivatives/Bias, the
// lane's own for Gradients) and the lane whose coordinates place them on a cube face.
// False when λ has no footprint (Explicit).
bool laneDerivatives(const SampleRequest& req, const float* const c[3], int lane, float dx[3],
                     float dy[3], int& footLane) {
  switch (req.lodMode) {
    case LodMode::Explicit:
      return false;
    case LodMode::Gradients:
      for (int i = 0; i < 3; ++i) {
        dx[i] = req.ddx[i] ? req.ddx[i][lane] : 0.0f;
        dy[i] = req.ddy[i] ? req.ddy[i][lane] : 0.0f;
      }
      footLane = lane;
      return true;
    case LodMode::Derivatives:
    case LodMode::Bias:
      break;
  }
  const int tl = lane & ~3, tr = tl + 1, bl = tl + 2;
  for (int i = 0; i < 3; ++i) {
    dx[i] = c[i][tr] - c[i][tl];
    dy[i] = c[i][bl] - c[i][tl];
  }
  footLane = tl;
  return true;
}

AnisoProbes anisoProbes(const Footprint& fp, const SamplerState& st, const SampleRequest& req,
                        const float* const c[3], int lane) {
  AnisoProbes p;
  float dx[3], dy[3];
  int footLane;
  if (!laneDerivatives(req, c, lane, dx, dy, footLane)) return p;
  float la, lb;
  fp.squaredLengths(c, footLane, dx, dy, la, lb);
  const float pmax2 = std::max(la, lb), pmin2 = std::min(la, lb);
  // No footprint to stretch: zero, infinite or NaN lengths filter as LINEAR.
  if (!(pmax2 > 0.0f) || !std::isfinite(pmax2) || !(pmin2 >= 0.0f)) return p;
  const uint32_t limit = anisotropyLimit(st);
  const float ratio = std::sqrt(pmax2 / pmin2);  // Pmax/Pmin; +inf when Pmin = 0
  p.count = ratio >= float(limit) ? int(limit) : int(std::ceil(ratio));
  const float* major = la >= lb ? dx : dy;
  for (int i = 0; i < 3; ++i) p.axis[i] = major[i];
  return p;
}

// λ' = λ - log2 N.
inline float anisoLambda(float lam, int count) {
  static const std::array<float, kMaxAnisotropy + 1> log2N = [] {
    std::array<float, kMaxAnisotropy + 1> t{};
    for (uint32_t n = 1; n <= kMaxAnisotropy; ++n) t[n] = std::log2(float(n));
    return t;
  }();
  return count == 1 ? lam : lam - log2N[size_t(count)];
}

// Offset of probe i of n along the axis, in axis lengths: the centre of the i-th of n
// equal parts of [-1/2, 1/2].
inline float probeOffset(int i, int n) { return (float(i) + 0.5f) / float(n) - 0.5f; }

// Coordinate k of probe i.
inline float probeCoord(const float* const c[3], const AnisoProbes& p, int k, int lane, int i) {
  if (p.count == 1) return c[k][lane];
  return c[k][lane] + probeOffset(i, p.count) * p.axis[k];
}

// The reference: lane by lane, probe by probe, with the scalar sampler.
void sampleAnisoReference(const Texture& tex, const SamplerState& st, const SampleRequest& req,
                          const float* const c[3], const float lam[kLanes], uint32_t lanes,
                          float out[4][kLanes]) {
  const Footprint fp(tex);
  const bool cube = tex.type() == TextureType::Cube;
  for (int l = 0; l < kLanes; ++l) {
    if (!(lanes >> l & 1)) continue;
    const AnisoProbes probes = anisoProbes(fp, st, req, c, l);
    LevelChoice levels{{0, 0}, 0.0f};
    if (st.mipFilter != TextureFilter::None)
      levels = chooseLevels(tex, st, anisoLambda(lam[l], probes.count));
    Color4 sum{0, 0, 0, 0};
    for (int i = 0; i < probes.count; ++i) {
      float p[3] = {probeCoord(c, probes, 0, l, i), probeCoord(c, probes, 1, l, i),
                    probeCoord(c, probes, 2, l, i)};
      int face = 0;
      TextureAddress addr[3] = {validAddress(st.addressU), validAddress(st.addressV),
                                validAddress(st.addressW)};
      if (cube) {
        const float d[3] = {p[0], p[1], p[2]};
        face = selectCubeFace(d[0], d[1], d[2]);
        faceCoords(face, d, p[0], p[1]);
        addr[0] = addr[1] = TextureAddress::Clamp;
      }
      const LevelReader first(tex.sampleLevel(face, levels.level[0]), st);
      Color4 s = sampleScalar(first, addr, true, false, p[0], p[1], p[2]);
      if (levels.frac > 0) {
        const LevelReader second(tex.sampleLevel(face, levels.level[1]), st);
        s = lerp(s, sampleScalar(second, addr, true, false, p[0], p[1], p[2]), levels.frac);
      }
      sum = {sum.r + s.r, sum.g + s.g, sum.b + s.b, sum.a + s.a};
    }
    const float n = float(probes.count);
    out[0][l] = sum.r / n, out[1][l] = sum.g / n, out[2][l] = sum.b / n, out[3][l] = sum.a / n;
  }
}

// The batched path: probe i of every lane at once through samplePass (the vectorised
// kernel where the level allows it). The same operations per lane as the reference.
void sampleAnisoBatched(const Texture& tex, const SamplerState& st, const SampleRequest& req,
                        const float* const c[3], const float lam[kLanes], uint32_t lanes,
                        float out[4][kLanes]) {
  const Footprint fp(tex);
  const bool cube = tex.type() == TextureType::Cube;
  const int dims = cube ? 3 : 2;  // a 2D probe's w is never read
  // Per lane, as rows: N (0 for lanes not sampled here) and the axis.
  int count[kLanes] = {};
  float axis[3][kLanes] = {};
  float lamA[kLanes];
  const bool perQuad = req.lodMode == LodMode::Derivatives || req.lodMode == LodMode::Bias;
  int maxCount = 1;
  for (int l = 0; l < kLanes; ++l) {
    if (!(lanes >> l & 1)) {
      lamA[l] = lam[l];
      continue;
    }
    // Quad derivatives: the probes depend on the quad alone, so its lanes share them.
    const int from = perQuad ? l & ~3 : l;
    if (from != l && (lanes >> from & 1)) {
      count[l] = count[from];
      for (int k = 0; k < 3; ++k) axis[k][l] = axis[k][from];
    } else {
      const AnisoProbes p = anisoProbes(fp, st, req, c, l);
      count[l] = p.count;
      for (int k = 0; k < 3; ++k) axis[k][l] = p.axis[k];
    }
    lamA[l] = anisoLambda(lam[l], count[l]);
    maxCount = std::max(maxCount, count[l]);
  }
  LanePlan plan;
  planLevels(tex, st, lamA, plan);
  for (int l = 0; l < kLanes; ++l) plan.linear[l] = 1;
  uint32_t blendLanes = 0;
  for (int l = 0; l < kLanes; ++l) blendLanes |= uint32_t(plan.mipFrac[l] > 0) << l;

  TextureAddress addr[3] = {validAddress(st.addressU), validAddress(st.addressV),
                            validAddress(st.addressW)};
  if (cube) addr[0] = addr[1] = TextureAddress::Clamp;
  float sum[4][kLanes] = {};
  for (int i = 0; i < maxCount; ++i) {
    uint32_t todo = 0;
    for (int l = 0; l < kLanes; ++l) todo |= uint32_t(count[l] > i) << l;
    // Probe i's coordinates: probeCoord's operations, lanes not sampled keep c.
    float p[3][kLanes];
    for (int l = 0; l < kLanes; ++l) {
      const int n = count[l] > 1 ? count[l] : 1;
      const float t = probeOffset(i, n);
      const bool moved = count[l] > 1 && count[l] > i;
      for (int k = 0; k < dims; ++k) p[k][l] = moved ? c[k][l] + t * axis[k][l] : c[k][l];
    }
    if (!cube) std::memcpy(p[2], c[2], sizeof p[2]);
    int face[kLanes] = {};
    if (cube)
      for (int l = 0; l < kLanes; ++l) {
        const float d[3] = {p[0][l], p[1][l], p[2][l]};
        face[l] = selectCubeFace(d[0], d[1], d[2]);
        faceCoords(face[l], d, p[0][l], p[1][l]);
      }
    float s[4][kLanes];
    samplePass(tex, st, plan, 0, todo, face, p[0], p[1], p[2], addr, true, s);
    const uint32_t blend = blendLanes & todo;
    if (blend) {
      float second[4][kLanes];
      samplePass(tex, st, plan, 1, blend, face, p[0], p[1], p[2], addr, true, second);
      for (int ch = 0; ch < 4; ++ch)
        for (int l = 0; l < kLanes; ++l)
          if (blend >> l & 1) s[ch][l] = s[ch][l] + plan.mipFrac[l] * (second[ch][l] - s[ch][l]);
    }
    for (int ch = 0; ch < 4; ++ch)
      for (int l = 0; l < kLanes; ++l)
        if (todo >> l & 1) sum[ch][l] += s[ch][l];
  }
  for (int ch = 0; ch < 4; ++ch)
    for (int l = 0; l < kLanes; ++l)
      if (lanes >> l & 1) out[ch][l] = sum[ch][l] / float(count[l]);
}

// What the one-level 2D path needs to know about a texture and sampler state
// (MIPFILTER NONE or POINT, λ from quad derivatives).
struct Fast2D {
  const Texture* tex;
  const SamplerState* st;
  TextureAddress addr[3];
  float size[3];  // level 0 width, height, 0
  int first, last, minLinear, magLinear;
  bool mipNone;
  const SampleLevel* const* levels = nullptr;  // per level, nullptr: not for the kernel
  Kernel2D kernels[2] = {};                    // POINT, LINEAR; null: select per call

  Fast2D(const Texture& t, const SamplerState& s, const TextureAddress a[3])
      : tex(&t), st(&s), addr{a[0], a[1], a[2]},
        size{float(t.width(0)), float(t.height(0)), 0.0f},
        minLinear(isLinear(s.minFilter)), magLinear(isLinear(s.magFilter)),
        mipNone(s.mipFilter == TextureFilter::None) {
    last = t.levelCount() - 1;
    first = int(std::min<uint32_t>(s.maxMipLevel, uint32_t(last)));
  }
};

// A batch whose quads chose different levels or filters (keys: (level << 1) | linear per
// quad): one kernel call per key, each lane taken from its quad's. Lanes are independent
// in the kernel, so this is what samplePass gives. False (nothing written) when a level
// is not for the kernel.
[[gnu::noinline]] bool sample2DMixed(const Fast2D& f, const float* const c[3], uint32_t mask,
                                     const int keys[4], float out[4][kLanes]) {
  const SampleLevel* lv[4];
  for (int q = 0; q < 4; ++q) {
    lv[q] = f.levels ? f.levels[keys[q] >> 1] : &f.tex->sampleLevel(0, keys[q] >> 1);
    if (!lv[q] || (!f.levels && !fastLevel(*lv[q], *f.st, f.addr))) return false;
  }
  uint32_t done = 0;  // quads sampled
  for (int q = 0; q < 4; ++q) {
    if (done >> q & 1) continue;
    uint32_t lanes = 0;
    for (int r = q; r < 4; ++r)
      if (keys[r] == keys[q]) done |= 1u << r, lanes |= 0xfu << (4 * r);
    const Kernel2D kernel = f.kernels[keys[q] & 1];
    float tmp[4][kLanes];
    (kernel ? kernel : selectKernel2D(f.addr[0], f.addr[1], keys[q] & 1))(*lv[q], c[0], c[1], tmp);
    for (int ch = 0; ch < 4; ++ch)
      for (int l = 0; l < kLanes; ++l)
        if (lanes >> l & 1) out[ch][l] = tmp[ch][l];
  }
  if (mask != 0xffff) clearLanes(out, mask);
  return true;
}

// λ per quad and the level it selects, with the operations of computeLambda and
// planLevels for a 2D texture (MIPFILTER NONE or POINT); samples the batch with one
// kernel call when all four quads agree, one per level and filter otherwise. Returns
// false to leave it to the general path.
[[gnu::always_inline]] inline bool sample2DUniform(const Fast2D& f, const float* const c[3],
                                                  uint32_t mask, float out[4][kLanes]) {
  const SamplerState& st = *f.st;
  const int magLinear = f.magLinear, minLinear = f.minLinear;
  const bool mipNone = f.mipNone;
  const int last = f.last, first = f.first;
  const float* size = f.size;
  // ρ² of the four quads at once, with the same operations in the same order as
  // Footprint::lod. Quad q's lanes tl, tr, bl, br are one 128-bit half of a v8f, so
  // subtracting the half's first lane gives tr - tl and bl - tl in its lanes 1 and 2.
  typedef float v4f __attribute__((vector_size(16)));
  v8f sq[2];
  for (int h = 0; h < 2; ++h) {
    for (int i = 0; i < 2; ++i) {  // 2D: u and v (see Footprint::lod)
      v8f x;
      std::memcpy(&x, c[i] + 8 * h, sizeof x);
      const v8f d = (x - __builtin_shufflevector(x, x, 0, 0, 0, 0, 4, 4, 4, 4)) * size[i];
      sq[h] = i == 0 ? d * d : sq[h] + d * d;
    }
  }
  const v4f la = __builtin_shufflevector(sq[0], sq[1], 1, 5, 9, 13);  // a² of quads 0..3
  const v4f lb = __builtin_shufflevector(sq[0], sq[1], 2, 6, 10, 14);  // b²
  const v4f ms = la < lb ? lb : la;  // std::max(la, lb)
  int key = -1;
  int keys[4];  // per quad
  bool classified = false, mixed = false;
  // All four quads at once when every ρ² has the exponent form (see below).
  typedef uint32_t v4u __attribute__((vector_size(16)));
  typedef int32_t v4i __attribute__((vector_size(16)));
  v4u mbits;
  std::memcpy(&mbits, &ms, sizeof mbits);
  // Every lane true (all bits set)?
  const auto all4 = [](v4i t) {
#if defined(__AVX__)
    __m128 m;
    std::memcpy(&m, &t, sizeof m);
    return _mm_movemask_ps(m) == 0xf;
#else
    return t[0] && t[1] && t[2] && t[3];
#endif
  };
  // Normal, positive and finite (bits in [2^23, 0x7f800000) as signed ints), mantissa
  // in [0x1000, 0x7ff000): signed compares only.
  const v4i sbits = v4i(mbits), smant = sbits & 0x7fffff;
  const v4i form = (sbits >= 0x00800000) & (sbits < 0x7f800000) & (smant >= 0x1000) &
                   (smant < 0x7ff000);
  if (st.mipLodBias == 0.0f && all4(form)) {
    const v4i e = v4i(mbits >> 23) - 127;
    const v4i linear = e >= 0 ? v4i{} + minLinear : v4i{} + magLinear;
    v4i level = (e + 1) >> 1;
    level = level < first ? v4i{} + first : level;
    level = level > last ? v4i{} + last : level;
    if (mipNone) level = v4i{};
    const v4i k = (level << 1) | linear;
    if (!all4(k == __builtin_shufflevector(k, k, 0, 0, 0, 0))) {
      for (int q = 0; q < 4; ++q) keys[q] = k[q];
      return sample2DMixed(f, c, mask, keys, out);
    }
    key = k[0];
    classified = true;
  }
  for (int q = 0; q < kLanes / 4 && !classified; ++q) {
    const float m = ms[q];
    int linear, level;
    uint32_t bits;
    std::memcpy(&bits, &m, sizeof bits);
    const uint32_t mant = bits & 0x7fffff;
    if (st.mipLodBias == 0.0f && bits - 0x00800000u < 0x7f000000u && mant >= 0x1000 &&
        mant < 0x7ff000) {
      // m = 2^e * (1 + f), f not within 2^-11 of 0 or 1: log2 m lies inside (e, e+1)
      // by far more than log2f's error, so λ = log2(m)/2 is inside (e/2, (e+1)/2),
      // λ > 0 iff e >= 0, and the nearest level is floor((e+1)/2), clamped.
      const int e = int(bits >> 23) - 127;
      linear = e >= 0 ? minLinear : magLinear;
      level = mipNone ? 0 : std::clamp((e + 1) >> 1, first, last);
    } else {
      const float lam = 0.5f * std::log2(m) + st.mipLodBias;
      linear = lam > 0 ? minLinear : magLinear;
      level = mipNone ? 0 : int(std::floor(clampFinite(lam, float(first), float(last)) + 0.5f));
    }
    const int k = (level << 1) | linear;
    mixed |= key >= 0 && k != key;
    key = keys[q] = k;
  }
  if (mixed) return sample2DMixed(f, c, mask, keys, out);
  const SampleLevel* lv =
      f.levels ? levelByCount(f.levels, key >> 1) : &f.tex->sampleLevel(0, key >> 1);
  if (!lv || (!f.levels && !fastLevel(*lv, st, f.addr))) return false;
  const Kernel2D kernel = f.kernels[key & 1];
  (kernel ? kernel : selectKernel2D(f.addr[0], f.addr[1], key & 1))(*lv, c[0], c[1], out);
  if (mask != 0xffff) clearLanes(out, mask);
  return true;
}

void sampleImpl(const Texture& tex, const SamplerState& st, const SampleRequest& req,
                float out[4][kLanes], bool allowFast) {
  const float* c[3] = {req.u ? req.u : kZeros, req.v ? req.v : kZeros, req.w ? req.w : kZeros};
  const TextureType type = tex.type();
  TextureAddress addr[3] = {validAddress(st.addressU), validAddress(st.addressV),
                            validAddress(st.addressW)};

  // ANISOTROPIC probes the footprint; the vectorised paths leave MAXANISOTROPY 1 to
  // LINEAR, which it equals (the reference takes the anisotropic path to show that).
  const bool aniso = anisotropicFootprint(tex, st) && (!allowFast || anisotropyLimit(st) > 1);
  // λ only matters when it picks a level or chooses between MAGFILTER and MINFILTER.
  const bool needLambda = aniso || st.mipFilter != TextureFilter::None ||
                          isLinear(st.magFilter) != isLinear(st.minFilter);
  uint32_t mask = req.laneMask;

  // Common case: one 2D level, one filter for every lane.
  if (!needLambda && type == TextureType::Texture2D && allowFast) {
    const SampleLevel& lv = tex.sampleLevel(0, 0);
    if (fastLevel(lv, st, addr)) {
      kernel2D(lv, addr[0], addr[1], isLinear(st.magFilter), c[0], c[1], out);
      if (mask != 0xffff) clearLanes(out, mask);
      return;
    }
  }

  // Common case with mip levels: a 2D texture, λ from quad derivatives, no mip
  // blending, and one level and filter for the whole batch.
  if (needLambda && !aniso && type == TextureType::Texture2D && allowFast &&
      req.lodMode == LodMode::Derivatives && st.mipFilter != TextureFilter::Linear &&
      sample2DUniform(Fast2D(tex, st, addr), c, mask, out))
    return;

  float lam[kLanes] = {};
  if (needLambda) computeLambda(tex, st, req, c, lam);

  // Lanes whose filter (MINFILTER for λ > 0, else MAGFILTER) is ANISOTROPIC, sampled
  // into their own rows; the rest go on below.
  uint32_t anisoLanes = 0;
  float anisoOut[4][kLanes];
  if (aniso) {
    for (int l = 0; l < kLanes; ++l)
      anisoLanes |= uint32_t((lam[l] > 0 ? st.minFilter : st.magFilter) ==
                             TextureFilter::Anisotropic) << l;
    anisoLanes &= mask;
    if (anisoLanes) {
      (allowFast ? sampleAnisoBatched : sampleAnisoReference)(tex, st, req, c, lam, anisoLanes,
                                                              anisoOut);
      mask &= ~anisoLanes;
      if (!mask) {  // every lane anisotropic
        for (int ch = 0; ch < 4; ++ch) std::memcpy(out[ch], anisoOut[ch], sizeof out[ch]);
        if (req.laneMask != 0xffff) clearLanes(out, req.laneMask);
        return;
      }
    }
  }

  LanePlan plan;
  planLevels(tex, st, lam, plan);

  // 2D coordinates (on each lane's cube face for cube maps).
  int face[kLanes] = {};
  float faceU[kLanes], faceV[kLanes];
  const float* cu = c[0];
  const float* cv = c[1];
  if (type == TextureType::Cube) {
    for (int l = 0; l < kLanes; ++l) {
      const float d[3] = {c[0][l], c[1][l], c[2][l]};
      face[l] = selectCubeFace(d[0], d[1], d[2]);
      faceCoords(face[l], d, faceU[l], faceV[l]);
    }
    cu = faceU, cv = faceV;
    // Filtering clamps within the face (no seamless filtering across edges).
    addr[0] = addr[1] = TextureAddress::Clamp;
  }

  samplePass(tex, st, plan, 0, mask, face, cu, cv, c[2], addr, allowFast, out);

  // MIPFILTER LINEAR: blend level[1] in by frac(λ).
  uint32_t blend = 0;
  for (int l = 0; l < kLanes; ++l) blend |= uint32_t(plan.mipFrac[l] > 0) << l;
  blend &= mask;
  if (blend) {
    float second[4][kLanes] = {};
    samplePass(tex, st, plan, 1, blend, face, cu, cv, c[2], addr, allowFast, second);
    for (int ch = 0; ch < 4; ++ch)
      for (int l = 0; l < kLanes; ++l) {
        float r0 = out[ch][l], f = plan.mipFrac[l];
        out[ch][l] = blend >> l & 1 ? r0 + f * (second[ch][l] - r0) : r0;
      }
  }

  for (int ch = 0; ch < 4; ++ch)
    for (int l = 0; l < kLanes; ++l)
      if (anisoLanes >> l & 1) out[ch][l] = anisoOut[ch][l];
  if (req.laneMask != 0xffff) clearLanes(out, req.laneMask);
}

}  // namespace

float resource::srgbToLinear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

int cubeFaceCoords(float x, float y, float z, float& u, float& v) {
  const float d[3] = {x, y, z};
  int face = selectCubeFace(x, y, z);
  faceCoords(face, d, u, v);
  return face;
}

void sampleTexture(const Texture& tex, const SamplerState& state, const SampleRequest& req,
                   float out[4][kBatchLanes]) {
  sampleImpl(tex, state, req, out, true);
}

namespace {

// PreparedSampler's plan: the 2D fast paths of sampleImpl with their per-call checks
// done once.
struct PreparedPlan {
  SamplerState st;
  std::vector<const SampleLevel*> levels;  // nullptr: level not for the kernel
  Fast2D fast;
  bool needLambda;
  Kernel2D single = nullptr;  // no λ needed: kernel for level 0 (levels[0] set)
  // sample2DUniform's common case in one step where the instruction set has it, and
  // with sampleImplicit's other paths behind it (context: uniformPlan).
  resource::Uniform2D uniform = nullptr;
  resource::Implicit2D implicit = nullptr;
  resource::ImplicitPair2D implicitPair = nullptr;  // two `implicit` calls in one
  resource::ImplicitGroup2D implicitGroup = nullptr;  // `implicit` for a group of batches
  resource::ImplicitPairGroup2D implicitPairGroup = nullptr;
  resource::UniformColorsGroup2D uniformColorsGroup = nullptr;
  resource::UniformColors2D uniformColors = nullptr;  // `uniform` as 8-bit unorm D3DCOLORs
  resource::UniformPlan uniformPlan{};

  PreparedPlan(const Texture& tex, const SamplerState& state, const TextureAddress addr[3])
      : st(state), fast(tex, st, addr) {
    fast.st = &st;
    for (int l = 0; l < tex.levelCount(); ++l) {
      const SampleLevel& lv = tex.sampleLevel(0, l);
      levels.push_back(fastLevel(lv, st, addr) ? &lv : nullptr);
    }
    fast.levels = levels.data();
    fast.kernels[0] = selectKernel2D(addr[0], addr[1], false);
    fast.kernels[1] = selectKernel2D(addr[0], addr[1], true);
    needLambda =
        st.mipFilter != TextureFilter::None || isLinear(st.magFilter) != isLinear(st.minFilter);
    if (!needLambda && levels[0]) single = fast.kernels[isLinear(st.magFilter)];
    if (needLambda && st.mipFilter != TextureFilter::Linear && st.mipLodBias == 0.0f &&
        activeIsa() == CpuIsa::Avx512) {
      uniform = resource::selectUniform2DAvx512(addr[0], addr[1]);
      implicit = resource::selectImplicit2DAvx512(addr[0], addr[1]);
      implicitPair = resource::selectImplicitPair2DAvx512(addr[0], addr[1]);
      implicitGroup = resource::selectImplicitGroup2DAvx512(addr[0], addr[1]);
      implicitPairGroup = resource::selectImplicitPairGroup2DAvx512(addr[0], addr[1]);
      uniformColorsGroup = resource::selectUniformColorsGroup2DAvx512(addr[0], addr[1]);
      uniformColors = resource::selectUniformColors2DAvx512(addr[0], addr[1]);
      uniformPlan = {{fast.size[0], fast.size[1]}, fast.first, fast.last, fast.minLinear,
                     fast.magLinear, fast.mipNone, levels.data(), sampleImplicitRest, this};
    }
  }

  // sampleImplicit past the batch kernel (tried and declined, or not there): out of
  // line, so that the common call does not set up this path's frame.
  [[gnu::noinline]] static void sampleImplicitRest(const void* plan, const float* u,
                                                   const float* v, const float* w,
                                                   uint16_t laneMask, float (*out)[kBatchLanes]);
};

}  // namespace

PreparedSampler::PreparedSampler(const Texture& tex, const SamplerState& state)
    : tex_(&tex), state_(state) {
  const TextureAddress addr[3] = {validAddress(state.addressU), validAddress(state.addressV),
                                  validAddress(state.addressW)};
  // ANISOTROPIC (beyond MAXANISOTROPY 1) goes through sampleImpl every time.
  const bool aniso = anisotropicFootprint(tex, state) && anisotropyLimit(state) > 1;
  if (tex.type() == TextureType::Texture2D && tex.levelCount() > 0 && !aniso) {
    auto plan = std::make_shared<const PreparedPlan>(tex, state, addr);
    implicit_ = plan->implicit ? ImplicitKernel{plan->implicit, &plan->uniformPlan}
                               : ImplicitKernel{PreparedPlan::sampleImplicitRest, plan.get()};
    pair_ = plan->implicitPair;
    group_ = plan->implicitGroup;
    pairGroup_ = plan->implicitPairGroup;
    plan_ = std::move(plan);
  }
}

namespace {

// The prepared plan's fast paths, with sampleImpl's choices in the same order: true when
// one of them sampled the request.
[[gnu::always_inline]] inline bool samplePrepared(const PreparedPlan* p, const float* u,
                                                  const float* v, const float* w,
                                                  bool derivatives, uint16_t laneMask,
                                                  float out[4][kBatchLanes],
                                                  bool tryUniform = true) {
  if (!p) return false;
  const float* c[3] = {u ? u : kZeros, v ? v : kZeros, w ? w : kZeros};
  if (p->single) {
    p->single(*p->levels[0], c[0], c[1], out);
    if (laneMask != 0xffff) clearLanes(out, laneMask);
    return true;
  }
  if (!p->needLambda || !derivatives || p->st.mipFilter == TextureFilter::Linear) return false;
  return (tryUniform && p->uniform && p->uniform(p->uniformPlan, c[0], c[1], laneMask, out)) ||
         sample2DUniform(p->fast, c, laneMask, out);
}

}  // namespace

void PreparedPlan::sampleImplicitRest(const void* plan, const float* u, const float* v,
                                      const float* w, uint16_t laneMask,
                                      float (*out)[kBatchLanes]) {
  const auto* p = static_cast<const PreparedPlan*>(plan);
  if (samplePrepared(p, u, v, w, true, laneMask, out, false)) return;
  SampleRequest req;
  req.u = u, req.v = v, req.w = w;
  req.laneMask = laneMask;
  sampleImpl(*p->fast.tex, p->st, req, out, true);
}

void PreparedSampler::sample(const SampleRequest& req, float out[4][kBatchLanes]) const {
  if (!samplePrepared(static_cast<const PreparedPlan*>(plan_.get()), req.u, req.v, req.w,
                      req.lodMode == LodMode::Derivatives, req.laneMask, out))
    sampleImpl(*tex_, state_, req, out, true);
}

void PreparedSampler::sampleImplicit(const float* u, const float* v, const float* w,
                                     uint16_t laneMask, float out[4][kBatchLanes]) const {
  // samplePrepared's order: a plan with the batch kernel has no `single` and takes λ
  // from derivatives without mip blending, so the kernel comes first.
  if (implicit_.fn) {
    implicit_.fn(implicit_.context, u ? u : kZeros, v ? v : kZeros, w, laneMask, out);
    return;
  }
  SampleRequest req;
  req.u = u, req.v = v, req.w = w;
  req.laneMask = laneMask;
  sampleImpl(*tex_, state_, req, out, true);
}

bool PreparedSampler::sampleImplicitArgb8(const float* u, const float* v, uint16_t laneMask,
                                          uint32_t out[kBatchLanes]) const {
  const auto* p = static_cast<const PreparedPlan*>(plan_.get());
  return p && p->uniformColors && p->uniformColors(p->uniformPlan, u ? u : kZeros, v ? v : kZeros, laneMask, out);
}

void PreparedSampler::sampleImplicitGroup(int count, const uint16_t* laneMasks, const SampleBatch* batches,
                                          ProvenRho proven) const {
  if (group_) {
    group_(implicit_.context, count, laneMasks, batches, proven);
    return;
  }
  for (int g = 0; g < count; ++g)
    sampleImplicit(batches[g].coords[0], batches[g].coords[1], batches[g].coords[2], laneMasks[g], batches[g].out);
}

void PreparedSampler::sampleImplicitPairGroup(const PreparedSampler& a, const PreparedSampler& b, int count,
                                              const uint16_t* laneMasks, const SampleBatch* batchesA,
                                              const SampleBatch* batchesB, ProvenRho proven) {
  if (a.pairGroup_ && a.pairGroup_ == b.pairGroup_) {
    a.pairGroup_(a.implicit_.context, b.implicit_.context, count, laneMasks, batchesA, batchesB, proven);
    return;
  }
  a.sampleImplicitGroup(count, laneMasks, batchesA);
  b.sampleImplicitGroup(count, laneMasks, batchesB);
}

uint32_t PreparedSampler::sampleImplicitArgb8Group(int count, const float* const* u, const float* const* v,
                                                   const uint16_t* laneMasks, uint32_t* const* out,
                                                   ProvenRho proven) const {
  const auto* p = static_cast<const PreparedPlan*>(plan_.get());
  if (p && p->uniformColorsGroup)
    return p->uniformColorsGroup(p->uniformPlan, count, u, v, laneMasks, out, proven);
  uint32_t done = 0;
  for (int g = 0; g < count; ++g)
    if (sampleImplicitArgb8(u[g], v[g], laneMasks[g], out[g])) done |= 1u << g;
  return done;
}

bool PreparedSampler::levelZeroSize(float& width, float& height) const {
  const auto* p = static_cast<const PreparedPlan*>(plan_.get());
  if (!p || !p->implicitGroup) return false;  // the group lookups are the AVX-512 ones
  width = p->uniformPlan.size[0];
  height = p->uniformPlan.size[1];
  return true;
}

Kernel2D resource::selectKernel2D(TextureAddress au, TextureAddress av, bool linear, CpuIsa isa) {
  return isa == CpuIsa::Avx512 ? selectKernel2DAvx512(au, av, linear)
                               : selectKernel2DAvx2(au, av, linear);
}

void resource::sampleTextureReference(const Texture& tex, const SamplerState& state,
                            const SampleRequest& req, float out[4][kBatchLanes]) {
  sampleImpl(tex, state, req, out, false);
}

}  // namespace refx
