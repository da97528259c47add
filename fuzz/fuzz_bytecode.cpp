// Shader bytecode fuzz target: any bytes either decode or give refx::Error; a decoded
// shader re-encodes to tokens that decode to the same tokens, and the validator and
// the disassembler (plain and listing, which parses CTAB comments) accept it without
// crashing. A shader that validates
//  * disassembles to text that assembles back to the same tokens (comments aside, as
//    the disassembler writes them as `//` lines);
//  * lowers to the IR (or gives refx::Error for what the executor cannot run), and one
//    batch of 16 vertices or pixels runs through the interpreter, decoded by prepare()
//    and not, with the same results.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/exec/interpreter.h"
#include "refx/exec/lower.h"
#include "refx/shader/assembler.h"
#include "refx/shader/bytecode.h"
#include "refx/shader/disassembler.h"
#include "refx/shader/validator.h"

namespace {

using namespace refx;

std::vector<uint32_t> withoutComments(const shader::Shader& s) {
  shader::Shader copy = s;
  std::erase_if(copy.instructions,
                [](const shader::Instruction& i) { return i.opcode == shader::Opcode::Comment; });
  return shader::encode(copy);
}

void checkReassembles(const shader::Shader& shader) {
  const std::string text = shader::disassemble(shader);
  std::vector<uint32_t> again;
  try {
    again = shader::assembleTokens(text, "disassembly");
  } catch (const Error&) {
    std::abort();  // the disassembly of a valid shader must assemble
  }
  if (again != withoutComments(shader)) std::abort();
}

// Sampling returns the coordinates (plus the sampler number), so texture results feed
// the rest of the program like any other value.
void fakeSample(const void* context, exec::SampleMode, const float (*coords)[kBatchLanes],
                uint16_t, float (*out)[kBatchLanes]) {
  const float offset = float(reinterpret_cast<uintptr_t>(context)) * 0.0625f;
  for (int c = 0; c < 4; ++c)
    for (int l = 0; l < kBatchLanes; ++l) out[c][l] = coords[c][l] + offset;
}

// A small spread of values per lane and component, negative, fractional and > 1.
float laneValue(int reg, int component, int lane) {
  return float((reg * 7 + component * 3 + lane * 5) % 19 - 9) * 0.25f;
}

void fill(std::vector<exec::LaneVec4>& regs) {
  for (size_t r = 0; r < regs.size(); ++r)
    for (int c = 0; c < 4; ++c)
      for (int l = 0; l < kBatchLanes; ++l) regs[r].c[c][l] = laneValue(int(r), c, l);
}

// Equal values, NaN matching any NaN. The sign of a zero result is not compared: the
// decoded routines may give +0 where the plain interpreter gives -0 (as D3D9 hardware
// makes no promise about it either).
bool sameValues(const std::vector<exec::LaneVec4>& a, const std::vector<exec::LaneVec4>& b) {
  for (size_t r = 0; r < a.size(); ++r)
    for (int c = 0; c < 4; ++c)
      for (int l = 0; l < kBatchLanes; ++l) {
        const float x = a[r].c[c][l], y = b[r].c[c][l];
        if (!(x == y || (std::isnan(x) && std::isnan(y)))) return false;
      }
  return true;
}

void execute(const shader::Shader& shader) {
  exec::LoweredShader lowered;
  try {
    lowered = exec::lowerShader(shader);
  } catch (const Error&) {
    return;
  }
  std::vector<Vec4> constants(exec::kConstBumpEnv + exec::kConstBumpEnvCount);
  for (size_t i = 0; i < constants.size(); ++i)
    constants[i] = Vec4(laneValue(int(i), 0, 1), laneValue(int(i), 1, 2), laneValue(int(i), 2, 3),
                        laneValue(int(i), 3, 4));
  std::array<std::array<int, 4>, 16> ints{};
  for (size_t i = 0; i < ints.size(); ++i) ints[i] = {int(i % 5), int(i % 3), 1, 0};
  std::array<bool, 16> bools{};
  for (size_t i = 0; i < bools.size(); ++i) bools[i] = i % 2;
  std::array<exec::SamplerBinding, 16> samplers{};
  for (size_t i = 0; i < samplers.size(); ++i)
    samplers[i] = {reinterpret_cast<const void*>(i), fakeSample};
  exec::ExecContext ctx;
  ctx.constants = constants.data();
  ctx.constantCount = int(constants.size());
  ctx.samplers = samplers.data();
  ctx.samplerCount = int(samplers.size());
  ctx.intConstants = ints.data();
  ctx.intConstantCount = int(ints.size());
  ctx.boolConstants = bools.data();
  ctx.boolConstantCount = int(bools.size());

  exec::BatchRegisters plain, prepared;
  for (exec::BatchRegisters* regs : {&plain, &prepared}) {
    regs->resize(lowered.program);
    fill(regs->temps);
    fill(regs->inputs);
    fill(regs->outputs);
  }
  exec::execute(lowered.program, ctx, plain);
  exec::prepare(lowered.program, ctx, prepared);
  exec::execute(lowered.program, ctx, prepared);
  if (plain.laneMask != prepared.laneMask || !sameValues(plain.outputs, prepared.outputs))
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<uint32_t> tokens = shader::tokensFromBytes({data, size - size % 4});
  shader::Shader shader;
  try {
    shader = shader::decode(tokens);
  } catch (const Error&) {
    return 0;
  }
  // Re-encoding is canonical: decode → encode is a fixed point after one pass.
  std::vector<uint32_t> once = shader::encode(shader);
  if (shader::encode(shader::decode(once)) != once) __builtin_trap();
  const bool valid = shader::validate(shader).empty();
  (void)shader::countSlots(shader);
  (void)shader::disassemble(shader);
  shader::DisassemblyOptions listing;
  listing.listing = true;
  (void)shader::disassemble(shader, listing);
  if (!valid) return 0;
  checkReassembles(shader::decode(once));
  execute(shader);
  return 0;
}
