// The validator as a flat list of small checks. A driver (validator.cpp) walks the
// instructions once and hands each one to every check of the shader's version, in the
// order of the version's check table; at the end each check reports what only the
// whole shader shows (slot totals, unclosed blocks, outputs never written).
//
// Each check keeps its own state. Facts several checks read (what is written, what is
// declared, the open flow-control blocks, the ps_1_4 phase) live in the Context; the
// check that owns a fact updates it, and checks later in the table see the update for
// the same instruction, as the rules need (a dcl declares before an operand is read).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "refx/core/diagnostics.h"
#include "refx/shader/validator.h"
#include "refx/shader/version_rules.h"

namespace refx::shader::checks {

// An open if / rep / loop block.
struct Block {
  Opcode opcode;   // If, IfC, Rep, Loop
  bool dynamic;    // if_comp / if p0
  bool hasElse = false;
  SourcePos pos;
};

constexpr uint32_t registerKey(RegType t, unsigned index) { return (uint32_t(t) << 16) | (index & 0xFFFF); }

struct Context {
  Context(const Shader& s, const VersionRules& r, const ValidationCaps& c, DiagnosticSink& out, std::string f);

  const Shader& shader;
  const VersionRules& rules;
  ValidationCaps caps;
  Version v;
  std::string_view name;  // "ps_1_1"
  DiagnosticSink& sink;
  std::string file;       // for the diagnostics' location
  SourcePos end;          // position of the last instruction (whole-shader limits)

  // The rule of the instruction being checked (set by the driver once the opcode
  // check has accepted it).
  const OpcodeRule* rule = nullptr;
  // The previous instruction the opcode check accepted; Nop after a rejected one.
  Opcode previous = Opcode::Nop;

  // ---- facts shared between checks ----
  std::unordered_map<unsigned, TextureType> samplers;    // dcl_2d s# … (whole shader)
  std::unordered_map<uint32_t, uint8_t> written;         // component masks written so far
  std::unordered_map<uint32_t, uint8_t> declared;        // dcl masks so far
  std::unordered_map<uint32_t, uint8_t> subWritten;      // temps written inside subroutines
  bool anyInputDcl = false;                              // a dcl of v# anywhere
  bool hasPhase = false;                                 // ps_1_4 shader with `phase`
  int phase = 2;                                         // ps_1_4: 1 before `phase`
  std::unordered_map<unsigned, uint8_t> writtenInPhase1; // ps_1_4 r# masks at `phase`
  std::vector<Block> blocks;                             // open flow-control blocks
  bool inSubroutine = false;

  bool ps11() const { return v.ps1x() && !v.atLeast(1, 4); }  // ps_1_1 – ps_1_3
  bool ps14() const { return v.ps1x() && v.atLeast(1, 4); }
  bool isTextureOp() const { return rule && rule->textureSlots > 0; }

  template <typename... Args>
  void error(const Instruction& in, const char* code, fmt::format_string<Args...> f, Args&&... args) {
    errorAt(in.pos, code, f, std::forward<Args>(args)...);
  }
  template <typename... Args>
  void errorAt(SourcePos pos, const char* code, fmt::format_string<Args...> f, Args&&... args) {
    sink.error(SourceLocation{file, pos.line, pos.column}, code, f, std::forward<Args>(args)...);
  }

  std::string op(const Instruction& in) const;
  std::string reg(RegType t, unsigned i) const;
  int registerCount(const RegisterRule& r) const;
  // Components of source `s`'s register that the instruction reads.
  uint8_t readMask(const Instruction& in, int s) const;
  // Components an instruction writes into its destination register.
  uint8_t writtenMask(const Instruction& in) const;
  bool inLoop() const;
  bool inDynamicFlow() const;
};

class Check {
 public:
  virtual ~Check() = default;
  // Every instruction the opcode check accepted (comments are skipped).
  virtual void instruction(Context& ctx, const Instruction& in) = 0;
  virtual void finish(Context&) {}
};

// ---- names and opcode facts for messages -------------------------------------------

std::string opName(const Instruction& in, Version v);
std::string regName(RegType t, unsigned index, Version v);
std::string fileName(RegType t, Version v);  // "c", "oT", "oPos"
std::string maskName(uint8_t mask);          // ".xyz"
const char* srcModName(SrcMod m);
const char* blockName(Opcode op);
std::string versionName(Version v);

inline int swizzleComponent(uint8_t swizzle, int c) { return (swizzle >> (2 * c)) & 3; }
inline bool isReplicate(uint8_t s) { return s == 0x00 || s == 0x55 || s == 0xAA || s == 0xFF; }
inline constexpr uint8_t kIdentitySwizzle = 0xE4;

// Opcode facts, read from the opcode table (opcode_table.h).
bool isReservedOpcode(Opcode op);  // texm3x3diff
bool isMatrixTex(Opcode op);   // texm3x2pad … texm3x3
bool isFlowOp(Opcode op);      // call … breakp
bool isFreeOp(Opcode op);      // def*, dcl, comment, phase, label: no instruction slot
bool isDefOp(Opcode op);       // def, defi, defb
bool isScalarOp(Opcode op);    // rcp, rsq, exp, log, expp, logp, pow
int matrixRows(Opcode op);     // m4x4: 4 … m3x2: 2; 0 for other opcodes
uint8_t matrixRowMask(Opcode op);

// Instruction slots of one instruction as the version counts them.
struct Cost {
  int texture = 0, arithmetic = 0, flow = 0;
};
Cost instructionCost(const VersionRules& rules, const Instruction& in,
                     const std::unordered_map<unsigned, TextureType>& samplers);
std::unordered_map<unsigned, TextureType> samplerTypes(const Shader& s);

// ---- the checks ---------------------------------------------------------------------

// The opcode exists in the version, with defined control and modifier bits. The driver
// runs it first and passes an instruction on only when it accepts it.
class OpcodeCheck final : public Check {
 public:
  bool accept(Context& ctx, const Instruction& in);
  void instruction(Context&, const Instruction&) override {}
};

std::unique_ptr<Check> makeCoissueCheck();
std::unique_ptr<Check> makePredicationCheck();
std::unique_ptr<Check> makeInstructionOrderCheck();
std::unique_ptr<Check> makeDefCheck();
std::unique_ptr<Check> makeDclCheck();
std::unique_ptr<Check> makePhaseCheck();
std::unique_ptr<Check> makeRegisterCheck();
std::unique_ptr<Check> makeModifierCheck();
std::unique_ptr<Check> makeReadPortCheck();
std::unique_ptr<Check> makeTextureSequenceCheck();
std::unique_ptr<Check> makePs14TextureCheck();
std::unique_ptr<Check> makeInstructionFormCheck();
std::unique_ptr<Check> makePs11FormCheck();
std::unique_ptr<Check> makeSamplingCheck();
std::unique_ptr<Check> makeDeclaredInputCheck();
std::unique_ptr<Check> makeFlowControlCheck();
std::unique_ptr<Check> makeInitialisedReadCheck();
std::unique_ptr<Check> makeOutputCheck();
std::unique_ptr<Check> makePerShaderCountCheck();
std::unique_ptr<Check> makeSlotCheck();

}  // namespace refx::shader::checks
