// Runs a Program over one batch of kBatchLanes lanes. Dispatch happens once per
// instruction per batch; each instruction's body is a loop over the lanes.
#pragma once
#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "refx/core/batch.h"
#include "refx/exec/ir.h"

namespace refx::exec {

// One vec4 register for every lane, SoA: c[component][lane].
struct alignas(64) LaneVec4 {
  float c[4][kBatchLanes];
};

// Texture sampling as the executor sees it. coords[i][lane]; `mode` tells how
// the LOD is obtained (matching the Tex* ops). out[channel][lane].
// Grad (texldd): coords has 12 rows: 0..3 the coordinates, 4..7 their derivatives
// along screen x, 8..11 along y; a binding without gradient support may treat it as
// Implicit.
enum class SampleMode : uint8_t { Implicit, Projected, Bias, Lod, Grad };
// Lanes a texture lookup asks its sampler for: every lane of a 2x2 quad with a live
// lane. Helper pixels outside the primitive still compute values, so the derivatives
// of a dependent read (texture result used as coordinates) stay those of the surface.
inline uint16_t quadLanes(uint16_t live) {
  uint16_t m = 0;
  for (int q = 0; q < kBatchLanes / 4; ++q)
    if ((live >> (4 * q)) & 0xF) m |= uint16_t(0xF << (4 * q));
  return m;
}

struct SamplerBinding {
  const void* context = nullptr;
  void (*sample)(const void* context, SampleMode mode, const float (*coords)[kBatchLanes],
                 uint16_t laneMask, float (*out)[kBatchLanes]) = nullptr;
  // Optional: two Implicit lookups in one call. Where bindings a and b have the same
  // non-null samplePair, samplePair(a.pairContext, b.pairContext, coordsA, coordsB,
  // laneMask, outA, outB) gives what a.sample(Implicit, coordsA, ...) followed by
  // b.sample(Implicit, coordsB, ...) gives, when outA is not one of coordsB's rows.
  void (*samplePair)(const void* a, const void* b, const float (*coordsA)[kBatchLanes],
                     const float (*coordsB)[kBatchLanes], uint16_t laneMask, float (*outA)[kBatchLanes],
                     float (*outB)[kBatchLanes]) = nullptr;
  const void* pairContext = nullptr;
};

struct ExecContext {
  const Vec4* constants = nullptr;  // Const file
  int constantCount = 0;
  const SamplerBinding* samplers = nullptr;  // indexed by Instr::sampler
  int samplerCount = 0;
  const std::array<int, 4>* intConstants = nullptr;  // ConstInt file (i#)
  int intConstantCount = 0;
  const bool* boolConstants = nullptr;  // ConstBool file (b#)
  int boolConstantCount = 0;
  // Counts the batches that kMaxExecutedInstructions stopped before the program's
  // end (their outputs hold what was written so far); null: not counted.
  std::atomic<uint32_t>* boundStops = nullptr;
};

struct PreparedProgram;  // see prepare()

// Register storage for one batch; sized for a program once and reused.
struct BatchRegisters {
  std::vector<LaneVec4> temps, inputs, outputs;
  uint16_t laneMask = 0xffff;  // live lanes; Kill clears bits
  // Lanes that flow control lets write (programs with flow control only; all lanes
  // otherwise). Runs leave it at 0xffff.
  uint16_t execMask = 0xffff;
  int loopCounter = 0;  // aL of the innermost running loop
  // Instructions the last run of a program with flow control executed (flow-control
  // instructions included, lanes counted once per batch); at most kMaxExecutedInstructions.
  long executedInstructions = 0;
  std::shared_ptr<const PreparedProgram> prepared;  // set by prepare()
  void resize(const Program& p);
};

// Programs with flow control stop after this many executed instructions per batch
// (D3D9's guaranteed minimum of MaxVShaderInstructionsExecuted /
// MaxPShaderInstructionsExecuted), so no program runs forever.
constexpr long kMaxExecutedInstructions = 65535;

void execute(const Program& program, const ExecContext& ctx, BatchRegisters& regs);

namespace detail {
struct JitFrame;
}
// execute() of a prepared program on the registers it was prepared with, for many
// batches of one draw: what execute() checks on each call is checked once, and a run is
// one call of the native code. Empty (false) where execute() has more to do: no native
// code, flow control, constants the API did not set.
class ProgramRunner {
 public:
  ProgramRunner() = default;
  explicit operator bool() const { return fn_ != nullptr; }
  void operator()() const { fn_(frame_); }

 private:
  friend ProgramRunner runnerFor(const Program&, const ExecContext&, BatchRegisters&);
  void (*fn_)(detail::JitFrame*) = nullptr;
  detail::JitFrame* frame_ = nullptr;
};
// The context and registers must outlive the runner and stay as they are (the lanes'
// values excepted); the runner runs the program as execute(program, ctx, regs).
ProgramRunner runnerFor(const Program& program, const ExecContext& ctx, BatchRegisters& regs);

// How prepare() may run a program.
struct PrepareOptions {
  // Native code when the CPU allows it (AVX-512 or AVX2); false: the interpreter.
  // The environment variable REFX_JIT=0 turns native code off whatever this says.
  bool jit = true;
  // Instruction set of the native code: Auto takes the best the CPU has (AVX-512
  // with F/BW/DQ/VL, else AVX2 with FMA) at refx's active level (activeIsa() in
  // refx/core/cpu_features.h: REFX_ISA=avx2 in the environment makes Auto choose AVX2). A set the CPU lacks means the interpreter.
  enum class Isa : uint8_t { Auto, Avx2, Avx512 } isa = Isa::Auto;
};

// What prepare() chose to run a program with.
struct ProgramBuildInfo {
  const char* backend = "interpreter";  // "jit-avx512", "jit-avx2" or "interpreter"
  int instructions = 0;                 // the program's IR instructions
  // Time this call spent compiling native code: 0 when the process-wide cache
  // already held the program (or for the interpreter).
  double compileMicroseconds = 0;
  // Instructions the native code hands to the interpreter's routine, decoding their
  // operands as they run (relative addressing, integer and boolean constants …).
  int interpretedInstructions = 0;
};

// Decodes `program` once for these registers: operands resolved to lane arrays,
// constants and immediates expanded, common ops bound to specialised routines, or
// native code compiled once per process for the program's instructions (shared by
// every thread and draw; constants and immediates are read when the code runs, so
// new values never recompile).
// execute() then runs the decoded form for this program; it stays valid while the
// registers are not resized and the program, constants and samplers are unchanged.
// The results are bit-identical to the interpreter's.
ProgramBuildInfo prepare(const Program& program, const ExecContext& ctx, BatchRegisters& regs,
                         const PrepareOptions& options = {});

// Process-wide counters of the native code cache (programs by instructions and ISA).
struct JitCacheStats {
  uint64_t compiled = 0;     // programs compiled to native code
  uint64_t unsupported = 0;  // programs the code generator failed on (left to the interpreter)
  uint64_t hits = 0;         // prepare() calls that found their program compiled
  double compileMicroseconds = 0;  // total compile time
};
JitCacheStats jitCacheStats();

}  // namespace refx::exec
