#include "hlsl/constant_table.h"

#include <cstring>
#include <map>

namespace refx::hlsl::detail {

namespace {

class Writer {
 public:
  size_t size() const { return bytes_.size(); }
  void u16(uint16_t v) { bytes_.push_back(uint8_t(v)); bytes_.push_back(uint8_t(v >> 8)); }
  void u32(uint32_t v) { for (int i = 0; i < 4; ++i) bytes_.push_back(uint8_t(v >> (8 * i))); }
  void patch32(size_t at, uint32_t v) { for (int i = 0; i < 4; ++i) bytes_[at + i] = uint8_t(v >> (8 * i)); }
  uint32_t str(const std::string& s) {
    uint32_t at = uint32_t(bytes_.size());
    bytes_.insert(bytes_.end(), s.begin(), s.end());
    bytes_.push_back(0);
    while (bytes_.size() % 4) bytes_.push_back(0xAB);  // fxc pads with 0xAB
    return at;
  }
  uint32_t floats(const std::vector<float>& v) {
    uint32_t at = uint32_t(bytes_.size());
    for (float f : v) { uint32_t u; std::memcpy(&u, &f, 4); u32(u); }
    return at;
  }
  std::vector<uint8_t>& bytes() { return bytes_; }

 private:
  std::vector<uint8_t> bytes_;
};

uint16_t parameterClass(const Type& t) {
  const Type& e = t.isArray() ? *t.element : t;
  switch (e.cls) {
    case TypeClass::Scalar: return 0;
    case TypeClass::Vector: return 1;
    case TypeClass::Matrix: return e.packing == 1 ? 2 : 3;
    case TypeClass::Object: return 4;
    case TypeClass::Struct: return 5;
    default: return 0;
  }
}

uint16_t parameterType(const Type& t) {
  const Type& e = t.isArray() ? *t.element : t;
  switch (e.base) {
    case BaseType::Bool: return 1;
    case BaseType::Int: case BaseType::Uint: return 2;
    case BaseType::Half: case BaseType::Float: case BaseType::Double: return 3;
    case BaseType::String: return 4;
    case BaseType::Texture:
      return e.dim == SamplerDim::Dim3D ? 8 : e.dim == SamplerDim::Cube ? 9 : e.dim == SamplerDim::Dim2D ? 7 : 5;
    case BaseType::Sampler:
      switch (e.dim) {
        case SamplerDim::Dim1D: return 11;
        case SamplerDim::Dim2D: return 12;
        case SamplerDim::Dim3D: return 13;
        case SamplerDim::Cube: return 14;
        default: return 10;
      }
    default: return 0;
  }
}

// Writes the type info (and struct members) after everything else; returns its offset.
uint32_t writeType(Writer& w, const Type& t, std::map<std::string, uint32_t>& names) {
  const Type& e = t.isArray() ? *t.element : t;
  std::vector<std::pair<uint32_t, uint32_t>> members;
  if (e.cls == TypeClass::Struct && e.structDef) {
    for (const StructMember& m : e.structDef->members) {
      uint32_t name = names.count(m.name) ? names[m.name] : (names[m.name] = w.str(m.name));
      members.emplace_back(name, writeType(w, m.type, names));
    }
  }
  uint32_t memberInfo = 0;
  if (!members.empty()) {
    memberInfo = uint32_t(w.size());
    for (auto [n, ti] : members) { w.u32(n); w.u32(ti); }
  }
  uint32_t at = uint32_t(w.size());
  w.u16(parameterClass(t));
  w.u16(parameterType(t));
  int rows = e.cls == TypeClass::Matrix ? e.rows : 1, cols = e.cls == TypeClass::Struct ? 0 : e.cols;
  if (e.cls == TypeClass::Struct) { rows = 1; cols = e.flatSize(); }
  w.u16(uint16_t(rows));
  w.u16(uint16_t(cols));
  w.u16(uint16_t(t.isArray() ? t.arraySize : 1));
  w.u16(uint16_t(members.size()));
  w.u32(memberInfo);
  return at;
}

}  // namespace

std::vector<uint32_t> ConstantTable::encode() const {
  Writer w;
  // Header (28 bytes), offsets patched below.
  w.u32(28);
  w.u32(0);  // creator
  w.u32(versionToken);
  w.u32(uint32_t(constants.size()));
  w.u32(constants.empty() ? 0 : 28);
  w.u32(flags);
  w.u32(0);  // target
  size_t infoAt = w.size();
  for (size_t i = 0; i < constants.size(); ++i) for (int k = 0; k < 5; ++k) w.u32(0);
  std::map<std::string, uint32_t> names;
  for (size_t i = 0; i < constants.size(); ++i) {
    const Constant& c = constants[i];
    size_t at = infoAt + 20 * i;
    uint32_t name = w.str(c.name);
    uint32_t type = writeType(w, c.type, names);
    uint32_t def = c.defaultValue.empty() ? 0 : w.floats(c.defaultValue);
    w.patch32(at, name);
    auto& b = w.bytes();
    auto put16 = [&](size_t off, uint16_t v) { b[off] = uint8_t(v); b[off + 1] = uint8_t(v >> 8); };
    put16(at + 4, uint16_t(c.registerSet));
    put16(at + 6, uint16_t(c.registerIndex));
    put16(at + 8, uint16_t(c.registerCount));
    put16(at + 10, 0);
    w.patch32(at + 12, type);
    w.patch32(at + 16, def);
  }
  w.patch32(4, w.str(creator));
  w.patch32(24, w.str(target));
  std::vector<uint32_t> out{0x42415443u};  // 'CTAB'
  auto& b = w.bytes();
  while (b.size() % 4) b.push_back(0);
  for (size_t i = 0; i < b.size(); i += 4)
    out.push_back(uint32_t(b[i]) | uint32_t(b[i + 1]) << 8 | uint32_t(b[i + 2]) << 16 | uint32_t(b[i + 3]) << 24);
  return out;
}

shader::Instruction constantTableComment(const IrProgram& ir, const std::string& creator, const shader::Version& v) {
  ConstantTable table;
  table.creator = creator;
  table.target = v.name();
  table.versionToken = v.token();
  for (const IrUniform& u : ir.uniforms) {
    if (u.flowRegister < 0) continue;
    ConstantTable::Constant c;
    c.name = u.name;
    c.registerSet = u.loopCount ? ConstantTable::RegisterSet::Int4 : ConstantTable::RegisterSet::Bool;
    c.registerIndex = u.flowRegister;
    c.registerCount = 1;
    c.type = u.type;
    table.constants.push_back(c);
  }
  for (const IrUniform& u : ir.uniforms) {
    if (!u.used || u.flowRegister >= 0 || u.preshaderOutput) continue;
    ConstantTable::Constant c;
    c.name = u.name;
    c.registerSet = ConstantTable::RegisterSet::Float4;
    c.registerIndex = u.firstRegister;
    c.registerCount = u.registerCount;
    c.type = u.type;
    c.defaultValue = u.defaults;
    table.constants.push_back(c);
  }
  for (const IrSampler& s : ir.samplers) {
    if (s.registerIndex < 0) continue;
    ConstantTable::Constant c;
    c.name = s.name;
    c.registerSet = ConstantTable::RegisterSet::Sampler;
    c.registerIndex = s.registerIndex;
    c.registerCount = 1;
    c.type.cls = TypeClass::Object;
    c.type.base = BaseType::Sampler;
    c.type.dim = s.dim;
    table.constants.push_back(c);
  }
  shader::Instruction in;
  in.opcode = shader::Opcode::Comment;
  in.comment = table.encode();
  return in;
}

}  // namespace refx::hlsl::detail
