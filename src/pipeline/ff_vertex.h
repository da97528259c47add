// Fixed-function vertex processing (transform, D3D lighting, vertex fog, texture
// coordinate generation and texture transforms) expressed as an exec::Program, so
// fixed-function draws run on the same engine as vertex shaders.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "refx/exec/abi.h"
#include "refx/exec/ir.h"
#include "refx/pipeline/state.h"

namespace refx::pipeline {

// Vertex input registers: the DirectX 8 D3DVSDE_* numbering, also used for vs_1_1
// declarations.
enum VertexInput : int {
  kVertexInPosition = 0,
  kVertexInBlendWeight = 1,
  kVertexInBlendIndices = 2,
  kVertexInNormal = 3,
  kVertexInPSize = 4,
  kVertexInDiffuse = 5,
  kVertexInSpecular = 6,
  kVertexInTex0 = 7,  // ..14: texture coordinate sets 0..7
  kVertexInPosition1 = 15,  // POSITION1 and NORMAL1: the second position and normal
  kVertexInNormal1 = 16,    // that vertex tweening blends toward
  kVertexInputCount = 17,
};

// Vertex outputs as a vertex shader writes them (exec/abi.h).
using exec::kVertexOutPosition;
using exec::kVertexOutDiffuse;
using exec::kVertexOutSpecular;
using exec::kVertexOutTex0;
using exec::kVertexOutFog;
using exec::kVertexOutPSize;
using exec::kVertexOutputCount;

// What the vertex declaration supplies. Absent inputs are filled by the fetcher:
// diffuse (1,1,1,1), specular (0,0,0,0), position w = 1, missing texcoord components 0.
struct FixedFunctionVertexConfig {
  bool pretransformed = false;  // XYZRHW / POSITIONT
  bool hasNormal = false, hasDiffuse = false, hasSpecular = false;
  bool hasPSize = false;
  std::array<int, 8> texCoordDims{};  // components present in each input texcoord set (0 = absent)
  // Vertex blending: BLENDWEIGHT components present (0 = absent), the DECLTYPE of the
  // BLENDINDICES element (-1 = absent), and the tweening partners POSITION1 / NORMAL1.
  int blendWeightCount = 0;
  int blendIndicesType = -1;
  bool hasPosition1 = false, hasNormal1 = false;
};

// The program reads the draw's values from constants (exec/abi.h kConstVertex*);
// its structure depends on the state the draw plan's key holds, including
// fixedFunctionLightKey for every light.
exec::Program buildFixedFunctionVertexProgram(const DeviceState& state,
                                              const FixedFunctionVertexConfig& cfg);

// What of light i shapes the program: whether it takes part, its type, which of its
// colours are black, whether its falloff is 1.
uint32_t fixedFunctionLightKey(const DeviceState& state, int i);

// The constant array the program reads, from the state's current values.
void fixedFunctionVertexConstants(const DeviceState& state, const FixedFunctionVertexConfig& cfg,
                                  std::vector<Vec4>& constants);

}  // namespace refx::pipeline
