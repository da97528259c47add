// Instruction-form check: matrix macros take a plain matrix operand within the
// register file and write .xyz (m3x3, m4x3) or .xy (m3x2); sincos, crs, nrm, pow and
// sgn write temporaries with their documented masks and distinct scratch operands;
// frc in vs_1_1 writes .y or .xy.
#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

TEST(ValidatorVs, InstructionForms) {
  EXPECT_TRUE(hasError("vs_1_1\nfrc r0.x, v0\nmov oPos, v0", "frc in vs_1_1 writes .y or .xy"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\nm4x4 oPos, v0, c0.yxzw", "m4x4 takes no swizzle or modifier on the matrix operand"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\nm3x3 r0.xyzw, v0, c0\nmov oPos, r0", "m3x3 writes .xyz"));
  // Without a mask (as the DirectX 8 shaders write it) m3x3 writes the .xyz it computes.
  EXPECT_TRUE(isValid("vs_1_1\nm3x3 r0, v0, c0\nmov r0.w, v0.w\nmov oPos, r0"));
  EXPECT_TRUE(hasError("vs_1_1\nm4x4 oPos, v0, c94", "m4x4 reads c94..c97 but vs_1_1 has 96 constant registers"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\nsincos r0.xy, v0.x, c0, c0\nmov oPos, v0",
                       "sincos in vs_2_0 takes two different constant registers"));
  EXPECT_TRUE(isValid("vs_2_0\ndcl_position v0\nsincos r0.xy, v0.x, c0, c1\nmov oPos, v0"));
  EXPECT_TRUE(hasError("vs_3_0\ndcl_position v0\ndcl_position o0\nsincos r0.xyz, v0.x\nmov o0, v0", "sincos writes .x, .y or .xy"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\ncrs r0.xyzw, v0, v0\nmov oPos, v0", "crs writes a subset of .xyz"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\nmov r0, v0\nnrm r0, r0\nmov oPos, r0", "nrm cannot write the register it reads"));
}

}  // namespace
}  // namespace refx::shader
