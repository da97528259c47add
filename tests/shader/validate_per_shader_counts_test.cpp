// Per-shader count check: some instructions are limited per shader on their own, beyond
// the slot counts: ps_1_2 – ps_1_3 run cmp at most 3 times and dp4 at most 4 times
// (each takes 2 of the 8 arithmetic slots there), ps_1_4 runs bem once.
#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

TEST(ValidatorPs11, CmpAndDp4Limits) {
  // ps_1_2: cmp 2 slots, at most 3; dp4 2 slots, at most 4.
  std::string three = "ps_1_2\ndef c0, 1, 1, 1, 1\ntex t0\ncmp r0, t0, c0, -c0\ncmp r1, r0, c0, -c0\ncmp r0, r1, c0, -c0\n";
  EXPECT_TRUE(isValid(three));
  EXPECT_TRUE(hasError(three + "cmp r1, r0, c0, -c0\nmov r0, r1", "ps_1_2 allows 3 cmp instructions per shader"));
  EXPECT_TRUE(hasError(three + "mov r1, r0\nmov r0, r1\nmov r1, r0", "ps_1_2 allows 8 arithmetic instructions, this shader has 9"));
}

TEST(ValidatePerShaderCounts, Dp4AndBem) {
  // Four dp4 in ps_1_3 take 8 slots, the whole arithmetic budget, and are allowed.
  std::string four = "ps_1_3\ntex t0\ndp4 r0, t0, t0\ndp4 r0, t0, r0\ndp4 r0, t0, r0\ndp4 r0, t0, r0\n";
  EXPECT_TRUE(isValid(four));
  EXPECT_TRUE(hasError(four + "dp4 r0, t0, r0\n", "ps_1_3 allows 4 dp4 instructions per shader, this shader has more"));
  // bem once per ps_1_4 shader, in phase 1.
  const std::string bem = "ps_1_4\ntexld r1, t1\ntexcrd r2.rgb, t2\nbem r2.rg, r2, r1\n";
  EXPECT_TRUE(isValid(bem + "phase\ntexld r2, r2\nmov r0, r2"));
  EXPECT_TRUE(hasError(bem + "bem r3.rg, r2, r1\nphase\ntexld r2, r2\nmov r0, r2",
                       "ps_1_4 allows 1 bem instruction per shader"));
}

}  // namespace
}  // namespace refx::shader
