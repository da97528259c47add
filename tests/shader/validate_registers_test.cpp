// Register check: register files, counts (vs_1_1: 96 constants or the device's
// MaxVertexShaderConst, 12 temporaries; vs_2_x: the device's NumTemps), read-only and
// write-only files, relative addressing (vs_1_1: c[a0.x + n] after a0.x is written;
// ps_2_0: none).
#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

TEST(ValidatorVs, RegisterCounts) {
  EXPECT_TRUE(hasError("vs_1_1\nmov oPos, c96", "c96 is out of range: vs_1_1 has 96 constant registers (c0..c95)"));
  ValidationCaps dx81;
  dx81.maxVertexShaderConst = 192;
  EXPECT_TRUE(isValid("vs_1_1\nmov oPos, c96", dx81));
  EXPECT_TRUE(hasError("vs_1_1\nmov r12, v0\nmov oPos, r12", "r12 is out of range: vs_1_1 has 12 temporary registers (r0..r11)"));
  EXPECT_TRUE(hasError("vs_1_1\nmov oPos, v0\nmov oT8, v0", "oT8 is out of range: vs_1_1 has 8 texture coordinate output registers"));
  ValidationCaps temps;
  temps.vs2xTemps = 32;
  EXPECT_TRUE(isValid("vs_2_x\ndcl_position v0\nmov r20, v0\nmov oPos, r20", temps));
  EXPECT_TRUE(hasError("vs_2_x\ndcl_position v0\nmov r20, v0\nmov oPos, r20", "r20 is out of range: vs_2_x has 12 temporary registers"));
  EXPECT_TRUE(hasError("vs_1_1\nmov v0, c0\nmov oPos, v0", "v0 is read-only in vs_1_1"));
  EXPECT_TRUE(hasError("vs_1_1\nmov oPos, oD0", "oD0 cannot be read in vs_1_1"));
  EXPECT_TRUE(hasError(readRaw("vs_1_1\nmov oPos, v0\nmov oC0, v0"), "oC0 is not a vs_1_1 register"));
}

TEST(ValidatorVs, AddressRegister) {
  EXPECT_TRUE(isValid("vs_1_1\nmov a0.x, v1.x\nmov oPos, c[a0.x + 3]"));
  EXPECT_TRUE(hasError("vs_1_1\nmov a0.xy, v1\nmov oPos, c[a0.x + 3]", "vs_1_1 writes a0 only with mov a0.x"));
  EXPECT_TRUE(hasError("vs_1_1\nmova a0.x, v1\nmov oPos, v0", "mova is not a vs_1_1 instruction"));
  EXPECT_TRUE(hasError("vs_1_1\nmov oPos, c[a0.x + 3]", "a0.x is used as an index before it is written"));
  EXPECT_TRUE(hasError(readRaw("vs_1_1\nmov a0.x, v1.x\nmov oPos, c[a0.y + 3]"), "vs_1_1 indexes constants only with a0.x"));
  EXPECT_TRUE(isValid("vs_2_0\ndcl_position v0\nmova a0.y, v0.x\nmov oPos, c[a0.y + 3]"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\nmov a0.x, v0.x\nmov oPos, c[a0.x]", "vs_2_0 writes a0 only with mova"));
  EXPECT_TRUE(hasError("vs_1_1\nmov oPos, a0", "a0 cannot be read in vs_1_1"));
  EXPECT_TRUE(hasError(readRaw("ps_2_0\ndcl t0\nmov oC0, c[a0.x + 1]"), "relative addressing is not available for constant registers in ps_2_0"));
}

}  // namespace
}  // namespace refx::shader
