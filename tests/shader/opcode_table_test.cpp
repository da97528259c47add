// The opcode table against the D3D9 documentation: opcode numbers of the
// D3DSHADER_INSTRUCTION_OPCODE_TYPE enumeration (reference/bytecode.md §10), slot costs
// of the instruction tables (bytecode.md §10 notes and §10.1, instructions.md), and
// assembly text that assembles to the documented number and disassembles back.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "refx/shader/assembler.h"
#include "refx/shader/disassembler.h"
#include "refx/shader/opcode_table.h"
#include "refx/shader/version_rules.h"

using namespace refx::shader;

namespace {

constexpr Version vs(uint8_t major, uint8_t minor) { return {ShaderType::Vertex, major, minor}; }
constexpr Version ps(uint8_t major, uint8_t minor) { return {ShaderType::Pixel, major, minor}; }

// D3DSIO_* values as the D3D9 headers number them (bytecode.md §10, "#" column).
struct Numbered {
  const char* mnemonic;
  unsigned number;
};
constexpr Numbered kDocumentedNumbers[] = {
    {"nop", 0},           {"mov", 1},          {"add", 2},           {"sub", 3},
    {"mad", 4},           {"mul", 5},          {"rcp", 6},           {"rsq", 7},
    {"dp3", 8},           {"dp4", 9},          {"min", 10},          {"max", 11},
    {"slt", 12},          {"sge", 13},         {"exp", 14},          {"log", 15},
    {"lit", 16},          {"dst", 17},         {"lrp", 18},          {"frc", 19},
    {"m4x4", 20},         {"m4x3", 21},        {"m3x4", 22},         {"m3x3", 23},
    {"m3x2", 24},         {"call", 25},        {"callnz", 26},       {"loop", 27},
    {"ret", 28},          {"endloop", 29},     {"label", 30},        {"dcl", 31},
    {"pow", 32},          {"crs", 33},         {"sgn", 34},          {"abs", 35},
    {"nrm", 36},          {"sincos", 37},      {"rep", 38},          {"endrep", 39},
    {"if", 40},           {"ifc", 41},         {"else", 42},         {"endif", 43},
    {"break", 44},        {"breakc", 45},      {"mova", 46},         {"defb", 47},
    {"defi", 48},         {"texcoord", 64},    {"texcrd", 64},       {"texkill", 65},
    {"tex", 66},          {"texld", 66},       {"texldp", 66},       {"texldb", 66},
    {"texbem", 67},       {"texbeml", 68},     {"texreg2ar", 69},    {"texreg2gb", 70},
    {"texm3x2pad", 71},   {"texm3x2tex", 72},  {"texm3x3pad", 73},   {"texm3x3tex", 74},
    {"texm3x3diff", 75},  {"texm3x3spec", 76}, {"texm3x3vspec", 77}, {"expp", 78},
    {"logp", 79},         {"cnd", 80},         {"def", 81},          {"texreg2rgb", 82},
    {"texdp3tex", 83},    {"texm3x2depth", 84}, {"texdp3", 85},      {"texm3x3", 86},
    {"texdepth", 87},     {"cmp", 88},         {"bem", 89},          {"dp2add", 90},
    {"dsx", 91},          {"dsy", 92},         {"texldd", 93},       {"setp", 94},
    {"texldl", 95},       {"breakp", 96},      {"phase", 0xFFFD},
};

TEST(OpcodeTable, EveryDocumentedMnemonicHasItsNumber) {
  for (const Numbered& n : kDocumentedNumbers) {
    const Mnemonic* m = findMnemonic(n.mnemonic);
    ASSERT_NE(m, nullptr) << n.mnemonic;
    EXPECT_EQ(unsigned(m->opcode), n.number) << n.mnemonic;
  }
  // And the table spells nothing the documentation does not list.
  EXPECT_EQ(allMnemonics().size(), std::size(kDocumentedNumbers));
}

TEST(OpcodeTable, CanonicalNamesAreTheSm2Spellings) {
  EXPECT_EQ(opcodeName(Opcode::Tex), "texld");
  EXPECT_EQ(opcodeName(Opcode::TexCoord), "texcoord");
  EXPECT_EQ(opcodeName(Opcode::IfC), "ifc");
  EXPECT_EQ(opcodeName(Opcode::M3x2), "m3x2");
  for (const OpcodeInfo& info : allOpcodes()) {
    const Mnemonic* m = findMnemonic(info.name);
    ASSERT_NE(m, nullptr) << info.name;
    EXPECT_EQ(m->opcode, info.opcode) << info.name;
    EXPECT_TRUE(m->canonical) << info.name;
  }
}

TEST(OpcodeTable, SpellingsPerVersion) {
  // bytecode.md §10: tex (1_1-1_3), texld (1_4 and 2_0+), texldp/texldb are control 1/2.
  EXPECT_EQ(mnemonicIn(Opcode::Tex, 0, ps(1, 1)), "tex");
  EXPECT_EQ(mnemonicIn(Opcode::Tex, 0, ps(1, 4)), "texld");
  EXPECT_EQ(mnemonicIn(Opcode::Tex, 0, ps(2, 0)), "texld");
  EXPECT_EQ(mnemonicIn(Opcode::Tex, 1, ps(2, 0)), "texldp");
  EXPECT_EQ(mnemonicIn(Opcode::Tex, 2, ps(3, 0)), "texldb");
  EXPECT_EQ(mnemonicIn(Opcode::TexCoord, 0, ps(1, 3)), "texcoord");
  EXPECT_EQ(mnemonicIn(Opcode::TexCoord, 0, ps(1, 4)), "texcrd");
  EXPECT_EQ(findMnemonic("texldp")->control, 1);  // D3DSI_TEXLD_PROJECT
  EXPECT_EQ(findMnemonic("texldb")->control, 2);  // D3DSI_TEXLD_BIAS
  EXPECT_EQ(findMnemonic("if")->compareOpcode, Opcode::IfC);
  EXPECT_EQ(findMnemonic("break")->compareOpcode, Opcode::BreakC);
}

TEST(OpcodeTable, ReservedOpcodeIsNotDecodable) {
  // texm3x3diff (75) is reserved: spelled, so the assembler can name it, never decoded.
  EXPECT_EQ(findOpcode(Opcode::TexM3x3Diff), nullptr);
  EXPECT_EQ(findMnemonic("texm3x3diff")->form, FormRule::Reserved);
}

TEST(OpcodeTable, OperandForms) {
  // bytecode.md §10 operands column.
  EXPECT_EQ(findOpcode(Opcode::Mad)->srcCount, 3);              // D S S S
  EXPECT_FALSE(findOpcode(Opcode::Call)->hasDst);              // S(label)
  EXPECT_EQ(findOpcode(Opcode::Def)->literals, 4);              // D + 4 float literals
  EXPECT_EQ(findOpcode(Opcode::DefB)->literals, 1);             // D + 1 literal
  EXPECT_EQ(findOpcode(Opcode::TexLdd)->srcCount, 4);           // D S S S S
  EXPECT_EQ(operandCounts(Opcode::SinCos, vs(2, 0)).src, 3);    // D S S S (SM2)
  EXPECT_EQ(operandCounts(Opcode::SinCos, ps(3, 0)).src, 1);    // D S (SM3)
  EXPECT_EQ(operandCounts(Opcode::TexCoord, ps(1, 4)).src, 1);  // texcrd D S
}

TEST(OpcodeTable, Properties) {
  // instructions.md: m4x4 = 4 dp4 rows, m4x3 = 3 dp4, m3x4 = 4 dp3, m3x3 = 3 dp3, m3x2 = 2 dp3.
  EXPECT_EQ(findOpcode(Opcode::M4x4)->matrixRows, 4);
  EXPECT_EQ(findOpcode(Opcode::M4x4)->matrixColumns, 4);
  EXPECT_EQ(findOpcode(Opcode::M4x3)->matrixRows, 3);
  EXPECT_EQ(findOpcode(Opcode::M4x3)->matrixColumns, 4);
  EXPECT_EQ(findOpcode(Opcode::M3x4)->matrixRows, 4);
  EXPECT_EQ(findOpcode(Opcode::M3x4)->matrixColumns, 3);
  EXPECT_EQ(findOpcode(Opcode::M3x2)->matrixRows, 2);
  EXPECT_EQ(findOpcode(Opcode::Dp4)->matrixRows, 0);
  // Scalar instructions read one replicated component: rcp, rsq, exp, log, pow …
  for (Opcode op : {Opcode::Rcp, Opcode::Rsq, Opcode::Exp, Opcode::Log, Opcode::Pow, Opcode::ExpP, Opcode::LogP})
    EXPECT_TRUE(findOpcode(op)->has(OpReplicateSwizzle)) << opcodeName(op);
  EXPECT_TRUE(findOpcode(Opcode::SinCos)->has(OpScalarSource));
  EXPECT_FALSE(findOpcode(Opcode::Mul)->has(OpScalarSource));
  EXPECT_TRUE(findOpcode(Opcode::Rep)->has(OpFlowControl));
  EXPECT_TRUE(findOpcode(Opcode::TexM3x2Pad)->has(OpTextureMatrix));
  EXPECT_TRUE(findOpcode(Opcode::TexKill)->has(OpTexture));
  // def/dcl/label/phase = 0 slots (registers-and-limits.md §3).
  for (Opcode op : {Opcode::Def, Opcode::DefI, Opcode::DefB, Opcode::Dcl, Opcode::Label, Opcode::Phase})
    EXPECT_TRUE(findOpcode(op)->has(OpNoSlot)) << opcodeName(op);
  EXPECT_FALSE(findOpcode(Opcode::Nop)->has(OpNoSlot));
}

// The opcodes with `property`, in opcode order.
std::vector<Opcode> withProperty(OpcodeProperty property) {
  std::vector<Opcode> out;
  for (const OpcodeInfo& info : allOpcodes())
    if (info.has(property) && !info.has(OpReserved)) out.push_back(info.opcode);
  return out;
}

TEST(OpcodeTable, PropertySetsAreExact) {
  using O = Opcode;
  // instructions.md flow-control section: call … breakp, and label.
  EXPECT_EQ(withProperty(OpFlowControl),
            (std::vector<Opcode>{O::Call, O::CallNZ, O::Loop, O::Ret, O::EndLoop, O::Label, O::Rep, O::EndRep,
                                 O::If, O::IfC, O::Else, O::EndIf, O::Break, O::BreakC, O::BreakP}));
  // registers-and-limits.md §3: def/dcl/label/phase take no slot.
  EXPECT_EQ(withProperty(OpNoSlot),
            (std::vector<Opcode>{O::Label, O::Dcl, O::DefB, O::DefI, O::Def, O::Phase}));
  // The scalar instructions whose SM2+ source takes a replicate swizzle.
  EXPECT_EQ(withProperty(OpReplicateSwizzle),
            (std::vector<Opcode>{O::Rcp, O::Rsq, O::Exp, O::Log, O::Pow, O::ExpP, O::LogP}));
  // ps_1_x matrix texture instructions (texm3x3diff is reserved).
  EXPECT_EQ(withProperty(OpTextureMatrix),
            (std::vector<Opcode>{O::TexM3x2Pad, O::TexM3x2Tex, O::TexM3x3Pad, O::TexM3x3Tex, O::TexM3x3Spec,
                                 O::TexM3x3VSpec, O::TexM3x2Depth, O::TexM3x3}));
}

int arithmeticSlots(Opcode op, Version v) {
  const OpcodeRule* r = opcodeRuleIn(op, v);
  return r ? r->arithmeticSlots : -1;
}

TEST(OpcodeTable, SlotCostsPerVersion) {
  // bytecode.md §10 notes: exp/log cost 10 slots in vs_1_1 (macros), 1 slot in vs_2_0+.
  EXPECT_EQ(arithmeticSlots(Opcode::Exp, vs(1, 1)), 10);
  EXPECT_EQ(arithmeticSlots(Opcode::Exp, vs(2, 0)), 1);
  // frc in vs_1_1 is a 3-slot macro.
  EXPECT_EQ(arithmeticSlots(Opcode::Frc, vs(1, 1)), 3);
  // §10.1: lit 3 in vs_2_0+, 1 in vs_1_1.
  EXPECT_EQ(arithmeticSlots(Opcode::Lit, vs(1, 1)), 1);
  EXPECT_EQ(arithmeticSlots(Opcode::Lit, vs(3, 0)), 3);
  // cmp and dp4 in ps_1_2/1_3 cost 2 slots (max 3 and 4 per shader); cmp is 1 in ps_1_4.
  EXPECT_EQ(arithmeticSlots(Opcode::Cmp, ps(1, 2)), 2);
  EXPECT_EQ(opcodeRuleIn(Opcode::Cmp, ps(1, 3))->maxPerShader, 3);
  EXPECT_EQ(arithmeticSlots(Opcode::Dp4, ps(1, 3)), 2);
  EXPECT_EQ(opcodeRuleIn(Opcode::Dp4, ps(1, 2))->maxPerShader, 4);
  EXPECT_EQ(arithmeticSlots(Opcode::Cmp, ps(1, 4)), 1);
  // instructions.md: bem costs 2 arithmetic slots.
  EXPECT_EQ(arithmeticSlots(Opcode::Bem, ps(1, 4)), 2);
  // §10.1 arithmetic: m4x4 4, m3x2 2, lrp 2, dp2add 2, nrm 3, pow 3, sincos 8.
  EXPECT_EQ(arithmeticSlots(Opcode::M4x4, ps(2, 0)), 4);
  EXPECT_EQ(arithmeticSlots(Opcode::M3x2, vs(2, 0)), 2);
  EXPECT_EQ(arithmeticSlots(Opcode::Lrp, ps(2, 0)), 2);
  EXPECT_EQ(arithmeticSlots(Opcode::Dp2Add, ps(3, 0)), 2);
  EXPECT_EQ(arithmeticSlots(Opcode::Nrm, vs(3, 0)), 3);
  EXPECT_EQ(arithmeticSlots(Opcode::Pow, ps(2, 0)), 3);
  EXPECT_EQ(arithmeticSlots(Opcode::SinCos, ps(2, 0)), 8);
  // §10.1 flow: if/rep/loop 3, endrep/endloop 2, call 2, else/endif/ret 1.
  EXPECT_EQ(opcodeRuleIn(Opcode::If, vs(2, 0))->flowSlots, 3);
  EXPECT_EQ(opcodeRuleIn(Opcode::EndLoop, ps(3, 0))->flowSlots, 2);
  EXPECT_EQ(opcodeRuleIn(Opcode::Call, vs(3, 0))->flowSlots, 2);
  EXPECT_EQ(opcodeRuleIn(Opcode::Ret, ps(3, 0))->flowSlots, 1);
  // Availability (bytecode.md §10 version columns): lrp is not in vs_1_1, rcp not in ps_1_x,
  // texldl only in vs_3_0 / ps_3_0, loop not in ps_2_x.
  EXPECT_EQ(opcodeRuleIn(Opcode::Lrp, vs(1, 1)), nullptr);
  EXPECT_EQ(opcodeRuleIn(Opcode::Rcp, ps(1, 4)), nullptr);
  EXPECT_EQ(opcodeRuleIn(Opcode::TexLdl, ps(2, 0)), nullptr);
  EXPECT_NE(opcodeRuleIn(Opcode::TexLdl, vs(3, 0)), nullptr);
  EXPECT_EQ(opcodeRuleIn(Opcode::Loop, ps(2, 1)), nullptr);
}

// Assembly text → the documented opcode number in the first instruction token → the same text.
struct RoundTrip {
  const char* version;
  const char* text;
  unsigned opcode;
  unsigned control;
};
constexpr RoundTrip kRoundTrips[] = {
    {"vs_1_1", "m3x2 r0.xy, v0, c0", 24, 0},
    {"vs_1_1", "expp r0, v0.x", 78, 0},
    {"vs_2_0", "sincos r0.xy, r1.x, c0, c1", 37, 0},
    {"vs_2_0", "mova a0.x, r0.x", 46, 0},
    {"vs_2_x", "if_lt r0.x, r1.y", 41, 4},     // D3DSPC_LT = 4
    {"vs_2_x", "break_ge r0.x, r1.y", 45, 3},  // D3DSPC_GE = 3
    {"vs_2_x", "setp_eq p0, r0, r1", 94, 2},   // D3DSPC_EQ = 2
    {"vs_3_0", "texldl r0, r1, s0", 95, 0},
    {"ps_1_1", "tex t0", 66, 0},
    {"ps_1_1", "texcoord t1", 64, 0},
    {"ps_1_1", "texm3x3spec t3, t0, c0", 76, 0},
    {"ps_1_3", "texm3x2depth t3, t2", 84, 0},
    {"ps_1_4", "texcrd r0.xyz, t1", 64, 0},
    {"ps_1_4", "texld r1, t1", 66, 0},
    {"ps_1_4", "bem r1.xy, r0, r2", 89, 0},
    {"ps_1_4", "texdepth r5", 87, 0},
    {"ps_2_0", "texldp r0, t0, s0", 66, 1},
    {"ps_2_0", "texldb r0, t0, s0", 66, 2},
    {"ps_2_0", "dp2add r0, r1, r2, r3", 90, 0},
    {"ps_2_x", "dsx r0, r1", 91, 0},
    {"ps_3_0", "texldd r0, r1, s0, r2, r3", 93, 0},
    {"ps_3_0", "breakp p0.x", 96, 0},
};

TEST(OpcodeTable, MnemonicsAssembleToTheirNumberAndDisassembleBack) {
  for (const RoundTrip& c : kRoundTrips) {
    const std::string source = std::string(c.version) + "\n" + c.text + "\n";
    const std::vector<uint32_t> tokens = assembleTokens(source);
    ASSERT_GE(tokens.size(), 3u) << c.text;
    EXPECT_EQ(tokens[1] & 0xFFFFu, c.opcode) << c.text;
    EXPECT_EQ((tokens[1] >> 16) & 0xFFu, c.control) << c.text;
    EXPECT_EQ(disassemble(std::span<const uint32_t>(tokens)), source) << c.text;
  }
}

}  // namespace
