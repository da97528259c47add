// Shader assembly text (vs_1_1 … vs_3_0, ps_1_1 … ps_3_0, as psa/vsa and fxc read
// it) → decoded Shader → D3D9 tokens.
#pragma once
#include <cstdint>
#include <string_view>
#include <vector>

#include "refx/shader/bytecode.h"

namespace refx::shader {

// Parses one shader. Instructions carry their source position. Throws refx::Error
// "file:line:col: error: …" naming the instruction, operand and rule on bad input.
// Assembly checks syntax and encodability only; version rules are the validator's.
Shader assemble(std::string_view source, std::string_view fileName = "<input>");

// assemble() then encode().
std::vector<uint32_t> assembleTokens(std::string_view source, std::string_view fileName = "<input>");

}  // namespace refx::shader
