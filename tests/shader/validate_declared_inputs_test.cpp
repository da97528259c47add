// Declared-input check: from vs_2_0 / ps_2_0 on, every input a shader reads is declared
// first (v#; in pixel shaders also t#, vPos, vFace), and a pixel shader reads only the
// components it declares (dcl t0.xy leaves .zw undefined). vs_1_1 maps its inputs with
// the D3D8 vertex declaration unless it uses dcl, in which case dcl covers every read.
// texkill reads its operand, so a t# it tests is declared too.
#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

TEST(ValidateDeclaredInputs, Sm2InputsAreDeclaredBeforeUse) {
  EXPECT_TRUE(isValid("vs_2_0\ndcl_position v0\nmov oPos, v0"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\nmov oPos, v0\nmov oT0, v1", "v1 is read but not declared (dcl)"));
  EXPECT_TRUE(isValid("ps_2_0\ndcl t0\nmov oC0, t0"));
  EXPECT_TRUE(hasError("ps_2_0\nmov oC0, t0", "t0 is read but not declared (dcl)"));
  EXPECT_TRUE(hasError("ps_2_0\ndcl t1\ntexkill t0\nmov oC0, t1", "t0 is read but not declared (dcl)"));
}

TEST(ValidateDeclaredInputs, PixelShadersReadOnlyDeclaredComponents) {
  EXPECT_TRUE(isValid("ps_2_0\ndcl t0.xy\nmov r0.xy, t0\nmov r0.zw, c0\nmov oC0, r0"));
  // mov r0, t0 reads .xyzw; .zw are not declared.
  EXPECT_TRUE(hasError("ps_2_0\ndcl t0.xy\nmov r0, t0\nmov oC0, r0", "t0.zw is read but only t0.xy is declared"));
}

TEST(ValidateDeclaredInputs, Vs11DeclaresAllOrNothing) {
  EXPECT_TRUE(isValid("vs_1_1\nmov oPos, v0\nmov oT0, v7"));
  EXPECT_TRUE(hasError("vs_1_1\ndcl_position v0\nmov oPos, v0\nmov oT0, v7", "v7 is read but not declared (dcl)"));
}

}  // namespace
}  // namespace refx::shader
