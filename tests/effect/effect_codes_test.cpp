// The effect reader's diagnostic codes (docs/diagnostics.md, "Effects"): one bad source
// per code, matched on the code and the line, never on the message text; several
// syntax errors of one file reported at once; the assembler's codes for asm blocks.
#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "pipeline/device_helpers.h"
#include "refx/core/diagnostics.h"
#include "refx/effect/effect.h"

using namespace refx;
using namespace refx::effect;

namespace {

// "CODE@line" of each "file:line:col: error CODE: …" line of a message.
std::vector<std::string> codesIn(const std::string& message) {
  std::vector<std::string> out;
  static const std::regex kLine(R"((^|\n)[^\n]*?:([0-9]+):[0-9]+: error ([A-Z][0-9]{4}): )");
  for (auto it = std::sregex_iterator(message.begin(), message.end(), kLine); it != std::sregex_iterator(); ++it)
    out.push_back((*it)[3].str() + "@" + (*it)[2].str());
  return out;
}

// The codes of an effect text: those of the error it throws, or else those of its
// diagnostics (the errors binding its states and shaders).
std::vector<std::string> codesOf(const std::string& text) {
  std::unique_ptr<Effect> fx;
  try {
    fx = Effect::fromText(text, "e.fx");
  } catch (const Error& e) {
    std::vector<std::string> codes = codesIn(e.what());
    if (codes.empty()) codes.push_back(std::string("uncoded: ") + e.what());
    return codes;
  }
  std::vector<std::string> out;
  for (const EffectDiagnostic& d : fx->diagnostics()) out.push_back(d.code + "@" + std::to_string(d.where.line));
  return out;
}

std::string pass(const std::string& states) { return "technique t {\n pass p {\n" + states + "\n }\n}\n"; }

struct CodeCase {
  const char* code;
  std::string source;
  int line;
};

TEST(EffectCodes, EachMistakeHasItsCode) {
  const std::string deepExpression = "float x = " + std::string(200, '(') + "1" + std::string(200, ')') + ";\n";
  const std::vector<CodeCase> cases = {
      {"F1000", "float x;\n/* never closed\n", 2},
      {"F1001", "string s = \"open;\n", 1},
      {"F1002", "float x = @;\n", 1},
      {"F1003", "float x = 0x;\n", 1},
      {"F1004", "#define A A B\nfloat4 x = A;\n", 2},
      {"F1005", "float x;\n#endif\n", 2},
      {"F1006", "#include \"no_such_file.fxh\"\n", 1},
      {"F1007", "#if (1\n#endif\n", 1},
      {"F1008", "#define F(x) x\n", 1},
      {"F1009", "float x;\n#error not this one\n", 2},
      {"F1010", "#bogus\n", 1},
      // The asm block is never closed.
      {"F1011", "technique t { pass p {\nPixelShader = asm { ps.1.1\n", 2},
      // A state without a value.
      {"F1100", pass("ZEnable = ;"), 3},
      {"F1101", "Foo bar;\n", 1},
      {"F1102", "technique10 t { }\n", 1},
      {"F1103", "struct S { float a; };\nS s;\n", 2},
      // An annotation's value is a literal, not a name.
      {"F1104", "float x < float a = b; > = 1;\n", 1},
      // 200 parentheses are more than the 128 levels an expression may nest.
      {"F1105", deepExpression, 1},
      {"F1200", pass("Texture[0] = <missing>;"), 3},
      {"F1201", pass("ZEnabel = true;"), 3},
      // D3D9 has texture stages 0 to 7.
      {"F1202", pass("ColorOp[8] = Modulate;"), 3},
      {"F1203", pass("CullMode = Sideways;"), 3},
      // float4(…) takes four values.
      {"F1205", "float4 v = float4(1, 2);\n", 1},
      {"F1206", "float a;\nfloat a;\n", 2},
      // A vertex shader where the pixel shader belongs.
      {"F1207", pass("PixelShader = asm { vs.1.1 mov oPos, v0 };"), 3},
  };
  for (const CodeCase& c : cases) {
    EXPECT_EQ(codesOf(c.source), std::vector<std::string>{std::string(c.code) + "@" + std::to_string(c.line)})
        << c.source;
  }
}

// Shader constants set by a state must fit the register file, c0..c255 for vertex
// shaders (vs_3_0's 256 float constants): a 4x4 matrix from c254 needs c254..c257 and is
// refused when the pass is applied.
TEST(EffectCodes, ConstantsPastTheRegisterFile) {
  auto fx = Effect::fromText(pass("VertexShaderConstant4[254] = float4x4(1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1);"), "e.fx");
  ASSERT_TRUE(fx->diagnostics().empty()) << fx->diagnostics()[0].str();
  auto dev = test::makeDevice(4, 4);
  fx->begin(*dev, kDoNotSaveState);
  try {
    fx->beginPass(0);
    FAIL() << "a state past c255 must be an error";
  } catch (const Error& e) {
    EXPECT_EQ(codesIn(e.what()), std::vector<std::string>{"F1204@3"}) << e.what();
  }
}

TEST(EffectCodes, SeveralSyntaxErrorsAreReportedAtOnce) {
  // A state without a value, a state without ';' before the pass ends, a pass keyword
  // misspelt and a bad declaration: each construct is skipped and reading goes on.
  const char* text =
      "technique t {\n"
      "  pass p0 {\n"
      "    ZEnable = ;\n"           // 3
      "    CullMode = None;\n"
      "    AlphaBlendEnable = true\n"
      "  }\n"                       // 6: ';' missing before '}'
      "  pas p1 { ZEnable = true; }\n"  // 7: 'pass' misspelt
      "}\n"
      "float4 v = {1, 2;\n"         // 9: the list is not closed
      "technique u { pass { CullMode = None; } }\n";
  EXPECT_EQ(codesOf(text), (std::vector<std::string>{"F1100@3", "F1100@6", "F1100@7", "F1100@9"}));
}

TEST(EffectCodes, EveryBadDeclarationIsReported) {
  // A redefinition and an initializer of the wrong size; the good parameter between
  // them is no error.
  EXPECT_EQ(codesOf("float a;\nfloat a;\nfloat b = 2;\nfloat4 v = float4(1, 2);\n"),
            (std::vector<std::string>{"F1206@2", "F1205@4"}));
}

TEST(EffectCodes, AsmBlocksReportTheAssemblersCodesAtTheFilesLines) {
  const std::string text = pass(
      "PixelShader = asm {\n"
      "  ps.1.1\n"
      "  tex t0\n"
      "  foo r0, t0\n"       // line 6 of the file: unknown instruction
      "  mov r0, t0.xq\n"    // line 7: bad swizzle
      "};");
  EXPECT_EQ(codesOf(text), (std::vector<std::string>{"A2001@6", "A2008@7"}));
}

TEST(EffectCodes, ReadingStopsAfterOneHundredErrors) {
  std::string states;
  for (int i = 0; i < 150; ++i) states += "ZEnable = ;\n";
  EXPECT_EQ(codesOf(pass(states)).size(), 100u);
}

}  // namespace
