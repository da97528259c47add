// Inputs that once crashed or hung the compiler (found by fuzz/fuzz_hlsl_compiler.cpp):
// each now compiles or is rejected with a diagnostic. Deep nesting is bounded (256
// levels of statements / parentheses / unary operators, expression trees 256
// operations high, 640 levels of statements and expressions through inlined calls) so
// that no input exhausts the stack, and so is the work unrolling and inlining multiply
// (100,000 statements and expressions evaluated).
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "refx/hlsl/compiler.h"
#include "refx/shader/disassembler.h"

namespace refx {
namespace {

hlsl::CompileResult compile(const std::string& source, const char* profile = "ps_3_0") {
  hlsl::CompileOptions o;
  o.profile = profile;
  return hlsl::compile(source, "t.hlsl", o);
}

std::string repeat(const std::string& s, int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += s;
  return out;
}

// The codes of the errors, in order.
std::vector<std::string> errorCodes(const hlsl::CompileResult& r) {
  std::vector<std::string> codes;
  for (const Diagnostic& d : r.diagnostics)
    if (d.severity == Severity::Error) codes.push_back(d.code);
  return codes;
}

bool mentions(const hlsl::CompileResult& r, const std::string& text) {
  return r.messages().find(text) != std::string::npos;
}

const std::string kMain = "float4 main(float4 c : COLOR0) : COLOR { ";

TEST(HlslLimits, DeepParenthesesAreAnError) {
  const auto r = compile(kMain + "return " + repeat("(", 30000) + "c" + repeat(")", 30000) + "; }");
  EXPECT_EQ(errorCodes(r), std::vector<std::string>{"X3000"}) << r.messages();
  EXPECT_TRUE(mentions(r, "nested more than 256 levels deep")) << r.messages();
}

TEST(HlslLimits, DeepBlocksAndUnaryChainsAreAnError) {
  for (const std::string& body : {repeat("{", 30000) + repeat("}", 30000) + "return c;",
                                  "return " + repeat("-", 30000) + "c;",
                                  "return " + repeat("(float4)", 30000) + "c;",
                                  "float4 r = " + repeat("{", 30000) + "1" + repeat("}", 30000) + "; return r;"}) {
    const auto r = compile(kMain + body + " }");
    EXPECT_FALSE(r.ok());
    EXPECT_TRUE(mentions(r, "error X3000: syntax error: nested more than 256 levels deep")) << r.messages();
  }
}

TEST(HlslLimits, LongOperatorChainsAreAnError) {
  // Left-associative chains nest in the tree, not in the source.
  for (const std::string& e : {"c" + repeat(" + c", 30000), "c" + repeat(".x", 30000), "c" + repeat("++", 30000)}) {
    const auto r = compile(kMain + "float4 d = c; return " + e + "; }");
    EXPECT_FALSE(r.ok());
    EXPECT_TRUE(mentions(r, "error X3000: syntax error: expression more than 256 operations deep")) << r.messages();
  }
}

TEST(HlslLimits, NestingWithinTheLimitsCompiles) {
  // 100 parentheses, 200 nested blocks, a chain of 200 additions (199 add instructions).
  EXPECT_TRUE(compile(kMain + "return " + repeat("(", 100) + "c" + repeat(")", 100) + "; }").ok());
  EXPECT_TRUE(compile(kMain + "float4 r = c; " + repeat("{", 200) + "r = r * c;" + repeat("}", 200) + " return r; }").ok());
  const auto chain = compile("float4 k[2]; " + kMain + "return c" + repeat(" + k[0] * c", 199) + "; }");
  EXPECT_TRUE(chain.ok()) << chain.messages();
}

TEST(HlslLimits, NestingThroughInlinedCallsIsAnError) {
  // Each function nests 200 blocks and calls the previous one at the bottom of a chain
  // of 200 multiplications: four of them stack about 1,600 levels.
  std::string source;
  for (int i = 0; i < 4; ++i) {
    const std::string call = i == 0 ? "c" : "f" + std::to_string(i - 1) + "(c)";
    source += "float4 f" + std::to_string(i) + "(float4 c) { " + repeat("{", 200) + "return " + call +
              repeat(" * c", 200) + ";" + repeat("}", 200) + " }\n";
  }
  const auto r = compile(source + kMain + "return f3(c); }");
  // One error: no "function must return a value" for the returns it did not reach.
  EXPECT_EQ(errorCodes(r), std::vector<std::string>{"X3590"}) << r.messages();
  EXPECT_TRUE(mentions(r, "nested more than 640 levels deep")) << r.messages();
}

TEST(HlslLimits, WorkMultipliedByUnrollingAndInliningIsBounded) {
  // Two nested loops of 1,000 iterations each: a million evaluations of the body.
  auto r = compile(kMain + "float s = 0; for (int i = 0; i < 1000; i++) for (int j = 0; j < 1000; j++) s += 1; "
                           "return s; }");
  EXPECT_EQ(errorCodes(r), std::vector<std::string>{"X3590"}) << r.messages();
  EXPECT_TRUE(mentions(r, "the program is too large")) << r.messages();
  // Each function calls the one before twice: f25 inlines f0 2^25 times.
  std::string source = "float f0(float x) { return x * 0.5; }\n";
  for (int i = 1; i <= 25; ++i)
    source += "float f" + std::to_string(i) + "(float x) { return f" + std::to_string(i - 1) + "(x) + f" +
              std::to_string(i - 1) + "(x + 1); }\n";
  r = compile(source + kMain + "return f25(c.x); }");
  EXPECT_EQ(errorCodes(r), std::vector<std::string>{"X3590"}) << r.messages();
  // Eight levels of that, and a loop of 1,000 iterations, are fine (and fold to constants:
  // s = 500, f8(s) = sum over the 256 leaves k = 0..255 of (500 + bits of k) / 2
  // = 256 * 250 + (8 * 128) / 2 = 64512).
  r = compile(source + kMain + "float s = 0; for (int i = 0; i < 1000; i++) s += 0.5; return f8(s) * c; }");
  ASSERT_TRUE(r.ok()) << r.messages();
  bool found = false;
  for (const shader::Instruction& in : r.shader.instructions) {
    if (in.opcode != shader::Opcode::Def) continue;
    float v[4];
    std::memcpy(v, in.literal.data(), 16);
    for (float x : v) found = found || x == 64512.0f;
  }
  EXPECT_TRUE(found) << shader::disassemble(r.tokens);
}

TEST(HlslLimits, NothingIsDeclaredVoid) {
  for (const std::string& source : {"void g = 1; " + kMain + "return c; }",
                                    kMain + "void x = 1; return c; }",
                                    "float f(void x) { return 1; } " + kMain + "return f(1); }",
                                    "struct S { void m; float4 v; }; S s; " + kMain + "return s.v; }",
                                    "void g[2] = {1, 2}; " + kMain + "return c; }",
                                    "typedef void V[2]; V g; " + kMain + "return c; }"}) {
    const auto r = compile(source);
    EXPECT_FALSE(r.ok()) << source;
    EXPECT_TRUE(mentions(r, "error X3000: syntax error: '")) << r.messages();
    EXPECT_TRUE(mentions(r, "' cannot be declared void")) << r.messages();
  }
  // A function without parameters may still say (void).
  EXPECT_TRUE(compile("float f(void) { return 0.5; } " + kMain + "return f(); }").ok());
}

TEST(HlslLimits, GeometricIntrinsicsRejectMatrices) {
  for (const char* call : {"normalize(a)", "length(a)", "reflect(a, a)", "distance(a, a)", "faceforward(a, a, a)"}) {
    const auto r = compile(std::string("float3x3 a; ") + kMain + "float3x3 b = " + call + "; return b[0].xyzz; }");
    EXPECT_EQ(errorCodes(r), std::vector<std::string>{"X3013"}) << call << "\n" << r.messages();
    EXPECT_TRUE(mentions(r, "vector arguments expected, found 'float3x3'")) << r.messages();
  }
}

TEST(HlslLimits, ArraySizesAndTypeSizesAreBounded) {
  // A dimension that does not fit an int.
  auto r = compile("float a[3e14]; " + kMain + "return a[0]; }");
  EXPECT_TRUE(mentions(r, "error X3059: array dimension must be between 1 and 65536")) << r.messages();
  // 65536 x 65536 floats, and 8^7 float4 through nested structs: past 65,536 components.
  r = compile("float a[65536][65536]; " + kMain + "return a[1][1]; }");
  EXPECT_TRUE(mentions(r, "error X3059: 'float[65536][65536]' is too large")) << r.messages();
  std::string nested = "struct S0 { float4 a[8]; }; ";
  for (int i = 1; i < 7; ++i)
    nested += "struct S" + std::to_string(i) + " { S" + std::to_string(i - 1) + " a[8]; }; ";
  r = compile(nested + "static S6 g; " + kMain + "return c; }");
  EXPECT_TRUE(mentions(r, "error X3059: 'struct S3[8]' is too large")) << r.messages();
  // 40 structs each holding the previous one: 32 levels at most.
  std::string deep = "struct T0 { float4 v; }; ";
  for (int i = 1; i < 40; ++i) deep += "struct T" + std::to_string(i) + " { T" + std::to_string(i - 1) + " m; }; ";
  r = compile(deep + kMain + "return c; }");
  EXPECT_TRUE(mentions(r, "levels of arrays and structs")) << r.messages();
}

TEST(HlslLimits, LiteralIndicesThatAreNoIntegerAreOutOfBounds) {
  // 1 % 0 is NaN and 1e30 no int: both index out of bounds, read or written.
  for (const char* body : {"int z = 0; return a[1 % z];", "return a[1e30];",
                                  "float4 b[3] = a; int z = 0; b[2 % z] = 1; return b[0];"}) {
    const auto r = compile("float4 a[3]; " + kMain + body + " }");
    EXPECT_EQ(errorCodes(r), std::vector<std::string>{"X3504"}) << body << "\n" << r.messages();
  }
}

TEST(HlslLimits, UniformsPastTheConstantRegistersAreReported) {
  // ps_3_0 has 224 float constants; a uniform array of 65536 and a register(c…) far
  // past the end are limit errors, not internal errors.
  auto r = compile("float a[65536]; " + kMain + "return a[1]; }");
  EXPECT_EQ(errorCodes(r), std::vector<std::string>{"X4550"}) << r.messages();
  EXPECT_TRUE(mentions(r, "ps_3_0 has 224 constant registers, the uniforms need 65536")) << r.messages();
  r = compile("float4 a : register(c99999999999); " + kMain + "return a; }");
  EXPECT_EQ(errorCodes(r), std::vector<std::string>{"X4550"}) << r.messages();
  // c200 stays where it is bound; b fills c0..c29.
  r = compile("float4 a : register(c200); float4 b[30]; " + kMain + "return a + b[29]; }");
  ASSERT_TRUE(r.ok()) << r.messages();
  ASSERT_GE(r.shader.instructions.size(), 2u);
  const shader::Instruction& add = r.shader.instructions.back();
  EXPECT_EQ(add.opcode, shader::Opcode::Add);
  EXPECT_EQ(add.src[0].index, 200);
  EXPECT_EQ(add.src[1].index, 29);
}

}  // namespace
}  // namespace refx
