// D3D9 tokens → shader assembly text in the D3D assembler's syntax, written so the
// assembler turns it back into the same tokens; optionally an `fxc /Fc`-style
// listing with the constant table (CTAB comment) and the instruction-slot count.
#include "refx/shader/disassembler.h"

#include <bit>
#include <cstdio>
#include <cstdlib>
#include <optional>

#include <fmt/format.h>

#include "refx/shader/constant_table.h"
#include "refx/shader/opcode_table.h"
#include "refx/shader/validator.h"
#include "refx/shader/version_rules.h"
#include "shader/assembler_tables.h"


namespace refx::shader {

namespace {

constexpr char kComponents[] = "xyzw";

// "_gt" … for ifc/breakc/setp; nothing for the reserved values 0 and 7.
std::string comparisonSuffix(uint8_t control) {
  const std::string_view name = asmtables::comparisonName(Comparison(control & 7));
  return name.empty() ? std::string() : "_" + std::string(name);
}

// Float literal with the fewest digits that reads back to the same bits.
std::string floatText(uint32_t bits) {
  const float f = std::bit_cast<float>(bits);
  char buf[32];
  for (int digits = 1; digits <= 9; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, double(f));
    if (std::bit_cast<uint32_t>(std::strtof(buf, nullptr)) == bits) break;
  }
  return buf;
}

// Shortest swizzle text that the assembler expands back to `swizzle` (a short form
// repeats its last letter): "" for .xyzw, ".x" for .xxxx, ".xy" for .xyyy.
std::string swizzleText(uint8_t swizzle) {
  if (swizzle == 0xE4) return "";
  int c[4];
  for (int i = 0; i < 4; ++i) c[i] = (swizzle >> (2 * i)) & 3;
  int n = 4;
  while (n > 1 && c[n - 1] == c[n - 2]) --n;
  std::string s = ".";
  for (int i = 0; i < n; ++i) s += kComponents[c[i]];
  return s;
}

std::string maskText(uint8_t mask) {
  if ((mask & 0xF) == 0xF) return "";
  std::string s = ".";
  for (int i = 0; i < 4; ++i)
    if (mask & (1 << i)) s += kComponents[i];
  return s;
}

std::string relativeText(const RelativeAddress& rel) {
  if (rel.type == RegType::Loop) return "aL";
  return std::string("a0.") + kComponents[rel.component & 3];
}

// `c[a0.x+3]`, `v[aL]`, or the plain register name.
std::string registerText(RegType type, uint16_t index, bool relative, const RelativeAddress& rel,
                         Version version) {
  if (!relative) return registerName(type, index, version);
  // fmt rather than string concatenation: GCC 12 warns falsely (-Wrestrict) on the latter.
  return index != 0 ? fmt::format("{}[{}+{}]", registerTypeName(type, version), relativeText(rel), index)
                    : fmt::format("{}[{}]", registerTypeName(type, version), relativeText(rel));
}

std::string srcText(const SrcParam& s, Version version) {
  // vs_1_1 relative addressing is always a0.x (no address token).
  RelativeAddress rel = version.sm2plus() ? s.rel : RelativeAddress{};
  std::string reg = registerText(s.type, s.index, s.relative, rel, version);
  std::string prefix, suffix;
  switch (s.mod) {
    case SrcMod::None: break;
    case SrcMod::Neg: prefix = "-"; break;
    case SrcMod::Bias: suffix = "_bias"; break;
    case SrcMod::BiasNeg: prefix = "-", suffix = "_bias"; break;
    case SrcMod::Sign: suffix = "_bx2"; break;
    case SrcMod::SignNeg: prefix = "-", suffix = "_bx2"; break;
    case SrcMod::Comp: prefix = "1-"; break;
    case SrcMod::X2: suffix = "_x2"; break;
    case SrcMod::X2Neg: prefix = "-", suffix = "_x2"; break;
    case SrcMod::Dz: suffix = "_dz"; break;
    case SrcMod::Dw: suffix = "_dw"; break;
    case SrcMod::Abs: suffix = "_abs"; break;
    case SrcMod::AbsNeg: prefix = "-", suffix = "_abs"; break;
    case SrcMod::Not: prefix = "!"; break;
  }
  return prefix + reg + suffix + swizzleText(s.swizzle);
}

// The assembler reads a missing mask on m3x3/m4x3/m3x2 as the components they compute
// (.xyz/.xy), so a full mask is written out there to reassemble to the same token.
std::string dstText(const DstParam& d, Opcode op, Version version) {
  const OpcodeInfo* info = findOpcode(op);
  const bool maskImpliedByOpcode = info && info->matrixRows > 0 && info->matrixRows < 4;
  const bool full = (d.writeMask & 0xF) == 0xF;
  return registerText(d.type, d.index, d.relative, version.sm2plus() ? d.rel : RelativeAddress{}, version) +
         (full && maskImpliedByOpcode ? std::string(".xyzw") : maskText(d.writeMask));
}

std::string resultModifierText(const DstParam& d) {
  std::string s;
  if (d.shift >= -3 && d.shift <= 3) {
    if (d.shift != 0) s += "_" + std::string(asmtables::shiftName(d.shift));
  }
  else s += d.shift > 0 ? fmt::format("_x{}", 1 << d.shift) : fmt::format("_d{}", 1 << -d.shift);
  if (d.resultMod & ResultSaturate) s += "_sat";
  if (d.resultMod & ResultPartialPrecision) s += "_pp";
  if (d.resultMod & ResultCentroid) s += "_centroid";
  return s;
}

std::string dclMnemonic(const Instruction& ins, Version version) {
  const RegType t = ins.dst.type;
  if (t == RegType::Sampler) {
    const unsigned tt = unsigned(ins.textureType);
    if (tt == unsigned(TextureType::Unknown)) return "dcl";
    return tt <= unsigned(TextureType::Volume) ? fmt::format("dcl_{}", asmtables::textureTypeName(ins.textureType))
                                               : fmt::format("dcl_textype{}", tt);
  }
  // ps_2_0/2_x v#/t# and ps_3_0 vPos/vFace carry no usage: plain `dcl`.
  const bool plain = ins.usage == DeclUsage::Position && ins.usageIndex == 0 && version.isPixel() &&
                     (t == RegType::MiscType || (version.major < 3 && (t == RegType::Input || t == RegType::Texture)));
  if (plain) return "dcl";
  unsigned u = unsigned(ins.usage);
  std::string s = "dcl_";
  const std::string_view name = asmtables::usageName(ins.usage);
  s += name.empty() ? fmt::format("usage{}", u) : std::string(name);
  if (ins.usageIndex != 0) s += std::to_string(ins.usageIndex);
  return s;
}

std::string mnemonic(const Instruction& ins, Version version) {
  if (ins.opcode == Opcode::Dcl) return dclMnemonic(ins, version);
  if (!findOpcode(ins.opcode)) return fmt::format("opcode{}", unsigned(ins.opcode));
  // ifc/breakc/setp: the first spelling that takes a comparison suffix (if_gt, break_lt, setp_eq).
  for (const Mnemonic& m : allMnemonics())
    if (m.kind == MnemonicKind::Compare && m.compareOpcode == ins.opcode)
      return m.name + comparisonSuffix(ins.control);
  return std::string(mnemonicIn(ins.opcode, ins.control, version));
}

std::string instructionText(const Instruction& ins, Version version) {
  std::string line;
  if (ins.coissue) line += "+";
  if (ins.predicated) {
    line += ins.predicateNot ? "(!p0" : "(p0";
    line += swizzleText(ins.predicateSwizzle) + ") ";
  }
  line += mnemonic(ins, version);
  const OperandCounts counts = operandCounts(ins.opcode, version);
  if (counts.dst) line += resultModifierText(ins.dst);
  std::vector<std::string> ops;
  if (counts.dst) ops.push_back(dstText(ins.dst, ins.opcode, version));
  switch (ins.opcode) {
    case Opcode::Def:
      for (uint32_t v : ins.literal) ops.push_back(floatText(v));
      break;
    case Opcode::DefI:
      for (uint32_t v : ins.literal) ops.push_back(std::to_string(int32_t(v)));
      break;
    case Opcode::DefB: ops.push_back(ins.literal[0] ? "true" : "false"); break;
    default:
      for (int i = 0; i < counts.src && i < int(ins.srcCount); ++i) ops.push_back(srcText(ins.src[i], version));
  }
  for (size_t i = 0; i < ops.size(); ++i) line += (i == 0 ? " " : ", ") + ops[i];
  return line;
}

std::string fourcc(uint32_t v) {
  std::string s;
  for (int i = 0; i < 4; ++i) {
    char c = char(v >> (8 * i));
    s += (c >= 32 && c < 127) ? c : '.';
  }
  return s;
}

void appendCtabHeader(std::string& out, const ShaderConstantTable& t) {
  if (!t.creator.empty()) out += "// Generated by " + t.creator + "\n//\n";
  if (t.constants.empty()) return;
  out += "// Parameters:\n//\n";
  for (const ShaderConstant& c : t.constants) out += "//   " + c.typeName() + " " + c.name + ";\n";
  out += "//\n//\n// Registers:\n//\n";
  size_t width = 4;
  for (const ShaderConstant& c : t.constants) width = std::max(width, c.name.size());
  out += fmt::format("//   {:<{}} Reg   Size\n", "Name", width);
  out += fmt::format("//   {} ----- ----\n", std::string(width, '-'));
  static const char kSetLetter[] = {'b', 'i', 'c', 's'};
  for (const ShaderConstant& c : t.constants) {
    const size_t setIndex = size_t(c.registerSet);
    const char set = setIndex < 4 ? kSetLetter[setIndex] : '?';
    const std::string reg = fmt::format("{}{}", set, c.registerIndex);
    out += fmt::format("//   {:<{}} {:<5} {:>4}\n", c.name, width, reg, c.registerCount);
  }
  out += "//\n";
}

}  // namespace

std::string disassemble(const Shader& shader, const DisassemblyOptions& options) {
  const Version v = shader.version;
  const char* indent = options.listing ? "    " : "";
  std::string out;
  if (options.listing) {
    out += "//\n";
    bool ctab = false;
    for (const Instruction& ins : shader.instructions) {
      if (ins.opcode != Opcode::Comment) continue;
      if (auto t = readConstantTable(std::span<const uint32_t>(ins.comment))) {
        appendCtabHeader(out, *t);
        ctab = true;
        break;
      }
    }
    if (!ctab) out += "// " + v.name() + ", no constant table\n//\n";
    out += "\n";
  }
  out += indent + v.name() + "\n";
  for (const Instruction& ins : shader.instructions) {
    if (ins.opcode == Opcode::Comment) {
      // Comments carry no code; the listing notes where they were.
      if (options.listing && !readConstantTable(std::span<const uint32_t>(ins.comment)))
        out += fmt::format("{}// comment block '{}', {} DWORDs\n", indent,
                           ins.comment.empty() ? std::string() : fourcc(ins.comment[0]), ins.comment.size());
      continue;
    }
    if (ins.opcode == Opcode::Phase) {
      out += indent + std::string("phase\n");
      continue;
    }
    out += indent + instructionText(ins, v) + "\n";
  }
  if (options.listing) {
    // fxc's footer: pixel shaders split texture and arithmetic slots (flow control
    // counts as arithmetic there), vertex shaders give the total alone.
    const SlotCount slots = countSlots(shader);
    out += "\n";
    if (v.isPixel())
      out += fmt::format("// approximately {} instruction slots used ({} texture, {} arithmetic)\n", slots.total(),
                         slots.texture, slots.arithmetic + slots.flowControl);
    else
      out += fmt::format("// approximately {} instruction slots used\n", slots.total());
  }
  return out;
}

std::string disassemble(std::span<const uint32_t> tokens, const DisassemblyOptions& options) {
  return disassemble(decode(tokens), options);
}

}  // namespace refx::shader
