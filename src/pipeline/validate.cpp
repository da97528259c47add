// ValidateDevice for the shaders (their versions and constants against the profile,
// and the version rules of the shader layer), the fixed-function texture cascade,
// bound textures and the output merger. With a pixel shader bound the texture stage
// cascade is not used and is not checked.
#include <algorithm>
#include <optional>

#include "refx/core/diagnostics.h"
#include "refx/pipeline/caps.h"
#include "refx/pipeline/d3d9types.h"
#include "refx/pipeline/shader_object.h"
#include "refx/pipeline/state.h"

namespace refx {

using namespace d3d;

namespace {

// D3DPMISCCAPS_* and D3DPTEXTURECAPS_* bits the checks below read.
constexpr uint32_t kMiscTssArgTemp = 0x400;
constexpr uint32_t kMiscBlendOp = 0x800;
constexpr uint32_t kMiscPerStageConstant = 0x8000;
constexpr uint32_t kMiscSeparateAlphaBlend = 0x20000;
constexpr uint32_t kTexCapsCubeMap = 0x800;
constexpr uint32_t kTexCapsVolumeMap = 0x2000;

std::string nameOr(EnumKind kind, uint32_t value) {
  std::string_view n = enumName(kind, value);
  return n.empty() ? std::to_string(value) : std::string(n);
}

std::string stateName(TextureStageState s) { return nameOr(EnumKind::TextureStageState, s); }
std::string renderStateName(RenderState s) { return nameOr(EnumKind::RenderState, s); }

// Which arguments an operation reads (D3DTOP semantics in fixed-function.md §2).
struct OpUse {
  bool arg0, arg1, arg2;
  bool ownTexture;  // reads this stage's texture regardless of its arguments
  bool colorOnly;   // valid as COLOROP only
};

OpUse opUse(uint32_t op) {
  switch (op) {
    case TOP_DISABLE: return {false, false, false, false, false};
    case TOP_SELECTARG1: return {false, true, false, false, false};
    case TOP_SELECTARG2: return {false, false, true, false, false};
    case TOP_BLENDTEXTUREALPHA:
    case TOP_BLENDTEXTUREALPHAPM: return {false, true, true, true, false};
    case TOP_MODULATEALPHA_ADDCOLOR:
    case TOP_MODULATECOLOR_ADDALPHA:
    case TOP_MODULATEINVALPHA_ADDCOLOR:
    case TOP_MODULATEINVCOLOR_ADDALPHA: return {false, true, true, false, true};
    // The bump stage's texture holds du/dv; its arguments are not read.
    case TOP_BUMPENVMAP:
    case TOP_BUMPENVMAPLUMINANCE: return {false, false, false, true, true};
    case TOP_MULTIPLYADD:
    case TOP_LERP: return {true, true, true, false, false};
    default: return {false, true, true, false, false};
  }
}

bool validOp(uint32_t op) { return op >= TOP_DISABLE && op <= TOP_LERP; }
uint32_t opCapsBit(uint32_t op) { return 1u << (op - 1); }

class Validator {
 public:
  Validator(const DeviceState& state, const CapsProfile& caps) : s_(state), caps_(caps) {}

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
    if (auto r = blending()) return r;
    return std::nullopt;
  }

 private:
  const DeviceState& s_;
  const CapsProfile& caps_;

  bool misc(uint32_t bit) const { return (caps_.primitiveMiscCaps & bit) != 0; }

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
    const std::vector<shader::Diagnostic> problems = shader::validate(sh.decoded(), vc);
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
    if (!validOp(op))
      return fmt::format("stage {} {} {} is not a D3DTEXTUREOP", n, stateName(opState), op);
    OpUse use = opUse(op);
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

  // D3DPBLENDCAPS_x is bit (D3DBLEND_x - 1); INVBLENDFACTOR shares the BLENDFACTOR bit.
  std::optional<std::string> blendFactor(RenderState state, uint32_t caps,
                                         std::string_view capsName) {
    uint32_t blend = s_.rs(state);
    if (blend < BLEND_ZERO || blend > BLEND_INVBLENDFACTOR)
      return fmt::format("{} {} is not a D3DBLEND", renderStateName(state), blend);
    uint32_t bit = blend == BLEND_INVBLENDFACTOR ? 1u << (BLEND_BLENDFACTOR - 1)
                                                 : 1u << (blend - 1);
    if (!(caps & bit))
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
  ValidationResult result;
  if (auto reason = Validator(state, caps).run()) {
    result.ok = false;
    result.passes = 0;
    result.reason = std::move(*reason);
  }
  return result;
}

}  // namespace refx
