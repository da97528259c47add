#include "refx/pipeline/dx8_declaration.h"

#include <cstring>

#include "refx/pipeline/device.h"

namespace refx {

using namespace d3d;

namespace {

// D3DVSDE_* register -> the D3D9 usage and index the fixed-function pipeline reads.
struct UsageOf {
  uint8_t usage, index;
};
UsageOf usageOfRegister(int reg) {
  static constexpr UsageOf kRegisters[] = {
      {DECLUSAGE_POSITION, 0}, {DECLUSAGE_BLENDWEIGHT, 0}, {DECLUSAGE_BLENDINDICES, 0},
      {DECLUSAGE_NORMAL, 0},   {DECLUSAGE_PSIZE, 0},       {DECLUSAGE_COLOR, 0},
      {DECLUSAGE_COLOR, 1},    {DECLUSAGE_TEXCOORD, 0},    {DECLUSAGE_TEXCOORD, 1},
      {DECLUSAGE_TEXCOORD, 2}, {DECLUSAGE_TEXCOORD, 3},    {DECLUSAGE_TEXCOORD, 4},
      {DECLUSAGE_TEXCOORD, 5}, {DECLUSAGE_TEXCOORD, 6},    {DECLUSAGE_TEXCOORD, 7},
      {DECLUSAGE_POSITION, 1},  // D3DVSDE_POSITION2
      {DECLUSAGE_NORMAL, 1},    // D3DVSDE_NORMAL2
  };
  if (reg >= 0 && reg < int(std::size(kRegisters))) return kRegisters[reg];
  return {DECLUSAGE_TEXCOORD, uint8_t(8 + reg)};  // no fixed-function meaning
}

}  // namespace

VertexDeclaration vertexDeclarationFromVsd(const shader::VsDeclaration& decl) {
  VertexDeclaration out;
  for (const shader::VsdElement& e : shader::vsdElements(decl)) {
    VertexElement v;
    v.stream = e.stream;
    v.offset = e.offset;
    v.type = uint8_t(e.type);  // D3DVSDT_* and D3DDECLTYPE_* share values 0..7
    const UsageOf u = usageOfRegister(e.reg);
    v.usage = u.usage;
    v.usageIndex = u.index;
    v.shaderRegister = int8_t(e.reg);
    out.elements.push_back(v);
  }
  return out;
}

void setVsdConstants(Device& device, const shader::VsDeclaration& decl) {
  for (const shader::VsdEntry& e : decl.entries) {
    // D3DVSD_CONST(address, 0) loads nothing (and has no data to copy).
    if (e.kind != shader::VsdEntry::Kind::Const || e.count == 0 ||
        e.data.size() < size_t(e.count) * 4)
      continue;
    std::vector<float> values(size_t(e.count) * 4);
    std::memcpy(values.data(), e.data.data(), values.size() * sizeof(float));
    device.setVertexShaderConstantF(e.address, values.data(), e.count);
  }
}

}  // namespace refx
