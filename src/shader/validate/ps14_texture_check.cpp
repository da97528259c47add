// ps_1_4 texture instructions and registers: texld / texcrd write r# (the register
// number names the texture stage, once per phase) and read t# (with one .xyz or .xyw
// selector per register, _dw only on t#) or, in phase 2, an r# phase 1 wrote (_dz at
// most twice); t# is read only by them; color inputs v# arrive in phase 2; texdepth
// works on r5 in phase 2, bem in phase 1 writes .rg.
#include <map>
#include <set>

#include "shader/validate/check.h"

namespace refx::shader::checks {
namespace {

using O = Opcode;
using R = RegType;

class Ps14TextureCheck final : public Check {
 public:
  void instruction(Context& ctx, const Instruction& in) override {
    if (in.opcode == O::Phase) {
      dstThisPhase_.clear();
      return;
    }
    if (isDefOp(in.opcode)) return;
    if (!ctx.isTextureOp()) {
      arithmetic(ctx, in);
      return;
    }
    if (!in.hasDst) return;
    const DstParam& d = in.dst;
    if (in.opcode == O::TexDepth) {
      if (d.type != R::Temp || d.index != 5) ctx.error(in, "V1405", "texdepth works only on r5");
      if (ctx.phase != 2)
        ctx.error(in, "V1405",
                  "texdepth is available only in phase 2 (after the phase marker, or in a shader without one)");
      return;
    }
    if (in.opcode == O::TexKill) {
      if (d.type != R::Temp && d.type != R::Texture) ctx.error(in, "V1406", "texkill takes an r or t register");
      return;
    }
    // texld / texcrd
    if (d.type != R::Temp) {
      ctx.error(in, "V1407", "{} writes an r register in ps_1_4", ctx.op(in));
      return;
    }
    if (!dstThisPhase_.insert(d.index).second)
      ctx.error(in, "V1407",
                "r{} is already the destination of a texture instruction in this phase (r# names texture stage #)",
                d.index);
    if (in.opcode == O::TexCoord && d.writeMask != 0x7 && d.writeMask != 0x3 && d.writeMask != 0xF)
      ctx.error(in, "V1408", "texcrd writes .rgb or .rg");
    if (in.opcode == O::Tex && d.writeMask != 0xF) ctx.error(in, "V1408", "texld takes no write mask");
    if (d.resultMod || d.shift) ctx.error(in, "V1408", "{} takes no instruction modifier", ctx.op(in));
    if (in.srcCount < 1) return;
    source(ctx, in);
  }

 private:
  static void arithmetic(Context& ctx, const Instruction& in) {
    for (int s = 0; s < in.srcCount; ++s) {
      const SrcParam& p = in.src[s];
      if (p.type == R::Texture)
        ctx.error(in, "V1402", "{} can be read only by texld and texcrd in ps_1_4", ctx.reg(p.type, p.index));
      if (p.type == R::Input && ctx.phase == 1)
        ctx.error(in, "V1403", "{} cannot be read in phase 1 of ps_1_4 (color inputs arrive in phase 2)",
                  ctx.reg(p.type, p.index));
    }
    if (in.opcode == O::Bem) {
      if (ctx.phase != 1) ctx.error(in, "V1404", "bem is allowed only in phase 1 of ps_1_4 (before the phase marker)");
      if (in.hasDst && in.dst.writeMask != 0x3) ctx.error(in, "V1404", "bem writes .rg only");
    }
  }

  void source(Context& ctx, const Instruction& in) {
    const DstParam& d = in.dst;
    const SrcParam& p = in.src[0];
    uint8_t sw = p.swizzle;
    bool xyw = sw == 0xF4;
    if (sw != kIdentitySwizzle && sw != 0xA4 && sw != 0xF4)
      ctx.error(in, "V1409", "{} sources take the .xyz or .xyw selector only", ctx.op(in));
    if (p.mod != SrcMod::None && p.mod != SrcMod::Dz && p.mod != SrcMod::Dw)
      ctx.error(in, "V1410", "{} sources take _dz/_dw only", ctx.op(in));
    if (p.type == R::Texture) {
      if (p.mod == SrcMod::Dz) ctx.error(in, "V1410", "_dz applies to r registers; t registers take _dw");
      if (p.mod == SrcMod::Dw) xyw = true;
      if (p.mod == SrcMod::Dw && in.opcode == O::TexCoord && d.writeMask != 0x3)
        ctx.error(in, "V1408", "texcrd with _dw writes .rg only");
      auto [it, fresh] = selector_.emplace(p.index, xyw ? 1 : 0);
      if (!fresh && it->second != (xyw ? 1 : 0))
        ctx.error(in, "V1409", "t{} is read with both .xyz and .xyw; every read of one t register uses the same selector",
                  p.index);
    } else if (p.type == R::Temp) {
      if (in.opcode == O::TexCoord) {
        ctx.error(in, "V1411", "texcrd reads only t registers");
      } else if (ctx.phase == 1 || !ctx.hasPhase) {
        ctx.error(in, "V1411", "texld reads r{}, but r registers are texld coordinates only in phase 2 (after the phase marker)",
                  p.index);
      } else {
        uint8_t need = ctx.readMask(in, 0);
        uint8_t have = ctx.writtenInPhase1[p.index];
        if (need & ~have)
          ctx.error(in, "V1411", "r{}{} used as texld coordinates must be written in phase 1", p.index,
                    maskName(need & ~have));
      }
      if (p.mod == SrcMod::Dw) ctx.error(in, "V1410", "_dw applies to t registers; r registers take _dz");
      if (p.mod == SrcMod::Dz && ++dzCount_ == 3) ctx.error(in, "V1412", "ps_1_4 allows _dz at most twice per shader");
    } else {
      ctx.error(in, "V1411", "{} reads a t or r register, not {}", ctx.op(in), ctx.reg(p.type, p.index));
    }
  }

  std::set<unsigned> dstThisPhase_;     // texld/texcrd destinations
  std::map<unsigned, int> selector_;    // t#: 0 = .xyz, 1 = .xyw
  int dzCount_ = 0;
};

}  // namespace

std::unique_ptr<Check> makePs14TextureCheck() { return std::make_unique<Ps14TextureCheck>(); }

}  // namespace refx::shader::checks
