// Code generation for ps_1_1 … ps_1_4 (the DirectX 8 pixel shader models).
#pragma once
#include <string>

#include "hlsl/ir.h"

namespace refx::hlsl::detail {

// IR → ps_1_x instructions for programs that fit the model: texture reads at the
// start, then arithmetic that maps onto the ps_1_x instructions and their
// modifiers. What does not fit is an error naming the construct, the profile and
// the expression's position (X4532, X4550 for constants).
shader::Shader generateCodePs1x(IrProgram& ir, const std::string& creator, DiagnosticSink& sink,
                                const SourceLocation& entryWhere);

}  // namespace refx::hlsl::detail
