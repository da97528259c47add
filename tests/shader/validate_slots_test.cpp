// Slot check: instruction slots as the D3D9 docs count them (macros expanded,
// a co-issued pair once, predication one more): ps_1_1 – ps_1_3 allow 4 texture and 8
// arithmetic instructions, ps_1_4 6 and 8 per phase, vs_1_1 128 slots, ps_2_0 32
// texture and 64 arithmetic, ps_2_x NumInstructionSlots (96 – 512).
#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

TEST(ValidatorPs11, ArithmeticSlots) {
  std::string eight = "ps_1_1\ntex t0\n";
  for (int i = 0; i < 8; ++i) eight += "mul r0, t0, t0\n";
  EXPECT_TRUE(isValid(eight));
  EXPECT_TRUE(hasError(eight + "mul r0, r0, t0\n", "ps_1_1 allows 8 arithmetic instructions, this shader has 9"));
  // A co-issued pair takes one slot: 7 + 1 pair = 8.
  std::string paired = "ps_1_1\ntex t0\n";
  for (int i = 0; i < 7; ++i) paired += "mul r0, t0, t0\n";
  EXPECT_TRUE(isValid(paired + "mul r0.rgb, r0, t0\n+mov r0.a, t0\n"));
}

TEST(ValidatorPs11, TextureSlots) {
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\ntex t1\ntex t2\ntex t3\nmov r0, t3"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntex t1\ntex t2\ntex t3\ntex t4\nmov r0, t3",
                       "ps_1_1 allows 4 texture instructions, this shader has 5"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t4\nmov r0, t4", "t4 is out of range: ps_1_1 has 4 texture registers (t0..t3)"));
}

TEST(ValidatorPs14, SlotsPerPhase) {
  std::string p1 = "ps_1_4\ntexld r0, t0\n";
  for (int i = 0; i < 8; ++i) p1 += "mul r0, r0, r0\n";
  std::string p2 = "phase\ntexld r1, t1\n";
  for (int i = 0; i < 8; ++i) p2 += "mul r0, r1, r1\n";
  EXPECT_TRUE(isValid(p1 + p2));  // 16 arithmetic instructions in two phases
  EXPECT_TRUE(hasError(p1 + p2 + "mul r0, r0, r1\n", "ps_1_4 allows 8 arithmetic instructions per phase, phase 2 has 9"));
  EXPECT_TRUE(hasError(p1 + "mul r0, r0, r0\n" + p2, "ps_1_4 allows 8 arithmetic instructions per phase, phase 1 has 9"));
  std::string tex = "ps_1_4\ntexld r0, t0\ntexld r1, t1\ntexld r2, t2\ntexld r3, t3\ntexld r4, t4\ntexld r5, t5\n";
  EXPECT_TRUE(isValid(tex + "mov r0, r5"));
  EXPECT_TRUE(hasError(tex + "texkill t0\nmov r0, r5", "ps_1_4 allows 6 texture instructions per phase, phase 2 has 7"));
  EXPECT_TRUE(hasError("ps_1_4\ntexld r0, t0\ntexld r0, t1\nmov r0, r0",
                       "r0 is already the destination of a texture instruction in this phase"));
}

TEST(ValidatorVs, SlotLimitsAndMacroCosts) {
  std::string body = "vs_1_1\nmov oPos, v0\n";
  for (int i = 0; i < 31; ++i) body += "m4x4 r0, v0, c0\n";  // 1 + 31*4 = 125
  EXPECT_TRUE(isValid(body + "frc r1.xy, v0\n"));               // + 3 = 128
  EXPECT_TRUE(hasError(body + "frc r1.xy, v0\nmov r2, v0\n", "vs_1_1 allows 128 instruction slots, this shader uses 129"));
  std::string exps = "vs_1_1\nmov oPos, v0\n";
  for (int i = 0; i < 13; ++i) exps += "exp r0, v0.x\n";  // exp is a 10-slot macro in vs_1_1
  EXPECT_TRUE(hasError(exps, "vs_1_1 allows 128 instruction slots, this shader uses 131"));
  std::string vs20 = "vs_2_0\ndcl_position v0\nmov oPos, v0\n";
  for (int i = 0; i < 13; ++i) vs20 += "exp r0, v0.x\n";  // 1 slot in vs_2_0
  EXPECT_TRUE(isValid(vs20));
}

TEST(ValidatorPs20, Slots) {
  std::string s = "ps_2_0\ndcl t0\ndcl_2d s0\n";
  for (int i = 0; i < 32; ++i) s += "texld r0, t0, s0\n";
  for (int i = 0; i < 63; ++i) s += "add r1, r0, c0\n";
  s += "mov oC0, r1\n";
  EXPECT_TRUE(isValid(s));  // 32 texture + 64 arithmetic
  EXPECT_TRUE(hasError(s + "add r1, r0, c0\n", "ps_2_0 allows 64 arithmetic instruction slots, this shader uses 65"));
  std::string tex33 = "ps_2_0\ndcl t0\ndcl_2d s0\n";
  for (int i = 0; i < 33; ++i) tex33 += "texld r0, t0, s0\n";
  EXPECT_TRUE(hasError(tex33 + "mov oC0, r0\n", "ps_2_0 allows 32 texture instruction slots, this shader uses 33"));
  std::string x = "ps_2_x\ndcl t0\n";
  for (int i = 0; i < 96; ++i) x += "add r0, t0, c0\n";
  EXPECT_TRUE(hasError(x + "mov oC0, r0\n", "ps_2_x allows 96 instruction slots, this shader uses 97"));
  ValidationCaps big;
  big.ps2xInstructionSlots = 512;
  EXPECT_TRUE(isValid(x + "mov oC0, r0\n", big));
}

TEST(CountSlots, MacrosAndVersions) {
  auto slots = [](const std::string& text) { return countSlots(read(text)); };
  // vs_1_1: m4x4 = 4, exp = 10, frc = 3, lit = 1; def/dcl free.
  SlotCount a = slots("vs_1_1\ndef c0, 1, 1, 1, 1\nm4x4 oPos, v0, c0\nexp r0, v0.x\nfrc r1.xy, v0\nlit r2, v0");
  EXPECT_EQ(a.arithmetic, 4 + 10 + 3 + 1);
  EXPECT_EQ(a.texture, 0);
  // vs_2_0: exp = 1, frc = 1, lit = 3, sincos = 8, nrm = 3, m3x3 = 3, rep = 3 + endrep = 2.
  SlotCount b = slots("vs_2_0\ndcl_position v0\nexp r0, v0.x\nfrc r1, v0\nlit r2, v0\nsincos r3.xy, v0.x, c0, c1\n"
                      "nrm r4, v0\nm3x3 r5.xyz, v0, c0\nrep i0\nendrep");
  EXPECT_EQ(b.arithmetic, 1 + 1 + 3 + 8 + 3 + 3);
  EXPECT_EQ(b.flowControl, 3 + 2);
  // ps_1_1: 4 texture; co-issued pair = 1 arithmetic slot (RacorX10 SpecDot3).
  SlotCount c = slots("ps.1.1\ntex t0\ntex t1\ntexm3x2pad t2, t1_bx2\ntexm3x2tex t3, t1_bx2\n"
                      "mul r1.rgb, t3, t0\n+mul r1.a, t0.a, t3.a\nadd r0, r1.a, r1");
  EXPECT_EQ(c.texture, 4);
  EXPECT_EQ(c.arithmetic, 2);
  // ps_1_2: cmp and dp4 take 2 slots each; phase and def are free in ps_1_4.
  EXPECT_EQ(slots("ps_1_2\ntex t0\ncmp r0, t0, c0, c1\ndp4 r1, t0, t0").arithmetic, 4);
  SlotCount d = slots("ps_1_4\ndef c0, 0, 0, 0, 0\ntexld r0, t0\nmov r1, r0\nphase\ntexld r2, r1\nmul r0, r2, r0");
  EXPECT_EQ(d.texture, 2);
  EXPECT_EQ(d.arithmetic, 2);
  // ps_3_0 texture costs: texld 1 (4 on a cube), texldp 3, texldb 6, texldl 2, texkill 2.
  SlotCount e = slots("ps_3_0\ndcl_2d s0\ndcl_cube s1\ntexld r0, v0, s0\ntexld r0, v0, s1\ntexldp r0, v0, s0\n"
                      "texldb r0, v0, s0\ntexldl r0, v0, s0\ntexkill r0");
  EXPECT_EQ(e.texture, 1 + 4 + 3 + 6 + 2 + 2);
  // ps_2_0: texld = 1 whatever the sampler; predication adds a slot (vs_3_0).
  EXPECT_EQ(slots("ps_2_0\ndcl_cube s0\ntexld r0, t0, s0\ntexldp r0, t0, s0").texture, 2);
  EXPECT_EQ(slots("vs_3_0\nsetp_gt p0, v0, c0\n(p0) add r0, v0, c0").arithmetic, 1 + 2);
  EXPECT_EQ(slots("vs_3_0\nsetp_gt p0, v0, c0\n(p0) add r0, v0, c0").total(), 3);
}

}  // namespace
}  // namespace refx::shader
