// dcl check: which files a version declares, each register once (vs_3_0 outputs
// with disjoint masks), a texture type exactly on samplers, a D3DDECLUSAGE usage, a
// non-empty mask, no shift or _sat; vs_3_0 declares its outputs, one as the position.
#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

TEST(ValidatorVs, Declarations) {
  EXPECT_TRUE(isValid("vs_2_0\ndcl_position v0\ndcl_texcoord0 v1\nmov oPos, v0\nmov oT0, v1"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\nmov oPos, v0\nmov oT0, v1", "v1 is read but not declared (dcl)"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\nmov oPos, v0\ndcl_texcoord0 v1\nmov oT0, v1",
                       "dcl must come before the first arithmetic, texture or flow-control instruction"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\ndcl_normal v0\nmov oPos, v0", "v0 is declared twice"));
  EXPECT_TRUE(isValid("vs_1_1\nmov oPos, v0\nmov oT0, v7"));  // D3D8 vertex declarations: no dcl
  EXPECT_TRUE(hasError("vs_1_1\ndcl_position v0\nmov oPos, v0\nmov oT0, v7", "v7 is read but not declared (dcl)"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position oPos\nmov oPos, c0", "dcl cannot declare oPos in vs_2_0"));
  // vs_3_0 outputs are declared, one of them as the position.
  EXPECT_TRUE(isValid("vs_3_0\ndcl_position v0\ndcl_position o0\ndcl_texcoord0 o1.xy\nmov o0, v0\nmov o1.xy, v0"));
  EXPECT_TRUE(hasError("vs_3_0\ndcl_position v0\ndcl_position o0\nmov o0, v0\nmov o1, v0", "o1 is written but not declared"));
  EXPECT_TRUE(hasError("vs_3_0\ndcl_position v0\ndcl_texcoord0 o0\nmov o0, v0", "vs_3_0 must declare a position output (dcl_position o#)"));
  EXPECT_TRUE(hasError("vs_3_0\ndcl_position v0\ndcl_position o0\ndcl_texcoord0 o1.xy\nmov o0, v0\nmov o1, v0",
                       "o1.zw is written but only o1.xy is declared"));
}

TEST(ValidatorPs20, Declarations) {
  EXPECT_TRUE(hasError("ps_2_0\ndcl t0\ntexld r0, t0, s0\nmov oC0, r0", "s0 is used before it is declared (dcl_2d, dcl_cube or dcl_volume)"));
  EXPECT_TRUE(hasError("ps_2_0\ndcl_2d s0\ntexld r0, t0, s0\nmov oC0, r0", "t0 is read but not declared (dcl)"));
  EXPECT_TRUE(hasError("ps_2_0\ndcl t0.xy\nmov r0, t0\nmov oC0, r0", "t0.zw is read but only t0.xy is declared"));
  EXPECT_TRUE(hasError("ps_1_1\ndcl t0\ntex t0\nmov r0, t0", "dcl is not a ps_1_1 instruction"));
  EXPECT_TRUE(hasError("ps_2_0\ndcl s0\nmov oC0, c0", "dcl of s0 needs a texture type"));
  EXPECT_TRUE(isValid("ps_2_0\ndcl_centroid t0\nmov oC0, t0"));
  EXPECT_TRUE(hasError("ps_2_0\ndcl t0\nmov r0, t0\nmov oC0, r0\ndcl v0", "dcl must come before"));
}

TEST(ValidatorTokens, DclTakesNoShift) {
  using namespace refx::shader;
  // vs_2_0: dcl_position v0 whose destination token has shift bits 27:24 = 0x9 (-7, a
  // "_d128" no assembler can write); m4x4 oPos, v0, c0.
  EXPECT_EQ(firstProblem(vs20WithDcl(0x80000000, 0x990F0000)),
            "dcl takes no shift (_x2, _d2 ...)");
}

TEST(ValidatorTokens, TextureTypeBelongsToSamplerDcls) {
  using namespace refx::shader;
  // vs_2_0: dcl_position v0 with bits 30:27 of its usage token = 8 (0xC0000000: the
  // texture type field, which only a sampler dcl uses); m4x4 oPos, v0, c0.
  EXPECT_EQ(firstProblem(vs20WithDcl(0xC0000000, 0x900F0000)),
            "dcl of v0 has a texture type; only samplers (s#) have one");
}

TEST(ValidatorTokens, SamplerDclsCarryNoUsage) {
  using namespace refx::shader;
  // ps_2_0: dcl_2d s0 whose usage token 0x900A0000 has usage index 10 in bits 19:16 (a
  // sampler's usage fields are reserved, and no assembler text can express them);
  // mov oC0, c0.
  EXPECT_EQ(firstProblem({0xFFFF0200, 0x0200001F, 0x900A0000, 0xA00F0800, 0x02000001, 0x800F0800,
                          0xA0E40000, 0x0000FFFF}),
            "dcl of s0 has a usage (0, index 10); a sampler dcl carries only a texture type");
  // The same with usage 5 (texcoord) in bits 3:0.
  EXPECT_EQ(firstProblem({0xFFFF0200, 0x0200001F, 0x90000005, 0xA00F0800, 0x02000001, 0x800F0800,
                          0xA0E40000, 0x0000FFFF}),
            "dcl of s0 has a usage (5, index 0); a sampler dcl carries only a texture type");
}

TEST(ValidatorTokens, Ps2xInputDclsCarryNoUsage) {
  using namespace refx::shader;
  // ps_2_0: dcl t1 whose usage token 0x80000005 says texcoord (usage 5): ps_2_x input
  // declarations are bit 31 alone; mov oC0, t1.
  EXPECT_EQ(firstProblem({0xFFFF0200, 0x0200001F, 0x80000005, 0xB00F0001, 0x02000001, 0x800F0800,
                          0xB0E40001, 0x0000FFFF}),
            "dcl of t1 has a usage (5, index 0); ps_2_0 declarations carry none");
  // The same with usage index 3 (bits 19:16) on v0.
  EXPECT_EQ(firstProblem({0xFFFF0200, 0x0200001F, 0x80030000, 0x900F0000, 0x02000001, 0x800F0800,
                          0x90E40000, 0x0000FFFF}),
            "dcl of v0 has a usage (0, index 3); ps_2_0 declarations carry none");
}

TEST(ValidatorTokens, DclUsageBeyondSampleIsRejected) {
  using namespace refx::shader;
  // vs_2_0: dcl v0 with usage 14 in its usage token (0x8000000E; D3DDECLUSAGE_SAMPLE = 13
  // is the last); m4x4 oPos, v0, c0.
  EXPECT_EQ(firstProblem(vs20WithDcl(0x8000000E, 0x900F0000)),
            "dcl of v0 has usage 14; D3DDECLUSAGE ends at 13 (sample)");
}

TEST(ValidatorTokens, DclWithAnEmptyMaskIsRejected) {
  using namespace refx::shader;
  // vs_2_0: dcl_position v0 with write mask 0 (0x90000000); m4x4 oPos, v0, c0.
  EXPECT_EQ(firstProblem(vs20WithDcl(0x80000000, 0x90000000)),
            "dcl of v0 declares no component (empty write mask)");
}

}  // namespace
}  // namespace refx::shader
