// Register files, counts and indices: every operand names a register file the version
// has (version_rules.h), within its count (some counts come from the device caps), is
// written only where the file is writable and read only where it is readable; relative
// addressing uses a0 (vs) or aL (loop) where the version allows it; special operands
// (s#, l#, i#, b#, aL, p0, vFace) appear only in the instructions that take them.
#include <algorithm>

#include "shader/validate/check.h"

namespace refx::shader::checks {
namespace {

using O = Opcode;
using R = RegType;

class RegisterCheck final : public Check {
 public:
  void instruction(Context& ctx, const Instruction& in) override {
    if (isDefOp(in.opcode) || in.opcode == O::Dcl || in.opcode == O::Phase) return;
    if (in.hasDst) {
      // texkill's operand is encoded as a destination but only read.
      const bool written = in.opcode != O::TexKill;
      const RegisterRule* r = checkIndex(ctx, in, in.dst.type, in.dst.index, written, in.dst.relative);
      if (in.dst.relative) checkRelative(ctx, in, r, in.dst.type, in.dst.rel);
    }
    for (int s = 0; s < in.srcCount; ++s) {
      const SrcParam& p = in.src[s];
      const RegisterRule* r = checkIndex(ctx, in, p.type, p.index, false, p.relative);
      if (p.relative) checkRelative(ctx, in, r, p.type, p.rel);
    }

    // Matrix macros read consecutive registers of src1.
    if (int rows = matrixRows(in.opcode); rows && in.srcCount >= 2) {
      const SrcParam& m = in.src[1];
      if (const RegisterRule* r = findRegisterRule(ctx.rules, m.type); r && !m.relative) {
        int count = ctx.registerCount(*r);
        if (int(m.index) + rows > count && int(m.index) < count)
          ctx.error(in, "V1106", "{} reads {}..{} but {} has {} {} registers", ctx.op(in), ctx.reg(m.type, m.index),
                    ctx.reg(m.type, m.index + rows - 1), ctx.name, count, r->meaning);
      }
    }
    operandKinds(ctx, in);
  }

 private:
  static const RegisterRule* checkIndex(Context& ctx, const Instruction& in, RegType t, unsigned index, bool isDst,
                                        bool relative) {
    const RegisterRule* r = findRegisterRule(ctx.rules, t);
    if (!r) {
      ctx.error(in, "V1101", "{} is not a {} register", ctx.reg(t, index), ctx.name);
      return nullptr;
    }
    int count = ctx.registerCount(*r);
    if (!relative && int(index) >= count) {
      if (count == 1)
        ctx.error(in, "V1102", "{} is out of range: {} has only {}", ctx.reg(t, index), ctx.name, ctx.reg(t, 0));
      else
        ctx.error(in, "V1102", "{} is out of range: {} has {} {} registers ({}..{})", ctx.reg(t, index), ctx.name,
                  count, r->meaning, ctx.reg(t, 0), ctx.reg(t, count - 1));
    }
    if (isDst && !(r->access & RegWrite)) {
      ctx.error(in, "V1103", "{} is read-only in {}", ctx.reg(t, index), ctx.name);
      return nullptr;
    }
    if (!isDst && !(r->access & RegRead)) {
      ctx.error(in, "V1104", "{} cannot be read in {}", ctx.reg(t, index), ctx.name);
      return nullptr;
    }
    return r;
  }

  static bool insideLoopBlock(const Context& ctx) {
    return std::any_of(ctx.blocks.begin(), ctx.blocks.end(), [](const Block& b) { return b.opcode == O::Loop; });
  }

  static void checkRelative(Context& ctx, const Instruction& in, const RegisterRule* r, RegType t,
                            const RelativeAddress& rel) {
    if (!r) return;
    const uint8_t index = ctx.rules.indexRegisters;
    if (!r->indexable || !index) {
      ctx.error(in, "V1105", "{}[…] relative addressing is not available for {} registers in {}",
                fileName(t, ctx.v), r->meaning, ctx.name);
      return;
    }
    if (rel.type == R::Loop) {
      if (!(index & IndexLoop))
        ctx.error(in, "V1105", "{} cannot index with aL", ctx.name);
      else if (!insideLoopBlock(ctx) && !ctx.inSubroutine)
        ctx.error(in, "V1107", "aL is used outside a loop … endloop block");
    } else if (rel.type == R::Addr) {
      if (!(index & (IndexA0X | IndexA0Any))) {
        ctx.error(in, "V1105", "{} cannot index with a0", ctx.name);
      } else if (!(index & IndexA0Any) && rel.component != 0) {
        ctx.error(in, "V1105", "{} indexes constants only with a0.x", ctx.name);
      } else if (!(ctx.written[registerKey(R::Addr, 0)] & (1 << (rel.component & 3)))) {
        ctx.error(in, "V1930", "a0.{} is used as an index before it is written", "xyzw"[rel.component & 3]);
      }
      if (ctx.v.major >= 3 && ctx.v.isVertex() && t == R::Output)
        ctx.error(in, "V1105", "o[…] outputs can be indexed only with aL");
    } else {
      ctx.error(in, "V1105", "relative addressing uses a0 or aL, not {}", ctx.reg(rel.type, 0));
    }
  }

  static void operandKinds(Context& ctx, const Instruction& in) {
    for (int s = 0; s < in.srcCount; ++s) {
      RegType t = in.src[s].type;
      bool ok = true;
      const char* what = "";
      switch (t) {
        case R::Sampler:
          ok = (in.opcode == O::Tex || in.opcode == O::TexLdl || in.opcode == O::TexLdd) && s == 1;
          what = "only as the sampler operand of texld/texldl/texldd";
          break;
        case R::Label:
          ok = (in.opcode == O::Call || in.opcode == O::CallNZ || in.opcode == O::Label) && s == 0;
          what = "only by call, callnz and label";
          break;
        case R::ConstInt:
          ok = (in.opcode == O::Rep && s == 0) || (in.opcode == O::Loop && s == 1);
          what = "only by rep and loop";
          break;
        case R::ConstBool:
          ok = (in.opcode == O::If && s == 0) || (in.opcode == O::CallNZ && s == 1);
          what = "only by if and callnz";
          break;
        case R::Loop:
          ok = in.opcode == O::Loop && s == 0;
          what = "only as the loop operand and as an index (c[aL + n])";
          break;
        case R::Predicate:
          ok = ((in.opcode == O::If || in.opcode == O::BreakP) && s == 0) || (in.opcode == O::CallNZ && s == 1);
          what = "only by if, callnz, breakp and as an instruction predicate";
          break;
        case R::MiscType:
          if (in.src[s].index == 1) {
            ok = in.opcode == O::SetP || in.opcode == O::IfC || in.opcode == O::BreakC;
            what = "only in comparisons (setp, if_comp, break_comp)";
          }
          break;
        default:
          break;
      }
      if (!ok && findRegisterRule(ctx.rules, t))
        ctx.error(in, "V1108", "{} can be read {}", ctx.reg(t, in.src[s].index), what);
    }
    if (in.hasDst && in.dst.type == R::Predicate && in.opcode != O::SetP)
      ctx.error(in, "V1109", "p0 is written only by setp");
    if (in.opcode == O::SetP && in.hasDst && in.dst.type != R::Predicate) ctx.error(in, "V1109", "setp writes p0");
  }
};

}  // namespace

std::unique_ptr<Check> makeRegisterCheck() { return std::make_unique<RegisterCheck>(); }

}  // namespace refx::shader::checks
