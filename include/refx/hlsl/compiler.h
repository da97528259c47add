// DirectX 9 HLSL → D3D9 shader bytecode (vs_1_1 … vs_3_0, ps_1_1 … ps_3_0), the job
// fxc did. Everything it produces passes refx's own validator for the profile.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/shader/bytecode.h"
#include "refx/shader/constant_table.h"

namespace refx::hlsl {

struct MacroDefinition {
  std::string name;
  std::string value;  // "" defines the name as empty (fxc's /D NAME)
};

struct CompileOptions {
  std::string profile = "ps_2_0";  // vs_1_1 vs_2_0 vs_2_x vs_3_0 ps_1_1..ps_1_4 ps_2_0 ps_2_x ps_3_0
  std::string entry = "main";
  std::vector<MacroDefinition> defines;
  std::vector<std::string> includeDirs;  // searched after the including file's directory
  bool rowMajorDefault = false;          // /Zpr: matrices row_major unless declared otherwise
  bool optimize = true;                  // false = /Od
  // The pre-release dialect of the DirectX 9 white paper: vec3/vec4, len, frc,
  // sample1d/sample3d, volumetexture, a leading `fx.2.0` line.
  bool compatibility = false;
  // Take the computations that read only uniforms out of the shader into a preshader,
  // run on the CPU when the uniforms change (effects do; a plain shader has no one to
  // run it).
  bool preshaders = false;
  // Uniform arguments of the entry point (`compile ps_2_0 PS(3, true)` in effects),
  // as constant expressions in HLSL syntax, in parameter order.
  std::vector<std::string> entryArguments;
};

// Expressions of uniforms only, computed on the CPU once per change of the uniforms
// instead of once per vertex or pixel (fxc's preshaders); the shader reads the results
// from constant registers.
class Preshader {
 public:
  struct Program;
  // The uniforms it reads, laid out in its own input registers as a constant table.
  shader::ShaderConstantTable inputs;
  // The shader's float constant register each result goes to, one float4 each.
  std::vector<int> outputRegisters;

  // `inputRegisters` holds 4 floats per input register (as `inputs` lays them out; a
  // short span reads zeros); returns 4 floats per output register.
  std::vector<float> run(std::span<const float> inputRegisters) const;
  int instructionCount() const;

  std::shared_ptr<const Program> program;
};

struct CompileResult {
  std::vector<uint32_t> tokens;  // empty when compilation failed
  shader::Shader shader;         // decoded form of `tokens`
  std::vector<Diagnostic> diagnostics;
  int instructionSlots = 0;      // as the validator counts them
  std::optional<Preshader> preshader;  // with CompileOptions::preshaders, when there is one

  bool ok() const { return !tokens.empty(); }
  // Every diagnostic in fxc's "file(line,col): error X3000: message" form, one per line.
  std::string messages() const;
};

// Compiles `source` (named `fileName` in diagnostics). Never throws for bad input:
// errors are in `diagnostics`.
CompileResult compile(std::string_view source, std::string_view fileName, const CompileOptions& options);

// Reads and compiles a file; a missing file is a diagnostic too.
CompileResult compileFile(const std::string& path, const CompileOptions& options);

}  // namespace refx::hlsl
