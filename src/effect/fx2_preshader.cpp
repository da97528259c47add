// A compiled shader's preshader (hlsl::Preshader, the HLSL compiler's IR program) as
// FXLC code, and the PRES comment fxc puts in the shader (fx2-binary.md §5.1, §5.8).
#include "fx2_preshader.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "hlsl/preshader.h"
#include "refx/core/diagnostics.h"

namespace refx::effect::detail {

namespace {

using hlsl::detail::IrInst;
using hlsl::detail::IrOp;
using hlsl::detail::IrSrc;

struct Translator {
  FxlcProgram prog;
  uint32_t temps = 0;

  FxlcOperand literal(double x) {
    for (size_t i = 0; i < prog.literals.size(); ++i)
      if (prog.literals[i] == x && std::signbit(prog.literals[i]) == std::signbit(x)) return {FxlcTable::Literal, uint32_t(i)};
    prog.literals.push_back(x);
    return {FxlcTable::Literal, uint32_t(prog.literals.size() - 1)};
  }
  FxlcOperand op(uint32_t opcode, std::vector<FxlcOperand> in) {
    FxlcInstruction i;
    i.opcode = opcode;
    i.inputs = std::move(in);
    i.output = {FxlcTable::Temp, temps++};
    prog.code.push_back(i);
    return i.output;
  }
  FxlcOperand abs(FxlcOperand a) { return op(fxlc_op::Max, {a, op(fxlc_op::Neg, {a})}); }
};

}  // namespace

FxlcProgram fxlcFromPreshader(const hlsl::Preshader& pre) {
  if (!pre.program) fail("a preshader without its program");
  const hlsl::Preshader::Program& ir = *pre.program;
  Translator t;
  t.prog.inputs = pre.inputs;
  t.prog.inputs.creator = "refx";
  t.prog.inputs.target = "tx";
  using Slots = std::array<FxlcOperand, 4>;
  std::vector<Slots> reg(ir.regWidth.size());
  for (Slots& s : reg) s.fill(t.literal(0));
  auto src = [&](const IrSrc& s, int c) {
    if (s.reg < 0 || size_t(s.reg) >= reg.size()) fail("preshader source register {} is out of range", s.reg);
    FxlcOperand o = reg[size_t(s.reg)][s.swizzle[size_t(c)] & 3];
    if (s.absolute) o = t.abs(o);
    if (s.negate) o = t.op(fxlc_op::Neg, {o});
    return o;
  };
  for (const IrInst& in : ir.code) {
    Slots r;
    r.fill(t.literal(0));
    const int width = std::clamp(in.width, 1, 4);
    auto each = [&](auto f) {
      for (int c = 0; c < width; ++c) r[size_t(c)] = f(c);
    };
    auto binary = [&](uint32_t opcode) {
      each([&](int c) { return t.op(opcode, {src(in.src[0], c), src(in.src[1], c)}); });
    };
    auto unary = [&](uint32_t opcode) { each([&](int c) { return t.op(opcode, {src(in.src[0], c)}); }); };
    auto dot = [&](int n) {
      FxlcOperand sum = t.op(fxlc_op::Mul, {src(in.src[0], 0), src(in.src[1], 0)});
      for (int i = 1; i < n; ++i) sum = t.op(fxlc_op::Add, {sum, t.op(fxlc_op::Mul, {src(in.src[0], i), src(in.src[1], i)})});
      return sum;
    };
    switch (in.op) {
      case IrOp::Uniform:
        for (int c = 0; c < 4; ++c) r[size_t(c)] = {FxlcTable::Input, uint32_t((in.index & 0xFFFF) * 4 + c)};
        break;
      case IrOp::Constant:
        for (int c = 0; c < 4; ++c) r[size_t(c)] = t.literal(double(in.literal[size_t(c)]));
        break;
      case IrOp::Combine:
        for (size_t c = 0; c < in.parts.size() && c < 4; ++c) {
          const hlsl::detail::IrPart& part = in.parts[c];
          r[c] = part.reg >= 0 ? reg.at(size_t(part.reg))[part.component & 3] : t.literal(double(part.literal));
        }
        break;
      case IrOp::Mov: each([&](int c) { return src(in.src[0], c); }); break;
      case IrOp::Add: binary(fxlc_op::Add); break;
      case IrOp::Mul: binary(fxlc_op::Mul); break;
      case IrOp::Min: binary(fxlc_op::Min); break;
      case IrOp::Max: binary(fxlc_op::Max); break;
      case IrOp::Slt: binary(fxlc_op::Lt); break;
      case IrOp::Sge: binary(fxlc_op::Ge); break;
      case IrOp::Mad:
        each([&](int c) {
          return t.op(fxlc_op::Add, {t.op(fxlc_op::Mul, {src(in.src[0], c), src(in.src[1], c)}), src(in.src[2], c)});
        });
        break;
      case IrOp::Cmp:
        each([&](int c) { return t.op(fxlc_op::Cmp, {src(in.src[0], c), src(in.src[1], c), src(in.src[2], c)}); });
        break;
      case IrOp::Lrp:  // a * b + (1 - a) * c
        each([&](int c) {
          const FxlcOperand a = src(in.src[0], c);
          const FxlcOperand oneMinusA = t.op(fxlc_op::Add, {t.literal(1), t.op(fxlc_op::Neg, {a})});
          return t.op(fxlc_op::Add, {t.op(fxlc_op::Mul, {a, src(in.src[1], c)}), t.op(fxlc_op::Mul, {oneMinusA, src(in.src[2], c)})});
        });
        break;
      case IrOp::Frc: unary(fxlc_op::Frc); break;
      case IrOp::Rcp: unary(fxlc_op::Rcp); break;
      case IrOp::Rsq: unary(fxlc_op::Rsq); break;
      case IrOp::Exp2: unary(fxlc_op::Exp); break;
      case IrOp::Log2: unary(fxlc_op::Log); break;
      case IrOp::Abs: each([&](int c) { return t.abs(src(in.src[0], c)); }); break;
      case IrOp::Pow:  // |a|^b = 2^(b · log2|a|)
        each([&](int c) {
          return t.op(fxlc_op::Exp, {t.op(fxlc_op::Mul, {src(in.src[1], c), t.op(fxlc_op::Log, {src(in.src[0], c)})})});
        });
        break;
      case IrOp::Dp2:
      case IrOp::Dp3:
      case IrOp::Dp4: {
        const FxlcOperand sum = dot(in.op == IrOp::Dp2 ? 2 : in.op == IrOp::Dp3 ? 3 : 4);
        r.fill(sum);
        break;
      }
      case IrOp::Nrm: {
        FxlcOperand sum = t.op(fxlc_op::Mul, {src(in.src[0], 0), src(in.src[0], 0)});
        for (int c = 1; c < 3; ++c)
          sum = t.op(fxlc_op::Add, {sum, t.op(fxlc_op::Mul, {src(in.src[0], c), src(in.src[0], c)})});
        const FxlcOperand inv = t.op(fxlc_op::Rsq, {sum});
        for (int c = 0; c < 3; ++c) r[size_t(c)] = t.op(fxlc_op::Mul, {src(in.src[0], c), inv});
        break;
      }
      case IrOp::Crs: {
        auto a = [&](int c) { return src(in.src[0], c); };
        auto b = [&](int c) { return src(in.src[1], c); };
        auto cross = [&](int i, int j) {
          return t.op(fxlc_op::Add, {t.op(fxlc_op::Mul, {a(i), b(j)}), t.op(fxlc_op::Neg, {t.op(fxlc_op::Mul, {a(j), b(i)})})});
        };
        r[0] = cross(1, 2);
        r[1] = cross(2, 0);
        r[2] = cross(0, 1);
        break;
      }
      case IrOp::SinCos: {
        const FxlcOperand a = src(in.src[0], 0);
        r[0] = t.op(fxlc_op::Cos, {a});
        r[1] = t.op(fxlc_op::Sin, {a});
        break;
      }
      default: fail("preshader instruction {} has no FXLC form", int(in.op));
    }
    if (in.saturate)
      for (int c = 0; c < width; ++c)
        r[size_t(c)] = t.op(fxlc_op::Min, {t.op(fxlc_op::Max, {r[size_t(c)], t.literal(0)}), t.literal(1)});
    if (in.dst >= 0) reg.at(size_t(in.dst)) = r;
  }
  if (ir.outputRegs.size() != pre.outputRegisters.size()) fail("preshader outputs do not match their registers");
  for (size_t i = 0; i < ir.outputRegs.size(); ++i)
    for (int c = 0; c < 4; ++c) {
      FxlcInstruction mov;
      mov.opcode = fxlc_op::Mov;
      mov.inputs = {reg.at(size_t(ir.outputRegs[i]))[size_t(c)]};
      mov.output = {FxlcTable::Output, uint32_t(pre.outputRegisters[i] * 4 + c)};
      t.prog.code.push_back(mov);
    }
  return t.prog;
}

std::vector<uint32_t> withPresComment(const std::vector<uint32_t>& tokens, const FxlcProgram& program) {
  std::vector<uint32_t> payload{0x53455250u};  // 'PRES'
  const std::vector<uint32_t> blob = encodeFxlc(program, kFxlcShaderVersion, true);
  payload.insert(payload.end(), blob.begin(), blob.end());
  if (payload.size() > 0x7FFF) fail("the preshader takes {} DWORDs; a comment holds at most 32767", payload.size());
  // After the version token and the leading comments (CTAB first), before the code.
  size_t at = 1;
  while (at < tokens.size() && (tokens[at] & 0xFFFF) == 0xFFFE) at += 1 + ((tokens[at] >> 16) & 0x7FFF);
  at = std::min(at, tokens.size());
  std::vector<uint32_t> out(tokens.begin(), tokens.begin() + std::ptrdiff_t(at));
  out.push_back(uint32_t(payload.size()) << 16 | 0xFFFE);
  out.insert(out.end(), payload.begin(), payload.end());
  out.insert(out.end(), tokens.begin() + std::ptrdiff_t(at), tokens.end());
  return out;
}

}  // namespace refx::effect::detail
