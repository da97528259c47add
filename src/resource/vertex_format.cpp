// FVF layouts and the vertex declarations D3D builds from them.
#include "refx/resource/vertex_format.h"

#include <algorithm>

#include "refx/core/diagnostics.h"

namespace refx {

using namespace d3d;

namespace {

// Bytes of the position part (with blend weights) per D3DFVF_POSITION_MASK value.
int positionBytes(uint32_t fvf) {
  uint32_t pos = fvf & FVF_POSITION_MASK;
  switch (pos) {
    case 0: return 0;
    case FVF_XYZRHW:
    case FVF_XYZW: return 16;
    case FVF_XYZ: return 12;
    case FVF_XYZB1: case FVF_XYZB2: case FVF_XYZB3: case FVF_XYZB4: case FVF_XYZB5:
      return 12 + 4 * fvfBetaCount(fvf);  // x y z and 1-5 betas
    default: fail("FVF 0x{:x}: position bits 0x{:x} are not a D3DFVF position type", fvf, pos);
  }
}

uint8_t declTypeForDims(int dims) {
  return static_cast<uint8_t>(DECLTYPE_FLOAT1 + (dims - 1));
}

}  // namespace

FVFLayout FVFLayout::of(uint32_t code) {
  FVFLayout l;
  int n = fvfTexCount(code);
  if (n > 8) fail("FVF 0x{:x}: {} texture coordinate sets, D3D allows at most 8", code, n);
  int off = positionBytes(code);
  if (off) l.position = 0;
  const uint32_t pos = code & FVF_POSITION_MASK;
  if (const int betas = fvfBetaCount(code)) {
    const bool indices = pos == FVF_XYZB5 || (code & (FVF_LASTBETA_UBYTE4 | FVF_LASTBETA_D3DCOLOR));
    l.blendWeightCount = betas - (indices ? 1 : 0);
    if (l.blendWeightCount > 0) l.blendWeights = 12;
    if (indices) l.blendIndices = 12 + 4 * l.blendWeightCount;
  }
  auto take = [&](uint32_t bit, int& field, int bytes) {
    if (code & bit) field = off, off += bytes;
  };
  take(FVF_NORMAL, l.normal, 12);
  take(FVF_PSIZE, l.psize, 4);
  take(FVF_DIFFUSE, l.diffuse, 4);
  take(FVF_SPECULAR, l.specular, 4);
  for (int i = 0; i < n; ++i) {
    l.texDims[i] = fvfTexCoordDims(code, i);
    l.texCoord[i] = off;
    off += 4 * l.texDims[i];
  }
  l.stride = uint32_t(off);
  return l;
}

uint32_t fvfStride(uint32_t fvf) { return FVFLayout::of(fvf).stride; }

uint32_t declTypeSize(uint8_t type) {
  switch (type) {
    case DECLTYPE_FLOAT1: return 4;
    case DECLTYPE_FLOAT2: return 8;
    case DECLTYPE_FLOAT3: return 12;
    case DECLTYPE_FLOAT4: return 16;
    case DECLTYPE_D3DCOLOR: case DECLTYPE_UBYTE4: case DECLTYPE_SHORT2: case DECLTYPE_UBYTE4N:
    case DECLTYPE_SHORT2N: case DECLTYPE_USHORT2N: case DECLTYPE_UDEC3: case DECLTYPE_DEC3N:
    case DECLTYPE_FLOAT16_2: return 4;
    case DECLTYPE_SHORT4: case DECLTYPE_SHORT4N: case DECLTYPE_USHORT4N: case DECLTYPE_FLOAT16_4:
      return 8;
    default: return 0;
  }
}

VertexDeclaration VertexDeclaration::fromFVF(uint32_t fvf) {
  VertexDeclaration d;
  d.fvf = fvf;
  uint16_t off = 0;
  auto add = [&](uint8_t type, uint8_t usage, uint8_t index) {
    d.elements.push_back(VertexElement{0, off, type, 0, usage, index});
    off = static_cast<uint16_t>(off + declTypeSize(type));
  };
  const uint32_t pos = fvf & FVF_POSITION_MASK;
  const int betas = fvfBetaCount(fvf);
  const uint32_t lastBeta = fvf & (FVF_LASTBETA_UBYTE4 | FVF_LASTBETA_D3DCOLOR);
  if (pos != 0 && pos != FVF_XYZRHW && pos != FVF_XYZW && pos != FVF_XYZ && betas == 0)
    fail("FVF 0x{:x}: position bits 0x{:x} are not a D3DFVF position type (XYZ, XYZRHW, XYZW, "
         "XYZB1-XYZB5)", fvf, pos);
  if (lastBeta == (FVF_LASTBETA_UBYTE4 | FVF_LASTBETA_D3DCOLOR))
    fail("FVF 0x{:x}: D3DFVF_LASTBETA_UBYTE4 and D3DFVF_LASTBETA_D3DCOLOR exclude each other", fvf);
  if (lastBeta && betas == 0)
    fail("FVF 0x{:x}: D3DFVF_LASTBETA_{} needs a position with betas (XYZB1-XYZB5)", fvf,
         lastBeta == FVF_LASTBETA_UBYTE4 ? "UBYTE4" : "D3DCOLOR");
  if (pos == FVF_XYZRHW) {
    add(DECLTYPE_FLOAT4, DECLUSAGE_POSITIONT, 0);
  } else if (pos == FVF_XYZW) {
    add(DECLTYPE_FLOAT4, DECLUSAGE_POSITION, 0);
  } else if (pos != 0) {
    add(DECLTYPE_FLOAT3, DECLUSAGE_POSITION, 0);
    // The last beta holds four packed matrix indices with a LASTBETA flag; XYZB5 always
    // ends with them, since a BLENDWEIGHT element has at most four floats.
    const bool indices = betas > 0 && (lastBeta != 0 || betas == 5);
    const int weights = betas - (indices ? 1 : 0);
    if (weights > 0) add(declTypeForDims(weights), DECLUSAGE_BLENDWEIGHT, 0);
    if (indices)
      add(lastBeta == FVF_LASTBETA_UBYTE4     ? DECLTYPE_UBYTE4
          : lastBeta == FVF_LASTBETA_D3DCOLOR ? DECLTYPE_D3DCOLOR
                                              : DECLTYPE_FLOAT1,
          DECLUSAGE_BLENDINDICES, 0);
  }
  if (fvf & FVF_NORMAL) add(DECLTYPE_FLOAT3, DECLUSAGE_NORMAL, 0);
  if (fvf & FVF_PSIZE) add(DECLTYPE_FLOAT1, DECLUSAGE_PSIZE, 0);
  if (fvf & FVF_DIFFUSE) add(DECLTYPE_D3DCOLOR, DECLUSAGE_COLOR, 0);
  if (fvf & FVF_SPECULAR) add(DECLTYPE_D3DCOLOR, DECLUSAGE_COLOR, 1);
  int texCount = int((fvf & FVF_TEXCOUNT_MASK) >> FVF_TEXCOUNT_SHIFT);
  for (int i = 0; i < texCount && i < 8; ++i)
    add(declTypeForDims(fvfTexCoordDims(fvf, i)), DECLUSAGE_TEXCOORD, static_cast<uint8_t>(i));
  return d;
}

uint32_t VertexDeclaration::streamStride(int stream) const {
  uint32_t stride = 0;
  for (const auto& e : elements)
    if (e.stream == stream) stride = std::max(stride, uint32_t(e.offset) + declTypeSize(e.type));
  return stride;
}

const VertexElement* VertexDeclaration::find(uint8_t usage, uint8_t usageIndex) const {
  for (const auto& e : elements)
    if (e.usage == usage && e.usageIndex == usageIndex) return &e;
  return nullptr;
}

}  // namespace refx
