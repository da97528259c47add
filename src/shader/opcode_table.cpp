// The opcode table (bytecode.md §4, instructions.md): every spelling of every
// D3D9 shader opcode, then the facts of each opcode, named from the spellings.
#include "refx/shader/opcode_table.h"

#include "refx/shader/version_rules.h"

namespace refx::shader {
namespace {

using K = MnemonicKind;
using F = FormRule;
using O = Opcode;

constexpr Mnemonic plain(const char* name, O op, F form = F::Any, uint8_t control = 0, bool canonical = true) {
  return {name, op, control, K::Plain, op, form, canonical};
}
constexpr Mnemonic other(const char* name, O op, F form, uint8_t control = 0) {
  return plain(name, op, form, control, false);
}
constexpr Mnemonic compare(const char* name, O op, O compareOp) {
  return {name, op, 0, K::Compare, compareOp, F::Any, true};
}
constexpr Mnemonic def(const char* name, O op) { return {name, op, 0, K::Def, op, F::Any, true}; }

// Every mnemonic of vs_1_1 … ps_3_0 (D3D9 and DirectX 8 spellings), in opcode order.
constexpr Mnemonic kMnemonics[] = {
    plain("nop", O::Nop),
    plain("mov", O::Mov),
    plain("add", O::Add),
    plain("sub", O::Sub),
    plain("mad", O::Mad),
    plain("mul", O::Mul),
    plain("rcp", O::Rcp),
    plain("rsq", O::Rsq),
    plain("dp3", O::Dp3),
    plain("dp4", O::Dp4),
    plain("min", O::Min),
    plain("max", O::Max),
    plain("slt", O::Slt),
    plain("sge", O::Sge),
    plain("exp", O::Exp),
    plain("log", O::Log),
    plain("lit", O::Lit),
    plain("dst", O::Dst),
    plain("lrp", O::Lrp),
    plain("frc", O::Frc),
    plain("m4x4", O::M4x4),
    plain("m4x3", O::M4x3),
    plain("m3x4", O::M3x4),
    plain("m3x3", O::M3x3),
    plain("m3x2", O::M3x2),
    plain("call", O::Call),
    plain("callnz", O::CallNZ),
    plain("loop", O::Loop),
    plain("ret", O::Ret),
    plain("endloop", O::EndLoop),
    plain("label", O::Label),
    {"dcl", O::Dcl, 0, K::Dcl, O::Dcl, F::Any, true},
    plain("pow", O::Pow),
    plain("crs", O::Crs),
    plain("sgn", O::Sgn),
    plain("abs", O::Abs),
    plain("nrm", O::Nrm),
    plain("sincos", O::SinCos),
    plain("rep", O::Rep),
    plain("endrep", O::EndRep),
    compare("if", O::If, O::IfC),
    compare("ifc", O::IfC, O::IfC),
    plain("else", O::Else),
    plain("endif", O::EndIf),
    compare("break", O::Break, O::BreakC),
    compare("breakc", O::BreakC, O::BreakC),
    plain("mova", O::MovA),
    def("defb", O::DefB),
    def("defi", O::DefI),
    plain("texcoord", O::TexCoord, F::Ps1Tex),
    other("texcrd", O::TexCoord, F::Ps14Only),
    plain("texkill", O::TexKill),
    other("tex", O::Tex, F::Ps1Tex),
    plain("texld", O::Tex, F::Ps14Up),
    other("texldp", O::Tex, F::Sm2Up, 1),  // D3DSI_TEXLD_PROJECT
    other("texldb", O::Tex, F::Sm2Up, 2),  // D3DSI_TEXLD_BIAS
    plain("texbem", O::TexBem),
    plain("texbeml", O::TexBemL),
    plain("texreg2ar", O::TexReg2AR),
    plain("texreg2gb", O::TexReg2GB),
    plain("texm3x2pad", O::TexM3x2Pad),
    plain("texm3x2tex", O::TexM3x2Tex),
    plain("texm3x3pad", O::TexM3x3Pad),
    plain("texm3x3tex", O::TexM3x3Tex),
    plain("texm3x3diff", O::TexM3x3Diff, F::Reserved),
    plain("texm3x3spec", O::TexM3x3Spec),
    plain("texm3x3vspec", O::TexM3x3VSpec),
    plain("expp", O::ExpP),
    plain("logp", O::LogP),
    plain("cnd", O::Cnd),
    def("def", O::Def),
    plain("texreg2rgb", O::TexReg2RGB),
    plain("texdp3tex", O::TexDP3Tex),
    plain("texm3x2depth", O::TexM3x2Depth),
    plain("texdp3", O::TexDP3),
    plain("texm3x3", O::TexM3x3),
    plain("texdepth", O::TexDepth),
    plain("cmp", O::Cmp),
    plain("bem", O::Bem),
    plain("dp2add", O::Dp2Add),
    plain("dsx", O::Dsx),
    plain("dsy", O::Dsy),
    plain("texldd", O::TexLdd),
    compare("setp", O::SetP, O::SetP),
    plain("texldl", O::TexLdl),
    plain("breakp", O::BreakP),
    plain("phase", O::Phase),
};

constexpr const char* canonicalName(O op) {
  for (const Mnemonic& m : kMnemonics)
    if (m.opcode == op && m.canonical) return m.name;
  return nullptr;
}

constexpr uint16_t Scalar = OpScalarSource;
// The scalar instructions whose SM2+ source must name one component (.x .y .z .w).
// sincos reads one component too, but its replicate swizzle is not enforced.
constexpr uint16_t ScalarReplicate = OpScalarSource | OpReplicateSwizzle;
constexpr uint16_t Flow = OpFlowControl;
constexpr uint16_t Tex = OpTexture;
constexpr uint16_t TexMatrix = OpTexture | OpTextureMatrix;
constexpr uint16_t NoSlot = OpNoSlot;

// An instruction with a destination and `src` sources.
constexpr OpcodeInfo op(O o, int8_t src, uint16_t properties = 0) {
  return {o, canonicalName(o), true, src, 0, properties, 0, 0};
}
// An instruction without a destination (flow control, nop, phase).
constexpr OpcodeInfo noDst(O o, int8_t src, uint16_t properties = 0) {
  return {o, canonicalName(o), false, src, 0, properties, 0, 0};
}
// def/defi/defb: a destination and `literals` DWORDs.
constexpr OpcodeInfo literal(O o, uint8_t literals) { return {o, canonicalName(o), true, 0, literals, NoSlot, 0, 0}; }
// m4x4 …: dst, vector, first row; one dot product of `columns` components per row.
constexpr OpcodeInfo matrix(O o, uint8_t rows, uint8_t columns) {
  return {o, canonicalName(o), true, 2, 0, 0, rows, columns};
}

// srcCount -1: the count depends on the version (operandCounts()).
constexpr OpcodeInfo kOpcodes[] = {
    noDst(O::Nop, 0),
    op(O::Mov, 1),
    op(O::Add, 2),
    op(O::Sub, 2),
    op(O::Mad, 3),
    op(O::Mul, 2),
    op(O::Rcp, 1, ScalarReplicate),
    op(O::Rsq, 1, ScalarReplicate),
    op(O::Dp3, 2),
    op(O::Dp4, 2),
    op(O::Min, 2),
    op(O::Max, 2),
    op(O::Slt, 2),
    op(O::Sge, 2),
    op(O::Exp, 1, ScalarReplicate),
    op(O::Log, 1, ScalarReplicate),
    op(O::Lit, 1),
    op(O::Dst, 2),
    op(O::Lrp, 3),
    op(O::Frc, 1),
    matrix(O::M4x4, 4, 4),
    matrix(O::M4x3, 3, 4),
    matrix(O::M3x4, 4, 3),
    matrix(O::M3x3, 3, 3),
    matrix(O::M3x2, 2, 3),
    noDst(O::Call, 1, Flow),
    noDst(O::CallNZ, 2, Flow),
    noDst(O::Loop, 2, Flow),
    noDst(O::Ret, 0, Flow),
    noDst(O::EndLoop, 0, Flow),
    noDst(O::Label, 1, Flow | NoSlot),
    op(O::Dcl, 0, NoSlot),  // + the usage token before the destination
    op(O::Pow, 2, ScalarReplicate),
    op(O::Crs, 2),
    op(O::Sgn, -1),
    op(O::Abs, 1),
    op(O::Nrm, 1),
    op(O::SinCos, -1, Scalar),
    noDst(O::Rep, 1, Flow),
    noDst(O::EndRep, 0, Flow),
    noDst(O::If, 1, Flow),
    noDst(O::IfC, 2, Flow),
    noDst(O::Else, 0, Flow),
    noDst(O::EndIf, 0, Flow),
    noDst(O::Break, 0, Flow),
    noDst(O::BreakC, 2, Flow),
    op(O::MovA, 1),
    literal(O::DefB, 1),
    literal(O::DefI, 4),
    op(O::TexCoord, -1, Tex),
    op(O::TexKill, 0, Tex),  // the operand is a destination token
    op(O::Tex, -1, Tex),
    op(O::TexBem, 1, Tex),
    op(O::TexBemL, 1, Tex),
    op(O::TexReg2AR, 1, Tex),
    op(O::TexReg2GB, 1, Tex),
    op(O::TexM3x2Pad, 1, TexMatrix),
    op(O::TexM3x2Tex, 1, TexMatrix),
    op(O::TexM3x3Pad, 1, TexMatrix),
    op(O::TexM3x3Tex, 1, TexMatrix),
    op(O::TexM3x3Diff, 1, TexMatrix | OpReserved),
    op(O::TexM3x3Spec, 2, TexMatrix),
    op(O::TexM3x3VSpec, 1, TexMatrix),
    op(O::ExpP, 1, ScalarReplicate),
    op(O::LogP, 1, ScalarReplicate),
    op(O::Cnd, 3),
    literal(O::Def, 4),
    op(O::TexReg2RGB, 1, Tex),
    op(O::TexDP3Tex, 1, Tex),
    op(O::TexM3x2Depth, 1, TexMatrix),
    op(O::TexDP3, 1, Tex),
    op(O::TexM3x3, 1, TexMatrix),
    op(O::TexDepth, 0, Tex),
    op(O::Cmp, 3),
    op(O::Bem, 2),
    op(O::Dp2Add, 3),
    op(O::Dsx, 1),
    op(O::Dsy, 1),
    op(O::TexLdd, 4, Tex),
    op(O::SetP, 2),
    op(O::TexLdl, 2, Tex),
    noDst(O::BreakP, 1, Flow),
    noDst(O::Phase, 0, NoSlot),
};

constexpr bool everyOpcodeIsNamed() {
  for (const OpcodeInfo& info : kOpcodes)
    if (!info.name) return false;
  return true;
}
static_assert(everyOpcodeIsNamed(), "every opcode needs a canonical spelling in kMnemonics");

const Mnemonic* spelling(O op, F form, uint8_t control) {
  for (const Mnemonic& m : kMnemonics)
    if (m.opcode == op && m.form == form && m.control == control) return &m;
  return nullptr;
}

const OpcodeInfo* findAny(O op) {
  for (const OpcodeInfo& info : kOpcodes)
    if (info.opcode == op) return &info;
  return nullptr;
}

}  // namespace

const OpcodeInfo* findOpcode(Opcode op) {
  const OpcodeInfo* info = findAny(op);
  return info && !info->has(OpReserved) ? info : nullptr;
}

std::span<const OpcodeInfo> allOpcodes() { return kOpcodes; }

OperandCounts operandCounts(Opcode op, Version version) {
  switch (op) {
    case Opcode::TexCoord:  // texcoord t# (1_1-1_3) / texcrd r#, t# (1_4)
      return {true, version.atLeast(1, 4) ? 1 : 0};
    case Opcode::Tex:  // tex t# / texld r#, t# (1_4) / texld r#, src, s# (2_0+)
      return {true, version.sm2plus() ? 2 : version.atLeast(1, 4) ? 1 : 0};
    case Opcode::SinCos:
    case Opcode::Sgn:  // SM2 needs two scratch temporaries as extra sources
      return {true, version.major >= 3 ? 1 : 3};
    default: break;
  }
  const OpcodeInfo* info = findOpcode(op);
  if (!info) return {false, 0};
  return {info->hasDst, info->srcCount < 0 ? 0 : info->srcCount};
}

std::span<const Mnemonic> allMnemonics() { return kMnemonics; }

const Mnemonic* findMnemonic(std::string_view name) {
  for (const Mnemonic& m : kMnemonics)
    if (name == m.name) return &m;
  return nullptr;
}

std::string_view mnemonicIn(Opcode op, uint8_t control, Version version) {
  const Mnemonic* m = nullptr;
  if (op == O::Tex) {
    if (!version.atLeast(1, 4)) m = spelling(op, F::Ps1Tex, 0);
    else if (version.sm2plus() && (control & 1)) m = spelling(op, F::Sm2Up, 1);
    else if (version.sm2plus() && (control & 2)) m = spelling(op, F::Sm2Up, 2);
  } else if (op == O::TexCoord && version.ps1x() && version.minor == 4) {
    m = spelling(op, F::Ps14Only, 0);
  }
  return m ? m->name : opcodeName(op);
}

std::string_view opcodeName(Opcode op) {
  const OpcodeInfo* info = findAny(op);
  return info ? info->name : "";
}

const OpcodeRule* opcodeRuleIn(Opcode op, Version version) {
  const VersionRules* rules = findVersionRules(version);
  return rules ? findOpcodeRule(*rules, op) : nullptr;
}

}  // namespace refx::shader
