// Render targets as Direct3D 9 binds them (SetRenderTarget 0-3, "Multiple Render
// Targets"): which textures may be bound together, and how the output merger sees them.
#pragma once
#include <array>

#include "raster.h"

namespace refx::pipeline {

using RenderTargets = std::array<TexturePtr, kMaxRenderTargets>;

// Throws refx::Error when `target` cannot be bound at `index` next to the other bound
// targets: an index beyond the caps' NumSimultaneousRTs, a null target 0, a format other
// than A8R8G8B8, X8R8G8B8 or A32B32G32R32F, a size unlike the others', or a bit depth
// unlike the others' without D3DPMISCCAPS_MRTINDEPENDENTBITDEPTHS.
void checkRenderTarget(int index, const Texture* target, const RenderTargets& bound,
                       const CapsProfile& caps);

// D3DRS_COLORWRITEENABLE for target 0, COLORWRITEENABLE1-3 for targets 1-3.
uint32_t colorWriteMask(const DeviceState& state, int index);

// The output merger's view of level 0 of `target`.
ColorTarget colorTargetOf(Texture& target, uint32_t writeMask);

}  // namespace refx::pipeline
