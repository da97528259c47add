// Initialised reads: a temporary (and in ps_1_1 – ps_1_3 a t register) is read only
// in components written before; vs_1_1 only rejects temps never written at all (D3D8
// shaders read partially written temps); in ps_1_4 the alpha of temps is lost at the
// phase marker. This check also records what each instruction writes.
#include "shader/validate/check.h"

namespace refx::shader::checks {
namespace {

using O = Opcode;
using R = RegType;

class InitialisedReadCheck final : public Check {
 public:
  void instruction(Context& ctx, const Instruction& in) override {
    if (isDefOp(in.opcode) || in.opcode == O::Dcl || in.opcode == O::Phase) return;
    reads(ctx, in);
    if (!in.hasDst) return;
    if (uint8_t m = ctx.writtenMask(in)) ctx.written[registerKey(in.dst.type, in.dst.index)] |= m;
  }

 private:
  static void check(Context& ctx, const Instruction& in, RegType t, unsigned index, uint8_t need) {
    const bool ps11 = ctx.ps11();
    bool tracked = t == R::Temp || (ps11 && t == R::Texture);
    if (!tracked || !need) return;
    uint8_t have = 0;
    auto it = ctx.written.find(registerKey(t, index));
    if (it != ctx.written.end()) have = it->second;
    // vs_1_1 shaders (D3D8 era) read unwritten components of partially written temps
    // routinely (m3x3 then .zxyw cross products); only whole unwritten temps fail there.
    if (ctx.v.isVertex() && ctx.v.major == 1) {
      if (!have) ctx.error(in, "V1930", "{} is read before it is written", ctx.reg(t, index));
      return;
    }
    uint8_t missing = need & ~have;
    if (!missing) return;
    if (!have) {
      if (ps11 && t == R::Texture)
        ctx.error(in, "V1930", "{} is read before it is written (no texture instruction writes it)", ctx.reg(t, index));
      else
        ctx.error(in, "V1930", "{} is read before it is written", ctx.reg(t, index));
    } else if (ctx.ps14() && ctx.phase == 2 && ctx.hasPhase && missing == 0x8 && (ctx.writtenInPhase1[index] & 0x8)) {
      ctx.error(in, "V1931", "{}.a is read in phase 2 but the alpha of temporaries is lost at the phase marker",
                ctx.reg(t, index));
    } else {
      ctx.error(in, "V1930", "{}{} is read before it is written", ctx.reg(t, index), maskName(missing));
    }
  }

  static void reads(Context& ctx, const Instruction& in) {
    const bool ps11 = ctx.ps11();
    if (ps11 && ctx.isTextureOp()) return;  // checked by the texture-sequence rules
    // ps_1_4 texld r(k) sources are checked against phase 1 (ps_1_4 texture rules).
    if (!(ctx.ps14() && ctx.isTextureOp())) {
      for (int s = 0; s < in.srcCount; ++s) {
        const SrcParam& p = in.src[s];
        check(ctx, in, p.type, p.index, ctx.readMask(in, s));
        if (int rows = matrixRows(in.opcode); rows && s == 1)
          for (int k = 1; k < rows; ++k) check(ctx, in, p.type, p.index + k, matrixRowMask(in.opcode));
      }
    }
    // texkill reads its (destination-encoded) operand in ps_1_4 and SM2+.
    if (in.opcode == O::TexKill && !ps11 && in.hasDst)
      check(ctx, in, in.dst.type, in.dst.index, ctx.v.major >= 2 ? in.dst.writeMask : 0x7);
  }
};

}  // namespace

std::unique_ptr<Check> makeInitialisedReadCheck() { return std::make_unique<InitialisedReadCheck>(); }

}  // namespace refx::shader::checks
