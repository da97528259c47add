// The parsed form of an effect file, before names are bound to parameters and
// states: what the text says, with positions.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lexer.h"
#include "refx/effect/effect.h"

namespace refx::effect::detail {

struct FxlcProgram;

struct Expr {
  enum class Kind {
    Number,    // number (isInt for integer literals)
    Bool,      // true / false
    String,    // "text"
    Name,      // identifier: a parameter or a state keyword (decided by the state)
    ParamRef,  // <name> or <name[i]>: a parameter reference (fx_1_0 form)
    List,      // { a, b, … }
    Call,      // float4(…) constructor
    Unary,     // text = "-", "!", "~"
    Binary,    // text = "+", "-", "*", "/", "|", "&", "<", …
    Index,     // args[0][args[1]]
    Member,    // args[0].text (swizzle or struct member)
    Null,      // NULL
    Preshader, // an fx_2_0 FXLC expression: `preshader`, result = its first `components` outputs
  };
  Kind kind = Kind::Number;
  SourceLocation where;
  double number = 0;
  bool isInt = false;
  std::string text;
  std::vector<Expr> args;
  std::shared_ptr<const FxlcProgram> preshader;
  int components = 0;
};

// The right-hand side of a shader state or the initializer of a shader variable.
struct ShaderExpr {
  enum class Kind { Null, Asm, Compile, Reference, Bytecode };
  Kind kind = Kind::Null;
  SourceLocation where;
  std::optional<RawBlock> decl;  // DirectX 8 `decl { … }` before `asm`
  RawBlock assembly;             // Asm
  std::string profile, entry;    // Compile
  std::vector<Expr> args;        // Compile: the entry point's uniform arguments
  Expr reference;                // Reference: <vs>, (vs), vs, or an array element
  std::vector<uint32_t> tokens;  // Bytecode: a shader from an fx_2_0 binary
};

struct StateAssignment {
  std::string name;
  std::optional<Expr> index;  // Name[index]
  SourceLocation where;
  Expr value;
  std::optional<ShaderExpr> shader;       // VertexShader / PixelShader states
  std::vector<StateAssignment> samplerState;  // `sampler_state { … }` value
  bool isSamplerState = false;
};

struct ParameterDecl {
  ParameterDesc desc;
  bool isStatic = false;  // not visible to the application
  SourceLocation where;
  std::vector<Annotation> annotations;
  std::optional<Expr> init;
  std::optional<ShaderExpr> shaderInit;
  std::optional<std::vector<StateAssignment>> samplerInit;
};

struct PassDecl {
  std::string name;
  SourceLocation where;
  std::vector<Annotation> annotations;
  std::vector<StateAssignment> states;
};

struct TechniqueDecl {
  std::string name;
  SourceLocation where;
  std::vector<Annotation> annotations;
  std::vector<PassDecl> passes;
};

struct EffectAst {
  std::vector<ParameterDecl> parameters;
  std::vector<TechniqueDecl> techniques;
  std::vector<std::string> functions;  // HLSL functions (compiled by `compile`)
  std::vector<std::string> files;      // the effect and its includes
  // The DirectX 9 white paper's pre-release dialect, announced by an `fx.2.0` line:
  // vec2/vec3/vec4 and volumetexture here, and `compile` uses the HLSL compiler's
  // compatibility option.
  bool preReleaseDialect = false;
};

// A numeric type name ("float4x3", "int2", "DWORD"): its class, scalar type and
// dimensions (matrices as MatrixColumns); nullopt for any other word.
std::optional<ParameterDesc> numericTypeName(std::string_view name);

// Throws refx::Error listing every syntax error of the file, one per line, each with
// its code (F10xx lexical and preprocessor, F11xx syntax).
EffectAst parseEffect(std::string_view text, const std::string& fileName, const EffectOptions& options);

}  // namespace refx::effect::detail
