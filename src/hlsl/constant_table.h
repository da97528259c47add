// The CTAB comment block compiled shaders carry (bytecode reference §8.1): names,
// register sets and ranges, types and default values of the uniforms, laid out as
// fxc lays it out, so tools that bind constants by name work with refx's output.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "hlsl/ast.h"
#include "hlsl/ir.h"
#include "refx/shader/bytecode.h"

namespace refx::hlsl::detail {

struct ConstantTable {
  enum class RegisterSet : uint16_t { Bool = 0, Int4 = 1, Float4 = 2, Sampler = 3 };
  struct Constant {
    std::string name;
    RegisterSet registerSet = RegisterSet::Float4;
    int registerIndex = 0;
    int registerCount = 0;
    Type type;
    std::vector<float> defaultValue;  // registerCount * 4 floats, or empty
  };
  std::string creator;
  std::string target;  // "ps_2_0"
  uint32_t versionToken = 0;
  uint32_t flags = 0;
  std::vector<Constant> constants;

  // The comment payload: 'CTAB' then the table, padded to whole DWORDs.
  std::vector<uint32_t> encode() const;
};

// The constant table of a compiled program, as a comment instruction: the int and bool
// registers of flow control, the float registers of the uniforms the code reads (not
// the preshader's outputs), the samplers.
shader::Instruction constantTableComment(const IrProgram& ir, const std::string& creator, const shader::Version& v);

}  // namespace refx::hlsl::detail
