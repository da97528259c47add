// ps_1_1 – ps_1_3 instruction forms: cnd takes r0.a as its condition (the only
// register the comparison reads there), and cmp (ps_1_2 – ps_1_3) never writes a
// register it reads.
#include "shader/validate/check.h"

namespace refx::shader::checks {
namespace {

using O = Opcode;
using R = RegType;

class Ps11FormCheck final : public Check {
 public:
  void instruction(Context& ctx, const Instruction& in) override {
    if (isDefOp(in.opcode) || ctx.isTextureOp()) return;
    if (in.opcode == O::Cnd && in.srcCount >= 1) {
      const SrcParam& c = in.src[0];
      if (c.type != R::Temp || c.index != 0 || c.swizzle != 0xFF || c.mod != SrcMod::None)
        ctx.error(in, "V1809", "cnd in {} takes r0.a as its first source", ctx.name);
    }
    if (in.opcode == O::Cmp && in.hasDst)
      for (int s = 0; s < in.srcCount; ++s)
        if (in.src[s].type == in.dst.type && in.src[s].index == in.dst.index)
          ctx.error(in, "V1810", "cmp in {} cannot write a register it reads ({})", ctx.name,
                    ctx.reg(in.dst.type, in.dst.index));
  }
};

}  // namespace

std::unique_ptr<Check> makePs11FormCheck() { return std::make_unique<Ps11FormCheck>(); }

}  // namespace refx::shader::checks
