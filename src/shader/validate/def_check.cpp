// def / defi / defb: each defines its own register file (c#, i#, b#) within the
// version's count, writes all of it (mask .xyzw), takes no modifier, and holds values the version can represent:
// ps_1_x constants lie in [-1, 1], integer constants are loop counts (0..255), starts
// (0..255) and steps (-128..127), BOOL constants are FALSE (0) or TRUE (1).
#include <cmath>
#include <cstring>

#include "shader/validate/check.h"

namespace refx::shader::checks {
namespace {

using O = Opcode;
using R = RegType;

class DefCheck final : public Check {
 public:
  void instruction(Context& ctx, const Instruction& in) override {
    if (!isDefOp(in.opcode)) return;
    RegType want = in.opcode == O::Def ? R::Const : in.opcode == O::DefI ? R::ConstInt : R::ConstBool;
    if (!in.hasDst || in.dst.type != want) {
      ctx.error(in, "V1601", "{} defines {} registers", ctx.op(in), fileName(want, ctx.v));
      return;
    }
    if (in.dst.shift || in.dst.resultMod) {
      ctx.error(in, "V1602", "{} takes no instruction modifier", ctx.op(in));
      return;
    }
    // The assembler writes .xyzw and has no text for another mask, so nothing else could
    // round-trip.
    if ((in.dst.writeMask & 0xF) != 0xF) {
      ctx.error(in, "V1602", "{} writes the whole register (write mask .xyzw), found {}", ctx.op(in),
                in.dst.writeMask & 0xF ? maskName(in.dst.writeMask & 0xF) : "an empty mask");
    }
    const RegisterRule* r = findRegisterRule(ctx.rules, want);
    if (!r) {
      ctx.error(in, "V1101", "{} is not a {} register", ctx.reg(want, in.dst.index), ctx.name);
      return;
    }
    int count = ctx.registerCount(*r);
    if (int(in.dst.index) >= count)
      ctx.error(in, "V1102", "{} is out of range: {} has {} {} registers ({}..{})", ctx.reg(want, in.dst.index),
                ctx.name, count, r->meaning, ctx.reg(want, 0), ctx.reg(want, count - 1));
    // A BOOL constant is TRUE (1) or FALSE (0), the values the assembler writes.
    if (in.opcode == O::DefB && in.literal[0] > 1)
      ctx.error(in, "V1603", "defb {}: value 0x{:x} is neither FALSE (0) nor TRUE (1)", ctx.reg(want, in.dst.index),
                in.literal[0]);
    if (in.opcode == O::Def) {
      for (int i = 0; i < 4; ++i) {
        float f;
        std::memcpy(&f, &in.literal[i], 4);
        if (!(f >= ctx.rules.defMin && f <= ctx.rules.defMax)) {
          if (std::isnan(f) || ctx.rules.defMin < -3.0e38f)
            ctx.error(in, "V1604", "def {}: value {} is not a finite number", ctx.reg(want, in.dst.index), i);
          else
            ctx.error(in, "V1604", "def {}: {} is outside [{}, {}], the range of {} constants",
                      ctx.reg(want, in.dst.index), f, ctx.rules.defMin, ctx.rules.defMax, ctx.name);
          break;
        }
      }
    } else if (in.opcode == O::DefI) {
      auto val = [&](int i) { return int32_t(in.literal[i]); };
      if (val(0) < 0 || val(0) > 255 || val(1) < 0 || val(1) > 255 || val(2) < -128 || val(2) > 127)
        ctx.error(in, "V1605", "defi {}: iteration count and start must be in 0..255 and the step in -128..127",
                  ctx.reg(want, in.dst.index));
    }
  }
};

}  // namespace

std::unique_ptr<Check> makeDefCheck() { return std::make_unique<DefCheck>(); }

}  // namespace refx::shader::checks
