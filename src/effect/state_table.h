// Effect state names (D3DX "Effect States"): which device call a state assignment
// makes, and how its value is read.
#pragma once
#include <cstdint>
#include <optional>
#include <string_view>

#include "refx/pipeline/d3d9types.h"

namespace refx::effect::detail {

enum class StateTarget {
  RenderState, StageState, SamplerState, Texture, Sampler, Transform, Light, LightEnable,
  Material, VertexShader, PixelShader, VertexConstF, VertexConstI, VertexConstB,
  PixelConstF, PixelConstI, PixelConstB, FVF, NPatchMode,
};

enum class LightMember { Type, Diffuse, Specular, Ambient, Position, Direction, Range, Falloff,
                         Attenuation0, Attenuation1, Attenuation2, Theta, Phi };
enum class MaterialMember { Ambient, Diffuse, Specular, Emissive, Power };

struct StateInfo {
  StateTarget target;
  uint32_t code = 0;      // D3DRS / D3DTSS / D3DSAMP / D3DTS / member / register limit
  bool indexed = false;   // takes [n]
  int maxIndex = 0;       // highest valid index
  d3d::StateValueInfo value{d3d::ValueKind::Uint, d3d::EnumKind::Bool};
};

// Case-insensitive; nullopt for an unknown name.
std::optional<StateInfo> findState(std::string_view name);

}  // namespace refx::effect::detail
