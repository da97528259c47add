// findSamplePassthrough: which programs are "output 0 = a texture sample, unchanged".
// Each case is lowered from assembly, so the shapes are the ones lowering really gives.
#include <gtest/gtest.h>

#include "refx/exec/abi.h"
#include "refx/exec/analysis.h"
#include "refx/exec/lower.h"
#include "refx/shader/assembler.h"
#include "refx/shader/bytecode.h"

namespace refx::exec {
namespace {

std::optional<SamplePassthrough> find(const char* source) {
  return findSamplePassthrough(lowerShader(shader::decode(shader::assembleTokens(source, "test"))).program);
}

TEST(SamplePassthrough, Ps11TexThenMov) {
  // ps.1.1 tex t0; mov r0, t0: r0 (output 0) = the sample of s0 at texture coordinate 0.
  const auto p = find("ps_1_1\ntex t0\nmov r0, t0\n");
  ASSERT_TRUE(p);
  EXPECT_EQ(p->sampler, 0);
  EXPECT_EQ(p->input, kPixelInTex0);
}

TEST(SamplePassthrough, OtherStageAndSaturate) {
  // t2 samples s2 at texture coordinate 2; _sat keeps [0, 1] as it is.
  const auto p = find("ps_1_1\ntex t2\nmov_sat r0, t2\n");
  ASSERT_TRUE(p);
  EXPECT_EQ(p->sampler, 2);
  EXPECT_EQ(p->input, kPixelInTex0 + 2);
}

TEST(SamplePassthrough, Ps20TexldThenMov) {
  const auto p = find("ps_2_0\ndcl t1\ndcl_2d s3\ntexld r0, t1, s3\nmov oC0, r0\n");
  ASSERT_TRUE(p);
  EXPECT_EQ(p->sampler, 3);
  EXPECT_EQ(p->input, kPixelInTex0 + 1);
}

TEST(SamplePassthrough, AnythingElseIsNot) {
  // A modifier, a shift, a swizzle, a partial mask, arithmetic, a second output, a
  // kill, the diffuse colour, a projected sample: each changes the value or adds an effect.
  EXPECT_FALSE(find("ps_1_1\ntex t0\nmov_x2 r0, t0\n"));
  EXPECT_FALSE(find("ps_1_1\ntex t0\nmov r0, t0_bx2\n"));
  EXPECT_FALSE(find("ps_1_1\ntex t0\nmov r0, -t0\n"));
  EXPECT_FALSE(find("ps_1_1\ntex t0\nmov r0, 1-t0\n"));
  EXPECT_FALSE(find("ps_1_1\ntex t0\nmul r0, t0, v0\n"));
  EXPECT_FALSE(find("ps_1_1\ntex t0\nmov r0.rgb, t0\n+mov r0.a, v0\n"));
  EXPECT_FALSE(find("ps_1_1\ntex t0\ntexkill t1\nmov r0, t0\n"));
  EXPECT_FALSE(find("ps_1_1\nmov r0, v0\n"));
  EXPECT_FALSE(find("ps_2_0\ndcl t0\ndcl_2d s0\ntexld r0, t0, s0\nmov oC0, r0.bgra\n"));
  EXPECT_FALSE(find("ps_2_0\ndcl t0\ndcl_2d s0\ntexldp r0, t0, s0\nmov oC0, r0\n"));
  EXPECT_FALSE(find("ps_2_0\ndcl t0\ndcl_2d s0\ntexld r0, t0, s0\nmov oC0, r0\nmov oC1, r0\n"));
  EXPECT_FALSE(find("ps_2_0\ndcl t0\ndcl_2d s0\ntexld r0, t0, s0\nmov oC0, r0\nmov oDepth, r0.x\n"));
}

}  // namespace
}  // namespace refx::exec
