// Instruction order: in ps_1_x every def comes before all other instructions; in SM2+
// every dcl comes before the first arithmetic, texture or flow-control instruction;
// ps_1_1 – ps_1_3 put all texture-address instructions before the arithmetic ones,
// and ps_1_4 does so in each phase.
#include "shader/validate/check.h"

namespace refx::shader::checks {
namespace {

using O = Opcode;

class InstructionOrderCheck final : public Check {
 public:
  void instruction(Context& ctx, const Instruction& in) override {
    if (in.opcode == O::Def && ctx.v.ps1x() && seenNonDef_)
      ctx.error(in, "V1301", "def must come before all other instructions in {}", ctx.name);
    if (in.opcode == O::Dcl && in.hasDst && seenNonDecl_)
      ctx.error(in, "V1302", "dcl must come before the first arithmetic, texture or flow-control instruction");
    if (in.opcode == O::Phase) seenArithmetic_ = false;
    if (ctx.v.ps1x() && !isDefOp(in.opcode) && in.opcode != O::Dcl && in.opcode != O::Phase) {
      if (!ctx.isTextureOp()) {
        seenArithmetic_ = true;
      } else if (seenArithmetic_) {
        if (ctx.ps14())
          ctx.error(in, "V1303",
                    "{} follows an arithmetic instruction; in each ps_1_4 phase the texture instructions come first",
                    ctx.op(in));
        else
          ctx.error(in, "V1303", "{} follows an arithmetic instruction; {} needs all texture instructions first",
                    ctx.op(in), ctx.name);
      }
    }
    if (in.opcode != O::Def) seenNonDef_ = true;
    if (!isFreeOp(in.opcode)) seenNonDecl_ = true;
  }

 private:
  bool seenNonDef_ = false;      // an instruction other than def (and comments)
  bool seenNonDecl_ = false;     // an instruction other than def/dcl/comment/phase/label
  bool seenArithmetic_ = false;  // ps_1_x: in the current phase
};

}  // namespace

std::unique_ptr<Check> makeInstructionOrderCheck() { return std::make_unique<InstructionOrderCheck>(); }

}  // namespace refx::shader::checks
