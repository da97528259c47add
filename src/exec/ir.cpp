#include "refx/exec/ir.h"

#include <fmt/format.h>

namespace refx::exec {

Src Program::imm(Vec4 v) {
  for (size_t i = 0; i < immediates.size(); ++i)
    if (immediates[i] == v) return reg(RegFile::Imm, static_cast<int>(i));
  immediates.push_back(v);
  return reg(RegFile::Imm, static_cast<int>(immediates.size() - 1));
}

Instr& Program::emit(Op op, Dst d, Src a, Src b, Src c) {
  Instr in;
  in.op = op;
  in.dst = d;
  in.src = {a, b, c};
  code.push_back(in);
  return code.back();
}

static const char* opName(Op op) {
  static const char* names[] = {"mov", "add", "sub", "mul", "mad", "dp3", "dp4", "rcp", "rsq",
                                "min", "max", "slt", "sge", "frc", "exp2", "log2", "pow", "lrp",
                                "cmp", "cnd", "abs", "nrm", "dp2add", "tex", "texproj",
                                "texbias", "texlod", "kill", "floor", "round", "lit", "dst",
                                "crs", "sgn", "sincos", "expp", "quot", "setp", "dsx", "dsy",
                                "texgrad", "if", "else", "endif", "rep", "endrep", "loop",
                                "endloop", "break", "call", "ret"};
  return names[static_cast<int>(op)];
}

static std::string fileName(RegFile f) {
  switch (f) {
    case RegFile::Temp: return "r";
    case RegFile::Input: return "v";
    case RegFile::Output: return "o";
    case RegFile::Const: return "c";
    case RegFile::Imm: return "imm";
    case RegFile::ConstInt: return "i";
    case RegFile::ConstBool: return "b";
  }
  return "?";
}

static std::string srcText(const Src& s) {
  static const char comp[] = "xyzw";
  (void)comp;
  std::string swz;
  if (s.swizzle != kSwzXYZW) {
    swz = ".";
    for (int i = 0; i < 4; ++i) swz += comp[(s.swizzle >> (2 * i)) & 3];
  }
  std::string r = fileName(s.file) + std::to_string(s.index) + swz;
  if (s.rel == RelMode::Loop)
    r = fileName(s.file) + "[aL+" + std::to_string(s.index) + "]" + swz;
  else if (s.rel == RelMode::Temp)
    r = fmt::format("{}[r{}.{}+{}]{}", fileName(s.file), s.relReg, comp[s.relComp & 3], s.index, swz);
  switch (s.mod) {
    case SrcMod::None: return r;
    case SrcMod::Neg: return "-" + r;
    case SrcMod::Bias: return r + "_bias";
    case SrcMod::BiasNeg: return "-" + r + "_bias";
    case SrcMod::Sign: return r + "_bx2";
    case SrcMod::SignNeg: return "-" + r + "_bx2";
    case SrcMod::Comp: return "1-" + r;
    case SrcMod::X2: return r + "_x2";
    case SrcMod::X2Neg: return "-" + r + "_x2";
    case SrcMod::Abs: return r + "_abs";
    case SrcMod::AbsNeg: return "-" + r + "_abs";
  }
  return r;
}

int sourceCount(Op op) {
  switch (op) {
    case Op::Mov: case Op::Rcp: case Op::Rsq: case Op::Frc: case Op::Exp2: case Op::Log2:
    case Op::Abs: case Op::Nrm: case Op::Tex: case Op::TexProj: case Op::TexBias:
    case Op::TexLod: case Op::Kill: case Op::Floor: case Op::Round: case Op::Lit: case Op::Sgn:
    case Op::SinCos: case Op::ExpP: case Op::Dsx: case Op::Dsy: case Op::Rep: case Op::Loop:
      return 1;
    case Op::Mad: case Op::Lrp: case Op::Cmp: case Op::Cnd: case Op::Dp2Add: case Op::TexGrad:
      return 3;
    case Op::Else: case Op::EndIf: case Op::EndRep: case Op::EndLoop: case Op::Ret:
      return 0;
    case Op::If: case Op::Break: case Op::Call:
      return 2;  // the condition's operands (unused when cmp is 0)
    default:
      return 2;
  }
}

std::string listProgram(const Program& p) {
  std::string out;
  static const char comp[] = "xyzw";
  for (const Instr& in : p.code) {
    std::string mods;
    if (in.shift > 0) mods += fmt::format("_x{}", 1 << in.shift);
    if (in.shift < 0) mods += fmt::format("_d{}", 1 << -in.shift);
    if (in.saturate) mods += "_sat";
    if (in.clamp) mods += fmt::format("_clamp({},{})", in.clampLo, in.clampHi);
    std::string mask;
    if (in.dst.mask != 0xF) {
      mask = ".";
      for (int i = 0; i < 4; ++i)
        if (in.dst.mask & (1 << i)) mask += comp[i];
    }
    std::string line = fmt::format("{}{} {}{}{}", opName(in.op), mods, fileName(in.dst.file),
                                   in.dst.index, mask);
    for (int i = 0; i < sourceCount(in.op); ++i) line += ", " + srcText(in.src[i]);
    if ((in.op >= Op::Tex && in.op <= Op::TexLod) || in.op == Op::TexGrad)
      line += fmt::format(", s{}", in.sampler);
    if (in.quantize) line += fmt::format(" q{}", in.quantize);
    if (in.target >= 0) line += fmt::format(" -> {}", in.target);
    out += line + "\n";
  }
  for (size_t i = 0; i < p.immediates.size(); ++i) {
    const Vec4& v = p.immediates[i];
    out += fmt::format("i{} = ({}, {}, {}, {})\n", i, v.x, v.y, v.z, v.w);
  }
  return out;
}

}  // namespace refx::exec
