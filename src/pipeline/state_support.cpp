#include "state_support.h"

#include <fmt/format.h>

#include "refx/core/diagnostics.h"
#include "refx/pipeline/d3d9types.h"
#include "refx/pipeline/state.h"

namespace refx::pipeline {

using namespace d3d;

namespace {

constexpr StateSupport kImpl = StateSupport::Implemented;
constexpr StateSupport kNoEffect = StateSupport::NoEffect;
constexpr StateSupport kDefault = StateSupport::DefaultOnly;
constexpr StateClass kRS = StateClass::Render;
constexpr StateClass kTSS = StateClass::TextureStage;
constexpr StateClass kSamp = StateClass::Sampler;

constexpr std::string_view kOutputMerger = "output merger (output_merger.cpp)";
constexpr std::string_view kStencil = "output merger stencil test (output_merger.cpp)";
constexpr std::string_view kBlend = "output merger blending (output_merger.cpp)";
constexpr std::string_view kFFVertex = "fixed-function vertex stage (ff_vertex.cpp)";
constexpr std::string_view kFFPixel = "fixed-function texture stages (ff_pixel.cpp)";
constexpr std::string_view kFog = "fog (ff_vertex.cpp vertex fog, ff_pixel.cpp table fog)";
constexpr std::string_view kVertexBlend = "fixed-function vertex blending (ff_vertex.cpp)";
constexpr std::string_view kPoints = "point size and point sprites (device point path)";
constexpr std::string_view kSampler = "texture sampler (resource/sampler.cpp)";
constexpr std::string_view kTessellation =
    "refx has no patch or N-patch tessellation; only the default is accepted";
constexpr std::string_view kWrapHigh =
    "refx applies D3DRS_WRAP0-7 only; WRAP8-15 accept only their default 0";

constexpr StateSupportEntry kTable[] = {
    {kRS, RS_ZENABLE, kImpl, "depth test (TRUE) and w-buffer (USEW) in the output merger"},
    {kRS, RS_FILLMODE, kImpl, "primitive assembly: POINT, WIREFRAME, SOLID (primitive_setup.cpp)"},
    {kRS, RS_SHADEMODE, kImpl, "flat or Gouraud interpolation (draw_plan.cpp, primitive_setup.cpp)"},
    {kRS, RS_ZWRITEENABLE, kImpl, kOutputMerger},
    {kRS, RS_ALPHATESTENABLE, kImpl, kOutputMerger},
    {kRS, RS_LASTPIXEL, kDefault,
     "lines always include their last pixel (the default TRUE); FALSE is refused"},
    {kRS, RS_SRCBLEND, kImpl, kBlend},
    {kRS, RS_DESTBLEND, kImpl, kBlend},
    {kRS, RS_CULLMODE, kImpl, "triangle setup (primitive_setup.cpp)"},
    {kRS, RS_ZFUNC, kImpl, kOutputMerger},
    {kRS, RS_ALPHAREF, kImpl, kOutputMerger},
    {kRS, RS_ALPHAFUNC, kImpl, kOutputMerger},
    {kRS, RS_DITHERENABLE, kImpl, "output merger: ordered dithering of 8-bit targets"},
    {kRS, RS_ALPHABLENDENABLE, kImpl, kBlend},
    {kRS, RS_FOGENABLE, kImpl, kFog},
    {kRS, RS_SPECULARENABLE, kImpl, "specular lighting and add (ff_vertex.cpp, ff_pixel.cpp)"},
    {kRS, RS_FOGCOLOR, kImpl, kFog},
    {kRS, RS_FOGTABLEMODE, kImpl, kFog},
    {kRS, RS_FOGSTART, kImpl, kFog},
    {kRS, RS_FOGEND, kImpl, kFog},
    {kRS, RS_FOGDENSITY, kImpl, kFog},
    {kRS, RS_RANGEFOGENABLE, kImpl, "vertex fog distance (ff_vertex.cpp)"},
    {kRS, RS_STENCILENABLE, kImpl, kStencil},
    {kRS, RS_STENCILFAIL, kImpl, kStencil},
    {kRS, RS_STENCILZFAIL, kImpl, kStencil},
    {kRS, RS_STENCILPASS, kImpl, kStencil},
    {kRS, RS_STENCILFUNC, kImpl, kStencil},
    {kRS, RS_STENCILREF, kImpl, kStencil},
    {kRS, RS_STENCILMASK, kImpl, kStencil},
    {kRS, RS_STENCILWRITEMASK, kImpl, kStencil},
    {kRS, RS_TEXTUREFACTOR, kImpl, kFFPixel},
    {kRS, RS_WRAP0 + 0, kImpl, "cylindrical wrap of texture coordinate sets (draw_plan.cpp, primitive_setup.cpp)"},
    {kRS, RS_WRAP0 + 1, kImpl, "cylindrical wrap of texture coordinate sets (draw_plan.cpp, primitive_setup.cpp)"},
    {kRS, RS_WRAP0 + 2, kImpl, "cylindrical wrap of texture coordinate sets (draw_plan.cpp, primitive_setup.cpp)"},
    {kRS, RS_WRAP0 + 3, kImpl, "cylindrical wrap of texture coordinate sets (draw_plan.cpp, primitive_setup.cpp)"},
    {kRS, RS_WRAP0 + 4, kImpl, "cylindrical wrap of texture coordinate sets (draw_plan.cpp, primitive_setup.cpp)"},
    {kRS, RS_WRAP0 + 5, kImpl, "cylindrical wrap of texture coordinate sets (draw_plan.cpp, primitive_setup.cpp)"},
    {kRS, RS_WRAP0 + 6, kImpl, "cylindrical wrap of texture coordinate sets (draw_plan.cpp, primitive_setup.cpp)"},
    {kRS, RS_WRAP0 + 7, kImpl, "cylindrical wrap of texture coordinate sets (draw_plan.cpp, primitive_setup.cpp)"},
    {kRS, RS_CLIPPING, kImpl,
     "FALSE turns the user clip planes off (clip.cpp); the view volume is always clipped, "
     "which FALSE only promises is not needed"},
    {kRS, RS_LIGHTING, kImpl, kFFVertex},
    {kRS, RS_AMBIENT, kImpl, kFFVertex},
    {kRS, RS_FOGVERTEXMODE, kImpl, kFog},
    {kRS, RS_COLORVERTEX, kImpl, kFFVertex},
    {kRS, RS_LOCALVIEWER, kImpl, kFFVertex},
    {kRS, RS_NORMALIZENORMALS, kImpl, kFFVertex},
    {kRS, RS_DIFFUSEMATERIALSOURCE, kImpl, kFFVertex},
    {kRS, RS_SPECULARMATERIALSOURCE, kImpl, kFFVertex},
    {kRS, RS_AMBIENTMATERIALSOURCE, kImpl, kFFVertex},
    {kRS, RS_EMISSIVEMATERIALSOURCE, kImpl, kFFVertex},
    {kRS, RS_VERTEXBLEND, kImpl, kVertexBlend},
    {kRS, RS_CLIPPLANEENABLE, kImpl, "user clip planes (clipper)"},
    {kRS, RS_POINTSIZE, kImpl, kPoints},
    {kRS, RS_POINTSIZE_MIN, kImpl, kPoints},
    {kRS, RS_POINTSPRITEENABLE, kImpl, kPoints},
    {kRS, RS_POINTSCALEENABLE, kImpl, kPoints},
    {kRS, RS_POINTSCALE_A, kImpl, kPoints},
    {kRS, RS_POINTSCALE_B, kImpl, kPoints},
    {kRS, RS_POINTSCALE_C, kImpl, kPoints},
    {kRS, RS_MULTISAMPLEANTIALIAS, kNoEffect,
     "refx render targets have one sample, where D3D9 gives it no effect"},
    {kRS, RS_MULTISAMPLEMASK, kNoEffect,
     "refx render targets have one sample, where D3D9 gives it no effect"},
    {kRS, RS_PATCHEDGESTYLE, kDefault, kTessellation},
    {kRS, RS_DEBUGMONITORTOKEN, kNoEffect, "read by the D3D9 debug runtime only"},
    {kRS, RS_POINTSIZE_MAX, kImpl, kPoints},
    {kRS, RS_INDEXEDVERTEXBLENDENABLE, kImpl, kVertexBlend},
    {kRS, RS_COLORWRITEENABLE, kImpl, kOutputMerger},
    {kRS, RS_TWEENFACTOR, kImpl, kVertexBlend},
    {kRS, RS_BLENDOP, kImpl, kBlend},
    {kRS, RS_POSITIONDEGREE, kDefault, kTessellation},
    {kRS, RS_NORMALDEGREE, kDefault, kTessellation},
    {kRS, RS_SCISSORTESTENABLE, kImpl, "raster bounds (primitive_setup.cpp)"},
    {kRS, RS_SLOPESCALEDEPTHBIAS, kImpl, "depth bias of triangles (raster setup)"},
    {kRS, RS_ANTIALIASEDLINEENABLE, kDefault,
     "refx draws aliased lines only; only the default FALSE is accepted"},
    {kRS, RS_MINTESSELLATIONLEVEL, kDefault, kTessellation},
    {kRS, RS_MAXTESSELLATIONLEVEL, kDefault, kTessellation},
    {kRS, RS_ADAPTIVETESS_X, kDefault, kTessellation},
    {kRS, RS_ADAPTIVETESS_Y, kDefault, kTessellation},
    {kRS, RS_ADAPTIVETESS_Z, kDefault, kTessellation},
    {kRS, RS_ADAPTIVETESS_W, kDefault, kTessellation},
    {kRS, RS_ENABLEADAPTIVETESSELLATION, kDefault, kTessellation},
    {kRS, RS_TWOSIDEDSTENCILMODE, kImpl, kStencil},
    {kRS, RS_CCW_STENCILFAIL, kImpl, kStencil},
    {kRS, RS_CCW_STENCILZFAIL, kImpl, kStencil},
    {kRS, RS_CCW_STENCILPASS, kImpl, kStencil},
    {kRS, RS_CCW_STENCILFUNC, kImpl, kStencil},
    {kRS, RS_COLORWRITEENABLE1, kImpl, "write mask of render target 1 (output merger)"},
    {kRS, RS_COLORWRITEENABLE2, kImpl, "write mask of render target 2 (output merger)"},
    {kRS, RS_COLORWRITEENABLE3, kImpl, "write mask of render target 3 (output merger)"},
    {kRS, RS_BLENDFACTOR, kImpl, kBlend},
    {kRS, RS_SRGBWRITEENABLE, kImpl, "sRGB conversion of the written colour (output merger)"},
    {kRS, RS_DEPTHBIAS, kImpl, "depth bias of triangles (raster setup)"},
    {kRS, RS_WRAP8 + 0, kDefault, kWrapHigh},
    {kRS, RS_WRAP8 + 1, kDefault, kWrapHigh},
    {kRS, RS_WRAP8 + 2, kDefault, kWrapHigh},
    {kRS, RS_WRAP8 + 3, kDefault, kWrapHigh},
    {kRS, RS_WRAP8 + 4, kDefault, kWrapHigh},
    {kRS, RS_WRAP8 + 5, kDefault, kWrapHigh},
    {kRS, RS_WRAP8 + 6, kDefault, kWrapHigh},
    {kRS, RS_WRAP8 + 7, kDefault, kWrapHigh},
    {kRS, RS_SEPARATEALPHABLENDENABLE, kImpl, kBlend},
    {kRS, RS_SRCBLENDALPHA, kImpl, kBlend},
    {kRS, RS_DESTBLENDALPHA, kImpl, kBlend},
    {kRS, RS_BLENDOPALPHA, kImpl, kBlend},

    {kTSS, TSS_COLOROP, kImpl, kFFPixel},
    {kTSS, TSS_COLORARG1, kImpl, kFFPixel},
    {kTSS, TSS_COLORARG2, kImpl, kFFPixel},
    {kTSS, TSS_ALPHAOP, kImpl, kFFPixel},
    {kTSS, TSS_ALPHAARG1, kImpl, kFFPixel},
    {kTSS, TSS_ALPHAARG2, kImpl, kFFPixel},
    {kTSS, TSS_BUMPENVMAT00, kImpl, "bump mapping: texture stages and ps_1_x texbem"},
    {kTSS, TSS_BUMPENVMAT01, kImpl, "bump mapping: texture stages and ps_1_x texbem"},
    {kTSS, TSS_BUMPENVMAT10, kImpl, "bump mapping: texture stages and ps_1_x texbem"},
    {kTSS, TSS_BUMPENVMAT11, kImpl, "bump mapping: texture stages and ps_1_x texbem"},
    {kTSS, TSS_TEXCOORDINDEX, kImpl, "texture coordinate selection and generation (ff_vertex.cpp)"},
    {kTSS, TSS_BUMPENVLSCALE, kImpl, "luminance bump mapping: texture stages and texbeml"},
    {kTSS, TSS_BUMPENVLOFFSET, kImpl, "luminance bump mapping: texture stages and texbeml"},
    {kTSS, TSS_TEXTURETRANSFORMFLAGS, kImpl,
     "texture transforms (ff_vertex.cpp) and projected lookups (ff_pixel.cpp, ps_1_x)"},
    {kTSS, TSS_COLORARG0, kImpl, kFFPixel},
    {kTSS, TSS_ALPHAARG0, kImpl, kFFPixel},
    {kTSS, TSS_RESULTARG, kImpl, kFFPixel},
    {kTSS, TSS_CONSTANT, kImpl, kFFPixel},

    {kSamp, SAMP_ADDRESSU, kImpl, kSampler},
    {kSamp, SAMP_ADDRESSV, kImpl, kSampler},
    {kSamp, SAMP_ADDRESSW, kImpl, kSampler},
    {kSamp, SAMP_BORDERCOLOR, kImpl, kSampler},
    {kSamp, SAMP_MAGFILTER, kImpl, kSampler},
    {kSamp, SAMP_MINFILTER, kImpl, kSampler},
    {kSamp, SAMP_MIPFILTER, kImpl, kSampler},
    {kSamp, SAMP_MIPMAPLODBIAS, kImpl, kSampler},
    {kSamp, SAMP_MAXMIPLEVEL, kImpl, kSampler},
    {kSamp, SAMP_MAXANISOTROPY, kImpl, "anisotropic filtering (resource/sampler.cpp)"},
    {kSamp, SAMP_SRGBTEXTURE, kImpl, kSampler},
    {kSamp, SAMP_ELEMENTINDEX, kDefault,
     "refx has no multi-element textures; only the default 0 is accepted"},
    {kSamp, SAMP_DMAPOFFSET, kDefault,
     "refx has no displacement maps; only the default 0 is accepted"},
};

EnumKind nameKind(StateClass c) {
  switch (c) {
    case StateClass::Render: return EnumKind::RenderState;
    case StateClass::TextureStage: return EnumKind::TextureStageState;
    case StateClass::Sampler: return EnumKind::SamplerState;
  }
  return EnumKind::RenderState;
}

std::string_view prefix(StateClass c) {
  switch (c) {
    case StateClass::Render: return "D3DRS_";
    case StateClass::TextureStage: return "D3DTSS_";
    case StateClass::Sampler: return "D3DSAMP_";
  }
  return "";
}

std::string_view kindName(StateClass c) {
  switch (c) {
    case StateClass::Render: return "render";
    case StateClass::TextureStage: return "texture stage";
    case StateClass::Sampler: return "sampler";
  }
  return "";
}

uint32_t defaultValue(StateClass c, uint32_t state) {
  static const DeviceState defaults;
  switch (c) {
    case StateClass::Render: return defaults.renderStates[state];
    // The refused stage and sampler states have the same default on every stage.
    case StateClass::TextureStage: return defaults.stageStates[0][state];
    case StateClass::Sampler: return defaults.samplerStates[0][state];
  }
  return 0;
}

StateValueInfo valueInfo(StateClass c, uint32_t state) {
  switch (c) {
    case StateClass::Render: return renderStateValue(state);
    case StateClass::TextureStage: return textureStageStateValue(state);
    case StateClass::Sampler: return samplerStateValue(state);
  }
  return {ValueKind::Uint, EnumKind::Bool};
}

// The default as the scene-script and effect syntax writes it: TRUE, 1.0, 0x..., 3.
std::string valueText(StateClass c, uint32_t state, uint32_t value) {
  const StateValueInfo info = valueInfo(c, state);
  switch (info.kind) {
    case ValueKind::Enum: {
      std::string_view name = enumName(info.enumKind, value);
      if (!name.empty()) return std::string(name);
      break;
    }
    case ValueKind::Float: return fmt::format("{:.1f}", bitsFloat(value));
    case ValueKind::Color: return fmt::format("0x{:08x}", value);
    default: break;
  }
  return std::to_string(value);
}

}  // namespace

std::span<const StateSupportEntry> stateSupportTable() { return kTable; }

const StateSupportEntry* findStateSupport(StateClass stateClass, uint32_t state) {
  for (const StateSupportEntry& e : kTable)
    if (e.stateClass == stateClass && e.state == state) return &e;
  return nullptr;
}

std::string stateDisplayName(StateClass stateClass, uint32_t state) {
  std::string_view name = enumName(nameKind(stateClass), state);
  if (name.empty()) return std::to_string(state);
  return std::string(prefix(stateClass)) + std::string(name);
}

void requireImplementedState(StateClass stateClass, uint32_t state, uint32_t value) {
  const StateSupportEntry* e = findStateSupport(stateClass, state);
  // A number between the D3D9 states (a DirectX 8 state such as D3DRS_ZBIAS 47, or
  // none at all) does nothing in refx: only its zero default is stored.
  if (!e && value != 0)
    fail("{} state {} is not a Direct3D 9 {} state", kindName(stateClass), state,
         kindName(stateClass));
  if (!e || e->support != StateSupport::DefaultOnly) return;
  const uint32_t def = defaultValue(stateClass, state);
  if (value == def) return;
  fail("{} is not implemented by refx (only its default {} is accepted, not {})",
       stateDisplayName(stateClass, state), valueText(stateClass, state, def),
       valueText(stateClass, state, value));
}

}  // namespace refx::pipeline
