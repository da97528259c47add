// Lowering of decoded shader bytecode (refx::shader::Shader) into the exec IR, so
// shaders run on the same interpreter as fixed-function programs.
//
// Register conventions of lowered programs (shared with the fixed-function builders):
//   vertex inputs   Input  v# of the shader as written (dcl says which element feeds it)
//   vertex outputs  Output 0 position, 1 diffuse (oD0), 2 specular (oD1), 3..10 oT0..oT7,
//                          11 fog (.x), 12 point size (.x); vs_3_0 o# are mapped here by
//                          their dcl semantic
//   pixel inputs    Input  0 diffuse v0, 1 specular v1, 2..9 texcoord t0..t7, 10 fog,
//                          11 position (vPos: screen x, y, z, w), 12 face (vFace .x: +1/-1);
//                          ps_3_0 v# are mapped here by their dcl semantic
//   pixel outputs   Output 0..3 oC0..oC3, 4 oDepth (.x)
//   constants       Const  0..N-1 the float constants c# set through the API (local
//                          `def` constants are resolved by the lowering itself);
//                          pixel shaders additionally read the texture stages' bump
//                          environment at kConstBumpEnv (see below), so their
//                          constant array needs kConstBumpEnv + kConstBumpEnvCount
//                          entries when bumpEnvStages is set
//                   ConstInt / ConstBool: i# / b# through ExecContext::intConstants /
//                          boolConstants (defi / defb resolved by the lowering)
//   samplers        Instr::sampler = the stage: ps_1_x stage m (t#/r# number), ps_2_0+
//                          s#; vertex shaders (vs_3_0 texldl) use s0..s3, which the
//                          device binds to D3DVERTEXTEXTURESAMPLER0..3
//   precision       ps_1_x values written to r#/t# clamp to ±pixelShader1xMaxValue
//                          (ps_1_4: at least 8), constants to [-1, 1], v0/v1 to [0, 1]
//                          (saturated in place at the start of the program, ps_2_x too)
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "refx/exec/ir.h"
#include "refx/shader/bytecode.h"

namespace refx::exec {

// exact: fp32 with the version's ranges clamped. hardware: ps_1_x values are also
// quantised to the fixed point of the era's parts.
enum class Precision : uint8_t { Exact, Hardware };

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

// Pixel shaders read BUMPENVMAT00/01/10/11 of texture stage n at
// Const[kConstBumpEnv + 2n] = (m00, m01, m10, m11) and BUMPENVLSCALE/LOFFSET at
// Const[kConstBumpEnv + 2n + 1] = (lscale, loffset, 0, 0).
constexpr int kConstBumpEnv = 256;
constexpr int kConstBumpEnvCount = 16;  // 8 stages x 2
constexpr int kPixelInFace = 12;
constexpr int kPixelOutDepth = 4;

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
