// The ps_1_x back end's machine program: instructions on values, between
// instruction selection (codegen_ps1x.cpp) and emission, and the steps that work on
// it alone (ps1x_registers.cpp): register allocation, no-op removal, co-issue.
#pragma once
#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/shader/bytecode.h"
#include "refx/shader/version_rules.h"

namespace refx::hlsl::detail::ps1x {

constexpr uint8_t kNone = 255;       // component not needed
constexpr uint8_t kIdentity = 0xE4;  // .xyzw
using Comps = std::array<uint8_t, 4>;  // per physical component: a component index or kNone

inline uint8_t maskOf(int width) { return uint8_t((1u << width) - 1); }
inline uint8_t replicate(int c) { return uint8_t(c * 0x55); }
inline int swizzleAt(uint8_t swizzle, int c) { return (swizzle >> (2 * c)) & 3; }

// How a value sits in its 4-component register.
enum class Layout : uint8_t {
  Vector,  // component i in physical component i
  Splat,   // one scalar in every component (dp3, dp4)
  Alpha,   // one scalar in .a (the alpha pipe)
};

// A value's register. Inputs and uniforms have fixed registers; values written by
// instructions get theirs from the allocator unless `pinned` (texture stages).
struct Home {
  bool fixed = false;   // v#, c#: not written by the shader
  bool pinned = false;  // written by the shader into a known register
  shader::RegType type = shader::RegType::Temp;
  int index = -1;
  Layout layout = Layout::Vector;
  int phase = 2;          // ps_1_4 phase that writes it
  bool texcoord = false;  // texcoord/texcrd of an input: w is not available
  int texcoordIndex = 0;
};

struct Register {
  shader::RegType type = shader::RegType::Temp;
  int index = -1;
  bool operator==(const Register&) const = default;
};

struct Operand {
  int value = -1;  // a value the shader writes; otherwise the fixed register below
  shader::RegType type = shader::RegType::Const;
  int index = 0;
  uint8_t swizzle = kIdentity;  // physical
  shader::SrcMod mod = shader::SrcMod::None;
};

struct MInst {
  shader::Opcode op = shader::Opcode::Nop;
  int dst = -1;  // value written
  uint8_t mask = 0xF;
  int8_t shift = 0;
  bool saturate = false;
  std::array<Operand, 3> src{};
  int srcCount = 0;
  bool texture = false;
  int phase = 2;
  bool coissue = false;
  SourceLocation where;
};

struct Program {
  const shader::VersionRules* rules = nullptr;
  bool ps14 = false;
  std::array<std::vector<MInst>, 3> tex, arith;  // per phase (1, 2); index 0 unused
  std::deque<Home> homes;                        // per value; a deque keeps references valid
  int color = -1;                                // the value that must end in r0
  uint8_t colorMask = 0xF;
  SourceLocation colorWhere;
  std::map<int, Register> registers;             // per value, after allocation

  Register registerOf(const Operand& o) const {
    if (o.value < 0) return {o.type, o.index};
    return registers.at(o.value);
  }
};

// Physical components source s of `m` reads.
uint8_t readMask(const MInst& m, int s);

// Registers for every value written (r#, and t# not holding a texture in ps_1_1 –
// 1_3), per component, within the read-port and cmp rules; the color ends in r0.
// False, with an X4532 error, when the values do not fit.
bool allocateRegisters(Program& program, DiagnosticSink& sink, const SourceLocation& entryWhere);

// Drops `mov x, x` left where a value already sits in its destination.
void removeNoOpMoves(Program& program);

// Pairs an .rgb and an .a instruction into one slot where that changes nothing.
void pairCoissue(Program& program);

}  // namespace refx::hlsl::detail::ps1x
