// Instruction forms: the operand shapes single instructions need. SM2+: scalar
// operations take a replicate swizzle; matrix macros take a plain matrix operand,
// write .xyz (m4x3, m3x3) or .xy (m3x2) and never a register they read; sincos, crs,
// nrm, pow and sgn write temporaries with their documented masks and scratch
// operands; a0 is written by mova (vs_1_1: mov a0.x). (ps_1_1 – ps_1_3 forms:
// ps11_form_check.cpp.)
#include "shader/validate/check.h"

namespace refx::shader::checks {
namespace {

using O = Opcode;
using R = RegType;

class InstructionFormCheck final : public Check {
 public:
  void instruction(Context& ctx, const Instruction& in) override {
    if (isDefOp(in.opcode) || in.opcode == O::Dcl || in.opcode == O::Phase) return;
    if (ctx.v.isVertex() && ctx.v.major == 1 && in.hasDst && in.dst.type == R::Addr &&
        (in.opcode != O::Mov || in.dst.writeMask != 0x1))
      ctx.error(in, "V1808", "vs_1_1 writes a0 only with mov a0.x");
    if (ctx.v.major >= 2) sm2(ctx, in);
  }

 private:
  static void sm2(Context& ctx, const Instruction& in) {
    // Scalar operations take one component: a replicate swizzle.
    auto needReplicate = [&](int s, const char* what) {
      if (s < in.srcCount && !isReplicate(in.src[s].swizzle))
        ctx.error(in, "V1801", "{} needs a replicate swizzle (.x, .y, .z or .w) on its {}", ctx.op(in), what);
    };
    if (ctx.rules.scalarReplicate) {
      if (isScalarOp(in.opcode)) {
        needReplicate(0, in.srcCount > 1 ? "first source" : "source");
        if (in.opcode == O::Pow) needReplicate(1, "second source");
      }
      if (in.opcode == O::SinCos) needReplicate(0, "source");
      if (in.opcode == O::Dp2Add) needReplicate(2, "third source");
      if (in.opcode == O::IfC || in.opcode == O::BreakC) {
        needReplicate(0, "first source");
        needReplicate(1, "second source");
      }
      if ((in.opcode == O::If || in.opcode == O::BreakP) && in.srcCount && in.src[0].type == R::Predicate)
        needReplicate(0, "p0 operand");
      if (in.opcode == O::CallNZ && in.srcCount > 1 && in.src[1].type == R::Predicate)
        needReplicate(1, "p0 operand");
    }

    const DstParam& d = in.dst;
    uint8_t mask = in.hasDst ? d.writeMask : 0;
    auto srcIsDst = [&](int s) {
      return s < in.srcCount && in.hasDst && in.src[s].type == d.type && in.src[s].index == d.index;
    };

    // Matrix macros: plain matrix operand, fixed masks, no overlap.
    if (int rows = matrixRows(in.opcode); rows && in.srcCount >= 2) {
      if (in.src[1].swizzle != kIdentitySwizzle || in.src[1].mod != SrcMod::None)
        ctx.error(in, "V1802", "{} takes no swizzle or modifier on the matrix operand", ctx.op(in));
      if ((in.opcode == O::M4x3 || in.opcode == O::M3x3) && mask != 0x7) ctx.error(in, "V1802", "{} writes .xyz", ctx.op(in));
      if (in.opcode == O::M3x2 && mask != 0x3) ctx.error(in, "V1802", "m3x2 writes .xy");
      for (int s = 0; s < 2; ++s)
        if (in.hasDst && in.src[s].type == d.type && in.src[s].index <= d.index &&
            d.index < in.src[s].index + (s == 1 ? rows : 1))
          ctx.error(in, "V1802", "{} cannot write a register it reads", ctx.op(in));
    }
    switch (in.opcode) {
      case O::SinCos:
        if (mask != 0x1 && mask != 0x2 && mask != 0x3) ctx.error(in, "V1803", "sincos writes .x, .y or .xy");
        if (d.type != R::Temp) ctx.error(in, "V1803", "sincos writes a temporary register");
        if (ctx.v.major == 2 && in.srcCount >= 3) {
          if (in.src[1].type != R::Const || in.src[2].type != R::Const || in.src[1].index == in.src[2].index)
            ctx.error(in, "V1803",
                      "sincos in {} takes two different constant registers (D3DSINCOSCONST1/2) as its 2nd and 3rd operands",
                      ctx.name);
        }
        break;
      case O::Crs:
        if (!mask || (mask & 0x8)) ctx.error(in, "V1804", "crs writes a subset of .xyz");
        if (d.type != R::Temp) ctx.error(in, "V1804", "crs writes a temporary register");
        for (int s = 0; s < 2 && s < in.srcCount; ++s) {
          if (in.src[s].swizzle != kIdentitySwizzle) ctx.error(in, "V1804", "crs takes no source swizzle");
          if (srcIsDst(s)) ctx.error(in, "V1804", "crs cannot write a register it reads");
        }
        break;
      case O::Nrm:
        if (d.type != R::Temp) ctx.error(in, "V1805", "nrm writes a temporary register");
        if (srcIsDst(0)) ctx.error(in, "V1805", "nrm cannot write the register it reads");
        break;
      case O::Pow:
        if (srcIsDst(1)) ctx.error(in, "V1806", "pow cannot write the register of its exponent operand");
        break;
      case O::Sgn:
        if (ctx.v.major == 2 && in.srcCount >= 3) {
          if (in.src[1].type != R::Temp || in.src[2].type != R::Temp || in.src[1].index == in.src[2].index)
            ctx.error(in, "V1807", "sgn in {} takes two different temporary registers as scratch operands", ctx.name);
        }
        break;
      case O::MovA:
        if (d.type != R::Addr) ctx.error(in, "V1808", "mova writes a0");
        break;
      default:
        break;
    }
    if (in.hasDst && d.type == R::Addr && ctx.v.isVertex() && in.opcode != O::MovA)
      ctx.error(in, "V1808", "{} writes a0 only with mova", ctx.name);
  }
};

}  // namespace

std::unique_ptr<Check> makeInstructionFormCheck() { return std::make_unique<InstructionFormCheck>(); }

}  // namespace refx::shader::checks
