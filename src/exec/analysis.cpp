#include "refx/exec/analysis.h"

namespace refx::exec {

namespace {

// A result modifier that leaves every value in [0, 1] as it is.
bool keepsUnitRange(const Instr& in) {
  if (in.shift != 0 || in.quantize != 0) return false;
  return !in.clamp || (in.clampLo <= 0.0f && in.clampHi >= 1.0f);
}

// A whole register read as it is (a clamp to [-1, 1] keeps [0, 1]).
bool plainRead(const Src& s, RegFile file) {
  return s.file == file && s.swizzle == kSwzXYZW && s.mod == SrcMod::None && s.rel == RelMode::None &&
         (s.flags & ~kSrcClampUnit) == 0;
}

}  // namespace

std::optional<SamplePassthrough> findSamplePassthrough(const Program& program) {
  if (program.flowControl || program.code.empty() || program.code.size() > 2) return std::nullopt;
  const Instr& tex = program.code[0];
  if (tex.op != Op::Tex || tex.dst.mask != 0xF || tex.dst.rel != RelMode::None || !keepsUnitRange(tex) ||
      !plainRead(tex.src[0], RegFile::Input))
    return std::nullopt;
  const SamplePassthrough found{tex.sampler, tex.src[0].index};
  if (program.code.size() == 1)
    return tex.dst.file == RegFile::Output && tex.dst.index == 0 ? std::optional(found) : std::nullopt;
  // tex into a temporary, then the temporary to output 0.
  const Instr& mov = program.code[1];
  if (tex.dst.file != RegFile::Temp || mov.op != Op::Mov || mov.dst.file != RegFile::Output ||
      mov.dst.index != 0 || mov.dst.mask != 0xF || mov.dst.rel != RelMode::None || !keepsUnitRange(mov) ||
      !plainRead(mov.src[0], RegFile::Temp) || mov.src[0].index != tex.dst.index)
    return std::nullopt;
  return found;
}

}  // namespace refx::exec
