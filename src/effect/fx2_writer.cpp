// The fx_2_0 binary writer (reference: fx2-binary.md). Layout: tag, the size U of the
// unstructured area, the unstructured area (a leading zero DWORD, then type
// descriptions, values and strings, each 4-byte aligned), then the structured area:
// counts, parameter records, technique records, small objects, large objects.
#include <algorithm>
#include <cstring>
#include <map>

#include "effect_internal.h"
#include "fx2_preshader.h"
#include "refx/core/text.h"
#include "refx/effect/fx2_binary.h"
#include "refx/shader/disassembler.h"

namespace refx::effect {

using namespace detail;

namespace {

constexpr uint32_t kTag = 0xFEFF0901;
// The index field fxc writes on every state inside a sampler_state block.
constexpr uint32_t kSamplerBlockIndex = 0x100;
constexpr uint32_t kNone = 0xFFFFFFFF;

// D3DRS value of each render-state operation 0 … 102, in operation order: the D3DRS
// enum with WRAP8–15 pulled up next to WRAP0–7. Operations 62–71 follow MojoShader's
// order (its MOJOSHADER_renderStateType): POINTSPRITEENABLE … DEBUGMONITORTOKEN, then
// POINTSIZE_MAX at 71.
constexpr uint16_t kRenderStateOps[] = {
    7,   8,   9,   14,  15,  16,  19,  20,  22,  23,  24,  25,  26,  27,  28,  29,  34,  35,  36,  37,  38,
    48,  52,  53,  54,  55,  56,  57,  58,  59,  60,  128, 129, 130, 131, 132, 133, 134, 135, 198, 199, 200,
    201, 202, 203, 204, 205, 136, 137, 139, 140, 141, 142, 143, 145, 146, 147, 148, 151, 152, 154, 155, 156,
    157, 158, 159, 160, 161, 162, 163, 165, 166, 167, 168, 170, 171, 172, 173, 174, 175, 176, 178, 179, 180,
    181, 182, 183, 184, 185, 186, 187, 188, 189, 190, 191, 192, 193, 194, 195, 206, 207, 208, 209};
static_assert(std::size(kRenderStateOps) == 103);
// D3DTSS value of each texture-stage operation 103 … 120.
constexpr uint16_t kStageStateOps[] = {1, 26, 2, 3, 4, 27, 5, 6, 28, 7, 8, 9, 10, 11, 22, 23, 24, 32};
constexpr uint32_t kFirstStageOp = 103, kFirstSamplerOp = 164;

std::optional<uint32_t> operationOf(const StateInfo& info, std::string_view name) {
  auto shaderConst = [&](uint32_t first) -> uint32_t {
    // …ConstantF, …ConstantB, …ConstantI, …Constant, …Constant1 … 4
    const char last = name.empty() ? 0 : char(std::tolower(static_cast<unsigned char>(name.back())));
    if (last == 'f') return first;
    if (last == 'b') return first + 1;
    if (last == 'i') return first + 2;
    if (last >= '1' && last <= '4') return first + 4 + uint32_t(last - '1');
    return first + 3;
  };
  switch (info.target) {
    case StateTarget::RenderState:
      for (uint32_t op = 0; op < std::size(kRenderStateOps); ++op)
        if (kRenderStateOps[op] == info.code) return op;
      return std::nullopt;
    case StateTarget::StageState:
      for (uint32_t i = 0; i < std::size(kStageStateOps); ++i)
        if (kStageStateOps[i] == info.code) return kFirstStageOp + i;
      return std::nullopt;
    case StateTarget::NPatchMode: return 121;
    case StateTarget::FVF: return 122;
    case StateTarget::Transform:
      switch (info.code) {
        case d3d::TS_PROJECTION: return 123;
        case d3d::TS_VIEW: return 124;
        case d3d::TS_WORLD: return 125;
        case d3d::TS_TEXTURE0: return 126;
        default: return std::nullopt;
      }
    case StateTarget::Material:
      // Wine's order (tested against native d3dx9): Diffuse 127, Ambient 128.
      switch (MaterialMember(info.code)) {
        case MaterialMember::Diffuse: return 127;
        case MaterialMember::Ambient: return 128;
        case MaterialMember::Specular: return 129;
        case MaterialMember::Emissive: return 130;
        case MaterialMember::Power: return 131;
      }
      return std::nullopt;
    case StateTarget::Light: return 132 + info.code;
    case StateTarget::LightEnable: return 145;
    case StateTarget::VertexShader: return 146;
    case StateTarget::PixelShader: return 147;
    case StateTarget::VertexConstF:
    case StateTarget::VertexConstB:
    case StateTarget::VertexConstI: return shaderConst(148);
    case StateTarget::PixelConstF:
    case StateTarget::PixelConstB:
    case StateTarget::PixelConstI: return shaderConst(156);
    case StateTarget::Texture: return kFirstSamplerOp;
    case StateTarget::SamplerState:
      if (info.code >= 1 && info.code <= 13) return kFirstSamplerOp + info.code;
      return std::nullopt;
    case StateTarget::Sampler: return 178;
  }
  return std::nullopt;
}

std::string numberText(double x) { return fmt::format("{}", x); }

std::string floatList(const std::vector<double>& v) {
  std::string s;
  for (double x : v) s += (s.empty() ? "" : ", ") + numberText(x);
  return "{" + s + "}";
}

std::vector<uint8_t> bytesOf(std::string_view s, bool nul) {
  std::vector<uint8_t> b(s.begin(), s.end());
  if (nul) b.push_back(0);
  return b;
}

std::vector<uint8_t> bytesOf(const std::vector<uint32_t>& tokens) {
  std::vector<uint8_t> b(tokens.size() * 4);
  for (size_t i = 0; i < tokens.size(); ++i)
    for (int k = 0; k < 4; ++k) b[4 * i + size_t(k)] = uint8_t(tokens[i] >> (8 * k));
  return b;
}

// How a state's value is typed in the file (fxc's habits, reference §3.3).
enum class ValueShape { Dword, FloatDword, Floats, Registers };

ValueShape shapeOf(const StateContents& s) {
  switch (s.info.target) {
    case StateTarget::Transform:
    case StateTarget::Material:
    case StateTarget::NPatchMode: return ValueShape::Floats;
    case StateTarget::Light:
      return LightMember(s.info.code) == LightMember::Type ? ValueShape::Dword : ValueShape::Floats;
    case StateTarget::VertexConstF:
    case StateTarget::PixelConstF:
    case StateTarget::VertexConstI:
    case StateTarget::PixelConstI:
    case StateTarget::VertexConstB:
    case StateTarget::PixelConstB: return ValueShape::Registers;
    default: return s.info.value.kind == d3d::ValueKind::Float ? ValueShape::FloatDword : ValueShape::Dword;
  }
}

ParameterType registerType(const StateContents& s) {
  switch (s.info.target) {
    case StateTarget::VertexConstI:
    case StateTarget::PixelConstI: return ParameterType::Int;
    case StateTarget::VertexConstB:
    case StateTarget::PixelConstB: return ParameterType::Bool;
    default: return ParameterType::Float;
  }
}

std::string stateLabel(const StateContents& s) {
  return s.info.indexed ? fmt::format("{}[{}]", s.name, s.index) : s.name;
}

class Writer {
 public:
  Writer(const EffectContents& fx, const Fx2WriteOptions& options) : fx_(fx), options_(options) {}

  Fx2Binary write() {
    for (const TechniqueContents& t : fx_.techniques)
      if (!t.desc.brokenReason.empty())
        fail("{}: error: technique '{}' did not load ({}); fix it before writing the effect", fx_.fileName, t.desc.name,
             t.desc.brokenReason);
    std::vector<uint32_t> structured;
    list("// fx_2_0 effect written from {}\n", fx_.fileName);
    list("\n// {} parameters\n", fx_.parameters.size());
    for (size_t i = 0; i < fx_.parameters.size(); ++i) parameter(structured, uint32_t(i));
    list("\n// {} techniques\n", fx_.techniques.size());
    for (size_t t = 0; t < fx_.techniques.size(); ++t) technique(structured, uint32_t(t));

    std::vector<uint32_t> out{kTag, uint32_t(u_.size() * 4)};
    out.insert(out.end(), u_.begin(), u_.end());
    out.push_back(uint32_t(fx_.parameters.size()));
    out.push_back(uint32_t(fx_.techniques.size()));
    out.push_back(shaderCount_);
    out.push_back(nextId_);  // object_count = highest id + 1
    out.insert(out.end(), structured.begin(), structured.end());
    out.push_back(uint32_t(smalls_.size()));
    out.push_back(uint32_t(larges_.size()));
    auto payload = [&](const std::vector<uint8_t>& data) {
      out.push_back(uint32_t(data.size()));
      for (size_t i = 0; i < data.size(); i += 4) {
        uint32_t w = 0;
        for (size_t k = 0; k < 4 && i + k < data.size(); ++k) w |= uint32_t(data[i + k]) << (8 * k);
        out.push_back(w);
      }
    };
    for (const Small& s : smalls_) {
      out.push_back(s.id);
      payload(s.data);
    }
    for (const Large& l : larges_) {
      for (uint32_t w : {l.technique, l.index, l.element, l.state, l.usage}) out.push_back(w);
      payload(l.data);
    }
    Fx2Binary bin;
    bin.bytes = bytesOf(out);
    bin.listing = fmt::format("// {} bytes: unstructured area {} bytes, {} objects ({} small, {} large)\n",
                              bin.bytes.size(), u_.size() * 4, nextId_, smalls_.size(), larges_.size()) +
                  listing_;
    return bin;
  }

 private:
  struct Small {
    uint32_t id;
    std::vector<uint8_t> data;
  };
  struct Large {
    uint32_t technique, index, element, state, usage;
    std::vector<uint8_t> data;
  };

  template <typename... Args>
  void list(fmt::format_string<Args...> f, Args&&... args) {
    listing_ += fmt::format(f, std::forward<Args>(args)...);
  }

  uint32_t here() const { return uint32_t(u_.size() * 4); }

  uint32_t string(std::string_view s) {
    if (s.empty()) return 0;
    const uint32_t at = here();
    const std::vector<uint8_t> b = bytesOf(s, true);
    u_.push_back(uint32_t(b.size()));
    for (size_t i = 0; i < b.size(); i += 4) {
      uint32_t w = 0;
      for (size_t k = 0; k < 4 && i + k < b.size(); ++k) w |= uint32_t(b[i + k]) << (8 * k);
      u_.push_back(w);
    }
    return at;
  }

  // A type description; returns its offset. `nameAt` / `semanticAt` are the indices
  // of the name and semantic DWORDs, patched once the strings are written.
  uint32_t typeDesc(ParameterType type, ParameterClass cls, int elements, int rows, int columns) {
    const uint32_t at = here();
    u_.push_back(uint32_t(type));
    const bool numeric = cls != ParameterClass::Object && cls != ParameterClass::Struct;
    // fxc writes MATRIX_ROWS for every matrix, whatever its packing (reference §2.2).
    const ParameterClass fileClass = cls == ParameterClass::MatrixColumns ? ParameterClass::MatrixRows : cls;
    u_.push_back(uint32_t(fileClass));
    u_.push_back(0);  // name
    u_.push_back(0);  // semantic
    u_.push_back(uint32_t(elements));
    if (numeric) {
      if (fileClass == ParameterClass::Scalar || fileClass == ParameterClass::Vector) {
        u_.push_back(uint32_t(columns));  // vectors: columns, rows
        u_.push_back(uint32_t(rows));
      } else {
        u_.push_back(uint32_t(rows));  // matrices: rows, columns
        u_.push_back(uint32_t(columns));
      }
    }
    return at;
  }

  void nameType(uint32_t typeAt, const std::string& name, const std::string& semantic) {
    const uint32_t n = string(name);
    const uint32_t s = string(semantic);
    u_[typeAt / 4 + 2] = n;
    u_[typeAt / 4 + 3] = s;
  }

  uint32_t newObject() { return nextId_++; }

  // A parameter's or an annotation's value: numbers inline, objects by id.
  uint32_t objectValues(const ParameterDesc& d, const std::string& text, bool parameter) {
    const int n = std::max(1, d.elements);
    std::vector<uint32_t> ids;
    for (int i = 0; i < n; ++i) ids.push_back(newObject());
    const uint32_t at = here();
    for (uint32_t id : ids) u_.push_back(id);
    for (uint32_t id : ids) {
      if (d.type == ParameterType::String) smalls_.push_back({id, bytesOf(text, true)});
      else if (d.isTexture()) smalls_.push_back({id, {}});
    }
    return at;
  }

  void annotations(std::vector<uint32_t>& rec, const std::vector<Annotation>& items, const std::string& indent) {
    for (const Annotation& a : items) {
      const ParameterDesc& d = a.desc;
      if (d.cls == ParameterClass::Struct) fail("{}: error: annotation '{}' is a struct; not written", fx_.fileName, d.name);
      const uint32_t type = typeDesc(d.type, d.cls, d.elements, d.rows, d.columns);
      uint32_t value;
      if (d.isNumeric()) {
        value = here();
        const size_t count = size_t(d.valueCount());
        for (size_t i = 0; i < count; ++i) {
          const double x = i < a.numbers.size() ? a.numbers[i] : 0.0;
          u_.push_back(d.type == ParameterType::Float  ? floatBits(float(x))
                       : d.type == ParameterType::Bool ? uint32_t(x != 0)
                                                       : uint32_t(int32_t(x)));
        }
      } else {
        value = objectValues(d, a.text, false);
      }
      nameType(type, d.name, d.semantic);
      rec.push_back(type);
      rec.push_back(value);
      list("{}annotation {} {} = {};\n", indent, parameterTypeName(d.type), d.name,
           d.type == ParameterType::String ? "\"" + a.text + "\"" : floatList(a.numbers));
    }
  }

  std::vector<uint32_t> shaderTokens(const ShaderContentsRef& sh, const std::string& what) {
    if (auto it = tokens_.find(sh.get()); it != tokens_.end()) return it->second;
    std::vector<uint32_t> t = sh->tokens;
    if (sh->preshader) {
      // The preshader goes into the shader as fxc writes it: a PRES comment after the
      // CTAB (reference §5.1, §5.8), which D3DX runs at BeginPass / CommitChanges.
      try {
        t = withPresComment(t, fxlcFromPreshader(*sh->preshader));
      } catch (const Error& e) {
        fail("{}: error: {}: compile {} {}: its preshader cannot be written: {}", fx_.fileName, what, sh->profile,
             sh->entry, e.what());
      }
    }
    tokens_.emplace(sh.get(), t);
    return t;
  }

  void listShader(const std::vector<uint32_t>& tokens, const std::string& indent) {
    shader::DisassemblyOptions o;
    o.listing = true;
    std::string text;
    try {
      text = shader::disassemble(tokens, o);
    } catch (const Error& e) {
      text = fmt::format("// cannot disassemble: {}\n", e.what());
    }
    size_t start = 0;
    while (start < text.size()) {
      size_t end = text.find('\n', start);
      if (end == std::string::npos) end = text.size();
      listing_ += indent + text.substr(start, end - start) + "\n";
      start = end + 1;
    }
  }

  void parameter(std::vector<uint32_t>& rec, uint32_t index) {
    const ParameterContents& p = fx_.parameters[index];
    const ParameterDesc& d = p.desc;
    const size_t mark = listing_.size();  // the parameter's line goes before its sampler states
    if (d.cls == ParameterClass::Struct) fail("{}: error: parameter '{}' is a struct; structs are not written", fx_.fileName, d.name);
    const uint32_t type = typeDesc(d.type, d.cls, d.elements, d.rows, d.columns);
    uint32_t value = 0;
    std::string shown;
    const int n = std::max(1, d.elements);
    if (d.isNumeric()) {
      value = here();
      for (uint32_t r : p.raw) u_.push_back(r);
      std::vector<double> v;
      for (uint32_t r : p.raw)
        v.push_back(d.type == ParameterType::Float ? double(bitsFloat(r)) : double(int32_t(r)));
      shown = " = " + floatList(v);
    } else if (d.isSampler()) {
      // One sampler state block per element (the same block for every element).
      std::vector<std::vector<uint32_t>> records(static_cast<size_t>(n));
      for (int e = 0; e < n; ++e) {
        for (size_t k = 0; k < p.samplerStates.size(); ++k) {
          const StateContents& s = p.samplerStates[k];
          const auto [stType, stValue] =
              stateValue(s, Owner{kNone, index, d.elements ? uint32_t(e) : kNone, uint32_t(k)}, e == 0 ? "    " : "");
          auto op = operationOf(s.info, s.name);
          if (!op) failAt(s.where, "state '{}' has no operation number in the fx_2_0 state table", s.name);
          for (uint32_t w : {*op, kSamplerBlockIndex, stType, stValue}) records[size_t(e)].push_back(w);
        }
      }
      value = here();
      for (const auto& r : records) {
        u_.push_back(uint32_t(r.size() / 4));
        u_.insert(u_.end(), r.begin(), r.end());
      }
    } else if (d.type == ParameterType::VertexShader || d.type == ParameterType::PixelShader) {
      std::vector<uint32_t> ids;
      for (int i = 0; i < n; ++i) ids.push_back(newObject());
      shaderCount_ += uint32_t(n);
      value = here();
      for (uint32_t id : ids) u_.push_back(id);
      for (uint32_t id : ids) {
        if (p.shader) smalls_.push_back({id, bytesOf(shaderTokens(p.shader, d.name))});
        else smalls_.push_back({id, {}});
      }
      shown = p.shader ? fmt::format(" = object {}", ids[0]) : " = NULL";
    } else {
      value = objectValues(d, p.text, true);
      shown = d.type == ParameterType::String ? " = \"" + p.text + "\"" : "";
    }
    nameType(type, d.name, d.semantic);
    std::string typeText = std::string(parameterTypeName(d.type));
    if (d.cls == ParameterClass::Vector) typeText += std::to_string(d.columns);
    if (d.cls == ParameterClass::MatrixRows || d.cls == ParameterClass::MatrixColumns)
      typeText += fmt::format("{}x{}", d.rows, d.columns);
    listing_.insert(mark, fmt::format("parameter {}: {}{} {}{}{}{};  // class {}, type {}, type@0x{:x}, value@0x{:x}\n", index,
         d.flags & kParameterShared ? "shared " : "", typeText, d.name,
         d.elements ? fmt::format("[{}]", d.elements) : "", d.semantic.empty() ? "" : " : " + d.semantic, shown,
         int(d.cls == ParameterClass::MatrixColumns ? ParameterClass::MatrixRows : d.cls), int(d.type), type, value));
    if (p.shader) listShader(shaderTokens(p.shader, d.name), "    ");
    rec.push_back(type);
    rec.push_back(value);
    rec.push_back(d.flags & kParameterShared);
    rec.push_back(uint32_t(p.annotations.size()));
    annotations(rec, p.annotations, "    ");
  }

  struct Owner {
    uint32_t technique, index, element, state;
  };

  // Writes a state's value and its type description; returns (type offset, value
  // offset) and records any object the value needs.
  std::pair<uint32_t, uint32_t> stateValue(const StateContents& s, const Owner& owner, const std::string& indent) {
    using K = StateContents::Kind;
    const auto op = operationOf(s.info, s.name);
    const std::string label = owner.technique == kNone ? s.name : stateLabel(s);
    auto large = [&](uint32_t usage, std::vector<uint8_t> data) {
      larges_.push_back({owner.technique, owner.index, owner.element, owner.state, usage, std::move(data)});
    };
    auto line = [&](const std::string& text) {
      if (!indent.empty())
        list("{}state {}: {} (op {}, index {}) = {}\n", indent, owner.state, label, op ? int(*op) : -1,
             owner.technique == kNone ? kSamplerBlockIndex : uint32_t(s.index), text);
    };
    const bool objectState = s.info.target == StateTarget::VertexShader || s.info.target == StateTarget::PixelShader ||
                             s.info.target == StateTarget::Texture || s.info.target == StateTarget::Sampler;
    if (s.kind == K::Expression && (objectState || !s.fxlc))
      failAt(s.where, "state '{}' is an expression of parameters that cannot be written as an fx_2_0 expression (FXLC){}",
             label, s.fxlcError.empty() ? "" : ": " + s.fxlcError);
    if (s.kind == K::Expression) {
      // An FXLC expression (reference §3.3, §5): zero placeholders typed FLOAT, as many
      // as the expression's result has components, and the standalone preshader blob
      // as a usage-0 large object. D3DX runs it at every BeginPass / CommitChanges.
      const uint32_t n = uint32_t(s.fxlcComponents);
      const uint32_t value = here();
      u_.insert(u_.end(), n, 0u);
      uint32_t rows = n, columns = 1;
      if (rows > 4 && rows % 4 == 0) {
        columns = rows / 4;
        rows = 4;
      }
      const ParameterClass cls = shapeOf(s) == ValueShape::Registers ? ParameterClass::MatrixColumns : ParameterClass::MatrixRows;
      const uint32_t type = here();
      for (uint32_t w : {uint32_t(ParameterType::Float), uint32_t(cls), 0u, 0u, 0u, rows, columns}) u_.push_back(w);
      const std::vector<uint32_t> blob = encodeFxlc(*s.fxlc, kFxlcStandaloneVersion, false);
      large(0, bytesOf(blob));
      ++shaderCount_;
      line(fmt::format("expression (large object, usage 0, FXLC, {} bytes, {} components)", blob.size() * 4, n));
      if (!indent.empty()) {
        std::string code = s.fxlc->listing();
        for (const shader::ShaderConstant& c : s.fxlc->inputs.constants)
          list("{}    // input {} c{}..c{}\n", indent, c.name, c.registerIndex, c.registerIndex + c.registerCount - 1);
        size_t start = 0;
        while (start < code.size()) {
          const size_t end = code.find('\n', start);
          list("{}    {}\n", indent, code.substr(start, end - start));
          start = end + 1;
        }
      }
      return {type, value};
    }
    if (s.kind == K::SamplerBlock)
      failAt(s.where, "state '{}': a sampler_state block here is written as separate sampler states", label);
    const bool shaderState = s.info.target == StateTarget::VertexShader || s.info.target == StateTarget::PixelShader;
    if (shaderState) {
      const ParameterType t = s.info.target == StateTarget::VertexShader ? ParameterType::VertexShader : ParameterType::PixelShader;
      const uint32_t id = newObject();
      const uint32_t value = here();
      u_.push_back(id);
      const uint32_t type = typeDesc(t, ParameterClass::Object, 0, 1, 1);
      ShaderContentsRef sh = s.shader;
      if (s.kind == K::Parameter && options_.inlineShaderReferences) {
        for (const ParameterContents& p : fx_.parameters)
          if (p.desc.name == s.parameter) sh = p.shader;
      }
      if (sh) {
        const std::vector<uint32_t> tokens = shaderTokens(sh, label);
        large(0, bytesOf(tokens));
        line(fmt::format("object {}: {} shader (large object, usage 0, {} bytes)", id, sh->compiled ? "compiled" : "assembled",
                         tokens.size() * 4));
        if (!indent.empty()) listShader(tokens, indent + "    ");
      } else if (s.kind == K::Parameter) {
        large(1, bytesOf(s.parameter, true));
        line(fmt::format("object {}: parameter {} (large object, usage 1)", id, s.parameter));
      } else {
        line(fmt::format("object {}: NULL", id));
      }
      ++shaderCount_;
      return {type, value};
    }
    if (s.info.target == StateTarget::Texture) {
      const uint32_t id = newObject();
      const uint32_t value = here();
      u_.push_back(id);
      ParameterType t = ParameterType::Texture;
      for (const ParameterContents& p : fx_.parameters)
        if (s.kind == K::Parameter && p.desc.name == s.parameter && p.desc.isTexture()) t = p.desc.type;
      const uint32_t type = typeDesc(t, ParameterClass::Object, 0, 1, 1);
      if (s.kind == K::Parameter) {
        large(1, bytesOf(s.parameter, true));
        line(fmt::format("object {}: parameter {} (large object, usage 1)", id, s.parameter));
      } else {
        line(fmt::format("object {}: NULL", id));
      }
      return {type, value};
    }
    if (s.info.target == StateTarget::Sampler) {
      const uint32_t value = here();
      u_.push_back(0);  // an empty sampler state block
      const uint32_t type = typeDesc(ParameterType::Sampler, ParameterClass::Object, 0, 1, 1);
      if (s.kind == K::Parameter) {
        large(1, bytesOf(s.parameter, true));
        line(fmt::format("parameter {} (large object, usage 1)", s.parameter));
      } else {
        line("NULL");
      }
      return {type, value};
    }
    // Numbers.
    const ValueShape shape = shapeOf(s);
    std::vector<uint32_t> words;
    ParameterType t = ParameterType::Int;
    ParameterClass cls = ParameterClass::MatrixRows;
    std::string shown;
    const bool reference = s.kind == K::Parameter;
    switch (shape) {
      case ValueShape::Dword:
      case ValueShape::FloatDword:
        t = shape == ValueShape::Dword ? ParameterType::Int : ParameterType::Float;
        words.push_back(reference ? 0 : s.dword);
        shown = shape == ValueShape::Dword ? fmt::format("{} (0x{:x})", s.dword, s.dword) : numberText(bitsFloat(s.dword));
        break;
      case ValueShape::Floats:
        t = ParameterType::Float;
        if (reference) words.assign(size_t(std::max(1, s.referencedValues)), 0);
        for (double x : s.numbers) words.push_back(floatBits(float(x)));
        shown = floatList(s.numbers);
        break;
      case ValueShape::Registers:
        t = registerType(s);
        cls = ParameterClass::MatrixColumns;
        if (reference) words.assign(size_t(std::max(1, s.referencedValues)), 0);
        for (double x : s.registers)
          words.push_back(t == ParameterType::Float ? floatBits(float(x)) : uint32_t(int32_t(x)));
        shown = floatList(s.registers);
        break;
    }
    const uint32_t value = here();
    u_.insert(u_.end(), words.begin(), words.end());
    // Written directly (not through typeDesc): fxc types state values as n × 1 of class
    // MATRIX_ROWS (MATRIX_COLUMNS for shader constants), tail (rows, columns). Readers
    // only use rows · columns; values of more than four components that fill whole
    // float4s are written 4 × n/4 (a transform 4 × 4, k registers 4 × k), because
    // MojoShader copies the first tail DWORD's count of values into each float4 slot.
    uint32_t rows = uint32_t(words.size()), columns = 1;
    if (rows > 4 && rows % 4 == 0) {
      columns = rows / 4;
      rows = 4;
    }
    const uint32_t type = here();
    for (uint32_t w : {uint32_t(t), uint32_t(cls), 0u, 0u, 0u, rows, columns}) u_.push_back(w);
    if (reference) {
      large(1, bytesOf(s.parameter, true));
      shown = fmt::format("parameter {} (large object, usage 1)", s.parameter);
    }
    line(fmt::format("{} ({}, {}x{})", shown, parameterTypeName(t), rows, columns));
    return {type, value};
  }

  // A pass's states, with `Sampler[n] = sampler_state { … }` written as the indexed
  // sampler states it sets (Texture[n], AddressU[n], …).
  static std::vector<StateContents> flatten(const std::vector<StateContents>& states) {
    std::vector<StateContents> out;
    for (const StateContents& s : states) {
      if (s.kind != StateContents::Kind::SamplerBlock) {
        out.push_back(s);
        continue;
      }
      for (StateContents st : s.samplerStates) {
        st.index = s.index;
        st.info.indexed = true;
        out.push_back(std::move(st));
      }
    }
    return out;
  }

  void technique(std::vector<uint32_t>& rec, uint32_t t) {
    const TechniqueContents& tc = fx_.techniques[t];
    list("technique {}  // {} passes\n", tc.desc.name, tc.passes.size());
    std::vector<uint32_t> body;
    annotations(body, tc.desc.annotations, "  ");
    for (size_t p = 0; p < tc.passes.size(); ++p) {
      const PassContents& pc = tc.passes[p];
      const std::vector<StateContents> states = flatten(pc.states);
      list("  pass {}  // {} states\n", pc.desc.name, states.size());
      std::vector<uint32_t> passRec;
      annotations(passRec, pc.desc.annotations, "    ");
      ++shaderCount_;
      for (size_t k = 0; k < states.size(); ++k) {
        const StateContents& s = states[k];
        auto op = operationOf(s.info, s.name);
        if (!op) failAt(s.where, "state '{}' has no operation number in the fx_2_0 state table", s.name);
        const auto [type, value] = stateValue(s, Owner{t, uint32_t(p), kNone, uint32_t(k)}, "    ");
        for (uint32_t w : {*op, uint32_t(s.index), type, value}) passRec.push_back(w);
      }
      body.push_back(string(pc.desc.name));
      body.push_back(uint32_t(pc.desc.annotations.size()));
      body.push_back(uint32_t(states.size()));
      body.insert(body.end(), passRec.begin(), passRec.end());
    }
    rec.push_back(string(tc.desc.name));
    rec.push_back(uint32_t(tc.desc.annotations.size()));
    rec.push_back(uint32_t(tc.passes.size()));
    rec.insert(rec.end(), body.begin(), body.end());
  }

  const EffectContents& fx_;
  const Fx2WriteOptions& options_;
  std::vector<uint32_t> u_{0};  // the unstructured area; offset 0 is the null DWORD
  std::vector<Small> smalls_;
  std::vector<Large> larges_;
  uint32_t nextId_ = 1;
  uint32_t shaderCount_ = 0;
  std::map<const ShaderContents*, std::vector<uint32_t>> tokens_;
  std::string listing_;
};

}  // namespace

Fx2Binary writeFx2(const Effect& effect, const Fx2WriteOptions& options) {
  const EffectContents fx = EffectAccess::contents(effect);
  return Writer(fx, options).write();
}

std::optional<uint32_t> fx2StateOperation(std::string_view stateName) {
  if (equalsNoCase(stateName, "Texture")) return kFirstSamplerOp;
  auto info = findState(stateName);
  if (!info) return std::nullopt;
  return operationOf(*info, stateName);
}

}  // namespace refx::effect
