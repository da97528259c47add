// Inputs must be declared before they are read (SM2+: v#, and in pixel shaders t#,
// vPos and vFace), and a pixel shader reads only the declared components.
#include "shader/validate/check.h"

namespace refx::shader::checks {
namespace {

using O = Opcode;
using R = RegType;

class DeclaredInputCheck final : public Check {
 public:
  void instruction(Context& ctx, const Instruction& in) override {
    if (isDefOp(in.opcode) || in.opcode == O::Dcl || in.opcode == O::Phase) return;
    if (ctx.v.isVertex() && ctx.v.major == 1) {
      // vs_1_1 with dcl (D3D9 style) declares every input it reads; without any dcl
      // the D3D8 vertex declaration maps the inputs.
      if (ctx.anyInputDcl)
        for (int s = 0; s < in.srcCount; ++s)
          if (in.src[s].type == R::Input && !ctx.declared.count(registerKey(R::Input, in.src[s].index)))
            ctx.error(in, "V1620", "{} is read but not declared (dcl)", ctx.reg(R::Input, in.src[s].index));
      return;
    }
    if (!ctx.rules.dclInputs) return;
    for (int s = 0; s < in.srcCount; ++s) {
      const SrcParam& p = in.src[s];
      bool needsDcl = p.type == R::Input || (ctx.v.isPixel() && (p.type == R::Texture || p.type == R::MiscType));
      if (!needsDcl || p.relative) continue;
      auto it = ctx.declared.find(registerKey(p.type, p.index));
      if (it == ctx.declared.end()) {
        ctx.error(in, "V1620", "{} is read but not declared (dcl)", ctx.reg(p.type, p.index));
      } else if (ctx.v.isPixel()) {
        uint8_t need = ctx.readMask(in, s);
        if (need & ~it->second)
          ctx.error(in, "V1621", "{}{} is read but only {}{} is declared", ctx.reg(p.type, p.index),
                    maskName(need & ~it->second), ctx.reg(p.type, p.index), maskName(it->second));
      }
    }
    const DstParam& d = in.dst;
    if (in.opcode == O::TexKill && in.hasDst && (d.type == R::Texture || d.type == R::Input) &&
        !ctx.declared.count(registerKey(d.type, d.index)))
      ctx.error(in, "V1620", "{} is read but not declared (dcl)", ctx.reg(d.type, d.index));
  }
};

}  // namespace

std::unique_ptr<Check> makeDeclaredInputCheck() { return std::make_unique<DeclaredInputCheck>(); }

}  // namespace refx::shader::checks
