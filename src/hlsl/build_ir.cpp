// Syntax tree → IR for one entry point. This is where HLSL's meaning lives: name
// lookup, types and implicit conversions, overloads, intrinsics, inlining of user
// functions, unrolling of loops and flattening of branches.
//
// Values are tracked per component: a variable is a list of components, each a
// literal or one component of a virtual register. So copies, swizzles, struct
// members and constant expressions cost nothing, and constants fold as they are
// built. Code under a condition known only at run time is executed under an
// "active" mask; assignments there become selects.
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <tuple>

#include "hlsl/ir.h"
#include "refx/shader/version_rules.h"

namespace refx::hlsl::detail {

namespace {

using shader::DeclUsage;

struct Comp {
  int reg = -1;  // -1: literal `k`
  uint8_t c = 0;
  float k = 0;
  bool sampler = false;  // a sampler value: `k` is the sampler index
  bool literal() const { return reg < 0; }
  bool operator==(const Comp& o) const {
    return reg == o.reg && (reg < 0 ? (std::memcmp(&k, &o.k, 4) == 0 && sampler == o.sampler) : c == o.c);
  }
};
using Comps = std::vector<Comp>;

Comp lit(float v) { Comp c; c.k = v; return c; }

struct Value {
  Type type;
  Comps comps;
  bool ok = true;
};

Value errorValue() { Value v; v.ok = false; v.type = Type::scalar(BaseType::Float); v.comps = {lit(0)}; return v; }

struct Variable {
  Type type;
  Comps comps;
  bool isConst = false;
  bool uniform = false;  // global uniform: comps bound lazily
  int uniformIndex = -1;
  bool bound = false;
  const VarDecl* decl = nullptr;
};

// One flat component position inside a variable.
struct LValue {
  Variable* var = nullptr;
  std::vector<int> indices;
  Type type;
};

struct SwizzleParse {
  std::vector<int> indices;  // flat component indices in the base value
  bool valid = false;
};

bool isIntegral(BaseType b) { return b == BaseType::Int || b == BaseType::Uint || b == BaseType::Bool; }

int baseRank(BaseType b) {
  switch (b) {
    case BaseType::Bool: return 0;
    case BaseType::Int: return 1;
    case BaseType::Uint: return 2;
    case BaseType::Half: return 3;
    case BaseType::Float: return 4;
    case BaseType::Double: return 5;
    default: return 4;
  }
}

struct Semantic {
  DeclUsage usage = DeclUsage::TexCoord;
  int index = 0;
  bool valid = false;
  bool vpos = false, vface = false;
};

Semantic parseSemantic(const std::string& raw) {
  std::string s;
  for (char ch : raw) s += char(std::toupper((unsigned char)ch));
  size_t digits = s.size();
  while (digits > 0 && std::isdigit((unsigned char)s[digits - 1])) --digits;
  std::string name = s.substr(0, digits);
  int index = digits < s.size() ? std::atoi(s.c_str() + digits) : 0;
  Semantic r;
  r.index = index;
  r.valid = true;
  static const std::map<std::string, DeclUsage> table = {
      {"POSITION", DeclUsage::Position}, {"SV_POSITION", DeclUsage::Position},
      {"BLENDWEIGHT", DeclUsage::BlendWeight}, {"BLENDINDICES", DeclUsage::BlendIndices},
      {"NORMAL", DeclUsage::Normal}, {"PSIZE", DeclUsage::PSize}, {"TEXCOORD", DeclUsage::TexCoord},
      {"TANGENT", DeclUsage::Tangent}, {"BINORMAL", DeclUsage::Binormal}, {"TESSFACTOR", DeclUsage::TessFactor},
      {"POSITIONT", DeclUsage::PositionT}, {"COLOR", DeclUsage::Color}, {"SV_TARGET", DeclUsage::Color},
      {"FOG", DeclUsage::Fog}, {"DEPTH", DeclUsage::Depth}, {"SV_DEPTH", DeclUsage::Depth},
      {"SAMPLE", DeclUsage::Sample}};
  if (name == "VPOS") { r.vpos = true; r.usage = DeclUsage::Position; return r; }
  if (name == "VFACE") { r.vface = true; return r; }
  auto it = table.find(name);
  if (it == table.end()) { r.valid = false; return r; }
  r.usage = it->second;
  return r;
}

float truncF(float x) { return std::trunc(x); }

class Builder {
 public:
  Builder(const Program& prog, const BuildOptions& opt, DiagnosticSink& sink)
      : prog_(prog), opt_(opt), sink_(&sink), rules_(shader::findVersionRules(opt.version)) {
    ir_.version = opt.version;
  }

  IrProgram run() {
    // Globals.
    scopes_.emplace_back();
    for (const auto& g : prog_.globals) declareGlobal(*g);
    // Entry point.
    const FunctionDecl* entry = nullptr;
    for (const auto& f : prog_.functions)
      if (f->name == opt_.entry && f->body) { entry = f.get(); break; }
    if (!entry) {
      sink_->error({opt_.fileName, 0, 0}, "X3501",
                  "'{}': entrypoint not found", opt_.entry);
      return std::move(ir_);
    }
    entryWhere_ = entry->where;
    runEntry(*entry);
    return std::move(ir_);
  }

  SourceLocation entryWhere_;

 private:
  bool isPixel() const { return opt_.version.isPixel(); }

  // ---- IR emission -----------------------------------------------------------------------------
  int emitInst(IrInst inst) {
    inst.dst = ir_.newReg(inst.width);
    ir_.code.push_back(std::move(inst));
    return ir_.code.back().dst;
  }

  int constantReg(const std::vector<float>& v) {
    auto key = v;
    auto it = constants_.find(key);
    if (it != constants_.end()) return it->second;
    IrInst inst;
    inst.op = IrOp::Constant;
    inst.width = int(v.size());
    for (size_t i = 0; i < v.size(); ++i) inst.literal[i] = v[i];
    int r = emitInst(std::move(inst));
    constants_[key] = r;
    return r;
  }

  IrSrc source(const Comps& comps) {
    IrSrc s;
    bool allLit = true, sameReg = true;
    for (const Comp& c : comps) {
      if (!c.literal()) allLit = false;
      if (c.literal() || c.reg != comps[0].reg) sameReg = false;
    }
    if (allLit) {
      std::vector<float> v;
      for (const Comp& c : comps) v.push_back(c.k);
      s.reg = constantReg(v);
      return s;
    }
    if (sameReg) {
      s.reg = comps[0].reg;
      for (size_t i = 0; i < comps.size(); ++i) s.swizzle[i] = comps[i].c;
      for (size_t i = comps.size(); i < 4; ++i) s.swizzle[i] = comps.back().c;
      return s;
    }
    // The same gather is one register (values are immutable).
    std::vector<std::tuple<int, int, float>> key;
    for (const Comp& c : comps) key.emplace_back(c.reg, c.c, c.reg < 0 ? c.k : 0.0f);
    if (auto it = combines_.find(key); it != combines_.end()) {
      s.reg = it->second;
      return s;
    }
    IrInst inst;
    inst.op = IrOp::Combine;
    inst.width = int(comps.size());
    for (const Comp& c : comps) {
      IrPart p;
      p.reg = c.reg;
      p.component = c.c;
      p.literal = c.k;
      inst.parts.push_back(p);
    }
    s.reg = emitInst(std::move(inst));
    combines_[key] = s.reg;
    return s;
  }

  static Comps regComps(int reg, int width) {
    Comps out(width);
    for (int i = 0; i < width; ++i) { out[i].reg = reg; out[i].c = uint8_t(i); }
    return out;
  }

  static bool allLiteral(const Comps& c) {
    for (const Comp& x : c)
      if (!x.literal()) return false;
    return true;
  }
  static bool allEqual(const Comps& c, float v) {
    for (const Comp& x : c)
      if (!x.literal() || x.k != v) return false;
    return true;
  }

  static float foldScalar(IrOp op, float a, float b, float c) { return evaluateComponent(op, a, b, c); }

  // Emits a component-wise op of `width` components; args are already `width` wide.
  Comps op(IrOp o, int width, std::initializer_list<Comps> args, bool saturate = false) {
    return op(o, width, std::vector<Comps>(args), saturate);
  }
  Comps op(IrOp o, int width, const std::vector<Comps>& a, bool saturate) {
    if (width > 4) {  // a matrix: one register's worth at a time
      Comps out;
      for (int at = 0; at < width; at += 4) {
        const int n = std::min(4, width - at);
        std::vector<Comps> part;
        for (const Comps& x : a) part.emplace_back(x.begin() + at, x.begin() + at + n);
        Comps r = op(o, n, part, saturate);
        out.insert(out.end(), r.begin(), r.end());
      }
      return out;
    }
    bool foldable = o != IrOp::Dsx && o != IrOp::Dsy && o != IrOp::Kill && o != IrOp::SinCos && o < IrOp::Tex;
    bool literal = foldable;
    for (const Comps& x : a)
      if (!allLiteral(x)) literal = false;
    if (literal) {
      Comps out(width);
      // Literal operands, absent ones zero.
      std::array<const Comps*, 3> operand{};
      for (size_t k = 0; k < a.size() && k < 3; ++k) operand[k] = &a[k];
      auto at = [&](size_t k, int i) { return operand[k] ? (*operand[k])[size_t(i)].k : 0.0f; };
      for (int i = 0; i < width; ++i) {
        float v = foldScalar(o, at(0, i), at(1, i), at(2, i));
        if (saturate) v = std::fmin(std::fmax(v, 0.0f), 1.0f);
        out[i] = lit(v);
      }
      return out;
    }
    if (!saturate) {  // algebraic identities fxc applies too
      if (o == IrOp::Mul) {
        if (allEqual(a[1], 1)) return a[0];
        if (allEqual(a[0], 1)) return a[1];
        if (allEqual(a[0], 0) || allEqual(a[1], 0)) return Comps(width, lit(0));
      }
      if (o == IrOp::Add) {
        if (allEqual(a[1], 0)) return a[0];
        if (allEqual(a[0], 0)) return a[1];
      }
      if (o == IrOp::Mov) return a[0];
    }
    if (o == IrOp::Rcp && width == 1 && !saturate && !a[0][0].literal()) {
      // rcp(rcp(x)) = x (sqrt then divide: rsq, rcp, rcp)
      auto it = rcpOf_.find({a[0][0].reg, a[0][0].c});
      if (it != rcpOf_.end()) return Comps{it->second};
    }
    IrInst inst;
    inst.op = o;
    inst.width = width;
    inst.saturate = saturate;
    inst.srcCount = int(a.size());
    for (size_t i = 0; i < a.size(); ++i) inst.src[i] = source(a[i]);
    inst.where = where_;
    // Common subexpressions: the same operation on the same sources is one register.
    std::vector<int> key{int(o), width, int(saturate)};
    for (int i = 0; i < inst.srcCount; ++i) {
      const IrSrc& s = inst.src[i];
      key.insert(key.end(), {s.reg, s.swizzle[0], s.swizzle[1], s.swizzle[2], s.swizzle[3], int(s.negate), int(s.absolute)});
    }
    if (auto it = cse_.find(key); it != cse_.end()) return regComps(it->second, width);
    int reg = emitInst(std::move(inst));
    cse_[key] = reg;
    if (o == IrOp::Rcp && width == 1) {
      Comp r;
      r.reg = reg;
      rcpOf_[{reg, 0}] = a[0][0];
    }
    return regComps(reg, width);
  }

  // Scalar-result ops (dp*) producing one component.
  Comps dot(const Comps& a, const Comps& b) {
    size_t n = a.size();
    if (allLiteral(a) && allLiteral(b)) {
      float s = 0;
      for (size_t i = 0; i < n; ++i) s += a[i].k * b[i].k;
      return {lit(s)};
    }
    if (n == 1) return op(IrOp::Mul, 1, {a, b});
    IrInst inst;
    inst.op = n == 2 ? IrOp::Dp2 : n == 3 ? IrOp::Dp3 : IrOp::Dp4;
    inst.width = 1;
    inst.srcCount = 2;
    inst.src[0] = source(a);
    inst.src[1] = source(b);
    inst.where = where_;
    return regComps(emitInst(std::move(inst)), 1);
  }

  Comps negate(const Comps& a) {
    if (allLiteral(a)) {
      Comps o = a;
      for (Comp& c : o) c.k = -c.k;
      return o;
    }
    if (a.size() > 4) {  // a matrix: one register's worth at a time
      Comps out;
      for (size_t at = 0; at < a.size(); at += 4) {
        Comps r = negate(Comps(a.begin() + long(at), a.begin() + long(std::min(a.size(), at + 4))));
        out.insert(out.end(), r.begin(), r.end());
      }
      return out;
    }
    IrInst inst;
    inst.op = IrOp::Mov;
    inst.width = int(a.size());
    inst.srcCount = 1;
    inst.src[0] = source(a);
    inst.src[0].negate = true;
    inst.where = where_;
    return regComps(emitInst(std::move(inst)), int(a.size()));
  }

  // Per-component op on a possibly multi-component value with a scalar-only IR op.
  Comps scalarOp(IrOp o, const Comps& a, const Comps* b = nullptr) {
    Comps out;
    for (size_t i = 0; i < a.size(); ++i) {
      Comps r = b ? op(o, 1, {Comps{a[i]}, Comps{(*b)[i]}}) : op(o, 1, {Comps{a[i]}});
      out.push_back(r[0]);
    }
    return out;
  }

  // ---- types and conversions -------------------------------------------------------------------
  void warnTruncation(const SourceLocation& at) {
    if (!truncationWarned_.insert({at.file, at.line, at.column}).second) return;
    sink_->warning(at, "X3206", "implicit truncation of vector type");
  }

  // Converts `v` to numeric type `to` (HLSL implicit rules; casts allow more).
  Value convert(const Value& v, const Type& to, const SourceLocation& at, bool explicitCast = false) {
    if (!v.ok) { Value e = errorValue(); e.type = to; e.comps.assign(std::max(1, to.flatSize()), lit(0)); return e; }
    Value out;
    out.type = to;
    if (to.cls == TypeClass::Struct || to.isArray() || v.type.cls == TypeClass::Struct || v.type.isArray()) {
      if (v.type.isScalar() && explicitCast) {  // (VS_OUTPUT)0: every component
        out.comps.assign(to.flatSize(), v.comps[0]);
        return out;
      }
      if (v.type.flatSize() == to.flatSize() && v.type.name() == to.name()) return Value{to, v.comps, true};
      if (v.type.flatSize() == to.flatSize() && explicitCast) return Value{to, v.comps, true};
      sink_->error(at, "X3017", "cannot convert from '{}' to '{}'", v.type.name(), to.name());
      Value e = errorValue(); e.type = to; e.comps.assign(std::max(1, to.flatSize()), lit(0));
      return e;
    }
    if (to.cls == TypeClass::Object || v.type.cls == TypeClass::Object) {
      if (to.cls == TypeClass::Object && v.type.cls == TypeClass::Object && to.base == v.type.base) return Value{to, v.comps, true};
      sink_->error(at, "X3017", "cannot convert from '{}' to '{}'", v.type.name(), to.name());
      return Value{to, {lit(0)}, false};
    }
    Comps src = v.comps;
    int n = to.components();
    if (v.type.isScalar()) {
      src.assign(n, v.comps[0]);
    } else if (to.cls == TypeClass::Matrix && v.type.cls == TypeClass::Matrix) {
      if (to.rows > v.type.rows || to.cols > v.type.cols) {
        sink_->error(at, "X3017", "cannot convert from '{}' to '{}'", v.type.name(), to.name());
        return Value{to, Comps(n, lit(0)), false};
      }
      if (!explicitCast && (to.rows < v.type.rows || to.cols < v.type.cols)) warnTruncation(at);
      src.clear();
      for (int r = 0; r < to.rows; ++r)
        for (int c = 0; c < to.cols; ++c) src.push_back(v.comps[r * v.type.cols + c]);
    } else {
      int have = v.type.components();
      if (have < n) {
        // float2x2 <-> float4 converts element-wise when the counts match
        sink_->error(at, "X3017", "cannot implicitly convert from '{}' to '{}'", v.type.name(), to.name());
        return Value{to, Comps(n, lit(0)), false};
      }
      if (have > n && !explicitCast && !to.isScalar()) warnTruncation(at);
      if (have > n && !explicitCast && to.isScalar() && have > 1) warnTruncation(at);
      src.resize(n);
    }
    // Value conversions between base types.
    if (isIntegral(to.base) && !isIntegral(v.type.base)) {
      if (to.base == BaseType::Bool) src = notEqualZero(src);
      else src = truncate(src);
    } else if (to.base == BaseType::Bool && v.type.base != BaseType::Bool) {
      src = notEqualZero(src);
    }
    out.comps = src;
    return out;
  }

  Comps notEqualZero(const Comps& a) {
    // (a != 0) = 1 - (a >= 0) * (-a >= 0)
    Comps z(a.size(), lit(0));
    Comps ge = op(IrOp::Sge, int(a.size()), {a, z});
    Comps le = op(IrOp::Sge, int(a.size()), {z, a});
    return op(IrOp::Add, int(a.size()), {Comps(a.size(), lit(1)), negate(op(IrOp::Mul, int(a.size()), {ge, le}))});
  }

  // Toward zero: x - frc(x), corrected for negative non-integers.
  Comps truncate(const Comps& a) {
    if (allLiteral(a)) {
      Comps o = a;
      for (Comp& c : o) c.k = truncF(c.k);
      return o;
    }
    int n = int(a.size());
    Comps fl = floorOf(a);
    // trunc = x >= 0 ? floor(x) : -floor(-x)
    Comps negFl = negate(floorOf(negate(a)));
    return select(op(IrOp::Sge, n, {a, Comps(n, lit(0))}), fl, negFl);
  }

  Comps floorOf(const Comps& a) {
    int n = int(a.size());
    return op(IrOp::Add, n, {a, negate(op(IrOp::Frc, n, {a}))});
  }

  // cond ? a : b per component; cond holds 0 or 1.
  Comps select(const Comps& cond, const Comps& a, const Comps& b) {
    int n = int(a.size());
    Comps c = cond;
    if (c.size() == 1 && n > 1) c.assign(n, cond[0]);
    Comps out(n);
    bool need = false;
    for (int i = 0; i < n; ++i) {
      if (a[i] == b[i]) continue;
      if (c[i].literal()) continue;
      need = true;
    }
    if (!need) {
      for (int i = 0; i < n; ++i) out[i] = a[i] == b[i] ? a[i] : (c[i].k != 0 ? a[i] : b[i]);
      return out;
    }
    // cmp(-cond, b, a): -cond >= 0 exactly when cond is 0
    return op(IrOp::Cmp, n, {negate(c), b, a});
  }

  Type arithmeticResult(const Type& a, const Type& b, const SourceLocation& at) {
    BaseType base = baseRank(a.base) >= baseRank(b.base) ? a.base : b.base;
    if (base == BaseType::Bool) base = BaseType::Int;
    if (a.isScalar()) { Type t = b; t.base = base; return t; }
    if (b.isScalar()) { Type t = a; t.base = base; return t; }
    if (a.cls == TypeClass::Matrix || b.cls == TypeClass::Matrix) {
      if (a.cls == TypeClass::Matrix && b.cls == TypeClass::Matrix) {
        Type t = Type::matrix(base, std::min(a.rows, b.rows), std::min(a.cols, b.cols));
        if (t.rows != a.rows || t.cols != a.cols || t.rows != b.rows || t.cols != b.cols) warnTruncation(at);
        return t;
      }
      // vector with matrix: only when the component counts match
      const Type& m = a.cls == TypeClass::Matrix ? a : b;
      const Type& v = a.cls == TypeClass::Matrix ? b : a;
      if (v.components() == m.components()) { Type t = m; t.base = base; return t; }
      sink_->error(at, "X3020", "type mismatch between '{}' and '{}'", a.name(), b.name());
      return Type::scalar(base);
    }
    int n = std::min(a.cols, b.cols);
    if (a.cols != b.cols) warnTruncation(at);
    Type t = Type::vector(base, n);
    if (n == 1) t.cls = TypeClass::Vector;
    return t;
  }

  // ---- globals ---------------------------------------------------------------------------------
  static int registerRows(const Type& t) {
    if (t.isArray()) return t.arraySize * registerRows(*t.element);
    if (t.cls == TypeClass::Struct) {
      int n = 0;
      for (const auto& m : t.structDef->members) n += registerRows(m.type);
      return n;
    }
    if (t.cls == TypeClass::Matrix) return t.packing == 1 ? t.rows : t.cols;
    if (t.cls == TypeClass::Scalar || t.cls == TypeClass::Vector) return 1;
    return 0;
  }

  void declareGlobal(const VarDecl& g) {
    auto var = std::make_unique<Variable>();
    var->type = g.type;
    var->decl = &g;
    var->isConst = g.isConst;
    where_ = g.where;
    if (g.type.cls == TypeClass::Object && g.type.base == BaseType::Sampler) {
      var->comps = {Comp{}};
      var->comps[0].sampler = true;
      var->comps[0].k = -1;  // bound on first use
      var->uniform = true;
    } else if (g.type.cls == TypeClass::Object && g.type.base == BaseType::Texture && opt_.compat()) {
      // The pre-release dialect samples textures directly (sample3d(noise, p)).
      var->comps = {Comp{}};
      var->comps[0].sampler = true;
      var->comps[0].k = -1;
      var->uniform = true;
    } else if (g.type.cls == TypeClass::Object) {
      var->comps = {lit(0)};
    } else if (g.isStatic) {
      var->comps = initialValue(g, g.type);
    } else {
      var->uniform = true;
      IrUniform u;
      u.name = g.name;
      u.decl = &g;
      u.type = g.type;
      u.registerCount = registerRows(g.type);
      if (g.init) {
        Comps init = initialValue(g, g.type);
        u.defaults = packDefaults(g.type, init);
      }
      var->uniformIndex = int(ir_.uniforms.size());
      ir_.uniforms.push_back(std::move(u));
    }
    if (scopes_.front().count(g.name))
      sink_->error(g.where, "X3003", "redefinition of '{}'", g.name);
    scopes_.front()[g.name] = var.get();
    variables_.push_back(std::move(var));
  }

  // Default values laid out as the constant registers hold them.
  std::vector<float> packDefaults(const Type& t, const Comps& init) {
    std::vector<float> out;
    size_t at = 0;
    std::function<void(const Type&)> walk = [&](const Type& ty) {
      if (ty.isArray()) { for (int i = 0; i < ty.arraySize; ++i) walk(*ty.element); return; }
      if (ty.cls == TypeClass::Struct) { for (const auto& m : ty.structDef->members) walk(m.type); return; }
      int regs = registerRows(ty);
      std::vector<float> block(size_t(regs) * 4, 0.0f);
      for (int r = 0; r < ty.rows; ++r)
        for (int c = 0; c < ty.cols; ++c) {
          float v = at < init.size() && init[at].literal() ? init[at].k : 0;
          ++at;
          if (ty.cls == TypeClass::Matrix && ty.packing != 1) block[size_t(c) * 4 + r] = v;
          else block[size_t(r) * 4 + c] = v;
        }
      out.insert(out.end(), block.begin(), block.end());
    };
    walk(t);
    return out;
  }

  Comps initialValue(const VarDecl& d, const Type& t) {
    if (!d.init) return Comps(std::max(1, t.flatSize()), lit(0));
    if (d.init->kind == ExprKind::InitList) {
      Comps flat;
      flattenInitList(*d.init, flat);
      int need = t.flatSize();
      if (int(flat.size()) != need) {
        if (flat.size() == 1 && t.isNumeric()) return Comps(need, flat[0]);
        sink_->error(d.init->where, "X3017", "initializer has {} components, '{}' needs {}", flat.size(), t.name(), need);
        flat.resize(need, lit(0));
      }
      return flat;
    }
    Value v = expr(*d.init);
    return convert(v, t, d.init->where).comps;
  }

  void flattenInitList(const Expr& e, Comps& out) {
    if (e.kind == ExprKind::InitList) {
      for (const auto& a : e.args) flattenInitList(*a, out);
      return;
    }
    Value v = expr(e);
    if (v.type.isNumeric() && v.type.base != BaseType::Float) v = convert(v, Type::vector(BaseType::Float, v.type.components()), e.where);
    out.insert(out.end(), v.comps.begin(), v.comps.end());
  }

  void bindUniform(Variable& v) {
    if (v.bound) return;
    v.bound = true;
    IrUniform& u = ir_.uniforms[v.uniformIndex];
    u.used = true;
    std::vector<int> rows;
    for (int r = 0; r < u.registerCount; ++r) {
      IrInst inst;
      inst.op = IrOp::Uniform;
      inst.width = 4;
      inst.index = (r << 16) | v.uniformIndex;
      rows.push_back(emitInst(std::move(inst)));
    }
    v.comps = layoutRows(u.type, rows);
  }

  // The components of a value of type `t` held in constant registers `rows` (one
  // virtual register each), as the constant table lays it out.
  static Comps layoutRows(const Type& t, const std::vector<int>& rows) {
    Comps out;
    int row = 0;
    std::function<void(const Type&)> walk = [&](const Type& ty) {
      if (ty.isArray()) { for (int i = 0; i < ty.arraySize; ++i) walk(*ty.element); return; }
      if (ty.cls == TypeClass::Struct) { for (const auto& m : ty.structDef->members) walk(m.type); return; }
      int regs = registerRows(ty);
      for (int r = 0; r < ty.rows; ++r)
        for (int c = 0; c < ty.cols; ++c) {
          Comp k;
          if (ty.cls == TypeClass::Matrix && ty.packing != 1) { k.reg = rows[row + c]; k.c = uint8_t(r); }
          else { k.reg = rows[row + r]; k.c = uint8_t(c); }
          out.push_back(k);
        }
      row += regs;
    };
    walk(t);
    return out;
  }

  // A uniform array named by `e` (a global uniform, or an array member of a uniform
  // struct): which uniform, the register row its element 0 starts at, its type.
  struct UniformArray {
    int uniform = -1;
    int row = 0;
    Type type;
  };
  std::optional<UniformArray> uniformArray(const Expr& e) {
    if (e.kind == ExprKind::Name) {
      Variable* v = lookup(e.op);
      if (!v || !v->uniform || v->uniformIndex < 0) return std::nullopt;
      return UniformArray{v->uniformIndex, 0, v->type};
    }
    if (e.kind == ExprKind::Member) {
      std::optional<UniformArray> base = uniformArray(*e.args[0]);
      if (!base || base->type.cls != TypeClass::Struct || base->type.isArray()) return std::nullopt;
      int row = base->row;
      for (const auto& m : base->type.structDef->members) {
        if (m.name == e.op) return UniformArray{base->uniform, row, m.type};
        row += registerRows(m.type);
      }
    }
    return std::nullopt;
  }

  int samplerIndex(Variable& v) {
    if (v.comps[0].k < 0) {
      IrSampler s;
      s.name = v.decl ? v.decl->name : "";
      s.decl = v.decl;
      s.dim = v.type.dim;
      v.comps[0].k = float(ir_.samplers.size());
      ir_.samplers.push_back(s);
    }
    return int(v.comps[0].k);
  }

  // ---- scopes ----------------------------------------------------------------------------------
  Variable* lookup(const std::string& name) {
    for (auto it = scopes_.rbegin(); it != scopes_.rend(); ++it) {
      auto f = it->find(name);
      if (f != it->end()) return f->second;
    }
    return nullptr;
  }

  Variable* declareLocal(const std::string& name, const Type& t, const SourceLocation& at) {
    auto var = std::make_unique<Variable>();
    var->type = t;
    var->comps.assign(std::max(1, t.flatSize()), lit(0));
    if (scopes_.back().count(name)) sink_->error(at, "X3003", "redefinition of '{}'", name);
    scopes_.back()[name] = var.get();
    variables_.push_back(std::move(var));
    return variables_.back().get();
  }

  // ---- flow state ------------------------------------------------------------------------------
  struct FunctionFrame {
    explicit FunctionFrame(const FunctionDecl* d) : decl(d) {}
    const FunctionDecl* decl;
    Comp returned = lit(0);
    Comps returnValue;
    bool hasReturnValue = false;
  };
  // Components `comps` of variables_[var] that a flow-control region changes, held in
  // `reg`, a register Assign writes (width comps.size()).
  struct Carried {
    int var = -1;
    std::vector<int> comps;
    int reg = -1;
  };
  struct LoopFrame {
    Comp broken = lit(0);
    Comp continued = lit(0);
    bool real = false;         // rep … endrep: a break is break_comp, not a mask
    bool ignoreBreak = false;  // counting the iterations of a [loop]
    std::vector<Carried> carried;  // real loops: the variables the body changes
  };

  Comp andC(Comp a, Comp b) {
    if (a.literal()) return a.k != 0 ? b : lit(0);
    if (b.literal()) return b.k != 0 ? a : lit(0);
    return op(IrOp::Mul, 1, {Comps{a}, Comps{b}})[0];
  }
  Comp orC(Comp a, Comp b) {
    if (a.literal()) return a.k != 0 ? lit(1) : b;
    if (b.literal()) return b.k != 0 ? lit(1) : a;
    return op(IrOp::Max, 1, {Comps{a}, Comps{b}})[0];
  }
  Comp notC(Comp a) {
    if (a.literal()) return lit(a.k != 0 ? 0 : 1);
    return op(IrOp::Add, 1, {Comps{lit(1)}, negate(Comps{a})})[0];
  }

  Comp active() {
    Comp a = conditions_.empty() ? lit(1) : conditions_.back();
    if (!functions_.empty()) a = andC(a, notC(functions_.back().returned));
    // Every enclosing loop: lanes that left an outer loop (or skip the rest of its
    // iteration) run nothing in the loops inside it either.
    for (const LoopFrame& l : loops_) a = andC(a, notC(orC(l.broken, l.continued)));
    return a;
  }

  // ---- bounds on recursion and work ------------------------------------------------------------
  // Statements, expressions and inlined calls recurse into each other. Past kMaxDepth
  // levels the program is reported as too deeply nested instead of exhausting the stack
  // (the parser bounds each construct; calls can stack them). Unrolling and inlining
  // multiply work (loops in loops, a function calling another twice, …): past kMaxWork
  // statements and expressions evaluated in all the program is reported as too large
  // instead of running for minutes. Either way evaluation then stops: statements do
  // nothing and expressions give an error value, so loops end at once.
  static constexpr int kMaxDepth = 640;
  static constexpr long kMaxWork = 100'000;
  class Deeper {
   public:
    explicit Deeper(Builder& b) : b_(b) { ++b_.depth_; ++b_.work_; }
    ~Deeper() { --b_.depth_; }
    Deeper(const Deeper&) = delete;
    Deeper& operator=(const Deeper&) = delete;

   private:
    Builder& b_;
  };
  bool tooDeep(const SourceLocation& at) {
    if (depth_ <= kMaxDepth && work_ <= kMaxWork && !tooDeepReported_) return false;
    if (!tooDeepReported_) {
      tooDeepReported_ = true;
      if (depth_ > kMaxDepth)
        sink_->error(at, "X3590", "statements, expressions and inlined calls are nested more than {} levels deep", kMaxDepth);
      else
        sink_->error(at, "X3590", "the program is too large: more than {} statements and expressions once loops are "
                    "unrolled and calls inlined", kMaxWork);
    }
    return true;
  }

  // ---- statements ------------------------------------------------------------------------------
  void statement(const Stmt& s) {
    Deeper deeper(*this);
    if (tooDeep(s.where)) return;
    where_ = s.where;
    Comp act = active();
    if (act.literal() && act.k == 0) return;  // unreachable here
    switch (s.kind) {
      case StmtKind::Empty: return;
      case StmtKind::Expr: expr(*s.expr); return;
      case StmtKind::Decl:
        for (const auto& d : s.decls) {
          Variable* v = declareLocal(d->name, d->type, d->where);
          v->isConst = d->isConst;
          if (d->init) v->comps = initialValue(*d, d->type);
          else if (!d->type.isNumeric() || true) uninitialized_.insert(v);
          if (d->init) uninitialized_.erase(v);
        }
        return;
      case StmtKind::Block:
        scopes_.emplace_back();
        for (const auto& b : s.block) statement(*b);
        scopes_.pop_back();
        return;
      case StmtKind::If: {
        if (breakStatement(s)) return;
        if (hasAttribute(s, "branch") && branch(s)) return;
        Value c = condition(*s.expr);
        Comp cond = c.comps[0];
        if (cond.literal()) {
          if (cond.k != 0) scoped(*s.body);
          else if (s.elseBody) scoped(*s.elseBody);
          return;
        }
        Comp outer = conditions_.empty() ? lit(1) : conditions_.back();
        conditions_.push_back(andC(outer, cond));
        scoped(*s.body);
        conditions_.back() = andC(outer, notC(cond));
        if (s.elseBody) scoped(*s.elseBody);
        conditions_.pop_back();
        return;
      }
      case StmtKind::For:
      case StmtKind::While:
      case StmtKind::Do: loop(s); return;
      case StmtKind::Break:
        if (loops_.empty()) { sink_->error(s.where, "X3518", "break must be inside a loop"); return; }
        if (loops_.back().real) { realBreak(act); return; }
        if (loops_.back().ignoreBreak) return;
        loops_.back().broken = orC(loops_.back().broken, act);
        return;
      case StmtKind::Continue:
        if (loops_.empty()) { sink_->error(s.where, "X3519", "continue must be inside a loop"); return; }
        loops_.back().continued = orC(loops_.back().continued, act);
        return;
      case StmtKind::Discard: {
        if (!isPixel()) { sink_->error(s.where, "X3539", "discard is only valid in pixel shaders"); return; }
        kill(Comps{negate(Comps{act})[0]});
        return;
      }
      case StmtKind::Return: {
        // Evaluate first: a call in the expression pushes frames (and may move them).
        const FunctionDecl* decl = functions_.back().decl;
        Value v;
        if (s.expr && !decl->returnType.isVoid()) v = convert(expr(*s.expr), decl->returnType, s.expr->where);
        act = active();
        FunctionFrame& f = functions_.back();
        if (s.expr) {
          if (f.decl->returnType.isVoid()) {
            sink_->error(s.where, "X3079", "void functions cannot return a value");
          } else {
            if (!f.hasReturnValue) { f.returnValue = v.comps; f.hasReturnValue = true; }
            else f.returnValue = select(Comps{act}, v.comps, f.returnValue);
          }
        } else if (!f.decl->returnType.isVoid()) {
          sink_->error(s.where, "X3080", "'{}': function must return a value", f.decl->name);
        }
        f.returned = orC(f.returned, act);
        return;
      }
    }
  }

  void scoped(const Stmt& s) {
    scopes_.emplace_back();
    statement(s);
    scopes_.pop_back();
  }

  void kill(const Comps& c) {
    IrInst inst;
    inst.op = IrOp::Kill;
    inst.width = 4;
    inst.srcCount = 1;
    Comps four = c;
    while (four.size() < 4) four.push_back(c.back());
    inst.src[0] = source(four);
    inst.where = where_;
    ir_.usesKill = true;
    emitInst(std::move(inst));
  }

  Value condition(const Expr& e) {
    Value v = expr(e);
    if (!v.type.isNumeric()) {
      sink_->error(e.where, "X3019", "if/loop condition must be a scalar, found '{}'", v.type.name());
      return Value{Type::scalar(BaseType::Bool), {lit(0)}, false};
    }
    if (!v.type.isScalar()) {
      warnTruncation(e.where);
      v.comps.resize(1);
      v.type = Type::scalar(v.type.base);
    }
    return convert(v, Type::scalar(BaseType::Bool), e.where);
  }

  // Loops unroll, unless marked [loop] on a profile with rep (see realLoop).
  void loop(const Stmt& s) {
    scopes_.emplace_back();
    if (s.init) statement(*s.init);
    std::string why;
    if (hasAttribute(s, "loop")) {
      why = realLoopObstacle(s);
      std::string code = "X3554";
      if (why.empty() && realLoop(s, why, code)) {
        scopes_.pop_back();
        return;
      }
      sink_->warning(s.where, code, "[loop] ignored: {}; the loop is unrolled", why);
    }
    unroll(s, why, false);
    scopes_.pop_back();
  }

  // Unrolls the loop after its init. `why`: the reason a [loop] is unrolled (its
  // failures then name the profile). `probe`: only count the iterations whose
  // condition is a literal true, with breaks ignored: returns that count, -1 when a
  // condition is known only at run time, -2 past 255.
  int unroll(const Stmt& s, const std::string& why, bool probe) {
    // A mask known only at run time (a break, or an enclosing if or loop) masks the
    // step too (i++ happens only where the loop goes on), so the counter stops being a
    // literal; the lanes still in the loop see the counter of an unmasked loop without
    // breaks: count that one first.
    int withoutBreaks = -1;
    if (!probe) {
      Contents c;
      scan(s.body.get(), c, false);
      if (c.breaks || !active().literal()) withoutBreaks = tripCount(s);
    }
    loops_.emplace_back();
    loops_.back().ignoreBreak = probe;
    const int kMaxIterations = probe ? 255 : 1024;
    int iterations = 0;
    int result = 0;
    bool first = true;
    auto cannotUnroll = [&](const std::string& reason) {
      if (why.empty()) sink_->error(s.where, "X3511", "unable to unroll loop{}", reason);
      else
        sink_->error(s.where, "X3531", "{} cannot run this [loop] ({}), and it cannot be unrolled{}",
                     opt_.version.name(), why, reason);
    };
    for (;;) {
      if (s.kind != StmtKind::Do || !first) {
        const Expr* c = s.expr.get();
        if (c) {
          Value cv = condition(*c);
          Comp cond = cv.comps[0];
          if (!cond.literal()) {
            // A condition only known at run time: the loop still unrolls when its
            // trip count is bounded by the attribute; otherwise it needs flow control.
            if (probe) {
              result = -1;
              break;
            }
            if (withoutBreaks >= 0) {
              if (iterations >= withoutBreaks) break;
            } else if (s.unrollCount > 0) {  // [unroll(n)]: at most n iterations
              if (iterations >= s.unrollCount) break;
              loops_.back().broken = orC(loops_.back().broken, andC(active(), notC(cond)));
            } else {
              cannotUnroll(": the loop condition does not depend only on constants");
              break;
            }
          } else if (cond.k == 0) {
            break;
          }
        }
      }
      first = false;
      Comp act = active();
      if (act.literal() && act.k == 0) break;
      if (++iterations > kMaxIterations) {
        if (probe) {
          result = -2;
          break;
        }
        cannotUnroll(fmt::format(", loop does not appear to terminate in a timely manner ({} iterations)", kMaxIterations));
        break;
      }
      scoped(*s.body);
      loops_.back().continued = lit(0);
      Comp after = active();
      if (after.literal() && after.k == 0) break;
      if (s.kind == StmtKind::For && s.step) expr(*s.step);
      if (s.kind == StmtKind::Do && !s.expr) break;
    }
    loops_.pop_back();
    return result < 0 ? result : iterations;
  }

  // ---- flow-control regions --------------------------------------------------------------------
  // [loop] and [branch] keep loops and branches as rep … endrep and if … else … endif
  // where the profile has them. A variable that such a region changes moves into a
  // register written by Assign: before the region, and where each body ends (and before
  // a break). A region is first built on trial when the variables it changes are not
  // known yet (loops); everything it touched is then rolled back.

  static bool hasAttribute(const Stmt& s, const char* name) {
    return std::find(s.attributes.begin(), s.attributes.end(), name) != s.attributes.end();
  }
  bool profileHas(shader::Opcode op) const { return rules_ && shader::findOpcodeRule(*rules_, op); }

  // What a statement holds that a region cannot express with masks: return, and
  // break/continue that leave it (not those of a loop inside it).
  struct Contents {
    bool returns = false, breaks = false, continues = false;
  };
  static void scan(const Stmt* s, Contents& c, bool inLoop) {
    if (!s) return;
    switch (s->kind) {
      case StmtKind::Return: c.returns = true; break;
      case StmtKind::Break: c.breaks |= !inLoop; break;
      case StmtKind::Continue: c.continues |= !inLoop; break;
      case StmtKind::For: case StmtKind::While: case StmtKind::Do: inLoop = true; break;
      default: break;
    }
    scan(s->body.get(), c, inLoop);
    scan(s->elseBody.get(), c, inLoop);
    for (const auto& b : s->block) scan(b.get(), c, inLoop);
  }
  // Assignments, ++/-- and calls that may write something (user functions, out
  // arguments of intrinsics).
  bool hasSideEffects(const Expr* e) const {
    if (!e) return false;
    if (e->kind == ExprKind::Assign || e->kind == ExprKind::Postfix) return true;
    if (e->kind == ExprKind::Unary && (e->op == "++" || e->op == "--")) return true;
    if (e->kind == ExprKind::Call) {
      if (e->op == "modf" || e->op == "frexp" || e->op == "sincos" || e->op == "clip") return true;
      for (const auto& f : prog_.functions)
        if (f->name == e->op) return true;
    }
    for (const auto& a : e->args)
      if (hasSideEffects(a.get())) return true;
    return false;
  }
  // Whether statement `s` assigns the variable called `name` (++, --, =, op=).
  static bool assignsName(const Stmt* s, const std::string& name) {
    if (!s) return false;
    std::function<bool(const Expr*)> inExpr = [&](const Expr* e) {
      if (!e) return false;
      bool writes = e->kind == ExprKind::Assign || e->kind == ExprKind::Postfix ||
                    (e->kind == ExprKind::Unary && (e->op == "++" || e->op == "--"));
      if (writes) {
        const Expr* root = e->args[0].get();
        while (root->kind == ExprKind::Member || root->kind == ExprKind::Index) root = root->args[0].get();
        if (root->kind == ExprKind::Name && root->op == name) return true;
      }
      for (const auto& a : e->args)
        if (inExpr(a.get())) return true;
      return false;
    };
    if (inExpr(s->expr.get()) || inExpr(s->step.get())) return true;
    for (const auto& d : s->decls)
      if (inExpr(d->init.get())) return true;
    if (assignsName(s->init.get(), name) || assignsName(s->body.get(), name) || assignsName(s->elseBody.get(), name))
      return true;
    for (const auto& b : s->block)
      if (assignsName(b.get(), name)) return true;
    return false;
  }

  // Everything building code changes, so a trial build can be undone.
  struct Checkpoint {
    size_t code = 0, regs = 0, samplers = 0, variables = 0;
    bool usesKill = false;
    std::vector<IrUniform> uniforms;
    std::vector<std::pair<Comps, bool>> values;  // per variable: comps, bound
    std::vector<std::map<std::string, Variable*>> scopes;
    std::set<Variable*> uninitialized;
    std::set<std::tuple<std::string, int, int>> truncationWarned;
    std::map<std::vector<float>, int> constants;
    std::map<std::vector<int>, int> cse;
    std::map<std::pair<int, int>, Comp> rcpOf;
    std::map<std::vector<std::tuple<int, int, float>>, int> combines;
    std::vector<Comp> conditions;
    std::vector<FunctionFrame> functions;
    std::vector<LoopFrame> loops;
    DiagnosticSink* sink = nullptr;
    SourceLocation where;
    int realLoops = 0;
  };
  Checkpoint save() const {
    Checkpoint c;
    c.code = ir_.code.size();
    c.regs = ir_.regWidth.size();
    c.samplers = ir_.samplers.size();
    c.variables = variables_.size();
    c.usesKill = ir_.usesKill;
    c.uniforms = ir_.uniforms;
    for (const auto& v : variables_) c.values.emplace_back(v->comps, v->bound);
    c.scopes = scopes_;
    c.uninitialized = uninitialized_;
    c.truncationWarned = truncationWarned_;
    c.constants = constants_;
    c.cse = cse_;
    c.rcpOf = rcpOf_;
    c.combines = combines_;
    c.conditions = conditions_;
    c.functions = functions_;
    c.loops = loops_;
    c.sink = sink_;
    c.where = where_;
    c.realLoops = realLoops_;
    return c;
  }
  void restore(Checkpoint& c) {
    ir_.code.resize(c.code);
    ir_.regWidth.resize(c.regs);
    ir_.samplers.resize(c.samplers);
    ir_.usesKill = c.usesKill;
    ir_.uniforms = std::move(c.uniforms);
    scopes_ = std::move(c.scopes);
    variables_.resize(c.variables);
    for (size_t i = 0; i < c.variables; ++i) std::tie(variables_[i]->comps, variables_[i]->bound) = c.values[i];
    uninitialized_ = std::move(c.uninitialized);
    truncationWarned_ = std::move(c.truncationWarned);
    constants_ = std::move(c.constants);
    cse_ = std::move(c.cse);
    rcpOf_ = std::move(c.rcpOf);
    combines_ = std::move(c.combines);
    conditions_ = std::move(c.conditions);
    functions_ = std::move(c.functions);
    loops_ = std::move(c.loops);
    sink_ = c.sink;
    where_ = c.where;
    realLoops_ = c.realLoops;
  }

  // Values computed inside a region (registers from `first` on) are not there after
  // it, nor in the other body of an if: common subexpressions forget them.
  void forgetValuesFrom(int first) {
    std::erase_if(cse_, [&](const auto& e) { return e.second >= first; });
    std::erase_if(combines_, [&](const auto& e) { return e.second >= first; });
    std::erase_if(rcpOf_, [&](const auto& e) { return e.first.first >= first; });
  }

  void emitMarker(IrOp o, std::initializer_list<Comp> sources = {},
                  shader::Comparison compare = shader::Comparison::None) {
    IrInst inst;
    inst.op = o;
    inst.width = 0;
    inst.compare = compare;
    for (const Comp& c : sources) inst.src[inst.srcCount++] = source(Comps{c});
    inst.where = where_;
    ir_.code.push_back(std::move(inst));
  }
  void emitAssign(int reg, const IrSrc& value, int width) {
    IrInst inst;
    inst.op = IrOp::Assign;
    inst.dst = reg;
    inst.width = width;
    inst.srcCount = 1;
    inst.src[0] = value;
    inst.where = where_;
    ir_.code.push_back(std::move(inst));
  }

  // New registers for components `idx` of variable `var`, four per register.
  void carry(int var, const std::vector<int>& idx, std::vector<Carried>& out) {
    for (size_t at = 0; at < idx.size(); at += 4) {
      Carried c;
      c.var = var;
      c.comps.assign(idx.begin() + at, idx.begin() + std::min(idx.size(), at + 4));
      c.reg = ir_.newReg(int(c.comps.size()));
      out.push_back(std::move(c));
    }
  }
  Comps valueOf(const Carried& c) const {
    Comps v;
    for (int k : c.comps) v.push_back(variables_[c.var]->comps[k]);
    return v;
  }
  bool holdsItsRegister(const Carried& c) const {
    for (size_t j = 0; j < c.comps.size(); ++j) {
      const Comp& k = variables_[c.var]->comps[c.comps[j]];
      if (k.literal() || k.reg != c.reg || k.c != j) return false;
    }
    return true;
  }
  void readFromRegister(const Carried& c) {
    for (size_t j = 0; j < c.comps.size(); ++j) {
      Comp k;
      k.reg = c.reg;
      k.c = uint8_t(j);
      variables_[c.var]->comps[c.comps[j]] = k;
    }
  }
  // A fresh register holding `v` now, for a value that reads a register about to be
  // written (never shared through the caches).
  IrSrc copyOut(const Comps& v) {
    IrInst inst;
    inst.op = IrOp::Mov;
    inst.width = int(v.size());
    inst.srcCount = 1;
    inst.src[0] = source(v);
    inst.where = where_;
    IrSrc out;
    out.reg = emitInst(std::move(inst));
    return out;
  }
  // Writes the current values of `groups` into their registers as one parallel copy:
  // a value that reads one of these registers is copied out first.
  void writeBack(const std::vector<Carried>& groups) {
    std::set<int> targets;
    for (const Carried& c : groups) targets.insert(c.reg);
    std::vector<std::pair<const Carried*, IrSrc>> pending;
    for (const Carried& c : groups) {
      if (holdsItsRegister(c)) continue;
      Comps v = valueOf(c);
      bool readsTarget = false;
      for (const Comp& k : v) readsTarget |= !k.literal() && targets.count(k.reg) > 0;
      pending.emplace_back(&c, readsTarget ? copyOut(v) : source(v));
    }
    for (auto& [c, value] : pending) emitAssign(c->reg, value, int(c->comps.size()));
  }

  // a CMP b for a condition: a comparison of two scalars directly, anything else as
  // (value != 0). False after an error.
  bool comparisonOf(const Expr& e, Comp& a, Comp& b, shader::Comparison& cmp) {
    using C = shader::Comparison;
    static const std::map<std::string, C> ops = {{"<", C::Lt}, {">", C::Gt}, {"<=", C::Le},
                                                 {">=", C::Ge}, {"==", C::Eq}, {"!=", C::Ne}};
    if (e.kind == ExprKind::Binary && ops.count(e.op)) {
      Value x = expr(*e.args[0]), y = expr(*e.args[1]);
      if (!x.ok || !y.ok) return false;
      if (x.type.isScalar() && y.type.isScalar()) {
        a = convert(x, Type::scalar(BaseType::Float), e.where).comps[0];
        b = convert(y, Type::scalar(BaseType::Float), e.where).comps[0];
        cmp = ops.at(e.op);
        return true;
      }
      // vectors: the general path below would evaluate the operands again
      Value r = arithmetic(e.op, x, y, e.where);
      if (!r.ok) return false;
      warnTruncation(e.where);
      a = r.comps[0];
    } else {
      Value c = condition(e);
      if (!c.ok) return false;
      a = c.comps[0];
    }
    b = lit(0);
    cmp = C::Ne;
    return true;
  }
  static bool compareLiterals(float a, float b, shader::Comparison cmp) {
    using C = shader::Comparison;
    switch (cmp) {
      case C::Gt: return a > b;
      case C::Eq: return a == b;
      case C::Ge: return a >= b;
      case C::Lt: return a < b;
      case C::Ne: return a != b;
      case C::Le: return a <= b;
      default: return false;
    }
  }
  static shader::Comparison inverse(shader::Comparison cmp) {
    using C = shader::Comparison;
    switch (cmp) {
      case C::Gt: return C::Le;
      case C::Eq: return C::Ne;
      case C::Ge: return C::Lt;
      case C::Lt: return C::Ge;
      case C::Ne: return C::Eq;
      case C::Le: return C::Gt;
      default: return cmp;
    }
  }

  // [branch] if: if_comp … else … endif, or if b# when the condition is a bool
  // uniform. False: the caller flattens it (after a warning saying why).
  bool branch(const Stmt& s) {
    const Expr* boolExpr = s.expr.get();
    bool negated = false;
    if (boolExpr->kind == ExprKind::Unary && boolExpr->op == "!") {
      boolExpr = boolExpr->args[0].get();
      negated = true;
    }
    int boolUniform = -1;
    if (boolExpr->kind == ExprKind::Name)
      if (Variable* v = lookup(boolExpr->op);
          v && v->uniform && v->uniformIndex >= 0 && v->type.isScalar() && v->type.base == BaseType::Bool)
        boolUniform = v->uniformIndex;
    Contents c;
    scan(s.body.get(), c, false);
    scan(s.elseBody.get(), c, false);
    const bool inRealLoop = !loops_.empty() && loops_.back().real;
    std::string why;
    if (boolUniform >= 0 && !profileHas(shader::Opcode::If)) why = opt_.version.name() + " has no if b#";
    else if (boolUniform < 0 && !profileHas(shader::Opcode::IfC)) why = opt_.version.name() + " has no if_comp";
    else if (c.returns) why = "a return inside the branch needs it flattened";
    else if (c.continues) why = "a continue inside the branch needs it flattened";
    else if (c.breaks && !inRealLoop) why = "a break inside the branch of an unrolled loop needs it flattened";
    if (!why.empty()) {
      sink_->warning(s.where, "X3554", "[branch] ignored: {}; the branch is flattened", why);
      return false;
    }
    // Built on trial: a per-pixel condition around gradient operations is undone.
    Checkpoint cp = save();
    DiagnosticSink scratch;
    sink_ = &scratch;
    auto commit = [&] {
      sink_ = cp.sink;
      for (const Diagnostic& d : scratch.all()) sink_->report(d);
      return true;
    };
    if (boolUniform >= 0) {
      ir_.uniforms[boolUniform].branchBool = true;
      IrInst inst;
      inst.op = IrOp::If;
      inst.width = 0;
      inst.uniform = boolUniform;
      inst.index = negated ? 1 : 0;
      inst.where = s.where;
      ifRegion(inst, s);
      return commit();
    }
    Comp a, b;
    shader::Comparison cmp;
    if (!comparisonOf(*s.expr, a, b, cmp)) return commit();
    if (a.literal() && b.literal()) {  // known now: no branch
      if (compareLiterals(a.k, b.k, cmp)) scoped(*s.body);
      else if (s.elseBody) scoped(*s.elseBody);
      return commit();
    }
    IrInst inst;
    inst.op = IrOp::If;
    inst.width = 0;
    inst.compare = cmp;
    inst.srcCount = 2;
    inst.src[0] = source(Comps{a});
    inst.src[1] = source(Comps{b});
    inst.where = s.where;
    size_t at = ifRegion(inst, s);
    if (isPixel() && gradientsFrom(at)) {
      restore(cp);
      sink_->warning(s.where, "X4121",
                     "[branch] ignored: gradient operations (tex2D, ddx …) inside a branch on a per-pixel condition "
                     "are undefined; the branch is flattened");
      return false;
    }
    return commit();
  }

  // Texture sampling with implicit gradients, or ddx/ddy, from instruction `from` on.
  bool gradientsFrom(size_t from) const {
    for (size_t i = from; i < ir_.code.size(); ++i)
      switch (ir_.code[i].op) {
        case IrOp::Tex: case IrOp::TexProj: case IrOp::TexBias: case IrOp::Dsx: case IrOp::Dsy: return true;
        default: break;
      }
    return false;
  }
  // A break from instruction `from` on: lanes may leave the loop at different times.
  bool breaksFrom(size_t from) const {
    for (size_t i = from; i < ir_.code.size(); ++i)
      if (ir_.code[i].op == IrOp::Break) return true;
    return false;
  }

  // if … [else …] endif around the bodies of `s`. The variables either body changes
  // get registers, initialised before the if and written at the end of each body.
  // Returns where the if marker ended up.
  size_t ifRegion(const IrInst& marker, const Stmt& s) {
    const size_t initAt = ir_.code.size();
    ir_.code.push_back(marker);
    const int barrier = int(ir_.regWidth.size());
    const size_t count = variables_.size();
    std::vector<Comps> before(count);
    for (size_t i = 0; i < count; ++i) before[i] = variables_[i]->comps;
    std::vector<Carried> groups;
    // A break ends its body here, not the loop body after the endif.
    const Comp brokenBefore = loops_.empty() ? lit(0) : loops_.back().broken;
    auto closeBody = [&] {
      if (!loops_.empty()) loops_.back().broken = brokenBefore;
      std::set<size_t> touched;
      for (size_t i = 0; i < count; ++i) {
        Variable* v = variables_[i].get();
        if (v->uniform) continue;
        std::vector<int> changed, fresh;
        for (size_t k = 0; k < v->comps.size(); ++k)
          if (!(v->comps[k] == before[i][k])) changed.push_back(int(k));
        for (int k : changed) {
          bool held = false;
          for (size_t g = 0; g < groups.size(); ++g)
            if (groups[g].var == int(i) && std::count(groups[g].comps.begin(), groups[g].comps.end(), k)) {
              touched.insert(g);
              held = true;
            }
          if (!held) fresh.push_back(k);
        }
        size_t first = groups.size();
        carry(int(i), fresh, groups);
        for (size_t g = first; g < groups.size(); ++g) touched.insert(g);
      }
      // This region's registers are not read inside it: no parallel copy needed.
      for (size_t g : touched) emitAssign(groups[g].reg, source(valueOf(groups[g])), int(groups[g].comps.size()));
      for (size_t i = 0; i < count; ++i)
        if (!variables_[i]->uniform) variables_[i]->comps = before[i];
      forgetValuesFrom(barrier);
    };
    scoped(*s.body);
    closeBody();
    if (s.elseBody) {
      emitMarker(IrOp::Else);
      scoped(*s.elseBody);
      closeBody();
    }
    emitMarker(IrOp::EndIf);
    // The registers start with the values before the if (inserted ahead of it).
    std::vector<IrInst> tail(std::make_move_iterator(ir_.code.begin() + long(initAt)),
                             std::make_move_iterator(ir_.code.end()));
    ir_.code.resize(initAt);
    for (const Carried& g : groups) {
      Comps v;
      for (int k : g.comps) v.push_back(before[g.var][k]);
      emitAssign(g.reg, source(v), int(g.comps.size()));
    }
    const size_t markerAt = ir_.code.size();
    for (IrInst& in : tail) ir_.code.push_back(std::move(in));
    forgetValuesFrom(barrier);
    for (const Carried& g : groups) readFromRegister(g);
    return markerAt;
  }

  // Why a [loop] cannot be a rep … endrep here ("" when it can).
  std::string realLoopObstacle(const Stmt& s) const {
    const std::string profile = opt_.version.name();
    if (!profileHas(shader::Opcode::Rep)) return profile + " has no rep or loop instruction";
    if (realLoops_ >= rules_->flow.loopDepth)
      return fmt::format("{} allows rep/loop nesting depth {}", profile, rules_->flow.loopDepth);
    Contents c;
    scan(s.body.get(), c, false);
    if (c.returns) return "a return inside the loop needs it unrolled";
    if (c.breaks && !profileHas(shader::Opcode::BreakC)) return profile + " has no break_comp for the break";
    if (hasSideEffects(s.expr.get())) return "the loop condition has side effects";
    return "";
  }

  // for (i = 0; i < n; i++) with n a uniform int and a body that leaves i alone: the
  // trip count is n, from an int register (rep i#). Returns n's uniform, or -1.
  int uniformTripCount(const Stmt& s) {
    if (s.kind != StmtKind::For || !s.expr || !s.step) return -1;
    const Expr& c = *s.expr;
    if (c.kind != ExprKind::Binary || c.op != "<" || c.args[0]->kind != ExprKind::Name ||
        c.args[1]->kind != ExprKind::Name)
      return -1;
    const std::string& name = c.args[0]->op;
    Variable* i = lookup(name);
    Variable* n = lookup(c.args[1]->op);
    if (!i || !n || i->uniform || !n->uniform || n->uniformIndex < 0 || !n->type.isScalar() ||
        (n->type.base != BaseType::Int && n->type.base != BaseType::Uint))
      return -1;
    if (i->comps.size() != 1 || !i->comps[0].literal() || i->comps[0].k != 0) return -1;
    const Expr& st = *s.step;
    auto isI = [&](const Expr& x) { return x.kind == ExprKind::Name && x.op == name; };
    bool plusOne = ((st.kind == ExprKind::Postfix || st.kind == ExprKind::Unary) && st.op == "++" && isI(*st.args[0])) ||
                   (st.kind == ExprKind::Assign && st.op == "+=" && isI(*st.args[0]) &&
                    st.args[1]->kind == ExprKind::Literal && st.args[1]->number == 1);
    if (!plusOne || assignsName(s.body.get(), name)) return -1;
    return n->uniformIndex;
  }

  // The iterations a loop runs when they are known now: its unrolling, on trial, as
  // the lanes that run it see it (no enclosing masks, breaks ignored).
  int tripCount(const Stmt& s) {
    Checkpoint cp = save();
    DiagnosticSink scratch;
    sink_ = &scratch;
    conditions_.push_back(lit(1));
    for (LoopFrame& l : loops_) l.broken = l.continued = lit(0);
    if (!functions_.empty()) functions_.back().returned = lit(0);
    int n = unroll(s, "", true);
    restore(cp);
    return n;
  }

  // [loop] as rep … endrep. False (with `why`) when it has to be unrolled after all.
  bool realLoop(const Stmt& s, std::string& why, std::string& code) {
    int count = tripCount(s);
    int countUniform = -1;
    bool checkCondition = false;
    if (count == -2) {
      Contents c;
      scan(s.body.get(), c, false);
      if (!c.breaks) {
        sink_->error(s.where, "X3531", "this [loop] runs more than 255 iterations; rep in {} counts at most 255",
                     opt_.version.name());
        return true;
      }
      // Left by its break (while (true) { … break; }): as many iterations as rep runs.
      sink_->warning(s.where, "X3532", "this [loop] runs at most 255 iterations (rep's count in {}); it has to "
                     "leave by its break before", opt_.version.name());
      count = 255;
    }
    if (count == -1) {
      countUniform = uniformTripCount(s);
      if (countUniform < 0) {
        if (!profileHas(shader::Opcode::BreakC)) {
          why = opt_.version.name() + " has no break_comp to end a loop whose trip count is known only at run time";
          return false;
        }
        count = 255;  // the most rep runs; break_comp ends the loop when its condition fails
        checkCondition = true;
      }
    }
    if (count == 0) return true;
    // Build the body until the set of variables it changes is known: each try carries
    // what the previous one found changed, from the start.
    std::set<std::pair<int, int>> carried;
    for (int attempt = 0; attempt < 16; ++attempt) {
      Checkpoint cp = save();
      DiagnosticSink scratch;
      sink_ = &scratch;
      const size_t at = ir_.code.size();
      bool settled = repRegion(s, count, countUniform, checkCondition, carried);
      if (settled && isPixel() && breaksFrom(at) && gradientsFrom(at)) {
        restore(cp);
        why = "gradient operations (tex2D, ddx …) inside a loop that lanes leave at different times are undefined";
        code = "X3553";
        return false;
      }
      if (settled) {
        // Indices that need the counter as a literal (uniform arrays in pixel shaders,
        // X3512; writes to local arrays, X3500): unrolled, it is one.
        for (const Diagnostic& d : scratch.all())
          if (d.code == "X3512" || d.code == "X3500") {
            restore(cp);
            why = fmt::format("{} cannot index {} by the loop counter", opt_.version.name(),
                              d.code == "X3512" ? "a uniform array" : "an array it writes");
            return false;
          }
        sink_ = cp.sink;
        for (const Diagnostic& d : scratch.all()) sink_->report(d);
        return true;
      }
      restore(cp);
    }
    sink_->error(s.where, "X9000", "internal error: the variables of this [loop] do not settle");
    return true;
  }

  // One try at rep … endrep with the components `carried` in registers. False (and
  // `carried` grown) when the body changes more.
  bool repRegion(const Stmt& s, int count, int countUniform, bool checkCondition,
                 std::set<std::pair<int, int>>& carried) {
    const int barrier = int(ir_.regWidth.size());
    const size_t varCount = variables_.size();
    LoopFrame frame;
    frame.real = true;
    std::map<int, std::vector<int>> byVariable;
    for (auto [v, k] : carried) byVariable[v].push_back(k);
    for (auto& [v, idx] : byVariable) carry(v, idx, frame.carried);
    for (const Carried& g : frame.carried) {
      emitAssign(g.reg, source(valueOf(g)), int(g.comps.size()));
      readFromRegister(g);
    }
    IrInst rep;
    rep.op = IrOp::Rep;
    rep.width = 0;
    rep.index = count;
    rep.uniform = countUniform;
    rep.where = s.where;
    ir_.code.push_back(rep);
    if (countUniform >= 0) ir_.uniforms[countUniform].loopCount = true;
    std::vector<Comps> start(varCount);
    for (size_t i = 0; i < varCount; ++i) start[i] = variables_[i]->comps;
    loops_.push_back(std::move(frame));
    ++realLoops_;
    // the condition of a loop whose trip count is known only at run time
    auto breakUnless = [&](const Expr& e) {
      Comp a, b;
      shader::Comparison cmp;
      if (!comparisonOf(e, a, b, cmp)) return;
      if (a.literal() && b.literal()) {
        if (!compareLiterals(a.k, b.k, cmp)) emitMarker(IrOp::Break);
        return;
      }
      std::set<int> targets;
      for (const Carried& g : loops_.back().carried) targets.insert(g.reg);
      auto stable = [&](Comp k) {  // read before the registers are written
        if (k.literal() || !targets.count(k.reg)) return k;
        Comp out;
        out.reg = copyOut(Comps{k}).reg;
        return out;
      };
      if (s.kind == StmtKind::Do) {
        a = stable(a);
        b = stable(b);
        writeBack(loops_.back().carried);
      }
      emitMarker(IrOp::Break, {a, b}, inverse(cmp));
    };
    if (checkCondition && s.kind != StmtKind::Do) breakUnless(*s.expr);
    scoped(*s.body);
    loops_.back().continued = lit(0);
    if (s.kind == StmtKind::For && s.step) expr(*s.step);
    bool settled = true;
    for (size_t i = 0; i < varCount; ++i) {
      if (variables_[i]->uniform) continue;
      for (size_t k = 0; k < start[i].size(); ++k)
        if (!(variables_[i]->comps[k] == start[i][k]) && carried.insert({int(i), int(k)}).second) settled = false;
    }
    if (settled) {
      if (checkCondition && s.kind == StmtKind::Do) breakUnless(*s.expr);
      else writeBack(loops_.back().carried);
      emitMarker(IrOp::EndRep);
      for (const Carried& g : loops_.back().carried) readFromRegister(g);
      forgetValuesFrom(barrier);
    }
    loops_.pop_back();
    --realLoops_;
    return settled;
  }

  // break inside rep … endrep: break_comp on the active mask. The loop's variables are
  // written first when the body has changed them, inside an if_comp so that only the
  // lanes that leave write them.
  void realBreak(Comp act) { realBreakIf(act, lit(0), shader::Comparison::Ne); }
  void realBreakIf(Comp a, Comp b, shader::Comparison cmp) {
    LoopFrame& f = loops_.back();
    const bool always = a.literal() && b.literal();
    if (always && !compareLiterals(a.k, b.k, cmp)) return;
    bool changed = false;
    for (const Carried& g : f.carried) changed |= !holdsItsRegister(g);
    if (!changed) {
      if (always) emitMarker(IrOp::Break);
      else emitMarker(IrOp::Break, {a, b}, cmp);
    } else if (always) {
      writeBack(f.carried);
      emitMarker(IrOp::Break);
    } else {
      emitMarker(IrOp::If, {a, b}, cmp);
      const int barrier = int(ir_.regWidth.size());
      writeBack(f.carried);
      emitMarker(IrOp::Break);
      emitMarker(IrOp::EndIf);
      forgetValuesFrom(barrier);
    }
    if (always) f.broken = lit(1);  // the rest of the body is not reached
  }

  // `if (a CMP b) break;` directly in a rep body: one break_comp on the comparison.
  bool breakStatement(const Stmt& s) {
    if (loops_.empty() || !loops_.back().real || s.elseBody || !s.body) return false;
    const Stmt* body = s.body.get();
    while (body->kind == StmtKind::Block && body->block.size() == 1) body = body->block[0].get();
    if (body->kind != StmtKind::Break) return false;
    Comp act = active();
    if (!act.literal() || act.k == 0) return false;
    Comp a, b;
    shader::Comparison cmp;
    if (comparisonOf(*s.expr, a, b, cmp)) realBreakIf(a, b, cmp);
    return true;
  }

  // ---- entry point -----------------------------------------------------------------------------
  void runEntry(const FunctionDecl& f) {
    scopes_.emplace_back();
    FunctionFrame frame{&f};
    functions_.push_back(frame);
    callStack_.insert(&f);
    std::vector<std::pair<const VarDecl*, Variable*>> outs;
    size_t argIndex = 0;
    for (const auto& p : f.params) {
      Variable* v = declareLocal(p->name, p->type, p->where);
      if (p->isUniform) {
        if (argIndex < opt_.entryArguments.size()) {
          Value a = expr(*opt_.entryArguments[argIndex++]);
          v->comps = convert(a, p->type, p->where).comps;
        } else {
          // A uniform parameter becomes a constant named "$name", as fxc names it.
          IrUniform u;
          u.name = "$" + p->name;
          u.decl = p.get();
          u.type = p->type;
          u.registerCount = registerRows(p->type);
          v->uniform = true;
          v->uniformIndex = int(ir_.uniforms.size());
          ir_.uniforms.push_back(std::move(u));
          bindUniform(*v);
        }
        continue;
      }
      if (p->isIn) bindInputs(*v, p->type, p->semantic, p->where);
      if (p->isOut) { outs.emplace_back(p.get(), v); if (!p->isIn) uninitialized_.insert(v); }
    }
    for (const auto& s : f.body->block) statement(*s);
    callStack_.erase(&f);
    FunctionFrame done = functions_.back();
    functions_.pop_back();
    if (!f.returnType.isVoid()) {
      if (!done.hasReturnValue) {
        if (!f.syntaxErrors && !tooDeepReported_) sink_->error(f.where, "X3080", "'{}': function must return a value", f.name);
      } else {
        size_t at = 0;
        bindOutputs(f.returnType, f.returnSemantic, done.returnValue, at, f.where);
      }
    }
    for (auto& [decl, var] : outs) {
      size_t at = 0;
      bindOutputs(decl->type, decl->semantic, var->comps, at, decl->where);
    }
    scopes_.pop_back();
    if (ir_.outputs.empty() && !sink_->hasErrors() && !f.syntaxErrors)
      sink_->error(f.where, "X4502", "'{}': the shader writes no outputs (add a semantic such as {})", f.name,
                  isPixel() ? "COLOR" : "POSITION");
  }

  void bindInputs(Variable& v, const Type& t, const std::string& semantic, const SourceLocation& at) {
    size_t flat = 0;
    bindInputsAt(v, t, semantic, at, flat);
  }

  void bindInputsAt(Variable& v, const Type& t, const std::string& semantic, const SourceLocation& at, size_t& flat) {
    if (t.cls == TypeClass::Struct && !t.isArray()) {
      for (const auto& m : t.structDef->members) bindInputsAt(v, m.type, m.semantic, at, flat);
      return;
    }
    if (!t.isNumeric()) {
      if (t.cls == TypeClass::Object) { flat += 1; return; }
      sink_->error(at, "X3502", "'{}' cannot be a shader input", t.name());
      flat += t.flatSize();
      return;
    }
    if (semantic.empty()) {
      sink_->error(at, "X3502", "'{}': input parameter is missing semantics", opt_.entry);
      flat += t.components();
      return;
    }
    Semantic sem = parseSemantic(semantic);
    if (!sem.valid) {
      sink_->error(at, "X4502", "invalid input semantic '{}'", semantic);
      flat += t.components();
      return;
    }
    if (isPixel() && !opt_.version.atLeast(3, 0) && (sem.vpos || sem.vface)) {
      sink_->error(at, "X4502", "{} semantic is only available in ps_3_0", semantic);
      flat += t.components();
      return;
    }
    int rows = t.cls == TypeClass::Matrix ? t.rows : 1;
    int width = t.cls == TypeClass::Matrix ? t.cols : t.components();
    for (int r = 0; r < rows; ++r) {
      // ps_2_0 and earlier have no position input: a POSITION parameter of the
      // pixel shader is accepted (fxc ignores it) and reads zero.
      if (isPixel() && sem.usage == DeclUsage::Position && !sem.vpos) {
        for (int c = 0; c < width; ++c) v.comps[flat++] = lit(0);
        continue;
      }
      IrInst inst;
      inst.op = IrOp::Input;
      inst.width = width;
      inst.index = int(ir_.inputs.size());
      IrInput in;
      in.usage = sem.usage;
      in.usageIndex = sem.index + r;
      in.width = width;
      in.semantic = semantic;
      in.isPosition = sem.vpos;
      in.isFace = sem.vface;
      ir_.inputs.push_back(in);
      int reg = emitInst(std::move(inst));
      for (int c = 0; c < width; ++c) {
        Comp k;
        k.reg = reg;
        k.c = uint8_t(c);
        v.comps[flat++] = k;
      }
    }
  }

  void bindOutputs(const Type& t, const std::string& semantic, const Comps& comps, size_t& at, const SourceLocation& where) {
    if (t.cls == TypeClass::Struct && !t.isArray()) {
      for (const auto& m : t.structDef->members) bindOutputs(m.type, m.semantic, comps, at, where);
      return;
    }
    int n = t.flatSize();
    if (semantic.empty()) {
      sink_->error(where, "X4502", "'{}': output is missing semantics", opt_.entry);
      at += n;
      return;
    }
    // A value that failed to convert to the output's type (reported where it failed)
    // has fewer components than the type: nothing to bind.
    if (at + size_t(n) > comps.size()) {
      if (!sink_->hasErrors())
        sink_->error(where, "X3017", "'{}': the output value has {} components, its type needs {}", opt_.entry,
                     comps.size() > at ? comps.size() - at : 0, n);
      at += n;
      return;
    }
    Semantic sem = parseSemantic(semantic);
    bool ok = sem.valid && !sem.vpos && !sem.vface;
    if (isPixel()) ok = ok && (sem.usage == DeclUsage::Color || sem.usage == DeclUsage::Depth);
    if (!ok) {
      sink_->error(where, "X4502", "invalid {} output semantic '{}'", isPixel() ? "ps" : "vs", semantic);
      at += n;
      return;
    }
    int rows = t.cls == TypeClass::Matrix ? t.rows : 1;
    int width = t.cls == TypeClass::Matrix ? t.cols : n;
    for (int r = 0; r < rows; ++r) {
      IrOutput o;
      o.usage = sem.usage;
      o.usageIndex = sem.index + r;
      o.semantic = semantic;
      o.where = where;
      for (int c = 0; c < width; ++c) {
        const Comp& k = comps[at++];
        IrPart p;
        p.reg = k.reg;
        p.component = k.c;
        p.literal = k.k;
        o.parts.push_back(p);
      }
      for (const IrOutput& prev : ir_.outputs)
        if (prev.usage == o.usage && prev.usageIndex == o.usageIndex)
          sink_->error(where, "X4504", "overlapping output semantics '{}'", semantic);
      ir_.outputs.push_back(std::move(o));
    }
  }

  // ---- expressions -----------------------------------------------------------------------------
  Value expr(const Expr& e) {
    Deeper deeper(*this);
    if (tooDeep(e.where)) return errorValue();
    SourceLocation saved = where_;
    where_ = e.where;
    Value v = exprInner(e);
    where_ = saved;
    return v;
  }

  Value literalValue(const Expr& e) {
    Value v;
    if (e.isBool) v.type = Type::scalar(BaseType::Bool);
    else if (e.isFloat) v.type = Type::scalar(BaseType::Float);
    else v.type = Type::scalar(BaseType::Int);
    v.comps = {lit(float(e.number))};
    return v;
  }

  Value exprInner(const Expr& e) {
    switch (e.kind) {
      case ExprKind::Literal: return literalValue(e);
      case ExprKind::StringLit: {
        Value v; v.type.cls = TypeClass::Object; v.type.base = BaseType::String; v.comps = {lit(0)}; return v;
      }
      case ExprKind::Name: {
        Variable* var = lookup(e.op);
        if (!var) {
          sink_->error(e.where, "X3004", "undeclared identifier '{}'", e.op);
          return errorValue();
        }
        if (var->uniform && var->uniformIndex >= 0) bindUniform(*var);
        if (var->uniform && var->comps[0].sampler) samplerIndex(*var);
        if (uninitialized_.count(var)) {
          sink_->warning(e.where, "X4000", "use of potentially uninitialized variable '{}'", e.op);
          uninitialized_.erase(var);
        }
        return Value{var->type, var->comps, true};
      }
      case ExprKind::Comma: {
        Value v;
        for (const auto& a : e.args) v = expr(*a);
        return v;
      }
      case ExprKind::InitList: {
        Comps flat;
        flattenInitList(e, flat);
        Value v;
        v.type = Type::vector(BaseType::Float, int(flat.size()));
        v.comps = flat;
        return v;
      }
      case ExprKind::Unary: return unaryExpr(e);
      case ExprKind::Postfix: {
        LValue lv = lvalue(*e.args[0]);
        if (!lv.var) return errorValue();
        Value old = readLValue(lv);
        Comps one(old.comps.size(), lit(1));
        Comps nv = op(IrOp::Add, int(old.comps.size()), {old.comps, e.op == "++" ? one : negate(one)});
        writeLValue(lv, nv, e.where);
        return old;
      }
      case ExprKind::Binary: return binaryExpr(e);
      case ExprKind::Assign: return assignExpr(e);
      case ExprKind::Ternary: {
        Value c = expr(*e.args[0]);
        Value a = expr(*e.args[1]);
        Value b = expr(*e.args[2]);
        if (!a.ok || !b.ok || !c.ok) return errorValue();
        if (!a.type.isNumeric() || !b.type.isNumeric()) {
          if (a.type.name() == b.type.name() && c.type.isScalar()) {
            Comps cc = convert(c, Type::scalar(BaseType::Bool), e.where).comps;
            return Value{a.type, select(cc, a.comps, b.comps), true};
          }
          sink_->error(e.where, "X3020", "type mismatch in the conditional expression");
          return errorValue();
        }
        Type rt = arithmeticResult(a.type, b.type, e.where);
        if (!c.type.isScalar()) rt = arithmeticResult(rt, c.type, e.where);
        Value av = convert(a, rt, e.where), bv = convert(b, rt, e.where);
        Type ct = rt;
        ct.base = BaseType::Bool;
        Value cv = convert(c, ct, e.where);
        return Value{rt, select(cv.comps, av.comps, bv.comps), true};
      }
      case ExprKind::Cast: {
        Value v = expr(*e.args[0]);
        return convert(v, e.type, e.where, true);
      }
      case ExprKind::Constructor: return constructor(e);
      case ExprKind::Member: return memberExpr(e);
      case ExprKind::Index: return indexExpr(e);
      case ExprKind::Call: return call(e);
    }
    return errorValue();
  }

  Value unaryExpr(const Expr& e) {
    if (e.op == "++" || e.op == "--") {
      LValue lv = lvalue(*e.args[0]);
      if (!lv.var) return errorValue();
      Value old = readLValue(lv);
      Comps one(old.comps.size(), lit(1));
      Comps nv = op(IrOp::Add, int(old.comps.size()), {old.comps, e.op == "++" ? one : negate(one)});
      writeLValue(lv, nv, e.where);
      return Value{old.type, nv, true};
    }
    Value v = expr(*e.args[0]);
    if (!v.ok) return v;
    if (!v.type.isNumeric()) {
      sink_->error(e.where, "X3022", "scalar, vector, or matrix expected for unary '{}'", e.op);
      return errorValue();
    }
    if (e.op == "+") return v;
    if (e.op == "-") {
      if (v.type.base == BaseType::Bool) v = convert(v, [&] { Type t = v.type; t.base = BaseType::Int; return t; }(), e.where);
      return Value{v.type, negate(v.comps), true};
    }
    if (e.op == "!") {
      Type bt = v.type;
      bt.base = BaseType::Bool;
      Value b = convert(v, bt, e.where);
      Comps out;
      int n = int(b.comps.size());
      Comps r = op(IrOp::Add, n, {Comps(n, lit(1)), negate(b.comps)});
      return Value{bt, r, true};
    }
    sink_->error(e.where, "X3082", "bitwise operations are not supported on this target");
    return errorValue();
  }

  Value binaryExpr(const Expr& e) {
    const std::string& o = e.op;
    if (o == "&&" || o == "||") {
      // HLSL evaluates both sides (no short circuit), per component.
      Value a = expr(*e.args[0]), b = expr(*e.args[1]);
      if (!a.ok || !b.ok) return errorValue();
      Type rt = arithmeticResult(a.type, b.type, e.where);
      rt.base = BaseType::Bool;
      Comps ac = convert(a, rt, e.where).comps, bc = convert(b, rt, e.where).comps;
      int n = int(ac.size());
      Comps r = o == "&&" ? op(IrOp::Mul, n, {ac, bc}) : op(IrOp::Max, n, {ac, bc});
      return Value{rt, r, true};
    }
    Value a = expr(*e.args[0]), b = expr(*e.args[1]);
    return arithmetic(o, a, b, e.where);
  }

  Value arithmetic(const std::string& o, const Value& a, const Value& b, const SourceLocation& at) {
    if (!a.ok || !b.ok) return errorValue();
    if (!a.type.isNumeric() || !b.type.isNumeric()) {
      sink_->error(at, "X3020", "type mismatch: '{}' {} '{}'", a.type.name(), o, b.type.name());
      return errorValue();
    }
    Type rt = arithmeticResult(a.type, b.type, at);
    Type opType = rt;
    bool compare = o == "<" || o == ">" || o == "<=" || o == ">=" || o == "==" || o == "!=";
    Value av = convert(a, opType, at), bv = convert(b, opType, at);
    int n = opType.components();
    const Comps& x = av.comps;
    const Comps& y = bv.comps;
    if (compare) {
      Type bt = rt;
      bt.base = BaseType::Bool;
      Comps r;
      if (o == "<") r = op(IrOp::Slt, n, {x, y});
      else if (o == ">") r = op(IrOp::Slt, n, {y, x});
      else if (o == "<=") r = op(IrOp::Sge, n, {y, x});
      else if (o == ">=") r = op(IrOp::Sge, n, {x, y});
      else {
        Comps eq = op(IrOp::Mul, n, {op(IrOp::Sge, n, {x, y}), op(IrOp::Sge, n, {y, x})});
        r = o == "==" ? eq : op(IrOp::Add, n, {Comps(n, lit(1)), negate(eq)});
      }
      return Value{bt, r, true};
    }
    bool integral = isIntegral(rt.base);
    if (o == "+") return Value{rt, op(IrOp::Add, n, {x, y}), true};
    if (o == "-") return Value{rt, op(IrOp::Add, n, {x, negate(y)}), true};
    if (o == "*") return Value{rt, op(IrOp::Mul, n, {x, y}), true};
    if (o == "/") {
      Comps q = divide(x, y);
      if (integral) q = truncate(q);
      return Value{rt, q, true};
    }
    if (o == "%") {
      // fmod semantics: x - y * trunc(x / y)
      Comps q = truncate(divide(x, y));
      return Value{rt, op(IrOp::Add, n, {x, negate(op(IrOp::Mul, n, {y, q}))}), true};
    }
    sink_->error(at, "X3082", "bitwise operator '{}' is not supported on this target", o);
    return errorValue();
  }

  Comps divide(const Comps& x, const Comps& y) {
    int n = int(x.size());
    if (allLiteral(x) && allLiteral(y)) {
      Comps r(n);
      for (int i = 0; i < n; ++i) r[i] = lit(x[i].k / y[i].k);
      return r;
    }
    Comps rcp;
    for (int i = 0; i < n; ++i) {
      // one rcp per distinct divisor component
      bool dup = false;
      for (int j = 0; j < i; ++j)
        if (y[j] == y[i]) { rcp.push_back(rcp[j]); dup = true; break; }
      if (!dup) rcp.push_back(op(IrOp::Rcp, 1, {Comps{y[i]}})[0]);
    }
    return op(IrOp::Mul, n, {x, rcp});
  }

  Value assignExpr(const Expr& e) {
    LValue lv = lvalue(*e.args[0]);
    Value rhs = expr(*e.args[1]);
    if (!lv.var || !rhs.ok) return errorValue();
    Value result;
    if (e.op == "=") {
      result = convert(rhs, lv.type, e.where);
    } else {
      Value cur = readLValue(lv);
      std::string bop = e.op.substr(0, e.op.size() - 1);
      Value r = arithmetic(bop, cur, rhs, e.where);
      result = convert(r, lv.type, e.where);
    }
    writeLValue(lv, result.comps, e.where);
    return result;
  }

  Value readLValue(const LValue& lv) {
    Value v;
    v.type = lv.type;
    for (int i : lv.indices) v.comps.push_back(lv.var->comps[i]);
    return v;
  }

  void writeLValue(const LValue& lv, const Comps& value, const SourceLocation& at) {
    if (lv.var->isConst || lv.var->uniform) {
      sink_->error(at, "X3025", "l-value specifies const object");
      return;
    }
    uninitialized_.erase(lv.var);
    Comp act = active();
    if (act.literal()) {
      if (act.k == 0) return;
      for (size_t i = 0; i < lv.indices.size() && i < value.size(); ++i) lv.var->comps[lv.indices[i]] = value[i];
      return;
    }
    Comps old;
    for (int i : lv.indices) old.push_back(lv.var->comps[i]);
    Comps sel = select(Comps{act}, value, old);
    for (size_t i = 0; i < lv.indices.size() && i < sel.size(); ++i) lv.var->comps[lv.indices[i]] = sel[i];
  }

  LValue lvalue(const Expr& e) {
    LValue lv;
    switch (e.kind) {
      case ExprKind::Name: {
        Variable* v = lookup(e.op);
        if (!v) { sink_->error(e.where, "X3004", "undeclared identifier '{}'", e.op); return lv; }
        if (v->uniform && v->uniformIndex >= 0) bindUniform(*v);
        lv.var = v;
        lv.type = v->type;
        for (int i = 0; i < int(v->comps.size()); ++i) lv.indices.push_back(i);
        return lv;
      }
      case ExprKind::Member: {
        LValue base = lvalue(*e.args[0]);
        if (!base.var) return base;
        std::vector<int> sel;
        Type t;
        if (!memberSelect(base.type, e.op, e.where, sel, t, true)) return LValue{};
        lv.var = base.var;
        lv.type = t;
        for (int i : sel) lv.indices.push_back(base.indices[i]);
        return lv;
      }
      case ExprKind::Index: {
        LValue base = lvalue(*e.args[0]);
        if (!base.var) return base;
        Value idx = expr(*e.args[1]);
        if (!idx.ok) return LValue{};
        if (!idx.comps[0].literal()) {
          sink_->error(e.where, "X3500", "array reference cannot be used as an l-value unless its index is a literal expression");
          return LValue{};
        }
        int i = literalIndex(idx.comps[0].k);
        std::vector<int> sel;
        Type t;
        if (!indexSelect(base.type, i, e.where, sel, t)) return LValue{};
        lv.var = base.var;
        lv.type = t;
        for (int k : sel) lv.indices.push_back(base.indices[k]);
        return lv;
      }
      default:
        sink_->error(e.where, "X3025", "expression is not an l-value");
        return lv;
    }
  }

  // Member access: struct member or swizzle; `sel` = flat indices into the base.
  bool memberSelect(const Type& t, const std::string& name, const SourceLocation& at, std::vector<int>& sel,
                    Type& out, bool forWrite) {
    if (t.cls == TypeClass::Struct && !t.isArray()) {
      int offset = 0;
      for (const auto& m : t.structDef->members) {
        int n = m.type.flatSize();
        if (m.name == name) {
          for (int i = 0; i < n; ++i) sel.push_back(offset + i);
          out = m.type;
          return true;
        }
        offset += n;
      }
      sink_->error(at, "X3018", "invalid subscript '{}'", name);
      return false;
    }
    if (!t.isNumeric()) {
      sink_->error(at, "X3018", "invalid subscript '{}' on '{}'", name, t.name());
      return false;
    }
    if (t.cls == TypeClass::Matrix) {
      // _m00 / _11 forms, repeated
      size_t i = 0;
      while (i < name.size()) {
        if (name[i] != '_') { sink_->error(at, "X3018", "invalid subscript '{}'", name); return false; }
        int r, c;
        if (i + 3 < name.size() + 0 && name[i + 1] == 'm' && i + 3 <= name.size() - 1 + 1) {
          if (i + 4 > name.size()) { sink_->error(at, "X3018", "invalid subscript '{}'", name); return false; }
          r = name[i + 2] - '0';
          c = name[i + 3] - '0';
          i += 4;
        } else {
          if (i + 3 > name.size()) { sink_->error(at, "X3018", "invalid subscript '{}'", name); return false; }
          r = name[i + 1] - '1';
          c = name[i + 2] - '1';
          i += 3;
        }
        if (r < 0 || r >= t.rows || c < 0 || c >= t.cols) { sink_->error(at, "X3018", "invalid subscript '{}'", name); return false; }
        sel.push_back(r * t.cols + c);
      }
    } else {
      int n = t.components();
      if (name.size() > 4) { sink_->error(at, "X3018", "invalid subscript '{}'", name); return false; }
      bool xyzw = false, rgba = false;
      for (char ch : name) {
        int k = -1;
        switch (ch) {
          case 'x': k = 0; xyzw = true; break; case 'y': k = 1; xyzw = true; break;
          case 'z': k = 2; xyzw = true; break; case 'w': k = 3; xyzw = true; break;
          case 'r': k = 0; rgba = true; break; case 'g': k = 1; rgba = true; break;
          case 'b': k = 2; rgba = true; break; case 'a': k = 3; rgba = true; break;
          default: break;
        }
        if (k < 0 || k >= n) {
          sink_->error(at, "X3018", "invalid subscript '{}' on '{}'", name, t.name());
          return false;
        }
        sel.push_back(k);
      }
      if (xyzw && rgba) { sink_->error(at, "X3018", "invalid subscript '{}': mixes xyzw and rgba", name); return false; }
    }
    if (forWrite) {
      std::set<int> seen(sel.begin(), sel.end());
      if (seen.size() != sel.size()) {
        sink_->error(at, "X3025", "l-value specifies a component more than once");
        return false;
      }
    }
    int n = int(sel.size());
    out = Type::vector(t.base, n);
    if (n == 1) out = Type::scalar(t.base);
    return true;
  }

  bool indexSelect(const Type& t, int i, const SourceLocation& at, std::vector<int>& sel, Type& out) {
    if (t.isArray()) {
      if (i < 0 || i >= t.arraySize) { sink_->error(at, "X3504", "array index {} out of bounds (size {})", i, t.arraySize); return false; }
      int n = t.element->flatSize();
      for (int k = 0; k < n; ++k) sel.push_back(i * n + k);
      out = *t.element;
      return true;
    }
    if (t.cls == TypeClass::Matrix) {
      if (i < 0 || i >= t.rows) { sink_->error(at, "X3504", "matrix row index {} out of bounds", i); return false; }
      for (int c = 0; c < t.cols; ++c) sel.push_back(i * t.cols + c);
      out = Type::vector(t.base, t.cols);
      return true;
    }
    if (t.cls == TypeClass::Vector) {
      if (i < 0 || i >= t.cols) { sink_->error(at, "X3504", "vector index {} out of bounds", i); return false; }
      sel.push_back(i);
      out = Type::scalar(t.base);
      return true;
    }
    sink_->error(at, "X3121", "array, matrix, vector, or indexable object type expected in index expression");
    return false;
  }

  Value memberExpr(const Expr& e) {
    Value base = expr(*e.args[0]);
    if (!base.ok) return base;
    std::vector<int> sel;
    Type t;
    if (base.type.isScalar()) {  // scalar.xxx
      for (char ch : e.op) {
        if (ch != 'x' && ch != 'r') { sink_->error(e.where, "X3018", "invalid subscript '{}'", e.op); return errorValue(); }
        sel.push_back(0);
      }
      t = sel.size() == 1 ? Type::scalar(base.type.base) : Type::vector(base.type.base, int(sel.size()));
      if (sel.size() > 4) { sink_->error(e.where, "X3018", "invalid subscript '{}'", e.op); return errorValue(); }
    } else if (!memberSelect(base.type, e.op, e.where, sel, t, false)) {
      return errorValue();
    }
    Value v;
    v.type = t;
    for (int i : sel) v.comps.push_back(base.comps[i]);
    return v;
  }

  // A literal index as an int; NaN, infinities and values past int's range (x % 0,
  // 1e30) become -1, out of bounds for every array.
  static int literalIndex(float k) { return std::fabs(k) < 1e9f ? int(k) : -1; }

  Value indexExpr(const Expr& e) {
    Value base = expr(*e.args[0]);
    Value idx = expr(*e.args[1]);
    if (!base.ok || !idx.ok) return errorValue();
    if (!idx.comps[0].literal() && idx.type.isNumeric()) {
      std::optional<UniformArray> ua = uniformArray(*e.args[0]);
      if (ua && ua->type.isArray() && registerRows(*ua->type.element) > 0) return relativeIndex(e, *ua, idx);
    }
    if (idx.comps[0].literal()) {
      std::vector<int> sel;
      Type t;
      if (!indexSelect(base.type, literalIndex(idx.comps[0].k), e.where, sel, t)) return errorValue();
      Value v;
      v.type = t;
      for (int i : sel) v.comps.push_back(base.comps[i]);
      return v;
    }
    // A run-time index: a sum of selects over the elements (works in every profile).
    int count = base.type.isArray() ? base.type.arraySize : base.type.cls == TypeClass::Matrix ? base.type.rows
                                                                                              : base.type.components();
    if (count > 64) {
      sink_->error(e.where, "X3500", "dynamic index into an array of {} elements is not supported for {}", count,
                  opt_.version.name());
      return errorValue();
    }
    Value result;
    for (int i = 0; i < count; ++i) {
      std::vector<int> sel;
      Type t;
      if (!indexSelect(base.type, i, e.where, sel, t)) return errorValue();
      Comps elem;
      for (int k : sel) elem.push_back(base.comps[k]);
      if (i == 0) { result.type = t; result.comps = elem; continue; }
      Comps ix = convert(idx, Type::scalar(BaseType::Float), e.where).comps;
      Comps hit = op(IrOp::Mul, 1, {op(IrOp::Sge, 1, {ix, Comps{lit(float(i))}}), op(IrOp::Slt, 1, {ix, Comps{lit(float(i + 1))}})});
      // index >= i selects element i over the earlier ones (indices are whole numbers)
      Comps ge = op(IrOp::Sge, 1, {ix, Comps{lit(float(i))}});
      (void)hit;
      result.comps = select(ge, elem, result.comps);
    }
    return result;
  }

  // uniform[index] with a run-time index: vertex shaders read the element's registers
  // relative to the address register, c[a0.x + first row]; a0.x holds index * (registers
  // per element). Pixel shaders have no address register for constants.
  Value relativeIndex(const Expr& e, const UniformArray& ua, const Value& idx) {
    if (isPixel()) {
      sink_->error(e.where, "X3512", "array index must be a literal expression: {} cannot index constant registers "
                  "with a run-time value", opt_.version.name());
      return errorValue();
    }
    const Type& elem = *ua.type.element;
    const int stride = registerRows(elem);
    // HLSL converts the index to int (toward zero); a negative index is out of bounds
    // and undefined, so floor serves. vs_1_1 loads a0.x with mov, which floors itself.
    Comps ix = convert(idx, Type::scalar(BaseType::Float), e.where).comps;
    const bool vs11 = !opt_.version.atLeast(2, 0);
    if (!isIntegral(idx.type.base) && !(vs11 && stride == 1)) ix = floorOf(ix);
    if (stride > 1) ix = op(IrOp::Mul, 1, {ix, Comps{lit(float(stride))}});
    ir_.uniforms[ua.uniform].used = true;
    std::vector<int> rows;
    for (int r = 0; r < stride; ++r) {
      IrInst inst;
      inst.op = IrOp::UniformRel;
      inst.width = 4;
      inst.srcCount = 1;
      inst.src[0] = source(ix);
      inst.index = ((ua.row + r) << 16) | ua.uniform;
      inst.where = where_;
      std::vector<int> key{int(IrOp::UniformRel), inst.index, inst.src[0].reg, inst.src[0].swizzle[0]};
      if (auto it = cse_.find(key); it != cse_.end()) { rows.push_back(it->second); continue; }
      int reg = emitInst(std::move(inst));
      cse_[key] = reg;
      rows.push_back(reg);
    }
    return Value{elem, layoutRows(elem, rows), true};
  }

  Value constructor(const Expr& e) {
    Comps flat;
    bool ok = true;
    for (const auto& a : e.args) {
      Value v = expr(*a);
      if (!v.ok) { ok = false; continue; }
      if (!v.type.isNumeric()) {
        sink_->error(a->where, "X3014", "incorrect number of arguments to numeric-type constructor");
        ok = false;
        continue;
      }
      Type et = v.type;
      et.base = e.type.base;
      v = convert(v, et, a->where, true);
      flat.insert(flat.end(), v.comps.begin(), v.comps.end());
    }
    if (!ok) { Value r = errorValue(); r.type = e.type; r.comps.assign(std::max(1, e.type.flatSize()), lit(0)); return r; }
    int need = e.type.flatSize();
    if (int(flat.size()) != need) {
      if (flat.size() == 1 && e.type.isNumeric()) {
        flat.assign(need, flat[0]);
      } else {
        sink_->error(e.where, "X3014", "incorrect number of arguments to numeric-type constructor: '{}' needs {} components, got {}",
                    e.type.name(), need, flat.size());
        flat.resize(need, lit(0));
      }
    }
    return Value{e.type, flat, true};
  }

  // ---- calls -----------------------------------------------------------------------------------
  Value call(const Expr& e) {
    // User functions first: a user function may shadow an intrinsic (the wood
    // shader's own smoothstep).
    std::vector<const FunctionDecl*> candidates;
    for (const auto& f : prog_.functions)
      if (f->name == e.op && f->params.size() == e.args.size()) candidates.push_back(f.get());
    if (!candidates.empty()) return userCall(e, candidates);
    std::vector<Value> args;
    for (const auto& a : e.args) args.push_back(expr(*a));
    for (const Value& a : args)
      if (!a.ok) return errorValue();
    std::optional<Value> r = intrinsic(e, args);
    if (r) return *r;
    bool anyUser = false;
    for (const auto& f : prog_.functions) anyUser |= f->name == e.op;
    if (anyUser) sink_->error(e.where, "X3013", "'{}': no matching {}-argument function", e.op, e.args.size());
    else sink_->error(e.where, "X3004", "undeclared identifier '{}'", e.op);
    return errorValue();
  }

  // Cost of converting `from` to parameter type `to` (lower is better; -1 = impossible).
  static int conversionCost(const Type& from, const Type& to) {
    if (from.name() == to.name()) return 0;
    if (to.cls == TypeClass::Struct || from.cls == TypeClass::Struct || to.isArray() || from.isArray()) return -1;
    if (to.cls == TypeClass::Object || from.cls == TypeClass::Object) {
      if (to.cls == TypeClass::Object && from.cls == TypeClass::Object && to.base == from.base) return 1;
      return -1;
    }
    int cost = from.base == to.base ? 0 : 1;
    if (from.components() == to.components() && from.cls == to.cls) return cost;
    if (from.isScalar()) return cost + 2;
    if (from.components() > to.components() && from.cls == to.cls) return cost + 4;  // truncation
    if (from.components() > to.components() && to.isScalar()) return cost + 4;
    return -1;
  }

  Value userCall(const Expr& e, const std::vector<const FunctionDecl*>& candidates) {
    std::vector<Value> args;
    for (const auto& a : e.args) args.push_back(a->kind == ExprKind::Name || a->kind == ExprKind::Member || a->kind == ExprKind::Index ? Value{} : Value{});
    // Evaluate in-arguments once.
    std::vector<Value> values;
    for (const auto& a : e.args) values.push_back(expr(*a));
    for (const Value& v : values)
      if (!v.ok) return errorValue();
    const FunctionDecl* best = nullptr;
    int bestCost = 1 << 30;
    bool ambiguous = false;
    for (const FunctionDecl* f : candidates) {
      int total = 0;
      bool ok = true;
      for (size_t i = 0; i < values.size(); ++i) {
        int c = conversionCost(values[i].type, f->params[i]->type);
        if (c < 0) { ok = false; break; }
        total += c;
      }
      if (!ok) continue;
      if (total < bestCost) { best = f; bestCost = total; ambiguous = false; }
      else if (total == bestCost) ambiguous = true;
    }
    if (!best) {
      sink_->error(e.where, "X3013", "'{}': no matching {}-argument function", e.op, e.args.size());
      return errorValue();
    }
    if (ambiguous) sink_->error(e.where, "X3067", "'{}': ambiguous function call", e.op);
    if (!best->body) {
      sink_->error(e.where, "X3080", "'{}': function is declared but not defined", e.op);
      return errorValue();
    }
    if (callStack_.count(best)) {
      sink_->error(e.where, "X3500", "'{}': recursive functions are not allowed", e.op);
      return errorValue();
    }
    // Bind parameters in a fresh scope chain: only globals are visible inside.
    std::vector<std::map<std::string, Variable*>> savedScopes(scopes_.begin() + 1, scopes_.end());
    scopes_.resize(1);
    scopes_.emplace_back();
    std::vector<std::pair<size_t, Variable*>> outs;
    for (size_t i = 0; i < values.size(); ++i) {
      const VarDecl& p = *best->params[i];
      Variable* v = declareLocal(p.name, p.type, p.where);
      if (p.isIn) v->comps = convert(values[i], p.type, e.args[i]->where).comps;
      if (p.isOut) outs.emplace_back(i, v);
    }
    std::vector<Comp> savedConditions = conditions_;
    functions_.push_back(FunctionFrame{best});
    callStack_.insert(best);
    for (const auto& s : best->body->block) statement(*s);
    callStack_.erase(best);
    FunctionFrame frame = functions_.back();
    functions_.pop_back();
    std::vector<std::pair<size_t, Comps>> outValues;
    for (auto& [i, v] : outs) outValues.emplace_back(i, v->comps);
    scopes_.resize(1);
    for (auto& s : savedScopes) scopes_.push_back(std::move(s));
    conditions_ = savedConditions;
    for (auto& [i, comps] : outValues) {
      LValue lv = lvalue(*e.args[i]);
      if (lv.var) writeLValue(lv, convert(Value{best->params[i]->type, comps, true}, lv.type, e.args[i]->where).comps, e.where);
    }
    if (best->returnType.isVoid()) {
      Value v; v.type = Type(); v.comps = {lit(0)}; return v;
    }
    if (!frame.hasReturnValue) {
      if (!best->syntaxErrors && !tooDeepReported_) sink_->error(best->where, "X3080", "'{}': function must return a value", best->name);
      return errorValue();
    }
    return Value{best->returnType, frame.returnValue, true};
  }

  // ---- intrinsics ------------------------------------------------------------------------------
  Value floatOf(const Value& v, const SourceLocation& at) {
    if (!v.type.isNumeric()) return v;
    if (v.type.base == BaseType::Float || v.type.base == BaseType::Half || v.type.base == BaseType::Double) return v;
    Type t = v.type;
    t.base = BaseType::Float;
    return convert(v, t, at);
  }

  // Common type of several numeric arguments (HLSL's intrinsic promotion).
  Type commonType(const std::vector<Value>& args, const SourceLocation& at) {
    Type t = args[0].type;
    for (size_t i = 1; i < args.size(); ++i) t = arithmeticResult(t, args[i].type, at);
    if (isIntegral(t.base)) t.base = BaseType::Float;
    return t;
  }

  bool expectArgs(const Expr& e, const std::vector<Value>& args, size_t n) {
    if (args.size() != n) {
      sink_->error(e.where, "X3013", "'{}': intrinsic function takes {} argument{}, {} given", e.op, n, n == 1 ? "" : "s",
                  args.size());
      return false;
    }
    for (const Value& a : args)
      if (!a.type.isNumeric() && !a.type.isSampler() && !(opt_.compat() && a.type.cls == TypeClass::Object)) {
        sink_->error(e.where, "X3013", "'{}': no matching intrinsic overload for '{}'", e.op, a.type.name());
        return false;
      }
    return true;
  }

  Comps rsqrt(const Comps& a) { return scalarOp(IrOp::Rsq, a); }
  Comps sqrtOf(const Comps& a) {
    // sqrt(x) = 1 / rsq(x), as fxc emits it
    Comps r = scalarOp(IrOp::Rsq, a);
    return scalarOp(IrOp::Rcp, r);
  }
  Comps lengthOf(const Comps& a) { return sqrtOf(dot(a, a)); }
  Comps normalizeOf(const Comps& a) {
    int n = int(a.size());
    if (n == 3 && !allLiteral(a)) return op(IrOp::Nrm, 3, {a});
    Comps inv = rsqrt(dot(a, a));
    return op(IrOp::Mul, n, {a, Comps(n, inv[0])});
  }
  Comps saturateOf(const Comps& a) { return op(IrOp::Mov, int(a.size()), {a}, true); }
  Comps lerpOf(const Comps& a, const Comps& b, const Comps& s) {
    int n = int(a.size());
    // a + s * (b - a)
    return op(IrOp::Mad, n, {s, op(IrOp::Add, n, {b, negate(a)}), a});
  }
  Comps expOf(const Comps& a, float scale) {
    int n = int(a.size());
    Comps x = scale == 1 ? a : op(IrOp::Mul, n, {a, Comps(n, lit(scale))});
    return scalarOp(IrOp::Exp2, x);
  }
  Comps logOf(const Comps& a, float scale) {
    int n = int(a.size());
    Comps l = scalarOp(IrOp::Log2, a);
    return scale == 1 ? l : op(IrOp::Mul, n, {l, Comps(n, lit(scale))});
  }

  // sin and cos of each component (first: sin, second: cos). The argument is reduced to
  // [-pi, pi) once for the whole vector: r = frc(x / 2pi + 0.5) * 2pi - pi, which differs
  // from x by a whole number of turns. SM2+ then runs one sincos per component (cos in .x,
  // sin in .y), shared by sin, cos, tan and sincos of the same value. vs_1_1 has no
  // sincos: a series in the half angle h = r / 2 in [-pi/2, pi/2), as fxc lowers it:
  //   sin h = h (1 - h^2/3! + h^4/5! - h^6/7! + h^8/9!)   (next term h^11/11! < 3.6e-6)
  //   cos h = 1 - h^2/2! + h^4/4! - h^6/6! + h^8/8!       (next term h^10/10! < 2.6e-5)
  //   sin r = 2 sin h cos h, cos r = 1 - 2 sin^2 h.
  std::pair<Comps, Comps> sinCosOf(const Comps& a) {
    int n = int(a.size());
    if (allLiteral(a)) {
      Comps s, c;
      for (const Comp& k : a) { s.push_back(lit(std::sin(k.k))); c.push_back(lit(std::cos(k.k))); }
      return {s, c};
    }
    auto splat = [&](float v) { return Comps(n, lit(v)); };
    Comps turns = op(IrOp::Frc, n, {op(IrOp::Mad, n, {a, splat(0.159154943f), splat(0.5f)})});
    if (opt_.version.major >= 2) {
      Comps r = op(IrOp::Mad, n, {turns, splat(6.28318548f), splat(-3.14159274f)});
      Comps s, c;
      for (int i = 0; i < n; ++i) {
        Comps sc = op(IrOp::SinCos, 2, {Comps{r[i]}});
        c.push_back(sc[0]);
        s.push_back(sc[1]);
      }
      return {s, c};
    }
    Comps h = op(IrOp::Mad, n, {turns, splat(3.14159274f), splat(-1.57079637f)});
    Comps h2 = op(IrOp::Mul, n, {h, h});
    auto series = [&](std::initializer_list<float> k) {  // highest power first
      auto it = k.begin();
      Comps p = splat(*it++);
      for (; it != k.end(); ++it) p = op(IrOp::Mad, n, {p, h2, splat(*it)});
      return p;
    };
    Comps sinH = op(IrOp::Mul, n, {h, series({1 / 362880.0f, -1 / 5040.0f, 1 / 120.0f, -1 / 6.0f, 1.0f})});
    Comps cosH = series({1 / 40320.0f, -1 / 720.0f, 1 / 24.0f, -0.5f, 1.0f});
    Comps sinH2 = op(IrOp::Add, n, {sinH, sinH});  // 2 sin h
    Comps s = op(IrOp::Mul, n, {sinH2, cosH});
    Comps c = op(IrOp::Mad, n, {negate(sinH2), sinH, splat(1.0f)});
    return {s, c};
  }

  // Polynomial atan on [-1, 1] scaled to the full range (max error ~1e-5).
  Comps atanOf(const Comps& y, const Comps* x) {
    int n = int(y.size());
    Comps xx = x ? *x : Comps(n, lit(1));
    Comps ay = op(IrOp::Abs, n, {y}), ax = op(IrOp::Abs, n, {xx});
    Comps mx = op(IrOp::Max, n, {ay, ax}), mn = op(IrOp::Min, n, {ay, ax});
    Comps t = op(IrOp::Mul, n, {mn, scalarOp(IrOp::Rcp, mx)});
    Comps t2 = op(IrOp::Mul, n, {t, t});
    // atan(t) ≈ t * (0.9998660 + t²(-0.3302995 + t²(0.1801410 + t²(-0.0851330 + t² 0.0208351))))
    Comps p = Comps(n, lit(0.0208351f));
    for (float k : {-0.0851330f, 0.1801410f, -0.3302995f, 0.9998660f}) p = op(IrOp::Mad, n, {p, t2, Comps(n, lit(k))});
    Comps r = op(IrOp::Mul, n, {p, t});
    // |y| > |x|: pi/2 - r
    Comps swap = op(IrOp::Slt, n, {ax, ay});
    r = select(swap, op(IrOp::Add, n, {Comps(n, lit(1.5707963f)), negate(r)}), r);
    if (x) {
      Comps xneg = op(IrOp::Slt, n, {xx, Comps(n, lit(0))});
      r = select(xneg, op(IrOp::Add, n, {Comps(n, lit(3.1415927f)), negate(r)}), r);
    }
    Comps yneg = op(IrOp::Slt, n, {y, Comps(n, lit(0))});
    return select(yneg, negate(r), r);
  }

  Comps asinOf(const Comps& a) {
    // asin(x) = atan2(x, sqrt(1 - x²))
    int n = int(a.size());
    Comps c = sqrtOf(op(IrOp::Mad, n, {negate(a), a, Comps(n, lit(1))}));
    return atanOf(a, &c);
  }

  std::optional<Value> intrinsic(const Expr& e, std::vector<Value>& args) {
    const std::string& name = e.op;
    SourceLocation at = e.where;
    auto unaryFloat = [&](auto fn) -> std::optional<Value> {
      if (!expectArgs(e, args, 1)) return errorValue();
      Value a = floatOf(args[0], at);
      return Value{a.type, fn(a.comps), true};
    };
    auto sameTypes = [&](size_t n) -> std::optional<Type> {
      if (!expectArgs(e, args, n)) return std::nullopt;
      Type t = commonType(args, at);
      for (Value& a : args) a = convert(a, t, at);
      return t;
    };
    int width = 0;
    auto W = [&](const Type& t) { return t.components(); };
    // Geometric intrinsics take vectors (and scalars), never matrices.
    if (name == "normalize" || name == "length" || name == "len" || name == "distance" || name == "reflect" ||
        name == "refract" || name == "faceforward") {
      for (const Value& a : args)
        if (a.type.cls == TypeClass::Matrix) {
          sink_->error(at, "X3013", "'{}': vector arguments expected, found '{}'", name, a.type.name());
          return errorValue();
        }
    }

    if (name == "abs") return unaryFloat([&](const Comps& a) { return op(IrOp::Abs, int(a.size()), {a}); });
    if (name == "saturate") return unaryFloat([&](const Comps& a) { return saturateOf(a); });
    if (name == "frac" || (opt_.compat() && name == "frc")) return unaryFloat([&](const Comps& a) { return op(IrOp::Frc, int(a.size()), {a}); });
    if (name == "floor") return unaryFloat([&](const Comps& a) { return floorOf(a); });
    if (name == "ceil") return unaryFloat([&](const Comps& a) { return negate(floorOf(negate(a))); });
    if (name == "trunc") return unaryFloat([&](const Comps& a) { return truncate(a); });
    if (name == "round") return unaryFloat([&](const Comps& a) {
      int n = int(a.size());
      return floorOf(op(IrOp::Add, n, {a, Comps(n, lit(0.5f))}));
    });
    if (name == "sqrt") return unaryFloat([&](const Comps& a) { return sqrtOf(a); });
    if (name == "rsqrt") return unaryFloat([&](const Comps& a) { return rsqrt(a); });
    if (name == "rcp") return unaryFloat([&](const Comps& a) { return scalarOp(IrOp::Rcp, a); });
    if (name == "exp") return unaryFloat([&](const Comps& a) { return expOf(a, 1.44269504f); });
    if (name == "exp2") return unaryFloat([&](const Comps& a) { return expOf(a, 1); });
    if (name == "log") return unaryFloat([&](const Comps& a) { return logOf(a, 0.69314718f); });
    if (name == "log2") return unaryFloat([&](const Comps& a) { return logOf(a, 1); });
    if (name == "log10") return unaryFloat([&](const Comps& a) { return logOf(a, 0.30103f); });
    if (name == "sin") return unaryFloat([&](const Comps& a) { return sinCosOf(a).first; });
    if (name == "cos") return unaryFloat([&](const Comps& a) { return sinCosOf(a).second; });
    if (name == "tan") return unaryFloat([&](const Comps& a) {
      // sin / cos from one shared sincos per component
      int n = int(a.size());
      auto [sn, cs] = sinCosOf(a);
      return op(IrOp::Mul, n, {sn, scalarOp(IrOp::Rcp, cs)});
    });
    if (name == "sinh" || name == "cosh" || name == "tanh") return unaryFloat([&](const Comps& a) {
      int n = int(a.size());
      Comps ep = expOf(a, 1.44269504f), en = expOf(negate(a), 1.44269504f);
      Comps half(n, lit(0.5f));
      Comps s = op(IrOp::Mul, n, {op(IrOp::Add, n, {ep, negate(en)}), half});
      Comps c = op(IrOp::Mul, n, {op(IrOp::Add, n, {ep, en}), half});
      if (name == "sinh") return s;
      if (name == "cosh") return c;
      return op(IrOp::Mul, n, {s, scalarOp(IrOp::Rcp, c)});
    });
    if (name == "atan") return unaryFloat([&](const Comps& a) { return atanOf(a, nullptr); });
    if (name == "asin") return unaryFloat([&](const Comps& a) { return asinOf(a); });
    if (name == "acos") return unaryFloat([&](const Comps& a) {
      int n = int(a.size());
      return op(IrOp::Add, n, {Comps(n, lit(1.5707963f)), negate(asinOf(a))});
    });
    if (name == "degrees") return unaryFloat([&](const Comps& a) { int n = int(a.size()); return op(IrOp::Mul, n, {a, Comps(n, lit(57.29578f))}); });
    if (name == "radians") return unaryFloat([&](const Comps& a) { int n = int(a.size()); return op(IrOp::Mul, n, {a, Comps(n, lit(0.017453292f))}); });
    if (name == "sign") return unaryFloat([&](const Comps& a) {
      int n = int(a.size());
      Comps z(n, lit(0));
      return op(IrOp::Add, n, {op(IrOp::Slt, n, {z, a}), negate(op(IrOp::Slt, n, {a, z}))});
    });
    if (name == "isnan" || name == "isinf" || name == "isfinite") {
      if (!expectArgs(e, args, 1)) return errorValue();
      Value a = floatOf(args[0], at);
      int n = W(a.type);
      Type bt = a.type;
      bt.base = BaseType::Bool;
      Comps r;
      // Compare x itself with cmp (no subtraction: inf - inf would be NaN).
      Comps one(n, lit(1)), zero(n, lit(0));
      Comps nonNegative = op(IrOp::Cmp, n, {a.comps, one, zero});
      Comps nonPositive = op(IrOp::Cmp, n, {negate(a.comps), one, zero});
      Comps nan = op(IrOp::Add, n, {one, negate(op(IrOp::Max, n, {nonNegative, nonPositive}))});
      Comps absA = op(IrOp::Abs, n, {a.comps});
      Comps inf = op(IrOp::Cmp, n, {op(IrOp::Add, n, {absA, Comps(n, lit(-3.4028235e38f))}), one, zero});
      if (name == "isnan") r = nan;
      else if (name == "isinf") r = inf;
      else r = op(IrOp::Add, n, {one, negate(op(IrOp::Add, n, {inf, nan}))});
      return Value{bt, r, true};
    }
    if (name == "normalize") return unaryFloat([&](const Comps& a) { return normalizeOf(a); });
    if (name == "length") {
      if (!expectArgs(e, args, 1)) return errorValue();
      Value a = floatOf(args[0], at);
      return Value{Type::scalar(BaseType::Float), lengthOf(a.comps), true};
    }
    if (opt_.compat() && name == "len") {
      if (!expectArgs(e, args, 1)) return errorValue();
      Value a = floatOf(args[0], at);
      return Value{Type::scalar(BaseType::Float), lengthOf(a.comps), true};
    }
    if (name == "all" || name == "any") {
      if (!expectArgs(e, args, 1)) return errorValue();
      Comps b = convert(args[0], [&] { Type t = args[0].type; t.base = BaseType::Bool; return t; }(), at).comps;
      Comps r{b[0]};
      for (size_t i = 1; i < b.size(); ++i) r = op(name == "all" ? IrOp::Mul : IrOp::Max, 1, {r, Comps{b[i]}});
      return Value{Type::scalar(BaseType::Bool), r, true};
    }
    if (name == "min" || name == "max") {
      auto t = sameTypes(2);
      if (!t) return errorValue();
      return Value{*t, op(name == "min" ? IrOp::Min : IrOp::Max, W(*t), {args[0].comps, args[1].comps}), true};
    }
    if (name == "pow") {
      auto t = sameTypes(2);
      if (!t) return errorValue();
      return Value{*t, scalarOp(IrOp::Pow, args[0].comps, &args[1].comps), true};
    }
    if (name == "fmod") {
      auto t = sameTypes(2);
      if (!t) return errorValue();
      return arithmetic("%", args[0], args[1], at);
    }
    if (name == "atan2") {
      auto t = sameTypes(2);
      if (!t) return errorValue();
      return Value{*t, atanOf(args[0].comps, &args[1].comps), true};
    }
    if (name == "step") {
      auto t = sameTypes(2);
      if (!t) return errorValue();
      return Value{*t, op(IrOp::Sge, W(*t), {args[1].comps, args[0].comps}), true};  // x >= a
    }
    if (name == "ldexp") {
      auto t = sameTypes(2);
      if (!t) return errorValue();
      return Value{*t, op(IrOp::Mul, W(*t), {args[0].comps, expOf(args[1].comps, 1)}), true};
    }
    if (name == "distance") {
      auto t = sameTypes(2);
      if (!t) return errorValue();
      int n = W(*t);
      return Value{Type::scalar(BaseType::Float), lengthOf(op(IrOp::Add, n, {args[0].comps, negate(args[1].comps)})), true};
    }
    if (name == "dot") {
      if (!expectArgs(e, args, 2)) return errorValue();
      Type t = commonType(args, at);
      if (t.cls == TypeClass::Matrix) { sink_->error(at, "X3013", "dot: vector arguments expected"); return errorValue(); }
      Value a = convert(args[0], t, at), b = convert(args[1], t, at);
      return Value{Type::scalar(t.base), dot(a.comps, b.comps), true};
    }
    if (name == "cross") {
      if (!expectArgs(e, args, 2)) return errorValue();
      Type t = Type::vector(BaseType::Float, 3);
      Value a = convert(args[0], t, at), b = convert(args[1], t, at);
      if (allLiteral(a.comps) && allLiteral(b.comps)) {
        auto k = [&](int i, const Value& v) { return v.comps[i].k; };
        return Value{t, {lit(k(1, a) * k(2, b) - k(2, a) * k(1, b)), lit(k(2, a) * k(0, b) - k(0, a) * k(2, b)),
                         lit(k(0, a) * k(1, b) - k(1, a) * k(0, b))}, true};
      }
      return Value{t, op(IrOp::Crs, 3, {a.comps, b.comps}), true};
    }
    if (name == "reflect") {
      // i - 2 * n * dot(n, i)
      auto t = sameTypes(2);
      if (!t) return errorValue();
      int n = W(*t);
      Comps d = dot(args[1].comps, args[0].comps);
      Comps two = op(IrOp::Add, 1, {d, d});
      return Value{*t, op(IrOp::Mad, n, {negate(Comps(n, two[0])), args[1].comps, args[0].comps}), true};
    }
    if (name == "refract") {
      if (!expectArgs(e, args, 3)) return errorValue();
      Type t = commonType({args[0], args[1]}, at);
      int n = W(t);
      Comps i = convert(args[0], t, at).comps, nn = convert(args[1], t, at).comps;
      Comps eta = convert(args[2], Type::scalar(BaseType::Float), at).comps;
      // k = 1 - eta² (1 - dot(n,i)²); r = k < 0 ? 0 : eta*i - (eta*dot(n,i) + sqrt(k)) * n
      Comps d = dot(nn, i);
      Comps k = op(IrOp::Add, 1, {Comps{lit(1)}, negate(op(IrOp::Mul, 1, {op(IrOp::Mul, 1, {eta, eta}),
                                                                    op(IrOp::Mad, 1, {negate(d), d, Comps{lit(1)}})}))});
      Comps f = op(IrOp::Mad, 1, {eta, d, sqrtOf(k)});
      Comps r = op(IrOp::Add, n, {op(IrOp::Mul, n, {Comps(n, eta[0]), i}), negate(op(IrOp::Mul, n, {Comps(n, f[0]), nn}))});
      Comps valid = op(IrOp::Sge, 1, {k, Comps{lit(0)}});
      return Value{t, select(valid, r, Comps(n, lit(0))), true};
    }
    if (name == "faceforward") {
      auto t = sameTypes(3);
      if (!t) return errorValue();
      // -n * sign(dot(i, ng))
      Comps d = dot(args[1].comps, args[2].comps);
      Comps neg = op(IrOp::Slt, 1, {d, Comps{lit(0)}});
      return Value{*t, select(neg, args[0].comps, negate(args[0].comps)), true};
    }
    if (name == "lerp") {
      auto t = sameTypes(3);
      if (!t) return errorValue();
      return Value{*t, lerpOf(args[0].comps, args[1].comps, args[2].comps), true};
    }
    if (name == "clamp") {
      auto t = sameTypes(3);
      if (!t) return errorValue();
      int n = W(*t);
      return Value{*t, op(IrOp::Min, n, {op(IrOp::Max, n, {args[0].comps, args[1].comps}), args[2].comps}), true};
    }
    if (name == "mad") {
      auto t = sameTypes(3);
      if (!t) return errorValue();
      return Value{*t, op(IrOp::Mad, W(*t), {args[0].comps, args[1].comps, args[2].comps}), true};
    }
    if (name == "smoothstep") {
      auto t = sameTypes(3);
      if (!t) return errorValue();
      int n = W(*t);
      // t = saturate((x - a) / (b - a)); t * t * (3 - 2t)
      Comps s = saturateOf(divide(op(IrOp::Add, n, {args[2].comps, negate(args[0].comps)}),
                                  op(IrOp::Add, n, {args[1].comps, negate(args[0].comps)})));
      Comps poly = op(IrOp::Mad, n, {Comps(n, lit(-2)), s, Comps(n, lit(3))});
      return Value{*t, op(IrOp::Mul, n, {op(IrOp::Mul, n, {s, s}), poly}), true};
    }
    if (name == "clip") {
      if (!expectArgs(e, args, 1)) return errorValue();
      if (!isPixel()) { sink_->error(at, "X3539", "clip is only valid in pixel shaders"); return errorValue(); }
      Value a = floatOf(args[0], at);
      Comp act = active();
      Comps c = a.comps;
      if (!(act.literal() && act.k != 0)) c = select(Comps{act}, c, Comps(c.size(), lit(0)));
      kill(c);
      Value v; v.type = Type(); v.comps = {lit(0)};
      return v;
    }
    if (name == "lit") {
      if (!expectArgs(e, args, 3)) return errorValue();
      Comps nl = convert(args[0], Type::scalar(BaseType::Float), at).comps;
      Comps nh = convert(args[1], Type::scalar(BaseType::Float), at).comps;
      Comps m = convert(args[2], Type::scalar(BaseType::Float), at).comps;
      // (1, max(nl,0), (nl < 0 || nh < 0) ? 0 : pow(nh, m), 1)
      Comps diff = op(IrOp::Max, 1, {nl, Comps{lit(0)}});
      Comps spec = scalarOp(IrOp::Pow, op(IrOp::Max, 1, {nh, Comps{lit(0)}}), &m);
      Comps neg = op(IrOp::Max, 1, {op(IrOp::Slt, 1, {nl, Comps{lit(0)}}), op(IrOp::Slt, 1, {nh, Comps{lit(0)}})});
      spec = select(neg, Comps{lit(0)}, spec);
      return Value{Type::vector(BaseType::Float, 4), {lit(1), diff[0], spec[0], lit(1)}, true};
    }
    if (name == "D3DCOLORtoUBYTE4") {
      if (!expectArgs(e, args, 1)) return errorValue();
      Comps c = convert(args[0], Type::vector(BaseType::Float, 4), at).comps;
      Comps bgra{c[2], c[1], c[0], c[3]};
      Comps scaled = op(IrOp::Mul, 4, {bgra, Comps(4, lit(255.001953f))});
      Type it = Type::vector(BaseType::Int, 4);
      return Value{it, truncate(scaled), true};
    }
    if (name == "ddx" || name == "ddy") {
      if (!expectArgs(e, args, 1)) return errorValue();
      if (!isPixel()) { sink_->error(at, "X3537", "{} is not available in vertex shaders", name); return errorValue(); }
      if (!opt_.version.atLeast(2, 1)) {
        sink_->error(at, "X3537", "{} needs ps_2_x or ps_3_0; {} has no gradient instructions", name, opt_.version.name());
        return errorValue();
      }
      Value a = floatOf(args[0], at);
      return Value{a.type, op(name == "ddx" ? IrOp::Dsx : IrOp::Dsy, W(a.type), {a.comps}), true};
    }
    if (name == "noise") {
      sink_->error(at, "X3533", "noise is not available in shaders; it only runs in texture fills");
      return errorValue();
    }
    if (name == "transpose") {
      if (!expectArgs(e, args, 1)) return errorValue();
      const Type& t = args[0].type;
      if (t.cls != TypeClass::Matrix) return args[0];
      Type rt = Type::matrix(t.base, t.cols, t.rows);
      Comps out;
      for (int r = 0; r < t.cols; ++r)
        for (int c = 0; c < t.rows; ++c) out.push_back(args[0].comps[c * t.cols + r]);
      return Value{rt, out, true};
    }
    if (name == "determinant") {
      if (!expectArgs(e, args, 1)) return errorValue();
      const Type& t = args[0].type;
      if (t.cls != TypeClass::Matrix || t.rows != t.cols) { sink_->error(at, "X3013", "determinant needs a square matrix"); return errorValue(); }
      return Value{Type::scalar(BaseType::Float), determinant(args[0].comps, t.rows), true};
    }
    if (name == "modf") {
      if (!expectArgs(e, args, 2)) return errorValue();
      Value a = floatOf(args[0], at);
      Comps ip = truncate(a.comps);
      LValue lv = lvalue(*e.args[1]);
      if (lv.var) writeLValue(lv, convert(Value{a.type, ip, true}, lv.type, at).comps, at);
      return Value{a.type, op(IrOp::Add, W(a.type), {a.comps, negate(ip)}), true};
    }
    if (name == "frexp") {
      if (!expectArgs(e, args, 2)) return errorValue();
      Value a = floatOf(args[0], at);
      int n = W(a.type);
      // exponent = floor(log2|x|) + 1; mantissa = x / 2^exponent
      Comps ex = op(IrOp::Add, n, {floorOf(logOf(op(IrOp::Abs, n, {a.comps}), 1)), Comps(n, lit(1))});
      LValue lv = lvalue(*e.args[1]);
      if (lv.var) writeLValue(lv, convert(Value{a.type, ex, true}, lv.type, at).comps, at);
      return Value{a.type, op(IrOp::Mul, n, {a.comps, expOf(negate(ex), 1)}), true};
    }
    if (name == "sincos") {
      if (!expectArgs(e, args, 3)) return errorValue();
      Value a = floatOf(args[0], at);
      auto [s, c] = sinCosOf(a.comps);
      LValue ls = lvalue(*e.args[1]), lc = lvalue(*e.args[2]);
      if (ls.var) writeLValue(ls, convert(Value{a.type, s, true}, ls.type, at).comps, at);
      if (lc.var) writeLValue(lc, convert(Value{a.type, c, true}, lc.type, at).comps, at);
      Value v; v.type = Type(); v.comps = {lit(0)};
      return v;
    }
    if (name == "mul") {
      if (!expectArgs(e, args, 2)) return errorValue();
      return mul(args[0], args[1], at);
    }
    if (auto t = textureIntrinsic(e, args)) return t;
    (void)width;
    return std::nullopt;
  }

  Comps determinant(const Comps& m, int n) {
    auto at = [&](int r, int c) { return Comps{m[r * n + c]}; };
    auto mul1 = [&](const Comps& a, const Comps& b) { return op(IrOp::Mul, 1, {a, b}); };
    auto sub1 = [&](const Comps& a, const Comps& b) { return op(IrOp::Add, 1, {a, negate(b)}); };
    if (n == 1) return at(0, 0);
    if (n == 2) return sub1(mul1(at(0, 0), at(1, 1)), mul1(at(0, 1), at(1, 0)));
    Comps sum{lit(0)};
    for (int c = 0; c < n; ++c) {
      Comps minor;
      for (int r = 1; r < n; ++r)
        for (int k = 0; k < n; ++k)
          if (k != c) minor.push_back(m[r * n + k]);
      Comps term = mul1(at(0, c), determinant(minor, n - 1));
      sum = (c % 2 == 0) ? op(IrOp::Add, 1, {sum, term}) : sub1(sum, term);
    }
    return sum;
  }

  // True when every component in `c` reads one virtual register (no gather needed).
  static bool singleSource(const Comps& c) {
    for (const Comp& k : c)
      if (k.literal() || k.reg != c[0].reg) return false;
    return true;
  }

  // mul() with HLSL's rules: vectors are rows on the left, columns on the right.
  Value mul(const Value& av, const Value& bv, const SourceLocation& at) {
    Value a = floatOf(av, at), b = floatOf(bv, at);
    const Type& ta = a.type;
    const Type& tb = b.type;
    if (ta.isScalar() || tb.isScalar()) return arithmetic("*", a, b, at);
    auto row = [](const Value& m, int r) {
      Comps out;
      for (int c = 0; c < m.type.cols; ++c) out.push_back(m.comps[r * m.type.cols + c]);
      return out;
    };
    auto col = [](const Value& m, int c, int rows) {
      Comps out;
      for (int r = 0; r < rows; ++r) out.push_back(m.comps[r * m.type.cols + c]);
      return out;
    };
    auto asMatrix = [](const Value& v, bool rowVector) {
      Value m = v;
      if (v.type.cls != TypeClass::Matrix) {
        int n = v.type.components();
        m.type = rowVector ? Type::matrix(v.type.base, 1, n) : Type::matrix(v.type.base, n, 1);
      }
      return m;
    };
    Value ma = asMatrix(a, true), mb = asMatrix(b, false);
    int inner = std::min(ma.type.cols, mb.type.rows);
    if (ma.type.cols != mb.type.rows) warnTruncation(at);
    int R = ma.type.rows, C = mb.type.cols;
    Comps out(size_t(R) * C);
    for (int r = 0; r < R; ++r) {
      Comps ar = row(ma, r);
      ar.resize(inner);
      // Prefer dot products when B's columns are whole registers (column_major
      // uniforms); otherwise a mul/mad chain over B's rows.
      bool colsWhole = true, rowsWhole = true;
      for (int c = 0; c < C; ++c) {
        Comps bc = col(mb, c, inner);
        if (!singleSource(bc)) colsWhole = false;
      }
      for (int k = 0; k < inner; ++k) {
        Comps br = row(mb, k);
        if (!singleSource(br)) rowsWhole = false;
      }
      if (colsWhole || !rowsWhole || C == 1) {
        for (int c = 0; c < C; ++c) out[size_t(r) * C + c] = dot(ar, col(mb, c, inner))[0];
      } else {
        Comps acc = op(IrOp::Mul, C, {Comps(C, ar[0]), row(mb, 0)});
        for (int k = 1; k < inner; ++k) acc = op(IrOp::Mad, C, {Comps(C, ar[k]), row(mb, k), acc});
        for (int c = 0; c < C; ++c) out[size_t(r) * C + c] = acc[c];
      }
    }
    Type rt;
    if (ta.cls != TypeClass::Matrix && tb.cls != TypeClass::Matrix) rt = Type::scalar(BaseType::Float);
    else if (ta.cls != TypeClass::Matrix) { rt = Type::vector(BaseType::Float, C); if (C == 1) rt.cls = TypeClass::Vector; }
    else if (tb.cls != TypeClass::Matrix) { rt = Type::vector(BaseType::Float, R); if (R == 1) rt.cls = TypeClass::Vector; }
    else rt = Type::matrix(BaseType::Float, R, C);
    return Value{rt, out, true};
  }

  std::optional<Value> textureIntrinsic(const Expr& e, std::vector<Value>& args) {
    std::string name = e.op;
    const SourceLocation& at = e.where;
    if (opt_.compat()) {
      if (name == "sample1d") name = "tex1D";
      else if (name == "sample2d") name = "tex2D";
      else if (name == "sample3d") name = "tex3D";
      else if (name == "samplecube") name = "texCUBE";
    }
    static const std::map<std::string, std::pair<SamplerDim, int>> bases = {
        {"tex1D", {SamplerDim::Dim1D, 1}}, {"tex2D", {SamplerDim::Dim2D, 2}},
        {"tex3D", {SamplerDim::Dim3D, 3}}, {"texCUBE", {SamplerDim::Cube, 3}}};
    std::string base = name, variant;
    for (const char* suffix : {"proj", "bias", "lod", "grad"})
      if (name.size() > std::strlen(suffix) && name.compare(name.size() - std::strlen(suffix), std::string::npos, suffix) == 0) {
        base = name.substr(0, name.size() - std::strlen(suffix));
        variant = suffix;
        break;
      }
    auto it = bases.find(base);
    if (it == bases.end()) return std::nullopt;
    size_t want = variant == "grad" ? 4 : 2;
    if (args.size() != want) {
      sink_->error(at, "X3013", "'{}': intrinsic function takes {} arguments", name, want);
      return errorValue();
    }
    bool textureAsSampler = opt_.compat() && args[0].type.cls == TypeClass::Object && args[0].type.base == BaseType::Texture;
    if ((!args[0].type.isSampler() && !textureAsSampler) || args[0].comps.empty() || !args[0].comps[0].sampler) {
      sink_->error(at, "X3013", "'{}': first argument must be a sampler", name);
      return errorValue();
    }
    int sampler = int(args[0].comps[0].k);
    if (sampler < 0) { sink_->error(at, "X3013", "'{}': sampler is not a global sampler", name); return errorValue(); }
    SamplerDim dim = it->second.first;
    IrSampler& s = ir_.samplers[sampler];
    if (s.dim == SamplerDim::Any) s.dim = dim;
    IrOp o = IrOp::Tex;
    int coordWidth = it->second.second;
    if (variant == "proj") { o = IrOp::TexProj; coordWidth = 4; }
    if (variant == "bias") { o = IrOp::TexBias; coordWidth = 4; }
    if (variant == "lod") { o = IrOp::TexLod; coordWidth = 4; }
    if (variant == "grad") o = IrOp::TexGrad;
    if (!isPixel() && o != IrOp::TexLod) {
      sink_->error(at, "X3537", "'{}' is not available in vertex shaders; use tex*lod (vs_3_0)", name);
      return errorValue();
    }
    if (!isPixel() && !opt_.version.atLeast(3, 0)) {
      sink_->error(at, "X3537", "vertex texture fetch needs vs_3_0, not {}", opt_.version.name());
      return errorValue();
    }
    if (o == IrOp::TexLod && isPixel() && !opt_.version.atLeast(3, 0)) {
      sink_->error(at, "X3537", "'{}' needs ps_3_0 (texldl), not {}", name, opt_.version.name());
      return errorValue();
    }
    if (o == IrOp::TexGrad && !opt_.version.atLeast(2, 1)) {
      sink_->error(at, "X3537", "'{}' needs ps_2_x or ps_3_0 (texldd), not {}", name, opt_.version.name());
      return errorValue();
    }
    Value coord = floatOf(args[1], at);
    if (coord.type.components() < coordWidth) {
      sink_->error(at, "X3017", "'{}': texture coordinate needs {} components, '{}' has {}", name, coordWidth,
                  coord.type.name(), coord.type.components());
      return errorValue();
    }
    Comps cc = coord.comps;
    cc.resize(coordWidth);
    // texld reads as many coordinates as the sampler has dimensions: a shorter lookup
    // (the pre-release sample1d on a volume texture) reads zeros in the others, never
    // whatever the register held before.
    const size_t samplerCoords = s.dim == SamplerDim::Dim1D ? 1 : s.dim == SamplerDim::Dim2D ? 2 : 3;
    while (o == IrOp::Tex && cc.size() < samplerCoords) cc.push_back(lit(0));
    IrInst inst;
    inst.op = o;
    inst.width = 4;
    inst.sampler = sampler;
    inst.index = coordWidth;
    inst.srcCount = 1;
    inst.src[0] = source(cc);
    if (o == IrOp::TexGrad) {
      Comps gx = floatOf(args[2], at).comps, gy = floatOf(args[3], at).comps;
      while (gx.size() < 4) gx.push_back(lit(0));
      while (gy.size() < 4) gy.push_back(lit(0));
      inst.src[1] = source(gx);
      inst.src[2] = source(gy);
      inst.srcCount = 3;
    }
    inst.where = at;
    int reg = emitInst(std::move(inst));
    return Value{Type::vector(BaseType::Float, 4), regComps(reg, 4), true};
  }

  const Program& prog_;
  BuildOptions opt_;
  DiagnosticSink* sink_;  // a scratch sink while a region is built on trial
  const shader::VersionRules* rules_;
  IrProgram ir_;
  SourceLocation where_;
  std::vector<std::map<std::string, Variable*>> scopes_;
  std::vector<std::unique_ptr<Variable>> variables_;
  std::set<Variable*> uninitialized_;
  std::map<std::vector<float>, int> constants_;
  std::map<std::vector<int>, int> cse_;
  std::map<std::pair<int, int>, Comp> rcpOf_;  // rcp result → its operand
  std::map<std::vector<std::tuple<int, int, float>>, int> combines_;
  std::set<std::tuple<std::string, int, int>> truncationWarned_;
  std::vector<Comp> conditions_;
  std::vector<FunctionFrame> functions_;
  std::vector<LoopFrame> loops_;
  int realLoops_ = 0;  // rep … endrep regions open
  std::set<const FunctionDecl*> callStack_;
  int depth_ = 0;
  long work_ = 0;
  bool tooDeepReported_ = false;
};

}  // namespace

IrProgram buildIr(const Program& program, const BuildOptions& options, DiagnosticSink& sink) {
  Builder b(program, options, sink);
  return b.run();
}

}  // namespace refx::hlsl::detail
