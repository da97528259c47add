// Sampler entry points private to the resource layer and its tests.
#pragma once
#include "refx/resource/sampler.h"

namespace refx::resource {

// Same results as sampleTexture, computed lane by lane with the plain scalar path
// only (no vectorised kernel). The reference the fast path is checked against.
void sampleTextureReference(const Texture& tex, const SamplerState& state,
                            const SampleRequest& req, float out[4][kBatchLanes]);

// Converts an sRGB-encoded value to linear: c <= 0.04045 ? c/12.92 : ((c+0.055)/1.055)^2.4.
float srgbToLinear(float c);

}  // namespace refx::resource
