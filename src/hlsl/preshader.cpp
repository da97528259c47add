#include "hlsl/preshader.h"

#include <algorithm>
#include <cmath>

#include "hlsl/constant_table.h"

namespace refx::hlsl {

using namespace detail;

namespace {

// Operations the preshader evaluator runs; anything else (inputs, texture reads,
// derivatives, texkill, relative addressing) keeps its instruction in the shader.
bool evaluable(IrOp op) {
  switch (op) {
    case IrOp::Uniform: case IrOp::Constant: case IrOp::Combine: case IrOp::Mov: case IrOp::Add:
    case IrOp::Mul: case IrOp::Mad: case IrOp::Dp2: case IrOp::Dp3: case IrOp::Dp4: case IrOp::Min:
    case IrOp::Max: case IrOp::Slt: case IrOp::Sge: case IrOp::Cmp: case IrOp::Lrp: case IrOp::Frc:
    case IrOp::Abs: case IrOp::Nrm: case IrOp::Crs: case IrOp::Rcp: case IrOp::Rsq: case IrOp::Exp2:
    case IrOp::Log2: case IrOp::Pow: case IrOp::SinCos:
      return true;
    default: return false;
  }
}

template <typename F>
void forEachSourceReg(const IrInst& in, F&& f) {
  for (int s = 0; s < in.srcCount; ++s) f(in.src[s].reg);
  for (const IrPart& p : in.parts)
    if (p.reg >= 0) f(p.reg);
}


}  // namespace

PreshaderExtraction detail::extractPreshader(IrProgram& ir) {
  PreshaderExtraction result;
  const size_t regs = ir.regWidth.size();
  std::vector<int> def(regs, -1);
  for (size_t i = 0; i < ir.code.size(); ++i)
    if (ir.code[i].dst >= 0) def[size_t(ir.code[i].dst)] = int(i);

  // uniformOnly: the value depends on uniforms and literals alone. computed: it also
  // takes an operation to make (a uniform or a gather of uniforms is read as it is).
  std::vector<bool> uniformOnly(regs, false), computed(regs, false);
  // A variable of a flow-control region (written by Assign) changes as the shader runs.
  std::vector<bool> variable(regs, false);
  for (const IrInst& in : ir.code)
    if (in.op == IrOp::Assign && in.dst >= 0) variable[size_t(in.dst)] = true;
  for (const IrInst& in : ir.code) {
    if (in.dst < 0 || variable[size_t(in.dst)] || !evaluable(in.op)) continue;
    bool only = true, anyComputed = false;
    forEachSourceReg(in, [&](int r) {
      only = only && uniformOnly[size_t(r)];
      anyComputed = anyComputed || computed[size_t(r)];
    });
    uniformOnly[size_t(in.dst)] = only;
    const bool isLoad = in.op == IrOp::Uniform || in.op == IrOp::Constant;
    computed[size_t(in.dst)] = only && !isLoad && (in.op != IrOp::Combine || anyComputed);
  }

  // Outputs of the preshader: computed values something in the shader still reads.
  std::vector<bool> isOutput(regs, false);
  auto readByShader = [&](int r) {
    if (r >= 0 && computed[size_t(r)]) isOutput[size_t(r)] = true;
  };
  for (const IrInst& in : ir.code)
    if (in.dst < 0 || !computed[size_t(in.dst)]) forEachSourceReg(in, readByShader);
  for (const IrOutput& o : ir.outputs)
    for (const IrPart& p : o.parts) readByShader(p.reg);
  std::vector<int> outputs;
  for (const IrInst& in : ir.code)
    if (in.dst >= 0 && isOutput[size_t(in.dst)]) outputs.push_back(in.dst);
  if (outputs.empty()) return result;

  // The preshader's code: every instruction the outputs need, in program order.
  std::vector<bool> needed(ir.code.size(), false);
  std::vector<int> work(outputs);
  while (!work.empty()) {
    const int r = work.back();
    work.pop_back();
    const int d = def[size_t(r)];
    if (d < 0 || needed[size_t(d)]) continue;
    needed[size_t(d)] = true;
    forEachSourceReg(ir.code[size_t(d)], [&](int s) { work.push_back(s); });
  }
  auto program = std::make_shared<Preshader::Program>();
  program->regWidth = ir.regWidth;
  std::vector<int> inputBase(ir.uniforms.size(), -1);
  int nextInput = 0;
  for (size_t i = 0; i < ir.code.size(); ++i) {
    if (!needed[i]) continue;
    IrInst in = ir.code[i];
    if (in.op == IrOp::Uniform) {
      const int u = in.index & 0xFFFF;
      if (inputBase[size_t(u)] < 0) {
        inputBase[size_t(u)] = nextInput;
        nextInput += ir.uniforms[size_t(u)].registerCount;
        result.inputUniforms.push_back(u);
      }
      in.index = inputBase[size_t(u)] + (in.index >> 16);
    }
    program->code.push_back(std::move(in));
  }
  program->outputRegs = outputs;

  // In the shader, each output becomes a read of a constant register of its own.
  for (int r : outputs) {
    IrUniform u;
    u.name = "$preshader" + std::to_string(result.outputUniforms.size());
    u.type = Type::vector(BaseType::Float, ir.regWidth[size_t(r)]);
    u.registerCount = 1;
    u.used = true;
    u.preshaderOutput = true;
    result.outputUniforms.push_back(int(ir.uniforms.size()));
    ir.uniforms.push_back(std::move(u));
    IrInst& in = ir.code[size_t(def[size_t(r)])];
    const SourceLocation where = in.where;
    const int width = in.width;
    in = IrInst{};
    in.op = IrOp::Uniform;
    in.dst = r;
    in.width = width;
    in.index = result.outputUniforms.back();
    in.where = where;
  }
  result.program = std::move(program);
  return result;
}

std::vector<float> Preshader::run(std::span<const float> inputRegisters) const {
  std::vector<float> out;
  if (!program) return out;
  const Program& p = *program;
  std::vector<std::array<float, 4>> value(p.regWidth.size(), std::array<float, 4>{});
  auto read = [&](const IrSrc& s, int c) {
    float v = value[size_t(s.reg)][s.swizzle[size_t(c)] & 3];
    if (s.absolute) v = std::fabs(v);
    if (s.negate) v = -v;
    return v;
  };
  for (const IrInst& in : p.code) {
    std::array<float, 4> r{};
    switch (in.op) {
      case IrOp::Uniform:
        for (int c = 0; c < 4; ++c) {
          const size_t at = size_t(in.index) * 4 + size_t(c);
          r[size_t(c)] = at < inputRegisters.size() ? inputRegisters[at] : 0.0f;
        }
        break;
      case IrOp::Constant: r = in.literal; break;
      case IrOp::Combine:
        for (size_t c = 0; c < in.parts.size() && c < 4; ++c) {
          const IrPart& part = in.parts[c];
          r[c] = part.reg >= 0 ? value[size_t(part.reg)][part.component & 3] : part.literal;
        }
        break;
      case IrOp::Dp2: case IrOp::Dp3: case IrOp::Dp4: {
        const int n = in.op == IrOp::Dp2 ? 2 : in.op == IrOp::Dp3 ? 3 : 4;
        float sum = 0;
        for (int i = 0; i < n; ++i) sum += read(in.src[0], i) * read(in.src[1], i);
        r.fill(sum);
        break;
      }
      case IrOp::SinCos: {  // from the replicated source: .x = cos, .y = sin
        const float a = read(in.src[0], 0);
        r = {std::cos(a), std::sin(a), 0, 0};
        break;
      }
      case IrOp::Nrm: {
        const float x = read(in.src[0], 0), y = read(in.src[0], 1), z = read(in.src[0], 2);
        const float inv = 1.0f / std::sqrt(x * x + y * y + z * z);
        r = {x * inv, y * inv, z * inv, 0};
        break;
      }
      case IrOp::Crs: {
        const float ax = read(in.src[0], 0), ay = read(in.src[0], 1), az = read(in.src[0], 2);
        const float bx = read(in.src[1], 0), by = read(in.src[1], 1), bz = read(in.src[1], 2);
        r = {ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx, 0};
        break;
      }
      default:
        for (int c = 0; c < in.width && c < 4; ++c)
          r[size_t(c)] = evaluateComponent(in.op, read(in.src[0], c), in.srcCount > 1 ? read(in.src[1], c) : 0.0f,
                                in.srcCount > 2 ? read(in.src[2], c) : 0.0f);
    }
    if (in.saturate)
      for (float& x : r) x = std::clamp(x, 0.0f, 1.0f);
    if (in.dst >= 0) value[size_t(in.dst)] = r;
  }
  for (int reg : p.outputRegs) out.insert(out.end(), value[size_t(reg)].begin(), value[size_t(reg)].end());
  return out;
}

int Preshader::instructionCount() const {
  if (!program) return 0;
  int n = 0;
  for (const IrInst& in : program->code) n += in.op != IrOp::Uniform && in.op != IrOp::Constant;
  return n;
}

}  // namespace refx::hlsl
