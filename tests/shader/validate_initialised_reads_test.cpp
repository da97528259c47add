// Initialised-read check: temporaries (ps_1_1 – ps_1_3: also t registers)
// are read only in components written before; ps_1_x must write r0.
#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

TEST(ValidatorPs11, UninitialisedReads) {
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmov r0, r1", "r1 is read before it is written"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmov r1.rgb, t0\nmov r0, r1", "r1.w is read before it is written"));
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\nmov r1.rgb, t0\nmov r0.rgb, r1\n+mov r0.a, t0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmul r0, t0, t3", "t3 is read before it is written (no texture instruction writes it)"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmov r1, t0", "ps_1_1 never writes r0, the pixel color"));
}

}  // namespace
}  // namespace refx::shader
