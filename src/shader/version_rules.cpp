// One table per shader version (registers-and-limits.md, bytecode.md §10), and the
// assembly names of the register files.
#include "refx/shader/version_rules.h"

#include <algorithm>
#include <array>
#include <limits>

namespace refx::shader {
namespace {

using O = Opcode;
using R = RegType;

// Arithmetic, texture, flow-control and free (def/dcl/label/phase) opcodes.
constexpr OpcodeRule A(O op, uint8_t slots = 1, uint8_t maxPerShader = 0, uint8_t flags = 0) {
  return {op, slots, 0, 0, maxPerShader, flags};
}
constexpr OpcodeRule T(O op, uint8_t slots = 1, uint8_t flags = 0) {
  return {op, 0, slots, 0, 0, uint8_t(flags | OpNoCoissue)};
}
constexpr OpcodeRule F(O op, uint8_t slots, uint8_t flags = 0) { return {op, 0, 0, slots, 0, flags}; }
constexpr OpcodeRule Z(O op) { return {op, 0, 0, 0, 0, OpNoCoissue}; }

constexpr uint8_t Cap = OpNeedsCap;

constexpr uint16_t mods(std::initializer_list<SrcMod> list) {
  uint16_t bits = 0;
  for (SrcMod m : list) bits |= uint16_t(1u << unsigned(m));
  return bits;
}

constexpr float kNoMin = std::numeric_limits<float>::lowest();
constexpr float kNoMax = std::numeric_limits<float>::max();

// ---- vertex shaders -------------------------------------------------------------

constexpr OpcodeRule vs11Ops[] = {
    Z(O::Dcl), Z(O::Def), A(O::Nop), A(O::Mov), A(O::Add), A(O::Sub), A(O::Mad), A(O::Mul),
    A(O::Rcp), A(O::Rsq), A(O::Dp3), A(O::Dp4), A(O::Min), A(O::Max), A(O::Slt), A(O::Sge),
    A(O::Exp, 10), A(O::Log, 10),  // full-precision macros in vs_1_1
    A(O::Lit), A(O::Dst), A(O::Frc, 3), A(O::M4x4, 4), A(O::M4x3, 3), A(O::M3x4, 4),
    A(O::M3x3, 3), A(O::M3x2, 2), A(O::ExpP), A(O::LogP),
};

#define VS20_COMMON                                                                          \
  Z(O::Dcl), Z(O::Def), Z(O::DefI), Z(O::DefB), Z(O::Label), A(O::Nop), A(O::Mov), A(O::Add), \
      A(O::Sub), A(O::Mad), A(O::Mul), A(O::Rcp), A(O::Rsq), A(O::Dp3), A(O::Dp4), A(O::Min), \
      A(O::Max), A(O::Slt), A(O::Sge), A(O::Exp), A(O::Log), A(O::Lit, 3), A(O::Dst),         \
      A(O::Lrp, 2), A(O::Frc), A(O::M4x4, 4), A(O::M4x3, 3), A(O::M3x4, 4), A(O::M3x3, 3),    \
      A(O::M3x2, 2), A(O::ExpP), A(O::LogP), A(O::Pow, 3), A(O::Crs, 2), A(O::Sgn, 3),        \
      A(O::Abs), A(O::Nrm, 3), A(O::SinCos, 8), A(O::MovA), F(O::Call, 2), F(O::CallNZ, 3),   \
      F(O::Loop, 3), F(O::EndLoop, 2), F(O::Ret, 1), F(O::Rep, 3), F(O::EndRep, 2),           \
      F(O::If, 3), F(O::Else, 1), F(O::EndIf, 1)

constexpr OpcodeRule vs20Ops[] = {VS20_COMMON};
// vs_2_x: dynamic flow control and predication as the device reports them.
constexpr OpcodeRule vs2xOps[] = {
    VS20_COMMON, F(O::IfC, 3, Cap), F(O::Break, 1, Cap), F(O::BreakC, 3, Cap),
    A(O::SetP, 1, 0, Cap), F(O::BreakP, 3, Cap),
};
constexpr OpcodeRule vs30Ops[] = {
    VS20_COMMON, F(O::IfC, 3), F(O::Break, 1), F(O::BreakC, 3), A(O::SetP), F(O::BreakP, 3),
    T(O::TexLdl, 2),
};
#undef VS20_COMMON

constexpr RegisterRule vs11Regs[] = {
    {R::Input, 16, RegRead, 0, false, CountFromCaps::None, "input"},
    {R::Temp, 12, RegReadWrite, 3, false, CountFromCaps::None, "temporary"},
    {R::Const, 96, RegRead, 0, true, CountFromCaps::VertexShaderConst, "constant"},
    {R::Addr, 1, RegWrite, 0, false, CountFromCaps::None, "address"},
    {R::RastOut, 3, RegWrite, 0, false, CountFromCaps::None, "rasterizer output"},
    {R::AttrOut, 2, RegWrite, 0, false, CountFromCaps::None, "color output"},
    {R::TexCrdOut, 8, RegWrite, 0, false, CountFromCaps::None, "texture coordinate output"},
};
constexpr RegisterRule vs20Regs[] = {
    {R::Input, 16, RegRead, 0, false, CountFromCaps::None, "input"},
    {R::Temp, 12, RegReadWrite, 3, false, CountFromCaps::None, "temporary"},
    {R::Const, 256, RegRead, 2, true, CountFromCaps::VertexShaderConst, "constant"},
    {R::Addr, 1, RegWrite, 0, false, CountFromCaps::None, "address"},
    {R::ConstInt, 16, RegRead, 0, false, CountFromCaps::None, "integer constant"},
    {R::ConstBool, 16, RegRead, 0, false, CountFromCaps::None, "boolean constant"},
    {R::Loop, 1, RegRead, 0, false, CountFromCaps::None, "loop counter"},
    {R::Label, 16, RegRead, 0, false, CountFromCaps::None, "label"},
    {R::RastOut, 3, RegWrite, 0, false, CountFromCaps::None, "rasterizer output"},
    {R::AttrOut, 2, RegWrite, 0, false, CountFromCaps::None, "color output"},
    {R::TexCrdOut, 8, RegWrite, 0, false, CountFromCaps::None, "texture coordinate output"},
};
constexpr RegisterRule vs2xRegs[] = {
    {R::Input, 16, RegRead, 0, false, CountFromCaps::None, "input"},
    {R::Temp, 12, RegReadWrite, 3, false, CountFromCaps::Vs2xTemps, "temporary"},
    {R::Const, 256, RegRead, 2, true, CountFromCaps::VertexShaderConst, "constant"},
    {R::Addr, 1, RegWrite, 0, false, CountFromCaps::None, "address"},
    {R::ConstInt, 16, RegRead, 0, false, CountFromCaps::None, "integer constant"},
    {R::ConstBool, 16, RegRead, 0, false, CountFromCaps::None, "boolean constant"},
    {R::Loop, 1, RegRead, 0, false, CountFromCaps::None, "loop counter"},
    {R::Predicate, 1, RegReadWrite, 0, false, CountFromCaps::None, "predicate"},
    {R::Label, 16, RegRead, 0, false, CountFromCaps::None, "label"},
    {R::RastOut, 3, RegWrite, 0, false, CountFromCaps::None, "rasterizer output"},
    {R::AttrOut, 2, RegWrite, 0, false, CountFromCaps::None, "color output"},
    {R::TexCrdOut, 8, RegWrite, 0, false, CountFromCaps::None, "texture coordinate output"},
};
constexpr RegisterRule vs30Regs[] = {
    {R::Input, 16, RegRead, 0, true, CountFromCaps::None, "input"},
    {R::Temp, 32, RegReadWrite, 3, false, CountFromCaps::None, "temporary"},
    {R::Const, 256, RegRead, 0, true, CountFromCaps::VertexShaderConst, "constant"},
    {R::Addr, 1, RegWrite, 0, false, CountFromCaps::None, "address"},
    {R::ConstInt, 16, RegRead, 0, false, CountFromCaps::None, "integer constant"},
    {R::ConstBool, 16, RegRead, 0, false, CountFromCaps::None, "boolean constant"},
    {R::Loop, 1, RegRead, 0, false, CountFromCaps::None, "loop counter"},
    {R::Predicate, 1, RegReadWrite, 0, false, CountFromCaps::None, "predicate"},
    {R::Sampler, 4, RegRead, 0, false, CountFromCaps::None, "sampler"},
    {R::Label, 2048, RegRead, 0, false, CountFromCaps::None, "label"},
    {R::Output, 12, RegWrite, 0, true, CountFromCaps::None, "output"},
};

// ---- pixel shaders --------------------------------------------------------------

#define PS11_COMMON                                                                          \
  Z(O::Def), A(O::Nop, 0), A(O::Mov), A(O::Add), A(O::Sub), A(O::Mad), A(O::Mul),             \
      A(O::Dp3, 1, 0, OpVectorOnly), A(O::Lrp), A(O::Cnd), T(O::TexCoord), T(O::TexKill),     \
      T(O::Tex), T(O::TexBem), {O::TexBemL, 1, 1, 0, 0, OpNoCoissue}, T(O::TexReg2AR),        \
      T(O::TexReg2GB), T(O::TexM3x2Pad), T(O::TexM3x2Tex), T(O::TexM3x3Pad), T(O::TexM3x3Tex), \
      T(O::TexM3x3Spec), T(O::TexM3x3VSpec)
// ps_1_2 adds dp4 and cmp (2 slots each, at most 4 and 3 per shader) and the
// texreg2rgb/texdp3* /texm3x3 texture instructions.
#define PS12_ADDS                                                                       \
  A(O::Dp4, 2, 4, OpNoCoissue), A(O::Cmp, 2, 3), T(O::TexReg2RGB), T(O::TexDP3Tex), \
      T(O::TexDP3), T(O::TexM3x3)

constexpr OpcodeRule ps11Ops[] = {PS11_COMMON};
constexpr OpcodeRule ps12Ops[] = {PS11_COMMON, PS12_ADDS};
constexpr OpcodeRule ps13Ops[] = {PS11_COMMON, PS12_ADDS, T(O::TexM3x2Depth)};
#undef PS11_COMMON
#undef PS12_ADDS

constexpr OpcodeRule ps14Ops[] = {
    Z(O::Def), Z(O::Phase), A(O::Nop, 0), A(O::Mov), A(O::Add), A(O::Sub), A(O::Mad),
    A(O::Mul), A(O::Dp3, 1, 0, OpVectorOnly), A(O::Dp4, 1, 0, OpNoCoissue), A(O::Lrp),
    A(O::Cnd), A(O::Cmp), A(O::Bem, 2, 1, OpNoCoissue),
    T(O::TexCoord), T(O::Tex), T(O::TexKill), T(O::TexDepth),  // texcrd, texld
};

#define PS20_COMMON                                                                           \
  Z(O::Dcl), Z(O::Def), A(O::Nop), A(O::Mov), A(O::Add), A(O::Sub), A(O::Mad), A(O::Mul),      \
      A(O::Rcp), A(O::Rsq), A(O::Dp3), A(O::Dp4), A(O::Min), A(O::Max), A(O::Exp), A(O::Log),  \
      A(O::Lrp, 2), A(O::Frc), A(O::M4x4, 4), A(O::M4x3, 3), A(O::M3x4, 4), A(O::M3x3, 3),     \
      A(O::M3x2, 2), A(O::Pow, 3), A(O::Crs, 2), A(O::Abs), A(O::Nrm, 3), A(O::SinCos, 8),     \
      A(O::Cmp), A(O::Dp2Add, 2), T(O::Tex), T(O::TexKill)

constexpr OpcodeRule ps20Ops[] = {PS20_COMMON};
// ps_2_x: static flow control, predication, dsx/dsy and texldd as the device reports them.
constexpr OpcodeRule ps2xOps[] = {
    PS20_COMMON, Z(O::DefI), Z(O::DefB), Z(O::Label), F(O::Call, 2, Cap), F(O::CallNZ, 3, Cap),
    F(O::Ret, 1, Cap), F(O::Rep, 3, Cap), F(O::EndRep, 2, Cap), F(O::If, 3, Cap),
    F(O::IfC, 3, Cap), F(O::Else, 1, Cap), F(O::EndIf, 1, Cap), F(O::Break, 1, Cap),
    F(O::BreakC, 3, Cap), F(O::BreakP, 3, Cap), A(O::SetP, 1, 0, Cap), A(O::Dsx, 2, 0, Cap),
    A(O::Dsy, 2, 0, Cap), T(O::TexLdd, 3, Cap),
};
constexpr OpcodeRule ps30Ops[] = {
    PS20_COMMON, Z(O::DefI), Z(O::DefB), Z(O::Label), F(O::Call, 2), F(O::CallNZ, 3),
    F(O::Ret, 1), F(O::Rep, 3), F(O::EndRep, 2), F(O::Loop, 3), F(O::EndLoop, 2), F(O::If, 3),
    F(O::IfC, 3), F(O::Else, 1), F(O::EndIf, 1), F(O::Break, 1), F(O::BreakC, 3),
    F(O::BreakP, 3), A(O::SetP), A(O::Dsx, 2), A(O::Dsy, 2), T(O::TexLdd, 3), T(O::TexLdl, 2),
};
#undef PS20_COMMON

constexpr RegisterRule ps11Regs[] = {
    {R::Const, 8, RegRead, 2, false, CountFromCaps::None, "constant"},
    {R::Temp, 2, RegReadWrite, 2, false, CountFromCaps::None, "temporary"},
    {R::Texture, 4, RegReadWrite, 2, false, CountFromCaps::None, "texture"},
    {R::Input, 2, RegRead, 2, false, CountFromCaps::None, "color"},
};
constexpr RegisterRule ps12Regs[] = {
    {R::Const, 8, RegRead, 2, false, CountFromCaps::None, "constant"},
    {R::Temp, 2, RegReadWrite, 2, false, CountFromCaps::None, "temporary"},
    {R::Texture, 4, RegReadWrite, 3, false, CountFromCaps::None, "texture"},
    {R::Input, 2, RegRead, 2, false, CountFromCaps::None, "color"},
};
constexpr RegisterRule ps14Regs[] = {
    {R::Const, 8, RegRead, 2, false, CountFromCaps::None, "constant"},
    {R::Temp, 6, RegReadWrite, 3, false, CountFromCaps::None, "temporary"},
    {R::Texture, 6, RegRead, 1, false, CountFromCaps::None, "texture coordinate"},
    {R::Input, 2, RegRead, 2, false, CountFromCaps::None, "color"},
};
constexpr RegisterRule ps20Regs[] = {
    {R::Input, 2, RegRead, 1, false, CountFromCaps::None, "color"},
    {R::Texture, 8, RegRead, 1, false, CountFromCaps::None, "texture coordinate"},
    {R::Temp, 12, RegReadWrite, 3, false, CountFromCaps::None, "temporary"},
    {R::Const, 32, RegRead, 2, false, CountFromCaps::None, "constant"},
    {R::Sampler, 16, RegRead, 0, false, CountFromCaps::None, "sampler"},
    {R::ColorOut, 4, RegWrite, 0, false, CountFromCaps::None, "color output"},
    {R::DepthOut, 1, RegWrite, 0, false, CountFromCaps::None, "depth output"},
};
constexpr RegisterRule ps2xRegs[] = {
    {R::Input, 2, RegRead, 1, false, CountFromCaps::None, "color"},
    {R::Texture, 8, RegRead, 1, false, CountFromCaps::None, "texture coordinate"},
    {R::Temp, 12, RegReadWrite, 3, false, CountFromCaps::Ps2xTemps, "temporary"},
    {R::Const, 32, RegRead, 2, false, CountFromCaps::None, "constant"},
    {R::ConstInt, 16, RegRead, 0, false, CountFromCaps::None, "integer constant"},
    {R::ConstBool, 16, RegRead, 0, false, CountFromCaps::None, "boolean constant"},
    {R::Predicate, 1, RegReadWrite, 0, false, CountFromCaps::None, "predicate"},
    {R::Sampler, 16, RegRead, 0, false, CountFromCaps::None, "sampler"},
    {R::Label, 16, RegRead, 0, false, CountFromCaps::None, "label"},
    {R::ColorOut, 4, RegWrite, 0, false, CountFromCaps::None, "color output"},
    {R::DepthOut, 1, RegWrite, 0, false, CountFromCaps::None, "depth output"},
};
constexpr RegisterRule ps30Regs[] = {
    {R::Input, 10, RegRead, 0, true, CountFromCaps::None, "input"},
    {R::Temp, 32, RegReadWrite, 3, false, CountFromCaps::None, "temporary"},
    {R::Const, 224, RegRead, 0, false, CountFromCaps::None, "constant"},
    {R::ConstInt, 16, RegRead, 0, false, CountFromCaps::None, "integer constant"},
    {R::ConstBool, 16, RegRead, 0, false, CountFromCaps::None, "boolean constant"},
    {R::Predicate, 1, RegReadWrite, 0, false, CountFromCaps::None, "predicate"},
    {R::Sampler, 16, RegRead, 0, false, CountFromCaps::None, "sampler"},
    {R::Loop, 1, RegRead, 0, false, CountFromCaps::None, "loop counter"},
    {R::MiscType, 2, RegRead, 0, false, CountFromCaps::None, "vPos/vFace"},
    {R::Label, 2048, RegRead, 0, false, CountFromCaps::None, "label"},
    {R::ColorOut, 4, RegWrite, 0, false, CountFromCaps::None, "color output"},
    {R::DepthOut, 1, RegWrite, 0, false, CountFromCaps::None, "depth output"},
};

using M = SrcMod;
constexpr uint16_t kVsMods = mods({M::None, M::Neg, M::Not});
constexpr uint16_t kVs30Mods = mods({M::None, M::Neg, M::Abs, M::AbsNeg, M::Not});
constexpr uint16_t kPs11Mods =
    mods({M::None, M::Neg, M::Bias, M::BiasNeg, M::Sign, M::SignNeg, M::Comp});
constexpr uint16_t kPs14Mods = kPs11Mods | mods({M::X2, M::X2Neg, M::Dz, M::Dw});
constexpr uint16_t kPs20Mods = mods({M::None, M::Neg, M::Not});
constexpr uint16_t kPs30Mods = kVs30Mods;

constexpr uint8_t kPsResult = ResultSaturate | ResultPartialPrecision | ResultCentroid;

constexpr Version vs(uint8_t major, uint8_t minor) { return {ShaderType::Vertex, major, minor}; }
constexpr Version ps(uint8_t major, uint8_t minor) { return {ShaderType::Pixel, major, minor}; }

// Flow limits: loop depth, call depth, static if depth, dynamic depth, static flow
// instruction count, labels. The _x profiles carry the largest values the caps
// allow; the validator lowers them to the device's StaticFlowControlDepth etc.
constexpr FlowLimits kNoFlow{};
constexpr FlowLimits kFlow20{1, 1, 16, 0, 16, 16};
constexpr FlowLimits kFlow2x{4, 4, 16, 24, 16, 16};
constexpr FlowLimits kFlow30{4, 4, 24, 24, 0, 2048};

// The last two columns: the least ps_1_x register range (registers-and-limits.md §2:
// PixelShader1xMaxValue is at least 1 for ps_1_1-1_3 parts, 8 for ps_1_4) and whether
// v0/v1 are saturated color inputs (ps_1_x-2_x; ps_3_0 inputs are full float).
// clang-format off
constexpr VersionRules kVs11{vs(1, 1), "vs_1_1", vs11Ops, vs11Regs, kVsMods, 0, 0, 0,
    SwizzleRule::Arbitrary, WriteMaskRule::Any, IndexA0X, {128}, kNoFlow, kNoMin, kNoMax,
    false, false, false, false, false, 0, false,
    0.0f, false};
constexpr VersionRules kVs20{vs(2, 0), "vs_2_0", vs20Ops, vs20Regs, kVsMods, 0, 0, 0,
    SwizzleRule::Arbitrary, WriteMaskRule::Any, IndexA0Any | IndexLoop, {256}, kFlow20, kNoMin,
    kNoMax, false, false, false, true, true, 0, false,
    0.0f, false};
constexpr VersionRules kVs2x{vs(2, 1), "vs_2_x", vs2xOps, vs2xRegs, kVsMods, 0, 0, 0,
    SwizzleRule::Arbitrary, WriteMaskRule::Any, IndexA0Any | IndexLoop, {256}, kFlow2x, kNoMin,
    kNoMax, false, false, true, true, true, 0, false,
    0.0f, false};
constexpr VersionRules kVs30{vs(3, 0), "vs_3_0", vs30Ops, vs30Regs, kVs30Mods, ResultSaturate, 0, 0,
    SwizzleRule::Arbitrary, WriteMaskRule::Any, IndexA0Any | IndexLoop, {512}, kFlow30, kNoMin,
    kNoMax, false, false, true, true, true, 0, false,
    0.0f, false};

constexpr VersionRules kPs11{ps(1, 1), "ps_1_1", ps11Ops, ps11Regs, kPs11Mods, ResultSaturate, -1, 2,
    SwizzleRule::Ps11, WriteMaskRule::Ps11, 0, {0, 4, 8}, kNoFlow, -1.0f, 1.0f,
    true, false, false, false, false, 0, false,
    1.0f, true};
constexpr VersionRules kPs12{ps(1, 2), "ps_1_2", ps12Ops, ps12Regs, kPs11Mods, ResultSaturate, -1, 2,
    SwizzleRule::Ps11, WriteMaskRule::Ps11, 0, {0, 4, 8}, kNoFlow, -1.0f, 1.0f,
    true, false, false, false, false, 0, false,
    1.0f, true};
constexpr VersionRules kPs13{ps(1, 3), "ps_1_3", ps13Ops, ps12Regs, kPs11Mods, ResultSaturate, -1, 2,
    SwizzleRule::Ps11, WriteMaskRule::Ps11, 0, {0, 4, 8}, kNoFlow, -1.0f, 1.0f,
    true, false, false, false, false, 0, false,
    1.0f, true};
constexpr VersionRules kPs14{ps(1, 4), "ps_1_4", ps14Ops, ps14Regs, kPs14Mods, ResultSaturate, -3, 3,
    SwizzleRule::Ps14, WriteMaskRule::Any, 0, {0, 6, 8, true}, kNoFlow, -1.0f, 1.0f,
    true, true, false, false, false, 0, false,
    8.0f, true};
constexpr VersionRules kPs20{ps(2, 0), "ps_2_0", ps20Ops, ps20Regs, kPs20Mods, kPsResult, 0, 0,
    SwizzleRule::Ps20, WriteMaskRule::Any, 0, {96, 32, 64}, kNoFlow, kNoMin, kNoMax,
    false, false, false, true, true, 4, false,
    0.0f, true};
constexpr VersionRules kPs2x{ps(2, 1), "ps_2_x", ps2xOps, ps2xRegs, kPs20Mods, kPsResult, 0, 0,
    SwizzleRule::Ps20, WriteMaskRule::Any, 0, {96, 32, 0, false, true}, kFlow2x, kNoMin, kNoMax,
    false, false, true, true, true, 4, false,
    0.0f, true};
constexpr VersionRules kPs30{ps(3, 0), "ps_3_0", ps30Ops, ps30Regs, kPs30Mods, kPsResult, 0, 0,
    SwizzleRule::Arbitrary, WriteMaskRule::Any, IndexLoop, {512}, kFlow30, kNoMin, kNoMax,
    false, false, true, true, true, 0, true,
    0.0f, false};
// clang-format on

constexpr const VersionRules* kAll[] = {&kVs11, &kVs20, &kVs2x, &kVs30, &kPs11, &kPs12,
                                        &kPs13, &kPs14, &kPs20, &kPs2x, &kPs30};

// ---- register names ----------------------------------------------------------------

enum NamedIn : uint8_t { InVertex = 1, InPixel = 2, InBoth = 3 };

constexpr RegisterNaming kRegisterNames[] = {
    {R::Temp, InBoth, 0, "r", {}, 0},
    {R::Input, InBoth, 0, "v", {}, 0},
    {R::Const, InBoth, 0, "c", {}, 0},
    {R::Const2, InBoth, 0, "c", {}, 2048},
    {R::Const3, InBoth, 0, "c", {}, 4096},
    {R::Const4, InBoth, 0, "c", {}, 6144},
    {R::Addr, InVertex, 0, "a", {}, 0},
    {R::Texture, InPixel, 0, "t", {}, 0},
    {R::RastOut, InBoth, 0, "oRast", {"oPos", "oFog", "oPts"}, 0},
    {R::AttrOut, InBoth, 0, "oD", {}, 0},
    {R::Output, InVertex, 3, "o", {}, 0},
    {R::TexCrdOut, InBoth, 0, "oT", {}, 0},
    {R::ConstInt, InBoth, 0, "i", {}, 0},
    {R::ColorOut, InBoth, 0, "oC", {}, 0},
    {R::DepthOut, InBoth, 0, "", {"oDepth"}, 0},
    {R::Sampler, InBoth, 0, "s", {}, 0},
    {R::ConstBool, InBoth, 0, "b", {}, 0},
    {R::Loop, InBoth, 0, "", {"aL"}, 0},
    {R::TempFloat16, InBoth, 0, "half", {}, 0},
    {R::MiscType, InBoth, 0, "vMisc", {"vPos", "vFace"}, 0},
    {R::Label, InBoth, 0, "l", {}, 0},
    {R::Predicate, InBoth, 0, "p", {}, 0},
};

}  // namespace

// The first row that matches the shader type and major version names the register.
const RegisterNaming* findRegisterNaming(RegType type, Version v) {
  const uint8_t shader = v.isVertex() ? InVertex : InPixel;
  for (const RegisterNaming& n : kRegisterNames)
    if (n.type == type && (n.namedIn & shader) && v.major >= n.fromMajor) return &n;
  return nullptr;
}

std::string_view registerTypeName(RegType type, Version version) {
  const RegisterNaming* n = findRegisterNaming(type, version);
  if (!n) return "?";
  return n->fixedNames[0] ? n->fixedNames[0] : n->prefix;
}

std::string registerName(RegType type, uint32_t index, Version version) {
  const RegisterNaming* n = findRegisterNaming(type, version);
  if (!n) return "?" + std::to_string(index);
  if (!*n->prefix) return n->fixedNames[0];
  if (index < n->fixedNames.size() && n->fixedNames[index]) return n->fixedNames[index];
  return n->prefix + std::to_string(index + n->numberOffset);
}

const VersionRules* findVersionRules(Version v) {
  if (v.major == 1 && v.minor == 0) v.minor = 1;  // vs_1_0 / ps_1_0 behave as 1_1
  for (const VersionRules* r : kAll)
    if (r->version == v) return r;
  return nullptr;
}

std::span<const VersionRules* const> allVersionRules() { return kAll; }

const OpcodeRule* findOpcodeRule(const VersionRules& rules, Opcode op) {
  for (const OpcodeRule& r : rules.opcodes)
    if (r.opcode == op) return &r;
  return nullptr;
}

const RegisterRule* findRegisterRule(const VersionRules& rules, RegType type) {
  for (const RegisterRule& r : rules.registers)
    if (r.type == type) return &r;
  return nullptr;
}

uint16_t registerCapacity(const VersionRules& rules, RegType type) {
  const RegisterRule* rule = findRegisterRule(rules, type);
  if (!rule) return 0;
  if (rule->fromCaps == CountFromCaps::None) return rule->count;
  uint16_t most = rule->count;
  for (const VersionRules* other : allVersionRules())
    if (other->version.type == rules.version.type)
      if (const RegisterRule* r = findRegisterRule(*other, type)) most = std::max(most, r->count);
  return most;
}

}  // namespace refx::shader
