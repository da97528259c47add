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

}  // namespace refx
