// Device generations as data: one caps profile per file under data/caps/, fields
// named after D3DCAPS9.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace refx {

struct CapsProfile {
  std::string name;         // "dx6-tnt2"
  std::string description;  // "DirectX 6 class: RIVA TNT2, 2 texture stages"
  // D3DCAPS9 fields that matter for validation.
  uint32_t textureOpCaps = 0;      // D3DTEXOPCAPS_* bits (bit n-1 for D3DTOP n)
  uint32_t maxTextureBlendStages = 8;
  uint32_t maxSimultaneousTextures = 8;
  uint32_t vertexShaderVersion = 0;  // D3DVS_VERSION(major, minor) = 0xFFFE0000 | major<<8 | minor
  uint32_t pixelShaderVersion = 0;   // D3DPS_VERSION = 0xFFFF0000 | major<<8 | minor
  float pixelShader1xMaxValue = 0;   // MaxPixelShaderValue
  uint32_t maxVertexShaderConst = 0;
  uint32_t maxTextureWidth = 2048, maxTextureHeight = 2048, maxVolumeExtent = 256;
  uint32_t textureFilterCaps = 0, cubeTextureFilterCaps = 0, volumeTextureFilterCaps = 0;
  uint32_t textureCaps = 0;         // D3DPTEXTURECAPS_* (CUBEMAP, VOLUMEMAP, MIPMAP, ...)
  uint32_t textureAddressCaps = 0;  // D3DPTADDRESSCAPS_*
  uint32_t srcBlendCaps = 0, destBlendCaps = 0;  // D3DPBLENDCAPS_*
  uint32_t primitiveMiscCaps = 0;   // D3DPMISCCAPS_* (TSSARGTEMP, SEPARATEALPHABLEND, BLENDOP ...)
  uint32_t rasterCaps = 0;          // D3DPRASTERCAPS_* (FOGTABLE, FOGVERTEX, ...)
  uint32_t devCaps = 0;             // D3DDEVCAPS_* (HWTRANSFORMANDLIGHT, ...)
  uint32_t maxActiveLights = 8;
  uint32_t maxStreams = 16;
  uint32_t fvfCaps = 8;             // low 16 bits: max texture coordinate sets
  uint32_t maxSimultaneousRenderTargets = 1;
  uint32_t vertexTextureFilterCaps = 0;  // D3DPTFILTERCAPS_*; nonzero = vertex texture fetch
  uint32_t maxTextureRepeat = 8192;      // texture coordinate range (ps_1_x texcoord clamp)
  uint32_t maxAnisotropy = 1;
  float maxPointSize = 1;                 // 1: the device draws points one pixel in size
  uint32_t maxVertexBlendMatrices = 0;    // world matrices blended per vertex (0: no blending)
  uint32_t maxVertexBlendMatrixIndex = 0; // highest D3DTS_WORLDMATRIX index; 0: not indexed
  uint32_t maxUserClipPlanes = 0;

  int vsMajor() const { return (vertexShaderVersion >> 8) & 0xff; }
  int vsMinor() const { return vertexShaderVersion & 0xff; }
  int psMajor() const { return (pixelShaderVersion >> 8) & 0xff; }
  int psMinor() const { return pixelShaderVersion & 0xff; }
};

// Names of the shipped profiles in generation order.
std::vector<std::string> capsProfileNames();
// Loads a shipped profile by name (or a path to a .caps file). Throws refx::Error.
CapsProfile loadCapsProfile(const std::string& nameOrPath);
// Parses a .caps file's text; `file` names it in errors.
CapsProfile parseCapsProfile(const std::string& text, const std::string& file);
// Human-readable listing of every field (for `refx caps PROFILE`).
std::string describeCapsProfile(const CapsProfile& caps);

struct DeviceState;
// ValidateDevice: ok with the number of passes (always 1 for a valid state), or the
// exact first reason the state cannot run on `caps`.
struct ValidationResult {
  bool ok = true;
  uint32_t passes = 1;
  std::string reason;  // "stage 0 COLOROP DOTPRODUCT3 is not in TextureOpCaps of dx6-tnt2"
};
ValidationResult validateDeviceState(const DeviceState& state, const CapsProfile& caps);

}  // namespace refx
