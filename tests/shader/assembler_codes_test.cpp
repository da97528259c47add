// The assembler's diagnostic codes (docs/diagnostics.md, "Assembler"): one bad source
// per code, matched on the code and the line, never on the message text; and every
// bad line of a file reported in one run.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/shader/assembler.h"

using namespace refx;

namespace {

std::vector<Diagnostic> diagnose(std::string_view text) {
  DiagnosticSink sink;
  shader::assemble(text, "t.asm", sink);
  return sink.all();
}

// "code@line" of every diagnostic, in order.
std::vector<std::string> codesAndLines(std::string_view text) {
  std::vector<std::string> out;
  for (const Diagnostic& d : diagnose(text)) out.push_back(d.code + "@" + std::to_string(d.where.line));
  return out;
}

struct CodeCase {
  const char* code;
  const char* source;
  int line;  // of the one error
};

// Each source has exactly one mistake, on the line given.
const CodeCase kCases[] = {
    // A number where a register belongs: immediates live in def'd constants.
    {"A2000", "vs_1_1\nmov r0, 5\n", 2},
    {"A2001", "vs_1_1\nmov r0, v0\nfoo r1, v0\n", 3},
    {"A2002", "mov r0, v0\n", 1},     // no version first
    {"A2002", "ps_1_5\nmov r0, v0\n", 1},  // ps_1_5 does not exist
    {"A2002", "vs_1_1\nvs_1_1\n", 2},      // a second version
    // tex is the ps_1_1–1_3 spelling; ps_1_4 samples with texld.
    {"A2003", "ps_1_4\ntex t0\n", 2},
    // Co-issue ('+') pairs exist only in ps_1_x.
    {"A2003", "vs_2_0\n+mov r0, r1\n", 2},
    // add is dst, src0, src1: one source is missing.
    {"A2004", "vs_1_1\nadd r0, v0\n", 2},
    {"A2005", "vs_1_1\nmov r0, q3\n", 2},
    // vs_1_1 has one address register, a0.
    {"A2006", "vs_1_1\nmov r0, a1\n", 2},
    // ps_2_0 has no relative addressing of constants.
    {"A2007", "ps_2_0\nmov r0, c[a0.x]\n", 2},
    // A write mask lists components in x, y, z, w order.
    {"A2008", "vs_1_1\nmov r0.yx, v0\n", 2},
    {"A2009", "ps_1_1\ntex t0\nmov r0, t0_bx3\n", 3},
    {"A2010", "ps_1_1\ntex t0\nmul_x3 r0, t0, t0\n", 3},
    // def writes a constant register c#.
    {"A2011", "ps_1_1\ndef r0, 1, 0, 0, 0\n", 2},
    {"A2012", "vs_2_0\ndefb b0, maybe\n", 2},
    {"A2013", "vs_2_0\ndcl_bogus v0\n", 2},
    // The predicate register is p0 only.
    {"A2014", "vs_2_x\n(p1) mov r0, v0\n", 2},
    // Assembly text is not preprocessed; only #line is read.
    {"A2015", "#define X 1\nvs_1_1\nmov r0, v0\n", 1},
    {"A2016", "vs_1_1\nmov r0, v0\n/* never closed\n", 3},
};

TEST(AssemblerCodes, EachMistakeHasItsCode) {
  for (const CodeCase& c : kCases) {
    const std::vector<Diagnostic> d = diagnose(c.source);
    ASSERT_EQ(d.size(), 1u) << c.source;
    EXPECT_EQ(d[0].code, c.code) << c.source << "\n" << d[0].str();
    EXPECT_EQ(d[0].where.line, c.line) << c.source << "\n" << d[0].str();
    EXPECT_EQ(d[0].where.file, "t.asm");
    EXPECT_EQ(d[0].severity, Severity::Error);
  }
}

TEST(AssemblerCodes, EveryBadLineIsReported) {
  const char* source =
      "vs_1_1\n"
      "mov r0, v0\n"
      "foo r1, v0\n"          // 3: unknown instruction
      "add r2, v0\n"          // 4: a source missing (the next line is not read as it)
      "mul r3, v0, c0\n"      // 5: fine
      "mov r4.xq, v0\n";      // 6: bad write mask
  EXPECT_EQ(codesAndLines(source), (std::vector<std::string>{"A2001@3", "A2004@4", "A2008@6"}));
}

TEST(AssemblerCodes, AnInstructionMissingAnOperandDoesNotSwallowTheNextLine) {
  // `mov r0` ends where `frob` begins; frob, an error of its own, is still reported.
  EXPECT_EQ(codesAndLines("vs_1_1\nmov r0\nfrob r1, v0\nmov r2, v0\n"),
            (std::vector<std::string>{"A2004@2", "A2001@3"}));
}

TEST(AssemblerCodes, ParsingGoesOnAfterBadCommentsAndDirectives) {
  EXPECT_EQ(codesAndLines("#pragma x\nvs_1_1\n#define Y\nfoo r0\n"),
            (std::vector<std::string>{"A2015@1", "A2015@3", "A2001@4"}));
}

TEST(AssemblerCodes, AMissingVersionEndsTheRun) {
  // Without a version no later line can be read: one error, not one per line.
  EXPECT_EQ(codesAndLines("mov r0, v0\nfoo\nbar\n"), (std::vector<std::string>{"A2002@1"}));
}

TEST(AssemblerCodes, StopsAfterOneHundredErrors) {
  std::string source = "vs_1_1\n";
  for (int i = 0; i < 150; ++i) source += "foo r0, v0\n";
  const std::vector<Diagnostic> d = diagnose(source);
  ASSERT_EQ(d.size(), 101u);  // 100 errors, then the one that says the assembler stops
  EXPECT_EQ(d[99].code, "A2001");
  EXPECT_EQ(d[99].where.line, 101);  // lines 2..101 hold the first hundred
  EXPECT_EQ(d[100].code, "A2099");
}

TEST(AssemblerCodes, TheThrowingFormListsEveryError) {
  try {
    shader::assemble("vs_1_1\nfoo r0, v0\nmov r0.yx, v0\n", "t.asm");
    FAIL() << "two errors must throw";
  } catch (const Error& e) {
    const std::string what = e.what();
    const size_t nl = what.find('\n');
    ASSERT_NE(nl, std::string::npos) << what;
    // The first line reads as before, with the code after "error".
    EXPECT_EQ(what.substr(0, nl).rfind("t.asm:2:1: error A2001: unknown instruction 'foo'", 0), 0u) << what;
    EXPECT_EQ(what.substr(nl + 1).rfind("t.asm:3:", 0), 0u) << what;
    EXPECT_NE(what.find("error A2008: "), std::string::npos) << what;
    EXPECT_EQ(what.find('\n', nl + 1), std::string::npos) << what;  // two lines, no trailing newline
  }
}

TEST(AssemblerCodes, AGoodShaderReportsNothing) {
  DiagnosticSink sink;
  const shader::Shader sh = shader::assemble("ps_1_1\ntex t0\nmov r0, t0\n", "t.asm", sink);
  EXPECT_FALSE(sink.hasErrors());
  EXPECT_TRUE(sink.all().empty());
  EXPECT_EQ(sh.instructions.size(), 2u);
}

}  // namespace
