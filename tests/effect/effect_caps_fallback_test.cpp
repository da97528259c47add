// Techniques falling back because ValidateDevice finds a sampler, raster or vertex
// state the profile's caps do not allow (the reasons name the caps field and flag).
#include <gtest/gtest.h>

#include "refx/effect/effect.h"
#include "refx/pipeline/caps.h"
#include "refx/resource/texture.h"

using namespace refx;
using namespace refx::effect;

namespace {

// Anisotropic filtering at 16 taps, then 4 taps, then trilinear: each part runs the
// first technique its filter caps and MaxAnisotropy allow.
constexpr const char* kFilterEffect = R"(
texture tex;
technique aniso16 {
  pass p0 { Texture[0] = <tex>; MinFilter[0] = Anisotropic; MagFilter[0] = Linear;
            MaxAnisotropy[0] = 16; }
}
technique aniso2 {
  pass p0 { Texture[0] = <tex>; MinFilter[0] = Anisotropic; MagFilter[0] = Linear;
            MaxAnisotropy[0] = 2; }
}
technique trilinear {
  pass p0 { Texture[0] = <tex>; MinFilter[0] = Linear; MagFilter[0] = Linear;
            MipFilter[0] = Linear; }
}
)";

// A scissored pass, then the same pass without the scissor test.
constexpr const char* kScissorEffect = R"(
technique scissored { pass p0 { ScissorTestEnable = true; } }
technique whole { pass p0 { ScissorTestEnable = false; } }
)";

// Two-matrix skinning with a palette, then without a palette, then none.
constexpr const char* kSkinningEffect = R"(
technique indexed { pass p0 { VertexBlend = 1; IndexedVertexBlendEnable = true; } }
technique weights { pass p0 { VertexBlend = 1; IndexedVertexBlendEnable = false; } }
technique rigid { pass p0 { VertexBlend = 0; } }
)";

}  // namespace

TEST(EffectCapsFallback, FilterCapsAndMaxAnisotropyPickTheTechnique) {
  auto fx = Effect::fromText(kFilterEffect, "filter.fx");
  ASSERT_TRUE(fx->diagnostics().empty()) << fx->diagnostics()[0].str();
  fx->setTexture(fx->parameterByName("tex"), Texture::create2D(Format::A8R8G8B8, 4, 4));
  // MaxAnisotropy: Radeon 8500 16, GeForce3 8, GeForce2 2; the TNT2 has no
  // MINFANISOTROPIC at all.
  EXPECT_EQ(fx->findNextValidTechnique(-1, loadCapsProfile("dx81")), 0);
  EXPECT_EQ(fx->findNextValidTechnique(-1, loadCapsProfile("dx8")), 1);
  EXPECT_EQ(fx->findNextValidTechnique(-1, loadCapsProfile("dx7")), 1);
  EXPECT_EQ(fx->findNextValidTechnique(-1, loadCapsProfile("dx6-tnt2")), 2);
  EXPECT_EQ(fx->validateTechnique(0, loadCapsProfile("dx8")).reason,
            "pass p0: sampler 0 MAXANISOTROPY 16 exceeds MaxAnisotropy 8 of dx8");
  EXPECT_EQ(fx->validateTechnique(1, loadCapsProfile("dx6-tnt2")).reason,
            "pass p0: sampler 0 MINFILTER ANISOTROPIC needs MINFANISOTROPIC in TextureFilterCaps "
            "of dx6-tnt2");
}

TEST(EffectCapsFallback, ScissorTestNeedsItsRasterCap) {
  auto fx = Effect::fromText(kScissorEffect, "scissor.fx");
  ASSERT_TRUE(fx->diagnostics().empty()) << fx->diagnostics()[0].str();
  EXPECT_EQ(fx->findNextValidTechnique(-1, loadCapsProfile("dx9")), 0);
  EXPECT_EQ(fx->findNextValidTechnique(-1, loadCapsProfile("dx81")), 1);
  EXPECT_EQ(fx->validateTechnique(0, loadCapsProfile("dx81")).reason,
            "pass p0: SCISSORTESTENABLE needs SCISSORTEST in RasterCaps of dx81");
}

TEST(EffectCapsFallback, VertexBlendCapsPickTheSkinningTechnique) {
  auto fx = Effect::fromText(kSkinningEffect, "skinning.fx");
  ASSERT_TRUE(fx->diagnostics().empty()) << fx->diagnostics()[0].str();
  // Radeon 8500: a palette (MaxVertexBlendMatrixIndex 37); GeForce3: 4 matrices without
  // a palette; GeForce2: 2 matrices, enough for one weight.
  EXPECT_EQ(fx->findNextValidTechnique(-1, loadCapsProfile("dx81")), 0);
  EXPECT_EQ(fx->findNextValidTechnique(-1, loadCapsProfile("dx8")), 1);
  EXPECT_EQ(fx->findNextValidTechnique(-1, loadCapsProfile("dx7")), 1);
  EXPECT_EQ(fx->validateTechnique(0, loadCapsProfile("dx8")).reason,
            "pass p0: INDEXEDVERTEXBLENDENABLE needs MaxVertexBlendMatrixIndex above 0; dx8 has 0");
}
