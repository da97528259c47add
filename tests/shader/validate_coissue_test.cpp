// Co-issue check: `+` pairs exist only in ps_1_1 – ps_1_4; a pair is two
// arithmetic instructions, one writing .rgb (ps_1_4: a subset of it) and one .a; some
// instructions cannot pair (dp4), some only as the color half (dp3 in ps_1_4).
#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

TEST(ValidatorPs11, Coissue) {
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\nmov r0.rgb, t0\n+mov r0.rgb, t0",
                       "a co-issued pair writes .rgb in one instruction and .a in the other; these write .xyz and .xyz"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\n+mov r0.a, t0\nmov r0.rgb, t0",
                       "co-issued mov (+) must follow an arithmetic instruction it pairs with"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\n+tex t1\nmov r0, t0", "tex cannot be co-issued (+); only arithmetic instructions pair"));
  EXPECT_TRUE(hasError("ps_1_2\ntex t0\ndp4 r0.rgb, t0, t0\n+mov r0.a, t0", "dp4 cannot be co-issued"));
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\ndp3 r0.rgb, t0, t0\n+mov r0.a, t0"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\nmov r1.rgb, r0\n+dp3 r1.a, r0, r0\nmov r0, r1",
                       "dp3 can be co-issued only as the color (.rgb) half"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r0, t0\nmov r0.rg, r0\n+mov r0.a, r0"));
  EXPECT_TRUE(hasError(readRaw("vs_1_1\nmov oPos, v0\n+mov oD0, v0"), "co-issue (+) exists only in ps_1_1 - ps_1_4, not in vs_1_1"));
}

}  // namespace
}  // namespace refx::shader
