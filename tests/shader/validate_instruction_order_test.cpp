// Instruction-order check: ps_1_x puts every def before all other
// instructions and (ps_1_1 – ps_1_3) every texture-address instruction before the
// arithmetic ones; ps_1_4 does so in each phase; SM2+ declares (dcl) before the first
// arithmetic, texture or flow-control instruction.
#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

TEST(ValidatorPs11, InstructionOrder) {
  EXPECT_TRUE(isValid("ps_1_1\ndef c0, 1, 0, 0, 1\ntex t0\nmul r0, t0, c0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ndef c0, 1, 0, 0, 1\nmul r0, t0, c0",
                       "def must come before all other instructions in ps_1_1"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmov r0, t0\ntex t1\nmul r0, r0, t1",
                       "tex follows an arithmetic instruction; ps_1_1 needs all texture instructions first"));
}

}  // namespace
}  // namespace refx::shader
