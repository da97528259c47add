// Phase check (ps_1_4): one phase marker; texture instructions first in each
// phase; r# read as texld coordinates in phase 2 were written in phase 1; v# arrive in
// phase 2; the alpha of temporaries is lost at the marker.
#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

TEST(ValidatorPs14, Phases) {
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\nmov r1, r0\ntexld r2, t2\nmov r0, r2",
                       "texld follows an arithmetic instruction; in each ps_1_4 phase the texture instructions come first"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\nphase\ntexld r1, t1\nphase\nmov r0, r1", "ps_1_4 allows one phase instruction"));
  // texld from r#: phase 2 only, coordinates written in phase 1.
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\ntexld r1, r0\nmov r0, r1",
                       "texld reads r0, but r registers are texld coordinates only in phase 2 (after the phase marker)"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\nphase\ntexld r1, r2\nmov r0, r1",
                       "r2.xyz used as texld coordinates must be written in phase 1"));
  EXPECT_TRUE(hasError("ps_1_4\ntexcrd r0.rgb, t0\nphase\ntexcrd r1.rgb, r0\nmov r0, r1", "texcrd reads only t registers"));
  // Color inputs arrive in phase 2.
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\nmul r0, r0, v0\nphase\ntexld r1, r0\nmov r0, r1",
                       "v0 cannot be read in phase 1 of ps_1_4"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r0, t0\nmov r0, r0\nphase\ntexld r1, r0\nmul r0, r1, v0"));
  // The alpha of temporaries is lost at the phase marker.
  EXPECT_TRUE(hasError("ps_1_4\ntexld r1, t0\nphase\nmov r0, r1.a",
                       "r1.a is read in phase 2 but the alpha of temporaries is lost at the phase marker"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r1, t0\nphase\nmov r0, r1.b"));
}

}  // namespace
}  // namespace refx::shader
