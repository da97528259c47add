// Vertex formats: the D3DFVF_* codes with their layout (D3DX meshes store vertices in
// it, the device builds its declaration from it) and vertex declarations
// (D3DVERTEXELEMENT9 with the D3DDECLTYPE / D3DDECLMETHOD / D3DDECLUSAGE values).
#pragma once
#include <cstdint>
#include <vector>

namespace refx::d3d {

// D3DFVF_*
enum FVF : uint32_t {
  FVF_XYZ = 0x002, FVF_XYZRHW = 0x004, FVF_XYZB1 = 0x006, FVF_XYZB2 = 0x008,
  FVF_XYZB3 = 0x00a, FVF_XYZB4 = 0x00c, FVF_XYZB5 = 0x00e, FVF_XYZW = 0x4002,
  FVF_POSITION_MASK = 0x400e, FVF_NORMAL = 0x010, FVF_PSIZE = 0x020, FVF_DIFFUSE = 0x040,
  FVF_SPECULAR = 0x080, FVF_TEXCOUNT_MASK = 0xf00, FVF_TEXCOUNT_SHIFT = 8,
  // The last beta of XYZB1-5 holds four 8-bit matrix indices (indexed vertex blending).
  FVF_LASTBETA_UBYTE4 = 0x1000, FVF_LASTBETA_D3DCOLOR = 0x8000,
};
// D3DFVF_TEXn: n texture coordinate sets (D3D defines n = 0-8).
constexpr uint32_t fvfTex(int count) { return uint32_t(count) << FVF_TEXCOUNT_SHIFT; }
constexpr int fvfTexCount(uint32_t fvf) {
  return int((fvf & FVF_TEXCOUNT_MASK) >> FVF_TEXCOUNT_SHIFT);
}
// Number of betas (floats after x y z) of an XYZB1-XYZB5 position; 0 for the others.
constexpr int fvfBetaCount(uint32_t fvf) {
  const uint32_t pos = fvf & FVF_POSITION_MASK;
  return pos >= FVF_XYZB1 && pos <= FVF_XYZB5 ? int(pos - FVF_XYZB1) / 2 + 1 : 0;
}
// D3DFVF_TEXCOORDSIZEn(i): bits 16+2i. 0 = 2 floats, 1 = 3, 2 = 4, 3 = 1.
constexpr uint32_t fvfTexCoordSize(int dims, int index) {
  uint32_t code = dims == 1 ? 3u : dims == 3 ? 1u : dims == 4 ? 2u : 0u;
  return code << (16 + 2 * index);
}
constexpr int fvfTexCoordDims(uint32_t fvf, int index) {
  uint32_t code = (fvf >> (16 + 2 * index)) & 3;
  return code == 0 ? 2 : code == 1 ? 3 : code == 2 ? 4 : 1;
}

// D3DDECLTYPE
enum DeclType : uint8_t {
  DECLTYPE_FLOAT1 = 0, DECLTYPE_FLOAT2, DECLTYPE_FLOAT3, DECLTYPE_FLOAT4, DECLTYPE_D3DCOLOR,
  DECLTYPE_UBYTE4, DECLTYPE_SHORT2, DECLTYPE_SHORT4, DECLTYPE_UBYTE4N, DECLTYPE_SHORT2N,
  DECLTYPE_SHORT4N, DECLTYPE_USHORT2N, DECLTYPE_USHORT4N, DECLTYPE_UDEC3, DECLTYPE_DEC3N,
  DECLTYPE_FLOAT16_2, DECLTYPE_FLOAT16_4, DECLTYPE_UNUSED = 17,
};
// D3DDECLMETHOD
enum DeclMethod : uint8_t {
  DECLMETHOD_DEFAULT = 0, DECLMETHOD_PARTIALU, DECLMETHOD_PARTIALV, DECLMETHOD_CROSSUV,
  DECLMETHOD_UV, DECLMETHOD_LOOKUP, DECLMETHOD_LOOKUPPRESAMPLED,
};
// D3DDECLUSAGE
enum DeclUsage : uint8_t {
  DECLUSAGE_POSITION = 0, DECLUSAGE_BLENDWEIGHT, DECLUSAGE_BLENDINDICES, DECLUSAGE_NORMAL,
  DECLUSAGE_PSIZE, DECLUSAGE_TEXCOORD, DECLUSAGE_TANGENT, DECLUSAGE_BINORMAL,
  DECLUSAGE_TESSFACTOR, DECLUSAGE_POSITIONT, DECLUSAGE_COLOR, DECLUSAGE_FOG, DECLUSAGE_DEPTH,
  DECLUSAGE_SAMPLE,
};

}  // namespace refx::d3d

namespace refx {

// Byte offsets of the elements of an FVF vertex, in D3D's fixed order (position,
// blend weights, normal, point size, diffuse, specular, texture coordinate sets);
// -1 where the element is absent.
struct FVFLayout {
  int position = -1, normal = -1, psize = -1, diffuse = -1, specular = -1;
  // Blend weights (floats after x y z) and the packed matrix indices (the last beta of
  // an XYZB5 or LASTBETA_* position); -1 / 0 when absent.
  int blendWeights = -1, blendWeightCount = 0, blendIndices = -1;
  int texCoord[8] = {-1, -1, -1, -1, -1, -1, -1, -1};
  int texDims[8] = {};
  uint32_t stride = 0;
  // Throws refx::Error for codes D3D rejects (an unknown position type, TEX9+).
  static FVFLayout of(uint32_t fvf);
};
// Size in bytes of one vertex (D3DXGetFVFVertexSize); throws as FVFLayout::of.
uint32_t fvfStride(uint32_t fvf);

struct VertexElement {  // D3DVERTEXELEMENT9
  uint16_t stream = 0;
  uint16_t offset = 0;
  uint8_t type = d3d::DECLTYPE_FLOAT3;
  uint8_t method = d3d::DECLMETHOD_DEFAULT;
  uint8_t usage = d3d::DECLUSAGE_POSITION;
  uint8_t usageIndex = 0;
  // The v register this element feeds in a vs_1_1 shader without dcl instructions
  // (a DirectX 8 declaration's D3DVSD_REG); -1: the D3DVSDE register of its usage.
  int8_t shaderRegister = -1;
  bool operator==(const VertexElement&) const = default;
};

// Size in bytes of one element of a D3DDECLTYPE (0 for UNUSED and unknown types).
uint32_t declTypeSize(uint8_t type);

struct VertexDeclaration {
  std::vector<VertexElement> elements;
  uint32_t fvf = 0;  // nonzero when made from an FVF code
  // The declaration D3D builds for an FVF code (stream 0, D3D's element order); throws
  // refx::Error for an unknown position type or contradicting LASTBETA flags.
  static VertexDeclaration fromFVF(uint32_t fvf);
  // Size in bytes of one vertex of stream `stream` (max offset+size of its elements).
  uint32_t streamStride(int stream) const;
  const VertexElement* find(uint8_t usage, uint8_t usageIndex) const;
  bool operator==(const VertexDeclaration&) const = default;
};

}  // namespace refx
