// Shader assembly text (vs_1_1 … vs_3_0, ps_1_1 … ps_3_0, as psa/vsa and fxc read
// it) → decoded Shader → D3D9 tokens.
#pragma once
#include <cstdint>
#include <string_view>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/shader/bytecode.h"

namespace refx::shader {

// Parses one shader, reporting every error to `diagnostics` with a code (A2xxx, listed
// in docs/diagnostics.md), the position and a message naming the instruction, operand
// and rule. After an error parsing goes on at the next line, so one run reports every
// bad line (at most 100 errors, then it stops). The returned Shader holds the
// instructions that parsed; it is usable only when no error was reported. Instructions
// carry their source position. Assembly checks syntax and encodability only; version
// rules are the validator's.
Shader assemble(std::string_view source, std::string_view fileName, DiagnosticSink& diagnostics);

// The same, throwing refx::Error on any error; its message lists every diagnostic, one
// per line: "file:line:col: error A2001: unknown instruction 'foo'".
Shader assemble(std::string_view source, std::string_view fileName = "<input>");

// assemble() then encode().
std::vector<uint32_t> assembleTokens(std::string_view source, std::string_view fileName = "<input>");

}  // namespace refx::shader
