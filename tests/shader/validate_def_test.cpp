// def check: def/defi/defb define c#/i#/b# within the version's count, take no
// modifier; ps_1_x constants lie in [-1, 1]; a BOOL constant is 0 or 1.
#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

TEST(ValidatorPs11, DefRange) {
  EXPECT_TRUE(isValid("ps_1_1\ndef c0, -1.0, 0.5, 1.0, 0\nmov r0, c0"));
  EXPECT_TRUE(hasError("ps_1_1\ndef c0, 1.5, 0, 0, 0\nmov r0, c0", "def c0: 1.5 is outside [-1, 1], the range of ps_1_1 constants"));
  EXPECT_TRUE(hasError("ps_1_4\ndef c0, 0, -2, 0, 0\nmov r0, c0", "def c0: -2 is outside [-1, 1], the range of ps_1_4 constants"));
  EXPECT_TRUE(isValid("ps_2_0\ndef c0, 1.5, 0, 0, 0\nmov oC0, c0"));
}

TEST(ValidatorTokens, DefTakesNoModifier) {
  using namespace refx::shader;
  // vs_2_0: defi i0, 4, 0, 1, 0 whose destination has shift 4 and _pp (0xF42F0000:
  // bits 27:24 = 4, 23:20 = 2); m4x4 oPos, v0, c0 after dcl_position v0.
  const std::vector<uint32_t> tokens = {0xFFFE0200, 0x0200001F, 0x80000000, 0x900F0000,
                                        0x05000030, 0xF42F0000, 4, 0, 1, 0,
                                        0x03000014, 0xC00F0000, 0x90E40000, 0xA0E40000,
                                        0x0000FFFF};
  EXPECT_EQ(firstProblem(tokens), "defi takes no instruction modifier");
}

TEST(ValidatorTokens, DefbIsFalseOrTrue) {
  using namespace refx::shader;
  // vs_2_0: defb b1 with the value 0x00100001 (TRUE is 1); then defb b2, true is fine.
  const std::vector<uint32_t> tokens = {0xFFFE0200, 0x0200002F, 0xE00F0801, 0x00100001,
                                        0x0200002F, 0xE00F0802, 0x00000001, 0x0000FFFF};
  const std::vector<Diagnostic> d = validate(decode(tokens));
  ASSERT_FALSE(d.empty());
  EXPECT_EQ(d[0].message, "defb b1: value 0x100001 is neither FALSE (0) nor TRUE (1)");
  for (size_t i = 1; i < d.size(); ++i) EXPECT_EQ(d[i].message.find("defb b2"), std::string::npos);
}

TEST(ValidatorTokens, DefsWriteTheWholeRegister) {
  using namespace refx::shader;
  // vs_3_0: defi i0 with write mask .xyw (0xF00B0000; the assembler writes .xyzw,
  // 0xF00F0000, and has no text for any other mask), values 2, 0, 1, 0.
  EXPECT_EQ(firstProblem({0xFFFE0300, 0x05000030, 0xF00B0000, 2, 0, 1, 0, 0x0000FFFF}),
            "defi writes the whole register (write mask .xyzw), found .xyw");
  // defb b1 with mask .x (0xE0010801).
  EXPECT_EQ(firstProblem({0xFFFE0300, 0x0200002F, 0xE0010801, 1, 0x0000FFFF}),
            "defb writes the whole register (write mask .xyzw), found .x");
}

}  // namespace
}  // namespace refx::shader
