// HLSL diagnostic codes: every X code of the preprocessor, parser/type checker and code
// generator listed in docs/diagnostics.md has a source here that triggers it, matched on
// the code and the line it is reported at. What each source does wrong is written next
// to it (the docs row's meaning, fxc's meaning of the number).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "refx/hlsl/compiler.h"

namespace refx {
namespace {

const std::string kIncludeDir = std::string(REFX_TEST_DIR) + "/hlsl/pp_include";

struct CodeCase {
  std::string code;
  std::string profile;
  std::string source;
  int line;                // where the diagnostic points
  std::string fileName = "t.hlsl";
  std::string reportedIn;  // the file the diagnostic names, when not the main one
};

std::string repeat(const std::string& s, int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += s;
  return out;
}

// A pixel shader whose body is `body` (line 1 is the signature, the body starts on line 2).
std::string ps(const std::string& body) { return "float4 main() : COLOR {\n" + body + "\n}\n"; }

std::vector<CodeCase> codeCases() {
  std::vector<CodeCase> c;
  auto add = [&](const char* code, const char* profile, std::string source, int line) {
    c.push_back({code, profile, std::move(source), line, "t.hlsl", ""});
  };
  const std::string ret = "return 0;";

  // ---- preprocessor (X1xxx) ----
  add("X1500", "ps_2_0", "#define\n" + ps(ret), 1);                                   // #define without a name
  add("X1504", "ps_2_0", "#frobnicate\n" + ps(ret), 1);                               // no such directive
  {
    // cycle_a.h includes cycle_b.h, which includes cycle_a.h again: recursion, reported
    // at cycle_b.h's #include (its line 1).
    CodeCase r{"X1506", "ps_2_0", "#include \"cycle_a.h\"\n" + ps(ret), 1, kIncludeDir + "/main.hlsl", "cycle_b.h"};
    c.push_back(r);
  }
  add("X1507", "ps_2_0", "\n#include \"no_such_header.h\"\n" + ps(ret), 2);           // nothing to open
  add("X1519", "ps_2_0", "#define A 1\n#define A 2\n" + ps(ret), 2);                  // same name, other body
  add("X1550", "ps_2_0", "\n\n#error stop here\n" + ps(ret), 3);                      // #error is an error
  add("X1551", "ps_2_0", ps(ret) + "/* never closed\n", 4);                           // comment runs to EOF
  add("X1552", "ps_2_0", "float4 main() : COLOR {\n  \"no end\n  return 0;\n}\n", 2);  // string runs to EOL
  add("X1553", "ps_2_0", "float4 main() : COLOR {\n  return 0; @\n}\n", 2);          // '@' is no HLSL character
  add("X1554", "ps_2_0", "#endif\n" + ps(ret), 1);                                    // #endif with no #if open
  add("X1555", "ps_2_0", "#if 1\n" + ps(ret), 1);                                     // #if never closed
  add("X1556", "ps_2_0", "#if 1\n#else\n#else\n#endif\n" + ps(ret), 3);               // second #else
  add("X1557", "ps_2_0", "#define F(x) x\n" + ps(ret) + "F(1\n", 5);                  // argument list runs to EOF
  add("X1558", "ps_2_0", "#define F(x) x\nfloat4 main() : COLOR {\n  return F(1, 2);\n}\n", 3);  // 2 args, 1 parameter
  add("X1559", "ps_2_0", "#if 1.5\n#endif\n" + ps(ret), 1);                           // #if takes integers only
  add("X1560", "ps_2_0", "#if 1 / 0\n#endif\n" + ps(ret), 1);                         // division by zero
  // Arguments nested 300 deep: past the 200 levels of argument pre-expansion.
  add("X1561", "ps_2_0", "#define F(x) x\nfloat4 main() : COLOR {\n  return " + repeat("F(", 300) + "0" +
                             repeat(")", 300) + ";\n}\n", 3);
  add("X1563", "ps_2_0", "#define A ## b\n" + ps(ret), 1);                            // ## at the start of a body
  // '+' pasted to '/' gives "+/", which is no token.
  add("X1564", "ps_2_0", "#define P(a, b) a ## b\nfloat4 main() : COLOR {\n  return 1 P(+, /) 1;\n}\n", 3);
  {
    // "sub" next to the including file is a directory, not a file.
    CodeCase r{"X1565", "ps_2_0", "#include \"sub\"\n" + ps(ret), 1, kIncludeDir + "/main.hlsl", ""};
    c.push_back(r);
  }
  add("X1567", "ps_2_0", "#if 1\n#endif extra\n" + ps(ret), 2);                       // tokens after #endif

  // ---- parser and type checker (X3xxx) ----
  add("X3000", "ps_2_0", ps("  return 0 0;"), 2);                                      // two expressions, no operator
  add("X3003", "ps_2_0", ps("  float a = 1;\n  float a = 2;\n  return a;"), 3);       // `a` twice in one scope
  add("X3004", "ps_2_0", ps("  return undeclared;"), 2);                               // no such variable
  add("X3013", "ps_2_0", "float f(float a) { return a; }\n" + ps("  return f(1, 2);"), 3);  // f takes one argument
  add("X3014", "ps_2_0", ps("  return float4(1, 2);"), 2);                             // float4 from 2 components
  add("X3017", "ps_2_0", ps("  float2 a = 1;\n  float4 b = a;\n  return b;"), 3);     // float2 cannot widen to float4
  add("X3018", "ps_2_0", ps("  float4 a = 1;\n  return a.q;"), 3);                     // no component q
  add("X3019", "ps_2_0",
      "struct S { float a; };\n" + ps("  S s;\n  s.a = 1;\n  if (s) return 1;\n  return 0;"), 5);  // struct condition
  add("X3020", "ps_2_0", "struct S { float a; };\n" + ps("  S s;\n  s.a = 1;\n  return s + 1;"), 5);  // struct + float
  add("X3022", "ps_2_0", "sampler2D tex;\n" + ps("  return -tex;"), 3);                // negating a sampler
  add("X3025", "ps_2_0", "float4 k;\n" + ps("  k = 1;\n  return k;"), 3);              // uniforms are read-only
  add("X3058", "ps_2_0", ps("  int n = 2;\n  float a[n];\n  return 0;"), 3);           // array size not a literal
  add("X3059", "ps_2_0", ps("  float a[0];\n  return 0;"), 2);                         // array size 0 out of 1..65536
  // f(1) converts int to float or to bool equally well: no overload is better.
  add("X3067", "ps_2_0", "float f(float a) { return a; }\nfloat f(bool a) { return 2; }\n" + ps("  return f(1);"), 4);
  add("X3079", "ps_2_0", "void f() { return 1; }\n" + ps("  f();\n  return 0;"), 1);                    // void function returns a value
  add("X3080", "ps_2_0", "float f() { }\n" + ps("  return f();"), 1);                  // float function, no return
  add("X3082", "ps_2_0", "int k;\n" + ps("  return k & 2;"), 3);                      // SM2 has no integer bit ops
  add("X3121", "ps_2_0", ps("  float a = 1;\n  return a[0];"), 3);                    // scalar is not indexable
  add("X3206", "ps_2_0", ps("  float2 a = float4(1, 2, 3, 4);\n  return a.xyxy;"), 2);  // float4 cut to float2
  add("X3500", "ps_2_0", "float f(float a) { return f(a); }\n" + ps("  return f(1);"), 1);  // recursion
  // No `main` to compile; the error names the file alone (line 0).
  add("X3501", "ps_2_0", "float4 other() : COLOR { return 0; }\n", 0);
  add("X3502", "ps_2_0", "float4 main(float4 t) : COLOR {\n  return t;\n}\n", 1);     // input without a semantic
  add("X3504", "ps_2_0", ps("  float a[2] = { 1, 2 };\n  return a[2];"), 3);          // index 2 of a[0..1]
  // ps_2_0 has no address register for constant registers.
  add("X3512", "ps_2_0", "float4 k[4];\nfloat4 main(float2 t : TEXCOORD0) : COLOR {\n  return k[int(t.x)];\n}\n", 3);
  add("X3511", "ps_2_0",
      "int n;\nfloat4 main() : COLOR {\n  float s = 0;\n  for (int i = 0; i < n; i++) s += 1;\n  return s;\n}\n",
      4);  // count is a uniform: ps_2_0 cannot loop, and it cannot be unrolled
  add("X3518", "ps_2_0", ps("  break;\n  return 0;"), 2);                              // break outside a loop
  add("X3519", "ps_2_0", ps("  continue;\n  return 0;"), 2);                           // continue outside a loop
  add("X3530", "ps_2_0", "float4 k : packoffset(c0);\n" + ps("  return k;"), 1);       // Direct3D 10 construct
  // A [loop] of 300 iterations: rep counts at most 255.
  add("X3531", "vs_2_0",
      "float4 main(float4 p : POSITION) : POSITION {\n  [loop] for (int i = 0; i < 300; i++) p += 1;\n  return p;\n}\n",
      2);
  // while (true) left by its break: rep bounds it at 255 iterations.
  add("X3532", "vs_3_0",
      "float4 main(float4 p : POSITION) : POSITION {\n  [loop] while (true) {\n    p += 1;\n    if (p.x > 10) break;\n"
      "  }\n  return p;\n}\n",
      2);
  add("X3533", "ps_2_0", "float4 main(float3 t : TEXCOORD0) : COLOR {\n  return noise(t);\n}\n", 2);  // texture fills only
  add("X3537", "ps_2_0", "float4 main(float4 t : TEXCOORD0) : COLOR {\n  return ddx(t);\n}\n", 2);   // ddx needs ps_2_x
  add("X3539", "vs_2_0", "float4 main(float4 p : POSITION) : POSITION {\n  clip(p);\n  return p;\n}\n", 2);  // vs has no kill
  // tex2D in a [loop] that lanes leave at different times (a per-pixel break).
  add("X3553", "ps_3_0",
      "sampler2D s;\nfloat4 main(float2 t : TEXCOORD0) : COLOR {\n  float4 c = 0;\n"
      "  [loop] for (int i = 0; i < 4; i++) {\n    c += tex2D(s, t);\n    if (c.x > t.y) break;\n  }\n  return c;\n}\n",
      4);
  // ps_2_0 has no rep: the [loop] is unrolled.
  add("X3554", "ps_2_0",
      "float4 main(float4 t : TEXCOORD0) : COLOR {\n  [loop] for (int i = 0; i < 4; i++) t += 1;\n  return t;\n}\n", 2);
  add("X3568", "ps_2_0", "#pragma pack_matrix(sideways)\n" + ps(ret), 1);              // neither row_ nor column_major
  // 1000 x 1000 unrolled iterations: over the 100,000 statements evaluated.
  add("X3590", "ps_2_0",
      ps("  float s = 0;\n  for (int i = 0; i < 1000; i++)\n    for (int j = 0; j < 1000; j++) s += 1;\n  return s;"), 4);

  // ---- code generation (X4xxx) ----
  add("X4000", "ps_2_0", ps("  float a;\n  return a;"), 3);                            // read before any write
  // tex2D under a [branch] on a per-pixel condition: gradients undefined, flattened.
  add("X4121", "ps_3_0",
      "sampler2D s;\nfloat4 main(float2 t : TEXCOORD0) : COLOR {\n  float4 c = 0;\n  [branch] if (t.x > 0.5)\n"
      "    c = tex2D(s, t);\n  return c;\n}\n",
      4);
  add("X4502", "ps_2_0", "float4 main() : POSITION {\n  return 0;\n}\n", 1);          // ps output must be COLOR/DEPTH
  add("X4504", "ps_2_0",
      "struct O { float4 a : COLOR0; float4 b : COLOR0; };\nO main() {\n  O o;\n  o.a = 0;\n  o.b = 1;\n  return o;\n}\n",
      2);  // two outputs to COLOR0
  {
    // 17 samplers, each read: ps_3_0 has s0..s15.
    std::string src, sum;
    for (int i = 0; i < 17; ++i) {
      src += "sampler2D s" + std::to_string(i) + ";\n";
      sum += " + tex2D(s" + std::to_string(i) + ", t)";
    }
    add("X4509", "ps_3_0", src + "float4 main(float2 t : TEXCOORD0) : COLOR {\n  return 0" + sum + ";\n}\n", 18);
  }
  // ps_1_1 has no division (no rcp).
  add("X4532", "ps_1_1", "float4 main(float4 t : TEXCOORD0) : COLOR {\n  return 1 / t;\n}\n", 2);
  // A uniform array of 40 registers: ps_2_0 has c0..c31.
  add("X4550", "ps_2_0", "float4 k[40];\n" + ps("  return k[0] + k[39];"), 2);
  // n counts a [loop] (an i# register) and is read as a value too.
  add("X4551", "vs_2_0",
      "int n;\nfloat4 main(float4 p : POSITION) : POSITION {\n  [loop] for (int i = 0; i < n; i++) p += 1;\n  return p * n;\n"
      "}\n",
      1);
  return c;
}

// Codes that no source can reach, with the reason.
const std::map<std::string, std::string>& unreachableCodes() {
  static const std::map<std::string, std::string> codes = {
      // The safety net for compiler bugs: code the compiler generates failing refx's
      // validator, a [loop] whose variables never settle, sincos on a profile without it.
      // A correct compiler never produces them from any source.
      {"X9000", "internal error: reported only when the compiler itself is wrong"},
  };
  return codes;
}

bool hasCodeAt(const hlsl::CompileResult& r, const CodeCase& c) {
  for (const Diagnostic& d : r.diagnostics) {
    if (d.code != c.code || d.where.line != c.line) continue;
    if (!c.reportedIn.empty() && !d.where.file.ends_with(c.reportedIn)) continue;
    return true;
  }
  return false;
}

TEST(HlslCodes, EachCodeHasASourceThatTriggersItAtItsLine) {
  for (const CodeCase& c : codeCases()) {
    hlsl::CompileOptions o;
    o.profile = c.profile;
    const hlsl::CompileResult r = hlsl::compile(c.source, c.fileName, o);
    EXPECT_TRUE(hasCodeAt(r, c)) << c.code << " expected at line " << c.line << "; got:\n" << r.messages();
  }
}

std::string readFile(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// The HLSL compiler's codes in docs/diagnostics.md: rows "| X3058, X3059 | error | …" of
// the X1xxx, X3xxx and X4xxx/X9000 tables (X5xxx are the shader validator's).
std::set<std::string> documentedHlslCodes() {
  const std::filesystem::path root = std::filesystem::path(REFX_TEST_DIR).parent_path();
  const std::string doc = readFile(root / "docs" / "diagnostics.md");
  std::set<std::string> codes;
  const std::regex row("\\n\\| (X[0-9]{4}(?:, X[0-9]{4})*) \\| (?:error|warning) \\|");
  const std::regex code("X[0-9]{4}");
  for (auto it = std::sregex_iterator(doc.begin(), doc.end(), row); it != std::sregex_iterator(); ++it) {
    const std::string cell = (*it)[1].str();
    for (auto k = std::sregex_iterator(cell.begin(), cell.end(), code); k != std::sregex_iterator(); ++k) {
      const std::string x = k->str();
      if (x[1] == '1' || x[1] == '3' || x[1] == '4' || x[1] == '9') codes.insert(x);
    }
  }
  return codes;
}

TEST(HlslCodes, EveryDocumentedCodeHasACase) {
  const std::set<std::string> documented = documentedHlslCodes();
  ASSERT_GE(documented.size(), 60u);  // the tables were found and read
  std::set<std::string> tested;
  for (const CodeCase& c : codeCases()) tested.insert(c.code);
  for (const std::string& c : documented)
    EXPECT_TRUE(tested.count(c) || unreachableCodes().count(c)) << c << " has no source in codeCases()";
  for (const std::string& c : tested) EXPECT_TRUE(documented.count(c)) << c << " is tested but not documented";
  for (const auto& [c, why] : unreachableCodes()) {
    EXPECT_TRUE(documented.count(c)) << c << " is listed as unreachable but not documented";
    EXPECT_FALSE(tested.count(c)) << c << " is listed as unreachable but has a case";
  }
}

}  // namespace
}  // namespace refx
