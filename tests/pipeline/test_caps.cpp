#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "refx/core/diagnostics.h"
#include "refx/pipeline/caps.h"

using namespace refx;

namespace {

// D3DTEXOPCAPS_x = 1 << (D3DTOP_x - 1): SUBTRACT 10, BUMPENVMAP 22,
// BUMPENVMAPLUMINANCE 23, DOTPRODUCT3 24, PREMODULATE 17, MULTIPLYADD 25, LERP 26.
constexpr uint32_t kOpSubtract = 1u << 9;
constexpr uint32_t kOpBumpEnvMap = 1u << 21;
constexpr uint32_t kOpBumpEnvMapLuminance = 1u << 22;
constexpr uint32_t kOpDotProduct3 = 1u << 23;
constexpr uint32_t kOpMultiplyAdd = 1u << 24;
// D3DPTEXTURECAPS_CUBEMAP 0x800, VOLUMEMAP 0x2000; D3DDEVCAPS_HWTRANSFORMANDLIGHT 0x10000;
// D3DPMISCCAPS_TSSARGTEMP 0x400, SEPARATEALPHABLEND 0x20000.
constexpr uint32_t kCubeMap = 0x800, kVolumeMap = 0x2000, kHwTnL = 0x10000;
constexpr uint32_t kTssArgTemp = 0x400, kSeparateAlphaBlend = 0x20000;
constexpr float kFltMax = std::numeric_limits<float>::max();

std::string errorOf(const std::string& text, const std::string& file = "test.caps") {
  try {
    parseCapsProfile(text, file);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(Caps, NamesInGenerationOrder) {
  std::vector<std::string> expected = {"dx6-tnt2", "dx6-g400", "dx7",     "dx8", "dx8-ps13",
                                       "dx81",     "dx9",      "dx9-sm3", "ref"};
  EXPECT_EQ(capsProfileNames(), expected);
}

TEST(Caps, EveryShippedProfileLoads) {
  for (const auto& name : capsProfileNames()) {
    SCOPED_TRACE(name);
    CapsProfile caps = loadCapsProfile(name);
    EXPECT_EQ(caps.name, name);
    EXPECT_FALSE(caps.description.empty());
    // Every device can at least disable a stage, select and modulate.
    EXPECT_EQ(caps.textureOpCaps & 0xf, 0xfu);
    EXPECT_GE(caps.maxTextureBlendStages, caps.maxSimultaneousTextures);
    EXPECT_GE(caps.maxTextureWidth, 2048u);
  }
}

TEST(Caps, ShaderVersionsNeverGoBackwardsAcrossGenerations) {
  uint32_t vs = 0, ps = 0;
  for (const auto& name : capsProfileNames()) {
    SCOPED_TRACE(name);
    CapsProfile caps = loadCapsProfile(name);
    uint32_t v = caps.vertexShaderVersion & 0xffff, p = caps.pixelShaderVersion & 0xffff;
    EXPECT_GE(v, vs);
    EXPECT_GE(p, ps);
    vs = v;
    ps = p;
  }
}

TEST(Caps, Tnt2HasTwoStagesAndNoBumpOrDot3) {
  CapsProfile caps = loadCapsProfile("dx6-tnt2");
  EXPECT_EQ(caps.maxTextureBlendStages, 2u);
  EXPECT_EQ(caps.maxSimultaneousTextures, 2u);
  EXPECT_EQ(caps.textureOpCaps & kOpBumpEnvMap, 0u);
  EXPECT_EQ(caps.textureOpCaps & kOpBumpEnvMapLuminance, 0u);
  EXPECT_EQ(caps.textureOpCaps & kOpDotProduct3, 0u);
  EXPECT_EQ(caps.textureOpCaps & kOpMultiplyAdd, 0u);
  EXPECT_EQ(caps.devCaps & kHwTnL, 0u);
  EXPECT_EQ(caps.textureCaps & kCubeMap, 0u);
  EXPECT_EQ(caps.vsMajor(), 0);
  EXPECT_EQ(caps.psMajor(), 0);
}

TEST(Caps, G400HasBumpEnvMap) {
  CapsProfile caps = loadCapsProfile("dx6-g400");
  EXPECT_NE(caps.textureOpCaps & kOpBumpEnvMap, 0u);
  EXPECT_NE(caps.textureOpCaps & kOpBumpEnvMapLuminance, 0u);
  EXPECT_EQ(caps.textureOpCaps & kOpDotProduct3, 0u);
  // Base + bump + environment map in one pass, as the seeds' DX6 listing needs.
  EXPECT_EQ(caps.maxTextureBlendStages, 3u);
  EXPECT_EQ(caps.maxSimultaneousTextures, 3u);
}

TEST(Caps, Dx7HasDot3SubtractHardwareTnLAndCubeMaps) {
  CapsProfile caps = loadCapsProfile("dx7");
  EXPECT_NE(caps.textureOpCaps & kOpDotProduct3, 0u);
  EXPECT_NE(caps.textureOpCaps & kOpSubtract, 0u);
  EXPECT_NE(caps.devCaps & kHwTnL, 0u);
  EXPECT_NE(caps.textureCaps & kCubeMap, 0u);
  EXPECT_EQ(caps.textureCaps & kVolumeMap, 0u);
  EXPECT_EQ(caps.primitiveMiscCaps & kTssArgTemp, 0u);
  EXPECT_EQ(caps.pixelShaderVersion & 0xffff, 0u);
}

TEST(Caps, Dx8IsPs11WithMaxValueOne) {
  CapsProfile caps = loadCapsProfile("dx8");
  // D3DPS_VERSION(1,1) = 0xFFFF0000 | 1<<8 | 1; D3DVS_VERSION(1,1) = 0xFFFE0101.
  EXPECT_EQ(caps.pixelShaderVersion, 0xFFFF0101u);
  EXPECT_EQ(caps.vertexShaderVersion, 0xFFFE0101u);
  EXPECT_EQ(caps.psMajor(), 1);
  EXPECT_EQ(caps.psMinor(), 1);
  EXPECT_EQ(caps.pixelShader1xMaxValue, 1.0f);
  EXPECT_EQ(caps.maxVertexShaderConst, 96u);
  EXPECT_EQ(caps.maxSimultaneousTextures, 4u);
  EXPECT_EQ(caps.maxTextureBlendStages, 8u);
  EXPECT_NE(caps.textureCaps & kVolumeMap, 0u);
  EXPECT_NE(caps.primitiveMiscCaps & kTssArgTemp, 0u);
}

TEST(Caps, Dx8Ps13IsPs13) {
  CapsProfile caps = loadCapsProfile("dx8-ps13");
  EXPECT_EQ(caps.pixelShaderVersion, 0xFFFF0103u);
  EXPECT_EQ(caps.pixelShader1xMaxValue, 1.0f);
}

TEST(Caps, Dx81IsPs14WithMaxValueEight) {
  CapsProfile caps = loadCapsProfile("dx81");
  EXPECT_EQ(caps.pixelShaderVersion, 0xFFFF0104u);
  EXPECT_EQ(caps.pixelShader1xMaxValue, 8.0f);
  EXPECT_EQ(caps.maxSimultaneousTextures, 6u);
  EXPECT_EQ(caps.maxTextureRepeat, 2048u);
}

TEST(Caps, Dx9ClassProfilesHaveFltMax) {
  CapsProfile dx9 = loadCapsProfile("dx9");
  EXPECT_EQ(dx9.pixelShader1xMaxValue, kFltMax);
  EXPECT_EQ(dx9.pixelShaderVersion, 0xFFFF0200u);
  EXPECT_EQ(dx9.vertexShaderVersion, 0xFFFE0200u);
  EXPECT_EQ(dx9.maxVertexShaderConst, 256u);
  EXPECT_EQ(dx9.maxSimultaneousTextures, 8u);
  EXPECT_NE(dx9.primitiveMiscCaps & kSeparateAlphaBlend, 0u);
  EXPECT_EQ(dx9.vertexTextureFilterCaps, 0u);

  CapsProfile sm3 = loadCapsProfile("dx9-sm3");
  EXPECT_EQ(sm3.pixelShader1xMaxValue, kFltMax);
  EXPECT_EQ(sm3.pixelShaderVersion, 0xFFFF0300u);
  EXPECT_EQ(sm3.vertexShaderVersion, 0xFFFE0300u);
  EXPECT_NE(sm3.vertexTextureFilterCaps, 0u);

  CapsProfile ref = loadCapsProfile("ref");
  EXPECT_EQ(ref.pixelShader1xMaxValue, kFltMax);
  // Every D3DTOP from DISABLE (1) to LERP (26): bits 0..25.
  EXPECT_EQ(ref.textureOpCaps, (1u << 26) - 1);
}

TEST(Caps, LoadsByPath) {
  CapsProfile caps = loadCapsProfile(std::string(REFX_DATA_DIR) + "/caps/dx7.caps");
  EXPECT_EQ(caps.name, "dx7");
  EXPECT_EQ(caps.maxSimultaneousTextures, 2u);
}

TEST(Caps, UnknownProfileListsKnownNames) {
  try {
    loadCapsProfile("dx10");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("unknown caps profile 'dx10'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("dx6-tnt2"), std::string::npos) << msg;
    EXPECT_NE(msg.find("dx9-sm3"), std::string::npos) << msg;
  }
  EXPECT_THROW(loadCapsProfile(""), Error);
  EXPECT_THROW(loadCapsProfile("/nonexistent/x.caps"), Error);
}

TEST(Caps, ParsesSymbolicFlagsNumbersAndContinuations) {
  CapsProfile caps = parseCapsProfile(
      "# comment\n"
      "Description = test device  # trailing comment\n"
      "TextureOpCaps = MODULATE | D3DTEXOPCAPS_ADD |   # continues\n"
      "\n"
      "    dotproduct3\n"
      "SrcBlendCaps = ONE | BLENDFACTOR\n"
      "PrimitiveMiscCaps = 0x400 | BLENDOP\n"
      "PixelShaderVersion = ps_1_4\n"
      "VertexShaderVersion = 2.0\n"
      "PixelShader1xMaxValue = 8\n"
      "MaxTextureBlendStages = 4\n"
      "FVFCaps = 8 | PSIZE\n",
      "my.caps");
  EXPECT_EQ(caps.name, "my");
  EXPECT_EQ(caps.description, "test device");
  // MODULATE = 4 -> bit 3 (0x8), ADD = 7 -> 0x40, DOTPRODUCT3 = 24 -> 0x800000.
  EXPECT_EQ(caps.textureOpCaps, 0x8u | 0x40u | 0x800000u);
  // D3DPBLENDCAPS_ONE 0x2, BLENDFACTOR 0x2000.
  EXPECT_EQ(caps.srcBlendCaps, 0x2002u);
  // TSSARGTEMP 0x400 | BLENDOP 0x800.
  EXPECT_EQ(caps.primitiveMiscCaps, 0xC00u);
  EXPECT_EQ(caps.pixelShaderVersion, 0xFFFF0104u);
  EXPECT_EQ(caps.vertexShaderVersion, 0xFFFE0200u);
  EXPECT_EQ(caps.pixelShader1xMaxValue, 8.0f);
  EXPECT_EQ(caps.maxTextureBlendStages, 4u);
  // 8 texture coordinate sets | D3DFVFCAPS_PSIZE 0x100000.
  EXPECT_EQ(caps.fvfCaps, 0x100008u);
}

TEST(Caps, ErrorsCarryFileAndLine) {
  std::string text = "# dx7\n\n\n\n\n\n\n\n\n\nMaxTextureBlendStages = 8\nFoo = 1\n";
  EXPECT_EQ(errorOf(text, "dx7.caps"), "dx7.caps:12: error: unknown caps field 'Foo'");

  std::string flag = errorOf("TextureOpCaps = MODULATE |\n  ADD | MODULATE9X\n");
  EXPECT_EQ(flag.rfind("test.caps:2: error: unknown D3DTEXOPCAPS_* flag 'MODULATE9X'", 0), 0u)
      << flag;
  EXPECT_EQ(errorOf("PixelShaderVersion = 1.5\n").rfind("test.caps:1: error: ", 0), 0u);
  EXPECT_EQ(errorOf("\nVertexShaderVersion = 1.4\n").rfind("test.caps:2: error: ", 0), 0u);
  EXPECT_EQ(errorOf("MaxTextureBlendStages = 9\n").rfind("test.caps:1: error: ", 0), 0u);
  EXPECT_EQ(errorOf("MaxTextureBlendStages = two\n").rfind("test.caps:1: error: ", 0), 0u);
  EXPECT_EQ(errorOf("MaxPixelShaderValue = -1\n").rfind("test.caps:1: error: ", 0), 0u);
  EXPECT_EQ(errorOf("MaxPixelShaderValue = inf\n").rfind("test.caps:1: error: ", 0), 0u);
  EXPECT_EQ(errorOf("MaxStreams = 4\nMaxStreams = 4\n").rfind("test.caps:2: error: ", 0), 0u);
  EXPECT_EQ(errorOf("just words\n").rfind("test.caps:1: error: ", 0), 0u);
  EXPECT_EQ(errorOf("TextureOpCaps = ADD | | MODULATE\n").rfind("test.caps:1: error: ", 0), 0u);
  EXPECT_EQ(errorOf("TextureOpCaps = ADD |\n").rfind("test.caps:1: error: ", 0), 0u);
  EXPECT_EQ(errorOf("TextureOpCaps =\n").rfind("test.caps:1: error: ", 0), 0u);
  EXPECT_EQ(errorOf("= 3\n").rfind("test.caps:1: error: ", 0), 0u);
  // INVBLENDFACTOR has no D3DPBLENDCAPS bit of its own (BLENDFACTOR covers it).
  EXPECT_EQ(errorOf("SrcBlendCaps = INVBLENDFACTOR\n").rfind("test.caps:1: error: ", 0), 0u);
}

TEST(Caps, DescriptionParsesBackToTheSameProfile) {
  for (const auto& name : capsProfileNames()) {
    SCOPED_TRACE(name);
    CapsProfile caps = loadCapsProfile(name);
    std::string text = describeCapsProfile(caps);
    CapsProfile again = parseCapsProfile(text, name + ".caps");
    EXPECT_EQ(describeCapsProfile(again), text);
    EXPECT_EQ(again.textureOpCaps, caps.textureOpCaps);
    EXPECT_EQ(again.pixelShaderVersion, caps.pixelShaderVersion);
    EXPECT_EQ(again.pixelShader1xMaxValue, caps.pixelShader1xMaxValue);
    EXPECT_EQ(again.fvfCaps, caps.fvfCaps);
  }
}

TEST(Caps, DescriptionUsesSymbolicNames) {
  std::string text = describeCapsProfile(loadCapsProfile("dx81"));
  EXPECT_NE(text.find("PixelShaderVersion = 1.4\n"), std::string::npos) << text;
  EXPECT_NE(text.find("MaxPixelShaderValue = 8.0\n"), std::string::npos) << text;
  EXPECT_NE(text.find("DOTPRODUCT3"), std::string::npos) << text;
  EXPECT_NE(text.find("TSSARGTEMP"), std::string::npos) << text;
  std::string ref = describeCapsProfile(loadCapsProfile("ref"));
  EXPECT_NE(ref.find("MaxPixelShaderValue = FLT_MAX\n"), std::string::npos) << ref;
  std::string tnt2 = describeCapsProfile(loadCapsProfile("dx6-tnt2"));
  EXPECT_NE(tnt2.find("PixelShaderVersion = none\n"), std::string::npos) << tnt2;
}
