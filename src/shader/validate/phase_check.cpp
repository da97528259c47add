// ps_1_4 phases: one `phase` instruction splits the shader in two; at the marker the
// alpha of every temporary is lost, and what phase 1 wrote is what phase 2's
// dependent texld may read as coordinates. A shader without `phase` is all phase 2.
#include "shader/validate/check.h"

namespace refx::shader::checks {
namespace {

class PhaseCheck final : public Check {
 public:
  void instruction(Context& ctx, const Instruction& in) override {
    if (in.opcode != Opcode::Phase) return;
    if (ctx.phase == 2 && ctx.hasPhase) ctx.error(in, "V1401", "ps_1_4 allows one phase instruction");
    for (auto& [k, mask] : ctx.written)
      if ((k >> 16) == uint32_t(RegType::Temp)) ctx.writtenInPhase1[k & 0xFFFF] = mask;
    for (auto& [k, mask] : ctx.written)
      if ((k >> 16) == uint32_t(RegType::Temp)) mask &= 0x7;
    ctx.phase = 2;
  }
};

}  // namespace

std::unique_ptr<Check> makePhaseCheck() { return std::make_unique<PhaseCheck>(); }

}  // namespace refx::shader::checks
