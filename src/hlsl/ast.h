// The HLSL syntax tree and its types.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "refx/core/diagnostics.h"

namespace refx::hlsl::detail {

enum class BaseType : uint8_t { Void, Bool, Int, Uint, Half, Float, Double, Sampler, Texture, String, Struct };
enum class TypeClass : uint8_t { Void, Scalar, Vector, Matrix, Object, Struct };
enum class SamplerDim : uint8_t { Any, Dim1D, Dim2D, Dim3D, Cube };

struct StructDef;

// A type as the checker sees it. Arrays wrap an element type.
struct Type {
  TypeClass cls = TypeClass::Void;
  BaseType base = BaseType::Void;
  int rows = 1, cols = 1;  // vector: rows 1; matrix: rows x cols
  SamplerDim dim = SamplerDim::Any;
  const StructDef* structDef = nullptr;
  int arraySize = 0;  // > 0: an array of `element`
  std::shared_ptr<const Type> element;
  int packing = 0;    // matrices: 0 default, 1 row_major, 2 column_major

  static Type scalar(BaseType b) { Type t; t.cls = TypeClass::Scalar; t.base = b; return t; }
  static Type vector(BaseType b, int n) {
    Type t; t.cls = n == 1 ? TypeClass::Scalar : TypeClass::Vector; t.base = b; t.cols = n; return t;
  }
  static Type matrix(BaseType b, int r, int c) { Type t; t.cls = TypeClass::Matrix; t.base = b; t.rows = r; t.cols = c; return t; }
  static Type arrayOf(const Type& e, int n) {
    Type t = e; t.arraySize = n; t.element = std::make_shared<Type>(e); return t;
  }
  bool isArray() const { return arraySize > 0; }
  bool isNumeric() const { return !isArray() && (cls == TypeClass::Scalar || cls == TypeClass::Vector || cls == TypeClass::Matrix); }
  bool isScalar() const { return !isArray() && cls == TypeClass::Scalar; }
  bool isSampler() const { return !isArray() && cls == TypeClass::Object && base == BaseType::Sampler; }
  bool isVoid() const { return cls == TypeClass::Void; }
  int components() const { return rows * cols; }  // numeric only
  // Components of the whole value, flattened (structs and arrays included); samplers count 1.
  int flatSize() const;
  std::string name() const;
};

struct StructMember {
  std::string name;
  Type type;
  std::string semantic;
  bool interpolationModifier = false;
};
struct StructDef {
  std::string name;
  std::vector<StructMember> members;
  SourceLocation where;
};

struct Expr;
using ExprPtr = std::unique_ptr<Expr>;

enum class ExprKind : uint8_t {
  Literal,     // number or bool
  Name,        // variable reference
  Unary,       // op: - + ! ~ ++pre --pre
  Postfix,     // op: ++ --
  Binary,      // op: + - * / % < > <= >= == != && || & | ^ << >>
  Assign,      // op: = += -= *= /= %= &= |= ^= <<= >>=
  Ternary,     // args: cond, a, b
  Call,        // name(args), intrinsic or user function
  Constructor, // type(args)
  Cast,        // (type) arg
  Member,      // arg.name: swizzle or struct member
  Index,       // args: base, index
  Comma,
  InitList,    // { a, b, … }
  StringLit,
};

struct Expr {
  ExprKind kind;
  SourceLocation where;
  std::string op;     // operator text, called name, member name
  double number = 0;  // Literal
  bool isFloat = false, isBool = false;
  Type type;          // Constructor / Cast target
  std::vector<ExprPtr> args;
  int height = 1;     // nodes on the longest path down to a leaf (the parser bounds it)
};

struct Stmt;
using StmtPtr = std::unique_ptr<Stmt>;

struct Annotation {
  std::string name;
  Type type;
  ExprPtr value;
};

// A declared variable (global, local, parameter) — one declarator.
struct VarDecl {
  std::string name;
  Type type;
  std::string semantic;
  std::string registerBinding;  // ": register(c0)"
  ExprPtr init;
  bool isStatic = false, isConst = false, isUniform = false, isExtern = false, isShared = false;
  bool isIn = true, isOut = false;  // parameters
  std::vector<Annotation> annotations;
  SourceLocation where;
  // sampler_state { … } initialiser kept for the effect framework (state name, value expr).
  std::vector<std::pair<std::string, ExprPtr>> samplerStates;
};

enum class StmtKind : uint8_t { Expr, Decl, Block, If, For, While, Do, Break, Continue, Return, Discard, Empty };

struct Stmt {
  StmtKind kind;
  SourceLocation where;
  std::vector<std::unique_ptr<VarDecl>> decls;  // Decl
  ExprPtr expr;   // Expr, Return value, If/While/Do condition, For condition
  ExprPtr step;   // For
  StmtPtr init;   // For
  StmtPtr body;   // If then, loops
  StmtPtr elseBody;
  std::vector<StmtPtr> block;
  std::vector<std::string> attributes;  // [unroll] [loop] [branch] [flatten] (lower-case names)
  int unrollCount = 0;
};

struct FunctionDecl {
  std::string name;
  Type returnType;
  std::string returnSemantic;
  std::vector<std::unique_ptr<VarDecl>> params;
  StmtPtr body;  // null for a prototype
  SourceLocation where;
  bool syntaxErrors = false;  // parts of the body were skipped: no missing-return error
};

// Whole translation unit. Technique blocks of effects are skipped by the parser.
struct Program {
  std::vector<std::unique_ptr<StructDef>> structs;
  std::vector<std::unique_ptr<VarDecl>> globals;
  std::vector<std::unique_ptr<FunctionDecl>> functions;
};

}  // namespace refx::hlsl::detail
