#include <gtest/gtest.h>

#include "refx/pipeline/d3d9types.h"

using namespace refx::d3d;

TEST(D3D9Names, RenderStateNamesMatchD3D9Values) {
  // Values from d3d9types.h: D3DRS_ZENABLE = 7, D3DRS_SRCBLEND = 19, D3DRS_WRAP1 = 129,
  // D3DRS_WRAP15 = 205, D3DRS_BLENDOPALPHA = 209.
  EXPECT_EQ(parseEnum(EnumKind::RenderState, "ZENABLE"), 7u);
  EXPECT_EQ(parseEnum(EnumKind::RenderState, "srcblend"), 19u);
  EXPECT_EQ(parseEnum(EnumKind::RenderState, "D3DRS_WRAP1"), 129u);
  EXPECT_EQ(parseEnum(EnumKind::RenderState, "d3drs_wrap15"), 205u);
  EXPECT_EQ(parseEnum(EnumKind::RenderState, "BLENDOPALPHA"), 209u);
  EXPECT_EQ(enumName(EnumKind::RenderState, 60), "TEXTUREFACTOR");
  EXPECT_EQ(enumName(EnumKind::RenderState, 1), "");
  EXPECT_FALSE(parseEnum(EnumKind::RenderState, "ZENABLED"));
  EXPECT_FALSE(parseEnum(EnumKind::RenderState, "D3DRS_"));
  EXPECT_FALSE(parseEnum(EnumKind::RenderState, ""));
}

TEST(D3D9Names, EveryNameRoundTrips) {
  // enumName(parseEnum(n)) == n for the canonical names of each kind.
  struct Case {
    EnumKind kind;
    uint32_t first, last;
  } cases[] = {
      {EnumKind::TextureOp, TOP_DISABLE, TOP_LERP},
      {EnumKind::Blend, BLEND_ZERO, BLEND_INVBLENDFACTOR},
      {EnumKind::BlendOp, BLENDOP_ADD, BLENDOP_MAX},
      {EnumKind::CmpFunc, CMP_NEVER, CMP_ALWAYS},
      {EnumKind::StencilOp, STENCILOP_KEEP, STENCILOP_DECR},
      {EnumKind::Cull, CULL_NONE, CULL_CCW},
      {EnumKind::FillMode, FILL_POINT, FILL_SOLID},
      {EnumKind::ShadeMode, SHADE_FLAT, SHADE_PHONG},
      {EnumKind::FogMode, FOG_NONE, FOG_LINEAR},
      {EnumKind::ZBufferType, ZB_FALSE, ZB_USEW},
      {EnumKind::MaterialColorSource, MCS_MATERIAL, MCS_COLOR2},
      {EnumKind::TextureAddress, 1, 5},
      {EnumKind::LightType, LIGHT_POINT, LIGHT_DIRECTIONAL},
      {EnumKind::PrimitiveType, PT_POINTLIST, PT_TRIANGLEFAN},
      {EnumKind::TextureArg, TA_DIFFUSE, TA_CONSTANT},
      {EnumKind::SamplerState, SAMP_ADDRESSU, SAMP_DMAPOFFSET},
  };
  for (const Case& c : cases) {
    for (uint32_t v = c.first; v <= c.last; ++v) {
      std::string_view name = enumName(c.kind, v);
      ASSERT_FALSE(name.empty()) << int(c.kind) << " value " << v;
      EXPECT_EQ(parseEnum(c.kind, name), v) << name;
    }
  }
  for (uint32_t rs = 0; rs < kRenderStateCount; ++rs) {
    std::string_view name = enumName(EnumKind::RenderState, rs);
    if (!name.empty()) {
      EXPECT_EQ(parseEnum(EnumKind::RenderState, name), rs) << name;
    }
  }
}

TEST(D3D9Names, CanonicalNamesAndPrefixes) {
  EXPECT_EQ(enumName(EnumKind::TextureOp, 24), "DOTPRODUCT3");  // D3DTOP_DOTPRODUCT3 = 24
  EXPECT_EQ(parseEnum(EnumKind::TextureOp, "D3DTOP_MODULATE"), 4u);
  EXPECT_EQ(parseEnum(EnumKind::TextureOp, "d3dtop_lerp"), 26u);
  EXPECT_EQ(parseEnum(EnumKind::Blend, "SRCCOLOR"), 3u);
  EXPECT_EQ(parseEnum(EnumKind::Blend, "D3DBLEND_INVSRCALPHA"), 6u);
  EXPECT_FALSE(parseEnum(EnumKind::Blend, "D3DBLENDOP_ADD"));  // wrong enumeration
  EXPECT_EQ(parseEnum(EnumKind::BlendOp, "D3DBLENDOP_REVSUBTRACT"), 3u);
  EXPECT_EQ(parseEnum(EnumKind::CmpFunc, "GreaterEqual"), 7u);
  EXPECT_EQ(parseEnum(EnumKind::CmpFunc, "D3DCMP_ALWAYS"), 8u);
  EXPECT_EQ(parseEnum(EnumKind::StencilOp, "D3DSTENCILOP_INCRSAT"), 4u);
  EXPECT_EQ(parseEnum(EnumKind::Cull, "D3DCULL_CW"), 2u);
  EXPECT_EQ(parseEnum(EnumKind::FillMode, "D3DFILL_WIREFRAME"), 2u);
  EXPECT_EQ(parseEnum(EnumKind::ShadeMode, "D3DSHADE_FLAT"), 1u);
  EXPECT_EQ(parseEnum(EnumKind::FogMode, "D3DFOG_EXP2"), 2u);
  EXPECT_EQ(parseEnum(EnumKind::ZBufferType, "D3DZB_USEW"), 2u);
  EXPECT_EQ(parseEnum(EnumKind::ZBufferType, "TRUE"), 1u);
  EXPECT_EQ(parseEnum(EnumKind::MaterialColorSource, "D3DMCS_COLOR1"), 1u);
  EXPECT_EQ(parseEnum(EnumKind::TextureAddress, "D3DTADDRESS_MIRRORONCE"), 5u);
  EXPECT_EQ(parseEnum(EnumKind::TextureFilter, "D3DTEXF_ANISOTROPIC"), 3u);
  EXPECT_EQ(parseEnum(EnumKind::TextureFilter, "none"), 0u);
  EXPECT_EQ(parseEnum(EnumKind::LightType, "D3DLIGHT_SPOT"), 2u);
  EXPECT_EQ(parseEnum(EnumKind::PrimitiveType, "D3DPT_TRIANGLESTRIP"), 5u);
  EXPECT_EQ(parseEnum(EnumKind::TransformType, "D3DTS_WORLD"), 256u);
  EXPECT_EQ(parseEnum(EnumKind::TransformType, "TEXTURE3"), 19u);  // D3DTS_TEXTURE0 + 3
  EXPECT_EQ(parseEnum(EnumKind::TransformType, "VIEW"), 2u);
  EXPECT_EQ(parseEnum(EnumKind::TextureStageState, "D3DTSS_COLOROP"), 1u);
  EXPECT_EQ(parseEnum(EnumKind::TextureStageState, "CONSTANT"), 32u);
  EXPECT_EQ(parseEnum(EnumKind::SamplerState, "D3DSAMP_MIPMAPLODBIAS"), 8u);
}

TEST(D3D9Names, Bool) {
  EXPECT_EQ(parseEnum(EnumKind::Bool, "TRUE"), 1u);
  EXPECT_EQ(parseEnum(EnumKind::Bool, "false"), 0u);
  EXPECT_EQ(parseEnum(EnumKind::Bool, "1"), 1u);
  EXPECT_EQ(parseEnum(EnumKind::Bool, "0"), 0u);
  EXPECT_FALSE(parseEnum(EnumKind::Bool, "2"));
  EXPECT_FALSE(parseEnum(EnumKind::Bool, "yes"));
  EXPECT_EQ(enumName(EnumKind::Bool, 1), "TRUE");
  EXPECT_EQ(enumName(EnumKind::Bool, 0), "FALSE");
}

TEST(D3D9Names, CombinedFlags) {
  // D3DTA_TEXTURE (2) | D3DTA_COMPLEMENT (0x10) | D3DTA_ALPHAREPLICATE (0x20) = 0x32
  EXPECT_EQ(parseEnum(EnumKind::TextureArg, "TEXTURE|COMPLEMENT|ALPHAREPLICATE"), 0x32u);
  EXPECT_EQ(parseEnum(EnumKind::TextureArg, "D3DTA_TFACTOR | D3DTA_COMPLEMENT"), 0x13u);
  EXPECT_FALSE(parseEnum(EnumKind::TextureArg, "TEXTURE|"));
  // D3DCOLORWRITEENABLE_RED (1) | ALPHA (8) = 9
  EXPECT_EQ(parseEnum(EnumKind::ColorWrite, "RED|ALPHA"), 9u);
  EXPECT_EQ(parseEnum(EnumKind::ColorWrite, "D3DCOLORWRITEENABLE_BLUE"), 4u);
  // D3DTTFF_COUNT2 (2) | D3DTTFF_PROJECTED (256) = 258
  EXPECT_EQ(parseEnum(EnumKind::TextureTransformFlags, "COUNT2|PROJECTED"), 258u);
  EXPECT_EQ(parseEnum(EnumKind::TextureTransformFlags, "D3DTTFF_DISABLE"), 0u);
  // Coordinate index 1 | D3DTSS_TCI_CAMERASPACENORMAL (0x10000)
  EXPECT_EQ(parseEnum(EnumKind::TexCoordIndexFlags, "1|CAMERASPACENORMAL"), 0x10001u);
  EXPECT_EQ(parseEnum(EnumKind::TexCoordIndexFlags, "D3DTSS_TCI_SPHEREMAP"), 0x40000u);
  EXPECT_EQ(parseEnum(EnumKind::TexCoordIndexFlags, "3"), 3u);
  EXPECT_FALSE(parseEnum(EnumKind::TexCoordIndexFlags, "9"));
  // Single-valued enumerations do not combine.
  EXPECT_FALSE(parseEnum(EnumKind::Blend, "ONE|ZERO"));
}

TEST(D3D9Names, Formats) {
  // D3DFMT_A8R8G8B8 = 21, D3DFMT_V8U8 = 60.
  EXPECT_EQ(parseEnum(EnumKind::Format, "A8R8G8B8"), 21u);
  EXPECT_EQ(parseEnum(EnumKind::Format, "D3DFMT_V8U8"), 60u);
  EXPECT_EQ(enumName(EnumKind::Format, 21), "A8R8G8B8");
  EXPECT_FALSE(parseEnum(EnumKind::Format, "A9R9G9B9"));
}

TEST(D3D9Names, StateValueKinds) {
  auto is = [](StateValueInfo i, ValueKind k) { return i.kind == k; };
  auto isEnum = [](StateValueInfo i, ValueKind k, EnumKind e) {
    return i.kind == k && i.enumKind == e;
  };
  EXPECT_TRUE(isEnum(renderStateValue(RS_SRCBLEND), ValueKind::Enum, EnumKind::Blend));
  EXPECT_TRUE(isEnum(renderStateValue(RS_ZENABLE), ValueKind::Enum, EnumKind::ZBufferType));
  EXPECT_TRUE(isEnum(renderStateValue(RS_CULLMODE), ValueKind::Enum, EnumKind::Cull));
  EXPECT_TRUE(isEnum(renderStateValue(RS_ALPHAFUNC), ValueKind::Enum, EnumKind::CmpFunc));
  EXPECT_TRUE(isEnum(renderStateValue(RS_BLENDOPALPHA), ValueKind::Enum, EnumKind::BlendOp));
  EXPECT_TRUE(isEnum(renderStateValue(RS_ALPHABLENDENABLE), ValueKind::Enum, EnumKind::Bool));
  EXPECT_TRUE(isEnum(renderStateValue(RS_COLORWRITEENABLE), ValueKind::Flags,
                     EnumKind::ColorWrite));
  EXPECT_TRUE(isEnum(renderStateValue(RS_FOGTABLEMODE), ValueKind::Enum, EnumKind::FogMode));
  EXPECT_TRUE(isEnum(renderStateValue(RS_DIFFUSEMATERIALSOURCE), ValueKind::Enum,
                     EnumKind::MaterialColorSource));
  EXPECT_TRUE(is(renderStateValue(RS_FOGSTART), ValueKind::Float));
  EXPECT_TRUE(is(renderStateValue(RS_POINTSIZE), ValueKind::Float));
  EXPECT_TRUE(is(renderStateValue(RS_DEPTHBIAS), ValueKind::Float));
  EXPECT_TRUE(is(renderStateValue(RS_TEXTUREFACTOR), ValueKind::Color));
  EXPECT_TRUE(is(renderStateValue(RS_BLENDFACTOR), ValueKind::Color));
  EXPECT_TRUE(is(renderStateValue(RS_STENCILREF), ValueKind::Uint));
  EXPECT_TRUE(is(renderStateValue(RS_ALPHAREF), ValueKind::Uint));
  // RS_WRAPn take D3DWRAP_U (1) | D3DWRAP_V (2) | D3DWRAP_W (4) | D3DWRAPCOORD_3 (8).
  EXPECT_TRUE(isEnum(renderStateValue(RS_WRAP0), ValueKind::Flags, EnumKind::Wrap));
  EXPECT_TRUE(isEnum(renderStateValue(RS_WRAP0 + 3), ValueKind::Flags, EnumKind::Wrap));
  EXPECT_TRUE(isEnum(renderStateValue(RS_WRAP8 + 7), ValueKind::Flags, EnumKind::Wrap));
  EXPECT_EQ(parseEnum(EnumKind::Wrap, "U|V"), 3u);
  EXPECT_EQ(parseEnum(EnumKind::Wrap, "D3DWRAP_W"), 4u);

  EXPECT_TRUE(isEnum(textureStageStateValue(TSS_COLOROP), ValueKind::Enum,
                     EnumKind::TextureOp));
  EXPECT_TRUE(isEnum(textureStageStateValue(TSS_ALPHAARG2), ValueKind::Flags,
                     EnumKind::TextureArg));
  EXPECT_TRUE(isEnum(textureStageStateValue(TSS_RESULTARG), ValueKind::Flags,
                     EnumKind::TextureArg));
  EXPECT_TRUE(is(textureStageStateValue(TSS_BUMPENVMAT00), ValueKind::Float));
  EXPECT_TRUE(is(textureStageStateValue(TSS_BUMPENVLOFFSET), ValueKind::Float));
  EXPECT_TRUE(isEnum(textureStageStateValue(TSS_TEXCOORDINDEX), ValueKind::Uint,
                     EnumKind::TexCoordIndexFlags));
  EXPECT_TRUE(isEnum(textureStageStateValue(TSS_TEXTURETRANSFORMFLAGS), ValueKind::Flags,
                     EnumKind::TextureTransformFlags));
  EXPECT_TRUE(is(textureStageStateValue(TSS_CONSTANT), ValueKind::Color));

  EXPECT_TRUE(isEnum(samplerStateValue(SAMP_ADDRESSV), ValueKind::Enum,
                     EnumKind::TextureAddress));
  EXPECT_TRUE(isEnum(samplerStateValue(SAMP_MIPFILTER), ValueKind::Enum,
                     EnumKind::TextureFilter));
  EXPECT_TRUE(is(samplerStateValue(SAMP_BORDERCOLOR), ValueKind::Color));
  EXPECT_TRUE(is(samplerStateValue(SAMP_MIPMAPLODBIAS), ValueKind::Float));
  EXPECT_TRUE(is(samplerStateValue(SAMP_MAXMIPLEVEL), ValueKind::Uint));
  EXPECT_TRUE(isEnum(samplerStateValue(SAMP_SRGBTEXTURE), ValueKind::Enum, EnumKind::Bool));
}
