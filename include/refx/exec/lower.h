// Lowering of decoded shader bytecode (refx::shader::Shader) into the exec IR, so
// shaders run on the same interpreter as fixed-function programs.
//
// Register conventions of lowered programs: exec/abi.h (shared with the fixed-function
// builders and the rasterizer). Ranges and register counts: the version's rules
// (shader/version_rules.h).
//   precision       ps_1_x values written to r#/t# clamp to ±pixelShader1xMaxValue
//                          (ps_1_4: at least 8), constants to [-1, 1], v0/v1 to [0, 1]
//                          (saturated in place at the start of the program, ps_2_x too)
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "refx/core/precision.h"
#include "refx/exec/abi.h"
#include "refx/exec/ir.h"
#include "refx/shader/bytecode.h"

namespace refx::exec {

using refx::Precision;

struct ShaderLoweringOptions {
  Precision precision = Precision::Exact;
  // The profile's PixelShader1xMaxValue: ps_1_x intermediates clamp to ±this
  // (1 on DX8 parts, 8 on ps_1_4 parts, FLT_MAX = not clamped on D3D9 float parts).
  float pixelShader1xMaxValue = 1.0f;
  // ps_1_1–1_3: bit m set when stage m has D3DTTFF_PROJECTED, so `tex t(m)` divides
  // its coordinates by w (ignored by ps_1_4 and later, as in D3D).
  uint8_t projectedTextureStages = 0;
  // The caller guarantees interpolated v0/v1 within [0, 1] (vertex colors clamped per
  // vertex, as D3D does for oD0/oD1): exact-precision programs then skip the
  // saturation of the color inputs at their start.
  bool colorInputsInRange = false;
};

struct LoweredShader {
  Program program;
  shader::Version version;
  // Vertex shaders: which declaration element feeds each input register.
  struct InputBinding {
    uint8_t reg;
    shader::DeclUsage usage;
    uint8_t usageIndex;
  };
  std::vector<InputBinding> vertexInputs;
  // Samplers the shader reads (bit s = sampler s) and their declared texture type.
  uint32_t samplersUsed = 0;
  std::array<shader::TextureType, 16> samplerTypes{};
  bool writesDepth = false;  // oDepth / texdepth / texm3x2depth
  bool kills = false;        // texkill
  int floatConstantsRead = 0;  // 1 + highest c# read (relative reads: the whole file)
  // Stages whose bump environment (kConstBumpEnv) the program reads: texbem, texbeml, bem.
  uint8_t bumpEnvStages = 0;
};

// Throws refx::Error if the shader uses something the executor cannot run.
LoweredShader lowerShader(const shader::Shader& shader, const ShaderLoweringOptions& options = {});

}  // namespace refx::exec
