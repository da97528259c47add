// The complete D3D9 device state as a value: what a state block captures and what
// ValidateDevice inspects.
#pragma once
#include <array>
#include <bit>
#include <cstdint>
#include <memory>
#include <vector>

#include "refx/core/color.h"
#include "refx/core/math.h"
#include "refx/pipeline/d3d9types.h"
#include "refx/resource/texture.h"
#include "refx/resource/vertex_format.h"

namespace refx {

class VertexShader;
class PixelShader;

// Float constant registers of the API (a D3D9 device: 256 vertex, 224 pixel), and
// the int and bool registers (16 each).
constexpr int kMaxVertexShaderConstF = 256;
constexpr int kMaxPixelShaderConstF = 224;
constexpr int kMaxShaderConstI = 16;
constexpr int kMaxShaderConstB = 16;
constexpr int kMaxUserClipPlanes = 6;  // SetClipPlane indices 0-5 (D3DMAXUSERCLIPPLANES)

struct Light {  // D3DLIGHT9
  uint32_t type = d3d::LIGHT_DIRECTIONAL;
  Color4 diffuse{1, 1, 1, 0}, specular{0, 0, 0, 0}, ambient{0, 0, 0, 0};
  Vec3 position{0, 0, 0};
  Vec3 direction{0, 0, 1};
  float range = 0, falloff = 0, attenuation0 = 0, attenuation1 = 0, attenuation2 = 0;
  float theta = 0, phi = 0;
};

struct Material {  // D3DMATERIAL9
  Color4 diffuse{0, 0, 0, 0}, ambient{0, 0, 0, 0}, specular{0, 0, 0, 0}, emissive{0, 0, 0, 0};
  float power = 0;
};

struct Viewport {  // D3DVIEWPORT9
  int x = 0, y = 0, width = 0, height = 0;
  float minZ = 0, maxZ = 1;
};

struct Rect {
  int left = 0, top = 0, right = 0, bottom = 0;
};

struct VertexBuffer {
  std::vector<uint8_t> data;
};
struct IndexBuffer {
  std::vector<uint8_t> data;
  bool index32 = false;
};
using VertexBufferPtr = std::shared_ptr<VertexBuffer>;
using IndexBufferPtr = std::shared_ptr<IndexBuffer>;

struct StreamSource {
  VertexBufferPtr buffer;
  uint32_t offset = 0;
  uint32_t stride = 0;
};

inline uint32_t floatBits(float f) { return std::bit_cast<uint32_t>(f); }
inline float bitsFloat(uint32_t u) { return std::bit_cast<float>(u); }

struct DeviceState {
  std::array<uint32_t, d3d::kRenderStateCount> renderStates{};
  std::array<std::array<uint32_t, d3d::kTextureStageStateCount>, d3d::kMaxTextureStages> stageStates{};
  std::array<std::array<uint32_t, d3d::kSamplerStateCount>, d3d::kMaxSamplers> samplerStates{};
  std::array<TexturePtr, d3d::kMaxSamplers> textures{};
  // `world` is D3DTS_WORLDMATRIX(0) (D3DTS_WORLD); worldMatrix(n) reaches all 256.
  Matrix world = Matrix::identity(), view = Matrix::identity(), projection = Matrix::identity();
  // D3DTS_WORLDMATRIX(1..255), the further vertex-blending matrices (identity by default).
  std::vector<Matrix> blendWorlds = std::vector<Matrix>(d3d::kMaxWorldMatrices - 1, Matrix::identity());
  std::array<Matrix, 8> textureTransforms{};
  std::array<Light, 8> lights{};
  std::array<bool, 8> lightEnabled{};
  Material material{};
  Viewport viewport{};
  Rect scissor{};
  // SetClipPlane (A, B, C, D): world space for fixed function, clip space for vertex
  // shaders; D3DRS_CLIPPLANEENABLE bit i enables plane i.
  std::array<Vec4, kMaxUserClipPlanes> clipPlanes{};
  VertexDeclaration declaration;
  std::array<StreamSource, 16> streams{};
  IndexBufferPtr indices;
  // Shaders (shader_object.h); nullptr = fixed function. Constants as
  // SetVertexShaderConstantF/I/B and SetPixelShaderConstantF/I/B set them.
  std::shared_ptr<const VertexShader> vertexShader;
  std::shared_ptr<const PixelShader> pixelShader;
  std::vector<Vec4> vsConstF = std::vector<Vec4>(kMaxVertexShaderConstF),
                    psConstF = std::vector<Vec4>(kMaxPixelShaderConstF);
  std::array<std::array<int, 4>, 16> vsConstI{}, psConstI{};
  std::array<bool, 16> vsConstB{}, psConstB{};

  DeviceState();  // D3D9 defaults

  uint32_t rs(d3d::RenderState s) const { return renderStates[s]; }
  float rsFloat(d3d::RenderState s) const { return bitsFloat(renderStates[s]); }
  uint32_t tss(int stage, d3d::TextureStageState s) const { return stageStates[stage][s]; }
  float tssFloat(int stage, d3d::TextureStageState s) const {
    return bitsFloat(stageStates[stage][s]);
  }
  uint32_t samp(int sampler, d3d::SamplerStateType s) const { return samplerStates[sampler][s]; }
  // D3DTS_WORLDMATRIX(n), n in [0, 255].
  const Matrix& worldMatrix(int n) const { return n == 0 ? world : blendWorlds[size_t(n - 1)]; }
  Matrix& worldMatrix(int n) { return n == 0 ? world : blendWorlds[size_t(n - 1)]; }
};

}  // namespace refx
