// The fx_2_0 binary reader (reference: fx2-binary.md §4.5): the binary becomes the
// parsed form of an effect (EffectAst) that the Effect builds like a text effect —
// values as literal expressions, parameter references as names, FXLC expressions as
// Preshader expressions, shaders as bytecode. Every offset, count and size is checked
// against the buffer; what is wrong is a refx::Error naming the file offset.
#include "fx2_reader.h"

#include <bit>
#include <cstring>
#include <map>
#include <tuple>

#include "fxlc.h"
#include "state_table.h"
#include "refx/core/text.h"
#include "refx/effect/fx2_binary.h"
#include "refx/pipeline/d3d9types.h"

namespace refx::effect::detail {

namespace {

constexpr uint32_t kTag = 0xFEFF0901;
constexpr uint32_t kNone = 0xFFFFFFFF;

// Reverse of the writer's operation table: the .fx name of each operation 0 … 178.
std::string stateNameOf(uint32_t op) {
  static const std::vector<std::string> kNames = [] {
    std::vector<std::string> names(179);
    static const char* const kSpecial[] = {
        "NPatchMode", "FVF", "ProjectionTransform", "ViewTransform", "WorldTransform", "TextureTransform",
        "MaterialDiffuse", "MaterialAmbient", "MaterialSpecular", "MaterialEmissive", "MaterialPower",
        "LightType", "LightDiffuse", "LightSpecular", "LightAmbient", "LightPosition", "LightDirection",
        "LightRange", "LightFalloff", "LightAttenuation0", "LightAttenuation1", "LightAttenuation2", "LightTheta",
        "LightPhi", "LightEnable", "VertexShader", "PixelShader", "VertexShaderConstantF", "VertexShaderConstantB",
        "VertexShaderConstantI", "VertexShaderConstant", "VertexShaderConstant1", "VertexShaderConstant2",
        "VertexShaderConstant3", "VertexShaderConstant4", "PixelShaderConstantF", "PixelShaderConstantB",
        "PixelShaderConstantI", "PixelShaderConstant", "PixelShaderConstant1", "PixelShaderConstant2",
        "PixelShaderConstant3", "PixelShaderConstant4", "Texture"};
    for (size_t i = 0; i < std::size(kSpecial); ++i) names[121 + i] = kSpecial[i];
    names[178] = "Sampler";
    // Render, texture-stage and sampler states: every name the enum tables know whose
    // operation number is `op`.
    for (d3d::EnumKind kind : {d3d::EnumKind::RenderState, d3d::EnumKind::TextureStageState, d3d::EnumKind::SamplerState})
      for (uint32_t code = 0; code < 256; ++code) {
        const std::string_view n = d3d::enumName(kind, code);
        if (n.empty()) continue;
        if (auto op = fx2StateOperation(n); op && *op < 179 && names[*op].empty()) names[*op] = std::string(n);
      }
    return names;
  }();
  return op < kNames.size() ? kNames[op] : std::string();
}

class Reader {
 public:
  Reader(std::span<const uint8_t> bytes, const std::string& name) : b_(bytes), name_(name) {}

  EffectAst read() {
    if (b_.size() < 8) bad(0, fmt::format("{} bytes is too short for an fx_2_0 effect", b_.size()));
    if (at(0) != kTag) bad(0, fmt::format("the tag is 0x{:08x}, not fx_2_0's 0xFEFF0901", at(0)));
    u_ = at(4);
    if (u_ % 4 || u_ > b_.size() - 8) bad(4, fmt::format("the unstructured area's size {} does not fit the file", u_));
    pos_ = 8 + size_t(u_);
    const uint32_t params = next(), techniques = next();
    next();  // the "shader count": readers ignore it (§1.6)
    objectCount_ = next();
    checkCount(params, 4, "parameters");
    checkCount(techniques, 3, "techniques");

    for (uint32_t i = 0; i < params; ++i) {
      RawParam p;
      p.at = pos_;
      p.value = pair(true);
      p.flags = next();
      const uint32_t a = next();
      checkCount(a, 2, "annotations");
      for (uint32_t k = 0; k < a; ++k) p.annotations.push_back(pair(false));
      params_.push_back(std::move(p));
    }
    for (uint32_t t = 0; t < techniques; ++t) {
      RawTechnique tech;
      tech.name = string(next(), pos_ - 4);
      const uint32_t a = next(), passes = next();
      checkCount(a, 2, "annotations");
      checkCount(passes, 3, "passes");
      for (uint32_t k = 0; k < a; ++k) tech.annotations.push_back(pair(false));
      for (uint32_t p = 0; p < passes; ++p) {
        RawPass pass;
        pass.name = string(next(), pos_ - 4);
        const uint32_t pa = next(), states = next();
        checkCount(pa, 2, "annotations");
        checkCount(states, 4, "states");
        for (uint32_t k = 0; k < pa; ++k) pass.annotations.push_back(pair(false));
        for (uint32_t s = 0; s < states; ++s) pass.states.push_back(state());
        tech.passes.push_back(std::move(pass));
      }
      techniques_.push_back(std::move(tech));
    }
    const uint32_t smalls = next(), larges = next();
    checkCount(smalls, 2, "small objects");
    checkCount(larges, 6, "large objects");
    for (uint32_t i = 0; i < smalls; ++i) {
      const size_t recordAt = pos_;
      const uint32_t id = next();
      if (id >= objectCount_) bad(recordAt, fmt::format("object id {} is not below the object count {}", id, objectCount_));
      smalls_[id] = payload();
    }
    for (uint32_t i = 0; i < larges; ++i) {
      const size_t recordAt = pos_;
      Large l;
      l.technique = next();
      l.index = next();
      l.element = next();
      l.state = next();
      l.usage = next();
      l.at = recordAt;
      l.data = payload();
      l.dataAt = pos_ - ((l.data.size() + 3) & ~size_t(3));
      if (l.usage > 2) bad(recordAt + 16, fmt::format("large object usage {} (0, 1 or 2)", l.usage));
      checkLarge(l);
      larges_[{l.technique, l.index, l.element, l.state}] = std::move(l);
    }
    return build();
  }

 private:
  struct RawState {
    uint32_t op = 0, index = 0;
    ParameterDesc type;
    uint32_t valueAt = 0;  // rel
    size_t at = 0;         // file offset of the record
  };
  struct RawValue {
    ParameterDesc desc;
    uint32_t valueAt = 0;
    size_t at = 0;
    std::vector<uint32_t> words;                    // numbers; object ids
    std::vector<std::vector<RawState>> samplerBlocks;  // samplers: one block per element
  };
  struct RawParam {
    size_t at = 0;
    RawValue value;
    uint32_t flags = 0;
    std::vector<RawValue> annotations;
  };
  struct RawPass {
    std::string name;
    std::vector<RawValue> annotations;
    std::vector<RawState> states;
  };
  struct RawTechnique {
    std::string name;
    std::vector<RawValue> annotations;
    std::vector<RawPass> passes;
  };
  struct Large {
    uint32_t technique = 0, index = 0, element = 0, state = 0, usage = 0;
    size_t at = 0, dataAt = 0;
    std::vector<uint8_t> data;
  };

  [[noreturn]] void bad(size_t offset, const std::string& message) const {
    fail("{}: error: fx_2_0 offset 0x{:x}: {}", name_, offset, message);
  }

  uint32_t at(size_t off) const {
    if (off > b_.size() || b_.size() - off < 4) bad(off, "the file ends inside a DWORD");
    uint32_t w;
    std::memcpy(&w, b_.data() + off, 4);
    return w;
  }
  uint32_t next() {
    const uint32_t w = at(pos_);
    pos_ += 4;
    return w;
  }
  void checkCount(uint32_t count, size_t minWords, const char* what) const {
    const size_t left = (b_.size() - std::min(b_.size(), pos_)) / 4;
    if (count > left / minWords) bad(pos_ - 4, fmt::format("{} {} cannot fit in the {} bytes left", count, what, left * 4));
  }
  // A file offset for `rel` with `size` bytes inside the unstructured area.
  size_t relative(uint32_t rel, size_t size, size_t from) const {
    if (rel % 4 || rel > u_ || u_ - rel < size)
      bad(from, fmt::format("offset 0x{:x} (+{} bytes) is outside the unstructured area (0x{:x} bytes)", rel, size, u_));
    return 8 + size_t(rel);
  }
  std::string string(uint32_t rel, size_t from) const {
    if (rel == 0) return "";
    const size_t off = relative(rel, 4, from);
    const uint32_t len = at(off);
    relative(rel + 4 > rel ? rel + 4 : rel, len, from);
    std::string s(reinterpret_cast<const char*>(b_.data() + off + 4), len);
    if (const size_t nul = s.find('\0'); nul != std::string::npos) s.resize(nul);
    return s;
  }
  std::vector<uint8_t> payload() {
    const size_t sizeAt = pos_;
    const uint32_t size = next();
    if (size > b_.size() - pos_) bad(sizeAt, fmt::format("an object of {} bytes runs past the end of the file", size));
    std::vector<uint8_t> data(b_.begin() + std::ptrdiff_t(pos_), b_.begin() + std::ptrdiff_t(pos_ + size));
    pos_ += (size_t(size) + 3) & ~size_t(3);
    return data;
  }

  ParameterDesc type(uint32_t rel, size_t from) const {
    const size_t off = relative(rel, 20, from);
    ParameterDesc d;
    const uint32_t t = at(off), cls = at(off + 4);
    if (t > uint32_t(ParameterType::VertexShader)) bad(off, fmt::format("parameter type {} is not one of fx_2_0's", t));
    if (cls > uint32_t(ParameterClass::Struct)) bad(off + 4, fmt::format("parameter class {} (0 to 5)", cls));
    if (cls == uint32_t(ParameterClass::Struct)) bad(off + 4, "struct parameters are not supported");
    d.type = ParameterType(t);
    d.cls = ParameterClass(cls);
    d.name = string(at(off + 8), off + 8);
    d.semantic = string(at(off + 12), off + 12);
    const uint32_t elements = at(off + 16);
    if (elements > 65535) bad(off + 16, fmt::format("{} array elements", elements));
    d.elements = int(elements);
    const bool numeric = d.cls != ParameterClass::Object;
    if (numeric != (d.type >= ParameterType::Bool && d.type <= ParameterType::Float))
      bad(off, fmt::format("type {} does not go with class {}", t, cls));
    if (numeric) {
      relative(rel, 28, from);
      uint32_t a = at(off + 20), c = at(off + 24);
      if (a < 1 || c < 1 || a > 65535 || c > 65535 || uint64_t(a) * c * std::max(1u, elements) > 65536)
        bad(off + 20, fmt::format("dimensions {} x {}", a, c));
      if (d.cls == ParameterClass::Scalar || d.cls == ParameterClass::Vector) {
        d.columns = int(a);  // vectors: columns, rows
        d.rows = int(c);
      } else {
        d.rows = int(a);  // matrices: rows, columns
        d.columns = int(c);
      }
    } else {
      d.rows = d.columns = 1;
    }
    return d;
  }

  RawState stateRecord(uint32_t op, uint32_t index, uint32_t typeAt, uint32_t valueAt, size_t recordAt) const {
    RawState s;
    s.at = recordAt;
    if (op > 178) bad(recordAt, fmt::format("state operation {} is not in the state table (0 to 178)", op));
    s.op = op;
    s.index = index;
    s.type = type(typeAt, recordAt + 8);
    s.valueAt = valueAt;
    relative(valueAt, 4, recordAt + 12);
    return s;
  }

  RawState state() {
    const size_t recordAt = pos_;
    const uint32_t op = next(), index = next(), typeAt = next(), valueAt = next();
    return stateRecord(op, index, typeAt, valueAt, recordAt);
  }

  // A (type offset, value offset) record and what it describes.
  RawValue pair(bool parameter) {
    const uint32_t typeAt = next();
    const uint32_t valueAt = next();
    return value(typeAt, valueAt, parameter);
  }

  // A parameter's or an annotation's type and value.
  RawValue value(uint32_t typeAt, uint32_t valueAt, bool parameter) {
    const size_t from = pos_ - 8;
    RawValue v;
    v.at = from;
    v.desc = type(typeAt, from);
    v.valueAt = valueAt;
    const ParameterDesc& d = v.desc;
    const size_t n = size_t(std::max(1, d.elements));
    if (d.isSampler()) {
      if (!parameter) bad(from, "an annotation cannot be a sampler");
      size_t off = relative(valueAt, 4, from + 4);
      for (size_t e = 0; e < n; ++e) {
        const uint32_t count = at(off);
        if (count > (u_ + 8 - off) / 16) bad(off, fmt::format("a sampler block of {} states runs past the unstructured area", count));
        std::vector<RawState> block;
        for (uint32_t k = 0; k < count; ++k) {
          const size_t r = off + 4 + 16 * size_t(k);
          block.push_back(stateRecord(at(r), at(r + 4), at(r + 8), at(r + 12), r));
        }
        v.samplerBlocks.push_back(std::move(block));
        off += 4 + 16 * size_t(count);
        if (e + 1 < n) relative(uint32_t(off - 8), 4, from + 4);
      }
      return v;
    }
    const size_t words = d.isNumeric() ? size_t(d.valueCount()) : n;
    const size_t off = relative(valueAt, words * 4, from + 4);
    for (size_t i = 0; i < words; ++i) v.words.push_back(at(off + 4 * i));
    if (!d.isNumeric())
      for (uint32_t id : v.words)
        if (id >= objectCount_) bad(off, fmt::format("object id {} is not below the object count {}", id, objectCount_));
    return v;
  }

  void checkLarge(const Large& l) const {
    if (l.technique == kNone) {
      if (l.index >= params_.size()) bad(l.at + 4, fmt::format("large object for parameter {}: there are {}", l.index, params_.size()));
      const RawValue& v = params_[l.index].value;
      const size_t element = l.element == kNone ? 0 : l.element;
      if (!v.desc.isSampler() || element >= v.samplerBlocks.size() || l.state >= v.samplerBlocks[element].size())
        bad(l.at, fmt::format("large object for parameter {} element {} state {}: no such sampler state", l.index,
                              int(l.element), l.state));
      return;
    }
    if (l.technique >= techniques_.size())
      bad(l.at, fmt::format("large object for technique {}: there are {}", l.technique, techniques_.size()));
    const RawTechnique& t = techniques_[l.technique];
    if (l.index >= t.passes.size()) bad(l.at + 4, fmt::format("large object for pass {}: there are {}", l.index, t.passes.size()));
    if (l.state >= t.passes[l.index].states.size())
      bad(l.at + 12, fmt::format("large object for state {}: the pass has {}", l.state, t.passes[l.index].states.size()));
  }

  // ---------------------------------------------------------------- building
  static Expr number(double x, bool isInt) {
    Expr e;
    e.kind = Expr::Kind::Number;
    e.number = x;
    e.isInt = isInt;
    return e;
  }

  static double scalar(ParameterType t, uint32_t w) {
    switch (t) {
      case ParameterType::Bool: return w ? 1.0 : 0.0;
      case ParameterType::Int: return double(int32_t(w));
      default: return double(std::bit_cast<float>(w));
    }
  }

  static Expr numbers(ParameterType t, const std::vector<uint32_t>& words) {
    if (words.size() == 1) return number(scalar(t, words[0]), t != ParameterType::Float);
    Expr list;
    list.kind = Expr::Kind::List;
    for (uint32_t w : words) list.args.push_back(number(scalar(t, w), t != ParameterType::Float));
    return list;
  }

  std::string objectText(uint32_t id) const {
    auto it = smalls_.find(id);
    if (it == smalls_.end()) return "";
    std::string s(it->second.begin(), it->second.end());
    if (const size_t nul = s.find('\0'); nul != std::string::npos) s.resize(nul);
    return s;
  }

  Annotation annotation(const RawValue& v) const {
    Annotation a;
    a.desc = v.desc;
    if (v.desc.isNumeric()) {
      for (uint32_t w : v.words) a.numbers.push_back(scalar(v.desc.type, w));
    } else if (v.desc.type == ParameterType::String && !v.words.empty()) {
      a.text = objectText(v.words[0]);
    }
    return a;
  }

  std::vector<Annotation> annotations(const std::vector<RawValue>& list) const {
    std::vector<Annotation> out;
    for (const RawValue& v : list) out.push_back(annotation(v));
    return out;
  }

  // "name" or "name[i]" (a usage-1 payload) as an expression.
  Expr reference(const Large& l) const {
    std::string s(l.data.begin(), l.data.end());
    if (const size_t nul = s.find('\0'); nul != std::string::npos) s.resize(nul);
    if (s.empty()) bad(l.dataAt, "a parameter reference without a name");
    Expr name;
    name.kind = Expr::Kind::Name;
    const size_t open = s.find('[');
    name.text = s.substr(0, open);
    if (open == std::string::npos) return name;
    const size_t close = s.find(']', open);
    if (close == std::string::npos || close == open + 1) bad(l.dataAt, fmt::format("bad parameter reference '{}'", s));
    const std::string digits = s.substr(open + 1, close - open - 1);
    if (digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 6)
      bad(l.dataAt, fmt::format("bad parameter reference '{}'", s));
    Expr index;
    index.kind = Expr::Kind::Index;
    index.args = {name, number(double(std::stoi(digits)), true)};
    return index;
  }

  std::vector<uint32_t> tokens(const std::vector<uint8_t>& data, size_t from) const {
    if (data.size() % 4) bad(from, fmt::format("shader bytecode of {} bytes is not whole DWORDs", data.size()));
    std::vector<uint32_t> t(data.size() / 4);
    if (!t.empty()) std::memcpy(t.data(), data.data(), data.size());
    return t;
  }

  StateAssignment assignment(const RawState& s, const Large* large, bool inSampler) const {
    StateAssignment a;
    a.name = inSampler && s.op == 164 ? "Texture" : stateNameOf(s.op);
    if (a.name.empty()) bad(s.at, fmt::format("state operation {} has no name", s.op));
    a.where = SourceLocation{name_, 0, 0};
    const auto info = inSampler && s.op == 164 ? std::optional<StateInfo>() : findState(a.name);
    if (!inSampler && info && info->indexed) a.index = number(double(s.index), true);
    if (inSampler && s.op != 164 && (s.op < 165 || s.op > 177))
      bad(s.at, fmt::format("state operation {} ({}) inside a sampler block", s.op, a.name));
    const ParameterDesc& t = s.type;
    if (large && large->usage == 2)
      bad(large->at, "shader array selectors (large object usage 2) are not supported");
    const bool shaderState = s.op == 146 || s.op == 147;
    if (shaderState) {
      ShaderExpr sh;
      sh.where = a.where;
      if (large && large->usage == 1) {
        sh.kind = ShaderExpr::Kind::Reference;
        sh.reference = reference(*large);
      } else if (large && large->usage == 0) {
        sh.kind = ShaderExpr::Kind::Bytecode;
        sh.tokens = tokens(large->data, large->dataAt);
      } else {
        const uint32_t id = at(relative(s.valueAt, 4, s.at + 12));
        auto it = smalls_.find(id);
        if (it != smalls_.end() && !it->second.empty()) {
          sh.kind = ShaderExpr::Kind::Bytecode;
          sh.tokens = tokens(it->second, s.at);
        }
      }
      a.shader = std::move(sh);
      return a;
    }
    if (large && large->usage == 1) {
      a.value = reference(*large);
      return a;
    }
    if (!t.isNumeric()) {
      if (large) bad(large->at, fmt::format("an expression (usage 0) for the {} state {}", parameterTypeName(t.type), a.name));
      a.value.kind = Expr::Kind::Null;
      return a;
    }
    if (large) {
      a.value.kind = Expr::Kind::Preshader;
      a.value.preshader = std::make_shared<FxlcProgram>(decodeFxlc(tokens(large->data, large->dataAt), name_, large->dataAt));
      a.value.components = t.valueCount();
      return a;
    }
    const size_t n = size_t(t.valueCount());
    const size_t off = relative(s.valueAt, 4 * n, s.at + 12);
    std::vector<uint32_t> words;
    for (size_t i = 0; i < n; ++i) words.push_back(at(off + 4 * i));
    a.value = numbers(t.type, words);
    return a;
  }

  EffectAst build() const {
    EffectAst ast;
    ast.files = {name_};
    for (size_t i = 0; i < params_.size(); ++i) {
      const RawParam& rp = params_[i];
      ParameterDecl p;
      p.desc = rp.value.desc;
      // fxc writes MATRIX_ROWS for every matrix (§2.2); the packing is not in the
      // binary, and refx reads matrices as column_major, HLSL's default.
      if (p.desc.cls == ParameterClass::MatrixRows) p.desc.cls = ParameterClass::MatrixColumns;
      p.desc.flags = rp.flags & kParameterShared;
      p.where = SourceLocation{name_, 0, 0};
      p.annotations = annotations(rp.annotations);
      if (p.desc.name.empty()) bad(rp.at, "a parameter without a name");
      const ParameterDesc& d = p.desc;
      if (d.isNumeric()) {
        p.init = numbers(d.type, rp.value.words);
      } else if (d.type == ParameterType::String) {
        Expr text;
        text.kind = Expr::Kind::String;
        text.text = rp.value.words.empty() ? "" : objectText(rp.value.words[0]);
        p.init = text;
      } else if (d.type == ParameterType::VertexShader || d.type == ParameterType::PixelShader) {
        if (!rp.value.words.empty()) {
          auto it = smalls_.find(rp.value.words[0]);
          if (it != smalls_.end() && !it->second.empty()) {
            ShaderExpr sh;
            sh.kind = ShaderExpr::Kind::Bytecode;
            sh.where = p.where;
            sh.tokens = tokens(it->second, rp.at);
            p.shaderInit = std::move(sh);
          }
        }
      } else if (d.isSampler() && !rp.value.samplerBlocks.empty()) {
        std::vector<StateAssignment> states;
        const auto& block = rp.value.samplerBlocks[0];
        for (size_t k = 0; k < block.size(); ++k) {
          const Large* l = large(kNone, uint32_t(i), d.elements ? 0 : kNone, uint32_t(k));
          if (!l && d.elements) l = large(kNone, uint32_t(i), kNone, uint32_t(k));
          states.push_back(assignment(block[k], l, true));
        }
        p.samplerInit = std::move(states);
      }
      ast.parameters.push_back(std::move(p));
    }
    for (size_t t = 0; t < techniques_.size(); ++t) {
      const RawTechnique& rt = techniques_[t];
      TechniqueDecl td;
      td.name = rt.name;
      td.where = SourceLocation{name_, 0, 0};
      td.annotations = annotations(rt.annotations);
      for (size_t p = 0; p < rt.passes.size(); ++p) {
        const RawPass& rpass = rt.passes[p];
        PassDecl pd;
        pd.name = rpass.name;
        pd.where = td.where;
        pd.annotations = annotations(rpass.annotations);
        for (size_t k = 0; k < rpass.states.size(); ++k)
          pd.states.push_back(assignment(rpass.states[k], large(uint32_t(t), uint32_t(p), kNone, uint32_t(k)), false));
        td.passes.push_back(std::move(pd));
      }
      ast.techniques.push_back(std::move(td));
    }
    return ast;
  }

  const Large* large(uint32_t technique, uint32_t index, uint32_t element, uint32_t state) const {
    auto it = larges_.find({technique, index, element, state});
    return it == larges_.end() ? nullptr : &it->second;
  }

  std::span<const uint8_t> b_;
  std::string name_;
  uint32_t u_ = 0;
  size_t pos_ = 0;
  uint32_t objectCount_ = 0;
  std::vector<RawParam> params_;
  std::vector<RawTechnique> techniques_;
  std::map<uint32_t, std::vector<uint8_t>> smalls_;
  std::map<std::tuple<uint32_t, uint32_t, uint32_t, uint32_t>, Large> larges_;
};

}  // namespace

bool isFx2Binary(std::span<const uint8_t> bytes) {
  if (bytes.size() < 4) return false;
  uint32_t tag;
  std::memcpy(&tag, bytes.data(), 4);
  return tag == kTag;
}

EffectAst readFx2(std::span<const uint8_t> bytes, const std::string& name) { return Reader(bytes, name).read(); }

}  // namespace refx::effect::detail
