// Tokens → syntax tree. Errors are reported to the sink and parsing resumes at the
// next statement or declaration, so one run reports every syntax error.
#pragma once
#include <vector>

#include "hlsl/ast.h"
#include "hlsl/token.h"

namespace refx::hlsl::detail {

struct ParseOptions {
  bool compatibility = false;   // pre-release dialect (vec3, volumetexture, fx.2.0 header)
  bool rowMajorDefault = false;  // initial #pragma pack_matrix state
};

Program parse(const std::vector<Token>& tokens, const ParseOptions& options, DiagnosticSink& sink);

// Parses one expression (used for entry-point arguments given as text).
ExprPtr parseExpression(const std::vector<Token>& tokens, DiagnosticSink& sink);

}  // namespace refx::hlsl::detail
