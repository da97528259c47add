// Reads vertex elements from streams into vertex-program input registers.
#pragma once
#include <cstdint>
#include <vector>

#include "refx/exec/interpreter.h"
#include "refx/exec/lower.h"
#include "refx/pipeline/state.h"

namespace refx::pipeline {

struct StreamView {
  const uint8_t* data = nullptr;
  size_t size = 0;
  uint32_t stride = 0;
};

// Input register a declaration element feeds (D3DVSDE numbering), or -1.
int inputRegisterForElement(const VertexElement& e);

// One declaration element and the input register it is read into.
struct FetchElement {
  VertexElement element;
  int reg;
};
// Fixed function: every element at its D3DVSDE register.
std::vector<FetchElement> fixedFunctionFetch(const VertexDeclaration& decl);
// A vertex shader: each dcl'd v# from the element of the same usage and index
// (POSITION and POSITIONT stand in for each other); a vs_1_1 shader without dcl (DirectX 8
// style) takes element i at its shaderRegister, or at the D3DVSDE register of its usage.
std::vector<FetchElement> shaderFetch(const VertexDeclaration& decl,
                                      const exec::LoweredShader& shader);

// Fills lanes [0, count) of `regs.inputs` with vertices first..first+count-1.
// Absent elements keep the defaults written beforehand by resetInputs.
void fetchVertices(const std::vector<FetchElement>& elements, const StreamView* streams,
                   uint32_t first, int count, exec::BatchRegisters& regs);
// Defaults for absent inputs: (0,0,0,1); for fixed function diffuse (1,1,1,1) and
// specular (0,0,0,0).
void resetInputs(exec::BatchRegisters& regs, bool fixedFunction = true);

}  // namespace refx::pipeline
