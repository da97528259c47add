// Sampling check: texld samples through a declared s register; in ps_2_0 it
// writes the full mask from t# or r# without swizzle or modifier, and dependent reads
// chain at most 4 levels (ps_2_x: unless D3DPS20CAPS_NODEPENDENTREADLIMIT).
#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

TEST(ValidatorPs20, Texld) {
  std::string h = "ps_2_0\ndcl t0\ndcl_2d s0\n";
  EXPECT_TRUE(isValid(h + "texld r0, t0, s0\nmov oC0, r0"));
  EXPECT_TRUE(hasError(h + "texld r0, t0.yxzw, s0\nmov oC0, r0", "texld coordinates take no swizzle or modifier in ps_2_0"));
  EXPECT_TRUE(hasError(h + "texld r0.xy, t0, s0\nmov oC0, r0", "texld in ps_2_0 writes the full .xyzw mask"));
  EXPECT_TRUE(hasError(h + "texld r0, t0, c0\nmov oC0, r0", "texld samples through an s register"));
  EXPECT_TRUE(hasError(h + "texld_sat r0, t0, s0\nmov oC0, r0", "texld cannot take _sat"));
  // Dependent reads: four levels allowed.
  std::string chain = h + "texld r0, t0, s0\ntexld r1, r0, s0\ntexld r2, r1, s0\ntexld r3, r2, s0\n";
  EXPECT_TRUE(isValid(chain + "mov oC0, r3"));
  EXPECT_TRUE(hasError(chain + "texld r4, r3, s0\nmov oC0, r4",
                       "ps_2_0 allows 4 levels of dependent texture reads, this texld is level 5"));
  ValidationCaps noLimit;
  noLimit.ps2xNoDependentReadLimit = true;
  std::string chainX = "ps_2_x\ndcl t0\ndcl_2d s0\ntexld r0, t0, s0\ntexld r1, r0, s0\ntexld r2, r1, s0\n"
                       "texld r3, r2, s0\ntexld r4, r3, s0\nmov oC0, r4";
  EXPECT_TRUE(isValid(chainX, noLimit));
  EXPECT_TRUE(hasError(chainX, "ps_2_x allows 4 levels of dependent texture reads"));
}

}  // namespace
}  // namespace refx::shader
