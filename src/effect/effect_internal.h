// What a loaded Effect holds, for the layer's own writers (the fx_2_0 binary): the
// parameters with their values, the techniques' bound state assignments with their
// values classified (a constant, a parameter, an expression of parameters, a shader),
// and the shaders exactly as they were assembled or compiled.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ast.h"
#include "fxlc.h"
#include "refx/effect/effect.h"
#include "refx/hlsl/compiler.h"
#include "state_table.h"

namespace refx::effect::detail {

struct ShaderContents {
  bool vertex = true;
  std::vector<uint32_t> tokens;  // as assembled or compiled (compiled: CTAB comment first)
  bool compiled = false;         // from `compile PROFILE Entry(args)`
  std::optional<hlsl::Preshader> preshader;
  std::string profile, entry;  // compiled ones
  std::vector<std::string> entryArguments;
};
using ShaderContentsRef = std::shared_ptr<const ShaderContents>;

struct StateContents {
  enum class Kind {
    Constant,      // numbers / registers / dword below
    Parameter,     // the current value of `parameter` ("name" or "name[i]")
    Expression,    // an expression that reads parameters: `expression`
    Shader,        // an asm block or a compile expression: `shader`
    Null,          // NULL (shaders, textures)
    SamplerBlock,  // Sampler[n] = sampler_state { … }: `samplerStates`
  };
  std::string name;
  StateInfo info;
  int index = 0;
  SourceLocation where;
  Kind kind = Kind::Constant;
  // Constant values, by target: render/stage/sampler states, LightEnable, LightType
  // and FVF take `dword` (float bits for float states); transforms, lights, materials
  // and NPatchMode take `numbers`; shader constants take `registers` (4 per register,
  // float, or int / 0-1 for the I and B forms).
  uint32_t dword = 0;
  std::vector<double> numbers;
  std::vector<double> registers;
  std::string parameter;
  const Expr* expression = nullptr;  // valid while the effect lives
  ShaderContentsRef shader;
  std::vector<StateContents> samplerStates;
  // The referenced parameter's value count (Parameter), for placeholders.
  int referencedValues = 0;
  // Expression: the expression as FXLC code whose first `fxlcComponents` outputs are
  // the state's value (as many as the state takes: registers for shader constants);
  // when it cannot be written as FXLC, `fxlcError` says why.
  std::shared_ptr<const FxlcProgram> fxlc;
  int fxlcComponents = 0;
  std::string fxlcError;
};

struct ParameterContents {
  ParameterDesc desc;
  std::vector<Annotation> annotations;
  std::vector<uint32_t> raw;  // numeric defaults, row-major per element
  std::string text;           // string parameters
  ShaderContentsRef shader;   // shader parameters with a shader
  bool hasSamplerState = false;
  std::vector<StateContents> samplerStates;
};

struct PassContents {
  PassDesc desc;
  std::vector<StateContents> states;
};

struct TechniqueContents {
  TechniqueDesc desc;
  std::vector<PassContents> passes;
};

struct EffectContents {
  std::string fileName;
  std::vector<ParameterContents> parameters;
  std::vector<TechniqueContents> techniques;
};

struct EffectAccess {
  // Throws refx::Error (file:line:col) for a state whose value cannot be classified.
  static EffectContents contents(const Effect& effect);
};

}  // namespace refx::effect::detail
