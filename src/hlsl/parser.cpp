// Recursive-descent HLSL parser (DirectX 9 dialect).
//
//   program    := (struct | typedef | declaration | function | technique | ';')*
//   declaration:= modifiers type declarator (',' declarator)* ';'
//   declarator := name ('[' expr ']')* (':' semantic | ':' register(...))* annotations? ('=' init)?
//   function   := modifiers type name '(' params ')' (':' semantic)? (block | ';')
//
// Parse errors report fxc's X3000 "syntax error" with what was expected, then skip
// to a synchronisation point (';' or the end of the enclosing block).
//
// Nesting is bounded so that no input exhausts the stack, here or in the passes that
// walk the tree recursively: statements, parentheses, unary operators and types nest at
// most kMaxNesting deep, and an expression tree is at most kMaxExpressionHeight nodes
// high (a chain `a + b + c …` grows the tree without nesting in the source).
#include "hlsl/parser.h"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <set>

namespace refx::hlsl::detail {

namespace {

struct SyntaxError {};

constexpr int kMaxNesting = 256;
constexpr int kMaxExpressionHeight = 256;
// One variable holds at most 65,536 components (a float4 array of 16,384), and arrays
// and structs nest at most 32 deep in its type.
constexpr int64_t kMaxTypeComponents = 65536;
constexpr int kMaxTypeDepth = 32;

BaseType scalarBase(const std::string& s) {
  if (s == "bool") return BaseType::Bool;
  if (s == "int") return BaseType::Int;
  if (s == "uint" || s == "dword" || s == "DWORD") return BaseType::Uint;
  if (s == "half") return BaseType::Half;
  if (s == "float") return BaseType::Float;
  if (s == "double") return BaseType::Double;
  return BaseType::Void;
}

// "float3" → (Float, 1, 3); "float4x4" → (Float, 4, 4); "half" → (Half, 0, 0).
bool parseNumericTypeName(const std::string& s, Type& out) {
  static const char* bases[] = {"bool", "int", "uint", "dword", "half", "float", "double"};
  for (const char* b : bases) {
    std::string bs = b;
    if (s.compare(0, bs.size(), bs) != 0) continue;
    std::string rest = s.substr(bs.size());
    BaseType base = scalarBase(bs);
    if (rest.empty()) { out = Type::scalar(base); return true; }
    if (rest.size() == 1 && rest[0] >= '1' && rest[0] <= '4') { out = Type::vector(base, rest[0] - '0'); if (out.cols == 1) out.cls = TypeClass::Vector; return true; }
    if (rest.size() == 3 && rest[0] >= '1' && rest[0] <= '4' && rest[1] == 'x' && rest[2] >= '1' && rest[2] <= '4') {
      out = Type::matrix(base, rest[0] - '0', rest[2] - '0');
      return true;
    }
  }
  return false;
}

const std::set<std::string> kModifiers = {"static", "const", "uniform", "extern", "shared", "volatile", "inline",
                                          "in", "out", "inout", "row_major", "column_major", "linear", "centroid",
                                          "nointerpolation", "noperspective", "sample", "precise", "groupshared"};

class Parser {
 public:
  Parser(const std::vector<Token>& toks, const ParseOptions& opt, DiagnosticSink& sink)
      : toks_(toks), opt_(opt), sink_(sink), rowMajor_(opt.rowMajorDefault) {}

  Program program() {
    Program prog;
    prog_ = &prog;
    while (peek().kind != TokenKind::EndOfFile) {
      size_t start = pos_;
      try {
        topLevel(prog);
      } catch (const SyntaxError&) {
        syncTopLevel();
      }
      if (pos_ == start) ++pos_;  // always make progress
    }
    return prog;
  }

  ExprPtr singleExpression() {
    try {
      ExprPtr e = assignment();
      if (peek().kind != TokenKind::EndOfFile) error(peek(), "unexpected {} after the expression", describe(peek()));
      return e;
    } catch (const SyntaxError&) {
      return nullptr;
    }
  }

 private:
  // ---- token helpers -------------------------------------------------------------------------
  const Token& peek(size_t ahead = 0) const {
    size_t i = std::min(pos_ + ahead, toks_.size() - 1);
    return toks_[i];
  }
  const Token& next() {
    const Token& t = peek();
    if (pos_ < toks_.size() - 1) ++pos_;
    return t;
  }
  bool is(const char* text, size_t ahead = 0) const {
    const Token& t = peek(ahead);
    return (t.kind == TokenKind::Punct || t.kind == TokenKind::Identifier) && t.text == text;
  }
  bool accept(const char* text) {
    if (!is(text)) return false;
    next();
    return true;
  }
  static SourceLocation loc(const Token& t) { return {t.file, t.line, t.column}; }
  static std::string describe(const Token& t) {
    switch (t.kind) {
      case TokenKind::EndOfFile: return "end of file";
      case TokenKind::StringLiteral: return "string \"" + t.text + "\"";
      default: return "'" + t.text + "'";
    }
  }
  template <typename... Args>
  [[noreturn]] void error(const Token& at, fmt::format_string<Args...> f, Args&&... args) {
    sink_.error(loc(at), "X3000", "syntax error: {}", fmt::format(f, std::forward<Args>(args)...));
    throw SyntaxError{};
  }
  void expect(const char* text, const char* context) {
    if (!accept(text)) error(peek(), "expected '{}' {}, found {}", text, context, describe(peek()));
  }
  std::string identifier(const char* what) {
    if (peek().kind != TokenKind::Identifier) error(peek(), "expected {}, found {}", what, describe(peek()));
    return next().text;
  }

  // One level of recursion of the parser; past kMaxNesting the construct is an error.
  class Nested {
   public:
    Nested(Parser& p, const Token& at) : p_(p) {
      if (++p_.nesting_ > kMaxNesting) {
        --p_.nesting_;
        p_.sink_.error(loc(at), "X3000", "syntax error: nested more than {} levels deep", kMaxNesting);
        throw SyntaxError{};
      }
    }
    ~Nested() { --p_.nesting_; }
    Nested(const Nested&) = delete;
    Nested& operator=(const Nested&) = delete;

   private:
    Parser& p_;
  };

  // `e` has all its operands: its height is one more than theirs, at most
  // kMaxExpressionHeight.
  ExprPtr grown(ExprPtr e) {
    int below = 0;
    for (const ExprPtr& a : e->args)
      if (a) below = std::max(below, a->height);
    e->height = below + 1;
    if (e->height > kMaxExpressionHeight) {
      sink_.error(e->where, "X3000", "syntax error: expression more than {} operations deep", kMaxExpressionHeight);
      throw SyntaxError{};
    }
    return e;
  }

  void syncTopLevel() {
    int depth = 0;
    while (peek().kind != TokenKind::EndOfFile) {
      const Token& t = next();
      if (t.kind != TokenKind::Punct) continue;
      if (t.text == "{") ++depth;
      else if (t.text == "}") { if (--depth <= 0) { accept(";"); return; } }
      else if (t.text == ";" && depth == 0) return;
    }
  }
  void syncStatement() {
    int depth = 0;
    while (peek().kind != TokenKind::EndOfFile) {
      if (depth == 0 && is("}")) return;  // leave the block's closing brace to the block
      const Token& t = next();
      if (t.kind != TokenKind::Punct) continue;
      if (t.text == "{") ++depth;
      else if (t.text == "}") { if (--depth == 0) return; }
      else if (t.text == ";" && depth == 0) return;
    }
  }

  // ---- types ---------------------------------------------------------------------------------
  bool isTypeStart(size_t ahead = 0) const {
    const Token& t = peek(ahead);
    if (t.kind != TokenKind::Identifier) return false;
    const std::string& s = t.text;
    Type dummy;
    if (parseNumericTypeName(s, dummy)) return true;
    if (s == "void" || s == "vector" || s == "matrix" || s == "string" || s == "struct") return true;
    if (s.rfind("sampler", 0) == 0 || s.rfind("texture", 0) == 0 || s.rfind("Texture", 0) == 0) return true;
    if (s == "SamplerState" || s == "sampler_state") return s != "sampler_state";
    if (opt_.compatibility && (s == "vec2" || s == "vec3" || s == "vec4" || s == "volumetexture")) return true;
    return typedefs_.count(s) || structs_.count(s);
  }

  Type typeName() {
    const Token& t = peek();
    Nested nested(*this, t);
    if (t.kind != TokenKind::Identifier) error(t, "expected a type, found {}", describe(t));
    std::string s = t.text;
    Type ty;
    if (parseNumericTypeName(s, ty)) { next(); return ty; }
    if (opt_.compatibility && (s == "vec2" || s == "vec3" || s == "vec4")) {
      next();
      return Type::vector(BaseType::Float, s[3] - '0');
    }
    if (s == "void") { next(); return Type(); }
    if (s == "vector" || s == "matrix") {
      next();
      if (!accept("<")) return s == "vector" ? Type::vector(BaseType::Float, 4) : Type::matrix(BaseType::Float, 4, 4);
      Type elem = typeName();
      if (!elem.isScalar()) error(t, "{}<> needs a scalar element type", s);
      expect(",", "in the template arguments");
      int a = intLiteral();
      int b = 0;
      if (s == "matrix") { expect(",", "in matrix<type, rows, columns>"); b = intLiteral(); }
      expect(">", "to close the template arguments");
      if (a < 1 || a > 4 || (s == "matrix" && (b < 1 || b > 4))) error(t, "{} dimensions must be 1 to 4", s);
      if (s == "vector") { Type v = Type::vector(elem.base, a); if (a == 1) v.cls = TypeClass::Vector; return v; }
      return Type::matrix(elem.base, a, b);
    }
    if (s == "string") { next(); Type o; o.cls = TypeClass::Object; o.base = BaseType::String; return o; }
    if (s.rfind("sampler", 0) == 0 || s == "SamplerState") {
      next();
      Type o; o.cls = TypeClass::Object; o.base = BaseType::Sampler;
      if (s == "sampler1D") o.dim = SamplerDim::Dim1D;
      else if (s == "sampler2D") o.dim = SamplerDim::Dim2D;
      else if (s == "sampler3D") o.dim = SamplerDim::Dim3D;
      else if (s == "samplerCUBE") o.dim = SamplerDim::Cube;
      else if (s != "sampler" && s != "SamplerState") error(t, "unknown sampler type '{}'", s);
      return o;
    }
    if (s.rfind("texture", 0) == 0 || s.rfind("Texture", 0) == 0 || s == "volumetexture") {
      next();
      Type o; o.cls = TypeClass::Object; o.base = BaseType::Texture;
      if (s == "texture3D" || s == "volumetexture") o.dim = SamplerDim::Dim3D;
      else if (s == "textureCUBE") o.dim = SamplerDim::Cube;
      return o;
    }
    if (s == "struct") return structDefinition();
    if (auto it = typedefs_.find(s); it != typedefs_.end()) { next(); return it->second; }
    if (auto it = structs_.find(s); it != structs_.end()) {
      next();
      Type st; st.cls = TypeClass::Struct; st.base = BaseType::Struct; st.structDef = it->second;
      return st;
    }
    error(t, "expected a type, found {}", describe(t));
  }

  int intLiteral() {
    const Token& t = peek();
    if (t.kind != TokenKind::IntLiteral) error(t, "expected an integer, found {}", describe(t));
    next();
    return int(std::strtol(t.text.c_str(), nullptr, 0));
  }

  Type structDefinition() {
    const Token& kw = next();  // 'struct'
    auto def = std::make_unique<StructDef>();
    def->where = loc(kw);
    if (peek().kind == TokenKind::Identifier && !is("{")) def->name = next().text;
    if (!is("{")) {  // reference to a declared struct: "struct S s;"
      auto it = structs_.find(def->name);
      if (it == structs_.end()) error(peek(), "unknown struct '{}'", def->name);
      Type st; st.cls = TypeClass::Struct; st.base = BaseType::Struct; st.structDef = it->second;
      return st;
    }
    expect("{", "to open the struct");
    while (!is("}") && peek().kind != TokenKind::EndOfFile) {
      bool interp = false;
      int packing = 0;
      while (peek().kind == TokenKind::Identifier && kModifiers.count(peek().text)) {
        if (is("row_major")) packing = 1;
        if (is("column_major")) packing = 2;
        interp = true;
        next();
      }
      Type mt = typeName();
      if (packing) mt.packing = packing;
      do {
        StructMember m;
        m.interpolationModifier = interp;
        const Token& nameTok = peek();
        m.name = identifier("a member name");
        m.type = declaredType(mt, nameTok);
        if (accept(":")) m.semantic = identifier("a semantic");
        def->members.push_back(std::move(m));
      } while (accept(","));
      expect(";", "after the struct member");
    }
    expect("}", "to close the struct");
    StructDef* raw = def.get();
    if (!raw->name.empty()) structs_[raw->name] = raw;
    prog_->structs.push_back(std::move(def));
    Type st; st.cls = TypeClass::Struct; st.base = BaseType::Struct; st.structDef = raw;
    return st;
  }

  Type arraySuffix(Type t) {
    std::vector<int> dims;
    while (accept("[")) {
      if (is("]")) { next(); dims.push_back(-1); continue; }  // size from the initialiser
      ExprPtr e = assignment();
      int n = 1;
      if (e->kind != ExprKind::Literal) sink_.error(e->where, "X3058", "array dimensions must be literal scalar expressions");
      else if (!(e->number >= 1 && e->number <= 65536)) sink_.error(e->where, "X3059", "array dimension must be between 1 and 65536");
      else n = int(e->number);
      dims.push_back(n);
      expect("]", "to close the array dimension");
    }
    for (auto it = dims.rbegin(); it != dims.rend(); ++it) t = Type::arrayOf(t, *it);
    if (measure(t).components < 0) {
      sink_.error(loc(peek()), "X3059", "'{}' is too large: more than {} components or {} levels of arrays and structs",
                  t.name(), kMaxTypeComponents, kMaxTypeDepth);
      return Type::scalar(BaseType::Float);
    }
    return t;
  }

  // Components of a value of type `t` (as Type::flatSize counts them) and how deep
  // arrays and structs nest in it; components -1 past kMaxTypeComponents or
  // kMaxTypeDepth. Every declared type is measured, so a struct's members already fit.
  struct Measure {
    int64_t components = 0;
    int depth = 0;
  };
  Measure measure(const Type& t) {
    Measure m;
    if (t.isArray()) {
      m = measure(*t.element);
      if (m.components >= 0) m.components *= t.arraySize;
      ++m.depth;
    } else if (t.cls == TypeClass::Struct && t.structDef) {
      if (auto it = structSizes_.find(t.structDef); it != structSizes_.end()) return it->second;
      for (const StructMember& member : t.structDef->members) {
        const Measure e = measure(member.type);
        m.components = e.components < 0 || m.components < 0 ? -1 : m.components + e.components;
        m.depth = std::max(m.depth, e.depth + 1);
        if (m.components > kMaxTypeComponents) m.components = -1;
      }
      structSizes_[t.structDef] = m;
    } else {
      m.components = t.cls == TypeClass::Object ? 1 : int64_t(t.rows) * t.cols;
    }
    if (m.components > kMaxTypeComponents || m.depth > kMaxTypeDepth) m.components = -1;
    return m;
  }

  // The type of a declared variable, parameter or member: `base` with the declarator's
  // array dimensions. Nothing is declared void: that is an error, and the declaration
  // goes on as a float so that type checking can continue.
  Type declaredType(const Type& base, const Token& nameTok) {
    const Type* element = &base;
    while (element->isArray()) element = element->element.get();
    if (element->isVoid()) {
      sink_.error(loc(nameTok), "X3000", "syntax error: '{}' cannot be declared void", nameTok.text);
      return arraySuffix(Type::scalar(BaseType::Float));
    }
    return arraySuffix(base);
  }

  // ---- top level -----------------------------------------------------------------------------
  void topLevel(Program& prog) {
    if (accept(";")) return;
    if (opt_.compatibility && is("fx") && peek(1).line == peek().line) {  // "fx.2.0" header of the white paper
      const int line = peek().line;
      while (peek().kind != TokenKind::EndOfFile && peek().line == line) ++pos_;
      return;
    }
    if (peek().kind == TokenKind::Pragma) { pragma(next()); return; }
    if (is("technique") || is("technique10") || is("technique11")) { skipTechnique(); return; }
    if (isEffectShaderObject()) { skipDeclaration(); return; }
    if (is("typedef")) {
      next();
      accept("const");
      Type t = typeName();
      do {
        std::string name = identifier("a type name");
        typedefs_[name] = arraySuffix(t);
      } while (accept(","));
      expect(";", "after the typedef");
      return;
    }
    if (is("struct") && (is("{", 1) || (peek(1).kind == TokenKind::Identifier && is("{", 2)))) {
      Type st = structDefinition();
      if (accept(";")) return;
      declarationRest(prog, st, VarDecl{}, peek());
      return;
    }
    VarDecl mods;
    int packing = storageModifiers(mods);
    const Token& typeTok = peek();
    Type t = typeName();
    if (packing) t.packing = packing;
    else if (t.cls == TypeClass::Matrix) t.packing = rowMajor_ ? 1 : 2;
    if (peek().kind == TokenKind::Identifier && is("(", 1)) {
      function(prog, t, typeTok);
      return;
    }
    declarationRest(prog, t, std::move(mods), typeTok);
  }

  // static/const/uniform/extern/shared into `mods`; returns the matrix packing
  // (0 default, 1 row_major, 2 column_major). Other modifiers are accepted and ignored.
  int storageModifiers(VarDecl& mods) {
    int packing = 0;
    while (peek().kind == TokenKind::Identifier && kModifiers.count(peek().text)) {
      const std::string& m = next().text;
      if (m == "static") mods.isStatic = true;
      else if (m == "const") mods.isConst = true;
      else if (m == "uniform") mods.isUniform = true;
      else if (m == "extern") mods.isExtern = true;
      else if (m == "shared") mods.isShared = true;
      else if (m == "row_major") packing = 1;
      else if (m == "column_major") packing = 2;
    }
    return packing;
  }

  void pragma(const Token& p) {
    std::string s;
    for (char c : p.text)
      if (c != ' ' && c != '\t') s += c;
    if (s.rfind("pack_matrix(", 0) == 0) {
      if (s.find("row_major") != std::string::npos) rowMajor_ = true;
      else if (s.find("column_major") != std::string::npos) rowMajor_ = false;
      else sink_.warning(loc(p), "X3568", "unknown pack_matrix argument: '{}'", p.text);
    }
    // #pragma warning and others: accepted and ignored.
  }

  // `VertexShader vs = compile vs_2_0 VS();`, `PixelShader ps = asm { … };`: shader
  // objects of effects, which the effect framework builds; the compiler passes over them.
  bool isEffectShaderObject() const {
    static const std::set<std::string> kObjects = {"VertexShader", "PixelShader", "vertexshader", "pixelshader",
                                                   "VertexFragment", "PixelFragment"};
    return peek().kind == TokenKind::Identifier && kObjects.count(peek().text) &&
           peek(1).kind == TokenKind::Identifier;
  }

  void skipDeclaration() {
    int depth = 0;
    while (peek().kind != TokenKind::EndOfFile) {
      const Token& t = next();
      if (t.kind != TokenKind::Punct) continue;
      if (t.text == "{") ++depth;
      else if (t.text == "}") --depth;
      else if (t.text == ";" && depth <= 0) return;
    }
  }

  void skipTechnique() {
    next();
    int depth = 0;
    while (peek().kind != TokenKind::EndOfFile) {
      const Token& t = next();
      if (t.kind != TokenKind::Punct) continue;
      if (t.text == "{") ++depth;
      else if (t.text == "}" && --depth == 0) return;
    }
  }

  void declarationRest(Program& prog, const Type& base, VarDecl mods, const Token& typeTok) {
    do {
      auto v = std::make_unique<VarDecl>();
      v->isStatic = mods.isStatic; v->isConst = mods.isConst; v->isUniform = mods.isUniform;
      v->isExtern = mods.isExtern; v->isShared = mods.isShared;
      v->where = loc(peek());
      const Token& nameTok = peek();
      v->name = identifier("a variable name");
      v->type = declaredType(base, nameTok);
      declaratorTail(*v);
      prog.globals.push_back(std::move(v));
    } while (accept(","));
    expect(";", "after the declaration");
  }

  // semantics, register bindings, annotations and the initialiser of one declarator.
  void declaratorTail(VarDecl& v) {
    while (accept(":")) {
      if (is("register")) {
        next();
        expect("(", "after 'register'");
        std::string r;
        while (!is(")") && peek().kind != TokenKind::EndOfFile) r += next().text;
        expect(")", "to close register(...)");
        v.registerBinding = r;
      } else if (is("packoffset")) {
        sink_.error(loc(peek()), "X3530", "packoffset is a Direct3D 10 construct");
        while (!is(")") && peek().kind != TokenKind::EndOfFile) next();
        accept(")");
      } else {
        v.semantic = identifier("a semantic");
      }
    }
    if (is("<")) annotations(v.annotations);
    if (accept("=")) {
      if (is("sampler_state") || is("SamplerState")) {
        next();
        expect("{", "to open sampler_state");
        while (!is("}") && peek().kind != TokenKind::EndOfFile) {
          std::string state = identifier("a sampler state name");
          if (accept("[")) { while (!is("]") && peek().kind != TokenKind::EndOfFile) next(); expect("]", "to close the index"); }
          expect("=", "after the sampler state name");
          ExprPtr value;
          if (accept("<")) {  // <texture>
            auto e = std::make_unique<Expr>();
            e->kind = ExprKind::Name;
            e->where = loc(peek());
            e->op = identifier("a texture name");
            expect(">", "to close the parameter reference");
            value = std::move(e);
          } else {
            value = assignment();
          }
          expect(";", "after the sampler state");
          v.samplerStates.emplace_back(state, std::move(value));
        }
        expect("}", "to close sampler_state");
      } else if (is("{")) {
        v.init = initList();
      } else {
        v.init = assignment();
      }
    }
  }

  void annotations(std::vector<Annotation>& out) {
    expect("<", "to open annotations");
    while (!is(">") && peek().kind != TokenKind::EndOfFile) {
      Annotation a;
      a.type = typeName();
      a.name = identifier("an annotation name");
      expect("=", "in the annotation");
      if (is("{")) a.value = initList();
      else a.value = ternary();  // '>' must not be read as an operator here
      expect(";", "after the annotation");
      out.push_back(std::move(a));
    }
    expect(">", "to close annotations");
  }

  ExprPtr initList() {
    Nested nested(*this, peek());
    auto e = std::make_unique<Expr>();
    e->kind = ExprKind::InitList;
    e->where = loc(peek());
    expect("{", "to open the initialiser list");
    while (!is("}")) {
      e->args.push_back(is("{") ? initList() : assignment());
      if (!accept(",")) break;
    }
    expect("}", "to close the initialiser list");
    return grown(std::move(e));
  }

  void function(Program& prog, const Type& ret, const Token& typeTok) {
    auto f = std::make_unique<FunctionDecl>();
    f->returnType = ret;
    f->where = loc(peek());
    f->name = next().text;
    expect("(", "to open the parameter list");
    if (is("void") && is(")", 1)) next();
    while (!is(")")) {
      auto p = std::make_unique<VarDecl>();
      int packing = 0;
      while (peek().kind == TokenKind::Identifier && kModifiers.count(peek().text)) {
        const std::string& m = next().text;
        if (m == "out") { p->isOut = true; p->isIn = false; }
        else if (m == "inout") { p->isOut = true; p->isIn = true; }
        else if (m == "uniform") p->isUniform = true;
        else if (m == "const") p->isConst = true;
        else if (m == "row_major") packing = 1;
        else if (m == "column_major") packing = 2;
      }
      p->type = typeName();
      if (packing) p->type.packing = packing;
      else if (p->type.cls == TypeClass::Matrix) p->type.packing = rowMajor_ ? 1 : 2;
      p->where = loc(peek());
      const Token& nameTok = peek();
      p->name = identifier("a parameter name");
      p->type = declaredType(p->type, nameTok);
      declaratorTail(*p);
      f->params.push_back(std::move(p));
      if (!accept(",")) break;
    }
    expect(")", "to close the parameter list");
    if (accept(":")) f->returnSemantic = identifier("a semantic");
    if (accept(";")) { prog.functions.push_back(std::move(f)); return; }
    if (!is("{")) error(peek(), "expected '{{' to open the body of '{}', found {}", f->name, describe(peek()));
    int before = sink_.errorCount();
    f->body = block();
    f->syntaxErrors = sink_.errorCount() > before;
    prog.functions.push_back(std::move(f));
  }

  // ---- statements ----------------------------------------------------------------------------
  StmtPtr makeStmt(StmtKind k, const Token& at) {
    auto s = std::make_unique<Stmt>();
    s->kind = k;
    s->where = loc(at);
    return s;
  }

  StmtPtr block() {
    auto s = makeStmt(StmtKind::Block, peek());
    expect("{", "to open a block");
    while (!is("}") && peek().kind != TokenKind::EndOfFile) {
      size_t start = pos_;
      try {
        s->block.push_back(statement());
      } catch (const SyntaxError&) {
        syncStatement();
      }
      if (pos_ == start) next();
    }
    expect("}", "to close the block");
    return s;
  }

  StmtPtr statement() {
    Nested nested(*this, peek());
    std::vector<std::string> attrs;
    int unroll = 0;
    while (is("[") && peek(1).kind == TokenKind::Identifier) {
      next();
      std::string a = next().text;
      for (char& c : a) c = char(std::tolower((unsigned char)c));
      if (accept("(")) {
        if (peek().kind == TokenKind::IntLiteral) unroll = intLiteral();
        while (!is(")") && peek().kind != TokenKind::EndOfFile) next();
        expect(")", "to close the attribute");
      }
      expect("]", "to close the attribute");
      attrs.push_back(a);
    }
    const Token& t = peek();
    StmtPtr s;
    if (is("{")) s = block();
    else if (accept(";")) s = makeStmt(StmtKind::Empty, t);
    else if (is("if")) {
      next();
      s = makeStmt(StmtKind::If, t);
      expect("(", "after 'if'");
      s->expr = expression();
      expect(")", "to close the condition");
      s->body = statement();
      if (accept("else")) s->elseBody = statement();
    } else if (is("for")) {
      next();
      s = makeStmt(StmtKind::For, t);
      expect("(", "after 'for'");
      if (!accept(";")) s->init = simpleStatement();
      if (!is(";")) s->expr = expression();
      expect(";", "after the loop condition");
      if (!is(")")) s->step = expression();
      expect(")", "to close the for header");
      s->body = statement();
    } else if (is("while")) {
      next();
      s = makeStmt(StmtKind::While, t);
      expect("(", "after 'while'");
      s->expr = expression();
      expect(")", "to close the condition");
      s->body = statement();
    } else if (is("do")) {
      next();
      s = makeStmt(StmtKind::Do, t);
      s->body = statement();
      expect("while", "after the do body");
      expect("(", "after 'while'");
      s->expr = expression();
      expect(")", "to close the condition");
      expect(";", "after do-while");
    } else if (is("break")) { next(); s = makeStmt(StmtKind::Break, t); expect(";", "after 'break'"); }
    else if (is("continue")) { next(); s = makeStmt(StmtKind::Continue, t); expect(";", "after 'continue'"); }
    else if (is("discard")) { next(); s = makeStmt(StmtKind::Discard, t); expect(";", "after 'discard'"); }
    else if (is("return")) {
      next();
      s = makeStmt(StmtKind::Return, t);
      if (!is(";")) s->expr = expression();
      expect(";", "after the return statement");
    } else {
      s = simpleStatement();
    }
    s->attributes = std::move(attrs);
    s->unrollCount = unroll;
    return s;
  }

  // A declaration or an expression statement, ending with ';' (consumed).
  StmtPtr simpleStatement() {
    const Token& t = peek();
    bool isDecl = false;
    if (peek().kind == TokenKind::Identifier && kModifiers.count(peek().text)) isDecl = true;
    else if (isTypeStart() && !is("(", 1)) isDecl = true;  // "float3(...)" starts an expression
    else if (isTypeStart() && peek(1).kind == TokenKind::Identifier) isDecl = true;
    if (!isDecl) {
      auto s = makeStmt(StmtKind::Expr, t);
      s->expr = expression();
      expect(";", "after the expression");
      return s;
    }
    auto s = makeStmt(StmtKind::Decl, t);
    VarDecl mods;
    int packing = storageModifiers(mods);
    Type base = typeName();
    if (packing) base.packing = packing;
    else if (base.cls == TypeClass::Matrix) base.packing = rowMajor_ ? 1 : 2;
    do {
      auto v = std::make_unique<VarDecl>();
      v->isStatic = mods.isStatic;
      v->isConst = mods.isConst;
      v->where = loc(peek());
      const Token& nameTok = peek();
      v->name = identifier("a variable name");
      v->type = declaredType(base, nameTok);
      declaratorTail(*v);
      s->decls.push_back(std::move(v));
    } while (accept(","));
    if (!accept(";")) error(peek(), "expected ';' after the declaration, found {}", describe(peek()));
    return s;
  }

  // ---- expressions ---------------------------------------------------------------------------
  ExprPtr make(ExprKind k, const Token& at, std::string op = {}) {
    auto e = std::make_unique<Expr>();
    e->kind = k;
    e->where = loc(at);
    e->op = std::move(op);
    return e;
  }

  ExprPtr expression() {
    ExprPtr e = assignment();
    if (!is(",")) return e;
    auto c = make(ExprKind::Comma, peek());
    c->args.push_back(std::move(e));
    while (accept(",")) c->args.push_back(assignment());
    return grown(std::move(c));
  }

  ExprPtr assignment() {
    Nested nested(*this, peek());
    ExprPtr lhs = ternary();
    static const char* ops[] = {"=", "+=", "-=", "*=", "/=", "%=", "&=", "|=", "^=", "<<=", ">>="};
    for (const char* op : ops) {
      if (is(op) && peek().kind == TokenKind::Punct) {
        const Token& t = next();
        auto e = make(ExprKind::Assign, t, op);
        e->args.push_back(std::move(lhs));
        e->args.push_back(assignment());
        return grown(std::move(e));
      }
    }
    return lhs;
  }

  ExprPtr ternary() {
    ExprPtr c = binary(0);
    if (!is("?")) return c;
    const Token& t = next();
    auto e = make(ExprKind::Ternary, t, "?");
    e->args.push_back(std::move(c));
    e->args.push_back(assignment());
    expect(":", "in the conditional expression");
    e->args.push_back(assignment());
    return grown(std::move(e));
  }

  static int precedence(const std::string& op) {
    static const std::map<std::string, int> table = {
        {"||", 1}, {"&&", 2}, {"|", 3}, {"^", 4}, {"&", 5}, {"==", 6}, {"!=", 6}, {"<", 7}, {">", 7},
        {"<=", 7}, {">=", 7}, {"<<", 8}, {">>", 8}, {"+", 9}, {"-", 9}, {"*", 10}, {"/", 10}, {"%", 10}};
    auto it = table.find(op);
    return it == table.end() ? -1 : it->second;
  }

  ExprPtr binary(int minPrec) {
    ExprPtr lhs = unary();
    for (;;) {
      const Token& t = peek();
      if (t.kind != TokenKind::Punct) return lhs;
      int p = precedence(t.text);
      if (p < 0 || p <= minPrec - 1 || p < minPrec) return lhs;
      next();
      ExprPtr rhs = binary(p + 1);
      auto e = make(ExprKind::Binary, t, t.text);
      e->args.push_back(std::move(lhs));
      e->args.push_back(std::move(rhs));
      lhs = grown(std::move(e));
    }
  }

  // '(' type ')' starts a cast when the token after '(' names a type.
  bool castAhead() const {
    if (!is("(")) return false;
    size_t k = 1;
    while (peek(k).kind == TokenKind::Identifier && kModifiers.count(peek(k).text)) ++k;
    if (!isTypeStart(k)) return false;
    // "(float3(…))" is a parenthesised constructor, not a cast.
    const Token& after = peek(k + 1);
    if (after.kind == TokenKind::Punct && after.text == "(") return false;
    return true;
  }

  ExprPtr unary() {
    const Token& t = peek();
    Nested nested(*this, t);
    if (t.kind == TokenKind::Punct &&
        (t.text == "-" || t.text == "+" || t.text == "!" || t.text == "~" || t.text == "++" || t.text == "--")) {
      next();
      auto e = make(ExprKind::Unary, t, t.text);
      e->args.push_back(unary());
      return grown(std::move(e));
    }
    if (castAhead()) {
      next();
      while (peek().kind == TokenKind::Identifier && kModifiers.count(peek().text)) next();
      Type ty = typeName();
      ty = arraySuffix(ty);
      expect(")", "to close the cast");
      auto e = make(ExprKind::Cast, t);
      e->type = ty;
      e->args.push_back(unary());
      return grown(std::move(e));
    }
    return postfix(primary());
  }

  ExprPtr postfix(ExprPtr e) {
    for (;;) {
      const Token& t = peek();
      if (accept(".")) {
        auto m = make(ExprKind::Member, t, identifier("a member or swizzle"));
        m->args.push_back(std::move(e));
        e = grown(std::move(m));
      } else if (is("[")) {
        next();
        auto ix = make(ExprKind::Index, t);
        ix->args.push_back(std::move(e));
        ix->args.push_back(expression());
        expect("]", "to close the index");
        e = grown(std::move(ix));
      } else if (is("++") || is("--")) {
        next();
        auto p = make(ExprKind::Postfix, t, t.text);
        p->args.push_back(std::move(e));
        e = grown(std::move(p));
      } else {
        return e;
      }
    }
  }

  void callArguments(Expr& e) {
    expect("(", "to open the argument list");
    while (!is(")")) {
      e.args.push_back(assignment());
      if (!accept(",")) break;
    }
    expect(")", "to close the argument list");
  }

  ExprPtr primary() {
    const Token& t = peek();
    switch (t.kind) {
      case TokenKind::IntLiteral:
      case TokenKind::FloatLiteral: {
        next();
        auto e = make(ExprKind::Literal, t);
        e->isFloat = t.kind == TokenKind::FloatLiteral;
        std::string text = t.text;
        while (!text.empty() && std::strchr("fFhHlLuU", text.back())) {
          if (e->isFloat || (text.back() != 'f' && text.back() != 'F')) text.pop_back();
          else break;
        }
        e->number = e->isFloat ? std::strtod(text.c_str(), nullptr) : double(std::strtoull(text.c_str(), nullptr, 0));
        return e;
      }
      case TokenKind::StringLiteral: {
        next();
        auto e = make(ExprKind::StringLit, t, t.text);
        return e;
      }
      case TokenKind::Identifier: {
        if (t.text == "true" || t.text == "false") {
          next();
          auto e = make(ExprKind::Literal, t);
          e->isBool = true;
          e->number = t.text == "true" ? 1 : 0;
          return e;
        }
        if (isTypeStart() && is("(", 1)) {  // constructor
          Type ty = typeName();
          auto e = make(ExprKind::Constructor, t);
          e->type = ty;
          callArguments(*e);
          return grown(std::move(e));
        }
        next();
        if (is("(")) {
          auto e = make(ExprKind::Call, t, t.text);
          callArguments(*e);
          return grown(std::move(e));
        }
        return make(ExprKind::Name, t, t.text);
      }
      case TokenKind::Punct:
        if (t.text == "(") {
          next();
          ExprPtr e = expression();
          expect(")", "to close the parenthesis");
          return e;
        }
        if (t.text == "{") return initList();
        break;
      default:
        break;
    }
    error(t, "expected an expression, found {}", describe(t));
  }

  const std::vector<Token>& toks_;
  ParseOptions opt_;
  DiagnosticSink& sink_;
  size_t pos_ = 0;
  int nesting_ = 0;
  std::map<const StructDef*, Measure> structSizes_;
  bool rowMajor_ = false;
  Program* prog_ = nullptr;
  std::map<std::string, Type> typedefs_;
  std::map<std::string, const StructDef*> structs_;
};

}  // namespace

int Type::flatSize() const {
  if (isArray()) return arraySize * element->flatSize();
  switch (cls) {
    case TypeClass::Scalar: case TypeClass::Vector: case TypeClass::Matrix: return rows * cols;
    case TypeClass::Object: return 1;
    case TypeClass::Struct: {
      int n = 0;
      for (const StructMember& m : structDef->members) n += m.type.flatSize();
      return n;
    }
    default: return 0;
  }
}

std::string Type::name() const {
  if (isArray()) return element->name() + "[" + std::to_string(arraySize) + "]";
  static const char* bases[] = {"void", "bool", "int", "uint", "half", "float", "double", "sampler", "texture", "string", "struct"};
  std::string b = bases[int(base)];
  switch (cls) {
    case TypeClass::Void: return "void";
    case TypeClass::Scalar: return b;
    case TypeClass::Vector: return b + std::to_string(cols);
    case TypeClass::Matrix: return b + std::to_string(rows) + "x" + std::to_string(cols);
    case TypeClass::Object:
      if (base == BaseType::Sampler) {
        static const char* dims[] = {"sampler", "sampler1D", "sampler2D", "sampler3D", "samplerCUBE"};
        return dims[int(dim)];
      }
      return b;
    case TypeClass::Struct: return structDef ? "struct " + structDef->name : "struct";
  }
  return b;
}

Program parse(const std::vector<Token>& tokens, const ParseOptions& options, DiagnosticSink& sink) {
  Parser p(tokens, options, sink);
  return p.program();
}

ExprPtr parseExpression(const std::vector<Token>& tokens, DiagnosticSink& sink) {
  Parser p(tokens, {}, sink);
  return p.singleExpression();
}

}  // namespace refx::hlsl::detail
