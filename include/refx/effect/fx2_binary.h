// Compiled D3D9 effects: the fx_2_0 binary that `fxc /T fx_2_0` writes and
// D3DXCreateEffect (and MojoShader, Wine's d3dx9) load — parameters with types,
// semantics, annotations and default values, techniques and passes of state
// assignments (operation numbers of the effect state table), shaders as bytecode.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "refx/effect/effect.h"

namespace refx::effect {

struct Fx2WriteOptions {
  // MojoShader (and FNA) cannot load a shader state that names a shader parameter
  // (`VertexShader = <vs>;`, a usage-1 reference); with this option the parameter's
  // bytecode is written inline in the pass instead, which loads the same shader.
  bool inlineShaderReferences = false;
};

struct Fx2Binary {
  std::vector<uint8_t> bytes;
  // Readable listing of what was written: parameters with types, semantics, defaults
  // and annotations; techniques, passes and states with their operation numbers;
  // shaders disassembled.
  std::string listing;
};

// Serialises a loaded effect. State values that are expressions of parameters are
// written as FXLC expressions, compiled shaders with their preshader (PRES). Throws
// refx::Error ("file:line:col: error: …") for what cannot be written: a technique that
// did not load, an expression FXLC cannot express (bitwise operators, a shader chosen
// by a parameter index), a struct parameter.
Fx2Binary writeFx2(const Effect& effect, const Fx2WriteOptions& options = {});

// The operation number of an effect state in the fx_2_0 state table (0 … 178):
// "ZEnable" → 0, "ColorOp" → 103, "VertexShaderConstant4" → 155, "Sampler" → 178.
// Case-insensitive; nullopt for an unknown name.
std::optional<uint32_t> fx2StateOperation(std::string_view stateName);

}  // namespace refx::effect
