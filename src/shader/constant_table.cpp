#include "refx/shader/constant_table.h"

#include <bit>
#include <cstring>

#include <fmt/format.h>

namespace refx::shader {

namespace {

constexpr uint32_t kCtabTag = 0x42415443u;  // 'CTAB'

// Bounds-checked little-endian reads from the table (offsets relative to its header).
class CtabReader {
 public:
  explicit CtabReader(std::span<const uint32_t> payload) {
    for (uint32_t w : payload)
      for (int i = 0; i < 4; ++i) bytes_.push_back(uint8_t(w >> (8 * i)));
  }
  std::optional<uint32_t> u32(size_t off) const {
    if (off > bytes_.size() || bytes_.size() - off < 4) return std::nullopt;
    return uint32_t(bytes_[off]) | uint32_t(bytes_[off + 1]) << 8 | uint32_t(bytes_[off + 2]) << 16 |
           uint32_t(bytes_[off + 3]) << 24;
  }
  std::optional<uint16_t> u16(size_t off) const {
    if (off > bytes_.size() || bytes_.size() - off < 2) return std::nullopt;
    return uint16_t(bytes_[off] | bytes_[off + 1] << 8);
  }
  std::optional<std::string> str(size_t off) const {
    if (off >= bytes_.size()) return std::nullopt;
    std::string s;
    for (size_t i = off; i < bytes_.size() && bytes_[i] != 0 && s.size() < 256; ++i) {
      const char c = char(bytes_[i]);
      s += (c >= 32 && c < 127) ? c : '?';
    }
    return s;
  }

 private:
  std::vector<uint8_t> bytes_;
};

}  // namespace

std::string ShaderConstant::typeName() const {
  static const char* const kTypes[] = {"void",      "bool",      "int",       "float",       "string",
                                       "texture",   "texture1D", "texture2D", "texture3D",   "textureCUBE",
                                       "sampler",   "sampler1D", "sampler2D", "sampler3D",   "samplerCUBE",
                                       "pixelshader", "vertexshader", "pixelfragment", "vertexfragment"};
  std::string s;
  if (cls == ConstantClass::Struct) s = "struct";
  else s = type >= 0 && size_t(type) < std::size(kTypes) ? kTypes[type] : fmt::format("type{}", type);
  if (cls == ConstantClass::Vector) s += std::to_string(columns);
  else if (cls == ConstantClass::MatrixRows || cls == ConstantClass::MatrixColumns) s += fmt::format("{}x{}", rows, columns);
  if (cls == ConstantClass::MatrixRows) s = "row_major " + s;
  if (elements > 1) s += fmt::format("[{}]", elements);
  return s;
}

const ShaderConstant* ShaderConstantTable::find(std::string_view name) const {
  for (const ShaderConstant& c : constants)
    if (c.name == name) return &c;
  return nullptr;
}

std::optional<ShaderConstantTable> readConstantTable(std::span<const uint32_t> comment) {
  if (comment.empty() || comment[0] != kCtabTag) return std::nullopt;
  const CtabReader r(comment.subspan(1));
  auto size = r.u32(0), creator = r.u32(4), count = r.u32(12), info = r.u32(16), target = r.u32(24);
  if (!size || !creator || !count || !info || !target) return std::nullopt;
  ShaderConstantTable t;
  t.creator = r.str(*creator).value_or("");
  t.target = r.str(*target).value_or("");
  for (uint32_t i = 0; i < *count && i < 4096; ++i) {
    const size_t at = size_t(*info) + 20 * size_t(i);
    auto name = r.u32(at);
    auto set = r.u16(at + 4), index = r.u16(at + 6), regs = r.u16(at + 8);
    auto typeInfo = r.u32(at + 12), defaults = r.u32(at + 16);
    if (!name || !set || !index || !regs || !typeInfo || !defaults) break;
    auto cls = r.u16(*typeInfo), type = r.u16(*typeInfo + 2), rows = r.u16(*typeInfo + 4),
         cols = r.u16(*typeInfo + 6), elems = r.u16(*typeInfo + 8);
    if (!cls || !type || !rows || !cols || !elems) break;
    ShaderConstant c;
    c.name = r.str(*name).value_or("?");
    c.registerSet = RegisterSet(*set);
    c.registerIndex = *index;
    c.registerCount = *regs;
    c.cls = ConstantClass(*cls);
    c.type = *type;
    c.rows = *rows;
    c.columns = *cols;
    c.elements = *elems;
    if (*defaults) {
      for (int k = 0; k < 4 * c.registerCount; ++k) {
        auto bits = r.u32(*defaults + 4 * size_t(k));
        if (!bits) break;
        c.defaultValue.push_back(std::bit_cast<float>(*bits));
      }
      if (c.defaultValue.size() != size_t(4 * c.registerCount)) c.defaultValue.clear();
    }
    t.constants.push_back(std::move(c));
  }
  return t;
}

std::optional<ShaderConstantTable> readConstantTable(const Shader& shader) {
  for (const Instruction& ins : shader.instructions)
    if (ins.opcode == Opcode::Comment)
      if (auto t = readConstantTable(std::span<const uint32_t>(ins.comment))) return t;
  return std::nullopt;
}

}  // namespace refx::shader
