// The D3D9 shader token format (SM1–SM3 "d3dbc") and its decoded form. Every
// front end produces a Shader and encodes it; every consumer (disassembler,
// validator, lowering to the exec IR) decodes tokens into a Shader first.
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace refx::shader {

enum class ShaderType : uint8_t { Vertex, Pixel };

struct Version {
  ShaderType type = ShaderType::Vertex;
  uint8_t major = 1, minor = 1;  // 2_x is minor 1, _sw is minor 0xFF

  uint32_t token() const {
    return (type == ShaderType::Vertex ? 0xFFFE0000u : 0xFFFF0000u) | (uint32_t(major) << 8) | minor;
  }
  static Version fromToken(uint32_t t) {
    return Version{(t >> 16) == 0xFFFE ? ShaderType::Vertex : ShaderType::Pixel, uint8_t(t >> 8),
                   uint8_t(t)};
  }
  bool isPixel() const { return type == ShaderType::Pixel; }
  bool isVertex() const { return type == ShaderType::Vertex; }
  bool ps1x() const { return isPixel() && major == 1; }
  bool sm2plus() const { return major >= 2; }
  // Compare as major.minor: at(1,4) is true for ps_1_4 and every later version.
  bool atLeast(int ma, int mi) const { return major > ma || (major == ma && minor >= mi); }
  std::string name() const;  // "vs_1_1", "ps_2_x", "ps_3_0" …
  bool operator==(const Version&) const = default;
};

// D3DSPR_* register types (5 bits).
enum class RegType : uint8_t {
  Temp = 0, Input = 1, Const = 2,
  Addr = 3, Texture = 3,        // a0 in vertex shaders, t# in pixel shaders
  RastOut = 4,                  // oPos (0), oFog (1), oPts (2)
  AttrOut = 5,                  // oD0, oD1
  TexCrdOut = 6, Output = 6,    // oT# (vs < 3.0), o# (vs_3_0)
  ConstInt = 7, ColorOut = 8, DepthOut = 9, Sampler = 10,
  Const2 = 11, Const3 = 12, Const4 = 13,  // folded into Const by decode()
  ConstBool = 14, Loop = 15, TempFloat16 = 16,
  MiscType = 17,                // vPos (0), vFace (1)
  Label = 18, Predicate = 19,
};

// D3DSIO_* opcodes.
enum class Opcode : uint16_t {
  Nop = 0, Mov, Add, Sub, Mad, Mul, Rcp, Rsq, Dp3, Dp4, Min, Max, Slt, Sge, Exp, Log, Lit, Dst, Lrp,
  Frc, M4x4, M4x3, M3x4, M3x3, M3x2, Call, CallNZ, Loop, Ret, EndLoop, Label, Dcl, Pow, Crs, Sgn,
  Abs, Nrm, SinCos, Rep, EndRep, If, IfC, Else, EndIf, Break, BreakC, MovA, DefB, DefI,
  TexCoord = 64, TexKill, Tex, TexBem, TexBemL, TexReg2AR, TexReg2GB, TexM3x2Pad, TexM3x2Tex,
  TexM3x3Pad, TexM3x3Tex, TexM3x3Diff, TexM3x3Spec, TexM3x3VSpec, ExpP, LogP, Cnd, Def,
  TexReg2RGB, TexDP3Tex, TexM3x2Depth, TexDP3, TexM3x3, TexDepth, Cmp, Bem, Dp2Add, Dsx, Dsy,
  TexLdd, SetP, TexLdl, BreakP,
  Phase = 0xFFFD, Comment = 0xFFFE, End = 0xFFFF,
};

// D3DSPSM_* source modifiers.
enum class SrcMod : uint8_t {
  None = 0, Neg, Bias, BiasNeg, Sign, SignNeg, Comp, X2, X2Neg, Dz, Dw, Abs, AbsNeg, Not,
};

// D3DSPDM_* result modifier bits.
enum ResultMod : uint8_t { ResultSaturate = 1, ResultPartialPrecision = 2, ResultCentroid = 4 };

// D3DSHADER_COMPARISON for ifc/breakc/setp (specific-control bits 18:16).
enum class Comparison : uint8_t { None = 0, Gt, Eq, Ge, Lt, Ne, Le };

// D3DDECLUSAGE.
enum class DeclUsage : uint8_t {
  Position = 0, BlendWeight, BlendIndices, Normal, PSize, TexCoord, Tangent, Binormal,
  TessFactor, PositionT, Color, Fog, Depth, Sample,
};

// Sampler texture type of `dcl_2d s0` etc. (usage-token bits 30:27).
enum class TextureType : uint8_t { Unknown = 0, Tex1D = 1, Tex2D = 2, Cube = 3, Volume = 4 };

// The address register of a relative operand: a0.<component> or aL.
struct RelativeAddress {
  RegType type = RegType::Addr;  // Addr (a0) or Loop (aL)
  uint8_t component = 0;         // 0..3 = x..w (a0 only)
};

struct DstParam {
  RegType type = RegType::Temp;
  uint16_t index = 0;          // Const2..4 folded: c2048+ have type Const and index >= 2048
  uint8_t writeMask = 0xF;     // bit i = component i
  uint8_t resultMod = 0;       // ResultMod bits
  int8_t shift = 0;            // ps_1_x: 1 = _x2, 2 = _x4, 3 = _x8, -1 = _d2 …
  bool relative = false;       // vs_3_0 o[aL + n]
  RelativeAddress rel;
};

struct SrcParam {
  RegType type = RegType::Temp;
  uint16_t index = 0;
  uint8_t swizzle = 0xE4;      // 2 bits per component: bits 1:0 select the source of x …
  SrcMod mod = SrcMod::None;
  bool relative = false;       // c[a0.x + n], c[aL + n], v[aL + n]
  RelativeAddress rel;
};

// Where an instruction came from in assembly text (0 = unknown, e.g. decoded bytecode).
struct SourcePos {
  int line = 0, column = 0;
};

struct Instruction {
  Opcode opcode = Opcode::Nop;
  uint8_t control = 0;         // specific-control bits 23:16 (comparison, texld project/bias)
  bool coissue = false;        // ps_1_x `+` prefix
  bool predicated = false;     // SM2+: carries `predicate`
  bool predicateNot = false;   // (!p0)
  uint8_t predicateSwizzle = 0xE4;
  bool hasDst = false;
  DstParam dst;
  uint8_t srcCount = 0;
  std::array<SrcParam, 4> src{};  // texldd has 4 sources
  // def: 4 float bit patterns; defi: 4 int32; defb: literal[0]. dcl: see below.
  std::array<uint32_t, 4> literal{};
  // dcl: usage and index (input/output/texcoord) or sampler texture type.
  DeclUsage usage = DeclUsage::Position;
  uint8_t usageIndex = 0;
  TextureType textureType = TextureType::Unknown;
  std::vector<uint32_t> comment;  // Comment: the payload DWORDs
  SourcePos pos;

  Comparison comparison() const { return Comparison(control & 7); }
};

struct Shader {
  Version version;
  std::vector<Instruction> instructions;  // includes Comment and Phase, excludes End
};

// Opcode names, operand forms and properties: opcode_table.h.

// Tokens → Shader. Throws refx::Error naming the token offset and what was expected
// for truncated or malformed input (unknown opcode, bad register type, length
// mismatch, missing end token …). Never reads out of bounds.
Shader decode(std::span<const uint32_t> tokens);
// Bytes → tokens (little endian); size must be a multiple of 4.
std::vector<uint32_t> tokensFromBytes(std::span<const uint8_t> bytes);

// Shader → tokens, exactly as Microsoft's assembler lays them out (length field in
// SM2+, relative-address tokens, predicate token after the destination, end token).
std::vector<uint32_t> encode(const Shader& shader);

// Register names for messages and listings: version_rules.h.

}  // namespace refx::shader
