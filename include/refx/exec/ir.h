// The internal program form every shading path is lowered to: fixed-function
// vertex/pixel state and shader bytecode alike. Programs are flat lists of vec4
// instructions executed on SoA batches of kBatchLanes lanes.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "refx/core/batch.h"
#include "refx/core/math.h"

namespace refx::exec {

enum class RegFile : uint8_t {
  Temp,     // r#: scratch, per lane
  Input,    // v#: per-lane inputs (vertex attributes or interpolated values)
  Output,   // o#: per-lane outputs
  Const,    // c#: uniform float4 constants supplied per draw
  Imm,      // literal float4 values owned by the program
};

// Source modifiers: the D3D set (ps_1_x bias/bx2/comp/x2 included).
enum class SrcMod : uint8_t {
  None, Neg, Bias, BiasNeg, Sign, SignNeg, Comp, X2, X2Neg, Abs, AbsNeg,
};

struct Src {
  RegFile file = RegFile::Temp;
  uint16_t index = 0;
  uint8_t swizzle = 0xE4;  // 2 bits per component, D3D order: .xyzw = 0b11'10'01'00
  SrcMod mod = SrcMod::None;
};

struct Dst {
  RegFile file = RegFile::Temp;
  uint16_t index = 0;
  uint8_t mask = 0xF;  // bit i = component i
};

enum class Op : uint8_t {
  Mov, Add, Sub, Mul, Mad, Dp3, Dp4, Rcp, Rsq, Min, Max, Slt, Sge, Frc, Exp2, Log2, Pow,
  Lrp,   // dst = s0*s1 + (1-s0)*s2
  Cmp,   // dst = s0 >= 0 ? s1 : s2
  Cnd,   // dst = s0 > 0.5 ? s1 : s2
  Abs, Nrm, Dp2Add,
  Tex,   // dst = sample(sampler, s0.xyz) with LOD from quad derivatives
  TexProj,  // dst = sample(sampler, s0.xyz / s0.w)
  TexBias,  // dst = sample(sampler, s0.xyz) with bias s0.w
  TexLod,   // dst = sample(sampler, s0.xyz) at level s0.w
  Kill,     // lanes with any of s0.xyz < 0 (masked components) are discarded
};

// Result modifiers: shift (x2 = 1, x4 = 2, d2 = -1 …), then saturate or clamp.
struct Instr {
  Op op = Op::Mov;
  Dst dst;
  std::array<Src, 3> src{};
  int8_t shift = 0;
  bool saturate = false;
  bool clamp = false;  // clamp to [clampLo, clampHi] (ps_1_x register range)
  float clampLo = -1, clampHi = 1;
  uint8_t sampler = 0;
};

struct Program {
  std::vector<Instr> code;
  std::vector<Vec4> immediates;
  int tempCount = 0;
  int inputCount = 0;
  int outputCount = 0;
  std::string name;  // for listings

  // Helpers for program builders.
  Src imm(Vec4 v);
  int newTemp() { return tempCount++; }
  Instr& emit(Op op, Dst dst, Src a = {}, Src b = {}, Src c = {});
};

inline Src reg(RegFile f, int index, uint8_t swizzle = 0xE4, SrcMod mod = SrcMod::None) {
  return Src{f, static_cast<uint16_t>(index), swizzle, mod};
}
inline Dst dst(RegFile f, int index, uint8_t mask = 0xF) {
  return Dst{f, static_cast<uint16_t>(index), mask};
}
constexpr uint8_t swz(int x, int y, int z, int w) {
  return uint8_t(x | (y << 2) | (z << 4) | (w << 6));
}
constexpr uint8_t kSwzXYZW = swz(0, 1, 2, 3);
constexpr uint8_t kSwzWWWW = swz(3, 3, 3, 3);
constexpr uint8_t kSwzXXXX = swz(0, 0, 0, 0);
constexpr uint8_t kSwzYYYY = swz(1, 1, 1, 1);
constexpr uint8_t kSwzZZZZ = swz(2, 2, 2, 2);

// Number of source operands an op reads.
int sourceCount(Op op);
// Readable listing of a program (one instruction per line).
std::string listProgram(const Program& p);

}  // namespace refx::exec
