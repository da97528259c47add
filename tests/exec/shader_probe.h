// Probe helpers for lowered shaders: build a Shader directly (or assemble text), lower
// it, run one batch with inputs and constants given per lane, read registers back.
#pragma once
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/exec/interpreter.h"
#include "refx/exec/lower.h"
#include "refx/shader/bytecode.h"

namespace probe {

using namespace refx;
using namespace refx::exec;
namespace sh = refx::shader;

inline sh::DstParam D(sh::RegType t, int n, uint8_t mask = 0xF) {
  sh::DstParam d;
  d.type = t;
  d.index = uint16_t(n);
  d.writeMask = mask;
  return d;
}
inline sh::SrcParam S(sh::RegType t, int n, uint8_t swizzle = 0xE4, sh::SrcMod mod = sh::SrcMod::None) {
  sh::SrcParam s;
  s.type = t;
  s.index = uint16_t(n);
  s.swizzle = swizzle;
  s.mod = mod;
  return s;
}

// A shader built instruction by instruction.
struct Builder {
  sh::Shader shader;
  Builder(sh::ShaderType type, int major, int minor) {
    shader.version.type = type;
    shader.version.major = uint8_t(major);
    shader.version.minor = uint8_t(minor);
  }
  sh::Instruction& op(sh::Opcode opcode, std::initializer_list<sh::SrcParam> srcs = {}) {
    sh::Instruction in;
    in.opcode = opcode;
    for (const sh::SrcParam& s : srcs) in.src[in.srcCount++] = s;
    shader.instructions.push_back(in);
    return shader.instructions.back();
  }
  sh::Instruction& op(sh::Opcode opcode, sh::DstParam d, std::initializer_list<sh::SrcParam> srcs = {}) {
    sh::Instruction& in = op(opcode, srcs);
    in.hasDst = true;
    in.dst = d;
    return in;
  }
  sh::Instruction& def(int c, float x, float y, float z, float w) {
    sh::Instruction& in = op(sh::Opcode::Def, D(sh::RegType::Const, c));
    const float v[4] = {x, y, z, w};
    for (int k = 0; k < 4; ++k) std::memcpy(&in.literal[size_t(k)], &v[k], 4);
    return in;
  }
};

// Fake sampler: returns the coordinates as the color, (u, v, w, q) → (r, g, b, a),
// plus `offset` per sampler so the stage is visible; records the mode.
struct FakeSampler {
  float offset = 0;
  SampleMode lastMode = SampleMode::Implicit;
  uint16_t lastMask = 0;
  static void sample(const void* ctx, SampleMode mode, const float (*co)[kBatchLanes], uint16_t laneMask,
                     float (*out)[kBatchLanes]) {
    auto* self = const_cast<FakeSampler*>(static_cast<const FakeSampler*>(ctx));
    self->lastMode = mode;
    self->lastMask = laneMask;
    for (int c = 0; c < 4; ++c)
      for (int l = 0; l < kBatchLanes; ++l) out[c][l] = co[c][l] + self->offset;
  }
};

// One batch run of a lowered shader.
struct ShaderRun {
  LoweredShader lowered;
  BatchRegisters regs;
  std::vector<Vec4> constants = std::vector<Vec4>(kConstBumpEnv + kConstBumpEnvCount);
  std::array<std::array<int, 4>, 16> ints{};
  std::array<bool, 16> bools{};
  std::array<FakeSampler, 16> fakes{};
  std::array<SamplerBinding, 16> bindings{};
  bool usePrepare = true;

  explicit ShaderRun(const sh::Shader& s, const ShaderLoweringOptions& o = {}) : lowered(lowerShader(s, o)) {
    regs.resize(lowered.program);
    for (auto& r : regs.inputs) std::memset(&r, 0, sizeof r);
    for (auto& r : regs.outputs) std::memset(&r, 0, sizeof r);
    for (auto& r : regs.temps) std::memset(&r, 0, sizeof r);
    for (int i = 0; i < 16; ++i) {
      fakes[size_t(i)].offset = 0;
      bindings[size_t(i)] = SamplerBinding{&fakes[size_t(i)], FakeSampler::sample};
    }
  }
  // Input register value in every lane.
  ShaderRun& input(int index, Vec4 v) {
    for (int l = 0; l < kBatchLanes; ++l) setInput(index, l, v);
    return *this;
  }
  ShaderRun& setInput(int index, int lane, Vec4 v) {
    for (int c = 0; c < 4; ++c) regs.inputs[size_t(index)].c[c][lane] = v[c];
    return *this;
  }
  ShaderRun& constant(int index, Vec4 v) {
    constants[size_t(index)] = v;
    return *this;
  }
  ShaderRun& execute() {
    ExecContext ctx;
    ctx.constants = constants.data();
    ctx.constantCount = int(constants.size());
    ctx.samplers = bindings.data();
    ctx.samplerCount = 16;
    ctx.intConstants = ints.data();
    ctx.intConstantCount = 16;
    ctx.boolConstants = bools.data();
    ctx.boolConstantCount = 16;
    if (usePrepare) prepare(lowered.program, ctx, regs);
    exec::execute(lowered.program, ctx, regs);
    return *this;
  }
  Vec4 output(int index, int lane = 0) const {
    const LaneVec4& r = regs.outputs[size_t(index)];
    return {r.c[0][lane], r.c[1][lane], r.c[2][lane], r.c[3][lane]};
  }
  Vec4 temp(int index, int lane = 0) const {
    const LaneVec4& r = regs.temps[size_t(index)];
    return {r.c[0][lane], r.c[1][lane], r.c[2][lane], r.c[3][lane]};
  }
  bool laneLive(int lane) const { return regs.laneMask >> lane & 1; }
};

inline void expectNear(Vec4 got, Vec4 want, float tol = 1e-5f) {
  for (int c = 0; c < 4; ++c) {
    if (std::isnan(want[c])) {
      EXPECT_TRUE(std::isnan(got[c])) << "component " << c;
      continue;
    }
    if (std::isinf(want[c])) {
      EXPECT_EQ(got[c], want[c]) << "component " << c;
      continue;
    }
    EXPECT_NEAR(got[c], want[c], tol) << "component " << c << " got (" << got.x << ", " << got.y
                                      << ", " << got.z << ", " << got.w << ")";
  }
}

}  // namespace probe

#include "refx/shader/assembler.h"

namespace probe {

// Assembly text → lowered program ready to run.
inline ShaderRun asmRun(const char* text, const ShaderLoweringOptions& o = {}) {
  return ShaderRun(sh::assemble(text), o);
}

}  // namespace probe
