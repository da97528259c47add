// Flow-control check: blocks nest properly and within the version's depths
// (vs_2_0: rep/loop 1, call 1, static if 16; vs_3_0: 4, 4, 24, dynamic 24; vs_2_x /
// ps_2_x: the device's caps), vs_2_0 allows 16 static flow-control instructions,
// break only in a loop, subroutines start with label after ret and end with ret.
#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

TEST(ValidatorFlow, Nesting) {
  std::string h = kVs20Head;
  EXPECT_TRUE(isValid(h + "rep i0\nadd r0, v0, c0\nendrep"));
  EXPECT_TRUE(hasError(h + "rep i0\nrep i0\nendrep\nendrep", "vs_2_0 allows rep/loop nesting depth 1, this rep is at depth 2"));
  std::string v3 = "vs_3_0\ndefi i0, 3, 0, 1, 0\ndcl_position v0\ndcl_position o0\nmov o0, v0\n";
  std::string four = "rep i0\nrep i0\nrep i0\nrep i0\nendrep\nendrep\nendrep\nendrep\n";
  EXPECT_TRUE(isValid(v3 + four));
  EXPECT_TRUE(hasError(v3 + "rep i0\n" + four + "endrep\n", "vs_3_0 allows rep/loop nesting depth 4, this rep is at depth 5"));
  std::string ifs, ends;
  for (int i = 0; i < 25; ++i) ifs += "if b0\n", ends += "endif\n";
  EXPECT_TRUE(hasError("vs_3_0\ndefb b0, true\ndcl_position v0\ndcl_position o0\nmov o0, v0\n" + ifs + ends,
                       "vs_3_0 allows if nesting depth 24, this if is at depth 25"));
  std::string dyn, dynEnd;
  for (int i = 0; i < 25; ++i) dyn += "if_gt v0.x, c0.x\n", dynEnd += "endif\n";
  EXPECT_TRUE(hasError(v3 + dyn + dynEnd, "vs_3_0 allows dynamic flow-control nesting depth 24, this if_comp is at depth 25"));
  ValidationCaps shallow;
  shallow.staticFlowControlDepth = 1;
  std::string v2x = "vs_2_x\ndefi i0, 3, 0, 1, 0\ndcl_position v0\nmov oPos, v0\n";
  EXPECT_TRUE(isValid(v2x + "rep i0\nrep i0\nendrep\nendrep"));
  EXPECT_TRUE(hasError(v2x + "rep i0\nrep i0\nendrep\nendrep", "vs_2_x allows rep/loop nesting depth 1", shallow));
}

TEST(ValidatorFlow, StaticFlowCount) {
  std::string s = kVs20Head;
  for (int i = 0; i < 16; ++i) s += "if b0\nendif\n";
  EXPECT_TRUE(isValid(s));
  EXPECT_TRUE(hasError(s + "if b0\nendif\n", "vs_2_0 allows 16 static flow-control instructions"));
}

TEST(ValidatorFlow, Matching) {
  std::string h = kVs20Head;
  EXPECT_TRUE(hasError(h + "endif", "endif without if"));
  EXPECT_TRUE(hasError(h + "rep i0\nendif\nendrep", "endif without if (the open block is rep)"));
  EXPECT_TRUE(hasError(h + "if b0\nendrep", "endrep without rep (the open block is if)"));
  EXPECT_TRUE(hasError(h + "rep i0\nmov r0, v0", "rep is never closed with endrep"));
  EXPECT_TRUE(hasError(h + "if b0\nelse\nelse\nendif", "if has a second else"));
  EXPECT_TRUE(hasError(h + "else\nendif", "else without if"));
  EXPECT_TRUE(isValid(h + "if b0\nmov r0, v0\nelse\nmov r0, c0\nendif\nmov oD0, r0"));
  EXPECT_TRUE(hasError(h + "loop aL, i0\nendrep", "endrep without rep (the open block is loop)"));
}

TEST(ValidatorFlow, LoopOperandsAndBreak) {
  std::string h = kVs20Head;
  EXPECT_TRUE(isValid(h + "loop aL, i0\nadd r0, v0, c[aL + 2]\nendloop"));
  EXPECT_TRUE(hasError(h + "loop i0, i0\nendloop", "loop takes aL and an integer constant (loop aL, i#)"));
  EXPECT_TRUE(hasError(h + "rep b0\nendrep", "rep takes an integer constant (rep i#)"));
  EXPECT_TRUE(hasError(h + "add r0, v0, c[aL + 2]", "aL is used outside a loop"));
  std::string x = "vs_2_x\ndefi i0, 3, 0, 1, 0\ndcl_position v0\nmov oPos, v0\n";
  EXPECT_TRUE(isValid(x + "rep i0\nbreak\nendrep"));
  EXPECT_TRUE(hasError(x + "break", "break outside a rep or loop block"));
  EXPECT_TRUE(hasError(h + "rep i0\nbreak\nendrep", "break is not a vs_2_0 instruction"));
}

TEST(ValidatorFlow, Subroutines) {
  std::string h = kVs20Head;
  EXPECT_TRUE(isValid(h + "call l0\nmov oD0, r0\nret\nlabel l0\nmov r0, c0\nret"));
  EXPECT_TRUE(hasError(h + "call l1\nret\nlabel l0\nret", "call to l1: the shader has no label l1"));
  EXPECT_TRUE(hasError(h + "call l0\nret\nmov r0, v0\nlabel l0\nret", "label l0 must directly follow a ret"));
  EXPECT_TRUE(hasError(h + "call l0\nret\nlabel l0\ncall l1\nret\nlabel l1\nret",
                       "vs_2_0 allows call nesting depth 1, this shader nests calls 2 deep"));
  EXPECT_TRUE(isValid("vs_3_0\ndcl_position v0\ndcl_position o0\nmov o0, v0\ncall l0\nret\nlabel l0\ncall l1\nret\nlabel l1\nret"));
  EXPECT_TRUE(hasError(h + "call l0\nret\nlabel l0\nmov r0, v0", "subroutine l0 does not end with ret"));
  EXPECT_TRUE(hasError(h + "callnz l0, i0\nret\nlabel l0\nret", "callnz takes a b# or p0 condition"));
}

}  // namespace
}  // namespace refx::shader
