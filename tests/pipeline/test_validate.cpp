#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <string>

#include "refx/pipeline/caps.h"
#include "refx/pipeline/state.h"

using namespace refx;
using namespace refx::d3d;

namespace {

const CapsProfile& caps(const std::string& name) {
  static std::map<std::string, CapsProfile> loaded;
  auto it = loaded.find(name);
  if (it == loaded.end()) it = loaded.emplace(name, loadCapsProfile(name)).first;
  return it->second;
}

std::string reason(const DeviceState& s, const std::string& profile) {
  ValidationResult r = validateDeviceState(s, caps(profile));
  return r.ok ? "ok" : r.reason;
}

void setStage(DeviceState& s, int stage, uint32_t colorOp, uint32_t arg1, uint32_t arg2) {
  s.stageStates[stage][TSS_COLOROP] = colorOp;
  s.stageStates[stage][TSS_COLORARG1] = arg1;
  s.stageStates[stage][TSS_COLORARG2] = arg2;
}

}  // namespace

TEST(ValidateDevice, DefaultStateIsValidEverywhere) {
  DeviceState s;  // stage 0 MODULATE TEXTURE, CURRENT; no blending
  for (const auto& name : capsProfileNames()) {
    SCOPED_TRACE(name);
    ValidationResult r = validateDeviceState(s, caps(name));
    EXPECT_TRUE(r.ok) << r.reason;
    EXPECT_EQ(r.passes, 1u);
    EXPECT_EQ(r.reason, "");
  }
}

TEST(ValidateDevice, DotProduct3NeedsADx7Device) {
  DeviceState s;
  setStage(s, 0, TOP_DOTPRODUCT3, TA_TEXTURE, TA_DIFFUSE);
  ValidationResult r = validateDeviceState(s, caps("dx6-tnt2"));
  EXPECT_FALSE(r.ok);
  EXPECT_EQ(r.reason, "stage 0 COLOROP DOTPRODUCT3 is not in TextureOpCaps of dx6-tnt2");
  EXPECT_EQ(reason(s, "dx6-g400"),
            "stage 0 COLOROP DOTPRODUCT3 is not in TextureOpCaps of dx6-g400");
  EXPECT_EQ(reason(s, "dx7"), "ok");
  EXPECT_EQ(reason(s, "ref"), "ok");
}

TEST(ValidateDevice, BumpEnvMapNeedsG400OrLater) {
  // EMBM: stage 0 bump map (du, dv), stage 1 environment map perturbed by it.
  DeviceState s;
  setStage(s, 0, TOP_BUMPENVMAP, TA_TEXTURE, TA_CURRENT);
  setStage(s, 1, TOP_MODULATE, TA_TEXTURE, TA_DIFFUSE);
  EXPECT_EQ(reason(s, "dx6-tnt2"), "stage 0 COLOROP BUMPENVMAP is not in TextureOpCaps of dx6-tnt2");
  EXPECT_EQ(reason(s, "dx6-g400"), "ok");
  // The GeForce2 has no dependent texture read.
  EXPECT_EQ(reason(s, "dx7"), "stage 0 COLOROP BUMPENVMAP is not in TextureOpCaps of dx7");
  EXPECT_EQ(reason(s, "dx8"), "ok");
}

TEST(ValidateDevice, StageCountIsLimited) {
  // Stages 1 and 2 only combine DIFFUSE/CURRENT, so one texture is used in total.
  DeviceState s;
  setStage(s, 1, TOP_MODULATE, TA_DIFFUSE, TA_CURRENT);
  setStage(s, 2, TOP_ADD, TA_DIFFUSE, TA_CURRENT);
  EXPECT_EQ(reason(s, "dx6-tnt2"), "stage 2 is enabled but dx6-tnt2 has MaxTextureBlendStages 2");
  EXPECT_EQ(reason(s, "dx6-g400"), "ok");  // 3 stages
  // Stages after the first COLOROP DISABLE are not looked at.
  DeviceState t = s;
  t.stageStates[1][TSS_COLOROP] = TOP_DISABLE;
  EXPECT_EQ(reason(t, "dx6-tnt2"), "ok");
}

TEST(ValidateDevice, SimultaneousTexturesAreLimited) {
  // Three stages each modulating their own texture: 3 textures.
  DeviceState s;
  setStage(s, 1, TOP_MODULATE, TA_TEXTURE, TA_CURRENT);
  setStage(s, 2, TOP_MODULATE, TA_TEXTURE, TA_CURRENT);
  EXPECT_EQ(reason(s, "dx7"),
            "stage 2 is stage number 3 to use a texture but dx7 has MaxSimultaneousTextures 2");
  EXPECT_EQ(reason(s, "dx8"), "ok");  // 4 textures
  // The same cascade with stage 2 reading TFACTOR instead fits two textures.
  s.stageStates[2][TSS_COLORARG1] = TA_TFACTOR;
  EXPECT_EQ(reason(s, "dx7"), "ok");
  // An alpha argument reading TEXTURE counts too.
  s.stageStates[2][TSS_ALPHAOP] = TOP_SELECTARG1;
  s.stageStates[2][TSS_ALPHAARG1] = TA_TEXTURE;
  EXPECT_EQ(reason(s, "dx7"),
            "stage 2 is stage number 3 to use a texture but dx7 has MaxSimultaneousTextures 2");
}

TEST(ValidateDevice, BumpStageCountsItsTexture) {
  // Base texture, bump map (stage 1 reads its own texture though no argument says
  // TEXTURE), environment map: 3 textures. The seeds' DX6 listing runs on the G400
  // (3 textures); a 3-stage card with 2 texture units must reject it.
  DeviceState s;
  setStage(s, 0, TOP_MODULATE, TA_TEXTURE, TA_DIFFUSE);
  setStage(s, 1, TOP_BUMPENVMAP, TA_DIFFUSE, TA_CURRENT);
  setStage(s, 2, TOP_ADD, TA_TEXTURE, TA_CURRENT);
  EXPECT_EQ(reason(s, "dx6-g400"), "ok");
  EXPECT_EQ(reason(s, "dx8"), "ok");
  CapsProfile twoUnits = caps("dx6-g400");
  twoUnits.name = "two-units";
  twoUnits.maxSimultaneousTextures = 2;
  ValidationResult r = validateDeviceState(s, twoUnits);
  EXPECT_EQ(r.reason, "stage 2 is stage number 3 to use a texture but two-units has MaxSimultaneousTextures 2");
}

TEST(ValidateDevice, AlphaOpIsCheckedUnlessDisabled) {
  DeviceState s;
  s.stageStates[0][TSS_ALPHAOP] = TOP_DISABLE;  // COLOROP stays MODULATE: fine
  EXPECT_EQ(reason(s, "dx6-tnt2"), "ok");
  s.stageStates[0][TSS_ALPHAOP] = TOP_DOTPRODUCT3;
  EXPECT_EQ(reason(s, "dx6-tnt2"), "stage 0 ALPHAOP DOTPRODUCT3 is not in TextureOpCaps of dx6-tnt2");
  EXPECT_EQ(reason(s, "dx7"), "ok");
  // BUMPENVMAP is a color operation only (D3DTOP docs).
  s.stageStates[0][TSS_ALPHAOP] = TOP_BUMPENVMAP;
  EXPECT_EQ(reason(s, "ref"), "stage 0 ALPHAOP BUMPENVMAP is a color-only operation");
}

TEST(ValidateDevice, TempRegisterNeedsTssArgTemp) {
  DeviceState s;
  // SELECTARG2 does not read ARG1, so a TEMP there is never used.
  setStage(s, 0, TOP_SELECTARG2, TA_TEMP, TA_DIFFUSE);
  EXPECT_EQ(reason(s, "dx7"), "ok");
  s.stageStates[0][TSS_COLOROP] = TOP_SELECTARG1;
  EXPECT_EQ(reason(s, "dx7"), "stage 0 COLORARG1 TEMP needs TSSARGTEMP in PrimitiveMiscCaps of dx7");
  EXPECT_EQ(reason(s, "dx8"), "ok");

  DeviceState r;
  r.stageStates[0][TSS_RESULTARG] = TA_TEMP;
  setStage(r, 1, TOP_ADD, TA_TEMP, TA_DIFFUSE);
  EXPECT_EQ(reason(r, "dx7"), "stage 0 RESULTARG TEMP needs TSSARGTEMP in PrimitiveMiscCaps of dx7");
  EXPECT_EQ(reason(r, "dx8"), "ok");
}

TEST(ValidateDevice, ThreeArgumentOpsAreDirectX8) {
  DeviceState s;
  setStage(s, 0, TOP_LERP, TA_TEXTURE, TA_DIFFUSE);
  s.stageStates[0][TSS_COLORARG0] = TA_TFACTOR;
  EXPECT_EQ(reason(s, "dx7"), "stage 0 COLOROP LERP is not in TextureOpCaps of dx7");
  EXPECT_EQ(reason(s, "dx8"), "ok");
  // ARG0 is read by LERP, so a CONSTANT there needs per-stage constants.
  s.stageStates[0][TSS_COLORARG0] = TA_CONSTANT;
  EXPECT_EQ(reason(s, "dx9"),
            "stage 0 COLORARG0 CONSTANT needs PERSTAGECONSTANT in PrimitiveMiscCaps of dx9");
  EXPECT_EQ(reason(s, "dx9-sm3"), "ok");
}

TEST(ValidateDevice, InvalidValuesAreReported) {
  DeviceState s;
  s.stageStates[0][TSS_COLOROP] = 99;
  EXPECT_EQ(reason(s, "ref"), "stage 0 COLOROP 99 is not a D3DTEXTUREOP");
  DeviceState t;
  t.stageStates[0][TSS_COLORARG1] = 9;
  EXPECT_EQ(reason(t, "ref"), "stage 0 COLORARG1 9 is not a D3DTA register");
}

// With a pixel shader bound the stage cascade is not checked: shader_device_test.cpp.

TEST(ValidateDevice, BlendFactorsMustBeInBlendCaps) {
  DeviceState s;
  s.renderStates[RS_SRCBLEND] = BLEND_BLENDFACTOR;
  s.renderStates[RS_DESTBLEND] = BLEND_INVBLENDFACTOR;
  // Blend states do not matter while blending is off.
  EXPECT_EQ(reason(s, "dx8"), "ok");
  s.renderStates[RS_ALPHABLENDENABLE] = 1;
  EXPECT_EQ(reason(s, "dx8"), "SRCBLEND BLENDFACTOR is not in SrcBlendCaps of dx8");
  EXPECT_EQ(reason(s, "dx9"), "ok");
  s.renderStates[RS_SRCBLEND] = BLEND_SRCALPHA;
  // INVBLENDFACTOR is covered by D3DPBLENDCAPS_BLENDFACTOR.
  EXPECT_EQ(reason(s, "dx8"), "DESTBLEND INVBLENDFACTOR is not in DestBlendCaps of dx8");
  // BOTHSRCALPHA is a SRCBLEND-only value.
  s.renderStates[RS_DESTBLEND] = BLEND_BOTHSRCALPHA;
  EXPECT_EQ(reason(s, "ref"), "DESTBLEND BOTHSRCALPHA is not in DestBlendCaps of ref");
  // As SRCBLEND it overrides DESTBLEND, which is then not looked at.
  s.renderStates[RS_SRCBLEND] = BLEND_BOTHSRCALPHA;
  s.renderStates[RS_DESTBLEND] = 77;
  EXPECT_EQ(reason(s, "dx6-tnt2"), "ok");
  // Classic transparency works on every generation.
  s.renderStates[RS_SRCBLEND] = BLEND_SRCALPHA;
  s.renderStates[RS_DESTBLEND] = BLEND_INVSRCALPHA;
  for (const auto& name : capsProfileNames()) EXPECT_EQ(reason(s, name), "ok") << name;
  s.renderStates[RS_DESTBLEND] = 77;
  EXPECT_EQ(reason(s, "ref"), "DESTBLEND 77 is not a D3DBLEND");
}

TEST(ValidateDevice, BlendOpAndSeparateAlphaNeedMiscCaps) {
  DeviceState s;
  s.renderStates[RS_ALPHABLENDENABLE] = 1;
  s.renderStates[RS_BLENDOP] = BLENDOP_REVSUBTRACT;
  EXPECT_EQ(reason(s, "dx6-tnt2"), "BLENDOP REVSUBTRACT needs BLENDOP in PrimitiveMiscCaps of dx6-tnt2");
  EXPECT_EQ(reason(s, "dx7"), "ok");
  s.renderStates[RS_BLENDOP] = BLENDOP_ADD;
  s.renderStates[RS_SEPARATEALPHABLENDENABLE] = 1;
  EXPECT_EQ(reason(s, "dx8"),
            "SEPARATEALPHABLENDENABLE needs SEPARATEALPHABLEND in PrimitiveMiscCaps of dx8");
  EXPECT_EQ(reason(s, "dx9"), "ok");
  s.renderStates[RS_DESTBLENDALPHA] = BLEND_BOTHINVSRCALPHA;
  EXPECT_EQ(reason(s, "dx9"), "DESTBLENDALPHA BOTHINVSRCALPHA is not in DestBlendCaps of dx9");
  s.renderStates[RS_DESTBLENDALPHA] = BLEND_ZERO;
  s.renderStates[RS_BLENDOPALPHA] = BLENDOP_MAX;
  EXPECT_EQ(reason(s, "dx9"), "ok");
}

TEST(ValidateDevice, BoundTexturesMustFitTheDevice) {
  DeviceState s;
  s.textures[0] = Texture::createCube(Format::A8R8G8B8, 4);
  EXPECT_EQ(reason(s, "dx6-tnt2"), "sampler 0 has a cube texture but dx6-tnt2 lacks CUBEMAP in TextureCaps");
  EXPECT_EQ(reason(s, "dx7"), "ok");

  s.textures[0] = Texture::createVolume(Format::A8R8G8B8, 4, 4, 4);
  EXPECT_EQ(reason(s, "dx7"), "sampler 0 has a volume texture but dx7 lacks VOLUMEMAP in TextureCaps");
  EXPECT_EQ(reason(s, "dx8"), "ok");

  // 4096 wide: over the GeForce2's 2048, within the GeForce3's 4096.
  s.textures[0] = Texture::create2D(Format::A8R8G8B8, 4096, 4);
  EXPECT_EQ(reason(s, "dx7"), "sampler 0 texture is 4096x4 but dx7 has MaxTextureWidth 2048");
  EXPECT_EQ(reason(s, "dx8"), "ok");

  DeviceState v;
  v.textures[kVertexSampler0] = Texture::create2D(Format::A8R8G8B8, 4, 4);
  EXPECT_EQ(reason(v, "dx9"),
            "vertex sampler 0 has a texture but dx9 has no vertex texture fetch "
            "(VertexTextureFilterCaps 0)");
  EXPECT_EQ(reason(v, "dx9-sm3"), "ok");
}
