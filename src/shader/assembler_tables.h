// Name tables of the shader assembly language: modifiers, register letters, declaration
// usages and versions. Shared by the assembler (and its messages) and the disassembler.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "refx/shader/bytecode.h"
#include "refx/shader/opcode_table.h"
#include "refx/shader/version_rules.h"

namespace refx::shader::asmtables {

// Mnemonics come from the opcode table.
using shader::FormRule;
using shader::MnemonicKind;
using MnemonicInfo = shader::Mnemonic;
using shader::findMnemonic;

// The closest known mnemonic within edit distance 2, or "".
std::string nearestMnemonic(std::string_view lowerName);
// The canonical mnemonic of an opcode ("mov", "texld" …).
std::string opcodeMnemonic(Opcode op);

// "vs_1_1", "ps.1.4", "ps_2_a", "vs_3_sw" (lower case) → Version.
std::optional<Version> parseVersionName(std::string_view lowerText);

Comparison findComparison(std::string_view s);          // "gt" … "le"; None if not one
std::string_view comparisonName(Comparison c);           // "gt" … "le"; "" for none or invalid
std::optional<int8_t> findShift(std::string_view s);    // "x2" → 1, "d2" → -1 …
std::string_view shiftName(int8_t shift);               // 1 → "x2", -1 → "d2"; "" for 0 or beyond ±3
std::optional<uint8_t> findResultModifier(std::string_view s);  // "sat", "pp", "centroid"
std::optional<TextureType> findTextureType(std::string_view s);  // "2d", "cube", "volume"
const char* textureTypeName(TextureType t);
std::optional<DeclUsage> findUsage(std::string_view s);  // "position", "texcoord" …
std::string_view usageName(DeclUsage u);                 // "position" …; "" beyond D3DDECLUSAGE_SAMPLE

struct OperandForm {
  bool dst;
  int src;
};
// Operands of `op` as the assembler reads them in `version` (def/dcl are parsed apart).
OperandForm operandForm(Opcode op, Version version);

struct RegisterName {
  std::string letters;  // lower case: "r", "opos", "od" … (the register namer's spelling)
  RegType type;
  bool indexed;         // takes a number (r0) or not (oPos)
  uint32_t fixedIndex;  // for names without a number (oFog = 1)
  uint32_t maxIndex;    // highest encodable number
};
// The register file named `letters` in `version`, or nullptr.
const RegisterName* findRegisterName(std::string_view letters, Version version);
// "registers of vs_1_1: r#, v#, c#, a0, oPos, …" for messages.
std::string registerHelp(Version version);

}  // namespace refx::shader::asmtables
