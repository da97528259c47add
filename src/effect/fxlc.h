// fx_2_0 preshaders (reference fx2-binary.md §5): the FXLC code that D3DX runs on the
// CPU — for a state value that is an expression of parameters (a standalone blob,
// version 0x46580200) and for the uniform-only computations of a compiled shader (a
// PRES comment inside the shader, version 0x46580201). A blob is a version token,
// comment blocks CTAB (the inputs: parameters in input registers), PRSI (shaders only),
// CLIT (64-bit literals), FXLC (the code), and the end token 0x0000FFFF.
#pragma once
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "refx/shader/constant_table.h"

namespace refx::effect::detail {

constexpr uint32_t kFxlcStandaloneVersion = 0x46580200;  // FXLC state expressions
constexpr uint32_t kFxlcShaderVersion = 0x46580201;      // PRES inside a shader

// Register tables of an operand (§5.5).
enum class FxlcTable : uint32_t { Literal = 1, Input = 2, Output = 4, BoolOutput = 5, IntOutput = 6, Temp = 7 };

// Opcodes (bits 20–30 of the opword, §5.6).
namespace fxlc_op {
constexpr uint32_t Nop = 0x000, Mov = 0x100, Neg = 0x101, Rcp = 0x103, Frc = 0x104, Exp = 0x105, Log = 0x106,
                   Rsq = 0x107, Sin = 0x108, Cos = 0x109, Asin = 0x10A, Acos = 0x10B, Atan = 0x10C, Min = 0x200,
                   Max = 0x201, Lt = 0x202, Ge = 0x203, Add = 0x204, Mul = 0x205, Atan2 = 0x206, Div = 0x208,
                   Cmp = 0x300, Dot = 0x500;
}

struct FxlcOperand {
  FxlcTable table = FxlcTable::Temp;
  uint32_t offset = 0;  // component index: register * 4 + component (literals: the literal's index)
  bool indexed = false;
  FxlcTable indexTable = FxlcTable::Input;
  uint32_t indexOffset = 0;
};

struct FxlcInstruction {
  uint32_t opcode = fxlc_op::Mov;
  bool scalar = false;  // the first input is one component, replicated
  uint32_t count = 1;   // components 1–4
  std::vector<FxlcOperand> inputs;
  FxlcOperand output;
};

struct FxlcProgram {
  shader::ShaderConstantTable inputs;  // CTAB: parameters by name in input registers (Float4)
  std::vector<double> literals;        // CLIT
  std::vector<FxlcInstruction> code;   // FXLC

  // Output float registers (OCONST) the code writes, ascending.
  std::vector<int> outputRegisters() const;
  // Runs the code; `inputRegisters` has 4 floats per input register (a short span
  // reads zeros). Returns the output float table, 4 floats per register up to the
  // highest register written. Computes in double, keeps temporaries in double and
  // stores outputs as float.
  std::vector<float> run(std::span<const float> inputRegisters) const;
  std::string listing() const;  // "mul r0.x, c0.x, lit1" …, one instruction per line
};

// The blob: version, CTAB, PRSI (when `prsi`: shader-embedded), CLIT, FXLC, end token.
std::vector<uint32_t> encodeFxlc(const FxlcProgram& program, uint32_t version, bool prsi);
// Reads a blob (`tokens` from the version token on; anything after the end token is
// ignored). Throws refx::Error naming `what` and the byte offset `at + 4·i` of the
// DWORD that is wrong.
FxlcProgram decodeFxlc(std::span<const uint32_t> tokens, const std::string& what, size_t at);

// The comment payload ('CTAB', then the table) of a constant table, target `target`.
std::vector<uint32_t> encodeConstantTable(const shader::ShaderConstantTable& table, uint32_t version);

}  // namespace refx::effect::detail
