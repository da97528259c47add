#include "refx/pipeline/state.h"

#include "refx/core/diagnostics.h"

namespace refx {

using namespace d3d;

DeviceState::DeviceState() {
  auto& r = renderStates;
  r[RS_ZENABLE] = ZB_FALSE;
  r[RS_FILLMODE] = FILL_SOLID;
  r[RS_SHADEMODE] = SHADE_GOURAUD;
  r[RS_ZWRITEENABLE] = 1;
  r[RS_LASTPIXEL] = 1;
  r[RS_SRCBLEND] = BLEND_ONE;
  r[RS_DESTBLEND] = BLEND_ZERO;
  r[RS_CULLMODE] = CULL_CCW;
  r[RS_ZFUNC] = CMP_LESSEQUAL;
  r[RS_ALPHAFUNC] = CMP_ALWAYS;
  r[RS_FOGSTART] = floatBits(0.0f);
  r[RS_FOGEND] = floatBits(1.0f);
  r[RS_FOGDENSITY] = floatBits(1.0f);
  r[RS_STENCILFAIL] = r[RS_STENCILZFAIL] = r[RS_STENCILPASS] = STENCILOP_KEEP;
  r[RS_STENCILFUNC] = CMP_ALWAYS;
  r[RS_STENCILMASK] = r[RS_STENCILWRITEMASK] = 0xffffffff;
  r[RS_TEXTUREFACTOR] = 0xffffffff;
  r[RS_CLIPPING] = 1;
  r[RS_LIGHTING] = 1;
  r[RS_COLORVERTEX] = 1;
  r[RS_LOCALVIEWER] = 1;
  r[RS_DIFFUSEMATERIALSOURCE] = MCS_COLOR1;
  r[RS_SPECULARMATERIALSOURCE] = MCS_COLOR2;
  r[RS_AMBIENTMATERIALSOURCE] = MCS_MATERIAL;
  r[RS_EMISSIVEMATERIALSOURCE] = MCS_MATERIAL;
  r[RS_POINTSIZE] = floatBits(1.0f);
  r[RS_POINTSIZE_MIN] = floatBits(1.0f);
  r[RS_POINTSCALE_A] = floatBits(1.0f);
  r[RS_POINTSIZE_MAX] = floatBits(64.0f);
  r[RS_MULTISAMPLEANTIALIAS] = 1;
  r[RS_MULTISAMPLEMASK] = 0xffffffff;
  r[RS_COLORWRITEENABLE] = r[RS_COLORWRITEENABLE1] = r[RS_COLORWRITEENABLE2] =
      r[RS_COLORWRITEENABLE3] = 0xf;
  r[RS_BLENDOP] = BLENDOP_ADD;
  r[RS_CCW_STENCILFAIL] = r[RS_CCW_STENCILZFAIL] = r[RS_CCW_STENCILPASS] = STENCILOP_KEEP;
  r[RS_CCW_STENCILFUNC] = CMP_ALWAYS;
  r[RS_BLENDFACTOR] = 0xffffffff;
  r[RS_SRCBLENDALPHA] = BLEND_ONE;
  r[RS_DESTBLENDALPHA] = BLEND_ZERO;
  r[RS_BLENDOPALPHA] = BLENDOP_ADD;
  r[RS_MINTESSELLATIONLEVEL] = floatBits(1.0f);
  r[RS_MAXTESSELLATIONLEVEL] = floatBits(1.0f);
  r[RS_ADAPTIVETESS_W] = floatBits(1.0f);
  r[RS_POSITIONDEGREE] = 3;  // D3DDEGREE_CUBIC
  r[RS_NORMALDEGREE] = 1;    // D3DDEGREE_LINEAR

  for (int s = 0; s < kMaxTextureStages; ++s) {
    auto& t = stageStates[s];
    t[TSS_COLOROP] = s == 0 ? TOP_MODULATE : TOP_DISABLE;
    t[TSS_COLORARG1] = TA_TEXTURE;
    t[TSS_COLORARG2] = TA_CURRENT;
    t[TSS_ALPHAOP] = s == 0 ? TOP_SELECTARG1 : TOP_DISABLE;
    t[TSS_ALPHAARG1] = TA_TEXTURE;
    t[TSS_ALPHAARG2] = TA_CURRENT;
    t[TSS_TEXCOORDINDEX] = s;
    t[TSS_COLORARG0] = TA_CURRENT;
    t[TSS_ALPHAARG0] = TA_CURRENT;
    t[TSS_RESULTARG] = TA_CURRENT;
    textureTransforms[s] = Matrix::identity();
  }
  for (auto& sm : samplerStates) {
    sm[SAMP_ADDRESSU] = sm[SAMP_ADDRESSV] = sm[SAMP_ADDRESSW] = 1;  // WRAP
    sm[SAMP_MAGFILTER] = sm[SAMP_MINFILTER] = 1;                    // POINT
    sm[SAMP_MIPFILTER] = 0;                                         // NONE
    sm[SAMP_MAXANISOTROPY] = 1;
  }
}

static uint8_t declTypeForDims(int dims) {
  return static_cast<uint8_t>(DECLTYPE_FLOAT1 + (dims - 1));
}

static uint32_t declTypeSize(uint8_t type) {
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
