// Modifier check: result modifiers and shifts the version has (ps_1_1 – ps_1_3
// _x2 _x4 _d2, ps_1_4 _x2 … _d8, _pp from ps_2_0, _sat in vs from vs_3_0), write masks
// (ps_1_1 – ps_1_3: .rgba, .rgb, .a), the version's source modifiers (_bias _bx2 1- in
// ps_1_x, _x2 from ps_1_4, _abs from SM3) and swizzles (ps_1_1: .a, .b on alpha writes;
// ps_1_4: replicates; ps_2_0: replicates, .yzxw, .zxyw, .wzyx; arbitrary in SM3 and
// with D3DPS20CAPS_ARBITRARYSWIZZLE).
#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

TEST(ValidatorPs11, Selectors) {
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\nmul r0, t0, t0.a"));
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\nmov r0.rgb, t0\n+mov r0.a, t0.b"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmov r0, t0.b", "the .b selector is allowed in ps_1_1 only on instructions that write .a"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmov r0, t0.g", "ps_1_1 source selectors are .a and .b (replicate)"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r0, t0\nmov r0, r0.g"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\nmov r0, r0.yxzw", "ps_1_4 source selectors are .r, .g, .b and .a"));
}

TEST(ValidatorPs11, WriteMasks) {
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\nmov r0.rgb, t0\nmov r0.a, t0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmov r0, t0\nmov r0.rg, t0", "ps_1_1 write masks are .rgba, .rgb and .a; .xy is not allowed"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmov r0, t0\ndp3 r0.a, t0, t0", "dp3 in ps_1_1 writes .rgb or .rgba"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r0, t0\nmov r0.rg, r0"));
}

TEST(ValidatorPs11, InstructionModifiers) {
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\nmul_x4 r0, t0, t0\nmul_d2_sat r0, r0, t0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmul_x8 r0, t0, t0", "_x8 is not available in ps_1_1"));
  EXPECT_TRUE(hasError("ps_1_3\ntex t0\nmul_d4 r0, t0, t0", "_d4 is not available in ps_1_3"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r0, t0\nmul_x8 r0, r0, r0\nmul_d8 r0, r0, r0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmul_pp r0, t0, t0", "_pp is not available in ps_1_1"));
}

TEST(ValidatorPs11, SourceModifiers) {
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\nmad r0, t0_bias, -t0_bx2, 1-t0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmov r0, t0_x2", "source modifier _x2 is not available in ps_1_1"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r0, t0\nmov r0, r0_x2"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\nadd r0, r0, -c0", "source modifiers on constants are not allowed in ps_1_4 (c0)"));
}

TEST(ValidatorVs, Saturate) {
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\nmov_sat oPos, v0", "_sat is not available in vs_2_0"));
  EXPECT_TRUE(isValid("vs_3_0\ndcl_position v0\ndcl_position o0\nmov_sat o0, v0"));
  EXPECT_TRUE(hasError("vs_3_0\ndcl_position v0\ndcl_position o0\nfrc_sat r0, v0\nmov o0, r0", "frc cannot take _sat"));
}

TEST(ValidatorPs20, ModifiersAndSwizzles) {
  std::string h = "ps_2_0\ndcl t0\n";
  EXPECT_TRUE(hasError(h + "mov r0, t0_bias\nmov oC0, r0", "source modifier _bias is not available in ps_2_0"));
  EXPECT_TRUE(hasError(h + "mov r0, t0_bx2\nmov oC0, r0", "source modifier _bx2 is not available in ps_2_0"));
  EXPECT_TRUE(hasError(h + "mov r0, t0_abs\nmov oC0, r0", "source modifier _abs is not available in ps_2_0"));
  EXPECT_TRUE(isValid("ps_3_0\ndcl_texcoord0 v0\nmov r0, v0_abs\nmov oC0, r0"));
  EXPECT_TRUE(hasError(readRaw(h + "mul_x2 r0, t0, t0\nmov oC0, r0"), "_x2 is not available in ps_2_0"));
  EXPECT_TRUE(isValid(h + "mul_pp r0, t0, t0.yzxw\nmov oC0, r0"));
  EXPECT_TRUE(hasError(h + "mov r0, t0.yxzw\nmov oC0, r0", "ps_2_0 allows the swizzles .xyzw, replicate, .yzxw, .zxyw and .wzyx only"));
  ValidationCaps arb;
  arb.ps2xArbitrarySwizzle = true;
  EXPECT_TRUE(isValid("ps_2_x\ndcl t0\nmov r0, t0.yxzw\nmov oC0, r0", arb));
  EXPECT_TRUE(isValid("ps_3_0\ndcl_texcoord0 v0\nmov r0, v0.yxzw\nmov oC0, r0"));
}

}  // namespace
}  // namespace refx::shader
