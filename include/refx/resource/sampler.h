// Texture sampling over SoA batches: addressing, point/linear/anisotropic
// filtering, mip selection from quad derivatives, cube face selection, border, sRGB.
#pragma once
#include <cstdint>
#include <memory>

#include "refx/core/batch.h"
#include "refx/core/color.h"
#include "refx/resource/texture.h"

namespace refx {

// D3DTEXTUREADDRESS
enum class TextureAddress : uint32_t { Wrap = 1, Mirror = 2, Clamp = 3, Border = 4, MirrorOnce = 5 };
// D3DTEXTUREFILTERTYPE
enum class TextureFilter : uint32_t { None = 0, Point = 1, Linear = 2, Anisotropic = 3 };

// The D3DSAMP_* states that affect sampling, decoded.
struct SamplerState {
  TextureAddress addressU = TextureAddress::Wrap, addressV = TextureAddress::Wrap,
                 addressW = TextureAddress::Wrap;
  Color4 borderColor{0, 0, 0, 0};
  TextureFilter magFilter = TextureFilter::Point, minFilter = TextureFilter::Point,
                mipFilter = TextureFilter::None;
  float mipLodBias = 0;
  uint32_t maxMipLevel = 0;
  uint32_t maxAnisotropy = 1;
  bool srgb = false;
};

// Cube maps: direction derivatives are projected on the face of the quad's top-left
// lane (per lane for Gradients), d(u,v) = chain rule of u = (sc/|ma| + 1)/2.
enum class LodMode {
  Derivatives,  // λ from the 2x2 quad's coordinate differences (+ bias); pixel shaders
  Bias,         // derivatives + per-lane bias in `lod` (texldb)
  Explicit,     // λ = lod[lane] (texldl, vertex texture fetch)
  Gradients,    // λ from ddx/ddy given per lane (texldd)
};

struct SampleRequest {
  // Coordinates per lane; w is used by volume and cube textures (cube: direction xyz).
  const float* u = nullptr;
  const float* v = nullptr;
  const float* w = nullptr;
  LodMode lodMode = LodMode::Derivatives;
  const float* lod = nullptr;        // Bias / Explicit
  const float* ddx[3] = {};          // Gradients: d(u,v,w)/dx per lane
  const float* ddy[3] = {};
  uint16_t laneMask = 0xffff;        // lanes whose result is needed (others may be skipped)
};

// out[channel][lane] = sampled (r,g,b,a) as the shader sees it. LINEAR filtering and
// the MIPFILTER LINEAR blend weigh with 8 bits of sub-texel precision (positions and λ
// rounded to 1/256). 8-bit unorm texels: POINT gives byte/255 exactly, bilinear gives
// S/(255·65536) rounded once, S = sum of texel·wx·wy with weights in 1/256 units.
void sampleTexture(const Texture& tex, const SamplerState& state, const SampleRequest& req,
                   float out[4][kBatchLanes]);

// One batch of a group lookup (PreparedSampler::sampleImplicitGroup): its coordinate
// rows u, v, w and where its result goes.
struct SampleBatch {
  const float (*coords)[kBatchLanes];
  float (*out)[kBatchLanes];
  uint8_t channels = 0xF;  // the components of `out` wanted (bit c: component c); others may be left as they are
};
// Four: the group's registers and footprints stay in the L1 cache with the texels.
constexpr int kMaxSampleGroup = 4;
// What a caller has proven of every quad's ρ² in a group's lookups (ρ² as the texture's
// level-0 size, levelZeroSize(), scales it): 2^low <= ρ² < 2^(high + 1); lowNearEdge:
// ρ² may lie within 2^-11 (relative) above 2^low, highNearEdge: within 2^-11 below
// 2^(high + 1), where the exponent alone does not tell the level and filter. Where the
// range allows one level and filter only, the lookups use them for every quad instead
// of classifying each batch's quads. low == kUnprovenExponent: nothing is proven.
constexpr int kUnprovenExponent = -1000;
struct ProvenRho {
  int low = kUnprovenExponent, high = kUnprovenExponent;
  bool lowNearEdge = false, highNearEdge = false;
};

// A texture and sampler state prepared for many requests (one draw): the checks
// sampleTexture makes per call (addressing, filters, which levels the vectorised
// kernels can read and with which kernel) made once. sample() gives exactly what
// sampleTexture gives. The texture must outlive it and not change meanwhile.
class PreparedSampler {
 public:
  PreparedSampler(const Texture& tex, const SamplerState& state);
  void sample(const SampleRequest& req, float out[4][kBatchLanes]) const;
  // The common request on its own (λ from quad derivatives, coordinate rows u, v, w):
  // what sample() gives for it, without building a SampleRequest.
  void sampleImplicit(const float* u, const float* v, const float* w, uint16_t laneMask,
                      float out[4][kBatchLanes]) const;
  // sampleImplicit of a 2D texture at (u, v) as 8-bit unorm D3DCOLORs: out[lane] =
  // unorm8(a) << 24 | unorm8(r) << 16 | unorm8(g) << 8 | unorm8(b) of its result (lanes
  // outside laneMask: unspecified), formed from the filter's integer sums where the
  // batch kernel serves the request (same bytes, see sampler.cpp). False: nothing
  // written (no such kernel for this texture, state or batch).
  bool sampleImplicitArgb8(const float* u, const float* v, uint16_t laneMask, uint32_t out[kBatchLanes]) const;

  // sampleImplicit as one function and its context, where the texture and state have
  // the one-level 2D paths (fn null otherwise: ANISOTROPIC, cube and volume textures):
  // fn(context, u, v, w, laneMask, out), u and v not null, gives what sampleImplicit
  // gives. Callers that sample through a function pointer reach the batch kernel (the
  // AVX-512 one where the state allows it) with no call in between. The context is
  // shared by copies of this PreparedSampler and lives as long as the last of them.
  struct ImplicitKernel {
    void (*fn)(const void* context, const float* u, const float* v, const float* w,
               uint16_t laneMask, float (*out)[kBatchLanes]) = nullptr;
    const void* context = nullptr;
  };
  const ImplicitKernel& implicitKernel() const { return implicit_; }
  // The implicit lookups of two samplers in one call: for two PreparedSamplers with the
  // same non-null implicitPair(), pair(a.implicitKernel().context,
  // b.implicitKernel().context, coordsA, coordsB, laneMask, outA, outB) gives what their
  // two implicitKernel() calls give (coords: the rows u, v, w). Where both read the same
  // coordinates and their textures have one size, the texel addresses and weights are
  // computed once and the fetches of both overlap.
  using ImplicitPairFn = void (*)(const void* a, const void* b, const float (*coordsA)[kBatchLanes],
                                  const float (*coordsB)[kBatchLanes], uint16_t laneMask,
                                  float (*outA)[kBatchLanes], float (*outB)[kBatchLanes]);
  ImplicitPairFn implicitPair() const { return pair_; }
  // Implicit lookups of a group of batches (at most kMaxSampleGroup) in one call: what
  // implicitKernel() gives for each batch g (coordinate rows batches[g].coords, lanes
  // laneMasks[g], result into batches[g].out). The batches' work is interleaved phase
  // by phase so that their long dependency chains overlap.
  using ImplicitGroupFn = void (*)(const void* context, int count, const uint16_t* laneMasks,
                                   const SampleBatch* batches, ProvenRho proven);
  void sampleImplicitGroup(int count, const uint16_t* laneMasks, const SampleBatch* batches,
                           ProvenRho proven = {}) const;
  // The group lookups of two samplers (batchesA of this one, batchesB of `b`): what
  // implicitPair() gives for each batch, where both have the same implicitPairGroup().
  using ImplicitPairGroupFn = void (*)(const void* a, const void* b, int count, const uint16_t* laneMasks,
                                       const SampleBatch* batchesA, const SampleBatch* batchesB,
                                       ProvenRho proven);
  // proven: of the quads' ρ² at batchesA's coordinates with a's levelZeroSize().
  static void sampleImplicitPairGroup(const PreparedSampler& a, const PreparedSampler& b, int count,
                                      const uint16_t* laneMasks, const SampleBatch* batchesA,
                                      const SampleBatch* batchesB, ProvenRho proven = {});
  // sampleImplicitArgb8 for a group of batches: batch g at (u[g], v[g]) into out[g].
  // Returns the batches written (bit g), as count sampleImplicitArgb8 calls would.
  uint32_t sampleImplicitArgb8Group(int count, const float* const* u, const float* const* v,
                                    const uint16_t* laneMasks, uint32_t* const* out,
                                    ProvenRho proven = {}) const;
  // The level-0 size the group lookups measure ρ² with (ProvenRho), where they take a
  // proven range; false: they never do (a ProvenRho is ignored).
  bool levelZeroSize(float& width, float& height) const;

 private:
  const Texture* tex_;
  SamplerState state_;
  std::shared_ptr<const void> plan_;  // one-level 2D plan when the state allows it
  ImplicitKernel implicit_;
  ImplicitPairFn pair_ = nullptr;
  ImplicitGroupFn group_ = nullptr;
  ImplicitPairGroupFn pairGroup_ = nullptr;
};

// Cube face selection: face index (D3DCUBEMAP_FACES) and (u,v) in [0,1] on that face.
int cubeFaceCoords(float x, float y, float z, float& u, float& v);

}  // namespace refx
