#include "refx/exec/analysis.h"

#include <cstddef>

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

std::optional<TexturePrologue> findTexturePrologue(const Program& program) {
  if (program.flowControl) return std::nullopt;
  // Registers read and written by the instructions that stay (file, index; index -1:
  // the whole file, relative addressing).
  std::vector<std::pair<RegFile, int>> read, written;
  const auto touches = [](const std::vector<std::pair<RegFile, int>>& set, RegFile file, int index) {
    for (const auto& [f, i] : set)
      if (f == file && (i == index || i < 0)) return true;
    return false;
  };
  TexturePrologue found;
  std::vector<bool> moved(program.code.size(), false);
  for (size_t n = 0; n < program.code.size(); ++n) {
    const Instr& in = program.code[n];
    if (in.op == Op::Kill) break;  // lookups after it sample fewer lanes
    const Src& c = in.src[0];
    const bool plain = in.op == Op::Tex && in.dst.mask == 0xF && in.dst.rel == RelMode::None && in.shift == 0 &&
                       !in.saturate && !in.clamp && in.quantize == 0 &&
                       (in.dst.file == RegFile::Temp || in.dst.file == RegFile::Output) &&
                       c.file == RegFile::Input && c.swizzle == kSwzXYZW && c.mod == SrcMod::None &&
                       c.rel == RelMode::None && c.flags == 0;
    // Moved ahead of the instructions before it: none of them writes its coordinates or
    // reads or writes its result.
    if (plain && !touches(written, c.file, c.index) && !touches(read, in.dst.file, in.dst.index) &&
        !touches(written, in.dst.file, in.dst.index)) {
      found.lookups.push_back({in.sampler, c.index, in.dst.file, in.dst.index});
      moved[n] = true;
      continue;
    }
    for (int i = 0; i < sourceCount(in.op); ++i)
      read.emplace_back(in.src[size_t(i)].file, in.src[size_t(i)].rel == RelMode::None ? in.src[size_t(i)].index : -1);
    written.emplace_back(in.dst.file, in.dst.rel == RelMode::None ? in.dst.index : -1);
  }
  if (found.lookups.empty()) return std::nullopt;
  found.rest = program;
  found.rest.name.append(" after its texture lookups");
  found.rest.code.clear();
  for (size_t n = 0; n < program.code.size(); ++n)
    if (!moved[n]) found.rest.code.push_back(program.code[n]);
  for (TexturePrologue::Lookup& l : found.lookups) {
    int writers = 0;
    for (const TexturePrologue::Lookup& o : found.lookups) writers += o.file == l.file && o.index == l.index;
    // Outputs are read after the program; a register two lookups write keeps all.
    if (l.file == RegFile::Temp && writers == 1) l.channels = channelsRead(found.rest, l.index);
  }
  return found;
}

namespace {

// The components of source `s` instruction `in` reads for its write mask, before the
// swizzle (0xF for the ops whose reads are not per component or a fixed set).
uint8_t componentsReadBy(const Instr& in, int s) {
  switch (in.op) {
    case Op::Mov: case Op::Add: case Op::Sub: case Op::Mul: case Op::Mad: case Op::Min: case Op::Max:
    case Op::Slt: case Op::Sge: case Op::Frc: case Op::Lrp: case Op::Cmp: case Op::Cnd: case Op::Abs:
    case Op::Floor: case Op::Round: case Op::Sgn:
      return in.dst.mask;
    case Op::Dp3: return 0x7;
    default: (void)s; return 0xF;
  }
}

}  // namespace

uint8_t channelsRead(const Program& program, int index) {
  if (program.flowControl) return 0xF;
  uint8_t read = 0;
  for (const Instr& in : program.code) {
    for (int i = 0; i < sourceCount(in.op); ++i) {
      const Src& s = in.src[size_t(i)];
      if (s.file != RegFile::Temp) continue;
      if (s.rel != RelMode::None) return 0xF;
      if (s.index != index) continue;
      const uint8_t used = componentsReadBy(in, i);
      for (int c = 0; c < 4; ++c)
        if (used >> c & 1) read = uint8_t(read | 1u << (s.swizzle >> (2 * c) & 3));
    }
    if (in.dst.file == RegFile::Temp && in.dst.rel != RelMode::None) return 0xF;
    if (in.dst.file == RegFile::Temp && in.dst.index == index && in.dst.mask == 0xF) break;
  }
  return read;
}

}  // namespace refx::exec
