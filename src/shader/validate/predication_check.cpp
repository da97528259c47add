// Predication (`(p0) add …`): SM3, and vs_2_x / ps_2_x where the device reports it;
// p0 must have been written by setp first.
#include "shader/validate/check.h"

namespace refx::shader::checks {
namespace {

class PredicationCheck final : public Check {
 public:
  void instruction(Context& ctx, const Instruction& in) override {
    if (!in.predicated) return;
    const Version v = ctx.v;
    bool ok = ctx.rules.predication &&
              (v.major >= 3 || (v.isPixel() ? ctx.caps.ps2xFlowControl : ctx.caps.vs2xFlowControl));
    if (!ok)
      ctx.error(in, "V1701", "predication ({}p0) is not available in {}", in.predicateNot ? "!" : "", ctx.name);
    else if (!ctx.written[registerKey(RegType::Predicate, 0)])
      ctx.error(in, "V1702", "p0 is read before it is written (setp)");
  }
};

}  // namespace

std::unique_ptr<Check> makePredicationCheck() { return std::make_unique<PredicationCheck>(); }

}  // namespace refx::shader::checks
