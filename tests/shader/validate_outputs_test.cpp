// Output check: vs_1_1 – vs_2_x write all of oPos; ps_2_x writes oC0 and render
// targets in order, each by one full-mask mov without modifiers outside flow control;
// oDepth takes a replicate swizzle; ps_3_0 writes outputs anywhere but in dynamic flow
// control.
#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

TEST(ValidatorVs, PositionOutput) {
  EXPECT_TRUE(isValid("vs_1_1\nmov oPos.xy, v0\nmov oPos.zw, v1"));
  EXPECT_TRUE(hasError("vs_1_1\nmov oPos.xyz, v0", "a vs_1_1 shader must write all four components of oPos (.w is never written)"));
  EXPECT_TRUE(hasError("vs_1_1\nmov oD0, v0", "must write all four components of oPos"));
}

TEST(ValidatorPs20, ColorOutputs) {
  std::string h = "ps_2_0\ndcl t0\n";
  EXPECT_TRUE(hasError(h + "mov r0, t0", "ps_2_0 must write oC0"));
  EXPECT_TRUE(hasError(h + "add oC0, t0, t0", "oC0 is written only by mov in ps_2_0"));
  EXPECT_TRUE(hasError(h + "mov_sat oC0, t0", "oC0 cannot be written with _sat in ps_2_0"));
  EXPECT_TRUE(hasError(h + "mov oC0, t0\nmov oC0, t0", "oC0 is written more than once"));
  EXPECT_TRUE(hasError(h + "mov oC0.xyz, t0", "oC0 is written with the full mask in ps_2_0"));
  EXPECT_TRUE(hasError(h + "mov oC0, t0\nmov oC2, t0", "oC2 is written but oC1 is not"));
  EXPECT_TRUE(hasError(h + "mov oC0, -t0", "mov to oC0 takes no source swizzle or modifier in ps_2_0"));
  EXPECT_TRUE(isValid("ps_3_0\ndcl_texcoord0 v0\nadd_sat oC0, v0, v0\nmul oC0.x, v0, c0"));
}

// oDepth takes one scalar: a replicate swizzle selects it (fxc writes mov oDepth, r0.x),
// any other swizzle and any modifier are errors, as for oCn.
TEST(ValidatorPs20, DepthOutputSwizzle) {
  for (std::string h : {"ps_2_0\ndcl t0\n", "ps_2_x\ndcl t0\n"}) {
    const std::string ver = h.substr(0, 6);
    for (const char* rep : {"x", "y", "z", "w", "r", "a"})
      EXPECT_TRUE(isValid(h + "mov r0, t0\nmov oC0, r0\nmov oDepth, r0." + rep)) << ver << " ." << rep;
    EXPECT_TRUE(isValid(h + "mov r0, t0\nmov oC0, r0\nmov oDepth, r0"));
    const std::string msg = "mov to oDepth takes no source modifier and no swizzle but .x .y .z .w in " + ver;
    EXPECT_TRUE(hasError(h + "mov r0, t0\nmov oC0, r0\nmov oDepth, r0.xy", msg)) << ver;
    EXPECT_TRUE(hasError(h + "mov r0, t0\nmov oC0, r0\nmov oDepth, r0.yx", msg)) << ver;
    EXPECT_TRUE(hasError(h + "mov r0, t0\nmov oC0, r0\nmov oDepth, r0.yzxw", msg)) << ver;
    EXPECT_TRUE(hasError(h + "mov r0, t0\nmov oC0, r0\nmov oDepth, -r0.x", msg)) << ver;
    // oCn keeps its rule: no swizzle at all.
    EXPECT_TRUE(hasError(h + "mov r0, t0\nmov oC0, r0.x", "mov to oC0 takes no source swizzle or modifier in " + ver));
  }
  EXPECT_TRUE(isValid("ps_3_0\ndcl_texcoord0 v0\nmov r0, v0\nmov oC0, r0\nmov oDepth, r0.x"));
  EXPECT_TRUE(isValid("ps_3_0\ndcl_texcoord0 v0\nmov r0, v0\nmov oC0, r0\nmov oDepth, r0.w"));
  EXPECT_TRUE(isValid("ps_3_0\ndcl_texcoord0 v0\nmov r0, v0\nmov oC0, r0\nmov oDepth, r0"));
  EXPECT_TRUE(hasError("ps_3_0\ndcl_texcoord0 v0\nmov r0, v0\nmov oC0, r0\nmov oDepth, r0.xy",
                       "mov to oDepth takes no swizzle but .x .y .z .w in ps_3_0"));
  EXPECT_TRUE(hasError("ps_3_0\ndcl_texcoord0 v0\nmov r0, v0\nmov oC0, r0\nmov oDepth, r0.yx",
                       "mov to oDepth takes no swizzle but .x .y .z .w in ps_3_0"));
}

TEST(ValidatorPs20, Ps30OutputsInDynamicFlow) {
  std::string h = "ps_3_0\ndcl_texcoord0 v0\n";
  EXPECT_TRUE(hasError(h + "if_gt v0.x, c0.x\nmov oC0, v0\nendif",
                       "oC0 cannot be written inside dynamic flow control or predicated"));
  EXPECT_TRUE(isValid(h + "defb b0, true\nmov oC0, c0\nif b0\nmov oC0, v0\nendif"));
}

}  // namespace
}  // namespace refx::shader
