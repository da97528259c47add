// Texture sampling (SM2+): texld/texldl/texldd sample through a declared s register
// (no swizzle or modifier on it in SM2) into a temporary; ps_2_0 texld writes the full
// mask from a t# or r# with no swizzle or modifier, and its dependent reads chain at
// most 4 levels deep (ps_2_x: unless NODEPENDENTREADLIMIT); texkill takes r# or t#.
#include <algorithm>

#include "shader/validate/check.h"

namespace refx::shader::checks {
namespace {

using O = Opcode;
using R = RegType;

class SamplingCheck final : public Check {
 public:
  void instruction(Context& ctx, const Instruction& in) override {
    if (isDefOp(in.opcode) || in.opcode == O::Dcl || in.opcode == O::Phase) return;
    const Version v = ctx.v;
    const DstParam& d = in.dst;
    uint8_t mask = in.hasDst ? d.writeMask : 0;
    if (in.opcode == O::Tex || in.opcode == O::TexLdl || in.opcode == O::TexLdd) {
      if (in.srcCount >= 2) {
        const SrcParam& s = in.src[1];
        if (s.type != R::Sampler)
          ctx.error(in, "V1820", "{} samples through an s register", ctx.op(in));
        else if (!ctx.declared.count(registerKey(R::Sampler, s.index)))
          ctx.error(in, "V1820", "{} is used before it is declared (dcl_2d, dcl_cube or dcl_volume)",
                    ctx.reg(R::Sampler, s.index));
        if (v.major == 2 && (s.swizzle != kIdentitySwizzle || s.mod != SrcMod::None))
          ctx.error(in, "V1821", "the sampler operand takes no swizzle or modifier in {}", ctx.name);
      }
      if (in.hasDst && d.type != R::Temp) ctx.error(in, "V1822", "{} writes a temporary register", ctx.op(in));
      if (v.isPixel() && v.major == 2 && in.opcode == O::Tex && in.srcCount >= 1) {
        const SrcParam& c = in.src[0];
        if (mask != 0xF) ctx.error(in, "V1822", "{} in {} writes the full .xyzw mask", ctx.op(in), ctx.name);
        if (c.type != R::Temp && c.type != R::Texture)
          ctx.error(in, "V1823", "{} coordinates come from a t or r register in {}", ctx.op(in), ctx.name);
        if (c.swizzle != kIdentitySwizzle || c.mod != SrcMod::None)
          ctx.error(in, "V1823", "{} coordinates take no swizzle or modifier in {}", ctx.op(in), ctx.name);
        // Dependent-read chains (ps_2_0 without NODEPENDENTREADLIMIT): at most 4 levels.
        int level = 1;
        if (c.type == R::Temp) level = std::max(1, level_[registerKey(R::Temp, c.index)]) + 1;
        bool limit = ctx.rules.dependentReadLevels && !(v.minor == 1 && ctx.caps.ps2xNoDependentReadLimit);
        if (limit && level > ctx.rules.dependentReadLevels)
          ctx.error(in, "X5426", "{} allows {} levels of dependent texture reads, this {} is level {}", ctx.name,
                    ctx.rules.dependentReadLevels, ctx.op(in), level);
        if (in.hasDst) level_[registerKey(d.type, d.index)] = level;
      }
    } else if (in.hasDst && d.type == R::Temp && v.isPixel()) {
      int level = 0;
      for (int s = 0; s < in.srcCount; ++s)
        if (in.src[s].type == R::Temp) level = std::max(level, level_[registerKey(R::Temp, in.src[s].index)]);
      int& cur = level_[registerKey(R::Temp, d.index)];
      cur = (mask == 0xF) ? level : std::max(cur, level);
    }
    if (in.opcode == O::TexKill && in.hasDst && d.type != R::Temp && d.type != R::Texture && d.type != R::Input)
      ctx.error(in, "V1406", "texkill takes an r or t register");
  }

 private:
  std::unordered_map<uint32_t, int> level_;  // dependent-read level of each r#
};

}  // namespace

std::unique_ptr<Check> makeSamplingCheck() { return std::make_unique<SamplingCheck>(); }

}  // namespace refx::shader::checks
