// ps_1_4 texture-instruction check: texld/texcrd write r# (once per phase), read
// t# with one .xyz or .xyw selector per register, _dz on r# at most twice, _dw on t#;
// t# is read only by texld/texcrd; texdepth works on r5 in phase 2; bem in phase 1
// writes .rg.
#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

TEST(ValidatorPs14, TextureRegisters) {
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\nadd r0, r0, t1", "t1 can be read only by texld and texcrd in ps_1_4"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\nmov t0, r0\nmov r0, r0", "t0 is read-only in ps_1_4"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld t0, t0\nmov r0, r0", "texld writes an r register in ps_1_4"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0.xyz\ntexld r1, t0.xyw\nadd r0, r0, r1",
                       "t0 is read with both .xyz and .xyw; every read of one t register uses the same selector"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r0, t0.xyw\ntexcrd r1.rg, t0_dw.xyw\nadd r0.rg, r0, r1"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0.yxz\nmov r0, r0", "texld sources take the .xyz or .xyw selector only"));
}

TEST(ValidatorPs14, DivideModifiers) {
  std::string ok = "ps_1_4\ntexcrd r0.rgb, t0\ntexcrd r1.rgb, t1\ntexcrd r2.rgb, t2\nphase\n";
  EXPECT_TRUE(isValid(ok + "texld r3, r0_dz\ntexld r4, r1_dz.xyz\nadd r0, r3, r4"));
  EXPECT_TRUE(hasError(ok + "texld r3, r0_dz\ntexld r4, r1_dz\ntexld r5, r2_dz\nadd r0, r3, r4",
                       "ps_1_4 allows _dz at most twice per shader"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0_dz\nmov r0, r0", "_dz applies to r registers; t registers take _dw"));
  EXPECT_TRUE(hasError(ok + "texld r3, r0_dw\nmov r0, r3", "_dw applies to t registers; r registers take _dz"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\nmov r0, r0_dz", "_dz/_dw apply only to texld and texcrd sources"));
  EXPECT_TRUE(hasError("ps_1_4\ntexcrd r0.rgb, t0_dw.xyw\nmov r0, r0", "texcrd with _dw writes .rg only"));
}

TEST(ValidatorPs14, TexdepthAndBem) {
  EXPECT_TRUE(isValid("ps_1_4\ntexcrd r5.rgb, t0\nphase\ntexdepth r5\nmov r0, c0"));
  // texkill reads its operand (encoded as a destination): read-only t# are fine.
  EXPECT_TRUE(isValid("ps_1_4\ntexld r0, t0\ntexkill t1\nmov r0, r0"));
  EXPECT_TRUE(isValid("ps_2_0\ndcl t1\ntexkill t1\nmov oC0, t1"));
  EXPECT_TRUE(hasError("ps_2_0\ndcl t1\ntexkill r0\nmov oC0, t1", "r0 is read before it is written"));
  EXPECT_TRUE(hasError("ps_1_4\ntexcrd r4.rgb, t0\nphase\ntexdepth r4\nmov r0, c0", "texdepth works only on r5"));
  // A ps_1_4 shader without `phase` is all phase 2 (registers-and-limits.md), so
  // texdepth is allowed there; in phase 1 of a two-phase shader it is not.
  EXPECT_TRUE(isValid("ps_1_4\ntexcrd r5.rgb, t0\ntexdepth r5\nmov r0, c0"));
  EXPECT_TRUE(hasError("ps_1_4\ntexcrd r5.rgb, t0\ntexdepth r5\nphase\nmov r0, c0",
                       "texdepth is available only in phase 2"));
  EXPECT_TRUE(isValid("ps_1_4\ntexld r1, t1\ntexcrd r2.rgb, t2\nbem r2.rg, r2, r1\nphase\ntexld r2, r2\nmov r0, r2"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\ntexld r1, t1\nbem r2.rg, r0, r1\nmov r0, r2",
                       "bem is allowed only in phase 1 of ps_1_4"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\ntexld r1, t1\nbem r2, r0, r1\nphase\nmov r0, r2", "bem writes .rg only"));
}

}  // namespace
}  // namespace refx::shader
