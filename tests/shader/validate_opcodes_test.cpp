// Opcode check: an instruction exists in the shader's version (dp4 from ps_1_2,
// texreg2rgb from ps_1_2, rcp never in ps_1_x, flow control from vs_2_0 / ps_2_x with
// caps), texm3x3diff is reserved everywhere, and the specific-control bits 23:16 and
// result-modifier bits 23:20 of a token hold only values D3D9 defines (bytecode.md).
#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

TEST(ValidatorPs11, InstructionAvailability) {
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ndp4 r0, t0, t0", "dp4 is not a ps_1_1 instruction"));
  EXPECT_TRUE(isValid("ps_1_2\ntex t0\ndp4 r0, t0, t0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexreg2rgb t1, t0\nmov r0, t1", "texreg2rgb is not a ps_1_1 instruction"));
  EXPECT_TRUE(hasError("ps_1_1\nrcp r0, v0", "rcp is not a ps_1_1 instruction"));
  EXPECT_TRUE(hasError(readRaw("ps_1_1\ntex t0\ntexm3x3diff t1, t0\nmov r0, t0"), "texm3x3diff is a reserved opcode"));
}

TEST(ValidatorPs20, FlowControlAvailability) {
  EXPECT_TRUE(hasError("ps_2_0\ndefi i0, 2, 0, 0, 0\nrep i0\nendrep\nmov oC0, c0", "defi is not a ps_2_0 instruction"));
  EXPECT_TRUE(hasError("ps_2_0\nrep i0\nendrep\nmov oC0, c0", "rep is not a ps_2_0 instruction"));
  std::string x = "ps_2_x\ndefi i0, 2, 0, 0, 0\nrep i0\nadd r0, c0, c0\nendrep\nmov oC0, r0";
  EXPECT_TRUE(isValid(x));
  ValidationCaps none;
  none.ps2xFlowControl = false;
  EXPECT_TRUE(hasError(x, "rep in ps_2_x needs a device that reports it", none));
  EXPECT_TRUE(hasError("ps_2_x\ndefi i0, 2, 0, 0, 0\nloop aL, i0\nendloop\nmov oC0, c0", "loop is not a ps_2_x instruction"));
  EXPECT_TRUE(isValid("ps_3_0\ndefi i0, 2, 0, 0, 0\ndcl_texcoord0 v0\nloop aL, i0\nadd r0, v[aL], c0\nendloop\nmov oC0, r0"));
}

TEST(ValidatorTokens, ReservedSpecificControlBitsAreRejected) {
  using namespace refx::shader;
  // ps_1_1: tex t0; mul r0, t0, v0 with bits 23:16 = 0x39, which mul does not define
  // (bytecode.md: instruction token bits 23:16 are opcode-specific controls).
  const std::vector<uint32_t> mul = {0xFFFF0101, 0x00000042, 0xB00F0000, 0x00390005,
                                     0x800F0000, 0xB0E40000, 0x90E40000, 0x0000FFFF};
  const std::vector<Diagnostic> d = validate(decode(mul));
  ASSERT_FALSE(d.empty());
  EXPECT_EQ(d[0].message, "mul has specific-control bits 0x39, which ps_1_1 does not define for it");
  // ps_2_0: dcl_2d s0; dcl t0; texld r0, t0, s0 with project and bias bits both set (3).
  const std::vector<uint32_t> texld = {0xFFFF0200, 0x0200001F, 0x90000000, 0xA00F0800,
                                       0x0200001F, 0x80000000, 0xB00F0000, 0x03030042,
                                       0x800F0000, 0xB0E40000, 0xA0E40800, 0x02000001,
                                       0x800F0800, 0x80E40000, 0x0000FFFF};
  EXPECT_FALSE(validate(decode(texld)).empty());
  // The same with the project bit alone is texldp, which ps_2_0 has.
  std::vector<uint32_t> texldp = texld;
  texldp[7] = 0x03010042;
  EXPECT_TRUE(validate(decode(texldp)).empty());
}

TEST(ValidatorTokens, UndefinedResultModifierBitsAreRejected) {
  using namespace refx::shader;
  // vs_1_1: mov oPos, v0 whose destination has result modifier bits 23:20 = 8 (defined:
  // 1 _sat, 2 _pp, 4 _centroid).
  const std::vector<uint32_t> tokens = {0xFFFE0101, 0x00000001, 0xC08F0000, 0x90E40000,
                                        0x0000FFFF};
  EXPECT_EQ(firstProblem(tokens), "mov has result modifier bits 0x8; only _sat, _pp and _centroid exist");
}

}  // namespace
}  // namespace refx::shader
