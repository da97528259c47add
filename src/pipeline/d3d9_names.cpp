// Name tables for the D3D9 enumerations: one {name, value} table per EnumKind, read
// by the scene-script parser, the effect state parser and validation messages.
#include <cctype>
#include <span>

#include "refx/pipeline/d3d9types.h"
#include "refx/core/text.h"
#include "refx/resource/format.h"

namespace refx::d3d {

namespace {

struct NameValue {
  std::string_view name;
  uint32_t value;
};

constexpr NameValue kRenderStates[] = {
    {"ZENABLE", RS_ZENABLE}, {"FILLMODE", RS_FILLMODE}, {"SHADEMODE", RS_SHADEMODE},
    {"ZWRITEENABLE", RS_ZWRITEENABLE}, {"ALPHATESTENABLE", RS_ALPHATESTENABLE},
    {"LASTPIXEL", RS_LASTPIXEL}, {"SRCBLEND", RS_SRCBLEND}, {"DESTBLEND", RS_DESTBLEND},
    {"CULLMODE", RS_CULLMODE}, {"ZFUNC", RS_ZFUNC}, {"ALPHAREF", RS_ALPHAREF},
    {"ALPHAFUNC", RS_ALPHAFUNC}, {"DITHERENABLE", RS_DITHERENABLE},
    {"ALPHABLENDENABLE", RS_ALPHABLENDENABLE}, {"FOGENABLE", RS_FOGENABLE},
    {"SPECULARENABLE", RS_SPECULARENABLE}, {"FOGCOLOR", RS_FOGCOLOR},
    {"FOGTABLEMODE", RS_FOGTABLEMODE}, {"FOGSTART", RS_FOGSTART}, {"FOGEND", RS_FOGEND},
    {"FOGDENSITY", RS_FOGDENSITY}, {"RANGEFOGENABLE", RS_RANGEFOGENABLE},
    {"STENCILENABLE", RS_STENCILENABLE}, {"STENCILFAIL", RS_STENCILFAIL},
    {"STENCILZFAIL", RS_STENCILZFAIL}, {"STENCILPASS", RS_STENCILPASS},
    {"STENCILFUNC", RS_STENCILFUNC}, {"STENCILREF", RS_STENCILREF},
    {"STENCILMASK", RS_STENCILMASK}, {"STENCILWRITEMASK", RS_STENCILWRITEMASK},
    {"TEXTUREFACTOR", RS_TEXTUREFACTOR},
    // D3DRS_WRAP0-7 are 128-135, WRAP8-15 are 198-205.
    {"WRAP0", RS_WRAP0}, {"WRAP1", RS_WRAP0 + 1}, {"WRAP2", RS_WRAP0 + 2},
    {"WRAP3", RS_WRAP0 + 3}, {"WRAP4", RS_WRAP0 + 4}, {"WRAP5", RS_WRAP0 + 5},
    {"WRAP6", RS_WRAP0 + 6}, {"WRAP7", RS_WRAP0 + 7}, {"CLIPPING", RS_CLIPPING},
    {"LIGHTING", RS_LIGHTING}, {"AMBIENT", RS_AMBIENT}, {"FOGVERTEXMODE", RS_FOGVERTEXMODE},
    {"COLORVERTEX", RS_COLORVERTEX}, {"LOCALVIEWER", RS_LOCALVIEWER},
    {"NORMALIZENORMALS", RS_NORMALIZENORMALS},
    {"DIFFUSEMATERIALSOURCE", RS_DIFFUSEMATERIALSOURCE},
    {"SPECULARMATERIALSOURCE", RS_SPECULARMATERIALSOURCE},
    {"AMBIENTMATERIALSOURCE", RS_AMBIENTMATERIALSOURCE},
    {"EMISSIVEMATERIALSOURCE", RS_EMISSIVEMATERIALSOURCE}, {"VERTEXBLEND", RS_VERTEXBLEND},
    {"CLIPPLANEENABLE", RS_CLIPPLANEENABLE}, {"POINTSIZE", RS_POINTSIZE},
    {"POINTSIZE_MIN", RS_POINTSIZE_MIN}, {"POINTSPRITEENABLE", RS_POINTSPRITEENABLE},
    {"POINTSCALEENABLE", RS_POINTSCALEENABLE}, {"POINTSCALE_A", RS_POINTSCALE_A},
    {"POINTSCALE_B", RS_POINTSCALE_B}, {"POINTSCALE_C", RS_POINTSCALE_C},
    {"MULTISAMPLEANTIALIAS", RS_MULTISAMPLEANTIALIAS},
    {"MULTISAMPLEMASK", RS_MULTISAMPLEMASK}, {"PATCHEDGESTYLE", RS_PATCHEDGESTYLE},
    {"DEBUGMONITORTOKEN", RS_DEBUGMONITORTOKEN}, {"POINTSIZE_MAX", RS_POINTSIZE_MAX},
    {"INDEXEDVERTEXBLENDENABLE", RS_INDEXEDVERTEXBLENDENABLE},
    {"COLORWRITEENABLE", RS_COLORWRITEENABLE}, {"TWEENFACTOR", RS_TWEENFACTOR},
    {"BLENDOP", RS_BLENDOP}, {"POSITIONDEGREE", RS_POSITIONDEGREE},
    {"NORMALDEGREE", RS_NORMALDEGREE}, {"SCISSORTESTENABLE", RS_SCISSORTESTENABLE},
    {"SLOPESCALEDEPTHBIAS", RS_SLOPESCALEDEPTHBIAS},
    {"ANTIALIASEDLINEENABLE", RS_ANTIALIASEDLINEENABLE},
    {"MINTESSELLATIONLEVEL", RS_MINTESSELLATIONLEVEL},
    {"MAXTESSELLATIONLEVEL", RS_MAXTESSELLATIONLEVEL}, {"ADAPTIVETESS_X", RS_ADAPTIVETESS_X},
    {"ADAPTIVETESS_Y", RS_ADAPTIVETESS_Y}, {"ADAPTIVETESS_Z", RS_ADAPTIVETESS_Z},
    {"ADAPTIVETESS_W", RS_ADAPTIVETESS_W},
    {"ENABLEADAPTIVETESSELLATION", RS_ENABLEADAPTIVETESSELLATION},
    {"TWOSIDEDSTENCILMODE", RS_TWOSIDEDSTENCILMODE}, {"CCW_STENCILFAIL", RS_CCW_STENCILFAIL},
    {"CCW_STENCILZFAIL", RS_CCW_STENCILZFAIL}, {"CCW_STENCILPASS", RS_CCW_STENCILPASS},
    {"CCW_STENCILFUNC", RS_CCW_STENCILFUNC}, {"COLORWRITEENABLE1", RS_COLORWRITEENABLE1},
    {"COLORWRITEENABLE2", RS_COLORWRITEENABLE2}, {"COLORWRITEENABLE3", RS_COLORWRITEENABLE3},
    {"BLENDFACTOR", RS_BLENDFACTOR}, {"SRGBWRITEENABLE", RS_SRGBWRITEENABLE},
    {"DEPTHBIAS", RS_DEPTHBIAS}, {"WRAP8", RS_WRAP8}, {"WRAP9", RS_WRAP8 + 1},
    {"WRAP10", RS_WRAP8 + 2}, {"WRAP11", RS_WRAP8 + 3}, {"WRAP12", RS_WRAP8 + 4},
    {"WRAP13", RS_WRAP8 + 5}, {"WRAP14", RS_WRAP8 + 6}, {"WRAP15", RS_WRAP8 + 7},
    {"SEPARATEALPHABLENDENABLE", RS_SEPARATEALPHABLENDENABLE},
    {"SRCBLENDALPHA", RS_SRCBLENDALPHA}, {"DESTBLENDALPHA", RS_DESTBLENDALPHA},
    {"BLENDOPALPHA", RS_BLENDOPALPHA},
};

constexpr NameValue kTextureStageStates[] = {
    {"COLOROP", TSS_COLOROP}, {"COLORARG1", TSS_COLORARG1}, {"COLORARG2", TSS_COLORARG2},
    {"ALPHAOP", TSS_ALPHAOP}, {"ALPHAARG1", TSS_ALPHAARG1}, {"ALPHAARG2", TSS_ALPHAARG2},
    {"BUMPENVMAT00", TSS_BUMPENVMAT00}, {"BUMPENVMAT01", TSS_BUMPENVMAT01},
    {"BUMPENVMAT10", TSS_BUMPENVMAT10}, {"BUMPENVMAT11", TSS_BUMPENVMAT11},
    {"TEXCOORDINDEX", TSS_TEXCOORDINDEX}, {"BUMPENVLSCALE", TSS_BUMPENVLSCALE},
    {"BUMPENVLOFFSET", TSS_BUMPENVLOFFSET},
    {"TEXTURETRANSFORMFLAGS", TSS_TEXTURETRANSFORMFLAGS}, {"COLORARG0", TSS_COLORARG0},
    {"ALPHAARG0", TSS_ALPHAARG0}, {"RESULTARG", TSS_RESULTARG}, {"CONSTANT", TSS_CONSTANT},
};

constexpr NameValue kSamplerStates[] = {
    {"ADDRESSU", SAMP_ADDRESSU}, {"ADDRESSV", SAMP_ADDRESSV}, {"ADDRESSW", SAMP_ADDRESSW},
    {"BORDERCOLOR", SAMP_BORDERCOLOR}, {"MAGFILTER", SAMP_MAGFILTER},
    {"MINFILTER", SAMP_MINFILTER}, {"MIPFILTER", SAMP_MIPFILTER},
    {"MIPMAPLODBIAS", SAMP_MIPMAPLODBIAS}, {"MAXMIPLEVEL", SAMP_MAXMIPLEVEL},
    {"MAXANISOTROPY", SAMP_MAXANISOTROPY}, {"SRGBTEXTURE", SAMP_SRGBTEXTURE},
    {"ELEMENTINDEX", SAMP_ELEMENTINDEX}, {"DMAPOFFSET", SAMP_DMAPOFFSET},
};

constexpr NameValue kTextureOps[] = {
    {"DISABLE", TOP_DISABLE}, {"SELECTARG1", TOP_SELECTARG1}, {"SELECTARG2", TOP_SELECTARG2},
    {"MODULATE", TOP_MODULATE}, {"MODULATE2X", TOP_MODULATE2X},
    {"MODULATE4X", TOP_MODULATE4X}, {"ADD", TOP_ADD}, {"ADDSIGNED", TOP_ADDSIGNED},
    {"ADDSIGNED2X", TOP_ADDSIGNED2X}, {"SUBTRACT", TOP_SUBTRACT},
    {"ADDSMOOTH", TOP_ADDSMOOTH}, {"BLENDDIFFUSEALPHA", TOP_BLENDDIFFUSEALPHA},
    {"BLENDTEXTUREALPHA", TOP_BLENDTEXTUREALPHA},
    {"BLENDFACTORALPHA", TOP_BLENDFACTORALPHA},
    {"BLENDTEXTUREALPHAPM", TOP_BLENDTEXTUREALPHAPM},
    {"BLENDCURRENTALPHA", TOP_BLENDCURRENTALPHA}, {"PREMODULATE", TOP_PREMODULATE},
    {"MODULATEALPHA_ADDCOLOR", TOP_MODULATEALPHA_ADDCOLOR},
    {"MODULATECOLOR_ADDALPHA", TOP_MODULATECOLOR_ADDALPHA},
    {"MODULATEINVALPHA_ADDCOLOR", TOP_MODULATEINVALPHA_ADDCOLOR},
    {"MODULATEINVCOLOR_ADDALPHA", TOP_MODULATEINVCOLOR_ADDALPHA},
    {"BUMPENVMAP", TOP_BUMPENVMAP}, {"BUMPENVMAPLUMINANCE", TOP_BUMPENVMAPLUMINANCE},
    {"DOTPRODUCT3", TOP_DOTPRODUCT3}, {"MULTIPLYADD", TOP_MULTIPLYADD}, {"LERP", TOP_LERP},
};

// Register selectors first (enumName of a plain argument finds them), then modifiers.
constexpr NameValue kTextureArgs[] = {
    {"DIFFUSE", TA_DIFFUSE}, {"CURRENT", TA_CURRENT}, {"TEXTURE", TA_TEXTURE},
    {"TFACTOR", TA_TFACTOR}, {"SPECULAR", TA_SPECULAR}, {"TEMP", TA_TEMP},
    {"CONSTANT", TA_CONSTANT}, {"COMPLEMENT", TA_COMPLEMENT},
    {"ALPHAREPLICATE", TA_ALPHAREPLICATE},
};

constexpr NameValue kBlends[] = {
    {"ZERO", BLEND_ZERO}, {"ONE", BLEND_ONE}, {"SRCCOLOR", BLEND_SRCCOLOR},
    {"INVSRCCOLOR", BLEND_INVSRCCOLOR}, {"SRCALPHA", BLEND_SRCALPHA},
    {"INVSRCALPHA", BLEND_INVSRCALPHA}, {"DESTALPHA", BLEND_DESTALPHA},
    {"INVDESTALPHA", BLEND_INVDESTALPHA}, {"DESTCOLOR", BLEND_DESTCOLOR},
    {"INVDESTCOLOR", BLEND_INVDESTCOLOR}, {"SRCALPHASAT", BLEND_SRCALPHASAT},
    {"BOTHSRCALPHA", BLEND_BOTHSRCALPHA}, {"BOTHINVSRCALPHA", BLEND_BOTHINVSRCALPHA},
    {"BLENDFACTOR", BLEND_BLENDFACTOR}, {"INVBLENDFACTOR", BLEND_INVBLENDFACTOR},
};

constexpr NameValue kBlendOps[] = {
    {"ADD", BLENDOP_ADD}, {"SUBTRACT", BLENDOP_SUBTRACT}, {"REVSUBTRACT", BLENDOP_REVSUBTRACT},
    {"MIN", BLENDOP_MIN}, {"MAX", BLENDOP_MAX},
};

constexpr NameValue kCmpFuncs[] = {
    {"NEVER", CMP_NEVER}, {"LESS", CMP_LESS}, {"EQUAL", CMP_EQUAL},
    {"LESSEQUAL", CMP_LESSEQUAL}, {"GREATER", CMP_GREATER}, {"NOTEQUAL", CMP_NOTEQUAL},
    {"GREATEREQUAL", CMP_GREATEREQUAL}, {"ALWAYS", CMP_ALWAYS},
};

constexpr NameValue kStencilOps[] = {
    {"KEEP", STENCILOP_KEEP}, {"ZERO", STENCILOP_ZERO}, {"REPLACE", STENCILOP_REPLACE},
    {"INCRSAT", STENCILOP_INCRSAT}, {"DECRSAT", STENCILOP_DECRSAT},
    {"INVERT", STENCILOP_INVERT}, {"INCR", STENCILOP_INCR}, {"DECR", STENCILOP_DECR},
};

constexpr NameValue kCulls[] = {{"NONE", CULL_NONE}, {"CW", CULL_CW}, {"CCW", CULL_CCW}};
constexpr NameValue kFillModes[] = {
    {"POINT", FILL_POINT}, {"WIREFRAME", FILL_WIREFRAME}, {"SOLID", FILL_SOLID}};
constexpr NameValue kShadeModes[] = {
    {"FLAT", SHADE_FLAT}, {"GOURAUD", SHADE_GOURAUD}, {"PHONG", SHADE_PHONG}};
constexpr NameValue kFogModes[] = {
    {"NONE", FOG_NONE}, {"EXP", FOG_EXP}, {"EXP2", FOG_EXP2}, {"LINEAR", FOG_LINEAR}};
constexpr NameValue kZBufferTypes[] = {{"FALSE", ZB_FALSE}, {"TRUE", ZB_TRUE}, {"USEW", ZB_USEW}};
constexpr NameValue kMaterialColorSources[] = {
    {"MATERIAL", MCS_MATERIAL}, {"COLOR1", MCS_COLOR1}, {"COLOR2", MCS_COLOR2}};
// D3DTEXTUREADDRESS
constexpr NameValue kTextureAddresses[] = {
    {"WRAP", 1}, {"MIRROR", 2}, {"CLAMP", 3}, {"BORDER", 4}, {"MIRRORONCE", 5}};
// D3DTEXTUREFILTERTYPE
constexpr NameValue kTextureFilters[] = {
    {"NONE", 0}, {"POINT", 1}, {"LINEAR", 2}, {"ANISOTROPIC", 3}, {"PYRAMIDALQUAD", 6},
    {"GAUSSIANQUAD", 7}, {"CONVOLUTIONMONO", 8}};
constexpr NameValue kLightTypes[] = {
    {"POINT", LIGHT_POINT}, {"SPOT", LIGHT_SPOT}, {"DIRECTIONAL", LIGHT_DIRECTIONAL}};
constexpr NameValue kPrimitiveTypes[] = {
    {"POINTLIST", PT_POINTLIST}, {"LINELIST", PT_LINELIST}, {"LINESTRIP", PT_LINESTRIP},
    {"TRIANGLELIST", PT_TRIANGLELIST}, {"TRIANGLESTRIP", PT_TRIANGLESTRIP},
    {"TRIANGLEFAN", PT_TRIANGLEFAN}};
// D3DTS_WORLD is D3DTS_WORLDMATRIX(0) = 256; WORLD1-3 follow it.
constexpr NameValue kTransformTypes[] = {
    {"VIEW", TS_VIEW}, {"PROJECTION", TS_PROJECTION}, {"TEXTURE0", TS_TEXTURE0},
    {"TEXTURE1", TS_TEXTURE0 + 1}, {"TEXTURE2", TS_TEXTURE0 + 2},
    {"TEXTURE3", TS_TEXTURE0 + 3}, {"TEXTURE4", TS_TEXTURE0 + 4},
    {"TEXTURE5", TS_TEXTURE0 + 5}, {"TEXTURE6", TS_TEXTURE0 + 6},
    {"TEXTURE7", TS_TEXTURE0 + 7}, {"WORLD", TS_WORLD}, {"WORLD1", TS_WORLD + 1},
    {"WORLD2", TS_WORLD + 2}, {"WORLD3", TS_WORLD + 3}};
constexpr NameValue kBools[] = {{"FALSE", 0}, {"TRUE", 1}, {"0", 0}, {"1", 1}};
constexpr NameValue kTexCoordIndexFlags[] = {
    {"PASSTHRU", TCI_PASSTHRU}, {"CAMERASPACENORMAL", TCI_CAMERASPACENORMAL},
    {"CAMERASPACEPOSITION", TCI_CAMERASPACEPOSITION},
    {"CAMERASPACEREFLECTIONVECTOR", TCI_CAMERASPACEREFLECTIONVECTOR},
    {"SPHEREMAP", TCI_SPHEREMAP}};
constexpr NameValue kTextureTransformFlags[] = {
    {"DISABLE", TTFF_DISABLE}, {"COUNT1", TTFF_COUNT1}, {"COUNT2", TTFF_COUNT2},
    {"COUNT3", TTFF_COUNT3}, {"COUNT4", TTFF_COUNT4}, {"PROJECTED", TTFF_PROJECTED}};
constexpr NameValue kColorWrites[] = {
    {"RED", CW_RED}, {"GREEN", CW_GREEN}, {"BLUE", CW_BLUE}, {"ALPHA", CW_ALPHA}};
// D3DWRAP_U/V/W and their D3DWRAPCOORD_0-3 aliases (same bits, plus COORD_3 = 8).
constexpr NameValue kWraps[] = {{"U", 1}, {"V", 2}, {"W", 4}, {"COORD_0", 1},
                                {"COORD_1", 2}, {"COORD_2", 4}, {"COORD_3", 8}};
constexpr NameValue kVertexBlends[] = {
    {"DISABLE", VBF_DISABLE}, {"1WEIGHTS", VBF_1WEIGHTS}, {"2WEIGHTS", VBF_2WEIGHTS},
    {"3WEIGHTS", VBF_3WEIGHTS}, {"TWEENING", VBF_TWEENING}, {"0WEIGHTS", VBF_0WEIGHTS}};

struct KindInfo {
  std::span<const NameValue> names;
  std::string_view prefix;  // D3D name prefix accepted by parseEnum
  bool combinable;          // "A|B" ORs the values
};

KindInfo kindInfo(EnumKind kind) {
  switch (kind) {
    case EnumKind::RenderState: return {kRenderStates, "D3DRS_", false};
    case EnumKind::TextureStageState: return {kTextureStageStates, "D3DTSS_", false};
    case EnumKind::SamplerState: return {kSamplerStates, "D3DSAMP_", false};
    case EnumKind::TextureOp: return {kTextureOps, "D3DTOP_", false};
    case EnumKind::TextureArg: return {kTextureArgs, "D3DTA_", true};
    case EnumKind::Blend: return {kBlends, "D3DBLEND_", false};
    case EnumKind::BlendOp: return {kBlendOps, "D3DBLENDOP_", false};
    case EnumKind::CmpFunc: return {kCmpFuncs, "D3DCMP_", false};
    case EnumKind::StencilOp: return {kStencilOps, "D3DSTENCILOP_", false};
    case EnumKind::Cull: return {kCulls, "D3DCULL_", false};
    case EnumKind::FillMode: return {kFillModes, "D3DFILL_", false};
    case EnumKind::ShadeMode: return {kShadeModes, "D3DSHADE_", false};
    case EnumKind::FogMode: return {kFogModes, "D3DFOG_", false};
    case EnumKind::ZBufferType: return {kZBufferTypes, "D3DZB_", false};
    case EnumKind::MaterialColorSource: return {kMaterialColorSources, "D3DMCS_", false};
    case EnumKind::TextureAddress: return {kTextureAddresses, "D3DTADDRESS_", false};
    case EnumKind::TextureFilter: return {kTextureFilters, "D3DTEXF_", false};
    case EnumKind::LightType: return {kLightTypes, "D3DLIGHT_", false};
    case EnumKind::PrimitiveType: return {kPrimitiveTypes, "D3DPT_", false};
    case EnumKind::TransformType: return {kTransformTypes, "D3DTS_", false};
    case EnumKind::Bool: return {kBools, "", false};
    case EnumKind::TexCoordIndexFlags: return {kTexCoordIndexFlags, "D3DTSS_TCI_", true};
    case EnumKind::TextureTransformFlags: return {kTextureTransformFlags, "D3DTTFF_", true};
    case EnumKind::ColorWrite: return {kColorWrites, "D3DCOLORWRITEENABLE_", true};
    case EnumKind::Format: return {{}, "D3DFMT_", false};
    case EnumKind::Wrap: return {kWraps, "D3DWRAP_", true};
    case EnumKind::VertexBlend: return {kVertexBlends, "D3DVBF_", false};
  }
  return {{}, "", false};
}

std::optional<uint32_t> lookup(const KindInfo& info, std::string_view name) {
  if (!info.prefix.empty() && startsWithNoCase(name, info.prefix) &&
      name.size() > info.prefix.size())
    name.remove_prefix(info.prefix.size());
  for (const NameValue& nv : info.names)
    if (equalsNoCase(nv.name, name)) return nv.value;
  return std::nullopt;
}

// The texture coordinate index in "1|CAMERASPACENORMAL" (D3D allows 0-7).
std::optional<uint32_t> smallIndex(std::string_view s) {
  if (s.size() != 1 || s[0] < '0' || s[0] > '7') return std::nullopt;
  return uint32_t(s[0] - '0');
}

}  // namespace

std::string_view enumName(EnumKind kind, uint32_t value) {
  if (kind == EnumKind::Format) return formatName(static_cast<Format>(value));
  for (const NameValue& nv : kindInfo(kind).names)
    if (nv.value == value) return nv.name;
  return {};
}

std::optional<uint32_t> parseEnum(EnumKind kind, std::string_view name) {
  name = trim(name);
  if (name.empty()) return std::nullopt;
  if (kind == EnumKind::Format) {
    auto f = parseFormat(name);
    if (!f) return std::nullopt;
    return static_cast<uint32_t>(*f);
  }
  KindInfo info = kindInfo(kind);
  if (!info.combinable || name.find('|') == std::string_view::npos) {
    if (auto v = lookup(info, name)) return v;
    if (kind == EnumKind::TexCoordIndexFlags) return smallIndex(name);
    return std::nullopt;
  }
  uint32_t value = 0;
  while (true) {
    size_t bar = name.find('|');
    std::string_view part = trim(name.substr(0, bar));
    auto v = lookup(info, part);
    if (!v && kind == EnumKind::TexCoordIndexFlags) v = smallIndex(part);
    if (!v) return std::nullopt;
    value |= *v;
    if (bar == std::string_view::npos) break;
    name.remove_prefix(bar + 1);
  }
  return value;
}

namespace {

constexpr StateValueInfo kEnum(EnumKind k) { return {ValueKind::Enum, k}; }
constexpr StateValueInfo kFlags(EnumKind k) { return {ValueKind::Flags, k}; }
constexpr StateValueInfo kBool{ValueKind::Enum, EnumKind::Bool};
constexpr StateValueInfo kUint{ValueKind::Uint, EnumKind::Bool};
constexpr StateValueInfo kFloat{ValueKind::Float, EnumKind::Bool};
constexpr StateValueInfo kColor{ValueKind::Color, EnumKind::Bool};

struct StateValue {
  uint32_t state;
  StateValueInfo info;
};

constexpr StateValue kRenderStateValues[] = {
    {RS_ZENABLE, kEnum(EnumKind::ZBufferType)}, {RS_FILLMODE, kEnum(EnumKind::FillMode)},
    {RS_SHADEMODE, kEnum(EnumKind::ShadeMode)}, {RS_ZWRITEENABLE, kBool},
    {RS_ALPHATESTENABLE, kBool}, {RS_LASTPIXEL, kBool},
    {RS_SRCBLEND, kEnum(EnumKind::Blend)}, {RS_DESTBLEND, kEnum(EnumKind::Blend)},
    {RS_CULLMODE, kEnum(EnumKind::Cull)}, {RS_ZFUNC, kEnum(EnumKind::CmpFunc)},
    {RS_ALPHAREF, kUint}, {RS_ALPHAFUNC, kEnum(EnumKind::CmpFunc)},
    {RS_DITHERENABLE, kBool}, {RS_ALPHABLENDENABLE, kBool}, {RS_FOGENABLE, kBool},
    {RS_SPECULARENABLE, kBool}, {RS_FOGCOLOR, kColor},
    {RS_FOGTABLEMODE, kEnum(EnumKind::FogMode)}, {RS_FOGSTART, kFloat}, {RS_FOGEND, kFloat},
    {RS_FOGDENSITY, kFloat}, {RS_RANGEFOGENABLE, kBool}, {RS_STENCILENABLE, kBool},
    {RS_STENCILFAIL, kEnum(EnumKind::StencilOp)}, {RS_STENCILZFAIL, kEnum(EnumKind::StencilOp)},
    {RS_STENCILPASS, kEnum(EnumKind::StencilOp)}, {RS_STENCILFUNC, kEnum(EnumKind::CmpFunc)},
    {RS_STENCILREF, kUint}, {RS_STENCILMASK, kUint}, {RS_STENCILWRITEMASK, kUint},
    {RS_TEXTUREFACTOR, kColor}, {RS_CLIPPING, kBool}, {RS_LIGHTING, kBool},
    {RS_AMBIENT, kColor}, {RS_FOGVERTEXMODE, kEnum(EnumKind::FogMode)},
    {RS_COLORVERTEX, kBool}, {RS_LOCALVIEWER, kBool}, {RS_NORMALIZENORMALS, kBool},
    {RS_DIFFUSEMATERIALSOURCE, kEnum(EnumKind::MaterialColorSource)},
    {RS_SPECULARMATERIALSOURCE, kEnum(EnumKind::MaterialColorSource)},
    {RS_AMBIENTMATERIALSOURCE, kEnum(EnumKind::MaterialColorSource)},
    {RS_EMISSIVEMATERIALSOURCE, kEnum(EnumKind::MaterialColorSource)},
    {RS_VERTEXBLEND, kEnum(EnumKind::VertexBlend)}, {RS_CLIPPLANEENABLE, kUint}, {RS_POINTSIZE, kFloat},
    {RS_POINTSIZE_MIN, kFloat}, {RS_POINTSPRITEENABLE, kBool}, {RS_POINTSCALEENABLE, kBool},
    {RS_POINTSCALE_A, kFloat}, {RS_POINTSCALE_B, kFloat}, {RS_POINTSCALE_C, kFloat},
    {RS_MULTISAMPLEANTIALIAS, kBool}, {RS_MULTISAMPLEMASK, kUint},
    {RS_PATCHEDGESTYLE, kUint}, {RS_DEBUGMONITORTOKEN, kUint}, {RS_POINTSIZE_MAX, kFloat},
    {RS_INDEXEDVERTEXBLENDENABLE, kBool},
    {RS_COLORWRITEENABLE, kFlags(EnumKind::ColorWrite)}, {RS_TWEENFACTOR, kFloat},
    {RS_BLENDOP, kEnum(EnumKind::BlendOp)}, {RS_POSITIONDEGREE, kUint},
    {RS_NORMALDEGREE, kUint}, {RS_SCISSORTESTENABLE, kBool},
    {RS_SLOPESCALEDEPTHBIAS, kFloat}, {RS_ANTIALIASEDLINEENABLE, kBool},
    {RS_MINTESSELLATIONLEVEL, kFloat}, {RS_MAXTESSELLATIONLEVEL, kFloat},
    {RS_ADAPTIVETESS_X, kFloat}, {RS_ADAPTIVETESS_Y, kFloat}, {RS_ADAPTIVETESS_Z, kFloat},
    {RS_ADAPTIVETESS_W, kFloat}, {RS_ENABLEADAPTIVETESSELLATION, kBool},
    {RS_TWOSIDEDSTENCILMODE, kBool}, {RS_CCW_STENCILFAIL, kEnum(EnumKind::StencilOp)},
    {RS_CCW_STENCILZFAIL, kEnum(EnumKind::StencilOp)},
    {RS_CCW_STENCILPASS, kEnum(EnumKind::StencilOp)},
    {RS_CCW_STENCILFUNC, kEnum(EnumKind::CmpFunc)},
    {RS_COLORWRITEENABLE1, kFlags(EnumKind::ColorWrite)},
    {RS_COLORWRITEENABLE2, kFlags(EnumKind::ColorWrite)},
    {RS_COLORWRITEENABLE3, kFlags(EnumKind::ColorWrite)}, {RS_BLENDFACTOR, kColor},
    {RS_SRGBWRITEENABLE, kBool}, {RS_DEPTHBIAS, kFloat},
    {RS_SEPARATEALPHABLENDENABLE, kBool}, {RS_SRCBLENDALPHA, kEnum(EnumKind::Blend)},
    {RS_DESTBLENDALPHA, kEnum(EnumKind::Blend)}, {RS_BLENDOPALPHA, kEnum(EnumKind::BlendOp)},
};

// Arguments are a register selector OR'ed with COMPLEMENT / ALPHAREPLICATE.
constexpr StateValue kTextureStageStateValues[] = {
    {TSS_COLOROP, kEnum(EnumKind::TextureOp)}, {TSS_ALPHAOP, kEnum(EnumKind::TextureOp)},
    {TSS_COLORARG0, kFlags(EnumKind::TextureArg)}, {TSS_COLORARG1, kFlags(EnumKind::TextureArg)},
    {TSS_COLORARG2, kFlags(EnumKind::TextureArg)}, {TSS_ALPHAARG0, kFlags(EnumKind::TextureArg)},
    {TSS_ALPHAARG1, kFlags(EnumKind::TextureArg)}, {TSS_ALPHAARG2, kFlags(EnumKind::TextureArg)},
    {TSS_RESULTARG, kFlags(EnumKind::TextureArg)}, {TSS_BUMPENVMAT00, kFloat},
    {TSS_BUMPENVMAT01, kFloat}, {TSS_BUMPENVMAT10, kFloat}, {TSS_BUMPENVMAT11, kFloat},
    {TSS_BUMPENVLSCALE, kFloat}, {TSS_BUMPENVLOFFSET, kFloat},
    // Coordinate set index in the low half, D3DTSS_TCI_* generation mode in the high half.
    {TSS_TEXCOORDINDEX, {ValueKind::Uint, EnumKind::TexCoordIndexFlags}},
    {TSS_TEXTURETRANSFORMFLAGS, kFlags(EnumKind::TextureTransformFlags)},
    {TSS_CONSTANT, kColor},
};

constexpr StateValue kSamplerStateValues[] = {
    {SAMP_ADDRESSU, kEnum(EnumKind::TextureAddress)},
    {SAMP_ADDRESSV, kEnum(EnumKind::TextureAddress)},
    {SAMP_ADDRESSW, kEnum(EnumKind::TextureAddress)}, {SAMP_BORDERCOLOR, kColor},
    {SAMP_MAGFILTER, kEnum(EnumKind::TextureFilter)},
    {SAMP_MINFILTER, kEnum(EnumKind::TextureFilter)},
    {SAMP_MIPFILTER, kEnum(EnumKind::TextureFilter)}, {SAMP_MIPMAPLODBIAS, kFloat},
    {SAMP_MAXMIPLEVEL, kUint}, {SAMP_MAXANISOTROPY, kUint}, {SAMP_SRGBTEXTURE, kBool},
    {SAMP_ELEMENTINDEX, kUint}, {SAMP_DMAPOFFSET, kUint},
};

StateValueInfo findValue(std::span<const StateValue> table, uint32_t state) {
  for (const StateValue& sv : table)
    if (sv.state == state) return sv.info;
  // D3DRS_WRAP0-7 (128-135) and WRAP8-15 (198-205): D3DWRAP_* flags.
  if ((state >= RS_WRAP0 && state < RS_WRAP0 + 8) || (state >= RS_WRAP8 && state < RS_WRAP8 + 8))
    return kFlags(EnumKind::Wrap);
  return kUint;  // unknown states: a plain number
}

}  // namespace

StateValueInfo renderStateValue(uint32_t state) { return findValue(kRenderStateValues, state); }
StateValueInfo textureStageStateValue(uint32_t state) {
  return findValue(kTextureStageStateValues, state);
}
StateValueInfo samplerStateValue(uint32_t state) {
  return findValue(kSamplerStateValues, state);
}

}  // namespace refx::d3d
