// Fixed-function pixel processing (texture stage cascade, specular add, fog)
// compiled once per draw plan into an exec::Program, so the per-pixel work runs on the
// same interpreter as pixel shaders.
#pragma once
#include <array>
#include <vector>

#include "refx/exec/abi.h"
#include "refx/exec/ir.h"
#include "refx/pipeline/state.h"
#include "refx/resource/texture.h"

namespace refx::pipeline {

// Pixel program register conventions shared by fixed function and pixel shaders
// (exec/abi.h). Fixed-function programs read the interpolated inputs and write the
// color alone.
using exec::kPixelInDiffuse;
using exec::kPixelInSpecular;
using exec::kPixelInTex0;
using exec::kPixelInFog;
using exec::kPixelInPosition;
constexpr int kPixelInputCount = exec::kPixelInterpolatedInputCount;
using exec::kPixelOutColor;
constexpr int kPixelOutputCount = exec::kPixelOutColor + 1;

struct FixedFunctionPixelConfig {
  std::array<const Texture*, 8> textures{};  // texture bound to sampler n (nullptr: none)
  // true: no texture stages (an empty program with the register counts set), for
  // appending specular/fog after a pixel shader.
  bool shaderPath = false;
};

// The texture stage cascade; its final CURRENT is written to kPixelOutColor.
// Specular add and fog are not included: the caller appends them with
// appendSpecularAndFog(p, state, true).
exec::Program buildFixedFunctionPixelProgram(const DeviceState& state,
                                             const FixedFunctionPixelConfig& cfg);

// Fog and specular stages appended after any pixel program writing kPixelOutColor.
// Reads and rewrites output kPixelOutColor in place. The specular add is applied
// only when fixedFunctionStages is true (pixel shaders add specular themselves).
// The fog's structure depends on FOGTABLEMODE, FOGVERTEXMODE, whether FOGSTART and
// FOGEND are equal and whether the projection is perspective; its values are constants.
void appendSpecularAndFog(exec::Program& p, const DeviceState& state, bool fixedFunctionStages);

// The constants fixed-function pixel programs and the appended fog read (exec/abi.h:
// bump environment, TFACTOR, stage CONSTANTs, fog), written into `constants` (grown to
// exec::kConstFixedPixelEnd if smaller; entries below kConstBumpEnv are left as they are).
void fixedFunctionPixelConstants(const DeviceState& state, std::vector<Vec4>& constants);

}  // namespace refx::pipeline
