#include "state_table.h"

#include "refx/core/text.h"
#include "refx/pipeline/state.h"

namespace refx::effect::detail {

namespace {

using d3d::EnumKind;
using d3d::ValueKind;

struct Named {
  std::string_view name;
  StateInfo info;
};

constexpr d3d::StateValueInfo kFloatValue{ValueKind::Float, EnumKind::Bool};
constexpr d3d::StateValueInfo kUintValue{ValueKind::Uint, EnumKind::Bool};
constexpr d3d::StateValueInfo kBoolValue{ValueKind::Enum, EnumKind::Bool};
constexpr int kStages = d3d::kMaxTextureStages - 1;
constexpr int kLights = 7;

// The states that are not render, texture-stage or sampler states. Register limits of
// the VertexShaderConstant1-4 forms are in `code` (0 = the whole value).
constexpr Named kSpecial[] = {
    {"VertexShader", {StateTarget::VertexShader}},
    {"PixelShader", {StateTarget::PixelShader}},
    {"VertexShaderConstant", {StateTarget::VertexConstF, 0, true, 255}},
    {"VertexShaderConstantF", {StateTarget::VertexConstF, 0, true, 255}},
    {"VertexShaderConstant1", {StateTarget::VertexConstF, 1, true, 255}},
    {"VertexShaderConstant2", {StateTarget::VertexConstF, 2, true, 255}},
    {"VertexShaderConstant3", {StateTarget::VertexConstF, 3, true, 255}},
    {"VertexShaderConstant4", {StateTarget::VertexConstF, 4, true, 255}},
    {"VertexShaderConstantI", {StateTarget::VertexConstI, 0, true, 15}},
    {"VertexShaderConstantB", {StateTarget::VertexConstB, 0, true, 15}},
    {"PixelShaderConstant", {StateTarget::PixelConstF, 0, true, 223}},
    {"PixelShaderConstantF", {StateTarget::PixelConstF, 0, true, 223}},
    {"PixelShaderConstant1", {StateTarget::PixelConstF, 1, true, 223}},
    {"PixelShaderConstant2", {StateTarget::PixelConstF, 2, true, 223}},
    {"PixelShaderConstant3", {StateTarget::PixelConstF, 3, true, 223}},
    {"PixelShaderConstant4", {StateTarget::PixelConstF, 4, true, 223}},
    {"PixelShaderConstantI", {StateTarget::PixelConstI, 0, true, 15}},
    {"PixelShaderConstantB", {StateTarget::PixelConstB, 0, true, 15}},
    {"Texture", {StateTarget::Texture, 0, true, d3d::kMaxSamplers - 1}},
    {"Sampler", {StateTarget::Sampler, 0, true, d3d::kMaxSamplers - 1}},
    {"ProjectionTransform", {StateTarget::Transform, d3d::TS_PROJECTION}},
    {"ViewTransform", {StateTarget::Transform, d3d::TS_VIEW}},
    {"WorldTransform", {StateTarget::Transform, d3d::TS_WORLD, true, 255}},
    {"TextureTransform", {StateTarget::Transform, d3d::TS_TEXTURE0, true, kStages}},
    {"MaterialAmbient", {StateTarget::Material, uint32_t(MaterialMember::Ambient)}},
    {"MaterialDiffuse", {StateTarget::Material, uint32_t(MaterialMember::Diffuse)}},
    {"MaterialSpecular", {StateTarget::Material, uint32_t(MaterialMember::Specular)}},
    {"MaterialEmissive", {StateTarget::Material, uint32_t(MaterialMember::Emissive)}},
    {"MaterialPower", {StateTarget::Material, uint32_t(MaterialMember::Power)}},
    {"LightType", {StateTarget::Light, uint32_t(LightMember::Type), true, kLights,
                   {ValueKind::Enum, EnumKind::LightType}}},
    {"LightDiffuse", {StateTarget::Light, uint32_t(LightMember::Diffuse), true, kLights}},
    {"LightSpecular", {StateTarget::Light, uint32_t(LightMember::Specular), true, kLights}},
    {"LightAmbient", {StateTarget::Light, uint32_t(LightMember::Ambient), true, kLights}},
    {"LightPosition", {StateTarget::Light, uint32_t(LightMember::Position), true, kLights}},
    {"LightDirection", {StateTarget::Light, uint32_t(LightMember::Direction), true, kLights}},
    {"LightRange", {StateTarget::Light, uint32_t(LightMember::Range), true, kLights}},
    {"LightFalloff", {StateTarget::Light, uint32_t(LightMember::Falloff), true, kLights}},
    {"LightAttenuation0", {StateTarget::Light, uint32_t(LightMember::Attenuation0), true, kLights}},
    {"LightAttenuation1", {StateTarget::Light, uint32_t(LightMember::Attenuation1), true, kLights}},
    {"LightAttenuation2", {StateTarget::Light, uint32_t(LightMember::Attenuation2), true, kLights}},
    {"LightTheta", {StateTarget::Light, uint32_t(LightMember::Theta), true, kLights}},
    {"LightPhi", {StateTarget::Light, uint32_t(LightMember::Phi), true, kLights}},
    {"LightEnable", {StateTarget::LightEnable, 0, true, kLights, kBoolValue}},
    {"FVF", {StateTarget::FVF}},
    {"NPatchMode", {StateTarget::NPatchMode, 0, false, 0, kFloatValue}},
    {"PatchSegments", {StateTarget::NPatchMode, 0, false, 0, kFloatValue}},
};

}  // namespace

std::optional<StateInfo> findState(std::string_view name) {
  for (const Named& n : kSpecial)
    if (equalsNoCase(n.name, name)) return n.info;
  // Texture-stage states come before render states: "Constant[n]" is D3DTSS_CONSTANT.
  if (auto tss = d3d::parseEnum(EnumKind::TextureStageState, name))
    return StateInfo{StateTarget::StageState, *tss, true, kStages, d3d::textureStageStateValue(*tss)};
  // DirectX 8 effects set sampler states per stage ("AddressU[0]"); D3DX9 maps them to samplers.
  if (auto samp = d3d::parseEnum(EnumKind::SamplerState, name))
    return StateInfo{StateTarget::SamplerState, *samp, true, d3d::kMaxSamplers - 1, d3d::samplerStateValue(*samp)};
  if (auto rs = d3d::parseEnum(EnumKind::RenderState, name))
    return StateInfo{StateTarget::RenderState, *rs, false, 0, d3d::renderStateValue(*rs)};
  return std::nullopt;
}

}  // namespace refx::effect::detail
