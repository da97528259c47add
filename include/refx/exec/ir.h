// The internal program form every shading path is lowered to: fixed-function
// vertex/pixel state and shader bytecode alike. Programs are flat lists of vec4
// instructions executed on SoA batches of kBatchLanes lanes.
#pragma once
#include <array>
#include <cmath>
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
  ConstInt,   // i#: uniform int4 constants (ExecContext::intConstants), read as floats
  ConstBool,  // b#: uniform bool constants (ExecContext::boolConstants), read as 1.0 / 0.0
};

// Relative addressing of a source or destination register: the effective register
// is index + the value of an address register (D3D c[a0.x + n], c[aL + n], v[aL + n],
// o[aL + n]).
enum class RelMode : uint8_t {
  None,
  Temp,  // per lane: Temp register relReg, component relComp (a0 is kept in a temp)
  Loop,  // the loop counter aL of the innermost running loop (uniform)
};

// Src::flags
constexpr uint8_t kSrcClampUnit = 1;  // clamp the register value to [-1, 1] before swizzle
                                      // and modifier (ps_1_x constant reads)

// Source modifiers: the D3D set (ps_1_x bias/bx2/comp/x2 included).
enum class SrcMod : uint8_t {
  None, Neg, Bias, BiasNeg, Sign, SignNeg, Comp, X2, X2Neg, Abs, AbsNeg,
};

// A source modifier applied to one value (the D3D definitions: bias x - 0.5, bx2
// 2(x - 0.5), comp 1 - x, …).
inline float applySourceModifier(float x, SrcMod m) {
  switch (m) {
    case SrcMod::None: return x;
    case SrcMod::Neg: return -x;
    case SrcMod::Bias: return x - 0.5f;
    case SrcMod::BiasNeg: return -(x - 0.5f);
    case SrcMod::Sign: return 2.0f * (x - 0.5f);
    case SrcMod::SignNeg: return -2.0f * (x - 0.5f);
    case SrcMod::Comp: return 1.0f - x;
    case SrcMod::X2: return 2.0f * x;
    case SrcMod::X2Neg: return -2.0f * x;
    case SrcMod::Abs: return std::fabs(x);
    case SrcMod::AbsNeg: return -std::fabs(x);
  }
  return x;
}

// The affine form v * scale + offset of a source modifier, for vector code (false: not
// affine, abs). Its rounding can differ from applySourceModifier's in the sign of a zero
// (-(x - 0.5) against -x + 0.5 at x = 0.5).
inline bool affineSourceModifier(SrcMod m, float& scale, float& offset) {
  static constexpr struct { SrcMod m; float scale, offset; } kAffine[] = {
      {SrcMod::Neg, -1, 0},     {SrcMod::Bias, 1, -0.5f}, {SrcMod::BiasNeg, -1, 0.5f},
      {SrcMod::Sign, 2, -1},    {SrcMod::SignNeg, -2, 1}, {SrcMod::Comp, -1, 1},
      {SrcMod::X2, 2, 0},       {SrcMod::X2Neg, -2, 0},
  };
  for (const auto& a : kAffine)
    if (a.m == m) {
      scale = a.scale, offset = a.offset;
      return true;
    }
  return false;
}

struct Src {
  RegFile file = RegFile::Temp;
  uint16_t index = 0;
  uint8_t swizzle = 0xE4;  // 2 bits per component, D3D order: .xyzw = 0b11'10'01'00
  SrcMod mod = SrcMod::None;
  RelMode rel = RelMode::None;
  uint8_t relComp = 0;
  uint8_t flags = 0;     // kSrcClampUnit
  uint16_t relReg = 0;
  // Lane-varying files: relative reads outside [relLo, relHi) read (0,0,0,0).
  // Const: the range is the constant file (Program::localConstants, then
  // ExecContext::constants).
  uint16_t relLo = 0, relHi = 0;
};

struct Dst {
  RegFile file = RegFile::Temp;
  uint16_t index = 0;
  uint8_t mask = 0xF;  // bit i = component i
  RelMode rel = RelMode::None;  // Loop only (vs_3_0 o[aL + n]); writes outside
  uint16_t relLo = 0, relHi = 0;  // [relLo, relHi) are dropped
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
  Floor,    // per component floor (vs_1_1 mov a0.x)
  Round,    // per component round to nearest, ties to even (mova)
  Lit,      // D3D lit of s0 (x = N.L, y = N.H, w = power)
  Dist,     // D3D dst: (1, s0.y*s1.y, s0.z, s1.w)
  Crs,      // cross product of s0.xyz and s1.xyz
  Sgn,      // per component -1 / 0 / +1
  SinCos,   // x = cos(s0.x), y = sin(s0.x)
  ExpP,     // vs_1_1 expp of s0.x: (2^floor(v), v - floor(v), 2^v, 1)
  Quot,     // s0 / s1 per component, 1.0 where s1 == 0 (ps_1_4 _dz/_dw, texdepth)
  SetP,     // per component (s0 CMP s1) ? 1 : 0 with Instr::cmp
  Dsx,      // s0(x+1, y) - s0(x, y) within each 2x2 quad
  Dsy,      // s0(x, y+1) - s0(x, y) within each 2x2 quad
  TexGrad,  // dst = sample(sampler, s0) with gradients s1 (d/dx) and s2 (d/dy)
  // Flow control. Conditions: Instr::cmp = 0 means always, otherwise the comparison
  // (shader::Comparison values) of s0.x and s1.x per lane. Instr::target is the index
  // of the matching instruction.
  If,       // lanes failing the condition are masked off until Else / EndIf
  Else,     // target: the EndIf
  EndIf,
  Rep,      // repeat s0.x times (int constant; 0..255); target: the EndRep
  EndRep,   // target: the Rep
  Loop,     // aL = s0.y, s0.x times, aL += s0.z after each pass; target: the EndLoop
  EndLoop,  // target: the Loop
  Break,    // lanes meeting the condition leave the innermost Rep/Loop
  Call,     // lanes meeting the condition run the subroutine at target
  Ret,      // return from a subroutine; in the main program: end of the program
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
  uint8_t cmp = 0;       // comparison of If/Break/Call/SetP (shader::Comparison values)
  uint8_t quantize = 0;  // > 0: result rounded to multiples of 2^-quantize (fixed point)
  int32_t target = -1;   // flow control: index of the matching instruction
};

struct Program {
  std::vector<Instr> code;
  std::vector<Vec4> immediates;
  int tempCount = 0;
  int inputCount = 0;
  int outputCount = 0;
  std::string name;  // for listings
  // c# → index into immediates of the shader's local (`def`) constants, -1 where
  // the API value is read; used by relative constant reads.
  std::vector<int32_t> localConstants;
  bool flowControl = false;  // contains flow-control ops (run with execution masks)

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
