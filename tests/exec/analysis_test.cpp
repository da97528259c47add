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

std::optional<TexturePrologue> prologue(const char* source) {
  return findTexturePrologue(lowerShader(shader::decode(shader::assembleTokens(source, "test"))).program);
}

TEST(TexturePrologue, Ps11LookupsThenArithmetic) {
  // RacorX6's shader: t0 samples s0 at texture coordinate 0, t1 samples s1 at 1; the
  // arithmetic after them is the rest.
  const char* src = "ps_1_1\ntex t0\ntex t1\ndp3 r1, t1_bx2, v0_bx2\nmul r0, t0, r1\n";
  const Program whole = lowerShader(shader::decode(shader::assembleTokens(src, "test"))).program;
  const auto p = prologue(src);
  ASSERT_TRUE(p);
  ASSERT_EQ(p->lookups.size(), 2u);
  EXPECT_EQ(p->lookups[0].sampler, 0);
  EXPECT_EQ(p->lookups[0].input, kPixelInTex0);
  EXPECT_EQ(p->lookups[1].sampler, 1);
  EXPECT_EQ(p->lookups[1].input, kPixelInTex0 + 1);
  EXPECT_NE(p->lookups[0].file, RegFile::Input);
  // The rest: the whole program without the two lookups, in its order (ps.1.1's
  // lowering saturates v0 first, which the lookups move ahead of).
  std::vector<Op> others;
  for (const Instr& in : whole.code)
    if (in.op != Op::Tex) others.push_back(in.op);
  ASSERT_EQ(p->rest.code.size(), whole.code.size() - 2);
  ASSERT_EQ(others.size(), p->rest.code.size());
  for (size_t i = 0; i < others.size(); ++i) EXPECT_EQ(p->rest.code[i].op, others[i]);
  EXPECT_EQ(p->rest.tempCount, whole.tempCount);
  EXPECT_EQ(p->rest.immediates.size(), whole.immediates.size());
}

TEST(TexturePrologue, Ps20LookupsStopAtTheFirstOtherInstruction) {
  // texld r0, t0, s0 and texld r1, t1, s2 read inputs; the third lookup reads r0 (a
  // dependent read) and ends the prologue.
  const auto p = prologue("ps_2_0\ndcl t0\ndcl t1\ndcl_2d s0\ndcl_2d s1\ndcl_2d s2\n"
                          "texld r0, t0, s0\ntexld r1, t1, s2\ntexld r2, r0, s1\nadd r0, r1, r2\nmov oC0, r0\n");
  ASSERT_TRUE(p);
  ASSERT_EQ(p->lookups.size(), 2u);
  EXPECT_EQ(p->lookups[1].sampler, 2);
  EXPECT_EQ(p->lookups[1].input, kPixelInTex0 + 1);
  EXPECT_EQ(p->rest.code.front().op, Op::Tex);
}

TEST(TexturePrologue, ALookupStaysBehindWhatTouchesItsResult) {
  // r0 written before the lookup into r0: the lookup stays; the one into r1 moves.
  auto p = prologue("ps_2_0\ndcl t0\ndcl_2d s0\nmov r0, c0\ntexld r0, t0, s0\ntexld r1, t0, s0\n"
                    "add r0, r0, r1\nmov oC0, r0\n");
  ASSERT_TRUE(p);
  ASSERT_EQ(p->lookups.size(), 1u);
  EXPECT_EQ(p->lookups[0].index, 1);
  // r0 read before the lookup into r0: it stays.
  p = prologue("ps_2_0\ndcl t0\ndcl_2d s0\nadd r1, r0, c0\ntexld r0, t0, s0\nadd r0, r0, r1\nmov oC0, r0\n");
  EXPECT_FALSE(p);
  // Nothing moves past a kill.
  p = prologue("ps_2_0\ndcl t0\ndcl_2d s0\ntexkill t0\ntexld r0, t0, s0\nmov oC0, r0\n");
  EXPECT_FALSE(p);
}

TEST(TexturePrologue, NoneWithoutALeadingPlainLookup) {
  EXPECT_FALSE(prologue("ps_1_1\nmov r0, v0\n"));
  // texld_sat changes the result; texldp divides the coordinates; a swizzle changes them.
  EXPECT_FALSE(prologue("ps_2_0\ndcl t0\ndcl_2d s0\ntexld_sat r0, t0, s0\nmov oC0, r0\n"));
  EXPECT_FALSE(prologue("ps_2_0\ndcl t0\ndcl_2d s0\ntexldp r0, t0, s0\nmov oC0, r0\n"));
  EXPECT_FALSE(prologue("ps_2_0\ndcl t0\ndcl_2d s0\ntexld r0, t0.yxzw, s0\nmov oC0, r0\n"));
  // Flow control anywhere: none.
  EXPECT_FALSE(prologue("ps_3_0\ndcl_texcoord0 v0\ndcl_2d s0\ntexld r0, v0, s0\nif_gt r0.x, r0.y\n"
                        "mov r0, r0.y\nendif\nmov oC0, r0\n"));
}

// Which components of each lookup's result the rest reads, by D3D's definitions of the
// instructions: dp3 reads .xyz of its sources, mul/mad/add the written components
// through the source's swizzle.
TEST(TexturePrologue, ChannelsTheRestReads) {
  // RacorX6: t0 goes whole into r0 (mul r0, t0, r1: rgba); t1 only into dp3: rgb.
  auto p = prologue("ps_1_1\ntex t0\ntex t1\ndp3 r1, t1_bx2, v0_bx2\nmul r0, t0, r1\n");
  ASSERT_TRUE(p);
  ASSERT_EQ(p->lookups.size(), 2u);
  EXPECT_EQ(p->lookups[0].channels, 0xF);
  EXPECT_EQ(p->lookups[1].channels, 0x7);
  // mul r0.xy, r1.zw: the write mask xy through the swizzle zwzw reads z and w only;
  // r2.y's replicate reads y; the r2 written whole after that is another value.
  p = prologue("ps_2_0\ndcl t0\ndcl_2d s0\ntexld r1, t0, s0\ntexld r2, t0, s0\n"
               "mul r0.xy, r1.zw, c0\nmov r0.zw, r2.y\nmov r2, c1\nadd r0, r0, r2\nmov oC0, r0\n");
  ASSERT_TRUE(p);
  ASSERT_EQ(p->lookups.size(), 2u);
  EXPECT_EQ(p->lookups[0].channels, 0xC);
  EXPECT_EQ(p->lookups[1].channels, 0x2);
  // r0.x replicated into all of oC0: x alone.
  p = prologue("ps_2_0\ndcl t0\ndcl_2d s0\ntexld r0, t0, s0\nmov oC0, r0.x\n");
  ASSERT_TRUE(p);
  EXPECT_EQ(p->lookups[0].channels, 0x1);
}

// IR built by hand (the lowering swizzles dp3's sources to .xyzx, which hides its own
// reads): dp3 reads x, y, z; dp4 and the ops read through their swizzles; a register
// written whole stops the scan; relative addressing and flow control read everything.
TEST(ChannelsRead, FromTheOpsReads) {
  Program p;
  p.tempCount = 4;
  p.emit(Op::Dp3, dst(RegFile::Temp, 0), reg(RegFile::Temp, 1), reg(RegFile::Const, 0));
  EXPECT_EQ(channelsRead(p, 1), 0x7);
  p.emit(Op::Mul, dst(RegFile::Temp, 0, 0x8), reg(RegFile::Temp, 2, swz(1, 1, 1, 0)), reg(RegFile::Const, 0));
  EXPECT_EQ(channelsRead(p, 2), 0x1);  // the mask w reads the swizzle's fourth: x
  p.emit(Op::Mov, dst(RegFile::Temp, 1), reg(RegFile::Const, 1));
  p.emit(Op::Dp4, dst(RegFile::Temp, 0), reg(RegFile::Temp, 1), reg(RegFile::Const, 0));
  EXPECT_EQ(channelsRead(p, 1), 0x7);  // the dp4 reads the mov's value
  EXPECT_EQ(channelsRead(p, 3), 0x0);
  Program flow = p;
  flow.flowControl = true;
  EXPECT_EQ(channelsRead(flow, 3), 0xF);
}

TEST(ChannelsRead, WholeWhereNotPlain) {
  // dp4 reads all four; a result nobody reads has none.
  Program p = lowerShader(shader::decode(shader::assembleTokens(
                              "ps_2_0\ndcl t0\ndcl_2d s0\ntexld r1, t0, s0\ndp4 r0, r1, c0\nmov oC0, r0\n", "test")))
                  .program;
  const auto p1 = findTexturePrologue(p);
  ASSERT_TRUE(p1);
  EXPECT_EQ(p1->lookups[0].channels, 0xF);
  EXPECT_EQ(channelsRead(p1->rest, 7), 0x0);
}

}  // namespace
}  // namespace refx::exec
