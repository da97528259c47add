// What each D3DTEXTUREOP reads (the D3D9 D3DTEXTUREOP documentation) and its TextureOpCaps
// bit (d3d9caps.h), as ValidateDevice and the fixed-function pixel program see them.
#include <gtest/gtest.h>

#include "pipeline/caps_flags.h"
#include "pipeline/texture_op_use.h"
#include "refx/pipeline/d3d9types.h"

namespace refx::pipeline {
namespace {

using namespace d3d;

struct Expected {
  uint32_t top;
  bool arg0, arg1, arg2, ownTexture, colorOnly;
};

// From the D3DTEXTUREOP page: SELECTARG1 = Arg1; SELECTARG2 = Arg2; the arithmetic ops
// combine Arg1 and Arg2; BLENDTEXTUREALPHA(PM) also read the stage's texture alpha;
// PREMODULATE passes Arg1 and modulates the next stage; the MODULATE*_ADD* ops are
// "supported only for color operations"; BUMPENVMAP(LUMINANCE) read the stage's du/dv
// texture, not its arguments, and are color operations; MULTIPLYADD = Arg0 + Arg1*Arg2
// and LERP = Arg0*Arg1 + (1-Arg0)*Arg2 are the only ops reading Arg0.
constexpr Expected kExpected[] = {
    {TOP_DISABLE, false, false, false, false, false},
    {TOP_SELECTARG1, false, true, false, false, false},
    {TOP_SELECTARG2, false, false, true, false, false},
    {TOP_MODULATE, false, true, true, false, false},
    {TOP_MODULATE2X, false, true, true, false, false},
    {TOP_MODULATE4X, false, true, true, false, false},
    {TOP_ADD, false, true, true, false, false},
    {TOP_ADDSIGNED, false, true, true, false, false},
    {TOP_ADDSIGNED2X, false, true, true, false, false},
    {TOP_SUBTRACT, false, true, true, false, false},
    {TOP_ADDSMOOTH, false, true, true, false, false},
    {TOP_BLENDDIFFUSEALPHA, false, true, true, false, false},
    {TOP_BLENDTEXTUREALPHA, false, true, true, true, false},
    {TOP_BLENDFACTORALPHA, false, true, true, false, false},
    {TOP_BLENDTEXTUREALPHAPM, false, true, true, true, false},
    {TOP_BLENDCURRENTALPHA, false, true, true, false, false},
    {TOP_PREMODULATE, false, true, false, false, false},
    {TOP_MODULATEALPHA_ADDCOLOR, false, true, true, false, true},
    {TOP_MODULATECOLOR_ADDALPHA, false, true, true, false, true},
    {TOP_MODULATEINVALPHA_ADDCOLOR, false, true, true, false, true},
    {TOP_MODULATEINVCOLOR_ADDALPHA, false, true, true, false, true},
    {TOP_BUMPENVMAP, false, false, false, true, true},
    {TOP_BUMPENVMAPLUMINANCE, false, false, false, true, true},
    {TOP_DOTPRODUCT3, false, true, true, false, false},
    {TOP_MULTIPLYADD, true, true, true, false, false},
    {TOP_LERP, true, true, true, false, false},
};

TEST(TextureOpUse, EveryOpReadsWhatD3D9Documents) {
  for (const Expected& e : kExpected) {
    SCOPED_TRACE(std::string(enumName(EnumKind::TextureOp, e.top)));
    const TextureOpUse use = textureOpUse(e.top);
    EXPECT_TRUE(use.valid);
    EXPECT_EQ(use.arg0, e.arg0);
    EXPECT_EQ(use.arg1, e.arg1);
    EXPECT_EQ(use.arg2, e.arg2);
    EXPECT_EQ(use.ownTexture, e.ownTexture);
    EXPECT_EQ(use.colorOnly, e.colorOnly);
  }
}

TEST(TextureOpUse, ValuesOutsideD3DTextureOpAreInvalid) {
  EXPECT_FALSE(textureOpUse(0).valid);
  EXPECT_FALSE(textureOpUse(TOP_LERP + 1).valid);
  EXPECT_FALSE(textureOpUse(0xFFFFFFFFu).valid);
}

// d3d9caps.h numbers D3DTEXOPCAPS_x as 1 << (D3DTOP_x - 1): DISABLE (1) = 0x1,
// MODULATE (4) = 0x8, LERP (26) = 0x2000000.
TEST(TextureOpUse, EveryOpHasItsTextureOpCapsBit) {
  for (uint32_t top = TOP_DISABLE; top <= TOP_LERP; ++top) {
    std::string_view name = enumName(EnumKind::TextureOp, top);
    EXPECT_EQ(caps_flags::bitOf(caps_flags::kTextureOpCaps, name), 1u << (top - 1)) << name;
  }
  EXPECT_EQ(caps_flags::bitOf(caps_flags::kTextureOpCaps, "MODULATE"), 0x8u);
  EXPECT_EQ(caps_flags::bitOf(caps_flags::kTextureOpCaps, "LERP"), 0x2000000u);
}

// D3DPBLENDCAPS_x = 1 << (D3DBLEND_x - 1) for ZERO (1) … BLENDFACTOR (14); D3DBLEND_
// INVBLENDFACTOR (15) has no bit of its own (D3DPBLENDCAPS_BLENDFACTOR covers both).
TEST(TextureOpUse, EveryBlendFactorHasItsBlendCapsBit) {
  for (uint32_t b = BLEND_ZERO; b <= BLEND_BLENDFACTOR; ++b) {
    std::string_view name = enumName(EnumKind::Blend, b);
    EXPECT_EQ(caps_flags::bitOf(caps_flags::kBlendCaps, name), 1u << (b - 1)) << name;
  }
  EXPECT_EQ(caps_flags::bitOf(caps_flags::kBlendCaps, "BLENDFACTOR"), 0x2000u);
  EXPECT_EQ(caps_flags::bitOf(caps_flags::kBlendCaps, "INVBLENDFACTOR"), 0u);
}

}  // namespace
}  // namespace refx::pipeline
