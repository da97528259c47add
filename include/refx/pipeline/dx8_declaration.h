// DirectX 8 vertex shader declarations (D3DVSD, shader/vs_declaration.h) on the D3D9
// device: the stream elements become a VertexDeclaration whose elements name the v
// register they feed (VertexElement::shaderRegister), and D3DVSD_CONST entries load
// vertex shader constants as D3D8's SetVertexShader did.
#pragma once
#include "refx/pipeline/state.h"
#include "refx/shader/vs_declaration.h"

namespace refx {

class Device;

// Elements in declaration order, each with usage/index of its D3DVSDE register (so the
// fixed-function pipeline reads the same data: v0 position, v3 normal, v5 diffuse,
// v6 specular, v7..v14 texture coordinates ...) and shaderRegister = the v register.
VertexDeclaration vertexDeclarationFromVsd(const shader::VsDeclaration& decl);

// SetVertexShaderConstantF for every D3DVSD_CONST entry.
void setVsdConstants(Device& device, const shader::VsDeclaration& decl);

}  // namespace refx
