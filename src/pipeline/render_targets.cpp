#include "render_targets.h"

#include "refx/core/diagnostics.h"

namespace refx::pipeline {

using namespace d3d;

namespace {

constexpr uint32_t kMiscCapsMrtIndependentBitDepths = 0x40000;  // D3DPMISCCAPS_MRTINDEPENDENTBITDEPTHS

bool renderTargetFormat(Format f) {
  return f == Format::A8R8G8B8 || f == Format::X8R8G8B8 || f == Format::A32B32G32R32F;
}

uint32_t bitsPerPixel(Format f) { return formatInfo(f)->blockBytes * 8; }

}  // namespace

void checkRenderTarget(int index, const Texture* target, const RenderTargets& bound,
                       const CapsProfile& caps) {
  if (index < 0 || index >= kMaxRenderTargets || uint32_t(index) >= caps.maxSimultaneousRenderTargets)
    fail("render target index {} is out of range: caps profile {} has NumSimultaneousRTs {}", index,
         caps.name, caps.maxSimultaneousRenderTargets);
  if (!target) {
    if (index == 0) fail("render target 0 cannot be null (only targets 1-3 may be unbound)");
    return;
  }
  if (target->type() != TextureType::Texture2D || !renderTargetFormat(target->format()))
    fail("render target must be a 2D A8R8G8B8, X8R8G8B8 or A32B32G32R32F texture, got {}",
         formatName(target->format()));
  const bool independentBitDepths = (caps.primitiveMiscCaps & kMiscCapsMrtIndependentBitDepths) != 0;
  for (int i = 0; i < kMaxRenderTargets; ++i) {
    const Texture* other = bound[size_t(i)].get();
    if (i == index || !other) continue;
    if (other->width() != target->width() || other->height() != target->height())
      fail("render target {} is {}x{}, render target {} is {}x{}: all bound render targets must "
           "have the same size", index, target->width(), target->height(), i, other->width(),
           other->height());
    if (!independentBitDepths && bitsPerPixel(other->format()) != bitsPerPixel(target->format()))
      fail("render target {} ({}, {} bits) and render target {} ({}, {} bits) differ in bit depth, "
           "which caps profile {} does not allow (no D3DPMISCCAPS_MRTINDEPENDENTBITDEPTHS)", index,
           formatName(target->format()), bitsPerPixel(target->format()), i,
           formatName(other->format()), bitsPerPixel(other->format()), caps.name);
  }
}

uint32_t colorWriteMask(const DeviceState& state, int index) {
  static constexpr RenderState kMasks[kMaxRenderTargets] = {
      RS_COLORWRITEENABLE, RS_COLORWRITEENABLE1, RS_COLORWRITEENABLE2, RS_COLORWRITEENABLE3};
  return state.rs(kMasks[index]) & 0xf;
}

ColorTarget colorTargetOf(Texture& target, uint32_t writeMask) {
  ColorTarget t;
  t.data = target.data(0, 0);
  t.pitch = int(target.rowPitch(0));
  t.hasAlpha = target.format() != Format::X8R8G8B8;
  t.isFloat = target.format() == Format::A32B32G32R32F;
  t.writeMask = writeMask;
  return t;
}

}  // namespace refx::pipeline
