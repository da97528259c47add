// Modifiers, swizzles and write masks: the result modifiers (_sat, _pp) and shifts
// (_x2 … _d8) the version has, and which instructions take them; write masks (ps_1_1
// – ps_1_3: .rgba, .rgb or .a); the source modifiers of the version's table, `!` only
// on b#/p0, _abs from SM3; the source swizzles the version allows (ps_1_1: .a and .b
// replicates, ps_1_4: replicates, ps_2_0: replicates and three fixed swizzles).
#include "shader/validate/check.h"

namespace refx::shader::checks {
namespace {

using O = Opcode;
using R = RegType;

class ModifierCheck final : public Check {
 public:
  void instruction(Context& ctx, const Instruction& in) override {
    if (isDefOp(in.opcode) || in.opcode == O::Dcl || in.opcode == O::Phase) return;
    if (in.hasDst) result(ctx, in);
    sources(ctx, in);
  }

 private:
  static void result(Context& ctx, const Instruction& in) {
    const VersionRules& rules = ctx.rules;
    const bool texOp = ctx.isTextureOp();
    uint8_t rm = in.dst.resultMod;
    if (rm & ~rules.resultModifiers & (ResultSaturate | ResultPartialPrecision)) {
      std::string which = (rm & ~rules.resultModifiers & ResultSaturate) ? "_sat" : "_pp";
      ctx.error(in, "V1201", "{} is not available in {}", which, ctx.name);
    }
    if (rm & ResultCentroid) ctx.error(in, "V1202", "_centroid applies only to dcl");
    if (in.dst.shift) {
      static const char* kShift[] = {"_d8", "_d4", "_d2", "", "_x2", "_x4", "_x8"};
      int sh = in.dst.shift;
      std::string n = (sh >= -3 && sh <= 3) ? kShift[sh + 3] : fmt::format("shift {}", sh);
      if (sh < rules.minShift || sh > rules.maxShift) ctx.error(in, "V1201", "{} is not available in {}", n, ctx.name);
      else if (texOp) ctx.error(in, "V1203", "{} cannot take the instruction modifier {}", ctx.op(in), n);
    }
    if ((rm & ResultSaturate) && (rules.resultModifiers & ResultSaturate)) {
      bool noSat = in.opcode == O::Frc || in.opcode == O::SinCos || (texOp && ctx.v.major >= 2);
      if (ctx.v.ps1x() && texOp) noSat = true;
      if (noSat) ctx.error(in, "V1203", "{} cannot take _sat", ctx.op(in));
    }

    // Write masks.
    uint8_t mask = in.dst.writeMask;
    if (mask == 0) ctx.error(in, "V1204", "empty write mask");
    if (in.opcode == O::Frc && ctx.v.isVertex() && ctx.v.major == 1 && mask != 0x2 && mask != 0x3)
      ctx.error(in, "V1204", "frc in {} writes .y or .xy", ctx.name);
    if (ctx.ps11()) {
      if (texOp && mask != 0xF) ctx.error(in, "V1204", "{} takes no write mask", ctx.op(in));
      else if (!texOp && mask != 0xF && mask != 0x7 && mask != 0x8)
        ctx.error(in, "V1204", "{} write masks are .rgba, .rgb and .a; {} is not allowed", ctx.name, maskName(mask));
      else if (in.opcode == O::Dp3 && mask == 0x8)
        ctx.error(in, "V1204", "dp3 in {} writes .rgb or .rgba (it runs in the color pipe)", ctx.name);
    }
  }

  static void sources(Context& ctx, const Instruction& in) {
    const VersionRules& rules = ctx.rules;
    const Version v = ctx.v;
    for (int s = 0; s < in.srcCount; ++s) {
      const SrcParam& p = in.src[s];
      unsigned m = unsigned(p.mod);
      if (m > 13 || !(rules.srcModifiers & (1u << m))) {
        ctx.error(in, "V1205", "source modifier {} is not available in {}", srcModName(p.mod), ctx.name);
        continue;
      }
      if (p.mod == SrcMod::Not && p.type != R::ConstBool && p.type != R::Predicate)
        ctx.error(in, "V1206", "! applies only to b# and p0 operands");
      if ((p.mod == SrcMod::Abs || p.mod == SrcMod::AbsNeg) && !isFreeOp(in.opcode) && v.major < 3)
        ctx.error(in, "V1205", "_abs is not available in {}", ctx.name);

      bool flowOperand = p.type == R::Sampler || p.type == R::Label || p.type == R::ConstInt ||
                         p.type == R::ConstBool || p.type == R::Loop || p.type == R::Predicate;
      if (flowOperand) continue;

      // ps_1_x texture-instruction sources have their own rules (texture sequences,
      // ps_1_4 texture instructions).
      if (v.ps1x() && ctx.isTextureOp()) continue;

      if (p.mod == SrcMod::Dz || p.mod == SrcMod::Dw) {
        ctx.error(in, "V1206", "_dz/_dw apply only to texld and texcrd sources");
        continue;
      }
      if (ctx.ps14() && p.type == R::Const && p.mod != SrcMod::None)
        ctx.error(in, "V1206", "source modifiers on constants are not allowed in ps_1_4 ({})",
                  ctx.reg(p.type, p.index));
      swizzle(ctx, in, p.swizzle);
    }
  }

  static void swizzle(Context& ctx, const Instruction& in, uint8_t sw) {
    switch (ctx.rules.swizzles) {
      case SwizzleRule::Ps11: {
        bool alphaOnly = in.hasDst && in.dst.writeMask == 0x8;
        if (sw == kIdentitySwizzle || sw == 0xFF) break;
        if (sw == 0xAA) {
          if (!alphaOnly)
            ctx.error(in, "V1207", "the .b selector is allowed in {} only on instructions that write .a", ctx.name);
          break;
        }
        ctx.error(in, "V1207", "{} source selectors are .a and .b (replicate); this swizzle is not allowed", ctx.name);
        break;
      }
      case SwizzleRule::Ps14:
        if (sw != kIdentitySwizzle && !isReplicate(sw))
          ctx.error(in, "V1207",
                    "ps_1_4 source selectors are .r, .g, .b and .a (replicate); this swizzle is not allowed");
        break;
      case SwizzleRule::Ps20: {
        bool arbitrary = ctx.v.major == 2 && ctx.v.minor == 1 && ctx.caps.ps2xArbitrarySwizzle;
        if (!arbitrary && sw != kIdentitySwizzle && !isReplicate(sw) && sw != 0xC9 && sw != 0xD2 && sw != 0x1B)
          ctx.error(in, "V1207", "{} allows the swizzles .xyzw, replicate, .yzxw, .zxyw and .wzyx only", ctx.name);
        break;
      }
      case SwizzleRule::Arbitrary:
        break;
    }
  }
};

}  // namespace

std::unique_ptr<Check> makeModifierCheck() { return std::make_unique<ModifierCheck>(); }

}  // namespace refx::shader::checks
