// ps_1_1 – ps_1_3 instruction-form check: cnd compares r0.a with 0.5 there, so its
// first source is r0.a and nothing else; cmp (ps_1_2, ps_1_3) never writes a register
// it reads. ps_1_4 lifts both rules (cnd takes any register, per component).
#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

TEST(ValidatorPs11, Cnd) {
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\ntex t1\nmov r0, t0\ncnd r0, r0.a, t0, t1"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntex t1\nmov r1, t0\ncnd r0, r1.a, t0, t1", "cnd in ps_1_1 takes r0.a as its first source"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r0, t0\ntexld r1, t1\ncnd r0, r1, r0, r1"));
}

TEST(ValidatePs11Forms, CmpWritesNoSourceRegister) {
  EXPECT_TRUE(isValid("ps_1_2\ntex t0\ntex t1\ncmp r0, t0, t1, t0"));
  EXPECT_TRUE(hasError("ps_1_2\ntex t0\ncmp r0, t0, r0, t0", "cmp in ps_1_2 cannot write a register it reads (r0)"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r0, t0\ncmp r0, r0, r0, r0"));
}

}  // namespace
}  // namespace refx::shader
