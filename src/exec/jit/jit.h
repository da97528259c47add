// Native code for IR programs: a process-wide cache of compiled programs (keyed by
// content and instruction set) and the code generator behind it. Private to exec;
// prepare() and execute() are the public entry points.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "refx/exec/interpreter.h"

namespace refx::exec::detail {

enum class JitIsa : uint8_t { Avx2, Avx512 };

// What compiled code receives: the registers and constants of one run. The
// generated code reads the fields at these offsets, so the layout is the contract.
struct JitFrame {
  float* temps;    // regs.temps[0].c[0]: register n component c at + n*64 + c*16 floats
  float* inputs;
  float* outputs;
  const Vec4* constants;   // covers JitProgram::constantsRead entries
  const Vec4* immediates;  // Program::immediates
  uint16_t* laneMask;     // regs.laneMask (kill clears bits)
  // For instructions run by the interpreter's routine:
  const Program* program;
  const ExecContext* ctx;
  BatchRegisters* regs;
};

using JitFunction = void (*)(JitFrame*);

struct JitBlock {
  JitFunction run = nullptr;  // null: no block starts here
  int32_t length = 0;         // instructions it runs
};

struct JitProgram {
  JitFunction run = nullptr;  // the whole program (without flow control)
  // Programs with flow control: by instruction index, the straight-line block that
  // starts there, run by the interpreter's flow control while every lane executes.
  std::vector<JitBlock> blocks;
  JitIsa isa = JitIsa::Avx2;
  // Inline code addresses registers up to these counts (1 + highest index) and
  // API constants below constantsRead.
  int tempsUsed = 0, inputsUsed = 0, outputsUsed = 0, constantsRead = 0;
  int inlineInstructions = 0, calledInstructions = 0;
  double compileMicroseconds = 0;
};

// The instruction set the CPU and the options allow (false: none, interpreter).
bool chooseJitIsa(const PrepareOptions& options, JitIsa& isa);

// The compiled form of `program` for `isa` from the cache, compiling it on first
// use (`compiled` tells). Null: the program is left to the interpreter.
std::shared_ptr<const JitProgram> jitProgram(const Program& program, JitIsa isa, bool& compiled);

// Code generation (jit_x86.cpp): null when the program is not supported.
std::unique_ptr<JitProgram> compileProgram(const Program& program, JitIsa isa);

// The frame of `program` running in `regs` (ctx and constants are set by runJit).
JitFrame jitFrame(const Program& program, BatchRegisters& regs);
// Runs compiled code (the program's, or one of its blocks) on one batch.
void runJit(const JitProgram& jit, JitFunction fn, JitFrame& frame, const ExecContext& ctx);
// Whether the code reads constants the API did not set (runJit reads them as zero from
// a padded copy).
inline bool constantsToPad(const JitProgram& jit, const ExecContext& ctx) {
  return jit.constantsRead > 0 && (ctx.constantCount < jit.constantsRead || !ctx.constants);
}

// The interpreter's routines the generated code and the code generator share
// (interpreter.cpp), so results stay bit-identical.
void executeInstruction(const Instr& in, const Program& program, const ExecContext& ctx, BatchRegisters& regs);
// Value of a uniform source register before swizzle and modifier (Imm, Const with
// local constants, unit clamp), as the interpreter reads it.
Vec4 uniformRegisterValue(const Src& s, int index, const ExecContext& ctx, const Program& p);
// Source `s` (swizzle and modifier applied) into out[component][lane], as the
// interpreter's routine reads it: relative addressing, integer and boolean constants.
void fetchSource(const Src& s, const Program& p, const ExecContext& ctx, const BatchRegisters& regs,
                 float (*out)[kBatchLanes]);

}  // namespace refx::exec::detail
