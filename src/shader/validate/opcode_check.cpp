// Opcodes: the instruction exists in the version (version_rules.h), its control bits
// and result-modifier bits are ones D3D9 defines, and a caps-dependent instruction
// runs only where the device reports it. Everything else is checked only for
// instructions this check accepts.
#include "shader/validate/check.h"

namespace refx::shader::checks {

using O = Opcode;

bool OpcodeCheck::accept(Context& ctx, const Instruction& in) {
  ctx.rule = findOpcodeRule(ctx.rules, in.opcode);
  if (isReservedOpcode(in.opcode)) {
    ctx.error(in, "V1001", "texm3x3diff is a reserved opcode and not valid in any shader");
    return false;
  }
  if (!ctx.rule) {
    ctx.error(in, "V1002", "{} is not a {} instruction", ctx.op(in), ctx.name);
    return false;
  }
  // Specific-control bits 23:16 hold the comparison of ifc/breakc/setp and, from SM2
  // on, texld's project (texldp) or bias (texldb) bit; they are reserved (0) elsewhere.
  const bool compares = in.opcode == O::IfC || in.opcode == O::BreakC || in.opcode == O::SetP;
  const bool controlOk = compares                                   ? in.control >= 1 && in.control <= 6
                         : in.opcode == O::Tex && ctx.v.major >= 2 ? in.control <= 2
                                                                    : in.control == 0;
  if (!controlOk) {
    ctx.error(in, "V1003", "{} has specific-control bits 0x{:02x}, which {} does not define for it", ctx.op(in),
              in.control, ctx.name);
    return false;
  }
  // Result modifier bits 23:20 of a destination: _sat, _pp and _centroid; bit 23 is
  // undefined.
  if (in.hasDst && (in.dst.resultMod & ~(ResultSaturate | ResultPartialPrecision | ResultCentroid))) {
    ctx.error(in, "V1004", "{} has result modifier bits 0x{:x}; only _sat, _pp and _centroid exist", ctx.op(in),
              in.dst.resultMod);
    return false;
  }
  if (ctx.rule->flags & OpNeedsCap) {
    bool ok = ctx.v.isPixel() ? ctx.caps.ps2xFlowControl : ctx.caps.vs2xFlowControl;
    if (!ok) {
      ctx.error(in, "V1005", "{} in {} needs a device that reports it (flow-control/predication caps)", ctx.op(in),
                ctx.name);
      return false;
    }
  }
  if (in.srcCount > 4) {
    ctx.error(in, "V1006", "{} has {} sources; instructions have at most 4", ctx.op(in), in.srcCount);
    return false;
  }
  return true;
}

}  // namespace refx::shader::checks
