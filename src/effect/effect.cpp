// The Effect object: parameters with their storage, techniques whose passes hold
// bound state assignments, and the evaluation of those assignments onto a Device.
#include "refx/effect/effect.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "ast.h"
#include "effect_errors.h"
#include "effect_internal.h"
#include "fx2_reader.h"
#include "fxlc.h"
#include "refx/core/text.h"
#include "refx/hlsl/compiler.h"
#include "refx/pipeline/dx8_declaration.h"
#include "refx/shader/assembler.h"
#include "refx/shader/constant_table.h"
#include "state_table.h"

namespace refx::effect {

using namespace detail;

// The value of a parameter; shared between the effects of a pool for `shared` ones.
struct EffectPool::Storage {
  ParameterDesc desc;
  std::vector<uint32_t> raw;  // numeric values, row-major per element: float bits, int, or 0/1
  std::string text;
  TexturePtr texture;
};

std::shared_ptr<EffectPool::Storage> EffectPool::find(const std::string& name) const {
  for (const auto& [n, s] : shared_)
    if (n == name) return s;
  return nullptr;
}

void EffectPool::add(const std::string& name, std::shared_ptr<Storage> s) { shared_.emplace_back(name, std::move(s)); }

std::string_view parameterTypeName(ParameterType type) {
  static constexpr std::string_view kNames[] = {
      "void", "bool", "int", "float", "string", "texture", "texture1D", "texture2D", "texture3D",
      "textureCUBE", "sampler", "sampler1D", "sampler2D", "sampler3D", "samplerCUBE",
      "pixelshader", "vertexshader"};
  const size_t i = size_t(type);
  return i < std::size(kNames) ? kNames[i] : "unknown";
}

std::string EffectDiagnostic::str() const {
  const std::string loc = where.str();
  return fmt::format("{}{}{}{}{}: {}", loc, loc.empty() ? "" : ": ", error ? "error" : "warning", code.empty() ? "" : " ",
                     code, message);
}

namespace {

// A shader made from an asm block (with its DirectX 8 declaration) or compiled from the
// effect's HLSL (with the constant table that binds parameters to registers).
struct CompiledShader {
  bool vertex = true;
  std::vector<uint32_t> tokens;
  std::optional<shader::VsDeclaration> declaration;
  std::optional<shader::ShaderConstantTable> constants;
  std::optional<hlsl::Preshader> preshader;  // run at each BeginPass / CommitChanges
  // A shader loaded from an fx_2_0 binary: its PRES preshader, run the same way.
  std::shared_ptr<const FxlcProgram> loadedPreshader;
  std::string profile, entry;                // compiled ones: what was compiled
  std::vector<std::string> entryArguments;
  VertexShaderPtr vs;
  PixelShaderPtr ps;
};
using ShaderRef = std::shared_ptr<const CompiledShader>;

struct Param;

// A state assignment bound to its target.
struct BoundState {
  std::string name;
  StateInfo info;
  int index = 0;
  SourceLocation where;
  Expr value;
  // Shader states: a shader made here, NULL, or a shader parameter (in `value`).
  ShaderRef shader;
  bool shaderFromValue = false;
  // Sampler states given by a sampler_state block on Sampler[n].
  std::vector<BoundState> samplerStates;
  bool samplerBlock = false;
};

struct Param {
  ParameterDecl decl;
  std::shared_ptr<EffectPool::Storage> store;
  ShaderRef shader;                     // vertexshader / pixelshader parameters
  std::vector<BoundState> samplerStates;  // sampler parameters (sampler_state)
};

struct Pass {
  PassDesc desc;
  std::vector<BoundState> states;
};

struct Technique {
  TechniqueDesc desc;
  std::vector<Pass> passes;
};

// Numbers are doubles while evaluated; these convert as a C cast would for values in
// range, and saturate (NaN: 0) instead of being undefined outside it.
int64_t toInteger(double x) {
  if (!(x == x)) return 0;
  if (x >= 9.2e18) return INT64_MAX;
  if (x <= -9.2e18) return INT64_MIN;
  return int64_t(x);
}
uint32_t toDword(double x) { return uint32_t(toInteger(x)); }

// `p[i]` on an array parameter of `elements` elements.
void checkElementIndex(const Expr& e, const Expr& base, int i, int elements) {
  if (i < 0 || i >= elements) failCode("F1205", e.where, "index {} is outside '{}[{}]'", i, base.text, elements);
}

// `v[i]` on a value: row i of a matrix, component i of anything else, as (first, count).
std::pair<size_t, size_t> indexedRow(const Expr& e, int i, int rows, int columns, size_t size) {
  const size_t per = columns > 0 && rows > 1 ? size_t(columns) : 1;
  if (i < 0 || (size_t(i) + 1) * per > size) failCode("F1205", e.where, "index {} is out of range", i);
  return {size_t(i) * per, per};
}

// The components a swizzle (`.xyzw` or `.rgba`, up to four) selects from a value of
// `count` components.
std::vector<size_t> swizzleComponents(const Expr& e, size_t count) {
  std::vector<size_t> out;
  for (char c : e.text) {
    const std::string_view xyzw = "xyzw", rgba = "rgba";
    size_t k = xyzw.find(c);
    if (k == std::string_view::npos) k = rgba.find(c);
    if (k == std::string_view::npos || k >= count || e.text.size() > 4)
      failCode("F1205", e.where, "'.{}' is not a swizzle of a {}-component value", e.text, count);
    out.push_back(k);
  }
  return out;
}
int toInt(double x) { return int(std::clamp<int64_t>(toInteger(x), INT32_MIN, INT32_MAX)); }

int scalarCount(const ParameterDesc& d) { return d.isNumeric() ? d.valueCount() : 0; }

uint32_t encodeScalar(ParameterType type, double v) {
  switch (type) {
    case ParameterType::Bool: return v != 0 ? 1u : 0u;
    case ParameterType::Int: return toDword(v);
    default: return floatBits(float(v));
  }
}

double decodeScalar(ParameterType type, uint32_t raw) {
  switch (type) {
    case ParameterType::Bool: return raw ? 1.0 : 0.0;
    case ParameterType::Int: return double(int32_t(raw));
    default: return double(bitsFloat(raw));
  }
}

// The result of evaluating a state value or an initializer.
struct Value {
  std::vector<double> numbers;
  ParameterClass cls = ParameterClass::Vector;  // how shader-constant registers are laid out
  int rows = 1, columns = 0;                    // columns 0: packed four per register
  const Param* object = nullptr;                // texture / sampler / shader / string parameter
  const Param* source = nullptr;                // the numeric parameter the value was read from
  bool isNull = false;
  std::string text;
  bool isString = false;
};

D3DColor packColor(const std::vector<double>& v) {
  auto byte = [](double x) { return uint32_t(std::lround(std::clamp(x, 0.0, 1.0) * 255.0)); };
  const double a = v.size() >= 4 ? v[3] : 1.0;
  return (byte(a) << 24) | (byte(v[0]) << 16) | (byte(v.size() > 1 ? v[1] : 0) << 8) | byte(v.size() > 2 ? v[2] : 0);
}

}  // namespace

struct Effect::Impl {
  std::string fileName;
  std::string sourceText;  // the effect's text, compiled again for each `compile` expression
  EffectOptions options;
  std::map<std::string, ShaderRef> compiled;
  bool preReleaseDialect = false;  // `fx.2.0` files compile with the compatibility option  // "profile entry(args)" → shader, within this effect
  std::vector<std::string> files;
  std::vector<EffectDiagnostic> diagnostics;
  std::vector<Param> params;
  std::vector<Technique> techniques;
  std::vector<std::string> functions;
  Handle current = -1;

  // Rendering state between begin and end.
  Device* device = nullptr;
  uint32_t beginFlags = 0;
  std::optional<StateBlock> saved;
  int activePass = -1;

  // ---------------------------------------------------------------- lookup
  const Param* findParam(std::string_view name) const {
    for (const Param& p : params)
      if (p.decl.desc.name == name) return &p;
    return nullptr;
  }

  Param& param(Handle h) {
    if (h < 0 || size_t(h) >= params.size()) fail("effect parameter handle {} is out of range", h);
    return params[size_t(h)];
  }
  const Param& param(Handle h) const { return const_cast<Impl*>(this)->param(h); }

  // ---------------------------------------------------------------- evaluation
  Value paramValue(const Param& p, int element = -1) const {
    Value v;
    const ParameterDesc& d = p.decl.desc;
    if (!d.isNumeric()) {
      v.object = &p;
      if (d.type == ParameterType::String) {
        v.text = p.store->text;
        v.isString = true;
      }
      return v;
    }
    const int per = d.rows * d.columns;
    const int first = element < 0 ? 0 : element * per;
    const int count = element < 0 ? scalarCount(d) : per;
    for (int i = 0; i < count; ++i) v.numbers.push_back(decodeScalar(d.type, p.store->raw[size_t(first + i)]));
    v.cls = d.cls == ParameterClass::Scalar ? ParameterClass::Vector : d.cls;
    v.source = &p;
    v.rows = d.rows;
    v.columns = d.columns;
    return v;
  }

  Value eval(const Expr& e) const {
    switch (e.kind) {
      case Expr::Kind::Number:
      case Expr::Kind::Bool: {
        Value v;
        v.numbers = {e.number};
        return v;
      }
      case Expr::Kind::String: {
        Value v;
        v.text = e.text;
        v.isString = true;
        return v;
      }
      case Expr::Kind::Null: {
        Value v;
        v.isNull = true;
        return v;
      }
      case Expr::Kind::Name: {
        if (const Param* p = findParam(e.text)) return paramValue(*p);
        failCode("F1200", e.where, "unknown parameter '{}'", e.text);
      }
      case Expr::Kind::ParamRef: return eval(e.args[0]);
      case Expr::Kind::Preshader: {
        Value v;
        const std::vector<float> out = e.preshader->run(preshaderInputs(e.preshader->inputs));
        for (int i = 0; i < e.components; ++i) v.numbers.push_back(size_t(i) < out.size() ? double(out[size_t(i)]) : 0.0);
        return v;
      }
      case Expr::Kind::List:
      case Expr::Kind::Call: {
        Value v;
        for (const Expr& a : e.args) {
          Value x = eval(a);
          if (x.object || x.isNull || x.isString)
            failCode("F1205", a.where, "expected a number in {}", e.kind == Expr::Kind::List ? "the list" : e.text + "(…)");
          v.numbers.insert(v.numbers.end(), x.numbers.begin(), x.numbers.end());
        }
        if (e.kind == Expr::Kind::Call) {
          ParameterDesc shape;
          if (!constructorShape(e.text, shape))
            failCode("F1205", e.where, "'{}' is not a constructor (float4(…), float4x4(…), …); other functions in "
                                       "state values need the HLSL compiler", e.text);
          const size_t want = size_t(shape.rows * shape.columns);
          if (v.numbers.size() == 1 && want > 1) v.numbers.assign(want, v.numbers[0]);
          if (v.numbers.size() != want)
            failCode("F1205", e.where, "{}(…) takes {} values, {} given", e.text, want, v.numbers.size());
          v.cls = shape.cls == ParameterClass::Scalar ? ParameterClass::Vector : shape.cls;
          v.rows = shape.rows;
          v.columns = shape.columns;
        }
        return v;
      }
      case Expr::Kind::Unary: {
        Value v = numeric(e.args[0]);
        for (double& x : v.numbers) {
          if (e.text == "-") x = -x;
          else if (e.text == "!") x = x == 0 ? 1 : 0;
          else x = double(~toDword(x));
        }
        return v;
      }
      case Expr::Kind::Binary: {
        Value a = numeric(e.args[0]);
        Value b = numeric(e.args[1]);
        if (a.numbers.size() != b.numbers.size() && a.numbers.size() != 1 && b.numbers.size() != 1)
          failCode("F1205", e.where, "'{}' between values of {} and {} components", e.text, a.numbers.size(), b.numbers.size());
        Value r = a.numbers.size() >= b.numbers.size() ? a : b;
        for (size_t i = 0; i < r.numbers.size(); ++i) {
          const double x = a.numbers[a.numbers.size() == 1 ? 0 : i];
          const double y = b.numbers[b.numbers.size() == 1 ? 0 : i];
          const uint32_t xi = toDword(x), yi = toDword(y);
          const std::string& op = e.text;
          double z = 0;
          if (op == "+") z = x + y;
          else if (op == "-") z = x - y;
          else if (op == "*") z = x * y;
          else if (op == "/") z = x / y;
          else if (op == "%") z = std::fmod(x, y);
          else if (op == "|") z = double(xi | yi);
          else if (op == "&") z = double(xi & yi);
          else if (op == "^") z = double(xi ^ yi);
          else if (op == "<<") z = double(yi < 32 ? xi << yi : 0);
          else if (op == ">>") z = double(yi < 32 ? xi >> yi : 0);
          else if (op == "<") z = x < y;
          else if (op == ">") z = x > y;
          else if (op == "<=") z = x <= y;
          else if (op == ">=") z = x >= y;
          else if (op == "==") z = x == y;
          else if (op == "!=") z = x != y;
          else if (op == "&&") z = x != 0 && y != 0;
          else if (op == "||") z = x != 0 || y != 0;
          r.numbers[i] = z;
        }
        return r;
      }
      case Expr::Kind::Index: {
        const Expr& base = e.args[0];
        const Value idx = numeric(e.args[1]);
        if (idx.numbers.size() != 1) failCode("F1205", e.args[1].where, "an index must be a scalar");
        const int i = toInt(idx.numbers[0]);
        if (base.kind == Expr::Kind::Name) {
          if (const Param* p = findParam(base.text); p && p->decl.desc.elements > 0) {
            checkElementIndex(e, base, i, p->decl.desc.elements);
            return paramValue(*p, i);
          }
        }
        Value v = numeric(base);
        const auto [first, per] = indexedRow(e, i, v.rows, v.columns, v.numbers.size());
        Value r;
        r.numbers.assign(v.numbers.begin() + std::ptrdiff_t(first), v.numbers.begin() + std::ptrdiff_t(first + per));
        r.columns = int(per);
        return r;
      }
      case Expr::Kind::Member: {
        Value v = numeric(e.args[0]);
        Value r;
        for (size_t k : swizzleComponents(e, v.numbers.size())) r.numbers.push_back(v.numbers[k]);
        r.columns = int(r.numbers.size());
        return r;
      }
    }
    failCode("F1205", e.where, "cannot evaluate this value");
  }

  Value numeric(const Expr& e) const {
    Value v = eval(e);
    if (v.object || v.isNull || v.isString) failCode("F1205", e.where, "expected a number");
    return v;
  }

  bool constructorShape(const std::string& name, ParameterDesc& shape) const {
    // The pre-release dialect's vec2/vec3/vec4 are float2/float3/float4.
    const bool vec = preReleaseDialect && name.size() == 4 && name.rfind("vec", 0) == 0;
    const auto t = numericTypeName(vec ? "float" + name.substr(3) : name);
    if (!t) return false;
    shape = *t;
    // A constructor lists a matrix's values row by row.
    if (shape.cls == ParameterClass::MatrixColumns) shape.cls = ParameterClass::MatrixRows;
    return true;
  }

  // A state value as the DWORD SetRenderState / SetTextureStageState / SetSamplerState take.
  uint32_t stateDword(const BoundState& s) const {
    const d3d::StateValueInfo vi = s.info.value;
    if (vi.kind == d3d::ValueKind::Enum || vi.kind == d3d::ValueKind::Flags ||
        s.info.target == StateTarget::StageState) {
      if (auto k = keyword(s.value, vi.enumKind)) return *k;
    }
    const Value v = eval(s.value);
    if (v.object || v.isNull || v.isString || v.numbers.empty())
      failCode("F1203", s.value.where, "'{}' takes a number{}", s.name,
                        vi.kind == d3d::ValueKind::Enum ? " or one of its keywords" : "");
    switch (vi.kind) {
      case d3d::ValueKind::Float: return floatBits(float(v.numbers[0]));
      case d3d::ValueKind::Color:
        if (v.numbers.size() >= 3) return packColor(v.numbers);
        return toDword(v.numbers[0]);
      default: return toDword(v.numbers[0]);
    }
  }

  // Keywords of the state's enumeration: "Modulate", "RED | GREEN", "1 | CameraSpaceNormal".
  std::optional<uint32_t> keyword(const Expr& e, d3d::EnumKind kind) const {
    if (e.kind == Expr::Kind::Name) {
      if (findParam(e.text)) return std::nullopt;  // a parameter wins over a keyword spelling
      if (auto v = d3d::parseEnum(kind, e.text)) return v;
      if (kind == d3d::EnumKind::Bool) return std::nullopt;
      // D3DX's keyword lists are per state; the enum tables cover them.
      return std::nullopt;
    }
    if (e.kind == Expr::Kind::Number && e.isInt) return toDword(e.number);
    if (e.kind == Expr::Kind::Bool) return toDword(e.number);
    if (e.kind == Expr::Kind::Binary && e.text == "|") {
      auto a = keyword(e.args[0], kind);
      auto b = keyword(e.args[1], kind);
      if (a && b) return *a | *b;
    }
    return std::nullopt;
  }

  // The registers a value fills from a shader-constant state.
  static std::vector<Vec4> registers(const Value& v) {
    std::vector<Vec4> regs;
    auto at = [&](size_t i) { return i < v.numbers.size() ? float(v.numbers[i]) : 0.0f; };
    if (v.columns > 0 && (v.cls == ParameterClass::MatrixColumns || v.cls == ParameterClass::MatrixRows)) {
      const size_t per = size_t(v.rows * v.columns);
      for (size_t base = 0; base < v.numbers.size(); base += per) {
        if (v.cls == ParameterClass::MatrixColumns) {  // one register per column
          for (int c = 0; c < v.columns; ++c)
            regs.push_back({at(base + 0 * v.columns + c), v.rows > 1 ? at(base + 1 * v.columns + c) : 0,
                            v.rows > 2 ? at(base + 2 * v.columns + c) : 0, v.rows > 3 ? at(base + 3 * v.columns + c) : 0});
        } else {
          for (int r = 0; r < v.rows; ++r) {
            const size_t o = base + size_t(r * v.columns);
            regs.push_back({at(o), v.columns > 1 ? at(o + 1) : 0, v.columns > 2 ? at(o + 2) : 0,
                            v.columns > 3 ? at(o + 3) : 0});
          }
        }
      }
      return regs;
    }
    const size_t per = v.columns > 0 ? size_t(v.columns) : 4;
    for (size_t o = 0; o < v.numbers.size(); o += per)
      regs.push_back({at(o), per > 1 && o + 1 < o + per ? at(o + 1) : 0, per > 2 ? at(o + 2) : 0, per > 3 ? at(o + 3) : 0});
    return regs;
  }

  const Param* objectParam(const BoundState& s, std::initializer_list<ParameterType> types, const char* what) const {
    const Value v = eval(s.value);
    if (v.isNull) return nullptr;
    if (!v.object && v.source)
      failCode("F1203", s.value.where, "'{}' takes a {} parameter; '{}' is a {}", s.name, what, v.source->decl.desc.name,
                        parameterTypeName(v.source->decl.desc.type));
    if (!v.object) failCode("F1203", s.value.where, "'{}' takes a {} parameter", s.name, what);
    const ParameterType t = v.object->decl.desc.type;
    const bool ok = std::find(types.begin(), types.end(), t) != types.end();
    if (!ok)
      failCode("F1203", s.value.where, "'{}' takes a {} parameter; '{}' is a {}", s.name, what, v.object->decl.desc.name,
                        parameterTypeName(t));
    return v.object;
  }

  // ---------------------------------------------------------------- applying
  void applyShader(Device& dev, const BoundState& s) const {
    const bool vertex = s.info.target == StateTarget::VertexShader;
    ShaderRef sh = s.shader;
    if (s.shaderFromValue) {
      const Param* p = objectParam(s, {vertex ? ParameterType::VertexShader : ParameterType::PixelShader},
                                   vertex ? "vertexshader" : "pixelshader");
      sh = p ? p->shader : nullptr;
    }
    if (vertex) {
      dev.setVertexShader(sh ? sh->vs : nullptr);
      if (sh && sh->declaration) {
        dev.setVertexDeclaration(vertexDeclarationFromVsd(*sh->declaration));
        setVsdConstants(dev, *sh->declaration);
      }
    } else {
      dev.setPixelShader(sh ? sh->ps : nullptr);
    }
    if (sh && (sh->constants || sh->loadedPreshader)) bindParameters(dev, *sh);
  }

  // What D3DX does for a compiled shader: every uniform of its constant table that names
  // a parameter gets the parameter's value in the table's registers, and every sampler
  // its sampler_state (with the texture) on the sampler the table gives.
  void bindParameters(Device& dev, const CompiledShader& sh) const {
    if (sh.constants) for (const shader::ShaderConstant& c : sh.constants->constants) {
      const Param* p = findParam(c.name);
      if (!p) continue;  // an entry point's uniform argument ("$k"), folded by the compiler
      const ParameterDesc& d = p->decl.desc;
      if (c.registerSet == shader::RegisterSet::Sampler) {
        if (d.isTexture()) {  // the pre-release dialect samples a texture directly
          for (int i = 0; i < std::max(1, c.registerCount); ++i) {
            const int sampler = (sh.vertex ? d3d::kVertexSampler0 : 0) + c.registerIndex + i;
            if (sampler < d3d::kMaxSamplers) dev.setTexture(sampler, p->store->texture);
          }
          continue;
        }
        if (!d.isSampler()) continue;
        for (int i = 0; i < std::max(1, c.registerCount); ++i) {
          const int sampler = (sh.vertex ? d3d::kVertexSampler0 : 0) + c.registerIndex + i;
          if (sampler < d3d::kMaxSamplers) applySamplerStates(dev, sampler, p->samplerStates);
        }
        continue;
      }
      if (!d.isNumeric()) continue;
      const Value v = paramValue(*p);
      const std::vector<Vec4> regs = constantRegisters(v, c);
      if (regs.empty()) continue;
      const uint32_t first = uint32_t(c.registerIndex), count = uint32_t(regs.size());
      switch (c.registerSet) {
        case shader::RegisterSet::Float4:
          if (sh.vertex) dev.setVertexShaderConstantF(first, &regs[0].x, count);
          else dev.setPixelShaderConstantF(first, &regs[0].x, count);
          break;
        case shader::RegisterSet::Int4: {
          std::vector<int> ints;
          for (const Vec4& r : regs)
            for (float x : {r.x, r.y, r.z, r.w}) ints.push_back(toInt(x));
          if (sh.vertex) dev.setVertexShaderConstantI(first, ints.data(), count);
          else dev.setPixelShaderConstantI(first, ints.data(), count);
          break;
        }
        case shader::RegisterSet::Bool: {
          // One bool register per value (registers() packs four values into one Vec4).
          std::vector<int> bools;
          for (double x : v.numbers) bools.push_back(x != 0);
          if (bools.size() > size_t(c.registerCount)) bools.resize(size_t(c.registerCount));
          if (sh.vertex) dev.setVertexShaderConstantB(first, bools.data(), uint32_t(bools.size()));
          else dev.setPixelShaderConstantB(first, bools.data(), uint32_t(bools.size()));
          break;
        }
        case shader::RegisterSet::Sampler: break;
      }
    }
    if (sh.preshader || sh.loadedPreshader) runPreshader(dev, sh);
  }

  // A parameter's value in the registers a constant table entry gives it (matrices
  // packed as the entry says).
  static std::vector<Vec4> constantRegisters(Value v, const shader::ShaderConstant& c) {
    if (c.cls == shader::ConstantClass::MatrixRows) v.cls = ParameterClass::MatrixRows;
    else if (c.cls == shader::ConstantClass::MatrixColumns) v.cls = ParameterClass::MatrixColumns;
    std::vector<Vec4> regs = registers(v);
    if (regs.size() > size_t(c.registerCount)) regs.resize(size_t(c.registerCount));
    return regs;
  }

  // The preshader's inputs are parameters (or, for a uniform no parameter names, its
  // default value); its results go to the shader's float constants.
  void runPreshader(Device& dev, const CompiledShader& sh) const {
    if (sh.loadedPreshader) {
      const FxlcProgram& pre = *sh.loadedPreshader;
      const std::vector<float> out = pre.run(preshaderInputs(pre.inputs));
      for (int reg : pre.outputRegisters()) {
        if (size_t(reg) * 4 + 4 > out.size()) continue;
        if (sh.vertex) dev.setVertexShaderConstantF(uint32_t(reg), &out[size_t(reg) * 4], 1);
        else dev.setPixelShaderConstantF(uint32_t(reg), &out[size_t(reg) * 4], 1);
      }
      return;
    }
    const hlsl::Preshader& pre = *sh.preshader;
    const std::vector<float> out = pre.run(preshaderInputs(pre.inputs));
    for (size_t i = 0; i < pre.outputRegisters.size(); ++i) {
      const uint32_t reg = uint32_t(pre.outputRegisters[i]);
      if (sh.vertex) dev.setVertexShaderConstantF(reg, &out[4 * i], 1);
      else dev.setPixelShaderConstantF(reg, &out[4 * i], 1);
    }
  }

  // A preshader's input registers: each constant of its table takes the named
  // parameter's value laid out as the table says (or the table's default value).
  std::vector<float> preshaderInputs(const shader::ShaderConstantTable& inputs) const {
    std::vector<float> input;
    for (const shader::ShaderConstant& c : inputs.constants) {
      const size_t at = size_t(c.registerIndex) * 4, size = size_t(c.registerCount) * 4;
      if (input.size() < at + size) input.resize(at + size, 0.0f);
      const Param* p = findParam(c.name);
      if (p && p->decl.desc.isNumeric()) {
        const std::vector<Vec4> regs = constantRegisters(paramValue(*p), c);
        for (size_t r = 0; r < regs.size(); ++r)
          for (size_t k = 0; k < 4; ++k) input[at + 4 * r + k] = (&regs[r].x)[k];
      } else if (c.defaultValue.size() == size) {
        std::copy(c.defaultValue.begin(), c.defaultValue.end(), input.begin() + std::ptrdiff_t(at));
      }
    }
    return input;
  }

  void applySamplerStates(Device& dev, int sampler, const std::vector<BoundState>& states) const {
    for (const BoundState& st : states) {
      if (st.info.target == StateTarget::Texture) {
        const Param* t = objectParam(st, {ParameterType::Texture, ParameterType::Texture1D, ParameterType::Texture2D,
                                          ParameterType::Texture3D, ParameterType::TextureCube},
                                     "texture");
        dev.setTexture(sampler, t ? t->store->texture : nullptr);
      } else {
        dev.setSamplerState(sampler, d3d::SamplerStateType(st.info.code), stateDword(st));
      }
    }
  }

  void apply(Device& dev, const BoundState& s) const {
    const int i = s.index;
    switch (s.info.target) {
      case StateTarget::RenderState: dev.setRenderState(d3d::RenderState(s.info.code), stateDword(s)); return;
      case StateTarget::StageState:
        dev.setTextureStageState(i, d3d::TextureStageState(s.info.code), stateDword(s));
        return;
      case StateTarget::SamplerState:
        dev.setSamplerState(i, d3d::SamplerStateType(s.info.code), stateDword(s));
        return;
      case StateTarget::Texture: {
        const Param* t = objectParam(s, {ParameterType::Texture, ParameterType::Texture1D, ParameterType::Texture2D,
                                         ParameterType::Texture3D, ParameterType::TextureCube},
                                     "texture");
        dev.setTexture(i, t ? t->store->texture : nullptr);
        return;
      }
      case StateTarget::Sampler: {
        if (s.samplerBlock) {
          applySamplerStates(dev, i, s.samplerStates);
          return;
        }
        const Param* p = objectParam(s, {ParameterType::Sampler, ParameterType::Sampler1D, ParameterType::Sampler2D,
                                         ParameterType::Sampler3D, ParameterType::SamplerCube},
                                     "sampler");
        if (p) applySamplerStates(dev, i, p->samplerStates);
        return;
      }
      case StateTarget::Transform: {
        const Value v = numeric(s.value);
        if (v.numbers.size() != 16) failCode("F1203", s.value.where, "'{}' takes a 4x4 matrix, not {} values", s.name, v.numbers.size());
        Matrix m;
        for (int r = 0; r < 4; ++r)
          for (int c = 0; c < 4; ++c) m.m[r][c] = float(v.numbers[size_t(r * 4 + c)]);
        dev.setTransform(s.info.code + uint32_t(i), m);
        return;
      }
      case StateTarget::Light: {
        Light l = dev.state().lights[size_t(i)];
        const auto member = LightMember(s.info.code);
        if (member == LightMember::Type) {
          l.type = stateDword(s);
        } else {
          const Value v = numeric(s.value);
          auto n = [&](size_t k) { return k < v.numbers.size() ? float(v.numbers[k]) : 0.0f; };
          const Color4 color{n(0), n(1), n(2), v.numbers.size() > 3 ? n(3) : 1.0f};
          switch (member) {
            case LightMember::Diffuse: l.diffuse = color; break;
            case LightMember::Specular: l.specular = color; break;
            case LightMember::Ambient: l.ambient = color; break;
            case LightMember::Position: l.position = {n(0), n(1), n(2)}; break;
            case LightMember::Direction: l.direction = {n(0), n(1), n(2)}; break;
            case LightMember::Range: l.range = n(0); break;
            case LightMember::Falloff: l.falloff = n(0); break;
            case LightMember::Attenuation0: l.attenuation0 = n(0); break;
            case LightMember::Attenuation1: l.attenuation1 = n(0); break;
            case LightMember::Attenuation2: l.attenuation2 = n(0); break;
            case LightMember::Theta: l.theta = n(0); break;
            case LightMember::Phi: l.phi = n(0); break;
            case LightMember::Type: break;
          }
        }
        dev.setLight(i, l);
        return;
      }
      case StateTarget::LightEnable: dev.lightEnable(i, stateDword(s) != 0); return;
      case StateTarget::Material: {
        Material m = dev.state().material;
        const Value v = numeric(s.value);
        auto n = [&](size_t k) { return k < v.numbers.size() ? float(v.numbers[k]) : 0.0f; };
        const Color4 color{n(0), n(1), n(2), v.numbers.size() > 3 ? n(3) : 1.0f};
        switch (MaterialMember(s.info.code)) {
          case MaterialMember::Ambient: m.ambient = color; break;
          case MaterialMember::Diffuse: m.diffuse = color; break;
          case MaterialMember::Specular: m.specular = color; break;
          case MaterialMember::Emissive: m.emissive = color; break;
          case MaterialMember::Power: m.power = n(0); break;
        }
        dev.setMaterial(m);
        return;
      }
      case StateTarget::VertexShader:
      case StateTarget::PixelShader: applyShader(dev, s); return;
      case StateTarget::VertexConstF:
      case StateTarget::PixelConstF: {
        std::vector<Vec4> regs = registers(numeric(s.value));
        if (s.info.code && regs.size() > s.info.code) regs.resize(s.info.code);
        const int limit = s.info.target == StateTarget::VertexConstF ? kMaxVertexShaderConstF : kMaxPixelShaderConstF;
        if (i + int(regs.size()) > limit)
          failCode("F1204", s.where, "'{}[{}]' writes {} registers, past c{}", s.name, i, regs.size(), limit - 1);
        if (regs.empty()) return;
        if (s.info.target == StateTarget::VertexConstF)
          dev.setVertexShaderConstantF(uint32_t(i), &regs[0].x, uint32_t(regs.size()));
        else
          dev.setPixelShaderConstantF(uint32_t(i), &regs[0].x, uint32_t(regs.size()));
        return;
      }
      case StateTarget::VertexConstI:
      case StateTarget::PixelConstI: {
        const Value v = numeric(s.value);
        std::vector<int> data;
        for (double x : v.numbers) data.push_back(toInt(x));
        while (data.size() % 4) data.push_back(0);
        const uint32_t count = uint32_t(data.size() / 4);
        if (i + int(count) > kMaxShaderConstI) failCode("F1204", s.where, "'{}[{}]' writes past i15", s.name, i);
        if (s.info.target == StateTarget::VertexConstI) dev.setVertexShaderConstantI(uint32_t(i), data.data(), count);
        else dev.setPixelShaderConstantI(uint32_t(i), data.data(), count);
        return;
      }
      case StateTarget::VertexConstB:
      case StateTarget::PixelConstB: {
        const Value v = numeric(s.value);
        std::vector<int> data;
        for (double x : v.numbers) data.push_back(x != 0);
        if (i + int(data.size()) > kMaxShaderConstB) failCode("F1204", s.where, "'{}[{}]' writes past b15", s.name, i);
        if (data.empty()) return;
        if (s.info.target == StateTarget::VertexConstB)
          dev.setVertexShaderConstantB(uint32_t(i), data.data(), uint32_t(data.size()));
        else
          dev.setPixelShaderConstantB(uint32_t(i), data.data(), uint32_t(data.size()));
        return;
      }
      case StateTarget::FVF: dev.setFVF(stateDword(s)); return;
      case StateTarget::NPatchMode: return;  // N-patches are not tessellated: the triangles draw as they are
    }
  }

  void applyPass(Device& dev, const Pass& pass) const {
    for (const BoundState& s : pass.states) apply(dev, s);
  }

  // ---------------------------------------------------------------- building
  ShaderRef buildShader(const ShaderExpr& e, bool vertex, const std::string& what) {
    if (e.kind == ShaderExpr::Kind::Compile) return compileShader(e, vertex, what);
    if (e.kind == ShaderExpr::Kind::Bytecode) return loadShader(e, vertex, what);
    auto sh = std::make_shared<CompiledShader>();
    sh->vertex = vertex;
    if (e.decl) {
      if (!vertex) failCode("F1207", e.decl->where, "{}: a decl block belongs to a vertex shader", what);
      sh->declaration = shader::parseVsDeclaration(e.decl->text, e.decl->file);
    }
    // Every error of the block, with the assembler's codes at the effect file's lines.
    DiagnosticSink asmErrors;
    shader::Shader parsed = shader::assemble(e.assembly.text, e.assembly.file, asmErrors);
    if (asmErrors.hasErrors()) {
      EffectError error(asmErrors.all().front(), false);
      error.also.assign(asmErrors.all().begin() + 1, asmErrors.all().end());
      throw error;
    }
    if ((parsed.version.type == shader::ShaderType::Vertex) != vertex)
      failCode("F1207", e.assembly.where, "{}: expected a {} shader, the asm block is {}", what, vertex ? "vertex" : "pixel",
                        parsed.version.name());
    sh->tokens = shader::encode(parsed);
    // The version's rules, reported at the instruction (the block's text keeps file positions).
    for (const Diagnostic& d : shader::validate(parsed, validationCaps()))
      failAt(SourceLocation{e.assembly.file, d.where.line, d.where.column}, "{}: {}", what, d.message);
    makeRuntimeShader(*sh, e.assembly.where, what);
    return sh;
  }

  // A shader from an fx_2_0 binary: its constant table binds parameters as a compiled
  // shader's does, and its PRES preshader (if any) runs at BeginPass / CommitChanges.
  ShaderRef loadShader(const ShaderExpr& e, bool vertex, const std::string& what) {
    auto sh = std::make_shared<CompiledShader>();
    sh->vertex = vertex;
    sh->tokens = e.tokens;
    shader::Shader decoded;
    try {
      decoded = shader::decode(e.tokens);
    } catch (const Error& err) {
      failCode("F1207", e.where, "{}: the shader's bytecode cannot be read: {}", what, err.what());
    }
    if ((decoded.version.type == shader::ShaderType::Vertex) != vertex)
      failCode("F1207", e.where, "{}: expected a {} shader, the bytecode is {}", what, vertex ? "vertex" : "pixel",
                        decoded.version.name());
    sh->constants = shader::readConstantTable(decoded);
    for (const shader::Instruction& ins : decoded.instructions) {
      if (ins.opcode != shader::Opcode::Comment) continue;
      if (ins.comment.size() < 2 || ins.comment[0] != 0x53455250u) continue;  // 'PRES'
      sh->loadedPreshader = std::make_shared<FxlcProgram>(
          decodeFxlc(std::span<const uint32_t>(ins.comment).subspan(1), what + " (PRES)", 0));
      break;
    }
    makeRuntimeShader(*sh, e.where, what);
    return sh;
  }

  static const shader::ValidationCaps& validationCaps() {
    static const shader::ValidationCaps kCaps = shaderValidationCaps(loadCapsProfile("ref"));
    return kCaps;
  }

  void makeRuntimeShader(CompiledShader& sh, const SourceLocation& where, const std::string& what) const {
    try {
      if (sh.vertex) sh.vs = std::make_shared<VertexShader>(sh.tokens, validationCaps());
      else sh.ps = std::make_shared<PixelShader>(sh.tokens, validationCaps());
    } catch (const Error& err) {
      // The shader's own rules, located at the block: "file:line:col: error: ps_1_1 allows …".
      std::string msg = err.what();
      if (msg.rfind("error: ", 0) == 0) msg = msg.substr(7);
      failAt(where, "{}: {}", what, msg);
    }
  }

  // An entry point's uniform argument as HLSL text: the value of a constant expression
  // of the effect (a literal, a vector constructor, a parameter's current value).
  std::string argumentText(const Expr& arg) const {
    const Value v = numeric(arg);
    if (v.numbers.empty()) failCode("F1205", arg.where, "an argument of 'compile' must have a value");
    std::string list;
    for (double x : v.numbers) list += fmt::format("{}{}", list.empty() ? "" : ", ", x);
    if (v.numbers.size() == 1) return list;
    return fmt::format("float{}({})", v.numbers.size(), list);
  }

  // `compile PROFILE Entry(args)`: the effect's own text goes to the HLSL compiler with
  // the entry point; each distinct compile expression is compiled once per effect.
  ShaderRef compileShader(const ShaderExpr& e, bool vertex, const std::string& what) {
    hlsl::CompileOptions opts;
    opts.profile = e.profile;
    opts.entry = e.entry;
    opts.includeDirs = options.includeDirs;
    opts.compatibility = preReleaseDialect;
    opts.preshaders = true;  // expressions of parameters run once per change, as fxc's effects did
    for (const auto& [name, value] : options.defines) opts.defines.push_back({name, value});
    for (const Expr& a : e.args) opts.entryArguments.push_back(argumentText(a));
    const bool vertexProfile = e.profile.rfind("vs", 0) == 0;
    if (vertexProfile != vertex)
      failCode("F1207", e.where, "{}: expected a {} shader profile, '{}' is a {} profile", what, vertex ? "vertex" : "pixel",
                        e.profile, vertexProfile ? "vertex" : "pixel");
    std::string key = e.profile + " " + e.entry + "(";
    for (const std::string& a : opts.entryArguments) key += a + ",";
    if (auto it = compiled.find(key); it != compiled.end()) return it->second;

    const hlsl::CompileResult r = hlsl::compile(sourceText, fileName, opts);
    if (!r.ok()) {
      // Every error goes to the diagnostics; the first one breaks the technique.
      const Diagnostic* first = nullptr;
      for (const Diagnostic& d : r.diagnostics) {
        if (d.severity != Severity::Error) continue;
        if (!first) { first = &d; continue; }
        EffectDiagnostic extra;
        extra.where = d.where;
        extra.message = fmt::format("{}: error {}: {}", what, d.code, d.message);
        diagnostics.push_back(std::move(extra));
      }
      if (!first) failAt(e.where, "{}: compile {} {} failed", what, e.profile, e.entry);
      failAt(first->where.line ? first->where : e.where, "{}: compile {} {}: error {}: {}", what, e.profile, e.entry,
             first->code, first->message);
    }
    auto sh = std::make_shared<CompiledShader>();
    sh->vertex = vertex;
    sh->tokens = r.tokens;
    sh->constants = shader::readConstantTable(r.shader);
    sh->preshader = r.preshader;
    sh->profile = e.profile;
    sh->entry = e.entry;
    sh->entryArguments = opts.entryArguments;
    makeRuntimeShader(*sh, e.where, what);
    compiled.emplace(key, sh);
    return sh;
  }

  int evalIndex(const StateAssignment& a, const StateInfo& info) const {
    if (!a.index) return 0;
    if (!info.indexed) failCode("F1201", a.index->where, "'{}' takes no index", a.name);
    const Value v = numeric(*a.index);
    if (v.numbers.size() != 1) failCode("F1202", a.index->where, "the index of '{}' must be a scalar", a.name);
    const double x = v.numbers[0];
    if (x < 0 || x > info.maxIndex || x != std::floor(x))
      failCode("F1202", a.index->where, "'{}[{}]' is out of range (0 to {})", a.name, x, info.maxIndex);
    return int(x);
  }

  BoundState bindState(const StateAssignment& a, bool inSamplerState) {
    BoundState s;
    s.name = a.name;
    s.where = a.where;
    s.value = a.value;
    if (inSamplerState && equalsNoCase(a.name, "Texture")) {
      s.info = {StateTarget::Texture};
      return s;
    }
    auto info = findState(a.name);
    if (!info) failCode("F1201", a.where, "unknown state '{}'", a.name);
    if (inSamplerState && info->target != StateTarget::SamplerState)
      failCode("F1201", a.where, "'{}' is not a sampler state (inside sampler_state: AddressU/V/W, BorderColor, "
                                 "Mag/Min/MipFilter, MipMapLodBias, MaxMipLevel, MaxAnisotropy, SRGBTexture, Texture)", a.name);
    if (inSamplerState && a.index) failCode("F1201", a.index->where, "sampler_state states take no index");
    s.info = *info;
    s.index = evalIndex(a, s.info);
    if (s.info.target == StateTarget::VertexShader || s.info.target == StateTarget::PixelShader) {
      const bool vertex = s.info.target == StateTarget::VertexShader;
      const ShaderExpr& e = *a.shader;
      if (e.kind == ShaderExpr::Kind::Reference) {
        s.value = e.reference;
        s.shaderFromValue = true;
        objectParam(s, {vertex ? ParameterType::VertexShader : ParameterType::PixelShader},
                    vertex ? "vertexshader" : "pixelshader");
      } else if (e.kind != ShaderExpr::Kind::Null) {
        s.shader = buildShader(e, vertex, a.name);
      }
      return s;
    }
    if (a.isSamplerState) {
      if (s.info.target != StateTarget::Sampler) failCode("F1201", a.where, "'{}' cannot take a sampler_state", a.name);
      for (const StateAssignment& st : a.samplerState) s.samplerStates.push_back(bindState(st, true));
      s.samplerBlock = true;
      return s;
    }
    checkValue(s);
    return s;
  }

  // Evaluates a state's value once at load so that bad references are reported there.
  void checkValue(const BoundState& s) const {
    switch (s.info.target) {
      case StateTarget::Texture:
        objectParam(s, {ParameterType::Texture, ParameterType::Texture1D, ParameterType::Texture2D,
                        ParameterType::Texture3D, ParameterType::TextureCube},
                    "texture");
        return;
      case StateTarget::Sampler:
        objectParam(s, {ParameterType::Sampler, ParameterType::Sampler1D, ParameterType::Sampler2D,
                        ParameterType::Sampler3D, ParameterType::SamplerCube},
                    "sampler");
        return;
      case StateTarget::RenderState:
      case StateTarget::StageState:
      case StateTarget::SamplerState:
      case StateTarget::LightEnable:
      case StateTarget::FVF:
        if (s.info.value.kind == d3d::ValueKind::Enum || s.info.value.kind == d3d::ValueKind::Flags) {
          const Expr& e = s.value;
          if (e.kind == Expr::Kind::Name && !findParam(e.text) && !d3d::parseEnum(s.info.value.enumKind, e.text))
            failCode("F1203", e.where, "'{}' is not a value of '{}' (a {} keyword or a parameter)", e.text, s.name,
                              enumKindName(s.info.value.enumKind));
        }
        stateDword(s);
        return;
      default: {
        if (s.info.target == StateTarget::Light && LightMember(s.info.code) == LightMember::Type) {
          stateDword(s);
          return;
        }
        numeric(s.value);
        return;
      }
    }
  }

  static std::string_view enumKindName(d3d::EnumKind k) {
    using K = d3d::EnumKind;
    switch (k) {
      case K::TextureOp: return "D3DTOP";
      case K::TextureArg: return "D3DTA";
      case K::Blend: return "D3DBLEND";
      case K::BlendOp: return "D3DBLENDOP";
      case K::CmpFunc: return "D3DCMP";
      case K::StencilOp: return "D3DSTENCILOP";
      case K::Cull: return "D3DCULL";
      case K::FillMode: return "D3DFILL";
      case K::ShadeMode: return "D3DSHADE";
      case K::FogMode: return "D3DFOG";
      case K::ZBufferType: return "D3DZB";
      case K::MaterialColorSource: return "D3DMCS";
      case K::TextureAddress: return "D3DTADDRESS";
      case K::TextureFilter: return "D3DTEXF";
      case K::LightType: return "D3DLIGHT";
      case K::Bool: return "TRUE/FALSE";
      case K::TexCoordIndexFlags: return "D3DTSS_TCI";
      case K::TextureTransformFlags: return "D3DTTFF";
      case K::ColorWrite: return "D3DCOLORWRITEENABLE";
      case K::Wrap: return "D3DWRAP";
      default: return "D3D";
    }
  }

  void initParameter(Param& p, const std::shared_ptr<EffectPool>& pool) {
    const ParameterDesc& d = p.decl.desc;
    if ((d.flags & kParameterShared) && pool) {
      if (auto s = pool->find(d.name)) {
        if (s->desc.type != d.type || s->desc.cls != d.cls || s->desc.rows != d.rows ||
            s->desc.columns != d.columns || s->desc.elements != d.elements)
          failCode("F1206", p.decl.where, "shared parameter '{}' has another type in the pool", d.name);
        p.store = s;
        return;  // the pool's value stands; this effect's initializer is not applied again
      }
    }
    p.store = std::make_shared<EffectPool::Storage>();
    p.store->desc = d;
    p.store->raw.assign(size_t(scalarCount(d)), 0);
    if (p.decl.init) {
      const Value v = eval(*p.decl.init);
      if (d.type == ParameterType::String) {
        if (!v.isString) failCode("F1206", p.decl.init->where, "'{}' is a string; expected \"text\"", d.name);
        p.store->text = v.text;
      } else if (d.isNumeric()) {
        if (v.object || v.isNull || v.isString)
          failCode("F1206", p.decl.init->where, "'{}' takes numbers as its initializer", d.name);
        std::vector<double> n = v.numbers;
        if (n.size() == 1 && p.store->raw.size() > 1 && !d.elements) n.assign(p.store->raw.size(), n[0]);
        if (n.size() != p.store->raw.size())
          failCode("F1206", p.decl.init->where, "'{}' has {} values, its initializer {}", d.name, p.store->raw.size(), n.size());
        for (size_t i = 0; i < n.size(); ++i) p.store->raw[i] = encodeScalar(d.type, n[i]);
      } else if (!v.isNull) {
        failCode("F1206", p.decl.init->where, "'{}' ({}) cannot be initialized with a value", d.name, parameterTypeName(d.type));
      }
    }
    if ((d.flags & kParameterShared) && pool) pool->add(d.name, p.store);
  }

  void build(EffectAst&& ast, const EffectOptions& options) {
    files = ast.files;
    functions = ast.functions;
    preReleaseDialect = ast.preReleaseDialect;
    // A declaration that cannot be made leaves its parameter out; every such error of
    // the file is reported, one per line, in the Error thrown after the declarations.
    std::string declarationErrors;
    for (ParameterDecl& decl : ast.parameters) {
      Param p;
      try {
        if (findParam(decl.desc.name))
          failCode("F1206", decl.where, "redefinition of parameter '{}'", decl.desc.name);
        p.decl = std::move(decl);
        initParameter(p, options.pool);
      } catch (const Error& e) {
        declarationErrors += (declarationErrors.empty() ? "" : "\n") + std::string(e.what());
        continue;
      }
      params.push_back(std::move(p));
      Param& q = params.back();
      // Shader and sampler parameters: a bad one is reported and left empty, so the
      // techniques that use it are the ones that break.
      try {
        if (q.decl.shaderInit && q.decl.shaderInit->kind != ShaderExpr::Kind::Null) {
          const bool vertex = q.decl.desc.type == ParameterType::VertexShader;
          if (q.decl.shaderInit->kind == ShaderExpr::Kind::Reference) {
            const Value v = eval(q.decl.shaderInit->reference);
            if (!v.object || v.object->decl.desc.type != q.decl.desc.type)
              failCode("F1207", q.decl.shaderInit->where, "'{}' must be initialized with a shader of its type", q.decl.desc.name);
            q.shader = v.object->shader;
          } else {
            q.shader = buildShader(*q.decl.shaderInit, vertex, q.decl.desc.name);
          }
        }
        if (q.decl.samplerInit)
          for (const StateAssignment& st : *q.decl.samplerInit) q.samplerStates.push_back(bindState(st, true));
      } catch (const Error& e) {
        diagnostics.push_back(diagnosticFrom(e));
        reportFollowing(e);
      }
    }
    if (!declarationErrors.empty()) throw Error(declarationErrors);
    for (TechniqueDecl& td : ast.techniques) {
      Technique t;
      t.desc.name = td.name;
      t.desc.annotations = td.annotations;
      for (PassDecl& pd : td.passes) {
        Pass pass;
        pass.desc.name = pd.name;
        pass.desc.annotations = pd.annotations;
        pass.desc.stateCount = int(pd.states.size());
        for (const StateAssignment& a : pd.states) {
          try {
            // A later assignment of the same state in a pass replaces the earlier one.
            BoundState s = bindState(a, false);
            std::erase_if(pass.states, [&](const BoundState& o) {
              return o.info.target == s.info.target && o.info.code == s.info.code && o.index == s.index &&
                     s.info.target != StateTarget::Light && s.info.target != StateTarget::Material;
            });
            pass.states.push_back(std::move(s));
          } catch (const Error& e) {
            EffectDiagnostic d = diagnosticFrom(e);
            if (t.desc.brokenReason.empty())
              t.desc.brokenReason = fmt::format("pass {}: {}", pd.name.empty() ? fmt::format("#{}", t.passes.size()) : pd.name, d.message);
            diagnostics.push_back(std::move(d));
            reportFollowing(e);
          }
        }
        t.desc.passes.push_back(pass.desc);
        t.passes.push_back(std::move(pass));
      }
      techniques.push_back(std::move(t));
    }
  }

  static EffectDiagnostic fromDiagnostic(const Diagnostic& from) {
    EffectDiagnostic d;
    d.where = from.where;
    d.message = from.message;
    d.error = from.severity == Severity::Error;
    d.code = from.code;
    return d;
  }

  // The errors an EffectError carries after its first one (the other errors of an asm block).
  void reportFollowing(const Error& e) {
    if (const auto* coded = dynamic_cast<const EffectError*>(&e))
      for (const Diagnostic& d : coded->also) diagnostics.push_back(fromDiagnostic(d));
  }

  // A coded error's diagnostic, or "file:line:col: error: message" split back into its parts.
  static EffectDiagnostic diagnosticFrom(const Error& e) {
    if (const auto* coded = dynamic_cast<const EffectError*>(&e)) return fromDiagnostic(coded->diagnostic);
    EffectDiagnostic d;
    std::string msg = e.what();
    const size_t pos = msg.find(": error: ");
    if (pos != std::string::npos) {
      const std::string loc = msg.substr(0, pos);
      d.message = msg.substr(pos + 9);
      // file may contain ':'; line and col are the last two fields
      const size_t c2 = loc.rfind(':');
      const size_t c1 = c2 == std::string::npos ? std::string::npos : loc.rfind(':', c2 - 1);
      if (c1 != std::string::npos) {
        d.where.file = loc.substr(0, c1);
        d.where.line = std::atoi(loc.c_str() + c1 + 1);
        d.where.column = std::atoi(loc.c_str() + c2 + 1);
      } else {
        d.where.file = loc;
      }
    } else {
      d.message = msg.rfind("error: ", 0) == 0 ? msg.substr(7) : msg;
    }
    return d;
  }
};

Effect::Effect() : impl_(std::make_unique<Impl>()) {}
Effect::~Effect() = default;

std::unique_ptr<Effect> Effect::fromText(std::string_view text, const std::string& fileName,
                                         const EffectOptions& options) {
  std::unique_ptr<Effect> e(new Effect());
  e->impl_->fileName = fileName;
  e->impl_->sourceText = text;
  e->impl_->options = options;
  e->impl_->build(parseEffect(text, fileName, options), options);
  return e;
}

std::unique_ptr<Effect> Effect::fromFx2(std::span<const uint8_t> bytes, const std::string& name,
                                        const EffectOptions& options) {
  std::unique_ptr<Effect> e(new Effect());
  e->impl_->fileName = name;
  e->impl_->options = options;
  e->impl_->build(readFx2(bytes, name), options);
  return e;
}

std::unique_ptr<Effect> Effect::fromFile(const std::string& path, const EffectOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("{}: error: cannot open the effect file", path);
  std::ostringstream s;
  s << in.rdbuf();
  const std::string text = s.str();
  const std::span<const uint8_t> bytes(reinterpret_cast<const uint8_t*>(text.data()), text.size());
  if (isFx2Binary(bytes)) return fromFx2(bytes, path, options);
  return fromText(text, path, options);
}

const std::string& Effect::fileName() const { return impl_->fileName; }
const std::vector<std::string>& Effect::sourceFiles() const { return impl_->files; }
const std::vector<EffectDiagnostic>& Effect::diagnostics() const { return impl_->diagnostics; }

// ---------------------------------------------------------------- parameters
int Effect::parameterCount() const { return int(impl_->params.size()); }
const ParameterDesc& Effect::parameterDesc(Handle p) const { return impl_->param(p).decl.desc; }
const std::vector<Annotation>& Effect::parameterAnnotations(Handle p) const { return impl_->param(p).decl.annotations; }

Handle Effect::parameterByName(std::string_view name) const {
  for (size_t i = 0; i < impl_->params.size(); ++i)
    if (impl_->params[i].decl.desc.name == name) return Handle(i);
  return -1;
}

Handle Effect::parameterBySemantic(std::string_view semantic) const {
  for (size_t i = 0; i < impl_->params.size(); ++i)
    if (!impl_->params[i].decl.desc.semantic.empty() && equalsNoCase(impl_->params[i].decl.desc.semantic, semantic))
      return Handle(i);
  return -1;
}

const Annotation* Effect::annotationByName(const std::vector<Annotation>& list, std::string_view name) const {
  for (const Annotation& a : list)
    if (a.desc.name == name) return &a;
  return nullptr;
}

namespace {

void requireNumeric(const ParameterDesc& d) {
  if (!d.isNumeric())
    fail("effect parameter '{}' is a {}, not a number", d.name, parameterTypeName(d.type));
}

}  // namespace

void Effect::setFloatArray(Handle p, const float* v, int count) {
  Param& q = impl_->param(p);
  requireNumeric(q.decl.desc);
  const size_t n = std::min(q.store->raw.size(), size_t(std::max(count, 0)));
  for (size_t i = 0; i < n; ++i) q.store->raw[i] = encodeScalar(q.decl.desc.type, v[i]);
}

void Effect::setIntArray(Handle p, const int* v, int count) {
  Param& q = impl_->param(p);
  requireNumeric(q.decl.desc);
  const size_t n = std::min(q.store->raw.size(), size_t(std::max(count, 0)));
  for (size_t i = 0; i < n; ++i) q.store->raw[i] = encodeScalar(q.decl.desc.type, double(v[i]));
}

void Effect::setBool(Handle p, bool v) { setInt(p, v ? 1 : 0); }
void Effect::setInt(Handle p, int v) { setIntArray(p, &v, 1); }
void Effect::setFloat(Handle p, float v) { setFloatArray(p, &v, 1); }
void Effect::setVector(Handle p, const Vec4& v) {
  const float f[4] = {v.x, v.y, v.z, v.w};
  setFloatArray(p, f, 4);
}

void Effect::setMatrix(Handle p, const Matrix& m) {
  Param& q = impl_->param(p);
  requireNumeric(q.decl.desc);
  const ParameterDesc& d = q.decl.desc;
  // Logical values row by row; the register layout (columns for column_major) is made
  // when a state or a shader constant reads the parameter.
  std::vector<float> f;
  for (int r = 0; r < d.rows; ++r)
    for (int c = 0; c < d.columns; ++c) f.push_back(m.m[r][c]);
  setFloatArray(p, f.data(), int(f.size()));
}

void Effect::setMatrixTranspose(Handle p, const Matrix& m) { setMatrix(p, transpose(m)); }

void Effect::setString(Handle p, std::string_view s) {
  Param& q = impl_->param(p);
  if (q.decl.desc.type != ParameterType::String) fail("effect parameter '{}' is not a string", q.decl.desc.name);
  q.store->text = std::string(s);
}

void Effect::setTexture(Handle p, TexturePtr t) {
  Param& q = impl_->param(p);
  if (!q.decl.desc.isTexture()) fail("effect parameter '{}' is not a texture", q.decl.desc.name);
  q.store->texture = std::move(t);
}

std::vector<float> Effect::getFloatArray(Handle p) const {
  const Param& q = impl_->param(p);
  requireNumeric(q.decl.desc);
  std::vector<float> out;
  for (uint32_t r : q.store->raw) out.push_back(float(decodeScalar(q.decl.desc.type, r)));
  return out;
}

bool Effect::getBool(Handle p) const { return getFloatArray(p).at(0) != 0; }
int Effect::getInt(Handle p) const {
  const Param& q = impl_->param(p);
  requireNumeric(q.decl.desc);
  return toInt(decodeScalar(q.decl.desc.type, q.store->raw.at(0)));
}
float Effect::getFloat(Handle p) const { return getFloatArray(p).at(0); }
Vec4 Effect::getVector(Handle p) const {
  std::vector<float> f = getFloatArray(p);
  f.resize(std::max<size_t>(f.size(), 4), 0.0f);
  return {f[0], f[1], f[2], f[3]};
}
Matrix Effect::getMatrix(Handle p) const {
  const Param& q = impl_->param(p);
  const std::vector<float> f = getFloatArray(p);
  Matrix m = Matrix::identity();
  for (int r = 0; r < q.decl.desc.rows; ++r)
    for (int c = 0; c < q.decl.desc.columns; ++c) m.m[r][c] = f[size_t(r * q.decl.desc.columns + c)];
  return m;
}
std::string Effect::getString(Handle p) const {
  const Param& q = impl_->param(p);
  if (q.decl.desc.type != ParameterType::String) fail("effect parameter '{}' is not a string", q.decl.desc.name);
  return q.store->text;
}
TexturePtr Effect::getTexture(Handle p) const {
  const Param& q = impl_->param(p);
  if (!q.decl.desc.isTexture()) fail("effect parameter '{}' is not a texture", q.decl.desc.name);
  return q.store->texture;
}

// ---------------------------------------------------------------- techniques
int Effect::techniqueCount() const { return int(impl_->techniques.size()); }

const TechniqueDesc& Effect::techniqueDesc(Handle t) const {
  if (t < 0 || t >= techniqueCount()) fail("effect technique handle {} is out of range", t);
  return impl_->techniques[size_t(t)].desc;
}

Handle Effect::techniqueByName(std::string_view name) const {
  for (size_t i = 0; i < impl_->techniques.size(); ++i)
    if (impl_->techniques[i].desc.name == name) return Handle(i);
  return -1;
}

TechniqueValidation Effect::validateTechnique(Handle t, const CapsProfile& caps) const {
  const Technique& tech = impl_->techniques.at(size_t(t));
  if (!tech.desc.brokenReason.empty()) return {false, tech.desc.brokenReason};
  if (tech.passes.empty()) return {false, "the technique has no pass"};
  DeviceOptions opts;
  opts.threads = 1;
  Device scratch(caps, opts);
  for (size_t i = 0; i < tech.passes.size(); ++i) {
    const Pass& pass = tech.passes[i];
    const std::string passName = pass.desc.name.empty() ? fmt::format("#{}", i) : pass.desc.name;
    try {
      impl_->applyPass(scratch, pass);
    } catch (const Error& e) {
      return {false, fmt::format("pass {}: {}", passName, Impl::diagnosticFrom(e).message)};
    }
    const ValidationResult r = scratch.validate();
    if (!r.ok) return {false, fmt::format("pass {}: {}", passName, r.reason)};
  }
  return {};
}

Handle Effect::findNextValidTechnique(Handle after, const CapsProfile& caps) const {
  for (Handle t = after + 1; t < techniqueCount(); ++t)
    if (validateTechnique(t, caps).ok) return t;
  return -1;
}

TechniqueSelection Effect::selectTechnique(const CapsProfile& caps, const SelectionPolicy& policy) const {
  std::vector<Handle> order;
  for (const std::string& name : policy.preferred) {
    const Handle t = techniqueByName(name);
    if (t < 0) fail("{}: no technique named '{}' to prefer", impl_->fileName, name);
    if (std::find(order.begin(), order.end(), t) == order.end()) order.push_back(t);
  }
  for (Handle t = 0; t < techniqueCount(); ++t)
    if (std::find(order.begin(), order.end(), t) == order.end()) order.push_back(t);
  TechniqueSelection sel;
  for (Handle t : order) {
    const TechniqueDesc& d = techniqueDesc(t);
    auto number = [&](std::string_view key) -> std::optional<double> {
      const Annotation* a = annotationByName(d.annotations, key);
      if (!a || a->numbers.empty()) return std::nullopt;
      return a->numbers[0];
    };
    if (policy.maxCost) {
      if (auto cost = number("Cost"); cost && *cost > *policy.maxCost) {
        sel.rejected.push_back(fmt::format("{}: Cost {} is above {}", d.name, *cost, *policy.maxCost));
        continue;
      }
    }
    if (policy.distance) {
      const double dist = *policy.distance;
      const auto lo = number("MinDistance"), hi = number("MaxDistance");
      if ((lo && dist < *lo) || (hi && dist >= *hi)) {
        sel.rejected.push_back(fmt::format("{}: camera distance {} is outside [{}, {})", d.name, dist,
                                           lo ? fmt::format("{}", *lo) : "0", hi ? fmt::format("{}", *hi) : "inf"));
        continue;
      }
    }
    const TechniqueValidation v = validateTechnique(t, caps);
    if (!v.ok) {
      sel.rejected.push_back(fmt::format("{}: {}", d.name, v.reason));
      continue;
    }
    sel.technique = t;
    return sel;
  }
  return sel;
}

void Effect::setTechnique(Handle t) {
  if (t < 0 || t >= techniqueCount()) fail("effect technique handle {} is out of range", t);
  impl_->current = t;
}

Handle Effect::currentTechnique() const { return impl_->current; }

// ---------------------------------------------------------------- rendering
int Effect::begin(Device& device, uint32_t flags) {
  Impl& m = *impl_;
  if (m.device) fail("Effect::begin called twice without end");
  if (m.current < 0) {
    if (techniqueCount() == 0) fail("{}: the effect has no technique", m.fileName);
    m.current = 0;
  }
  const Technique& tech = m.techniques[size_t(m.current)];
  if (!tech.desc.brokenReason.empty())
    fail("technique '{}' cannot be used: {}", tech.desc.name, tech.desc.brokenReason);
  m.device = &device;
  m.beginFlags = flags;
  if (!(flags & kDoNotSaveState)) m.saved = device.createStateBlock();
  return int(tech.passes.size());
}

void Effect::beginPass(int pass) {
  Impl& m = *impl_;
  if (!m.device) fail("Effect::beginPass outside begin/end");
  if (m.activePass >= 0) fail("Effect::beginPass: pass {} is still active (call endPass)", m.activePass);
  const Technique& tech = m.techniques[size_t(m.current)];
  if (pass < 0 || size_t(pass) >= tech.passes.size())
    fail("technique '{}' has {} passes; pass {} does not exist", tech.desc.name, tech.passes.size(), pass);
  m.activePass = pass;
  m.applyPass(*m.device, tech.passes[size_t(pass)]);
}

void Effect::commitChanges() {
  Impl& m = *impl_;
  if (m.activePass < 0) fail("Effect::commitChanges outside a pass");
  m.applyPass(*m.device, m.techniques[size_t(m.current)].passes[size_t(m.activePass)]);
}

void Effect::endPass() {
  if (impl_->activePass < 0) fail("Effect::endPass without beginPass");
  impl_->activePass = -1;
}

void Effect::end() {
  Impl& m = *impl_;
  if (!m.device) fail("Effect::end without begin");
  if (m.saved) {
    DeviceState restored = m.saved->state();
    const DeviceState& now = m.device->state();
    if (m.beginFlags & kDoNotSaveShaderState) {
      restored.vertexShader = now.vertexShader;
      restored.pixelShader = now.pixelShader;
      restored.vsConstF = now.vsConstF;
      restored.psConstF = now.psConstF;
      restored.vsConstI = now.vsConstI;
      restored.psConstI = now.psConstI;
      restored.vsConstB = now.vsConstB;
      restored.psConstB = now.psConstB;
    }
    if (m.beginFlags & kDoNotSaveSamplerState) restored.samplerStates = now.samplerStates;
    // Vertex and index buffers and the viewport are the application's, not the passes'.
    restored.streams = now.streams;
    restored.indices = now.indices;
    restored.viewport = now.viewport;
    restored.scissor = now.scissor;
    m.device->applyStateBlock(StateBlock(std::move(restored)));
  }
  m.saved.reset();
  m.device = nullptr;
  m.activePass = -1;
}


// ---------------------------------------------------------------- internals for the layer's writers
namespace detail {

namespace {

// An expression of parameters as FXLC code (fx2-binary.md §5), mirroring Impl::eval:
// every value is a list of scalar operands (an input component, a literal, a
// temporary), and each operation is one single-component instruction per result
// component. Parameters take input registers as the preshader's CTAB lays them out
// (one register per row of each element, class MATRIX_ROWS for matrices), which is
// how Impl::preshaderInputs fills them back.
template <class EffectImpl>
struct FxlcCompiler {
  explicit FxlcCompiler(const EffectImpl& impl) : m(impl) {}
  const EffectImpl& m;
  FxlcProgram prog;
  uint32_t temps = 0;
  int nextRegister = 0;
  std::map<std::string, int> firstRegister;

  struct V {
    std::vector<FxlcOperand> c;
    ParameterClass cls = ParameterClass::Vector;
    int rows = 1, columns = 0;
  };

  [[noreturn]] static void unsupported(const Expr& e, const std::string& what) {
    failAt(e.where, "{} cannot be written as an fx_2_0 expression (FXLC)", what);
  }

  FxlcOperand literal(double x) {
    for (size_t i = 0; i < prog.literals.size(); ++i)
      if (std::bit_cast<uint64_t>(prog.literals[i]) == std::bit_cast<uint64_t>(x)) return {FxlcTable::Literal, uint32_t(i)};
    prog.literals.push_back(x);
    return {FxlcTable::Literal, uint32_t(prog.literals.size() - 1)};
  }

  FxlcOperand op(uint32_t opcode, std::vector<FxlcOperand> in) {
    FxlcInstruction i;
    i.opcode = opcode;
    i.inputs = std::move(in);
    i.output = {FxlcTable::Temp, temps++};
    prog.code.push_back(i);
    return i.output;
  }

  V param(const Expr& e, const Param& p, int element) {
    const ParameterDesc& d = p.decl.desc;
    if (!d.isNumeric()) unsupported(e, fmt::format("'{}' ({})", d.name, parameterTypeName(d.type)));
    const bool matrix = d.cls == ParameterClass::MatrixRows || d.cls == ParameterClass::MatrixColumns;
    const int perElement = matrix ? d.rows : 1;
    auto it = firstRegister.find(d.name);
    if (it == firstRegister.end()) {
      shader::ShaderConstant c;
      c.name = d.name;
      c.registerSet = shader::RegisterSet::Float4;
      c.registerIndex = nextRegister;
      c.registerCount = std::max(1, d.elements) * perElement;
      c.cls = matrix ? shader::ConstantClass::MatrixRows : shader::ConstantClass(d.cls);
      c.type = int(d.type);
      c.rows = d.rows;
      c.columns = d.columns;
      c.elements = std::max(1, d.elements);
      prog.inputs.constants.push_back(c);
      it = firstRegister.emplace(d.name, nextRegister).first;
      nextRegister += c.registerCount;
    }
    V v;
    const int first = element < 0 ? 0 : element, last = element < 0 ? std::max(1, d.elements) : element + 1;
    for (int el = first; el < last; ++el)
      for (int r = 0; r < d.rows; ++r)
        for (int c = 0; c < d.columns; ++c)
          v.c.push_back({FxlcTable::Input, uint32_t((it->second + el * perElement + (matrix ? r : 0)) * 4 + c)});
    v.cls = d.cls == ParameterClass::Scalar ? ParameterClass::Vector : d.cls;
    v.rows = d.rows;
    v.columns = d.columns;
    return v;
  }

  static bool readsParameter(const EffectImpl& m, const Expr& e) {
    if (e.kind == Expr::Kind::ParamRef) return true;
    if (e.kind == Expr::Kind::Name && m.findParam(e.text)) return true;
    for (const Expr& a : e.args)
      if (readsParameter(m, a)) return true;
    return false;
  }

  FxlcOperand notZero(FxlcOperand x) {  // x != 0 → 1, else 0
    const FxlcOperand zero = literal(0);
    return op(fxlc_op::Add, {op(fxlc_op::Lt, {x, zero}), op(fxlc_op::Lt, {zero, x})});
  }

  V compile(const Expr& e) {
    switch (e.kind) {
      case Expr::Kind::Number:
      case Expr::Kind::Bool: return V{{literal(e.number)}};
      case Expr::Kind::Name: {
        if (const Param* p = m.findParam(e.text)) return param(e, *p, -1);
        failCode("F1200", e.where, "unknown parameter '{}'", e.text);
      }
      case Expr::Kind::ParamRef: return compile(e.args[0]);
      case Expr::Kind::List:
      case Expr::Kind::Call: {
        V v;
        for (const Expr& a : e.args) {
          V x = compile(a);
          v.c.insert(v.c.end(), x.c.begin(), x.c.end());
        }
        if (e.kind == Expr::Kind::Call) {
          ParameterDesc shape;
          if (!m.constructorShape(e.text, shape)) unsupported(e, "'" + e.text + "(…)'");
          const size_t want = size_t(shape.rows * shape.columns);
          if (v.c.size() == 1 && want > 1) v.c.assign(want, v.c[0]);
          if (v.c.size() != want) failCode("F1205", e.where, "{}(…) takes {} values, {} given", e.text, want, v.c.size());
          v.cls = shape.cls == ParameterClass::Scalar ? ParameterClass::Vector : shape.cls;
          v.rows = shape.rows;
          v.columns = shape.columns;
        }
        return v;
      }
      case Expr::Kind::Unary: {
        V v = compile(e.args[0]);
        for (FxlcOperand& x : v.c) {
          if (e.text == "-") x = op(fxlc_op::Neg, {x});
          else if (e.text == "!") x = op(fxlc_op::Add, {literal(1), op(fxlc_op::Neg, {notZero(x)})});
          else unsupported(e, "'" + e.text + "'");
        }
        return v;
      }
      case Expr::Kind::Binary: {
        V a = compile(e.args[0]);
        V b = compile(e.args[1]);
        if (a.c.size() != b.c.size() && a.c.size() != 1 && b.c.size() != 1)
          failCode("F1205", e.where, "'{}' between values of {} and {} components", e.text, a.c.size(), b.c.size());
        V r = a.c.size() >= b.c.size() ? a : b;
        const std::string& o = e.text;
        for (size_t i = 0; i < r.c.size(); ++i) {
          const FxlcOperand x = a.c[a.c.size() == 1 ? 0 : i];
          const FxlcOperand y = b.c[b.c.size() == 1 ? 0 : i];
          FxlcOperand z;
          if (o == "+") z = op(fxlc_op::Add, {x, y});
          else if (o == "-") z = op(fxlc_op::Add, {x, op(fxlc_op::Neg, {y})});
          else if (o == "*") z = op(fxlc_op::Mul, {x, y});
          else if (o == "/") z = op(fxlc_op::Mul, {x, op(fxlc_op::Rcp, {y})});  // fxc never writes div
          else if (o == "<") z = op(fxlc_op::Lt, {x, y});
          else if (o == ">") z = op(fxlc_op::Lt, {y, x});
          else if (o == "<=") z = op(fxlc_op::Ge, {y, x});
          else if (o == ">=") z = op(fxlc_op::Ge, {x, y});
          else if (o == "==") z = op(fxlc_op::Mul, {op(fxlc_op::Ge, {x, y}), op(fxlc_op::Ge, {y, x})});
          else if (o == "!=") z = op(fxlc_op::Add, {op(fxlc_op::Lt, {x, y}), op(fxlc_op::Lt, {y, x})});
          else if (o == "&&") z = op(fxlc_op::Mul, {notZero(x), notZero(y)});
          else if (o == "||") z = notZero(op(fxlc_op::Add, {notZero(x), notZero(y)}));
          else unsupported(e, "the operator '" + o + "'");
          r.c[i] = z;
        }
        return r;
      }
      case Expr::Kind::Index: {
        const Expr& base = e.args[0];
        if (readsParameter(m, e.args[1])) unsupported(e.args[1], "an index that reads parameters");
        const Value idx = m.numeric(e.args[1]);
        if (idx.numbers.size() != 1) failCode("F1205", e.args[1].where, "an index must be a scalar");
        const int i = toInt(idx.numbers[0]);
        if (base.kind == Expr::Kind::Name) {
          if (const Param* p = m.findParam(base.text); p && p->decl.desc.elements > 0) {
            checkElementIndex(e, base, i, p->decl.desc.elements);
            return param(base, *p, i);
          }
        }
        V v = compile(base);
        const auto [first, per] = indexedRow(e, i, v.rows, v.columns, v.c.size());
        V r;
        r.c.assign(v.c.begin() + std::ptrdiff_t(first), v.c.begin() + std::ptrdiff_t(first + per));
        r.columns = int(per);
        return r;
      }
      case Expr::Kind::Member: {
        V v = compile(e.args[0]);
        V r;
        for (size_t k : swizzleComponents(e, v.c.size())) r.c.push_back(v.c[k]);
        r.columns = int(r.c.size());
        return r;
      }
      default: unsupported(e, "this value");
    }
  }

  // The state's value as output components oc0.x, oc0.y, … in the order the state
  // reads them: float shader constants as the registers Impl::registers fills.
  void finish(const V& v, const StateInfo& info) {
    std::vector<FxlcOperand> out;
    if (info.target == StateTarget::VertexConstF || info.target == StateTarget::PixelConstF) {
      Value shape;
      shape.cls = v.cls;
      shape.rows = v.rows;
      shape.columns = v.columns;
      for (size_t i = 0; i < v.c.size(); ++i) shape.numbers.push_back(double(i + 1));
      std::vector<Vec4> regs = EffectImpl::registers(shape);
      if (info.code && regs.size() > info.code) regs.resize(info.code);
      for (const Vec4& r : regs)
        for (float x : {r.x, r.y, r.z, r.w}) out.push_back(x > 0 ? v.c[size_t(x) - 1] : literal(0));
    } else {
      out = v.c;
      if (info.target == StateTarget::VertexConstI || info.target == StateTarget::PixelConstI)
        while (out.size() % 4) out.push_back(literal(0));
    }
    for (size_t k = 0; k < out.size(); ++k) {
      FxlcInstruction i;
      i.opcode = fxlc_op::Mov;
      i.inputs = {out[k]};
      i.output = {FxlcTable::Output, uint32_t(k)};
      prog.code.push_back(i);
    }
  }
};

// A template over the effect's private Impl (only EffectAccess may name it).
template <class EffectImpl>
struct ContentsBuilder {
  const EffectImpl& m;
  std::map<const CompiledShader*, ShaderContentsRef> shaders;

  bool readsParameter(const Expr& e) const {
    if (e.kind == Expr::Kind::ParamRef) return true;
    if (e.kind == Expr::Kind::Name && m.findParam(e.text)) return true;
    for (const Expr& a : e.args)
      if (readsParameter(a)) return true;
    return false;
  }

  // "name" or "name[i]" when `e` is a parameter or a constant element of one.
  std::optional<std::string> parameterName(const Expr& e, int& values) const {
    if (e.kind == Expr::Kind::ParamRef) return parameterName(e.args[0], values);
    if (e.kind == Expr::Kind::Name) {
      const Param* p = m.findParam(e.text);
      if (!p) return std::nullopt;
      values = scalarCount(p->decl.desc);
      return e.text;
    }
    if (e.kind == Expr::Kind::Index && e.args[0].kind == Expr::Kind::Name && !readsParameter(e.args[1])) {
      const Param* p = m.findParam(e.args[0].text);
      if (!p || p->decl.desc.elements == 0) return std::nullopt;
      const Value i = m.numeric(e.args[1]);
      if (i.numbers.size() != 1) return std::nullopt;
      values = p->decl.desc.rows * p->decl.desc.columns;
      return fmt::format("{}[{}]", e.args[0].text, toInt(i.numbers[0]));
    }
    return std::nullopt;
  }

  ShaderContentsRef shader(const ShaderRef& sh) {
    if (!sh) return nullptr;
    if (auto it = shaders.find(sh.get()); it != shaders.end()) return it->second;
    auto c = std::make_shared<ShaderContents>();
    c->vertex = sh->vertex;
    c->tokens = sh->tokens;
    c->compiled = !sh->profile.empty();
    c->preshader = sh->preshader;
    c->profile = sh->profile;
    c->entry = sh->entry;
    c->entryArguments = sh->entryArguments;
    shaders.emplace(sh.get(), c);
    return c;
  }

  StateContents state(const BoundState& s) {
    StateContents c;
    c.name = s.name;
    c.info = s.info;
    c.index = s.index;
    c.where = s.where;
    using K = StateContents::Kind;
    switch (s.info.target) {
      case StateTarget::VertexShader:
      case StateTarget::PixelShader:
        if (s.shaderFromValue) {
          if (m.eval(s.value).isNull) {
            c.kind = K::Null;
          } else if (auto n = parameterName(s.value, c.referencedValues)) {
            c.kind = K::Parameter;
            c.parameter = *n;
          } else {
            c.kind = K::Expression;
            c.expression = &s.value;
          }
        } else if (s.shader) {
          c.kind = K::Shader;
          c.shader = shader(s.shader);
        } else {
          c.kind = K::Null;
        }
        return c;
      case StateTarget::Texture:
      case StateTarget::Sampler:
        if (s.samplerBlock) {
          c.kind = K::SamplerBlock;
          for (const BoundState& st : s.samplerStates) c.samplerStates.push_back(state(st));
        } else if (m.eval(s.value).isNull) {
          c.kind = K::Null;
        } else if (auto n = parameterName(s.value, c.referencedValues)) {
          c.kind = K::Parameter;
          c.parameter = *n;
        } else {
          c.kind = K::Expression;
          c.expression = &s.value;
        }
        return c;
      default: break;
    }
    if (readsParameter(s.value)) {
      if (auto n = parameterName(s.value, c.referencedValues)) {
        c.kind = K::Parameter;
        c.parameter = *n;
      } else {
        c.kind = K::Expression;
        c.expression = &s.value;
        try {
          FxlcCompiler<EffectImpl> fx{m};
          fx.finish(fx.compile(s.value), s.info);
          c.fxlcComponents = int(fx.prog.code.size() - size_t(fx.temps));
          c.fxlc = std::make_shared<const FxlcProgram>(std::move(fx.prog));
        } catch (const Error& e) {
          c.fxlcError = e.what();
        }
      }
      return c;
    }
    c.kind = K::Constant;
    switch (s.info.target) {
      case StateTarget::Transform:
      case StateTarget::Material:
      case StateTarget::NPatchMode: c.numbers = m.numeric(s.value).numbers; break;
      case StateTarget::Light:
        if (LightMember(s.info.code) == LightMember::Type) c.dword = m.stateDword(s);
        else c.numbers = m.numeric(s.value).numbers;
        break;
      case StateTarget::VertexConstF:
      case StateTarget::PixelConstF: {
        std::vector<Vec4> regs = m.registers(m.numeric(s.value));
        if (s.info.code && regs.size() > s.info.code) regs.resize(s.info.code);
        for (const Vec4& r : regs)
          for (float x : {r.x, r.y, r.z, r.w}) c.registers.push_back(x);
        break;
      }
      case StateTarget::VertexConstI:
      case StateTarget::PixelConstI:
        for (double x : m.numeric(s.value).numbers) c.registers.push_back(toInt(x));
        while (c.registers.size() % 4) c.registers.push_back(0);
        break;
      case StateTarget::VertexConstB:
      case StateTarget::PixelConstB:
        for (double x : m.numeric(s.value).numbers) c.registers.push_back(x != 0 ? 1 : 0);
        break;
      default: c.dword = m.stateDword(s); break;
    }
    return c;
  }
};

}  // namespace

EffectContents EffectAccess::contents(const Effect& effect) {
  const auto& m = *effect.impl_;
  ContentsBuilder<std::decay_t<decltype(m)>> b{m, {}};
  EffectContents out;
  out.fileName = m.fileName;
  for (const Param& p : m.params) {
    ParameterContents pc;
    pc.desc = p.decl.desc;
    pc.annotations = p.decl.annotations;
    pc.raw = p.store->raw;
    pc.text = p.store->text;
    pc.shader = b.shader(p.shader);
    pc.hasSamplerState = p.decl.samplerInit.has_value();
    for (const BoundState& s : p.samplerStates) pc.samplerStates.push_back(b.state(s));
    out.parameters.push_back(std::move(pc));
  }
  for (const Technique& t : m.techniques) {
    TechniqueContents tc;
    tc.desc = t.desc;
    for (const Pass& pass : t.passes) {
      PassContents pc;
      pc.desc = pass.desc;
      for (const BoundState& s : pass.states) pc.states.push_back(b.state(s));
      tc.passes.push_back(std::move(pc));
    }
    out.techniques.push_back(std::move(tc));
  }
  return out;
}

}  // namespace detail

}  // namespace refx::effect
