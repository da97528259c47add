// The vectorised 2D kernels (one level of packed rgba8 texels, all 16 lanes) and what
// their instruction-set variants share: sampler.cpp holds the AVX2 variant (8 lanes at
// a time), sampler_avx512.cpp the AVX-512 one (16 lanes at a time), compiled with its
// own flags. Both perform the same IEEE operations lane by lane, so they agree bit for
// bit (tests/resource/test_sampler_isa.cpp runs both).
#pragma once
#include "refx/core/batch.h"
#include "refx/core/cpu_features.h"
#include "refx/resource/sampler.h"
#include "refx/resource/texture.h"

namespace refx::resource {

// Filters one level for the 16 lanes' coordinates (u, v): POINT or LINEAR, the
// addressing pair fixed by the variant chosen.
using Kernel2D = void (*)(const SampleLevel&, const float*, const float*,
                          float[4][kBatchLanes]);

// The kernel for an addressing pair (BORDER excluded) and filter, in the variant of
// `isa` (which the CPU must support).
Kernel2D selectKernel2D(TextureAddress au, TextureAddress av, bool linear, CpuIsa isa);
Kernel2D selectKernel2DAvx512(TextureAddress au, TextureAddress av, bool linear);

// sample2DUniform of sampler.cpp for a prepared 2D texture (MIPFILTER NONE or POINT, λ
// from quad derivatives, no LOD bias): what it needs of the texture and sampler state.
struct UniformPlan {
  float size[2];                    // level 0 width, height
  int first, last;                  // MAXMIPLEVEL clamped, last level
  int minLinear, magLinear;         // 1: LINEAR
  bool mipNone;                     // MIPFILTER NONE: level 0
  const SampleLevel* const* levels;  // per level, nullptr: not for the kernels
  // What PreparedSampler::sampleImplicit does past the kernel, given `owner`.
  void (*rest)(const void* owner, const float* u, const float* v, const float* w,
               uint16_t laneMask, float (*out)[kBatchLanes]);
  const void* owner;
};

// Samples the batch when every quad's ρ² has the form that gives its level and filter
// without a logarithm and all four quads agree on them, with the kernel of that level
// and filter; lanes outside `mask` read 0. False: nothing written, the caller decides.
using Uniform2D = bool (*)(const UniformPlan&, const float* u, const float* v, uint32_t mask,
                           float out[4][kBatchLanes]);
Uniform2D selectUniform2DAvx512(TextureAddress au, TextureAddress av);
// Uniform2D with the 8-bit unorms of the result as D3DCOLORs (a << 24 | r << 16 |
// g << 8 | b), what PreparedSampler::sampleImplicitArgb8 gives; lanes outside `mask`
// read 0. False: nothing written.
using UniformColors2D = bool (*)(const UniformPlan&, const float* u, const float* v, uint32_t mask,
                                 uint32_t out[kBatchLanes]);
UniformColors2D selectUniformColors2DAvx512(TextureAddress au, TextureAddress av);

// The Uniform2D kernel, and plan.rest(plan.owner, ...) where it declines: the whole of
// sampleImplicit for a prepared plan (PreparedSampler::ImplicitKernel, context: the plan).
using Implicit2D = void (*)(const void* plan, const float* u, const float* v, const float* w,
                            uint16_t laneMask, float (*out)[kBatchLanes]);
Implicit2D selectImplicit2DAvx512(TextureAddress au, TextureAddress av);
// Two Implicit2D calls of the same variant in one (PreparedSampler::ImplicitPairFn).
using ImplicitPair2D = PreparedSampler::ImplicitPairFn;
ImplicitPair2D selectImplicitPair2DAvx512(TextureAddress au, TextureAddress av);
// Implicit2D and ImplicitPair2D for a group of batches (PreparedSampler::ImplicitGroupFn,
// ImplicitPairGroupFn).
using ImplicitGroup2D = PreparedSampler::ImplicitGroupFn;
ImplicitGroup2D selectImplicitGroup2DAvx512(TextureAddress au, TextureAddress av);
using ImplicitPairGroup2D = PreparedSampler::ImplicitPairGroupFn;
ImplicitPairGroup2D selectImplicitPairGroup2DAvx512(TextureAddress au, TextureAddress av);
// UniformColors2D for `count` batches (at most kMaxSampleGroup): batch g at (u[g], v[g])
// into out[g]. Returns the batches written (bit g), what count UniformColors2D calls give.
using UniformColorsGroup2D = uint32_t (*)(const UniformPlan&, int count, const float* const* u,
                                          const float* const* v, const uint16_t* laneMasks, uint32_t* const* out,
                                          ProvenRho proven);
UniformColorsGroup2D selectUniformColorsGroup2DAvx512(TextureAddress au, TextureAddress av);

namespace kernels {

// Sub-texel precision of filter weights (see the top of sampler.cpp).
constexpr int kWeightBits = 8;
constexpr float kWeightScale = float(1 << kWeightBits);
constexpr float kWeightUnit = 1.0f / kWeightScale;

// Coordinates are limited to +-2^22 first (NaN goes to the low end): beyond that a
// float has no fraction left, and it keeps every later step in int range.
constexpr float kCoordLimit = 4194304.0f;

// x / 65280 and b / 255 without a division: the reciprocal as an unevaluated sum of two
// floats, hi + lo, and fma(x, hi, x·lo), which is the correctly rounded quotient for
// every value the kernels divide (x = S/256, S in [0, 255·65536]; b in 0..255):
// tests/resource/test_filter_quotient.cpp checks all of them.
constexpr float kInv65280Hi = float(1.0 / 65280.0);
constexpr float kInv65280Lo = float(1.0 / 65280.0 - double(kInv65280Hi));
constexpr float kInv255Hi = float(1.0 / 255.0);
constexpr float kInv255Lo = float(1.0 / 255.0 - double(kInv255Hi));

// Texel-space positions are clamped to [lo, hi] before conversion to int. It never
// changes the texels of a finite coordinate and keeps indices small. (static: each
// variant's translation unit has its own copy, compiled with its own flags.)
static inline void positionRange(TextureAddress a, int n, float& lo, float& hi) {
  if (a == TextureAddress::Wrap) {
    lo = -1.0f, hi = float(n);
  } else if (a == TextureAddress::Mirror) {
    lo = -1.0f, hi = float(2 * n);
  } else {
    lo = -float(n + 2), hi = float(n + 2);
  }
}

// levels[index] (index >= 0), reached by counting up to it rather than by indexing: the
// level's size and texels then depend on predicted branches (a draw's batches mostly
// share a level), not on the LOD classification that computed `index`, so a kernel's
// long dependency chain starts on the coordinates while the classification is still
// being computed.
static inline const SampleLevel* levelByCount(const SampleLevel* const* levels, int index) {
  int counted = 0;
  while (counted != index) {
    ++counted;
    asm("" : "+r"(counted));  // a count the compiler cannot replace by index
  }
  asm("" : "+r"(counted));
  return levels[counted];
}

}  // namespace kernels
}  // namespace refx::resource
