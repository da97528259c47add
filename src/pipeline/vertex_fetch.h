// Reads vertex elements from streams into vertex-program input registers.
#pragma once
#include <cstdint>

#include "refx/exec/interpreter.h"
#include "refx/pipeline/state.h"

namespace refx::pipeline {

struct StreamView {
  const uint8_t* data = nullptr;
  size_t size = 0;
  uint32_t stride = 0;
};

// Input register a declaration element feeds (D3DVSDE numbering), or -1.
int inputRegisterForElement(const VertexElement& e);

// Fills lanes [0, count) of `regs.inputs` with vertices first..first+count-1.
// Absent elements keep the defaults written beforehand by resetInputs.
void fetchVertices(const VertexDeclaration& decl, const StreamView* streams, uint32_t first,
                   int count, exec::BatchRegisters& regs);
// Defaults for absent inputs: (0,0,0,1), diffuse (1,1,1,1), specular (0,0,0,0).
void resetInputs(exec::BatchRegisters& regs);

}  // namespace refx::pipeline
