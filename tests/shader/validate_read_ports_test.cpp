// Read-port check: one instruction reads at most N different registers of a
// file (ps_1_1: 2 constants and 2 texture registers; ps_1_2 – ps_1_3: 3 texture
// registers; vs_2_0: 2 constants; vs_1_1 constants: no limit). The file also keeps
// the SM2 replicate-swizzle rules of scalar instructions, read in the same tables.
#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

TEST(ValidatorPs11, ReadPorts) {
  EXPECT_TRUE(isValid("ps_1_1\nmad r0, c0, c1, v0"));
  EXPECT_TRUE(hasError("ps_1_1\nmad r0, c0, c1, c2",
                       "ps_1_1 reads at most 2 different constant registers in one instruction, mad reads 3 (c0, c1, c2)"));
  std::string threeT = "tex t0\ntex t1\ntex t2\nmad r0, t0, t1, t2";
  EXPECT_TRUE(hasError("ps_1_1\n" + threeT, "ps_1_1 reads at most 2 different texture registers in one instruction, mad reads 3"));
  EXPECT_TRUE(isValid("ps_1_2\n" + threeT));
}

TEST(ValidatorVs, ReadPortsAndSwizzles) {
  EXPECT_TRUE(isValid("vs_1_1\nmad oPos, c0, c1, c2"));  // constants: no port limit in vs_1_1 (reference table)
  EXPECT_TRUE(hasError("vs_2_0\nmad oPos, c0, c1, c2",
                       "vs_2_0 reads at most 2 different constant registers in one instruction, mad reads 3"));
  EXPECT_TRUE(isValid("vs_1_1\nrcp r0, v0\nmov oPos, r0"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\nrcp r0, v0\nmov oPos, r0",
                       "rcp needs a replicate swizzle (.x, .y, .z or .w) on its source"));
  EXPECT_TRUE(isValid("vs_2_0\ndcl_position v0\nrcp r0, v0.w\nmov oPos, r0"));
  EXPECT_TRUE(hasError("vs_2_0\ndcl_position v0\npow r0, v0.x, v0\nmov oPos, r0", "pow needs a replicate swizzle (.x, .y, .z or .w) on its second source"));
}

}  // namespace
}  // namespace refx::shader
