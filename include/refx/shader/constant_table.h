// Reading the constant table (CTAB comment block, bytecode reference §8) that compiled
// shaders carry: which uniform lives in which registers, with its type. Effects bind
// parameters to shaders through it, as D3DX does (ID3DXConstantTable).
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "refx/shader/bytecode.h"

namespace refx::shader {

// D3DXREGISTER_SET
enum class RegisterSet : uint16_t { Bool = 0, Int4 = 1, Float4 = 2, Sampler = 3 };
// D3DXPARAMETER_CLASS as the table stores it
enum class ConstantClass : uint16_t { Scalar = 0, Vector, MatrixRows, MatrixColumns, Object, Struct };

struct ShaderConstant {
  std::string name;
  RegisterSet registerSet = RegisterSet::Float4;
  int registerIndex = 0;
  int registerCount = 0;
  ConstantClass cls = ConstantClass::Scalar;
  int type = 3;  // D3DXPARAMETER_TYPE: 1 bool, 2 int, 3 float, 10..14 samplers
  int rows = 1, columns = 1, elements = 1;
  std::vector<float> defaultValue;  // registerCount * 4 floats when the table has one

  std::string typeName() const;  // "float4", "row_major float4x4", "sampler2D", "float3[8]"
};

struct ShaderConstantTable {
  std::string creator, target;
  std::vector<ShaderConstant> constants;
  const ShaderConstant* find(std::string_view name) const;
};

// The table of one comment payload ('CTAB' then the table); nullopt when the payload is
// another comment or too damaged to read. Out-of-range offsets end the reading early
// instead of reading past the block.
std::optional<ShaderConstantTable> readConstantTable(std::span<const uint32_t> comment);
// The table of the first CTAB comment in a shader.
std::optional<ShaderConstantTable> readConstantTable(const Shader& shader);

}  // namespace refx::shader
