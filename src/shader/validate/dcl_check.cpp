// dcl: which register files a version declares (v# everywhere that has dcl, o# and
// s# in vs_3_0, t# in ps_2_x, s# from ps_2_0, vPos/vFace in ps_3_0), within their
// counts, each once (vs_3_0 outputs may share an o# with disjoint masks), with a
// texture type exactly on samplers (and no usage on them), a D3DDECLUSAGE value (none
// in ps_2_x), a non-empty mask, no
// shift or _sat, and _centroid only on pixel-shader inputs.
#include "shader/validate/check.h"

namespace refx::shader::checks {
namespace {

using O = Opcode;
using R = RegType;

class DclCheck final : public Check {
 public:
  void instruction(Context& ctx, const Instruction& in) override {
    if (in.opcode != O::Dcl || !in.hasDst) return;
    const DstParam& d = in.dst;
    const Version v = ctx.v;
    bool vs = v.isVertex();
    bool ok = false;
    switch (d.type) {
      case R::Input: ok = true; break;
      case R::Output: ok = vs && v.major >= 3; break;
      case R::Sampler: ok = (vs && v.major >= 3) || (!vs && v.major >= 2); break;
      case R::Texture: ok = !vs && v.major == 2; break;
      case R::MiscType: ok = !vs && v.major >= 3; break;
      default: break;
    }
    if (!ok) {
      ctx.error(in, "V1610", "dcl cannot declare {} in {}", ctx.reg(d.type, d.index), ctx.name);
      return;
    }
    // A declaration computes nothing: its destination token carries no shift.
    if (d.shift) ctx.error(in, "V1611", "dcl takes no shift (_x2, _d2 ...)");
    if ((d.writeMask & 0xF) == 0)
      ctx.error(in, "V1612", "dcl of {} declares no component (empty write mask)", ctx.reg(d.type, d.index));
    // The texture type field (bits 30:27 of the usage token) belongs to sampler dcls.
    if (d.type != R::Sampler && in.textureType != TextureType::Unknown)
      ctx.error(in, "V1613", "dcl of {} has a texture type; only samplers (s#) have one", ctx.reg(d.type, d.index));
    const RegisterRule* r = findRegisterRule(ctx.rules, d.type);
    if (!r) return;
    if (int(d.index) >= ctx.registerCount(*r)) {
      ctx.error(in, "V1102", "{} is out of range: {} has {} {} registers", ctx.reg(d.type, d.index), ctx.name,
                ctx.registerCount(*r), r->meaning);
      return;
    }
    if (d.resultMod & ResultCentroid && (vs || (d.type != R::Input && d.type != R::Texture)))
      ctx.error(in, "V1614", "_centroid applies only to pixel shader input and texture coordinate declarations");
    if (d.resultMod & ResultSaturate) ctx.error(in, "V1611", "dcl takes no _sat");
    if (d.type == R::Sampler) {
      if (in.textureType != TextureType::Tex2D && in.textureType != TextureType::Cube &&
          in.textureType != TextureType::Volume)
        ctx.error(in, "V1613", "dcl of {} needs a texture type (dcl_2d, dcl_cube or dcl_volume)",
                  ctx.reg(d.type, d.index));
      // Bits 3:0 and 19:16 of a sampler's usage token are reserved: no text form writes them.
      if (in.usage != DeclUsage::Position || in.usageIndex != 0)
        ctx.error(in, "V1613", "dcl of {} has a usage ({}, index {}); a sampler dcl carries only a texture type",
                  ctx.reg(d.type, d.index), int(in.usage), int(in.usageIndex));
      if (ctx.declared.count(registerKey(d.type, d.index)))
        ctx.error(in, "V1615", "{} is declared twice", ctx.reg(d.type, d.index));
      ctx.declared[registerKey(d.type, d.index)] = 0xF;
      return;
    }
    // ps_2_0/2_x: the usage token of a v#/t# dcl is bit 31 alone (no usage in the text).
    if (!vs && v.major == 2 && (in.usage != DeclUsage::Position || in.usageIndex != 0))
      ctx.error(in, "V1616", "dcl of {} has a usage ({}, index {}); {} declarations carry none",
                ctx.reg(d.type, d.index), int(in.usage), int(in.usageIndex), ctx.name);
    else if (uint8_t(in.usage) > uint8_t(DeclUsage::Sample))
      ctx.error(in, "V1616", "dcl of {} has usage {}; D3DDECLUSAGE ends at 13 (sample)", ctx.reg(d.type, d.index),
                int(in.usage));
    uint8_t& m = ctx.declared[registerKey(d.type, d.index)];
    // vs_3_0 outputs may share one o# with disjoint masks; anything else once.
    if (m & d.writeMask) ctx.error(in, "V1615", "{} is declared twice", ctx.reg(d.type, d.index));
    m |= d.writeMask;
    if (vs && d.type == R::Input) ctx.written[registerKey(d.type, d.index)] = 0xF;
  }
};

}  // namespace

std::unique_ptr<Check> makeDclCheck() { return std::make_unique<DclCheck>(); }

}  // namespace refx::shader::checks
