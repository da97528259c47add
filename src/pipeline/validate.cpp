// ValidateDevice for the shaders (their versions and constants against the profile,
// and the version rules of the shader layer), the fixed-function texture cascade,
// bound textures (their sizes, mipmaps and power-of-two shapes against TextureCaps)
// and the sampler states of the samplers in use, the fixed-function
// vertex limits (lights, vertex blending), clip planes, point size, raster states,
// render targets and the output merger. With a pixel shader bound the texture stage
// cascade is not used and is not checked. Every reason names the caps field (and
// flag) that is missing.
#include "validate.h"

#include "caps_flags.h"
#include "texture_op_use.h"

#include <algorithm>
#include <bit>
#include <optional>

#include "refx/core/diagnostics.h"
#include "refx/pipeline/caps.h"
#include "refx/pipeline/d3d9types.h"
#include "refx/pipeline/shader_object.h"
#include "refx/pipeline/state.h"

namespace refx {

using namespace d3d;

namespace {

// A caps bit with its flag name, for the reasons (the names and bits of caps_flags.h).
using CapBit = caps_flags::FlagBit;
using caps_flags::flag;

// D3DPMISCCAPS_* and D3DPTEXTURECAPS_* bits the checks below read.
constexpr uint32_t kMiscTssArgTemp = flag(caps_flags::kMiscCaps, "TSSARGTEMP").bit;
constexpr uint32_t kMiscBlendOp = flag(caps_flags::kMiscCaps, "BLENDOP").bit;
constexpr uint32_t kMiscPerStageConstant = flag(caps_flags::kMiscCaps, "PERSTAGECONSTANT").bit;
constexpr uint32_t kMiscSeparateAlphaBlend = flag(caps_flags::kMiscCaps, "SEPARATEALPHABLEND").bit;
constexpr uint32_t kTexCapsCubeMap = flag(caps_flags::kTextureCaps, "CUBEMAP").bit;
constexpr uint32_t kTexCapsVolumeMap = flag(caps_flags::kTextureCaps, "VOLUMEMAP").bit;
constexpr uint32_t kTexCapsPow2 = flag(caps_flags::kTextureCaps, "POW2").bit;
constexpr uint32_t kTexCapsNonPow2Conditional = flag(caps_flags::kTextureCaps, "NONPOW2CONDITIONAL").bit;
constexpr uint32_t kTexCapsProjected = flag(caps_flags::kTextureCaps, "PROJECTED").bit;
constexpr uint32_t kTexCapsCubeMapPow2 = flag(caps_flags::kTextureCaps, "CUBEMAP_POW2").bit;
constexpr uint32_t kTexCapsVolumeMapPow2 = flag(caps_flags::kTextureCaps, "VOLUMEMAP_POW2").bit;
constexpr CapBit kTexCapsMipMap = flag(caps_flags::kTextureCaps, "MIPMAP");
constexpr CapBit kTexCapsMipVolumeMap = flag(caps_flags::kTextureCaps, "MIPVOLUMEMAP");
constexpr CapBit kTexCapsMipCubeMap = flag(caps_flags::kTextureCaps, "MIPCUBEMAP");
constexpr uint32_t kMiscMaskZ = flag(caps_flags::kMiscCaps, "MASKZ").bit;
constexpr uint32_t kMiscCullNone = flag(caps_flags::kMiscCaps, "CULLNONE").bit;
constexpr uint32_t kMiscCullCW = flag(caps_flags::kMiscCaps, "CULLCW").bit;
constexpr uint32_t kMiscCullCCW = flag(caps_flags::kMiscCaps, "CULLCCW").bit;
constexpr uint32_t kMiscColorWriteEnable = flag(caps_flags::kMiscCaps, "COLORWRITEENABLE").bit;
constexpr uint32_t kMiscIndependentWriteMasks = flag(caps_flags::kMiscCaps, "INDEPENDENTWRITEMASKS").bit;
constexpr uint32_t kMiscMrtPostPixelShaderBlending = flag(caps_flags::kMiscCaps, "MRTPOSTPIXELSHADERBLENDING").bit;
constexpr uint32_t kMiscMrtIndependentBitDepths = flag(caps_flags::kMiscCaps, "MRTINDEPENDENTBITDEPTHS").bit;
constexpr uint32_t kAddressIndependentUV = flag(caps_flags::kAddressCaps, "INDEPENDENTUV").bit;

// D3DPRASTERCAPS_* bits.
constexpr CapBit kRasterDither = flag(caps_flags::kRasterCaps, "DITHER");
constexpr CapBit kRasterZTest = flag(caps_flags::kRasterCaps, "ZTEST");
constexpr CapBit kRasterFogVertex = flag(caps_flags::kRasterCaps, "FOGVERTEX");
constexpr CapBit kRasterFogTable = flag(caps_flags::kRasterCaps, "FOGTABLE");
constexpr CapBit kRasterMipMapLodBias = flag(caps_flags::kRasterCaps, "MIPMAPLODBIAS");
constexpr CapBit kRasterFogRange = flag(caps_flags::kRasterCaps, "FOGRANGE");
constexpr CapBit kRasterAnisotropy = flag(caps_flags::kRasterCaps, "ANISOTROPY");
constexpr CapBit kRasterWBuffer = flag(caps_flags::kRasterCaps, "WBUFFER");
constexpr CapBit kRasterScissorTest = flag(caps_flags::kRasterCaps, "SCISSORTEST");
constexpr CapBit kRasterSlopeScaleDepthBias = flag(caps_flags::kRasterCaps, "SLOPESCALEDEPTHBIAS");
constexpr CapBit kRasterDepthBias = flag(caps_flags::kRasterCaps, "DEPTHBIAS");

// D3DTEXTUREFILTERTYPE and the D3DPTFILTERCAPS_* bit each needs as MIN and MAG filter.
struct FilterCaps {
  uint32_t filter;
  CapBit min, mag;
};
constexpr FilterCaps kFilterCaps[] = {
    {1, flag(caps_flags::kFilterCaps, "MINFPOINT"), flag(caps_flags::kFilterCaps, "MAGFPOINT")},
    {2, flag(caps_flags::kFilterCaps, "MINFLINEAR"), flag(caps_flags::kFilterCaps, "MAGFLINEAR")},
    {3, flag(caps_flags::kFilterCaps, "MINFANISOTROPIC"), flag(caps_flags::kFilterCaps, "MAGFANISOTROPIC")},
    {6, flag(caps_flags::kFilterCaps, "MINFPYRAMIDALQUAD"), flag(caps_flags::kFilterCaps, "MAGFPYRAMIDALQUAD")},
    {7, flag(caps_flags::kFilterCaps, "MINFGAUSSIANQUAD"), flag(caps_flags::kFilterCaps, "MAGFGAUSSIANQUAD")},
    {8, flag(caps_flags::kFilterCaps, "CONVOLUTIONMONO"), flag(caps_flags::kFilterCaps, "CONVOLUTIONMONO")},
};
constexpr uint32_t kFilterNone = 0, kFilterPoint = 1, kFilterLinear = 2, kFilterAnisotropic = 3;
constexpr CapBit kMipFilterPoint = flag(caps_flags::kFilterCaps, "MIPFPOINT");
constexpr CapBit kMipFilterLinear = flag(caps_flags::kFilterCaps, "MIPFLINEAR");

// D3DTEXTUREADDRESS (WRAP 1 .. MIRRORONCE 5) -> D3DPTADDRESSCAPS_* bit.
constexpr CapBit kAddressCaps[] = {
    flag(caps_flags::kAddressCaps, "WRAP"), flag(caps_flags::kAddressCaps, "MIRROR"),
    flag(caps_flags::kAddressCaps, "CLAMP"), flag(caps_flags::kAddressCaps, "BORDER"),
    flag(caps_flags::kAddressCaps, "MIRRORONCE")};


// ps_1_x texture instructions that sample the texture of the stage their
// destination register names (t# in 1.0-1.3, r# for texld in 1.4).
bool samplesDestinationStage(shader::Opcode op) {
  using shader::Opcode;
  switch (op) {
    case Opcode::Tex: case Opcode::TexBem: case Opcode::TexBemL: case Opcode::TexReg2AR:
    case Opcode::TexReg2GB: case Opcode::TexReg2RGB: case Opcode::TexM3x2Tex:
    case Opcode::TexM3x3Tex: case Opcode::TexM3x3Spec: case Opcode::TexM3x3VSpec:
    case Opcode::TexDP3Tex:
      return true;
    default: return false;
  }
}

// Bit n: sampler register s#n is declared or read (ps_2_0+, vs_3_0), or texture
// stage n is sampled (ps_1_x).
uint32_t shaderSamplers(const ShaderObject& sh) {
  uint32_t used = 0;
  const bool ps1 = sh.version().isPixel() && sh.version().major < 2;
  for (const shader::Instruction& in : sh.decoded().instructions) {
    if (ps1) {
      if (samplesDestinationStage(in.opcode) && in.dst.index < 32) used |= 1u << in.dst.index;
      continue;
    }
    if (in.dst.type == shader::RegType::Sampler && in.dst.index < 32) used |= 1u << in.dst.index;
    for (int i = 0; i < in.srcCount; ++i)
      if (in.src[i].type == shader::RegType::Sampler && in.src[i].index < 32)
        used |= 1u << in.src[i].index;
  }
  return used;
}

std::string nameOr(EnumKind kind, uint32_t value) {
  std::string_view n = enumName(kind, value);
  return n.empty() ? std::to_string(value) : std::string(n);
}

std::string stateName(TextureStageState s) { return nameOr(EnumKind::TextureStageState, s); }
std::string renderStateName(RenderState s) { return nameOr(EnumKind::RenderState, s); }

bool isPow2(int n) { return n > 0 && (n & (n - 1)) == 0; }

// The TextureOpCaps bit of a D3DTOP (0 for a value that is none).
uint32_t opCapsBit(uint32_t op) {
  return caps_flags::bitOf(caps_flags::kTextureOpCaps, enumName(EnumKind::TextureOp, op));
}
// The SrcBlendCaps/DestBlendCaps bit of a D3DBLEND; INVBLENDFACTOR shares BLENDFACTOR's.
uint32_t blendCapsBit(uint32_t blend) {
  if (blend == BLEND_INVBLENDFACTOR) blend = BLEND_BLENDFACTOR;
  return caps_flags::bitOf(caps_flags::kBlendCaps, enumName(EnumKind::Blend, blend));
}

class Validator {
 public:
  Validator(const DeviceState& state, const CapsProfile& caps, const RenderTargetBinding& targets)
      : s_(state), caps_(caps), targets_(targets) {}

  std::optional<std::string> run() {
    if (s_.vertexShader)
      if (auto r = shaderProgram(*s_.vertexShader, caps_.vertexShaderVersion)) return r;
    if (s_.pixelShader)
      if (auto r = shaderProgram(*s_.pixelShader, caps_.pixelShaderVersion)) return r;
    // Shader model 3 pixel shaders read vs_3_0 outputs by semantic only.
    if (s_.pixelShader && s_.pixelShader->version().atLeast(3, 0) &&
        (!s_.vertexShader || !s_.vertexShader->version().atLeast(3, 0)))
      return fmt::format("pixel shader {} needs a vs_3_0 vertex shader, not {}",
                         s_.pixelShader->version().name(),
                         s_.vertexShader ? s_.vertexShader->version().name()
                                         : std::string("fixed-function vertex processing"));
    if (!s_.pixelShader)
      if (auto r = stages()) return r;
    if (auto r = textures()) return r;
    if (auto r = samplers()) return r;
    if (!s_.vertexShader)
      if (auto r = fixedFunctionVertex()) return r;
    if (auto r = clipPlanesAndPoints()) return r;
    if (auto r = raster()) return r;
    if (auto r = blending()) return r;
    if (auto r = renderTargets()) return r;
    return std::nullopt;
  }

 private:
  const DeviceState& s_;
  const CapsProfile& caps_;
  const RenderTargetBinding& targets_;
  uint32_t stagesSampled_ = 0;  // fixed function: bit n = stage n reads its texture

  bool misc(uint32_t bit) const { return (caps_.primitiveMiscCaps & bit) != 0; }
  bool rasterCap(CapBit cap) const { return (caps_.rasterCaps & cap.bit) != 0; }
  std::string needsRaster(std::string_view what, CapBit cap) const {
    return fmt::format("{} needs {} in RasterCaps of {}", what, cap.name, caps_.name);
  }

  // "pixel shader ps_1_4 needs PixelShaderVersion 1.4; dx8 has 1.1"
  std::optional<std::string> shaderProgram(const ShaderObject& sh, uint32_t capsVersion) {
    const shader::Version v = sh.version();
    const bool pixel = v.isPixel();
    const char* kind = pixel ? "pixel" : "vertex";
    const char* field = pixel ? "PixelShaderVersion" : "VertexShaderVersion";
    const bool hasShaders = (capsVersion & 0xffff) != 0;
    const int capsMajor = int((capsVersion >> 8) & 0xff), capsMinor = int(capsVersion & 0xff);
    // ps_2_x / vs_2_x (minor 1) run on 2.0 parts with the extended caps.
    const int needMinor = v.major == 2 ? 0 : v.minor;
    if (!hasShaders || capsMajor < v.major || (capsMajor == v.major && capsMinor < needMinor)) {
      std::string has = hasShaders ? fmt::format("{}.{}", capsMajor, capsMinor) : "none";
      return fmt::format("{} shader {} needs {} {}.{}; {} has {}", kind, v.name(), field,
                         int(v.major), needMinor, caps_.name, has);
    }
    const shader::ValidationCaps vc = shaderValidationCaps(caps_);
    if (!pixel) {
      // Constant registers addressed directly (relative reads are checked when run).
      int highest = -1;
      for (const shader::Instruction& in : sh.decoded().instructions) {
        if (in.opcode == shader::Opcode::Def && in.dst.type == shader::RegType::Const)
          highest = std::max(highest, int(in.dst.index));
        for (int i = 0; i < in.srcCount; ++i)
          if (in.src[i].type == shader::RegType::Const && !in.src[i].relative)
            highest = std::max(highest, int(in.src[i].index));
      }
      const int limit = caps_.maxVertexShaderConst ? int(caps_.maxVertexShaderConst) : 96;
      if (highest >= limit)
        return fmt::format("vertex shader {} uses c{} but {} has MaxVertexShaderConst {}",
                           v.name(), highest, caps_.name, limit);
    }
    const std::vector<Diagnostic> problems = shader::validate(sh.decoded(), vc);
    if (!problems.empty())
      return fmt::format("{} shader {}: {}", kind, v.name(), problems.front().message);
    return std::nullopt;
  }

  std::optional<std::string> stages() {
    uint32_t texturesUsed = 0;
    for (int n = 0; n < kMaxTextureStages; ++n) {
      uint32_t colorOp = s_.tss(n, TSS_COLOROP);
      if (colorOp == TOP_DISABLE) break;
      if (uint32_t(n) >= caps_.maxTextureBlendStages)
        return fmt::format("stage {} is enabled but {} has MaxTextureBlendStages {}", n,
                           caps_.name, caps_.maxTextureBlendStages);
      bool usesTexture = false;
      if (auto r = operation(n, TSS_COLOROP, TSS_COLORARG0, TSS_COLORARG1, TSS_COLORARG2,
                             usesTexture))
        return r;
      // ALPHAOP DISABLE with COLOROP enabled passes CURRENT alpha through.
      if (s_.tss(n, TSS_ALPHAOP) != TOP_DISABLE)
        if (auto r = operation(n, TSS_ALPHAOP, TSS_ALPHAARG0, TSS_ALPHAARG1, TSS_ALPHAARG2,
                               usesTexture))
          return r;
      uint32_t result = s_.tss(n, TSS_RESULTARG) & ~uint32_t(TA_COMPLEMENT | TA_ALPHAREPLICATE);
      if (result != TA_CURRENT && result != TA_TEMP)
        return fmt::format("stage {} RESULTARG {} must be CURRENT or TEMP", n,
                           nameOr(EnumKind::TextureArg, result));
      if (result == TA_TEMP && !misc(kMiscTssArgTemp))
        return fmt::format("stage {} RESULTARG TEMP needs TSSARGTEMP in PrimitiveMiscCaps of {}",
                           n, caps_.name);
      // Fixed function: stage n samples the texture bound to sampler n.
      if (usesTexture) stagesSampled_ |= 1u << n;
      if (usesTexture && (s_.tss(n, TSS_TEXTURETRANSFORMFLAGS) & TTFF_PROJECTED) &&
          !(caps_.textureCaps & kTexCapsProjected))
        return fmt::format("stage {} TEXTURETRANSFORMFLAGS PROJECTED needs PROJECTED in "
                           "TextureCaps of {}",
                           n, caps_.name);
      if (usesTexture && ++texturesUsed > caps_.maxSimultaneousTextures)
        return fmt::format(
            "stage {} is stage number {} to use a texture but {} has MaxSimultaneousTextures {}",
            n, texturesUsed, caps_.name, caps_.maxSimultaneousTextures);
    }
    return std::nullopt;
  }

  std::optional<std::string> operation(int n, TextureStageState opState, TextureStageState a0,
                                       TextureStageState a1, TextureStageState a2,
                                       bool& usesTexture) {
    uint32_t op = s_.tss(n, opState);
    const pipeline::TextureOpUse use = pipeline::textureOpUse(op);
    if (!use.valid)
      return fmt::format("stage {} {} {} is not a D3DTEXTUREOP", n, stateName(opState), op);
    std::string opName = nameOr(EnumKind::TextureOp, op);
    if (use.colorOnly && opState == TSS_ALPHAOP)
      return fmt::format("stage {} ALPHAOP {} is a color-only operation", n, opName);
    if (!(caps_.textureOpCaps & opCapsBit(op)))
      return fmt::format("stage {} {} {} is not in TextureOpCaps of {}", n, stateName(opState),
                         opName, caps_.name);
    usesTexture |= use.ownTexture;
    const std::pair<bool, TextureStageState> args[] = {{use.arg0, a0}, {use.arg1, a1},
                                                       {use.arg2, a2}};
    for (auto [read, argState] : args) {
      if (!read) continue;
      uint32_t reg = s_.tss(n, argState) & TA_SELECTMASK;
      if (reg > TA_CONSTANT)
        return fmt::format("stage {} {} {} is not a D3DTA register", n, stateName(argState),
                           reg);
      if (reg == TA_TEXTURE) usesTexture = true;
      if (reg == TA_TEMP && !misc(kMiscTssArgTemp))
        return fmt::format("stage {} {} TEMP needs TSSARGTEMP in PrimitiveMiscCaps of {}", n,
                           stateName(argState), caps_.name);
      if (reg == TA_CONSTANT && !misc(kMiscPerStageConstant))
        return fmt::format(
            "stage {} {} CONSTANT needs PERSTAGECONSTANT in PrimitiveMiscCaps of {}", n,
            stateName(argState), caps_.name);
    }
    return std::nullopt;
  }

  std::optional<std::string> textures() {
    for (int i = 0; i < kMaxSamplers; ++i) {
      const TexturePtr& tex = s_.textures[i];
      if (!tex) continue;
      std::string sampler = i < kVertexSampler0
                                ? fmt::format("sampler {}", i)
                                : fmt::format("vertex sampler {}", i - kVertexSampler0);
      if (i >= kVertexSampler0 && caps_.vertexTextureFilterCaps == 0)
        return fmt::format(
            "{} has a texture but {} has no vertex texture fetch (VertexTextureFilterCaps 0)",
            sampler, caps_.name);
      switch (tex->type()) {
        case TextureType::Texture2D:
        case TextureType::Cube:
          if (tex->type() == TextureType::Cube && !(caps_.textureCaps & kTexCapsCubeMap))
            return fmt::format("{} has a cube texture but {} lacks CUBEMAP in TextureCaps",
                               sampler, caps_.name);
          if (uint32_t(tex->width()) > caps_.maxTextureWidth)
            return fmt::format("{} texture is {}x{} but {} has MaxTextureWidth {}", sampler,
                               tex->width(), tex->height(), caps_.name, caps_.maxTextureWidth);
          if (uint32_t(tex->height()) > caps_.maxTextureHeight)
            return fmt::format("{} texture is {}x{} but {} has MaxTextureHeight {}", sampler,
                               tex->width(), tex->height(), caps_.name, caps_.maxTextureHeight);
          break;
        case TextureType::Volume: {
          if (!(caps_.textureCaps & kTexCapsVolumeMap))
            return fmt::format("{} has a volume texture but {} lacks VOLUMEMAP in TextureCaps",
                               sampler, caps_.name);
          uint32_t extent = uint32_t(std::max({tex->width(), tex->height(), tex->depth()}));
          if (extent > caps_.maxVolumeExtent)
            return fmt::format("{} volume texture is {}x{}x{} but {} has MaxVolumeExtent {}",
                               sampler, tex->width(), tex->height(), tex->depth(), caps_.name,
                               caps_.maxVolumeExtent);
          break;
        }
      }
    }
    return std::nullopt;
  }

  // Samplers the active stages or shaders read: fixed-function stages (a PREMODULATE
  // or bump stage's successor reads its texture through its arguments), the pixel
  // shader's samplers, and vs_3_0's vertex samplers.
  uint32_t samplersInUse() const {
    uint32_t used = s_.pixelShader ? shaderSamplers(*s_.pixelShader) : stagesSampled_;
    used &= (1u << kMaxPixelSamplers) - 1;
    if (s_.vertexShader && s_.vertexShader->version().atLeast(3, 0))
      used |= (shaderSamplers(*s_.vertexShader) & 0xf) << kVertexSampler0;
    return used;
  }

  // "sampler 0 MINFILTER ANISOTROPIC needs MINFANISOTROPIC in TextureFilterCaps of dx6-tnt2"
  std::optional<std::string> samplers() {
    const uint32_t used = samplersInUse();
    for (int i = 0; i < kMaxSamplers; ++i) {
      const TexturePtr& tex = s_.textures[i];
      if (!tex || !(used & (1u << i))) continue;
      const bool vertex = i >= kVertexSampler0;
      const std::string sampler = vertex ? fmt::format("vertex sampler {}", i - kVertexSampler0)
                                         : fmt::format("sampler {}", i);
      uint32_t filterCaps = caps_.textureFilterCaps;
      std::string_view field = "TextureFilterCaps";
      if (vertex) {
        filterCaps = caps_.vertexTextureFilterCaps;
        field = "VertexTextureFilterCaps";
      } else if (tex->type() == TextureType::Cube) {
        filterCaps = caps_.cubeTextureFilterCaps;
        field = "CubeTextureFilterCaps";
      } else if (tex->type() == TextureType::Volume) {
        filterCaps = caps_.volumeTextureFilterCaps;
        field = "VolumeTextureFilterCaps";
      }
      for (SamplerStateType state : {SAMP_MINFILTER, SAMP_MAGFILTER}) {
        const uint32_t filter = s_.samp(i, state);
        if (filter == kFilterNone) continue;  // sampled as POINT
        const FilterCaps* row = nullptr;
        for (const FilterCaps& f : kFilterCaps)
          if (f.filter == filter) row = &f;
        const std::string stateName = nameOr(EnumKind::SamplerState, state);
        if (!row)
          return fmt::format("{} {} {} is not a D3DTEXTUREFILTERTYPE", sampler, stateName, filter);
        const CapBit need = state == SAMP_MINFILTER ? row->min : row->mag;
        if (!(filterCaps & need.bit))
          return fmt::format("{} {} {} needs {} in {} of {}", sampler, stateName,
                             nameOr(EnumKind::TextureFilter, filter), need.name, field,
                             caps_.name);
      }
      const uint32_t mip = s_.samp(i, SAMP_MIPFILTER);
      if (mip != kFilterNone) {
        if (mip != kFilterPoint && mip != kFilterLinear)
          return fmt::format("{} MIPFILTER {} is not a mip filter (NONE, POINT or LINEAR)",
                             sampler, nameOr(EnumKind::TextureFilter, mip));
        const CapBit need = mip == kFilterPoint ? kMipFilterPoint : kMipFilterLinear;
        if (!(filterCaps & need.bit))
          return fmt::format("{} MIPFILTER {} needs {} in {} of {}", sampler,
                             nameOr(EnumKind::TextureFilter, mip), need.name, field, caps_.name);
      }
      if (s_.samp(i, SAMP_MINFILTER) == kFilterAnisotropic ||
          s_.samp(i, SAMP_MAGFILTER) == kFilterAnisotropic) {
        if (!rasterCap(kRasterAnisotropy))
          return needsRaster(sampler + " ANISOTROPIC filtering", kRasterAnisotropy);
        const uint32_t maxAniso = s_.samp(i, SAMP_MAXANISOTROPY);
        if (maxAniso > caps_.maxAnisotropy)
          return fmt::format("{} MAXANISOTROPY {} exceeds MaxAnisotropy {} of {}", sampler,
                             maxAniso, caps_.maxAnisotropy, caps_.name);
      }
      if (bitsFloat(s_.samp(i, SAMP_MIPMAPLODBIAS)) != 0.0f && !rasterCap(kRasterMipMapLodBias))
        return needsRaster(fmt::format("{} MIPMAPLODBIAS {}", sampler,
                                       bitsFloat(s_.samp(i, SAMP_MIPMAPLODBIAS))),
                           kRasterMipMapLodBias);
      if (auto r = addressing(i, sampler, tex->type() == TextureType::Volume)) return r;
      if (auto r = textureShape(i, sampler, *tex)) return r;
    }
    return std::nullopt;
  }

  // Mipmaps and power-of-two sizes against TextureCaps.
  std::optional<std::string> textureShape(int i, const std::string& sampler, const Texture& tex) {
    const bool mipmapped = tex.levelCount() > 1 && s_.samp(i, SAMP_MIPFILTER) != kFilterNone;
    const CapBit mipCap = tex.type() == TextureType::Cube     ? kTexCapsMipCubeMap
                          : tex.type() == TextureType::Volume ? kTexCapsMipVolumeMap
                                                              : kTexCapsMipMap;
    if (mipmapped && !(caps_.textureCaps & mipCap.bit))
      return fmt::format("{} mipmapped texture ({} levels, MIPFILTER {}) needs {} in TextureCaps "
                         "of {}",
                         sampler, tex.levelCount(),
                         nameOr(EnumKind::TextureFilter, s_.samp(i, SAMP_MIPFILTER)),
                         mipCap.name, caps_.name);
    const bool pow2 = isPow2(tex.width()) && isPow2(tex.height()) &&
                      (tex.type() != TextureType::Volume || isPow2(tex.depth()));
    if (pow2) return std::nullopt;
    if (tex.type() == TextureType::Cube && (caps_.textureCaps & kTexCapsCubeMapPow2))
      return fmt::format("{} cube texture is {} texels wide but {} has CUBEMAP_POW2 in TextureCaps",
                         sampler, tex.width(), caps_.name);
    if (tex.type() == TextureType::Volume && (caps_.textureCaps & kTexCapsVolumeMapPow2))
      return fmt::format("{} volume texture is {}x{}x{} but {} has VOLUMEMAP_POW2 in TextureCaps",
                         sampler, tex.width(), tex.height(), tex.depth(), caps_.name);
    if (tex.type() != TextureType::Texture2D || !(caps_.textureCaps & kTexCapsPow2))
      return std::nullopt;
    const std::string size = fmt::format("{} texture is {}x{}", sampler, tex.width(), tex.height());
    if (!(caps_.textureCaps & kTexCapsNonPow2Conditional))
      return fmt::format("{} but {} has POW2 in TextureCaps", size, caps_.name);
    // NONPOW2CONDITIONAL: other sizes only clamped and without mipmaps.
    if (s_.samp(i, SAMP_ADDRESSU) != 3 || s_.samp(i, SAMP_ADDRESSV) != 3)
      return fmt::format("{}: with POW2 and NONPOW2CONDITIONAL in TextureCaps of {} it must be "
                         "addressed with CLAMP",
                         size, caps_.name);
    if (mipmapped)
      return fmt::format("{}: with POW2 and NONPOW2CONDITIONAL in TextureCaps of {} it cannot be "
                         "mipmapped",
                         size, caps_.name);
    return std::nullopt;
  }

  std::optional<std::string> addressing(int i, const std::string& sampler, bool volume) {
    const SamplerStateType states[] = {SAMP_ADDRESSU, SAMP_ADDRESSV, SAMP_ADDRESSW};
    for (int k = 0; k < (volume ? 3 : 2); ++k) {
      const uint32_t mode = s_.samp(i, states[k]);
      const std::string stateName = nameOr(EnumKind::SamplerState, states[k]);
      if (mode < 1 || mode > 5)
        return fmt::format("{} {} {} is not a D3DTEXTUREADDRESS", sampler, stateName, mode);
      const CapBit need = kAddressCaps[mode - 1];
      if (!(caps_.textureAddressCaps & need.bit))
        return fmt::format("{} {} {} needs {} in TextureAddressCaps of {}", sampler, stateName,
                           need.name, need.name, caps_.name);
    }
    if (s_.samp(i, SAMP_ADDRESSU) != s_.samp(i, SAMP_ADDRESSV) &&
        !(caps_.textureAddressCaps & kAddressIndependentUV))
      return fmt::format("{} ADDRESSU {} and ADDRESSV {} differ: needs INDEPENDENTUV in "
                         "TextureAddressCaps of {}",
                         sampler, nameOr(EnumKind::TextureAddress, s_.samp(i, SAMP_ADDRESSU)),
                         nameOr(EnumKind::TextureAddress, s_.samp(i, SAMP_ADDRESSV)), caps_.name);
    return std::nullopt;
  }

  // Fixed-function vertex processing: lights and vertex blending.
  std::optional<std::string> fixedFunctionVertex() {
    if (s_.rs(RS_LIGHTING)) {
      const auto lights = uint32_t(std::count(s_.lightEnabled.begin(), s_.lightEnabled.end(), true));
      if (lights > caps_.maxActiveLights)
        return fmt::format("{} lights are enabled with LIGHTING but {} has MaxActiveLights {}",
                           lights, caps_.name, caps_.maxActiveLights);
    }
    const uint32_t blend = s_.rs(RS_VERTEXBLEND);
    if (blend != VBF_DISABLE && blend != VBF_TWEENING) {
      // nWEIGHTS blends n+1 matrices; 0WEIGHTS one (useful with indices only).
      const uint32_t matrices = blend == VBF_0WEIGHTS ? 1 : blend + 1;
      if (blend > VBF_3WEIGHTS && blend != VBF_0WEIGHTS)
        return fmt::format("VERTEXBLEND {} is not a D3DVERTEXBLENDFLAGS", blend);
      if (matrices > caps_.maxVertexBlendMatrices)
        return fmt::format("VERTEXBLEND {}WEIGHTS blends {} matrices but {} has "
                           "MaxVertexBlendMatrices {}",
                           blend == VBF_0WEIGHTS ? 0 : blend, matrices, caps_.name,
                           caps_.maxVertexBlendMatrices);
    }
    if (s_.rs(RS_INDEXEDVERTEXBLENDENABLE) && caps_.maxVertexBlendMatrixIndex == 0)
      return fmt::format("INDEXEDVERTEXBLENDENABLE needs MaxVertexBlendMatrixIndex above 0; {} "
                         "has 0",
                         caps_.name);
    return std::nullopt;
  }

  std::optional<std::string> clipPlanesAndPoints() {
    if (const uint32_t planes = s_.rs(RS_CLIPPLANEENABLE)) {
      const int highest = 31 - std::countl_zero(planes);
      if (uint32_t(highest) >= caps_.maxUserClipPlanes)
        return fmt::format("CLIPPLANEENABLE 0x{:x} enables plane {} but {} has "
                           "MaxUserClipPlanes {}",
                           planes, highest, caps_.name, caps_.maxUserClipPlanes);
    }
    const float size = s_.rsFloat(RS_POINTSIZE);
    if (size > caps_.maxPointSize)
      return fmt::format("POINTSIZE {} exceeds MaxPointSize {} of {}", size, caps_.maxPointSize,
                         caps_.name);
    return std::nullopt;
  }

  // Raster and output-merger states that need a RasterCaps / PrimitiveMiscCaps flag.
  std::optional<std::string> raster() {
    const uint32_t z = s_.rs(RS_ZENABLE);
    if (z != ZB_FALSE && !rasterCap(kRasterZTest))
      return needsRaster(fmt::format("ZENABLE {}", nameOr(EnumKind::ZBufferType, z)),
                         kRasterZTest);
    if (z == ZB_USEW && !rasterCap(kRasterWBuffer))
      return needsRaster("ZENABLE USEW", kRasterWBuffer);
    if (!s_.rs(RS_ZWRITEENABLE) && !misc(kMiscMaskZ))
      return fmt::format("ZWRITEENABLE FALSE needs MASKZ in PrimitiveMiscCaps of {}", caps_.name);
    const uint32_t cull = s_.rs(RS_CULLMODE);
    const uint32_t cullBit = cull == CULL_NONE ? kMiscCullNone
                             : cull == CULL_CW ? kMiscCullCW
                             : cull == CULL_CCW ? kMiscCullCCW : 0;
    if (cullBit && !misc(cullBit))
      return fmt::format("CULLMODE {} needs CULL{} in PrimitiveMiscCaps of {}",
                         nameOr(EnumKind::Cull, cull), nameOr(EnumKind::Cull, cull), caps_.name);
    if ((s_.rs(RS_COLORWRITEENABLE) & 0xf) != 0xf && !misc(kMiscColorWriteEnable))
      return fmt::format("COLORWRITEENABLE 0x{:x} needs COLORWRITEENABLE in PrimitiveMiscCaps of {}",
                         s_.rs(RS_COLORWRITEENABLE), caps_.name);
    if (s_.rs(RS_SCISSORTESTENABLE) && !rasterCap(kRasterScissorTest))
      return needsRaster("SCISSORTESTENABLE", kRasterScissorTest);
    if (s_.rsFloat(RS_DEPTHBIAS) != 0.0f && !rasterCap(kRasterDepthBias))
      return needsRaster(fmt::format("DEPTHBIAS {}", s_.rsFloat(RS_DEPTHBIAS)), kRasterDepthBias);
    if (s_.rsFloat(RS_SLOPESCALEDEPTHBIAS) != 0.0f && !rasterCap(kRasterSlopeScaleDepthBias))
      return needsRaster(fmt::format("SLOPESCALEDEPTHBIAS {}", s_.rsFloat(RS_SLOPESCALEDEPTHBIAS)),
                         kRasterSlopeScaleDepthBias);
    if (s_.rs(RS_DITHERENABLE) && !rasterCap(kRasterDither))
      return needsRaster("DITHERENABLE", kRasterDither);
    return fog();
  }

  // ps_3_0 does its own fog; otherwise FOGTABLEMODE picks pixel fog, else the vertex
  // fog factor (computed by FOGVERTEXMODE or passed from the vertex) is interpolated.
  std::optional<std::string> fog() {
    if (!s_.rs(RS_FOGENABLE)) return std::nullopt;
    if (s_.pixelShader && s_.pixelShader->version().atLeast(3, 0)) return std::nullopt;
    const uint32_t table = s_.rs(RS_FOGTABLEMODE);
    if (table != FOG_NONE) {
      if (!rasterCap(kRasterFogTable))
        return needsRaster(fmt::format("FOGTABLEMODE {}", nameOr(EnumKind::FogMode, table)),
                           kRasterFogTable);
      return std::nullopt;
    }
    if (!rasterCap(kRasterFogVertex))
      return needsRaster("FOGENABLE with FOGTABLEMODE NONE (vertex fog)", kRasterFogVertex);
    const bool computed = !s_.vertexShader && s_.rs(RS_FOGVERTEXMODE) != FOG_NONE;
    if (computed && s_.rs(RS_RANGEFOGENABLE) && !rasterCap(kRasterFogRange))
      return needsRaster("RANGEFOGENABLE", kRasterFogRange);
    return std::nullopt;
  }

  // Render targets 1-3 (D3D9's multiple render targets).
  std::optional<std::string> renderTargets() {
    const int count = targets_.count;
    if (count <= 1) return std::nullopt;
    if (uint32_t(count) > caps_.maxSimultaneousRenderTargets)
      return fmt::format("{} render targets are bound but {} has NumSimultaneousRTs {}", count,
                         caps_.name, caps_.maxSimultaneousRenderTargets);
    if (targets_.formatsDiffer && !misc(kMiscMrtIndependentBitDepths))
      return fmt::format("render targets of different formats need MRTINDEPENDENTBITDEPTHS in "
                         "PrimitiveMiscCaps of {}",
                         caps_.name);
    const RenderState masks[] = {RS_COLORWRITEENABLE1, RS_COLORWRITEENABLE2,
                                 RS_COLORWRITEENABLE3};
    for (int t = 1; t < count && t < 4; ++t)
      if (s_.rs(masks[t - 1]) != s_.rs(RS_COLORWRITEENABLE) && !misc(kMiscIndependentWriteMasks))
        return fmt::format("{} differs from COLORWRITEENABLE: needs INDEPENDENTWRITEMASKS in "
                           "PrimitiveMiscCaps of {}",
                           renderStateName(masks[t - 1]), caps_.name);
    if (s_.rs(RS_ALPHABLENDENABLE) && !misc(kMiscMrtPostPixelShaderBlending))
      return fmt::format("ALPHABLENDENABLE with {} render targets needs "
                         "MRTPOSTPIXELSHADERBLENDING in PrimitiveMiscCaps of {}",
                         count, caps_.name);
    return std::nullopt;
  }

  std::optional<std::string> blendFactor(RenderState state, uint32_t caps,
                                         std::string_view capsName) {
    uint32_t blend = s_.rs(state);
    if (blend < BLEND_ZERO || blend > BLEND_INVBLENDFACTOR)
      return fmt::format("{} {} is not a D3DBLEND", renderStateName(state), blend);
    if (!(caps & blendCapsBit(blend)))
      return fmt::format("{} {} is not in {} of {}", renderStateName(state),
                         nameOr(EnumKind::Blend, blend), capsName, caps_.name);
    return std::nullopt;
  }

  std::optional<std::string> blendOp(RenderState state) {
    uint32_t op = s_.rs(state);
    if (op < BLENDOP_ADD || op > BLENDOP_MAX)
      return fmt::format("{} {} is not a D3DBLENDOP", renderStateName(state), op);
    if (op != BLENDOP_ADD && !misc(kMiscBlendOp))
      return fmt::format("{} {} needs BLENDOP in PrimitiveMiscCaps of {}",
                         renderStateName(state), nameOr(EnumKind::BlendOp, op), caps_.name);
    return std::nullopt;
  }

  // Blend states only matter while ALPHABLENDENABLE is on.
  std::optional<std::string> blending() {
    if (!s_.rs(RS_ALPHABLENDENABLE)) return std::nullopt;
    if (auto r = blendFactor(RS_SRCBLEND, caps_.srcBlendCaps, "SrcBlendCaps")) return r;
    // BOTHSRCALPHA / BOTHINVSRCALPHA as SRCBLEND override DESTBLEND.
    uint32_t src = s_.rs(RS_SRCBLEND);
    if (src != BLEND_BOTHSRCALPHA && src != BLEND_BOTHINVSRCALPHA)
      if (auto r = blendFactor(RS_DESTBLEND, caps_.destBlendCaps, "DestBlendCaps")) return r;
    if (auto r = blendOp(RS_BLENDOP)) return r;
    if (!s_.rs(RS_SEPARATEALPHABLENDENABLE)) return std::nullopt;
    if (!misc(kMiscSeparateAlphaBlend))
      return fmt::format(
          "SEPARATEALPHABLENDENABLE needs SEPARATEALPHABLEND in PrimitiveMiscCaps of {}",
          caps_.name);
    if (auto r = blendFactor(RS_SRCBLENDALPHA, caps_.srcBlendCaps, "SrcBlendCaps")) return r;
    if (auto r = blendFactor(RS_DESTBLENDALPHA, caps_.destBlendCaps, "DestBlendCaps")) return r;
    return blendOp(RS_BLENDOPALPHA);
  }
};

}  // namespace

ValidationResult validateDeviceState(const DeviceState& state, const CapsProfile& caps) {
  // DeviceState holds no render targets, so this form sees render target 0 alone.
  // Device::validate should pass the targets it binds (Device::setRenderTarget(index,
  // texture)) to the form below once it has more than one.
  return validateDeviceState(state, caps, RenderTargetBinding{});
}

ValidationResult validateDeviceState(const DeviceState& state, const CapsProfile& caps,
                                     const RenderTargetBinding& targets) {
  ValidationResult result;
  if (auto reason = Validator(state, caps, targets).run()) {
    result.ok = false;
    result.passes = 0;
    result.reason = std::move(*reason);
  }
  return result;
}

}  // namespace refx
