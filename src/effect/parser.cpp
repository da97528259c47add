// Effect text → EffectAst. Grammar (fx_1_0 and fx_2_0):
//   file        := (parameter | function | struct | typedef | technique | ';')*
//   parameter   := modifiers type declarator (',' declarator)* ';'
//   declarator  := name ('[' N ']')? (':' SEMANTIC)? annotations? ('=' initializer)?
//   technique   := 'technique' name? annotations? '{' pass* '}'
//   pass        := 'pass' name? annotations? '{' (state '=' value ';')* '}'
#include <cctype>
#include <map>
#include <set>

#include "ast.h"
#include "effect_errors.h"
#include "refx/core/text.h"

namespace refx::effect::detail {

namespace {

constexpr int kMaxExprDepth = 128;
// A file with more errors than this reports these and stops.
constexpr int kMaxErrors = 100;

// Ends parsing: the error limit, the end of the file inside a construct, or an error of
// the token stream itself.
struct StopParsing {};

}  // namespace

// "float4x3" → Float, 4, 3; "int2" → Int, 1, 2; "float" → Float, 1, 1.
std::optional<ParameterDesc> numericTypeName(std::string_view name) {
  struct Base {
    std::string_view name;
    ParameterType type;
  };
  static constexpr Base kBases[] = {
      {"bool", ParameterType::Bool},   {"int", ParameterType::Int},     {"uint", ParameterType::Int},
      {"dword", ParameterType::Int},   {"half", ParameterType::Float},  {"float", ParameterType::Float},
      {"double", ParameterType::Float},
  };
  for (const Base& b : kBases) {
    if (!startsWithNoCase(name, b.name)) continue;
    // HLSL type names are case-sensitive except DWORD, which effect files spell in capitals.
    if (name.substr(0, b.name.size()) != b.name && b.name != "dword") continue;
    std::string_view rest = name.substr(b.name.size());
    ParameterDesc d;
    d.type = b.type;
    if (rest.empty()) return d;
    auto dim = [](char c) { return c >= '1' && c <= '4' ? c - '0' : 0; };
    if (rest.size() == 1 && dim(rest[0])) {
      d.cls = ParameterClass::Vector;
      d.columns = dim(rest[0]);
      return d;
    }
    if (rest.size() == 3 && dim(rest[0]) && rest[1] == 'x' && dim(rest[2])) {
      d.cls = ParameterClass::MatrixColumns;
      d.rows = dim(rest[0]);
      d.columns = dim(rest[2]);
      return d;
    }
  }
  return std::nullopt;
}

namespace {

std::optional<ParameterType> objectType(std::string_view name) {
  struct Obj {
    std::string_view name;
    ParameterType type;
  };
  static constexpr Obj kObjects[] = {
      {"string", ParameterType::String},         {"texture", ParameterType::Texture},
      {"texture1D", ParameterType::Texture1D},   {"texture2D", ParameterType::Texture2D},
      {"texture3D", ParameterType::Texture3D},   {"textureCUBE", ParameterType::TextureCube},
      {"sampler", ParameterType::Sampler},       {"sampler1D", ParameterType::Sampler1D},
      {"sampler2D", ParameterType::Sampler2D},   {"sampler3D", ParameterType::Sampler3D},
      {"samplerCUBE", ParameterType::SamplerCube}, {"pixelshader", ParameterType::PixelShader},
      {"vertexshader", ParameterType::VertexShader},
  };
  for (const Obj& o : kObjects)
    if (equalsNoCase(o.name, name)) return o.type;
  return std::nullopt;
}

class Parser {
 public:
  Parser(std::string_view text, const std::string& file, const EffectOptions& o, DiagnosticSink& sink)
      : lex_(text, file, o.includeDirs, o.defines), sink_(sink) {}

  // Every error is reported: after one, parsing goes on after the construct it is in
  // (the state assignment, pass, technique or declaration).
  EffectAst run() {
    EffectAst ast;
    try {
      for (;;) {
        try {
          const Token& t = lex_.peek();
          if (t.kind == TokenKind::End) break;
          if (t.is(";")) {
            lex_.next();
          } else if (t.isIdent("technique")) {
            ast.techniques.push_back(technique());
          } else if (t.isIdent("technique10") || t.isIdent("technique11")) {
            failCode("F1102", t.where, "'{}' is a Direct3D 10/11 effect construct; D3D9 effects use 'technique'", t.text);
          } else if (t.isIdent("fx")) {  // no type is called fx: the `fx.2.0` header
            preReleaseHeader(ast);
          } else if (t.text == "struct") {
            skipStruct();
          } else if (t.text == "typedef") {
            typedefDeclaration();
          } else {
            topLevelDeclaration(ast);
          }
        } catch (const EffectError& e) {
          recover(e, true);
        }
      }
    } catch (const StopParsing&) {
    }
    ast.files = lex_.files();
    return ast;
  }

 private:
  // Reports the error and skips the rest of the construct it is in.
  void recover(const EffectError& e, bool topLevel) {
    sink_.report(e.diagnostic);
    if (e.fatal || sink_.errorCount() >= kMaxErrors) throw StopParsing{};
    skipConstruct(topLevel);
    if (!topLevel && lex_.peek().kind == TokenKind::End) throw StopParsing{};  // the end, inside a block
  }

  // A ';' ends the construct (and is consumed), as does a '{ … }' block skipped whole; a
  // '}' that closes the enclosing block ends it and is left to that block (at the top
  // level, where no block encloses, a stray '}' is skipped).
  void skipConstruct(bool topLevel) {
    int depth = 0;
    for (;;) {
      const Token& t = lex_.peek();
      if (t.kind == TokenKind::End) return;
      if (t.is("}")) {
        if (depth == 0 && !topLevel) return;
        lex_.next();
        if (depth <= 1) return;
        --depth;
        continue;
      }
      if (t.is("{")) ++depth;
      const bool end = depth == 0 && t.is(";");
      lex_.next();
      if (end) return;
    }
  }

  // The parse functions below check the next token before taking it, so that the token
  // an error points at (a '}' or ';' in the wrong place) is still there for recovery.
  Token expect(std::string_view punct, std::string_view what) {
    const Token& t = lex_.peek();
    if (!t.is(punct)) failCode("F1100", t.where, "expected '{}' {}, found {}", punct, what, describe(t));
    return lex_.next();
  }

  static std::string describe(const Token& t) {
    switch (t.kind) {
      case TokenKind::End: return "the end of the file";
      case TokenKind::String: return fmt::format("the string \"{}\"", t.text);
      default: return fmt::format("'{}'", t.text);
    }
  }

  Token expectIdent(std::string_view what) {
    const Token& t = lex_.peek();
    if (t.kind != TokenKind::Ident) failCode("F1100", t.where, "expected {}, found {}", what, describe(t));
    return lex_.next();
  }

  bool accept(std::string_view punct) {
    if (!lex_.peek().is(punct)) return false;
    lex_.next();
    return true;
  }

  void skipPast(std::string_view punct) {
    for (;;) {
      Token t = lex_.next();
      if (t.kind == TokenKind::End) failCode("F1100", t.where, "expected '{}' before the end of the file", punct);
      if (t.is(punct)) return;
    }
  }

  // Skips a balanced { … } group whose '{' is the next token.
  void skipBraces() {
    Token open = expect("{", "to open the body");
    int depth = 1;
    while (depth > 0) {
      Token t = lex_.next();
      if (t.kind == TokenKind::End) failCode("F1100", open.where, "expected '}}' to close the '{{' opened here");
      if (t.is("{")) ++depth;
      if (t.is("}")) --depth;
    }
  }

  // `fx.2.0`: the rest of the line is the version.
  void preReleaseHeader(EffectAst& ast) {
    const Token fx = lex_.next();
    while (lex_.peek().kind != TokenKind::End && lex_.peek().where.line == fx.where.line &&
           lex_.peek().where.file == fx.where.file)
      lex_.next();
    ast.preReleaseDialect = preRelease_ = true;
  }

  // Structs are the HLSL functions' business; the name is remembered so a function
  // returning one is recognised.
  void skipStruct() {
    lex_.next();  // struct
    userTypes_.insert(expectIdent("a struct name").text);
    skipBraces();
    expect(";", "after the struct");
  }

  // `typedef float4 color;` makes `color` a parameter type; other typedefs (of structs,
  // arrays) name types only HLSL functions use.
  void typedefDeclaration() {
    lex_.next();  // typedef
    accept("const");
    const Token typeTok = lex_.peek();
    auto base = type();
    if (!base) {
      skipPast(";");
      return;
    }
    for (;;) {
      Token name = expectIdent("a type name");
      if (lex_.peek().is("[")) {
        userTypes_.insert(name.text);
        skipPast(";");
        return;
      }
      aliases_[name.text] = *base;
      if (!accept(",")) break;
    }
    expect(";", "after the typedef");
    (void)typeTok;
  }

  // Storage classes and type modifiers before a type.
  struct Modifiers {
    bool isStatic = false, shared = false, rowMajor = false, columnMajor = false;
  };
  Modifiers modifiers() {
    Modifiers m;
    for (;;) {
      const Token& t = lex_.peek();
      if (t.kind != TokenKind::Ident) return m;
      const std::string& s = t.text;
      if (s == "static") m.isStatic = true;
      else if (s == "shared") m.shared = true;
      else if (s == "row_major") m.rowMajor = true;
      else if (s == "column_major") m.columnMajor = true;
      else if (s != "uniform" && s != "extern" && s != "const" && s != "volatile" && s != "inline")
        return m;
      lex_.next();
    }
  }

  // A type name; nullopt (nothing consumed) when the next token is not a type.
  std::optional<ParameterDesc> type() {
    const Token& t = lex_.peek();
    if (t.kind != TokenKind::Ident) return std::nullopt;
    if (t.text == "vector" || t.text == "matrix") {
      const bool isMatrix = t.text == "matrix";
      Token kw = lex_.next();
      ParameterDesc d;
      d.type = ParameterType::Float;
      d.cls = isMatrix ? ParameterClass::MatrixColumns : ParameterClass::Vector;
      d.rows = isMatrix ? 4 : 1;
      d.columns = 4;
      if (accept("<")) {  // vector<float, 3>, matrix<float, 4, 4>
        Token base = expectIdent("a scalar type in vector<…>/matrix<…>");
        auto scalar = numericTypeName(base.text);
        if (!scalar || scalar->cls != ParameterClass::Scalar)
          failCode("F1100", base.where, "expected a scalar type (float, int, bool, half), found '{}'", base.text);
        d.type = scalar->type;
        expect(",", "after the scalar type");
        d.rows = isMatrix ? dimension() : 1;
        if (isMatrix) expect(",", "between the matrix dimensions");
        d.columns = dimension();
        expect(">", "to close the type");
      }
      (void)kw;
      return d;
    }
    if (auto d = numericTypeName(t.text)) {
      lex_.next();
      return d;
    }
    if (preRelease_ && (t.text == "vec2" || t.text == "vec3" || t.text == "vec4")) {
      lex_.next();
      ParameterDesc d;
      d.cls = ParameterClass::Vector;
      d.columns = t.text[3] - '0';
      return d;
    }
    if (preRelease_ && t.text == "volumetexture") {
      lex_.next();
      ParameterDesc d;
      d.cls = ParameterClass::Object;
      d.type = ParameterType::Texture3D;
      return d;
    }
    if (auto a = aliases_.find(t.text); a != aliases_.end()) {
      lex_.next();
      return a->second;
    }
    if (auto o = objectType(t.text)) {
      lex_.next();
      ParameterDesc d;
      d.cls = ParameterClass::Object;
      d.type = *o;
      return d;
    }
    return std::nullopt;
  }

  int dimension() {
    const Token& n = lex_.peek();
    if (n.kind != TokenKind::Int || n.number < 1 || n.number > 4)
      failCode("F1100", n.where, "expected a dimension 1 to 4, found {}", describe(n));
    return int(lex_.next().number);
  }

  void topLevelDeclaration(EffectAst& ast) {
    const Modifiers mods = modifiers();
    const Token typeTok = lex_.peek();
    auto baseType = type();
    if (!baseType && typeTok.kind == TokenKind::Ident && userTypes_.count(typeTok.text)) {
      lex_.next();
      Token name = expectIdent("a name");
      if (lex_.peek().is("(")) {  // a function returning a struct
        skipFunction();
        ast.functions.push_back(name.text);
        return;
      }
      failCode("F1103", typeTok.where, "'{}' is a parameter of struct type '{}'; struct parameters are not supported, "
                                       "declare its members as parameters", name.text, typeTok.text);
    }
    if (!baseType) {
      if (typeTok.kind == TokenKind::Ident && lex_.peek().kind == TokenKind::Ident) {
        // A user type (struct) or an unknown word: `Name name …`.
        failCode("F1101", typeTok.where, "unknown type '{}' (expected a parameter type: float, float4, float4x4, "
                                         "int, bool, DWORD, vector, matrix, string, texture, sampler, vertexshader, "
                                         "pixelshader …)", typeTok.text);
      }
      failCode("F1100", typeTok.where, "expected a parameter declaration or 'technique', found {}", describe(typeTok));
    }
    if (mods.rowMajor && baseType->cls == ParameterClass::MatrixColumns) baseType->cls = ParameterClass::MatrixRows;
    if (mods.shared) baseType->flags |= kParameterShared;
    for (;;) {
      Token name = expectIdent("a name");
      if (lex_.peek().is("(")) {  // an HLSL function: kept for `compile`, body skipped
        skipFunction();
        ast.functions.push_back(name.text);
        return;
      }
      ParameterDecl p;
      p.desc = *baseType;
      p.desc.name = name.text;
      p.isStatic = mods.isStatic;
      p.where = name.where;
      if (accept("[")) {
        const Token& n = lex_.peek();
        if (n.kind != TokenKind::Int || n.number < 1 || n.number > 65536)
          failCode("F1100", n.where, "expected an array size, found {}", describe(n));
        p.desc.elements = int(lex_.next().number);
        expect("]", "after the array size");
      }
      if (accept(":")) {
        Token sem = expectIdent("a semantic after ':'");
        if (equalsNoCase(sem.text, "register")) {
          expect("(", "after register");
          skipPast(")");
        } else {
          p.desc.semantic = sem.text;
        }
      }
      if (lex_.peek().is("<")) p.annotations = annotations();
      if (accept("=")) initializer(p);
      ast.parameters.push_back(std::move(p));
      if (accept(",")) continue;
      expect(";", "after the declaration");
      return;
    }
  }

  void skipFunction() {
    expect("(", "");
    int depth = 1;
    while (depth > 0) {
      Token t = lex_.next();
      if (t.kind == TokenKind::End) failCode("F1100", t.where, "expected ')' to close the parameter list");
      if (t.is("(")) ++depth;
      if (t.is(")")) --depth;
    }
    if (accept(":")) expectIdent("a semantic");
    if (accept(";")) return;  // a prototype
    skipBraces();
  }

  void initializer(ParameterDecl& p) {
    const Token& t = lex_.peek();
    if (p.desc.type == ParameterType::VertexShader || p.desc.type == ParameterType::PixelShader) {
      p.shaderInit = shaderExpr();
      return;
    }
    if (p.desc.isSampler() && t.isIdent("sampler_state")) {
      lex_.next();
      p.samplerInit = samplerStateBlock();
      return;
    }
    p.init = expression();
  }

  std::vector<StateAssignment> samplerStateBlock() {
    expect("{", "after sampler_state");
    return stateBlock();
  }

  // `< type name = value; … >`
  std::vector<Annotation> annotations() {
    expect("<", "to open the annotations");
    std::vector<Annotation> list;
    while (!accept(">")) {
      try {
        list.push_back(annotation());
      } catch (const EffectError& e) {
        recover(e, false);
        if (lex_.peek().is("}")) break;  // the '>' is missing: the enclosing block reports it
      }
    }
    return list;
  }

  // `type name = value;`
  Annotation annotation() {
    Annotation a;
    const Token typeTok = lex_.peek();
    auto t = type();
    if (!t) failCode("F1100", typeTok.where, "expected an annotation type (string, int, float, bool …), found {}",
                              describe(typeTok));
    a.desc = *t;
    a.desc.name = expectIdent("an annotation name").text;
    expect("=", "after the annotation name");
    if (a.desc.type == ParameterType::String) {
      const Token& s = lex_.peek();
      if (s.kind != TokenKind::String) failCode("F1100", s.where, "expected a string, found {}", describe(s));
      a.text = lex_.next().text;
    } else {
      const Expr e = expression();
      constantNumbers(e, a.numbers);
    }
    expect(";", "after the annotation");
    return a;
  }

  // Numbers of a constant expression (annotations): literals, lists, constructors, negation.
  void constantNumbers(const Expr& e, std::vector<double>& out) {
    switch (e.kind) {
      case Expr::Kind::Number: out.push_back(e.number); return;
      case Expr::Kind::Bool: out.push_back(e.number); return;
      case Expr::Kind::List:
      case Expr::Kind::Call:
        for (const Expr& a : e.args) constantNumbers(a, out);
        return;
      case Expr::Kind::Unary:
        if (e.text == "-" && e.args[0].kind == Expr::Kind::Number) {
          out.push_back(-e.args[0].number);
          return;
        }
        break;
      default: break;
    }
    failCode("F1104", e.where, "an annotation value must be a constant");
  }

  TechniqueDecl technique() {
    TechniqueDecl t;
    t.where = lex_.next().where;
    if (lex_.peek().kind == TokenKind::Ident) t.name = lex_.next().text;
    if (lex_.peek().is("<")) t.annotations = annotations();
    expect("{", "to open the technique");
    while (!accept("}")) {
      try {
        t.passes.push_back(pass(t.name));
      } catch (const EffectError& e) {
        recover(e, false);
      }
    }
    return t;
  }

  PassDecl pass(const std::string& techniqueName) {
    const Token& p = lex_.peek();
    if (!p.isIdent("pass"))
      failCode("F1100", p.where, "expected 'pass' or '}}' in technique '{}', found {}", techniqueName, describe(p));
    PassDecl pass;
    pass.where = lex_.next().where;
    if (lex_.peek().kind == TokenKind::Ident) pass.name = lex_.next().text;
    if (lex_.peek().is("<")) pass.annotations = annotations();
    expect("{", "to open the pass");
    pass.states = stateBlock();
    return pass;
  }

  // State assignments up to the closing '}' (consumed); a bad one is reported and skipped.
  std::vector<StateAssignment> stateBlock() {
    std::vector<StateAssignment> states;
    while (!accept("}")) {
      try {
        states.push_back(stateAssignment());
      } catch (const EffectError& e) {
        recover(e, false);
      }
    }
    return states;
  }

  StateAssignment stateAssignment() {
    StateAssignment s;
    const Token& name = lex_.peek();
    if (name.kind != TokenKind::Ident)
      failCode("F1100", name.where, "expected a state name or '}}', found {}", describe(name));
    s.name = name.text;
    s.where = name.where;
    lex_.next();
    if (accept("[")) {
      s.index = expression();
      expect("]", "after the state index");
    }
    expect("=", fmt::format("after the state name '{}'", s.name));
    if (equalsNoCase(s.name, "VertexShader") || equalsNoCase(s.name, "PixelShader")) {
      s.shader = shaderExpr();
    } else if (lex_.peek().isIdent("sampler_state")) {
      lex_.next();
      s.samplerState = samplerStateBlock();
      s.isSamplerState = true;
    } else {
      s.value = expression();
    }
    expect(";", fmt::format("after the value of '{}'", s.name));
    return s;
  }

  ShaderExpr shaderExpr() {
    ShaderExpr sh;
    const Token& t = lex_.peek();
    sh.where = t.where;
    if (t.isIdent("NULL")) {
      lex_.next();
      sh.kind = ShaderExpr::Kind::Null;
      return sh;
    }
    if (t.isIdent("decl")) {
      lex_.next();
      Token brace = expect("{", "after decl");
      sh.decl = lex_.rawBlockAfterBrace(brace.where, false);
      const Token& a = lex_.peek();
      if (!a.isIdent("asm")) failCode("F1100", a.where, "expected 'asm {{' after the decl block, found {}", describe(a));
      lex_.next();
    }
    if (sh.decl || lex_.peek().isIdent("asm")) {
      if (!sh.decl) lex_.next();
      Token brace = expect("{", "after asm");
      sh.kind = ShaderExpr::Kind::Asm;
      sh.assembly = lex_.rawBlockAfterBrace(brace.where, true);
      return sh;
    }
    if (lex_.peek().isIdent("compile")) {
      lex_.next();
      sh.kind = ShaderExpr::Kind::Compile;
      sh.profile = expectIdent("a shader profile after compile (vs_1_1 … ps_3_0)").text;
      sh.entry = expectIdent("an entry point name").text;
      expect("(", "after the entry point");
      if (!accept(")")) {
        do sh.args.push_back(expression());
        while (accept(","));
        expect(")", "after the arguments");
      }
      return sh;
    }
    sh.kind = ShaderExpr::Kind::Reference;
    sh.reference = expression();
    return sh;
  }

  // ---- expressions (C precedence: | ^ & , comparisons, + -, * / %, unary, postfix)
  Expr expression() {
    depth_ = 0;
    return binary(0);
  }

  static int precedence(const Token& t) {
    if (t.kind != TokenKind::Punct) return -1;
    static constexpr std::pair<std::string_view, int> kOps[] = {
        {"||", 1}, {"&&", 2}, {"|", 3}, {"^", 4}, {"&", 5}, {"==", 6}, {"!=", 6},
        {"<", 7},  {">", 7},  {"<=", 7}, {">=", 7}, {"<<", 8}, {">>", 8}, {"+", 9},
        {"-", 9},  {"*", 10}, {"/", 10}, {"%", 10}};
    for (auto [op, p] : kOps)
      if (t.text == op) return p;
    return -1;
  }

  Expr binary(int minPrec) {
    Expr lhs = unary();
    for (;;) {
      const Token& op = lex_.peek();
      const int p = precedence(op);
      // '>' closes annotations and parameter references; '?:' is not an effect-state form.
      if (p < 0 || p < minPrec || (op.is(">") && angleDepth_ > 0)) return lhs;
      Token o = lex_.next();
      Expr rhs = binary(p + 1);
      Expr e;
      e.kind = Expr::Kind::Binary;
      e.where = o.where;
      e.text = o.text;
      e.args.push_back(std::move(lhs));
      e.args.push_back(std::move(rhs));
      lhs = std::move(e);
    }
  }

  Expr unary() {
    if (++depth_ > kMaxExprDepth) failCode("F1105", lex_.peek().where, "expression nested too deeply");
    const Token& t = lex_.peek();
    if (t.is("-") || t.is("!") || t.is("~") || t.is("+")) {
      Token op = lex_.next();
      Expr inner = unary();
      if (op.text == "+") return inner;
      Expr e;
      e.kind = Expr::Kind::Unary;
      e.where = op.where;
      e.text = op.text;
      e.args.push_back(std::move(inner));
      return e;
    }
    return postfix(primary());
  }

  Expr postfix(Expr e) {
    for (;;) {
      if (lex_.peek().is("[")) {
        Token b = lex_.next();
        Expr idx = binary(0);
        expect("]", "after the index");
        Expr x;
        x.kind = Expr::Kind::Index;
        x.where = b.where;
        x.args.push_back(std::move(e));
        x.args.push_back(std::move(idx));
        e = std::move(x);
      } else if (lex_.peek().is(".")) {
        Token d = lex_.next();
        Expr x;
        x.kind = Expr::Kind::Member;
        x.where = d.where;
        x.text = expectIdent("a member or swizzle after '.'").text;
        x.args.push_back(std::move(e));
        e = std::move(x);
      } else {
        return e;
      }
    }
  }

  Expr primary() {
    {
      const Token& p = lex_.peek();
      if (p.kind == TokenKind::End || (p.kind == TokenKind::Punct && !p.is("(") && !p.is("{") && !p.is("<")))
        failCode("F1100", p.where, "expected a value, found {}", describe(p));
    }
    Token t = lex_.next();
    Expr e;
    e.where = t.where;
    switch (t.kind) {
      case TokenKind::Int:
      case TokenKind::Float:
        e.kind = Expr::Kind::Number;
        e.number = t.number;
        e.isInt = t.kind == TokenKind::Int;
        return e;
      case TokenKind::String:
        e.kind = Expr::Kind::String;
        e.text = t.text;
        return e;
      case TokenKind::Ident:
        if (t.text == "true" || t.text == "TRUE" || t.text == "false" || t.text == "FALSE") {
          e.kind = Expr::Kind::Bool;
          e.number = (t.text == "true" || t.text == "TRUE") ? 1 : 0;
          return e;
        }
        if (t.isIdent("NULL")) {
          e.kind = Expr::Kind::Null;
          return e;
        }
        if (lex_.peek().is("(")) {  // constructor / intrinsic call
          lex_.next();
          e.kind = Expr::Kind::Call;
          e.text = t.text;
          if (!accept(")")) {
            do e.args.push_back(binary(0));
            while (accept(","));
            expect(")", "to close the argument list");
          }
          return e;
        }
        e.kind = Expr::Kind::Name;
        e.text = t.text;
        return e;
      case TokenKind::Punct:
        if (t.is("(")) {
          Expr inner = binary(0);
          expect(")", "to close '('");
          return inner;
        }
        if (t.is("{")) {
          e.kind = Expr::Kind::List;
          if (!accept("}")) {
            do {
              if (lex_.peek().is("}")) break;  // trailing comma
              e.args.push_back(binary(0));
            } while (accept(","));
            expect("}", "to close the list");
          }
          return e;
        }
        if (t.is("<")) {  // <param>
          ++angleDepth_;
          Expr inner = postfix(primary());
          --angleDepth_;
          if (inner.kind != Expr::Kind::Name && inner.kind != Expr::Kind::Index && inner.kind != Expr::Kind::Member)
            failCode("F1100", t.where, "expected a parameter name inside '<…>'");
          expect(">", "to close the parameter reference");
          e.kind = Expr::Kind::ParamRef;
          e.args.push_back(std::move(inner));
          return e;
        }
        break;
      case TokenKind::End: break;
    }
    failCode("F1100", t.where, "expected a value, found {}", describe(t));
  }

  Lexer lex_;
  DiagnosticSink& sink_;
  bool preRelease_ = false;
  std::set<std::string> userTypes_;                    // struct names and typedefs of them
  std::map<std::string, ParameterDesc> aliases_;        // typedefs of parameter types
  int depth_ = 0;
  int angleDepth_ = 0;
};

}  // namespace

EffectAst parseEffect(std::string_view text, const std::string& fileName, const EffectOptions& options) {
  DiagnosticSink sink;
  EffectAst ast = Parser(text, fileName, options, sink).run();
  if (sink.hasErrors()) {
    std::string message;
    for (const Diagnostic& d : sink.all()) message += (message.empty() ? "" : "\n") + d.str();
    throw Error(std::move(message));
  }
  return ast;
}

}  // namespace refx::effect::detail
