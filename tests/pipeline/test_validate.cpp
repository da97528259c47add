#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <string>

#include "refx/pipeline/caps.h"
#include "refx/pipeline/state.h"
#include "pipeline/validate.h"
#include "refx/pipeline/shader_object.h"
#include "refx/shader/assembler.h"

using namespace refx;
using namespace refx::d3d;
using namespace refx::pipeline;

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

// ---------------------------------------------------------------------------
// Sampler states of the samplers in use, per texture type.

namespace {

// A copy of a shipped profile under another name, for caps no shipped profile lacks.
CapsProfile variant(const std::string& base, const std::string& name) {
  CapsProfile c = caps(base);
  c.name = name;
  return c;
}

std::string reason(const DeviceState& s, const CapsProfile& c) {
  ValidationResult r = validateDeviceState(s, c);
  return r.ok ? "ok" : r.reason;
}

// Stage 0 modulates the texture of sampler 0 (the default state) and it is bound.
DeviceState textured(TexturePtr tex) {
  DeviceState s;
  s.textures[0] = std::move(tex);
  return s;
}

TexturePtr tex2D() { return Texture::create2D(Format::A8R8G8B8, 4, 4); }

}  // namespace

TEST(ValidateDevice, FilterCapsFollowTheTextureType) {
  // D3DTEXF_ANISOTROPIC = 3 needs D3DPTFILTERCAPS_MINFANISOTROPIC in the caps field of
  // the bound texture's type.
  DeviceState s = textured(tex2D());
  s.samplerStates[0][SAMP_MINFILTER] = 3;
  EXPECT_EQ(reason(s, "dx6-tnt2"),
            "sampler 0 MINFILTER ANISOTROPIC needs MINFANISOTROPIC in TextureFilterCaps of dx6-tnt2");
  EXPECT_EQ(reason(s, "dx7"), "ok");  // the GeForce2 filters 2D textures anisotropically
  // The GeForce2 and GeForce3 filter cube maps bilinearly at most.
  s.textures[0] = Texture::createCube(Format::A8R8G8B8, 4);
  EXPECT_EQ(reason(s, "dx7"),
            "sampler 0 MINFILTER ANISOTROPIC needs MINFANISOTROPIC in CubeTextureFilterCaps of dx7");
  EXPECT_EQ(reason(s, "dx9"), "ok");
  // No profile filters volumes anisotropically, the reference device included.
  s.textures[0] = Texture::createVolume(Format::A8R8G8B8, 4, 4, 4);
  s.samplerStates[0][SAMP_MINFILTER] = 2;
  s.samplerStates[0][SAMP_MAGFILTER] = 3;
  EXPECT_EQ(reason(s, "ref"),
            "sampler 0 MAGFILTER ANISOTROPIC needs MAGFANISOTROPIC in VolumeTextureFilterCaps of ref");
  s.samplerStates[0][SAMP_MAGFILTER] = 2;
  EXPECT_EQ(reason(s, "ref"), "ok");
  // PYRAMIDALQUAD (6) is in no profile.
  s.samplerStates[0][SAMP_MAGFILTER] = 6;
  EXPECT_EQ(reason(s, "ref"),
            "sampler 0 MAGFILTER PYRAMIDALQUAD needs MAGFPYRAMIDALQUAD in VolumeTextureFilterCaps of ref");
  s.samplerStates[0][SAMP_MAGFILTER] = 5;
  EXPECT_EQ(reason(s, "ref"), "sampler 0 MAGFILTER 5 is not a D3DTEXTUREFILTERTYPE");
}

TEST(ValidateDevice, MipFilterNeedsMipFilterCaps) {
  DeviceState s = textured(tex2D());
  s.samplerStates[0][SAMP_MIPFILTER] = 2;  // LINEAR
  CapsProfile noTrilinear = variant("dx6-tnt2", "no-trilinear");
  noTrilinear.textureFilterCaps &= ~0x20000u;  // D3DPTFILTERCAPS_MIPFLINEAR
  EXPECT_EQ(reason(s, noTrilinear),
            "sampler 0 MIPFILTER LINEAR needs MIPFLINEAR in TextureFilterCaps of no-trilinear");
  EXPECT_EQ(reason(s, "dx6-tnt2"), "ok");
  s.samplerStates[0][SAMP_MIPFILTER] = 3;  // ANISOTROPIC is no mip filter
  EXPECT_EQ(reason(s, "ref"),
            "sampler 0 MIPFILTER ANISOTROPIC is not a mip filter (NONE, POINT or LINEAR)");
}

TEST(ValidateDevice, MaxAnisotropyIsLimitedWhenFilteringAnisotropically) {
  DeviceState s = textured(tex2D());
  s.samplerStates[0][SAMP_MAXANISOTROPY] = 4;
  // MAXANISOTROPY only matters with an ANISOTROPIC filter.
  EXPECT_EQ(reason(s, "dx7"), "ok");
  s.samplerStates[0][SAMP_MAGFILTER] = 3;
  EXPECT_EQ(reason(s, "dx7"), "sampler 0 MAXANISOTROPY 4 exceeds MaxAnisotropy 2 of dx7");
  EXPECT_EQ(reason(s, "dx8"), "ok");  // 8
  s.samplerStates[0][SAMP_MAXANISOTROPY] = 16;
  EXPECT_EQ(reason(s, "dx8"), "sampler 0 MAXANISOTROPY 16 exceeds MaxAnisotropy 8 of dx8");
  EXPECT_EQ(reason(s, "ref"), "ok");
  // Anisotropic filtering also needs D3DPRASTERCAPS_ANISOTROPY.
  CapsProfile noAniso = variant("ref", "no-aniso");
  noAniso.rasterCaps &= ~0x20000u;
  EXPECT_EQ(reason(s, noAniso), "sampler 0 ANISOTROPIC filtering needs ANISOTROPY in RasterCaps of no-aniso");
}

TEST(ValidateDevice, OnlySamplersInUseAreChecked) {
  // Sampler 1 holds a texture with a filter the TNT2 lacks, but stage 1 is disabled.
  DeviceState s;
  s.textures[1] = tex2D();
  s.samplerStates[1][SAMP_MINFILTER] = 3;
  EXPECT_EQ(reason(s, "dx6-tnt2"), "ok");
  // Enabling stage 1 with a TEXTURE argument puts sampler 1 in use.
  setStage(s, 1, TOP_MODULATE, TA_TEXTURE, TA_CURRENT);
  EXPECT_EQ(reason(s, "dx6-tnt2"),
            "sampler 1 MINFILTER ANISOTROPIC needs MINFANISOTROPIC in TextureFilterCaps of dx6-tnt2");
}

TEST(ValidateDevice, MipMapLodBiasNeedsItsRasterCap) {
  DeviceState s = textured(tex2D());
  s.samplerStates[0][SAMP_MIPMAPLODBIAS] = floatBits(-1.0f);
  CapsProfile noBias = variant("dx6-tnt2", "no-lod-bias");
  noBias.rasterCaps &= ~0x2000u;  // D3DPRASTERCAPS_MIPMAPLODBIAS
  EXPECT_EQ(reason(s, noBias), "sampler 0 MIPMAPLODBIAS -1 needs MIPMAPLODBIAS in RasterCaps of no-lod-bias");
  EXPECT_EQ(reason(s, "dx6-tnt2"), "ok");
  s.samplerStates[0][SAMP_MIPMAPLODBIAS] = floatBits(0.0f);
  EXPECT_EQ(reason(s, noBias), "ok");
}

TEST(ValidateDevice, AddressModesNeedTextureAddressCaps) {
  DeviceState s = textured(tex2D());
  s.samplerStates[0][SAMP_ADDRESSU] = s.samplerStates[0][SAMP_ADDRESSV] = 4;  // BORDER
  EXPECT_EQ(reason(s, "dx6-tnt2"), "sampler 0 ADDRESSU BORDER needs BORDER in TextureAddressCaps of dx6-tnt2");
  EXPECT_EQ(reason(s, "dx7"), "ok");
  s.samplerStates[0][SAMP_ADDRESSU] = s.samplerStates[0][SAMP_ADDRESSV] = 5;  // MIRRORONCE
  EXPECT_EQ(reason(s, "dx7"),
            "sampler 0 ADDRESSU MIRRORONCE needs MIRRORONCE in TextureAddressCaps of dx7");
  EXPECT_EQ(reason(s, "dx8"), "ok");
  // U and V differing needs INDEPENDENTUV.
  s.samplerStates[0][SAMP_ADDRESSU] = 3;  // CLAMP
  s.samplerStates[0][SAMP_ADDRESSV] = 1;  // WRAP
  CapsProfile tied = variant("dx6-tnt2", "tied-uv");
  tied.textureAddressCaps &= ~0x10u;  // D3DPTADDRESSCAPS_INDEPENDENTUV
  EXPECT_EQ(reason(s, tied),
            "sampler 0 ADDRESSU CLAMP and ADDRESSV WRAP differ: needs INDEPENDENTUV in "
            "TextureAddressCaps of tied-uv");
  EXPECT_EQ(reason(s, "dx6-tnt2"), "ok");
  // ADDRESSW counts for volume textures only.
  s.samplerStates[0][SAMP_ADDRESSU] = s.samplerStates[0][SAMP_ADDRESSV] = 1;
  s.samplerStates[0][SAMP_ADDRESSW] = 4;
  EXPECT_EQ(reason(s, "dx6-tnt2"), "ok");
  s.textures[0] = Texture::createVolume(Format::A8R8G8B8, 4, 4, 4);
  CapsProfile noBorder = variant("dx8", "no-border");
  noBorder.textureAddressCaps &= ~0x8u;
  EXPECT_EQ(reason(s, noBorder), "sampler 0 ADDRESSW BORDER needs BORDER in TextureAddressCaps of no-border");
  s.samplerStates[0][SAMP_ADDRESSW] = 9;
  EXPECT_EQ(reason(s, "ref"), "sampler 0 ADDRESSW 9 is not a D3DTEXTUREADDRESS");
}

// ---------------------------------------------------------------------------
// Raster and output-merger states.

TEST(ValidateDevice, RasterStatesNeedRasterCaps) {
  DeviceState s;
  s.renderStates[RS_SCISSORTESTENABLE] = 1;
  EXPECT_EQ(reason(s, "dx8"), "SCISSORTESTENABLE needs SCISSORTEST in RasterCaps of dx8");
  EXPECT_EQ(reason(s, "dx9"), "ok");

  DeviceState bias;
  bias.renderStates[RS_DEPTHBIAS] = floatBits(0.5f);
  EXPECT_EQ(reason(bias, "dx81"), "DEPTHBIAS 0.5 needs DEPTHBIAS in RasterCaps of dx81");
  EXPECT_EQ(reason(bias, "dx9"), "ok");
  bias.renderStates[RS_DEPTHBIAS] = 0;
  bias.renderStates[RS_SLOPESCALEDEPTHBIAS] = floatBits(2.0f);
  EXPECT_EQ(reason(bias, "dx81"), "SLOPESCALEDEPTHBIAS 2 needs SLOPESCALEDEPTHBIAS in RasterCaps of dx81");
  EXPECT_EQ(reason(bias, "dx9"), "ok");

  // D3DZB_USEW: the DirectX 6 parts have a w-buffer, the GeForce line does not.
  DeviceState w;
  w.renderStates[RS_ZENABLE] = ZB_USEW;
  EXPECT_EQ(reason(w, "dx7"), "ZENABLE USEW needs WBUFFER in RasterCaps of dx7");
  EXPECT_EQ(reason(w, "dx6-tnt2"), "ok");
  CapsProfile noZ = variant("ref", "no-ztest");
  noZ.rasterCaps &= ~0x10u;
  w.renderStates[RS_ZENABLE] = ZB_TRUE;
  EXPECT_EQ(reason(w, noZ), "ZENABLE TRUE needs ZTEST in RasterCaps of no-ztest");

  DeviceState dither;
  dither.renderStates[RS_DITHERENABLE] = 1;
  CapsProfile noDither = variant("ref", "no-dither");
  noDither.rasterCaps &= ~0x1u;
  EXPECT_EQ(reason(dither, noDither), "DITHERENABLE needs DITHER in RasterCaps of no-dither");
  EXPECT_EQ(reason(dither, "dx6-tnt2"), "ok");
}

TEST(ValidateDevice, FogModesNeedFogCaps) {
  DeviceState s;
  s.renderStates[RS_FOGENABLE] = 1;
  s.renderStates[RS_FOGTABLEMODE] = FOG_LINEAR;
  CapsProfile vertexFogOnly = variant("ref", "vertex-fog-only");
  vertexFogOnly.rasterCaps &= ~0x100u;  // FOGTABLE
  EXPECT_EQ(reason(s, vertexFogOnly), "FOGTABLEMODE LINEAR needs FOGTABLE in RasterCaps of vertex-fog-only");
  s.renderStates[RS_FOGTABLEMODE] = FOG_NONE;
  s.renderStates[RS_FOGVERTEXMODE] = FOG_EXP;
  EXPECT_EQ(reason(s, vertexFogOnly), "ok");
  CapsProfile tableFogOnly = variant("ref", "table-fog-only");
  tableFogOnly.rasterCaps &= ~0x80u;  // FOGVERTEX
  EXPECT_EQ(reason(s, tableFogOnly),
            "FOGENABLE with FOGTABLEMODE NONE (vertex fog) needs FOGVERTEX in RasterCaps of table-fog-only");
  s.renderStates[RS_RANGEFOGENABLE] = 1;
  CapsProfile noRange = variant("ref", "no-range-fog");
  noRange.rasterCaps &= ~0x10000u;  // FOGRANGE
  EXPECT_EQ(reason(s, noRange), "RANGEFOGENABLE needs FOGRANGE in RasterCaps of no-range-fog");
  // Fog off: none of it matters.
  s.renderStates[RS_FOGENABLE] = 0;
  EXPECT_EQ(reason(s, noRange), "ok");
}

TEST(ValidateDevice, OutputStatesNeedMiscCaps) {
  DeviceState s;
  s.renderStates[RS_COLORWRITEENABLE] = CW_RED | CW_GREEN;
  EXPECT_EQ(reason(s, "dx7"), "COLORWRITEENABLE 0x3 needs COLORWRITEENABLE in PrimitiveMiscCaps of dx7");
  EXPECT_EQ(reason(s, "dx8"), "ok");

  DeviceState z;
  z.renderStates[RS_ZWRITEENABLE] = 0;
  CapsProfile noMaskZ = variant("ref", "no-maskz");
  noMaskZ.primitiveMiscCaps &= ~0x2u;
  EXPECT_EQ(reason(z, noMaskZ), "ZWRITEENABLE FALSE needs MASKZ in PrimitiveMiscCaps of no-maskz");

  DeviceState c;
  c.renderStates[RS_CULLMODE] = CULL_NONE;
  CapsProfile cullsAlways = variant("ref", "culls-always");
  cullsAlways.primitiveMiscCaps &= ~0x10u;  // CULLNONE
  EXPECT_EQ(reason(c, cullsAlways), "CULLMODE NONE needs CULLNONE in PrimitiveMiscCaps of culls-always");
  EXPECT_EQ(reason(c, "dx6-tnt2"), "ok");
}

// ---------------------------------------------------------------------------
// Fixed-function vertex limits, clip planes, points.

TEST(ValidateDevice, ActiveLightsAreLimited) {
  DeviceState s;
  s.lightEnabled[0] = s.lightEnabled[3] = s.lightEnabled[5] = true;
  CapsProfile twoLights = variant("dx7", "two-lights");
  twoLights.maxActiveLights = 2;
  EXPECT_EQ(reason(s, twoLights), "3 lights are enabled with LIGHTING but two-lights has MaxActiveLights 2");
  EXPECT_EQ(reason(s, "dx7"), "ok");  // 8
  // Without LIGHTING the enabled lights are not used.
  s.renderStates[RS_LIGHTING] = 0;
  EXPECT_EQ(reason(s, twoLights), "ok");
}

TEST(ValidateDevice, VertexBlendingIsLimited) {
  // D3DVBF_2WEIGHTS (2) blends 3 matrices; the GeForce2 blends 2.
  DeviceState s;
  s.renderStates[RS_VERTEXBLEND] = 2;
  EXPECT_EQ(reason(s, "dx7"), "VERTEXBLEND 2WEIGHTS blends 3 matrices but dx7 has MaxVertexBlendMatrices 2");
  EXPECT_EQ(reason(s, "dx8"), "ok");  // 4
  s.renderStates[RS_VERTEXBLEND] = 1;  // D3DVBF_1WEIGHTS: 2 matrices
  EXPECT_EQ(reason(s, "dx7"), "ok");
  s.renderStates[RS_VERTEXBLEND] = 255;  // D3DVBF_TWEENING blends no matrices
  EXPECT_EQ(reason(s, "dx7"), "ok");
  s.renderStates[RS_VERTEXBLEND] = 7;
  EXPECT_EQ(reason(s, "ref"), "VERTEXBLEND 7 is not a D3DVERTEXBLENDFLAGS");

  // Indexed blending needs a matrix palette: NVIDIA's parts report index 0.
  DeviceState i;
  i.renderStates[RS_INDEXEDVERTEXBLENDENABLE] = 1;
  EXPECT_EQ(reason(i, "dx8"), "INDEXEDVERTEXBLENDENABLE needs MaxVertexBlendMatrixIndex above 0; dx8 has 0");
  EXPECT_EQ(reason(i, "dx81"), "ok");
  EXPECT_EQ(reason(i, "ref"), "ok");
}

TEST(ValidateDevice, UserClipPlanesAreLimited) {
  DeviceState s;
  s.renderStates[RS_CLIPPLANEENABLE] = 0x1;
  EXPECT_EQ(reason(s, "dx7"), "CLIPPLANEENABLE 0x1 enables plane 0 but dx7 has MaxUserClipPlanes 0");
  s.renderStates[RS_CLIPPLANEENABLE] = 0x3f;  // planes 0-5
  EXPECT_EQ(reason(s, "ref"), "ok");
  s.renderStates[RS_CLIPPLANEENABLE] = 0x41;  // plane 6 does not exist in D3D9
  EXPECT_EQ(reason(s, "ref"), "CLIPPLANEENABLE 0x41 enables plane 6 but ref has MaxUserClipPlanes 6");
}

TEST(ValidateDevice, PointSizeIsLimited) {
  DeviceState s;
  s.renderStates[RS_POINTSIZE] = floatBits(8.0f);
  // MaxPointSize 1: a DirectX 7 part draws one-pixel points only.
  EXPECT_EQ(reason(s, "dx7"), "POINTSIZE 8 exceeds MaxPointSize 1 of dx7");
  EXPECT_EQ(reason(s, "ref"), "ok");
  s.renderStates[RS_POINTSIZE] = floatBits(300.0f);
  EXPECT_EQ(reason(s, "ref"), "POINTSIZE 300 exceeds MaxPointSize 256 of ref");
}

// ---------------------------------------------------------------------------
// Multiple render targets (the targets are the device's, passed beside the state).

TEST(ValidateDevice, RenderTargetsAreLimited) {
  auto mrt = [](const DeviceState& s, const std::string& profile, RenderTargetBinding t) {
    ValidationResult r = validateDeviceState(s, caps(profile), t);
    return r.ok ? std::string("ok") : r.reason;
  };
  DeviceState s;
  EXPECT_EQ(mrt(s, "dx8", {4, false}), "4 render targets are bound but dx8 has NumSimultaneousRTs 1");
  EXPECT_EQ(mrt(s, "dx9", {4, false}), "ok");
  EXPECT_EQ(mrt(s, "dx8", {1, false}), "ok");
  // The R300 blends render target 0 only; the NV40 blends all of them.
  s.renderStates[RS_ALPHABLENDENABLE] = 1;
  EXPECT_EQ(mrt(s, "dx9", {2, false}),
            "ALPHABLENDENABLE with 2 render targets needs MRTPOSTPIXELSHADERBLENDING in "
            "PrimitiveMiscCaps of dx9");
  EXPECT_EQ(mrt(s, "dx9-sm3", {2, false}), "ok");
  // Targets of different formats need MRTINDEPENDENTBITDEPTHS (none of the parts).
  EXPECT_EQ(mrt(s, "dx9-sm3", {2, true}),
            "render targets of different formats need MRTINDEPENDENTBITDEPTHS in "
            "PrimitiveMiscCaps of dx9-sm3");
  EXPECT_EQ(mrt(s, "ref", {2, true}), "ok");
  // A write mask of target 1 other than target 0's needs INDEPENDENTWRITEMASKS.
  DeviceState m;
  m.renderStates[RS_COLORWRITEENABLE1] = CW_RED;
  CapsProfile shared = variant("dx9", "shared-masks");
  shared.primitiveMiscCaps &= ~0x4000u;
  ValidationResult r = validateDeviceState(m, shared, {2, false});
  EXPECT_EQ(r.reason,
            "COLORWRITEENABLE1 differs from COLORWRITEENABLE: needs INDEPENDENTWRITEMASKS in "
            "PrimitiveMiscCaps of shared-masks");
  // With one target bound, COLORWRITEENABLE1 is not used.
  EXPECT_TRUE(validateDeviceState(m, shared, {1, false}).ok);
}

// ---------------------------------------------------------------------------
// With shaders, the samplers the shader declares or reads are the ones in use.

namespace {

std::shared_ptr<const PixelShader> pixelShader(std::string_view text) {
  return std::make_shared<PixelShader>(shader::assembleTokens(text, "p.psh"));
}
std::shared_ptr<const VertexShader> vertexShader(std::string_view text) {
  return std::make_shared<VertexShader>(shader::assembleTokens(text, "v.vsh"));
}

}  // namespace

TEST(ValidateDevice, PixelShaderSamplersAreTheOnesInUse) {
  CapsProfile noAniso = variant("ref", "no-aniso-filter");
  noAniso.textureFilterCaps &= ~0x400u;  // D3DPTFILTERCAPS_MINFANISOTROPIC
  DeviceState s;
  for (int i : {0, 1, 2}) {
    s.textures[i] = tex2D();
    s.samplerStates[i][SAMP_MINFILTER] = 3;  // ANISOTROPIC
  }
  // ps_2_0 reads s1 only: sampler 0 and 2 hold textures the shader never samples.
  s.pixelShader = pixelShader("ps_2_0\ndcl t0.xy\ndcl_2d s1\ntexld r0, t0, s1\nmov oC0, r0\n");
  EXPECT_EQ(reason(s, noAniso),
            "sampler 1 MINFILTER ANISOTROPIC needs MINFANISOTROPIC in TextureFilterCaps of "
            "no-aniso-filter");
  s.samplerStates[1][SAMP_MINFILTER] = 2;  // LINEAR
  EXPECT_EQ(reason(s, noAniso), "ok");
  // ps_1_1 `tex t2` samples stage 2's texture.
  s.pixelShader = pixelShader("ps_1_1\ntex t2\nmov r0, t2\n");
  EXPECT_EQ(reason(s, noAniso),
            "sampler 2 MINFILTER ANISOTROPIC needs MINFANISOTROPIC in TextureFilterCaps of "
            "no-aniso-filter");
}

TEST(ValidateDevice, VertexSamplersNeedVertexTextureFilterCaps) {
  // The NV40 fetches vertex textures with point filtering only
  // (VertexTextureFilterCaps MINFPOINT | MAGFPOINT).
  DeviceState s;
  s.textures[kVertexSampler0] = tex2D();
  s.vertexShader = vertexShader(
      "vs_3_0\ndcl_position v0\ndcl_2d s0\ndcl_position o0\ndcl_color0 o1\n"
      "mov o0, v0\ntexldl r0, v0, s0\nmov o1, r0\n");
  s.pixelShader = pixelShader("ps_3_0\ndcl_color0 v0\nmov oC0, v0\n");
  EXPECT_EQ(reason(s, "dx9-sm3"), "ok");
  s.samplerStates[kVertexSampler0][SAMP_MAGFILTER] = 2;  // LINEAR
  EXPECT_EQ(reason(s, "dx9-sm3"),
            "vertex sampler 0 MAGFILTER LINEAR needs MAGFLINEAR in VertexTextureFilterCaps of "
            "dx9-sm3");
  EXPECT_EQ(reason(s, "ref"), "ok");
}

// ---------------------------------------------------------------------------
// Texture shapes and projection against TextureCaps.

TEST(ValidateDevice, PowerOfTwoRestrictions) {
  // The TNT2 has POW2 without NONPOW2CONDITIONAL: power-of-two sizes only.
  DeviceState s = textured(Texture::create2D(Format::A8R8G8B8, 6, 4));
  EXPECT_EQ(reason(s, "dx6-tnt2"), "sampler 0 texture is 6x4 but dx6-tnt2 has POW2 in TextureCaps");
  // The GeForce2 has NONPOW2CONDITIONAL: other sizes clamped and without mipmaps.
  EXPECT_EQ(reason(s, "dx7"),
            "sampler 0 texture is 6x4: with POW2 and NONPOW2CONDITIONAL in TextureCaps of dx7 it "
            "must be addressed with CLAMP");
  s.samplerStates[0][SAMP_ADDRESSU] = s.samplerStates[0][SAMP_ADDRESSV] = 3;  // CLAMP
  EXPECT_EQ(reason(s, "dx7"), "ok");
  s.textures[0] = Texture::create2D(Format::A8R8G8B8, 6, 4, 2);
  s.samplerStates[0][SAMP_MIPFILTER] = 1;  // POINT
  EXPECT_EQ(reason(s, "dx7"),
            "sampler 0 texture is 6x4: with POW2 and NONPOW2CONDITIONAL in TextureCaps of dx7 it "
            "cannot be mipmapped");
  EXPECT_EQ(reason(s, "dx9-sm3"), "ok");  // no restriction
  // Cube maps: CUBEMAP_POW2.
  DeviceState c = textured(Texture::createCube(Format::A8R8G8B8, 6));
  EXPECT_EQ(reason(c, "dx7"), "sampler 0 cube texture is 6 texels wide but dx7 has CUBEMAP_POW2 in TextureCaps");
  EXPECT_EQ(reason(c, "ref"), "ok");
  DeviceState v = textured(Texture::createVolume(Format::A8R8G8B8, 4, 4, 3));
  EXPECT_EQ(reason(v, "dx8"), "sampler 0 volume texture is 4x4x3 but dx8 has VOLUMEMAP_POW2 in TextureCaps");
  EXPECT_EQ(reason(v, "ref"), "ok");
}

TEST(ValidateDevice, MipmapsNeedTheMipCapsOfTheirType) {
  DeviceState s = textured(Texture::createVolume(Format::A8R8G8B8, 4, 4, 4, 3));
  CapsProfile noVolumeMips = variant("ref", "no-volume-mips");
  noVolumeMips.textureCaps &= ~0x8000u;  // D3DPTEXTURECAPS_MIPVOLUMEMAP
  // MIPFILTER NONE samples level 0 only.
  EXPECT_EQ(reason(s, noVolumeMips), "ok");
  s.samplerStates[0][SAMP_MIPFILTER] = 2;  // LINEAR
  EXPECT_EQ(reason(s, noVolumeMips),
            "sampler 0 mipmapped texture (3 levels, MIPFILTER LINEAR) needs MIPVOLUMEMAP in "
            "TextureCaps of no-volume-mips");
  EXPECT_EQ(reason(s, "ref"), "ok");
}

TEST(ValidateDevice, ProjectedStagesNeedProjectedTextures) {
  // D3DTTFF_PROJECTED on a stage that samples its texture: the DirectX 6 parts lack
  // D3DPTEXTURECAPS_PROJECTED.
  DeviceState s = textured(tex2D());
  s.stageStates[0][TSS_TEXTURETRANSFORMFLAGS] = TTFF_COUNT3 | TTFF_PROJECTED;
  EXPECT_EQ(reason(s, "dx6-tnt2"),
            "stage 0 TEXTURETRANSFORMFLAGS PROJECTED needs PROJECTED in TextureCaps of dx6-tnt2");
  EXPECT_EQ(reason(s, "dx7"), "ok");
}
