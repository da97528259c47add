// ps_1_1 – ps_1_3 texture-address instructions: each writes its own t register, in
// increasing order, from lower t registers a texture instruction wrote; texm3x2pad /
// texm3x3pad chains continue on consecutive registers with the same source and end
// with the instruction that completes the matrix; pad (and texm3x2depth) destinations
// hold no color; a register texbem/texbeml read is afterwards read only by them;
// source modifiers are limited to _bx2 where the version allows it.
#include <algorithm>
#include <initializer_list>
#include <set>

#include "shader/validate/check.h"

namespace refx::shader::checks {
namespace {

using O = Opcode;
using R = RegType;

class TextureSequenceCheck final : public Check {
 public:
  void instruction(Context& ctx, const Instruction& in) override {
    if (isDefOp(in.opcode) || in.opcode == O::Dcl || in.opcode == O::Phase) return;
    const bool texOp = ctx.isTextureOp();

    // A texm3x2pad/texm3x3pad sequence must continue with the expected instruction.
    bool secondPad = false;
    if (pending_.active) {
      bool match = in.opcode == pending_.expect1 || in.opcode == pending_.expect2 ||
                   in.opcode == pending_.expect3 || in.opcode == pending_.expect4;
      match = match && in.hasDst && in.dst.type == R::Texture && in.dst.index == pending_.dst &&
              in.srcCount >= 1 && in.src[0].type == R::Texture && in.src[0].index == pending_.src;
      if (!match) ctx.error(in, "V1310", "{}", pending_.what);
      secondPad = match && in.opcode == O::TexM3x3Pad;
      pending_.active = false;
    } else if (in.opcode == O::TexM3x2Tex || in.opcode == O::TexM3x2Depth) {
      ctx.error(in, "V1311", "{} must follow texm3x2pad (a 3x2 matrix is a texm3x2pad, {} pair)", ctx.op(in),
                ctx.op(in));
    } else if (in.opcode == O::TexM3x3Tex || in.opcode == O::TexM3x3Spec || in.opcode == O::TexM3x3VSpec ||
               in.opcode == O::TexM3x3) {
      ctx.error(in, "V1311", "{} must follow two texm3x3pad instructions", ctx.op(in));
    }

    if (!texOp) {
      // Arithmetic reads of texture registers.
      for (int s = 0; s < in.srcCount; ++s) {
        const SrcParam& p = in.src[s];
        if (p.type != R::Texture) continue;
        if (unreadable_.count(p.index))
          ctx.error(in, "V1312", "{} holds no data after texm3x2pad/texm3x3pad/texm3x2depth and cannot be read",
                    ctx.reg(p.type, p.index));
        else if (bemRead_.count(p.index))
          ctx.error(in, "V1313", "{} was read by texbem/texbeml and can afterwards be read only by texbem/texbeml",
                    ctx.reg(p.type, p.index));
      }
      return;
    }

    if (!in.hasDst || in.dst.type != R::Texture) {
      ctx.error(in, "V1314", "{} writes a t register", ctx.op(in));
      return;
    }
    unsigned m = in.dst.index;
    if (in.opcode != O::TexKill) {
      if (defined_.count(m) || unreadable_.count(m))
        ctx.error(in, "V1315", "t{} is already the destination of a texture instruction", m);
      else if (int(m) < lastDst_)
        ctx.error(in, "V1315", "texture instructions must use t registers in increasing order: t{} comes after t{}", m,
                  lastDst_);
      lastDst_ = std::max(lastDst_, int(m));
    }
    sources(ctx, in, m);
    sequence(ctx, in, m, secondPad);
  }

  void finish(Context& ctx) override {
    if (pending_.active) ctx.errorAt(pending_.pos, "V1310", "{}", pending_.what);
  }

 private:
  void sources(Context& ctx, const Instruction& in, unsigned m) {
    bool ps11only = !ctx.v.atLeast(1, 2);
    for (int s = 0; s < in.srcCount; ++s) {
      const SrcParam& p = in.src[s];
      bool constOperand = in.opcode == O::TexM3x3Spec && s == 1;
      if (constOperand) {
        if (p.type != R::Const) ctx.error(in, "V1316", "texm3x3spec takes the eye vector from a c register");
        if (p.mod != SrcMod::None || p.swizzle != kIdentitySwizzle)
          ctx.error(in, "V1316", "texm3x3spec's constant takes no modifier or swizzle");
        continue;
      }
      if (p.type != R::Texture) {
        ctx.error(in, "V1317", "{} reads a t register, not {}", ctx.op(in), ctx.reg(p.type, p.index));
        continue;
      }
      if (p.swizzle != kIdentitySwizzle) ctx.error(in, "V1318", "{} sources take no swizzle", ctx.op(in));
      if (p.mod != SrcMod::None) {
        bool bx2ok = p.mod == SrcMod::Sign &&
                     (ps11only ? isMatrixTex(in.opcode)
                               : !(in.opcode == O::TexReg2AR || in.opcode == O::TexReg2GB ||
                                   in.opcode == O::TexBem || in.opcode == O::TexBemL));
        if (!bx2ok) {
          if (p.mod == SrcMod::Sign)
            ctx.error(in, "V1318", "_bx2 is not allowed on the source of {} in {}", ctx.op(in), ctx.name);
          else
            ctx.error(in, "V1318", "{} sources take no modifier other than _bx2", ctx.op(in));
        }
      }
      if (p.index >= m) {
        ctx.error(in, "V1317", "{} t{}, t{}: the source must be a lower t register than the destination", ctx.op(in), m,
                  p.index);
      } else if (unreadable_.count(p.index)) {
        ctx.error(in, "V1312", "t{} holds no data after texm3x2pad/texm3x3pad/texm3x2depth and cannot be read",
                  p.index);
      } else if (!defined_.count(p.index)) {
        ctx.error(in, "V1930", "t{} is read by {} before a texture instruction writes it", p.index, ctx.op(in));
      } else if (bemRead_.count(p.index) && in.opcode != O::TexBem && in.opcode != O::TexBemL) {
        ctx.error(in, "V1313", "t{} was read by texbem/texbeml and can afterwards be read only by texbem/texbeml",
                  p.index);
      }
      if (in.opcode == O::TexBem || in.opcode == O::TexBemL) bemRead_.insert(p.index);
    }
  }

  // Matrix sequences: pads on consecutive registers with one source, then the
  // instruction that completes the matrix.
  void sequence(Context& ctx, const Instruction& in, unsigned m, bool secondPad) {
    unsigned src = in.srcCount ? in.src[0].index : 0;
    auto expect = [&](std::initializer_list<Opcode> ops, std::string what) {
      pending_ = {};
      Opcode* slots[] = {&pending_.expect1, &pending_.expect2, &pending_.expect3, &pending_.expect4};
      int i = 0;
      for (Opcode o : ops) *slots[i++] = o;
      pending_.dst = m + 1;
      pending_.src = src;
      pending_.what = std::move(what);
      pending_.pos = in.pos;
      pending_.active = true;
    };
    switch (in.opcode) {
      case O::TexM3x2Pad:
        unreadable_.insert(m);
        expect({O::TexM3x2Tex, O::TexM3x2Depth},
               fmt::format("texm3x2pad t{0}, t{1} must be followed by texm3x2tex{2} t{3}, t{1}", m, src,
                           ctx.v.atLeast(1, 3) ? " or texm3x2depth" : "", m + 1));
        break;
      case O::TexM3x3Pad:
        unreadable_.insert(m);
        if (secondPad)
          expect({O::TexM3x3Tex, O::TexM3x3Spec, O::TexM3x3VSpec, O::TexM3x3},
                 fmt::format("texm3x3pad t{0}, t{1} must be followed by texm3x3tex, texm3x3spec, texm3x3vspec{2} t{3}, t{1}",
                             m, src, ctx.v.atLeast(1, 2) ? " or texm3x3" : "", m + 1));
        else
          expect({O::TexM3x3Pad},
                 fmt::format("texm3x3pad t{0}, t{1} must be followed by a second texm3x3pad t{2}, t{1}", m, src, m + 1));
        break;
      case O::TexM3x2Depth:
        unreadable_.insert(m);
        break;
      case O::TexKill:
        break;
      default:
        defined_.insert(m);
        break;
    }
  }

  int lastDst_ = -1;
  std::set<unsigned> defined_;     // written by a texture instruction
  std::set<unsigned> unreadable_;  // pad destinations, texm3x2depth destination
  std::set<unsigned> bemRead_;     // read by texbem/texbeml
  struct Pending {
    Opcode expect1 = Opcode::Nop;  // the next instruction must be one of these …
    Opcode expect2 = Opcode::Nop, expect3 = Opcode::Nop, expect4 = Opcode::Nop;
    unsigned dst = 0, src = 0;     // … writing t(dst) from t(src)
    std::string what;              // for the message
    SourcePos pos;
    bool active = false;
  } pending_;
};

}  // namespace

std::unique_ptr<Check> makeTextureSequenceCheck() { return std::make_unique<TextureSequenceCheck>(); }

}  // namespace refx::shader::checks
