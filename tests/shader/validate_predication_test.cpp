// Predication check: (p0) exists in SM3 and in vs_2_x / ps_2_x with caps, and
// p0 is written by setp before it is read.
#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

TEST(ValidatorFlow, Predication) {
  std::string v3 = "vs_3_0\ndcl_position v0\ndcl_position o0\nmov o0, v0\n";
  EXPECT_TRUE(isValid(v3 + "setp_gt p0, v0, c0\n(p0) add r0, v0, c0\n(!p0.x) mov r0, c1"));
  EXPECT_TRUE(hasError(v3 + "(p0) add r0, v0, c0", "p0 is read before it is written (setp)"));
  EXPECT_TRUE(hasError(std::string(kVs20Head) + "(p0) add r0, v0, c0", "predication (p0) is not available in vs_2_0"));
  EXPECT_TRUE(hasError(v3 + "mov p0, c0", "p0 is written only by setp"));
}

}  // namespace
}  // namespace refx::shader
