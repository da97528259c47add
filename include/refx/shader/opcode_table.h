// The one table of D3D9 shader opcodes: mnemonic spellings, operand form and the
// properties every reader needs (scalar sources, matrix macros, flow control,
// texture, declarations). The encoder and decoder, the assembler, the disassembler,
// the validator, the lowering to the exec IR and the HLSL back end read it.
//
// What depends on the version — whether a version has the opcode, its instruction-
// slot cost, co-issue — is in the version's opcode list (version_rules.h);
// opcodeRuleIn() reads it for one opcode.
#pragma once
#include <cstdint>
#include <span>
#include <string_view>

#include "refx/shader/bytecode.h"

namespace refx::shader {

struct OpcodeRule;
struct VersionRules;

// What kind of statement a mnemonic starts (the assembler parses each apart).
enum class MnemonicKind : uint8_t {
  Plain,
  Compare,  // if/break/setp: a comparison suffix (_gt …) selects the compare opcode
  Def,      // def/defi/defb: a register and literal values
  Dcl,      // dcl_usage / dcl_2d …: a usage token and a register
};

// The versions a spelling belongs to (the others spell the opcode differently).
enum class FormRule : uint8_t {
  Any,
  Ps1Tex,    // tex, texcoord: ps_1_0–ps_1_3
  Ps14Up,    // texld: ps_1_4 and later
  Ps14Only,  // texcrd
  Sm2Up,     // texldp, texldb
  Reserved,  // texm3x3diff: no version accepts it
};

// One way of writing an opcode in assembly ("texldp" is opcode tex, control 1).
struct Mnemonic {
  const char* name;        // lower case
  Opcode opcode;
  uint8_t control;         // specific-control bits 23:16 it sets
  MnemonicKind kind;
  Opcode compareOpcode;    // Compare kind: the opcode when a comparison suffix is present
  FormRule form;
  bool canonical;          // the name OpcodeInfo::name gives the opcode
};

enum OpcodeProperty : uint16_t {
  OpScalarSource = 1,      // each source is read as one component, replicated (rcp, exp, sincos …)
  OpReplicateSwizzle = 2,  // SM2+: that source must carry a replicate swizzle (.x .y .z .w)
  OpFlowControl = 4,       // call … endif, label
  OpNoSlot = 8,            // takes no instruction slot: def, defi, defb, dcl, label, phase
  OpTexture = 16,          // texture addressing or sampling
  OpTextureMatrix = 32,    // ps_1_x texm3x2* / texm3x3* rows
  OpReserved = 64,         // has a number but no version accepts it (texm3x3diff)
};

struct OpcodeInfo {
  Opcode opcode;
  const char* name;        // canonical mnemonic: the SM2+ form ("texld", "texcoord" …)
  bool hasDst;
  int8_t srcCount;         // sources of the common form; -1: per version (operandCounts())
  uint8_t literals;        // DWORDs after the destination: def/defi 4, defb 1
  uint16_t properties;     // OpcodeProperty bits
  uint8_t matrixRows;      // m4x4 … m3x2: rows (one dot product each); 0 otherwise
  uint8_t matrixColumns;   // m4x4 / m4x3: 4 (dp4); m3x4 / m3x3 / m3x2: 3 (dp3)

  bool has(OpcodeProperty p) const { return (properties & p) != 0; }
};

// The opcodes a shader may contain, nullptr for unknown and reserved numbers.
const OpcodeInfo* findOpcode(Opcode op);
// Every opcode of the table, reserved ones included, in opcode order.
std::span<const OpcodeInfo> allOpcodes();

struct OperandCounts {
  bool dst;
  int src;
};
// Operand counts of `op` in `version` (tex/texcoord/sincos/sgn change with the version).
OperandCounts operandCounts(Opcode op, Version version);

// Every assembly spelling, in the order the assembler suggests near misses.
std::span<const Mnemonic> allMnemonics();
const Mnemonic* findMnemonic(std::string_view lowerName);
// The name of an instruction as `version` writes it: "tex" (ps_1_1–1_3), "texld",
// "texldp", "texldb", "texcrd" (ps_1_4) … Comparisons are not appended ("ifc").
std::string_view mnemonicIn(Opcode op, uint8_t control, Version version);
// The canonical mnemonic of `op` ("texld" for tex), "" when unknown.
std::string_view opcodeName(Opcode op);

// The version's rule for `op` (availability, slot cost, co-issue), nullptr when the
// version does not have it or is unknown.
const OpcodeRule* opcodeRuleIn(Opcode op, Version version);

}  // namespace refx::shader
