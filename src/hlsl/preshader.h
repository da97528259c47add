// Preshaders: the computations of a shader that read only uniforms and literals are
// taken out of the shader and run on the CPU once per change of their inputs (what
// fxc does for effects); the shader reads their results from constant registers.
#pragma once
#include <vector>

#include "hlsl/ir.h"
#include "refx/hlsl/compiler.h"

namespace refx::hlsl {

// What the preshader computes: IR instructions over its own registers. Uniform
// instructions read input register `index` (the inputs table's layout).
struct Preshader::Program {
  std::vector<detail::IrInst> code;
  std::vector<int> regWidth;
  std::vector<int> outputRegs;  // IR register of each output, in output order
};

namespace detail {

// Moves the uniform-only computations of `ir` into a preshader. The shader keeps a
// placeholder uniform (IrUniform::preshaderOutput) per value it still reads. Returns
// the program and the index in ir.uniforms of each output; no program when there is
// nothing to move. Inputs are laid out with the uniforms' register counts.
struct PreshaderExtraction {
  std::shared_ptr<Preshader::Program> program;
  std::vector<int> outputUniforms;
  std::vector<int> inputUniforms;  // ir.uniforms read, in input-register order
};
PreshaderExtraction extractPreshader(IrProgram& ir);

}  // namespace detail

}  // namespace refx::hlsl
