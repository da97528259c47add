// D3D9 tokens → assembly text that the assembler turns back into the same tokens.
#pragma once
#include <cstdint>
#include <span>
#include <string>

#include "refx/shader/bytecode.h"

namespace refx::shader {

struct DisassemblyOptions {
  // fxc /Fc style: a header comment block (version, CTAB constants) and, after
  // the code, "// approximately N instruction slots used (T texture, A arithmetic)".
  bool listing = false;
};

std::string disassemble(const Shader& shader, const DisassemblyOptions& options = {});
std::string disassemble(std::span<const uint32_t> tokens, const DisassemblyOptions& options = {});

}  // namespace refx::shader
