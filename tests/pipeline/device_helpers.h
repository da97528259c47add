// Small helpers for probe tests that drive refx::Device directly.
#pragma once
#include <cstring>
#include <vector>

#include "refx/pipeline/device.h"

namespace refx::test {

struct TLVertex {  // D3DFVF_XYZRHW | D3DFVF_DIFFUSE | D3DFVF_TEX1
  float x, y, z, rhw;
  uint32_t diffuse;
  float u, v;
};
constexpr uint32_t kTLVertexFVF = d3d::FVF_XYZRHW | d3d::FVF_DIFFUSE | (1u << d3d::FVF_TEXCOUNT_SHIFT);

struct ColorVertex {  // D3DFVF_XYZ | D3DFVF_DIFFUSE
  float x, y, z;
  uint32_t diffuse;
};
constexpr uint32_t kColorVertexFVF = d3d::FVF_XYZ | d3d::FVF_DIFFUSE;

// A W x H A8R8G8B8 texture with a full mip chain of pseudo-random texels (a fixed LCG
// from `seed`).
inline TexturePtr noiseTexture(int w, int h, uint32_t seed = 12345) {
  auto t = Texture::create2D(Format::A8R8G8B8, w, h, 0);
  uint32_t x = seed;
  for (int y = 0; y < h; ++y)
    for (int i = 0; i < w; ++i) {
      x = x * 1664525u + 1013904223u;
      std::memcpy(t->data(0, 0) + y * t->rowPitch(0) + i * 4, &x, 4);
    }
  t->markDirty();
  t->generateMips();
  return t;
}

// A 1x1 A8R8G8B8 texture holding one texel.
inline TexturePtr texel(uint32_t argb) {
  auto t = Texture::create2D(Format::A8R8G8B8, 1, 1, 1);
  std::memcpy(t->data(0, 0), &argb, 4);
  t->markDirty();
  return t;
}

// A device with a W x H A8R8G8B8 target and a depth buffer, cleared to `clear`.
inline std::unique_ptr<Device> makeDevice(int w, int h, uint32_t clear = 0xff000000, int threads = 1) {
  DeviceOptions opt;
  opt.threads = threads;
  auto dev = std::make_unique<Device>(CapsProfile{}, opt);
  dev->setRenderTarget(Texture::create2D(Format::A8R8G8B8, w, h));
  dev->setDepthStencilSurface(std::make_shared<DepthStencilSurface>(w, h));
  dev->clear(d3d::CLEAR_TARGET | d3d::CLEAR_ZBUFFER | d3d::CLEAR_STENCIL, clear, 1.0f, 0);
  return dev;
}

// Stage 0 outputs the interpolated diffuse color (no texture involved).
inline void useDiffuseOnly(Device& dev) {
  dev.setTextureStageState(0, d3d::TSS_COLOROP, d3d::TOP_SELECTARG1);
  dev.setTextureStageState(0, d3d::TSS_COLORARG1, d3d::TA_DIFFUSE);
  dev.setTextureStageState(0, d3d::TSS_ALPHAOP, d3d::TOP_SELECTARG1);
  dev.setTextureStageState(0, d3d::TSS_ALPHAARG1, d3d::TA_DIFFUSE);
}

// Target pixel as 0xAARRGGBB.
inline uint32_t pixel(const Device& dev, int x, int y) {
  const Texture& t = *dev.renderTarget();
  uint32_t v;
  std::memcpy(&v, t.data(0, 0) + y * t.rowPitch(0) + x * 4, 4);
  return v;
}

// Filters and addressing (U and V alike) of sampler `stage`.
inline void setSampler(Device& dev, uint32_t stage, uint32_t minFilter, uint32_t magFilter, uint32_t mipFilter,
                       uint32_t address) {
  dev.setSamplerState(stage, d3d::SAMP_MINFILTER, minFilter);
  dev.setSamplerState(stage, d3d::SAMP_MAGFILTER, magFilter);
  dev.setSamplerState(stage, d3d::SAMP_MIPFILTER, mipFilter);
  dev.setSamplerState(stage, d3d::SAMP_ADDRESSU, address);
  dev.setSamplerState(stage, d3d::SAMP_ADDRESSV, address);
}

// A frame's colour bytes (rows of the target's level 0) and depths, compared whole.
struct FrameContents {
  std::vector<uint8_t> color;
  std::vector<float> depth;
};
inline FrameContents readFrame(const Texture& target, const DepthStencilSurface& ds) {
  FrameContents f;
  f.color.assign(target.data(0, 0), target.data(0, 0) + size_t(target.rowPitch(0)) * size_t(target.height(0)));
  f.depth.assign(ds.depth.begin(), ds.depth.end());
  return f;
}

inline void drawTL(Device& dev, d3d::PrimitiveType type, const std::vector<TLVertex>& v) {
  dev.setFVF(kTLVertexFVF);
  uint32_t prims = type == d3d::PT_TRIANGLELIST ? uint32_t(v.size() / 3)
                   : type == d3d::PT_TRIANGLESTRIP || type == d3d::PT_TRIANGLEFAN ? uint32_t(v.size() - 2)
                   : type == d3d::PT_LINELIST ? uint32_t(v.size() / 2)
                   : type == d3d::PT_LINESTRIP ? uint32_t(v.size() - 1) : uint32_t(v.size());
  dev.drawPrimitiveUP(type, prims, v.data(), sizeof(TLVertex));
}

}  // namespace refx::test
