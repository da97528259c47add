// Outputs: ps_1_x writes r0 (the pixel color); ps_2_x writes oC0, render targets in
// order from oC0, each oC# and oDepth once by a plain mov outside flow control; ps_3_0
// writes them with any instruction outside dynamic flow control; vs_1_1 – vs_2_x write
// all of oPos; vs_3_0 declares a position output and writes only declared o#
// components.
#include <set>

#include "shader/validate/check.h"

namespace refx::shader::checks {
namespace {

using O = Opcode;
using R = RegType;

class OutputCheck final : public Check {
 public:
  void instruction(Context& ctx, const Instruction& in) override {
    if (isDefOp(in.opcode) || in.opcode == O::Dcl || in.opcode == O::Phase) return;
    if (!in.hasDst) return;
    const DstParam& d = in.dst;
    if (d.type == R::Temp && d.index == 0 && ctx.writtenMask(in)) r0Written_ = true;
    if (ctx.v.isVertex()) {
      vertex(ctx, in);
      return;
    }
    if (d.type != R::ColorOut && d.type != R::DepthOut) return;
    const std::string n = ctx.reg(d.type, d.index);
    if (ctx.v.major == 2) {
      const SrcParam& s = in.src[0];
      if (in.opcode != O::Mov) ctx.error(in, "V1910", "{} is written only by mov in {}", n, ctx.name);
      // oDepth takes one component, which a replicate swizzle (.x .y .z .w) may select
      // (fxc emits mov oDepth, r0.x); other swizzles stay rejected, as for oCn.
      else if (d.type == R::DepthOut &&
               (s.mod != SrcMod::None || (s.swizzle != kIdentitySwizzle && !isReplicate(s.swizzle))))
        ctx.error(in, "V1911", "mov to {} takes no source modifier and no swizzle but .x .y .z .w in {}", n, ctx.name);
      else if (d.type == R::ColorOut && (s.swizzle != kIdentitySwizzle || s.mod != SrcMod::None))
        ctx.error(in, "V1911", "mov to {} takes no source swizzle or modifier in {}", n, ctx.name);
      if (d.type == R::ColorOut && d.writeMask != 0xF)
        ctx.error(in, "V1912", "{} is written with the full mask in {}", n, ctx.name);
      if (d.resultMod & ResultSaturate) ctx.error(in, "V1912", "{} cannot be written with _sat in {}", n, ctx.name);
      bool inFlow = !ctx.blocks.empty() || ctx.inSubroutine;
      if (inFlow || in.predicated)
        ctx.error(in, "V1913", "{} cannot be written inside flow control or predicated in {}", n, ctx.name);
      if (d.type == R::ColorOut) {
        if (!colorOutWritten_.insert(d.index).second) ctx.error(in, "V1914", "{} is written more than once", n);
      } else {
        if (depthWritten_) ctx.error(in, "V1914", "oDepth is written more than once");
        depthWritten_ = true;
      }
    } else {
      if (ctx.inDynamicFlow() || in.predicated)
        ctx.error(in, "V1913", "{} cannot be written inside dynamic flow control or predicated", n);
      // ps_3_0 writes outputs with any instruction; a mov to oDepth still selects one
      // component, so its swizzle is a replicate (or none, which reads .x).
      const uint8_t sw = in.src[0].swizzle;
      if (d.type == R::DepthOut && in.opcode == O::Mov && in.srcCount > 0 && sw != kIdentitySwizzle &&
          !isReplicate(sw))
        ctx.error(in, "V1911", "mov to {} takes no swizzle but .x .y .z .w in {}", n, ctx.name);
      if (d.type == R::ColorOut) colorOutWritten_.insert(d.index);
      else depthWritten_ = true;
    }
  }

  void finish(Context& ctx) override {
    const Version v = ctx.v;
    if (v.ps1x() && !r0Written_) ctx.errorAt(ctx.end, "V1915", "{} never writes r0, the pixel color", ctx.name);
    if (v.isPixel() && v.major == 2) {
      if (!colorOutWritten_.count(0)) ctx.errorAt(ctx.end, "V1915", "{} must write oC0", ctx.name);
      for (unsigned i : colorOutWritten_)
        for (unsigned k = 0; k < i; ++k)
          if (!colorOutWritten_.count(k)) {
            ctx.errorAt(ctx.end, "V1916", "oC{} is written but oC{} is not; render targets are written in order from oC0",
                        i, k);
            break;
          }
    }
    if (v.isVertex() && v.major < 3 && oPosMask_ != 0xF)
      ctx.errorAt(ctx.end, "V1915", "a {} shader must write all four components of oPos{}", ctx.name,
                  oPosMask_ ? fmt::format(" ({} is never written)", maskName(uint8_t(~oPosMask_ & 0xF))) : "");
    if (v.isVertex() && v.major >= 3) {
      bool position = false;
      for (const Instruction& in : ctx.shader.instructions)
        if (in.opcode == O::Dcl && in.hasDst && in.dst.type == R::Output && in.usage == DeclUsage::Position &&
            in.usageIndex == 0)
          position = true;
      if (!position) ctx.errorAt(ctx.end, "V1917", "vs_3_0 must declare a position output (dcl_position o#)");
    }
  }

 private:
  void vertex(Context& ctx, const Instruction& in) {
    const DstParam& d = in.dst;
    if (d.type == R::RastOut && d.index == 0) oPosMask_ |= d.writeMask;
    if (ctx.v.major < 3 || d.type != R::Output || d.relative) return;
    auto it = ctx.declared.find(registerKey(R::Output, d.index));
    if (it == ctx.declared.end())
      ctx.error(in, "V1917", "{} is written but not declared (dcl_position, dcl_texcoord …)", ctx.reg(d.type, d.index));
    else if (d.writeMask & ~it->second)
      ctx.error(in, "V1917", "{}{} is written but only {}{} is declared", ctx.reg(d.type, d.index),
                maskName(d.writeMask & ~it->second), ctx.reg(d.type, d.index), maskName(it->second));
  }

  std::set<unsigned> colorOutWritten_;
  bool depthWritten_ = false;
  uint8_t oPosMask_ = 0;
  bool r0Written_ = false;
};

}  // namespace

std::unique_ptr<Check> makeOutputCheck() { return std::make_unique<OutputCheck>(); }

}  // namespace refx::shader::checks
