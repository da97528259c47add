// Co-issue (ps_1_1 – ps_1_4 `+`): only pixel shaders 1.x pair instructions; a pair is
// two arithmetic instructions, one writing the color (.rgb; in ps_1_4 any subset of
// it) and one the alpha (.a), and some instructions cannot be half of a pair (the
// version table's OpNoCoissue / OpVectorOnly flags).
#include "shader/validate/check.h"

namespace refx::shader::checks {
namespace {

using O = Opcode;

class CoissueCheck final : public Check {
 public:
  void instruction(Context& ctx, const Instruction& in) override {
    if (in.coissue && !ctx.rules.coissue)
      ctx.error(in, "V1501", "co-issue (+) exists only in ps_1_1 - ps_1_4, not in {}", ctx.name);
    if (!ctx.v.ps1x()) return;
    if (in.opcode == O::Phase) {
      prevArith_ = nullptr;
      return;
    }
    if (isDefOp(in.opcode) || in.opcode == O::Dcl) return;
    pair(ctx, in);
  }

 private:
  void pair(Context& ctx, const Instruction& in) {
    bool arith = !ctx.isTextureOp() && !isFreeOp(in.opcode);
    if (!in.coissue) {
      prevArith_ = arith ? &in : nullptr;
      return;
    }
    const Instruction* first = prevArith_;
    prevArith_ = nullptr;
    if (!arith) {
      ctx.error(in, "V1502", "{} cannot be co-issued (+); only arithmetic instructions pair", ctx.op(in));
      return;
    }
    if (!first) {
      ctx.error(in, "V1503", "co-issued {} (+) must follow an arithmetic instruction it pairs with", ctx.op(in));
      return;
    }
    for (const Instruction* half : {first, &in}) {
      const OpcodeRule* r = findOpcodeRule(ctx.rules, half->opcode);
      if (r && (r->flags & OpNoCoissue)) ctx.error(in, "V1504", "{} cannot be co-issued", opName(*half, ctx.v));
    }
    uint8_t a = first->hasDst ? first->dst.writeMask : 0xF;
    uint8_t b = in.hasDst ? in.dst.writeMask : 0xF;
    bool ps14 = ctx.v.atLeast(1, 4);
    auto isColor = [&](uint8_t m) { return ps14 ? (m && !(m & 0x8)) : m == 0x7; };
    const Instruction* colorHalf = isColor(a) && b == 0x8 ? first : isColor(b) && a == 0x8 ? &in : nullptr;
    if (!colorHalf) {
      ctx.error(in, "V1505", "a co-issued pair writes {} in one instruction and .a in the other; these write {} and {}",
                ps14 ? "a subset of .rgb" : ".rgb", maskName(a), maskName(b));
      return;
    }
    const Instruction* alphaHalf = colorHalf == first ? &in : first;
    if (const OpcodeRule* r = findOpcodeRule(ctx.rules, alphaHalf->opcode); r && (r->flags & OpVectorOnly))
      ctx.error(in, "V1506", "{} can be co-issued only as the color (.rgb) half", opName(*alphaHalf, ctx.v));
  }

  const Instruction* prevArith_ = nullptr;  // the instruction a `+` pairs with
};

}  // namespace

std::unique_ptr<Check> makeCoissueCheck() { return std::make_unique<CoissueCheck>(); }

}  // namespace refx::shader::checks
