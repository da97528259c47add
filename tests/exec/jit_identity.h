// Identity checks of native code against the interpreter: the same program, inputs,
// constants and sampler run once on the interpreter (the reference) and once on the
// JIT, every register and the lane mask compared bit for bit.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "refx/exec/abi.h"
#include "refx/exec/interpreter.h"

namespace jit_identity {

using namespace refx;
using namespace refx::exec;

// Deterministic sampler, the same for both runs: a function of the coordinates and
// the mode, zero outside the lanes it is asked for (so a different lane mask shows).
inline void fakeSample(const void* context, SampleMode mode, const float (*co)[kBatchLanes],
                       uint16_t laneMask, float (*out)[kBatchLanes]) {
  const float stage = float(reinterpret_cast<uintptr_t>(context));
  for (int c = 0; c < 4; ++c)
    for (int l = 0; l < kBatchLanes; ++l) {
      const float x = co[c][l] * 0.75f + co[(c + 1) & 3][l] * 0.25f + 0.125f * float(mode) + stage;
      out[c][l] = laneMask >> l & 1 ? x - std::floor(x) : 0.0f;
    }
}

// SamplerBinding::samplePair as its contract has it: a's lookup, then b's.
inline void fakeSamplePair(const void* a, const void* b, const float (*coordsA)[kBatchLanes],
                           const float (*coordsB)[kBatchLanes], uint16_t laneMask, float (*outA)[kBatchLanes],
                           float (*outB)[kBatchLanes]) {
  fakeSample(a, SampleMode::Implicit, coordsA, laneMask, outA);
  fakeSample(b, SampleMode::Implicit, coordsB, laneMask, outB);
}
// A pair function no other binding has (pairs with it alone: the two lookups apart).
inline void otherSamplePair(const void* a, const void* b, const float (*coordsA)[kBatchLanes],
                            const float (*coordsB)[kBatchLanes], uint16_t laneMask, float (*outA)[kBatchLanes],
                            float (*outB)[kBatchLanes]) {
  fakeSamplePair(a, b, coordsA, coordsB, laneMask, outA, outB);
}

// Both results bit-identical, except that any NaN equals any NaN: when both operands
// of an op are NaN, which payload wins follows the operand order the C++ compiler
// picked for the interpreter.
inline bool sameBits(float a, float b) {
  if (std::isnan(a) && std::isnan(b)) return true;
  return std::memcmp(&a, &b, sizeof a) == 0;
}

struct Outcome {
  std::string backend;  // what ran the native side ("interpreter": not compiled)
  std::string mismatch;  // empty: identical
  double compileMicroseconds = 0;  // 0: found in the cache
  int interpretedInstructions = 0;  // run by the interpreter's routine from native code
  bool runner = false;  // the native side ran through runnerFor's runner
};

// Compile times of the programs a test compiled (cache hits left out).
struct CompileTimes {
  std::vector<double> us;
  void add(const Outcome& o) {
    if (o.compileMicroseconds > 0) us.push_back(o.compileMicroseconds);
  }
  std::string summary() const {
    if (us.empty()) return "no program compiled";
    std::vector<double> v = us;
    std::sort(v.begin(), v.end());
    double sum = 0;
    for (double x : v) sum += x;
    std::ostringstream s;
    s.precision(3);
    s << v.size() << " compiled, AsmJit compile time per program: median " << v[v.size() / 2] << " us, mean "
      << sum / double(v.size()) << " us, max " << v.back() << " us";
    return s.str();
  }
};

struct Ranges {
  float lo = -2.0f, hi = 2.0f;  // inputs, temps and constants
  bool specialValues = false;   // half the values from kSpecialValues
};

// Values where libm functions and comparisons take their special cases.
inline const float kSpecialValues[] = {
    0.0f, -0.0f, 1.0f, -1.0f, 0.5f, -0.5f, 2.0f, -2.0f, 3.0f, -3.0f, 0.25f,
    std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
    std::numeric_limits<float>::quiet_NaN(), -std::numeric_limits<float>::quiet_NaN(),
    std::numeric_limits<float>::denorm_min(), -std::numeric_limits<float>::denorm_min(),
    1e-40f, -1e-40f, std::numeric_limits<float>::min(), std::numeric_limits<float>::max(),
    -std::numeric_limits<float>::max(), 1e30f, -1e30f, 88.7f, -103.0f, 128.0f, -150.0f, 127.9961f,
    1e-7f, 100.5f, 1e6f, -1e6f, 3.14159265f, -6.2831853f, 1e10f};

inline std::string compareFile(const char* name, const std::vector<LaneVec4>& a, const std::vector<LaneVec4>& b) {
  for (size_t r = 0; r < a.size(); ++r)
    for (int c = 0; c < 4; ++c)
      for (int l = 0; l < kBatchLanes; ++l)
        if (!sameBits(a[r].c[c][l], b[r].c[c][l])) {
          std::ostringstream s;
          s.precision(9);
          s << name << r << "." << "xyzw"[c] << " lane " << l << ": interpreter " << a[r].c[c][l] << ", jit "
            << b[r].c[c][l];
          return s.str();
        }
  return {};
}

// Runs `program` over several batches (random values, full and partial lane masks)
// on the interpreter and on native code for `isa`. Samplers from `boundSamplers` on
// are unbound (the odd ones without a binding, the even ones beyond samplerCount).
inline Outcome compare(const Program& program, PrepareOptions::Isa isa, uint32_t seed, Ranges ranges = {},
                       int registerFloor = 0, int boundSamplers = kSamplerCount) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> uniform(ranges.lo, ranges.hi);
  auto value = [&](std::mt19937& g) {
    if (ranges.specialValues && g() % 2) return kSpecialValues[g() % std::size(kSpecialValues)];
    return uniform(g);
  };
  std::vector<Vec4> constants(kConstBumpEnv + kConstBumpEnvCount);
  for (Vec4& v : constants) v = Vec4(value(rng), value(rng), value(rng), value(rng));
  std::array<std::array<int, 4>, 16> ints{};
  for (auto& i : ints) i = {int(rng() % 8), int(rng() % 8), int(rng() % 3) - 1, 0};
  std::array<bool, 16> bools{};
  for (auto& b : bools) b = rng() & 1;
  std::array<SamplerBinding, kSamplerCount> samplers{};
  for (int s = 0; s < kSamplerCount; ++s) {
    SamplerBinding& b = samplers[size_t(s)];
    b.context = b.pairContext = reinterpret_cast<const void*>(uintptr_t(s));
    b.sample = s < boundSamplers || s % 2 == 0 ? fakeSample : nullptr;
    // Bound samplers but the last pair with each other (two implicit lookups in a row
    // may become one call); the last has a pair function of its own.
    if (b.sample) b.samplePair = s + 1 < kSamplerCount ? fakeSamplePair : otherSamplePair;
  }
  ExecContext ctx;
  ctx.constants = constants.data();
  ctx.constantCount = int(constants.size());
  ctx.samplers = samplers.data();
  ctx.samplerCount = std::max(boundSamplers, 2);
  ctx.intConstants = ints.data();
  ctx.intConstantCount = 16;
  ctx.boolConstants = bools.data();
  ctx.boolConstantCount = 16;

  BatchRegisters ref, jit;
  for (BatchRegisters* r : {&ref, &jit}) {
    r->resize(program);
    if (int(r->inputs.size()) < registerFloor) r->inputs.resize(size_t(registerFloor));
    if (int(r->outputs.size()) < registerFloor) r->outputs.resize(size_t(registerFloor));
  }
  PrepareOptions interpreter;
  interpreter.jit = false;
  prepare(program, ctx, ref, interpreter);
  PrepareOptions native;
  native.isa = isa;
  Outcome out;
  const ProgramBuildInfo info = prepare(program, ctx, jit, native);
  out.backend = info.backend;
  out.compileMicroseconds = info.compileMicroseconds;
  out.interpretedInstructions = info.interpretedInstructions;
  // The native side runs as the rasterizer runs it where it can: through a runner.
  const ProgramRunner run = runnerFor(program, ctx, jit);
  out.runner = bool(run);
  const uint16_t masks[] = {0xffff, 0x0f0f, 0x8421, 0xfff0, 0x0001};
  for (uint16_t mask : masks) {
    auto fill = [&](std::vector<LaneVec4>& file) {
      for (LaneVec4& r : file)
        for (auto& c : r.c)
          for (float& x : c) x = value(rng);
    };
    fill(ref.inputs), fill(ref.temps), fill(ref.outputs);
    jit.inputs = ref.inputs, jit.temps = ref.temps, jit.outputs = ref.outputs;
    ref.laneMask = jit.laneMask = mask;
    execute(program, ctx, ref);
    if (run) run();
    else execute(program, ctx, jit);
    std::string m = compareFile("o", ref.outputs, jit.outputs);
    if (m.empty()) m = compareFile("r", ref.temps, jit.temps);
    if (m.empty()) m = compareFile("v", ref.inputs, jit.inputs);
    if (m.empty() && ref.executedInstructions != jit.executedInstructions)
      m = "executed instructions: interpreter " + std::to_string(ref.executedInstructions) + ", jit " +
          std::to_string(jit.executedInstructions);
    if (m.empty() && ref.laneMask != jit.laneMask) {
      std::ostringstream s;
      s << std::hex << "laneMask: interpreter " << ref.laneMask << ", jit " << jit.laneMask;
      m = s.str();
    }
    if (!m.empty()) {
      std::ostringstream s;
      s << std::hex << "mask 0x" << mask << ": " << m;
      out.mismatch = s.str();
      return out;
    }
  }
  return out;
}

// The instruction sets to test on this machine.
inline std::vector<PrepareOptions::Isa> availableIsas() {
  std::vector<PrepareOptions::Isa> isas;
  Program p;
  p.tempCount = 1;
  p.emit(Op::Mov, dst(RegFile::Temp, 0), p.imm(Vec4(1, 2, 3, 4)));
  for (auto isa : {PrepareOptions::Isa::Avx2, PrepareOptions::Isa::Avx512}) {
    BatchRegisters r;
    r.resize(p);
    PrepareOptions o;
    o.isa = isa;
    if (std::string(prepare(p, ExecContext{}, r, o).backend) != "interpreter") isas.push_back(isa);
  }
  return isas;
}

inline const char* isaName(PrepareOptions::Isa isa) {
  return isa == PrepareOptions::Isa::Avx512 ? "avx512" : "avx2";
}

}  // namespace jit_identity
