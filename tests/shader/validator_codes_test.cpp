// Validator codes: every code the validator reports (src/shader/validate/, the driver in
// validator.cpp) has a row in docs/diagnostics.md ("Shader validator") and every row a
// code; and every code has a shader here that triggers it, matched on the code. The
// rule each shader breaks is written next to it; the rules themselves are tested in
// validate_<check>_test.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

struct CodeCase {
  std::string code;
  Shader shader;
  ValidationCaps caps;
};

Shader fromTokens(const std::vector<uint32_t>& tokens) { return decode(tokens); }

std::string repeat(const std::string& s, int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += s;
  return out;
}

std::vector<CodeCase> codeCases() {
  const std::string vs20 = kVs20Head;
  const std::string vs30 = "vs_3_0\ndcl_position v0\ndcl_position o0\nmov o0, v0\n";
  std::vector<CodeCase> c;
  auto add = [&](const char* code, Shader s, ValidationCaps caps = {}) { c.push_back({code, std::move(s), caps}); };

  // Opcodes.
  Shader ps40;
  ps40.version = {ShaderType::Pixel, 4, 0};
  add("V1000", ps40);  // no D3D9 ps_4_0
  add("V1001", readRaw("ps_1_1\ntex t0\ntexm3x3diff t1, t0\nmov r0, t0"));  // reserved opcode
  add("V1002", read("ps_1_1\ntex t0\ndp4 r0, t0, t0"));                     // dp4 from ps_1_2
  // mul with specific-control bits 0x39 (bits 23:16 are 0 for arithmetic instructions).
  add("V1003", fromTokens({0xFFFF0101, 0x00000042, 0xB00F0000, 0x00390005, 0x800F0000, 0xB0E40000,
                           0x90E40000, 0x0000FFFF}));
  // mov oPos, v0 with result-modifier bit 23 (only _sat 1, _pp 2, _centroid 4 exist).
  add("V1004", fromTokens({0xFFFE0101, 0x00000001, 0xC08F0000, 0x90E40000, 0x0000FFFF}));
  ValidationCaps noFlow;
  noFlow.ps2xFlowControl = false;  // rep in ps_2_x needs the static flow-control caps
  add("V1005", read("ps_2_x\ndefi i0, 2, 0, 0, 0\nrep i0\nadd r0, c0, c0\nendrep\nmov oC0, r0"), noFlow);
  Shader fiveSources = read("vs_1_1\nmov oPos, v0");
  fiveSources.instructions[0].srcCount = 5;  // instructions have at most 4 sources
  add("V1006", fiveSources);

  // Registers.
  add("V1101", readRaw("vs_1_1\nmov oPos, v0\nmov oC0, v0"));   // no oC# in vertex shaders
  add("V1102", read("vs_1_1\nmov oPos, c96"));                   // vs_1_1: c0..c95
  add("V1103", read("vs_1_1\nmov v0, c0\nmov oPos, v0"));        // inputs are read-only
  add("V1104", read("vs_1_1\nmov oPos, oD0"));                   // outputs are write-only
  add("V1105", readRaw("ps_2_0\ndcl t0\nmov oC0, c[a0.x + 1]"));  // ps_2_0 has no relative addressing
  add("V1106", read("vs_1_1\nm4x4 oPos, v0, c94"));              // c94..c97 passes c95
  add("V1107", read(vs20 + "add r0, v0, c[aL + 2]"));            // aL outside loop … endloop
  add("V1108", readRaw("ps_2_0\ndcl_2d s0\nmov r0, s0\nmov oC0, r0"));  // s# only as texld's sampler
  add("V1109", read(vs30 + "mov p0, c0"));                       // p0 is written by setp
  add("V1110", read("ps_1_1\nmad r0, c0, c1, c2"));              // ps_1_1: 2 constants per instruction

  // Modifiers, masks and swizzles.
  add("V1201", read("ps_1_1\ntex t0\nmul_x8 r0, t0, t0"));       // ps_1_1 shifts: _x2 _x4 _d2
  Shader centroid = read("ps_2_0\ndcl t0\nmov r0, t0\nmov oC0, r0");
  centroid.instructions[1].dst.resultMod = ResultCentroid;       // _centroid only on dcl
  add("V1202", centroid);
  add("V1203", read(vs30 + "frc_sat r0, v0\nmov o0, r0"));       // frc takes no _sat
  add("V1204", read("ps_1_1\ntex t0\nmov r0, t0\nmov r0.rg, t0"));  // ps_1_1 masks: .rgba .rgb .a
  add("V1205", read("ps_1_1\ntex t0\nmov r0, t0_x2"));           // _x2 source modifier from ps_1_4
  add("V1206", read("ps_1_4\ntexld r0, t0\nadd r0, r0, -c0"));   // ps_1_4 constants take no modifier
  add("V1207", read("ps_1_1\ntex t0\nmov r0, t0.g"));            // ps_1_1 selectors: .a, .b

  // Order and ps_1_1 – ps_1_3 texture sequences.
  add("V1301", read("ps_1_1\ntex t0\ndef c0, 1, 0, 0, 1\nmul r0, t0, c0"));  // def first
  add("V1302", read("vs_2_0\ndcl_position v0\nmov oPos, v0\ndcl_texcoord0 v1\nmov oT0, v1"));  // dcl first
  add("V1303", read("ps_1_1\ntex t0\nmov r0, t0\ntex t1\nmul r0, r0, t1"));  // texture before arithmetic
  add("V1310", read("ps_1_1\ntex t0\ntexm3x2pad t1, t0\nmov r0, t0"));       // pad without texm3x2tex
  add("V1311", read("ps_1_1\ntex t0\ntexm3x2tex t1, t0\nmov r0, t1"));       // texm3x2tex without pad
  add("V1312", read("ps_1_1\ntex t0\ntexm3x2pad t1, t0\ntexm3x2tex t2, t0\nmul r0, t2, t1"));  // pad holds no color
  add("V1313", read("ps_1_1\ntex t0\ntexbem t1, t0\nadd r0, t1, t0"));      // texbem's source is reserved
  add("V1314", readRaw("ps_1_1\ntex r0\nmov r0, r0"));                        // tex writes t#
  add("V1315", read("ps_1_1\ntex t1\ntex t0\nmul r0, t0, t1"));              // t# in increasing order
  add("V1316", readRaw("ps_1_1\ntex t0\ntexm3x3pad t1, t0\ntexm3x3pad t2, t0\ntexm3x3spec t3, t0, t0\nmov r0, t3"));
  add("V1317", read("ps_1_1\ntex t0\ntex t1\ntexbem t1, t1\nmov r0, t1"));   // source below the destination
  add("V1318", read("ps_1_1\ntex t0\ntexbem t1, t0_bx2\nmov r0, t1"));       // no _bx2 on texbem in ps_1_1

  // ps_1_4.
  add("V1401", read("ps_1_4\ntexld r0, t0\nphase\ntexld r1, t1\nphase\nmov r0, r1"));  // one phase
  add("V1402", read("ps_1_4\ntexld r0, t0\nadd r0, r0, t1"));  // t# only for texld/texcrd
  add("V1403", read("ps_1_4\ntexld r0, t0\nmul r0, r0, v0\nphase\ntexld r1, r0\nmov r0, r1"));  // v# in phase 2
  add("V1404", read("ps_1_4\ntexld r0, t0\ntexld r1, t1\nbem r2.rg, r0, r1\nmov r0, r2"));  // bem in phase 1
  add("V1405", read("ps_1_4\ntexcrd r4.rgb, t0\nphase\ntexdepth r4\nmov r0, c0"));  // texdepth on r5
  add("V1406", readRaw("ps_1_4\ntexkill v0\nmov r0, c0"));      // texkill takes r# or t#
  add("V1407", read("ps_1_4\ntexld r0, t0\ntexld r0, t1\nmov r0, r0"));  // one texld per r# and phase
  add("V1408", read("ps_1_4\ntexcrd r0.rgb, t0_dw.xyw\nmov r0, r0"));   // texcrd _dw writes .rg
  add("V1409", read("ps_1_4\ntexld r0, t0.yxz\nmov r0, r0"));          // .xyz or .xyw only
  add("V1410", read("ps_1_4\ntexld r0, t0_dz\nmov r0, r0"));           // _dz on r#, _dw on t#
  add("V1411", read("ps_1_4\ntexld r0, t0\ntexld r1, r0\nmov r0, r1"));  // r# coordinates in phase 2
  add("V1412", read("ps_1_4\ntexcrd r0.rgb, t0\ntexcrd r1.rgb, t1\ntexcrd r2.rgb, t2\nphase\n"
                    "texld r3, r0_dz\ntexld r4, r1_dz\ntexld r5, r2_dz\nadd r0, r3, r4"));  // _dz twice

  // Co-issue.
  add("V1501", readRaw("vs_1_1\nmov oPos, v0\n+mov oD0, v0"));       // `+` only in ps_1_x
  add("V1502", read("ps_1_1\ntex t0\n+tex t1\nmov r0, t0"));         // only arithmetic pairs
  add("V1503", read("ps_1_1\ntex t0\n+mov r0.a, t0\nmov r0.rgb, t0"));  // nothing to pair with
  add("V1504", read("ps_1_2\ntex t0\ndp4 r0.rgb, t0, t0\n+mov r0.a, t0"));  // dp4 never pairs
  add("V1505", read("ps_1_1\ntex t0\nmov r0.rgb, t0\n+mov r0.rgb, t0"));  // .rgb + .a
  add("V1506", read("ps_1_4\ntexld r0, t0\nmov r1.rgb, r0\n+dp3 r1.a, r0, r0\nmov r0, r1"));  // dp3: color half

  // def and dcl.
  add("V1601", readRaw("vs_2_0\ndef r0, 1, 0, 0, 0\ndcl_position v0\nmov oPos, v0"));  // def writes c#
  // defi i0 with shift 4 and _pp on its destination.
  add("V1602", fromTokens({0xFFFE0200, 0x0200001F, 0x80000000, 0x900F0000, 0x05000030, 0xF42F0000, 4, 0, 1, 0,
                           0x03000014, 0xC00F0000, 0x90E40000, 0xA0E40000, 0x0000FFFF}));
  // defb b1 = 0x00100001: neither FALSE (0) nor TRUE (1).
  add("V1603", fromTokens({0xFFFE0200, 0x0200002F, 0xE00F0801, 0x00100001, 0x0000FFFF}));
  add("V1604", read("ps_1_1\ndef c0, 1.5, 0, 0, 0\nmov r0, c0"));     // ps_1_x constants in [-1, 1]
  add("V1605", readRaw("vs_2_0\ndefi i0, 300, 0, 1, 0\ndcl_position v0\nmov oPos, v0"));  // count ≤ 255
  add("V1610", read("vs_2_0\ndcl_position oPos\nmov oPos, c0"));     // vs_2_0 declares no outputs
  add("V1611", fromTokens(vs20WithDcl(0x80000000, 0x990F0000)));    // dcl with a shift
  add("V1612", fromTokens(vs20WithDcl(0x80000000, 0x90000000)));    // dcl with an empty mask
  add("V1613", read("ps_2_0\ndcl s0\nmov oC0, c0"));                 // a sampler needs a texture type
  add("V1614", readRaw("vs_2_0\ndcl_position_centroid v0\nmov oPos, v0"));  // _centroid: ps inputs only
  add("V1615", read("vs_2_0\ndcl_position v0\ndcl_normal v0\nmov oPos, v0"));  // declared twice
  add("V1616", fromTokens(vs20WithDcl(0x8000000E, 0x900F0000)));    // usage 14 > D3DDECLUSAGE_SAMPLE
  add("V1620", read("vs_2_0\ndcl_position v0\nmov oPos, v0\nmov oT0, v1"));  // v1 not declared
  add("V1621", read("ps_2_0\ndcl t0.xy\nmov r0, t0\nmov oC0, r0"));  // t0.zw not declared

  // Flow control and predication.
  add("V1701", read(vs20 + "(p0) add r0, v0, c0"));    // no predication in vs_2_0
  add("V1702", read(vs30 + "(p0) add r0, v0, c0"));    // p0 before setp
  add("V1703", read(vs20 + repeat("if b0\nendif\n", 17)));  // vs_2_0: 16 static flow instructions
  add("V1704", read(vs20 + "ret\nmov r0, v0"));        // code after main's ret
  add("V1705", read(vs20 + "callnz l0, i0\nret\nlabel l0\nret"));  // callnz takes b# or p0
  add("V1706", read(vs20 + "rep i0\nrep i0\nendrep\nendrep"));     // vs_2_0: rep depth 1
  add("V1707", read(vs20 + "endif"));                  // endif without if
  add("V1708", read(vs20 + "rep b0\nendrep"));         // rep takes i#
  add("V1709", read("vs_2_x\ndefi i0, 3, 0, 1, 0\ndcl_position v0\nmov oPos, v0\nbreak"));  // break outside a loop
  add("V1710", readRaw(vs20 + "call c0\nret"));        // call takes l#
  add("V1711", read(vs20 + "call l0\nret\nmov r0, v0\nlabel l0\nret"));  // label right after ret
  add("V1712", read(vs20 + "call l1\nret\nlabel l0\nret"));              // no label l1
  add("V1713", read(vs30 + "call l0\nret\nlabel l0\ncall l0\nret"));     // recursion

  // Instruction forms and sampling.
  add("V1801", read("vs_2_0\ndcl_position v0\nrcp r0, v0\nmov oPos, r0"));  // rcp reads one component
  add("V1802", read("vs_2_0\ndcl_position v0\nm3x3 r0.xyzw, v0, c0\nmov oPos, r0"));  // m3x3 writes .xyz
  add("V1803", read(vs30 + "sincos r0.xyz, v0.x"));     // sincos writes .x, .y or .xy
  add("V1804", read("vs_2_0\ndcl_position v0\ncrs r0.xyzw, v0, v0\nmov oPos, v0"));  // crs writes ⊆ .xyz
  add("V1805", read("vs_2_0\ndcl_position v0\nmov r0, v0\nnrm r0, r0\nmov oPos, r0"));  // nrm r0, r0
  add("V1806", read(vs30 + "mov r0, v0\npow r0, v0.x, r0.x\nmov o0, r0"));  // pow's exponent register
  add("V1807", readRaw("vs_2_0\ndcl_position v0\nmov r0, v0\nmov r2, v0\nsgn r1, r0, r2, r2\nmov oPos, r1"));
  add("V1808", read("vs_2_0\ndcl_position v0\nmov a0.x, v0.x\nmov oPos, c[a0.x]"));  // a0 by mova
  add("V1809", read("ps_1_1\ntex t0\ntex t1\nmov r1, t0\ncnd r0, r1.a, t0, t1"));  // cnd takes r0.a
  add("V1810", read("ps_1_2\ntex t0\ncmp r0, t0, r0, t0"));  // cmp never writes a source register
  add("V1820", read("ps_2_0\ndcl t0\ntexld r0, t0, s0\nmov oC0, r0"));  // s0 not declared
  add("V1821", readRaw("ps_2_0\ndcl t0\ndcl_2d s0\ntexld r0, t0, s0.x\nmov oC0, r0"));  // plain sampler
  add("V1822", read("ps_2_0\ndcl t0\ndcl_2d s0\ntexld r0.xy, t0, s0\nmov oC0, r0"));  // full mask
  add("V1823", read("ps_2_0\ndcl t0\ndcl_2d s0\ntexld r0, t0.yxzw, s0\nmov oC0, r0"));  // plain coordinates
  // ps_2_0: at most 4 levels of dependent reads; r3 -> r4 is the fifth.
  add("X5426", read("ps_2_0\ndcl t0\ndcl_2d s0\ntexld r0, t0, s0\ntexld r1, r0, s0\ntexld r2, r1, s0\n"
                    "texld r3, r2, s0\ntexld r4, r3, s0\nmov oC0, r4"));

  // Slots.
  add("V1901", read("ps_1_1\ntex t0\ntex t1\ntex t2\ntex t3\ntex t4\nmov r0, t3"));  // 4 texture instructions
  // vs_1_1: 1 + 32 × m4x4 (4 slots) = 129 > 128.
  add("V1902", read("vs_1_1\nmov oPos, v0\n" + repeat("m4x4 r0, v0, c0\n", 32)));
  add("V1903", read("ps_1_4\ntexld r0, t0\ntexld r1, t1\nbem r2.rg, r0, r1\nbem r3.rg, r0, r1\nphase\nmov r0, r2"));
  add("X5608", read("ps_1_1\ntex t0\n" + repeat("mul r0, t0, t0\n", 9)));  // 8 arithmetic instructions

  // Outputs and reads.
  add("V1910", read("ps_2_0\ndcl t0\nadd oC0, t0, t0"));        // ps_2_0 writes oC# by mov
  add("V1911", read("ps_2_0\ndcl t0\nmov oC0, -t0"));           // plain source
  add("V1912", read("ps_2_0\ndcl t0\nmov oC0.xyz, t0"));        // full mask
  add("V1913", read("ps_3_0\ndcl_texcoord0 v0\nif_gt v0.x, c0.x\nmov oC0, v0\nendif"));  // not in dynamic flow
  add("V1914", read("ps_2_0\ndcl t0\nmov oC0, t0\nmov oC0, t0"));  // once
  add("V1915", read("ps_2_0\ndcl t0\nmov r0, t0"));             // oC0 never written
  add("V1916", read("ps_2_0\ndcl t0\nmov oC0, t0\nmov oC2, t0"));  // oC1 skipped
  add("V1917", read(vs30 + "mov o1, v0"));                      // o1 not declared
  add("V1930", read("ps_1_1\ntex t0\nmov r0, r1"));             // r1 never written
  add("V1931", read("ps_1_4\ntexld r1, t0\nphase\nmov r0, r1.a"));  // alpha lost at the phase marker
  return c;
}

TEST(ValidatorCodes, EachCodeHasAShaderThatTriggersIt) {
  for (const CodeCase& c : codeCases()) EXPECT_TRUE(hasCode(c.shader, c.code, c.caps)) << c.code;
}

std::string readFile(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::set<std::string> codesIn(const std::string& text, const std::regex& re) {
  std::set<std::string> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it)
    out.insert((*it)[1].str());
  return out;
}

TEST(ValidatorCodes, DocumentedCodesAreTheSourceCodes) {
  namespace fs = std::filesystem;
  const fs::path root = fs::path(REFX_TEST_DIR).parent_path();
  // Codes in the source: string literals "V1xxx" / "X5xxx" of the checks and the driver.
  std::string source = readFile(root / "src" / "shader" / "validator.cpp");
  for (const auto& e : fs::directory_iterator(root / "src" / "shader" / "validate")) source += readFile(e.path());
  const std::set<std::string> inSource = codesIn(source, std::regex("\"((?:V1|X5)[0-9]{3})\""));
  ASSERT_GE(inSource.size(), 50u);

  // Rows of the "Shader validator" section: | V1000 | error | meaning |.
  const std::string doc = readFile(root / "docs" / "diagnostics.md");
  const size_t section = doc.find("## Shader validator");
  ASSERT_NE(section, std::string::npos);
  size_t next = doc.find("\n## ", section + 1);
  const std::string table = doc.substr(section, next == std::string::npos ? std::string::npos : next - section);
  const std::set<std::string> documented = codesIn(table, std::regex("\\n\\| ((?:V1|X5)[0-9]{3}) \\| error \\|"));

  for (const std::string& c : inSource) EXPECT_TRUE(documented.count(c)) << c << " has no row in docs/diagnostics.md";
  for (const std::string& c : documented) EXPECT_TRUE(inSource.count(c)) << c << " is documented but never reported";

  std::set<std::string> tested;
  for (const CodeCase& c : codeCases()) tested.insert(c.code);
  for (const std::string& c : inSource) EXPECT_TRUE(tested.count(c)) << c << " has no shader in codeCases()";
}

}  // namespace
}  // namespace refx::shader

// A compiler maps limit violations to "cannot map to the profile" (fxc's X4532) and the
// rest to internal errors: slots (X5608: ps_1_1 has 8 arithmetic slots) and flow-control
// depth (V1706) are limits; a read before a write (V1930) or a register beyond the file
// (V1102) is a form error.
TEST(ValidatorCodes, LimitViolationsAreTheLimitCodes) {
  EXPECT_TRUE(refx::shader::isLimitViolation("X5608"));
  EXPECT_TRUE(refx::shader::isLimitViolation("V1706"));
  EXPECT_TRUE(refx::shader::isLimitViolation("V1902"));
  EXPECT_FALSE(refx::shader::isLimitViolation("V1930"));
  EXPECT_FALSE(refx::shader::isLimitViolation("V1102"));
}
