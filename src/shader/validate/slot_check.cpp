// Instruction slots: macros count expanded (m4x4 = 4, vs_1_1 exp = 10 …), a ps_1_x
// co-issued pair counts once, predication costs one more slot, ps_3_0 texld variants
// cost by sampler type. ps_1_1 – ps_1_3 allow 4 texture and 8 arithmetic
// instructions, ps_1_4 6 and 8 in each phase, SM2+ versions their total, arithmetic
// and texture slot counts (ps_2_x total: the device's NumInstructionSlots).
#include <algorithm>

#include "shader/validate/check.h"

namespace refx::shader::checks {
namespace {

using O = Opcode;

class SlotCheck final : public Check {
 public:
  void instruction(Context& ctx, const Instruction& in) override {
    const SlotLimits& L = ctx.rules.slots;
    if (in.opcode == O::Phase) {
      phaseTexture_ = phaseArithmetic_ = 0;
      reportedPhaseTexture_ = reportedPhaseArithmetic_ = false;
    }
    Cost c = instructionCost(ctx.rules, in, ctx.samplers);
    texture_ += c.texture;
    arithmetic_ += c.arithmetic;
    total_ += c.texture + c.arithmetic + c.flow;
    if (!L.perPhase) return;
    phaseTexture_ += c.texture;
    phaseArithmetic_ += c.arithmetic;
    if (phaseTexture_ > L.texture && !reportedPhaseTexture_) {
      reportedPhaseTexture_ = true;
      ctx.error(in, "V1901", "ps_1_4 allows {} texture instructions per phase, phase {} has {}", L.texture, ctx.phase,
                phaseTexture_);
    }
    if (phaseArithmetic_ > L.arithmetic && !reportedPhaseArithmetic_) {
      reportedPhaseArithmetic_ = true;
      ctx.error(in, "X5608", "ps_1_4 allows {} arithmetic instructions per phase, phase {} has {}", L.arithmetic,
                ctx.phase, phaseArithmetic_);
    }
  }

  // The totals are reported at the position of the shader's last instruction.
  void finish(Context& ctx) override {
    const SlotLimits& L = ctx.rules.slots;
    const Version v = ctx.v;
    if (v.ps1x()) {
      if (L.perPhase) return;
      if (texture_ > L.texture)
        ctx.errorAt(ctx.end, "V1901", "{} allows {} texture instructions, this shader has {}", ctx.name, L.texture,
                    texture_);
      if (arithmetic_ > L.arithmetic)
        ctx.errorAt(ctx.end, "X5608", "{} allows {} arithmetic instructions, this shader has {}", ctx.name,
                    L.arithmetic, arithmetic_);
      return;
    }
    int totalLimit = L.totalFromCaps ? std::clamp(ctx.caps.ps2xInstructionSlots, 96, 512) : L.total;
    if (totalLimit && total_ > totalLimit)
      ctx.errorAt(ctx.end, "V1902", "{} allows {} instruction slots, this shader uses {}", ctx.name, totalLimit,
                  total_);
    if (L.arithmetic && arithmetic_ > L.arithmetic)
      ctx.errorAt(ctx.end, "X5608", "{} allows {} arithmetic instruction slots, this shader uses {}", ctx.name,
                  L.arithmetic, arithmetic_);
    bool texLimit = L.texture && !(v.minor == 1 && ctx.caps.ps2xNoTexInstructionLimit);
    if (texLimit && texture_ > L.texture)
      ctx.errorAt(ctx.end, "V1901", "{} allows {} texture instruction slots, this shader uses {}", ctx.name,
                  L.texture, texture_);
  }

 private:
  int texture_ = 0, arithmetic_ = 0, total_ = 0;
  int phaseTexture_ = 0, phaseArithmetic_ = 0;  // ps_1_4
  bool reportedPhaseTexture_ = false, reportedPhaseArithmetic_ = false;
};

}  // namespace

std::unique_ptr<Check> makeSlotCheck() { return std::make_unique<SlotCheck>(); }

}  // namespace refx::shader::checks
