// Validator: the driver and its entry points (codes, every violation reported,
// requireValid, device versions, robustness) and the seeds' shaders as a whole. The
// rules themselves are tested per check in validate_<check>_test.cpp, the codes in
// validator_codes_test.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

// ---- the seeds' shaders (valid as written) ---------------------------------------

TEST(ValidatorSeeds, RacorXPixelShadersAreValid) {
  // RacorX6 diffDot3.psh and diffDot314.psh
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\ndp3 r1, t1_bx2, v0_bx2\nmul r0,t0, r1"));
  EXPECT_TRUE(isValid("ps.1.4\ntexld r0, t0\ntexld r1, t0\ndp3 r2, r1_bx2, v0_bx2\nmul r0, r0, r2"));
  // RacorX7 specular by four muls
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\ndp3 r0,t1_bx2,v1_bx2\nmul r1,r0,r0\nmul r0,r1,r1\n"
                      "mul r1,r0,r0\nmul r0,r1,r1\nmul r0,t0,r0"));
  // RacorX8 table lookup, both versions
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntexm3x2pad t1, t0_bx2\ntexm3x2tex t2, t0_bx2\ntex t3\nmul r0,t2,t3"));
  EXPECT_TRUE(isValid("ps.1.4\ntexld r0, t0\ntexcrd r1.rgb, t1\ndp3 r1.rg, r1, r0_bx2\nphase\n"
                      "texld r3, t0\ntexld r2, r1\nmul r0, r2, r3"));
  // RacorX9 both versions
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\ndp3 r0,t1_bx2,v1_bx2\nmul r1,r0,r0\nmul r0,r1,r1\n"
                      "mul r1,r0,r0\nmul r0,r1,r1\ndp3 r1, t1_bx2, v0_bx2\nmad r0, t0, r1, r0"));
  EXPECT_TRUE(isValid("ps.1.4\ntexld r1, t0\ntexcrd r4.rgb, t2\ndp3 r4.rg, r4_bx2, r1_bx2\nmov r2, r1\n"
                      "phase\ntexld r0, t0\ntexld r1, r4\ndp3 r3, r2_bx2, v0_bx2\nmad r0, r0, r3, r1.a"));
  // RacorX10 point light and SpecDot3
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\nadd r0, 1-t0, -t1.a"));
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\ntexm3x2pad t2, t1_bx2\ntexm3x2tex t3, t1_bx2\n"
                      "mul r1.rgb, t3, t0\n+mul r1.a, t0.a, t3.a\nadd r0, r1.a, r1"));
  // RacorX11 diffCubeMap and specular
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\ntex t2\ndp3 r1, t2_bx2, t1_bx2\nmul r0, t0, r1"));
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\ntexm3x2pad t2, t1_bx2\ntexm3x2tex t3, t1_bx2\nmul r0, t0.a, t3.a"));
  // RacorX12 (ps_1_2 texdp3tex)
  EXPECT_TRUE(isValid("ps.1.2\ntex t0\ntex t1\ntex t2\ntexdp3tex t3, t1_bx2\ndp3 r0, t2_bx2, t1_bx2\n"
                      "mul r1.rgb, t0, r0\n+mul r1.a, t0.a, t3.a\nadd r0, r1, r1.a"));
  // RacorX13 and the three RacorX14 shaders
  EXPECT_TRUE(isValid("ps.1.4\ntexld r1, t1\ntexld r0, t0\ntexcrd r3.rgb, t2\ndp3 r1.rgb, r1_bx2, r0_bx2\n"
                      "dp3 r4.rgb, r3, r0_bx2\nphase\ntexld r2, t0\ntexld r3, r4\ntexld r4, t4\ntexld r5, t5\n"
                      "add r5, 1-r4, -r5.a\nmul r1.a, r2.a, r3.a\n+mul r1.rgb, r1, r2\nadd r0, r1.a, r1\nmul r0, r0, r5"));
  EXPECT_TRUE(isValid("ps.1.4\ntexld r1, t1\ntexld r0, t0\ntexcrd r3.rgb, t2\ntexld r4, t5\n"
                      "dp3 r1.rgb, r1_bx2, r0_bx2\ndp3 r5.rgb, r3, r0_bx2\nmov r0.r, r4.a\nphase\n"
                      "texld r2, t0\ntexld r3, r5\ntexld r4, t4\nadd r0, 1-r4, -r0.r\nmul r1.a, r2.a, r3.a\n"
                      "+mul r1.rgb, r1, r2\nadd r5, r1.a, r1\nmul r0, r5, r0"));
  EXPECT_TRUE(isValid("ps.1.4\ntexld r1, t1\ntexld r0, t0\ntexld r5, t2\ntexld r4, t5\n"
                      "dp3 r1.rgb, r1_bx2, r0_bx2\ndp3 r5.rgb, r5, r0_bx2\nmov r0.r, r4.a\nphase\n"
                      "texld r2, t0\ntexld r3, r5\ntexld r4, t4\nadd r0, 1-r4, -r0.r\nmul r1.a, r2.a, r3.a\n"
                      "+mul r1.rgb, r1, r2\nadd r5, r1.a, r1\nmul r0, r5, r0"));
  EXPECT_TRUE(isValid("ps.1.4\ntexld r0, t0\ntexld r5, t2\ntexld r4, t5\ndp3 r5.rgb, r5, r0_bx2\n"
                      "mov r1.r, r4.a\nphase\ntexld r2, t0\ntexld r3, r5\ntexld r4, t4\ntexld r5, t1\n"
                      "dp3 r5.rgb, r5_bx2, r0_bx2\nadd r4, 1-r4, -r1.r\nmul r1.a, r2.a, r3.a\n"
                      "+mul r1.rgb, r5, r2\nadd r3, r1.a, r1\nmul r0, r3, r4"));
}

TEST(ValidatorSeeds, PaperShadersAreValid) {
  // Per-pixel lighting paper: diffuse, multiply-based specular, BRDF, hemisphere fragment.
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\ndp3_sat r1,t1_bx2,v0_bx2\nmul r0,t0, r1"));
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\ndp3_sat r0,t1_bx2,v1_bx2\nmul r1,r0,r0\nmul r0,r1,r1\n"
                      "mul r1,r0,r0\nmul r0,r1,r1\nmul r0,r0,t0"));
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\ntex t2\ntex t3\nmul r0,t0,t1\nmul r0,r0,t2\nmul r0,r0,t3\nmul r0,r0,v0"));
  EXPECT_TRUE(isValid("ps.1.1\ntex t0\ntex t1\ndp3_d2_sat r0,v0_bx2,t0_bx2\nadd r0,r0,c5\nlrp r0,r0,c1,c2\nmul r0,r0,t1"));
  // Vertex shaders: BRDF, diffuse, emboss, hemisphere (D3D8 style, no dcl).
  EXPECT_TRUE(isValid(R"(vs.1.1
    m4x4 oPos, v0, c4
    m4x4 r4,v0,c0
    m3x3 r0,v3,c0
    m3x3 r1,v8,c0
    mul r2,-r1.zxyw,r0.yzxw
    mad r2,-r1.yzxw,r0.zxyw,-r2
    add r4.xyz,-r4.xyz,c10
    dp3 r5.x,r4.xyz,r4.xyz
    rsq r5.x,r5.x
    mul r4.xyz,r5.xxx,r4.xyz
    add r5.xyz,r4.xyz,-c16
    dp3 r6.x,r5.xyz,r5.xyz
    rsq r6.x,r6.x
    mul r5.xyz,r6.xxx,r5.xyz
    dp3 oT0.x,r4,r1
    dp3 oT0.y,r4,r2
    dp3 oT0.z,r4,r0
    dp3 oT1.x,-c16,r1
    dp3 oT1.y,-c16,r2
    dp3 oT2.z,-c16,r0
    dp3 oT2.x,r5,r1
    dp3 oT2.y,r5,r2
    dp3 oT2.z,r5,r0
    mov oT3.xy,v7.xy
    mov oD0,c9)"));
  EXPECT_TRUE(isValid(R"(vs.1.1
    m4x4 oPos, v0,c8
    m3x3 r3, v8, c0
    m3x3 r5, v3, c0
    mul r0,r3.zxyw,r5.yzxw
    mad r4,r3.yzxw,r5.zxyw,-r0
    dp3 r6.x,r3,c12
    dp3 r6.y,r4,c12
    mul r1.xy,  r6.xy, -c24.xy
    mov oT0.xy, v7.xy
    add oT1.xy, v7.xy,  r1.xy
    dp3 oD0.xyz,v3.xyz,c12.xyz)"));
  EXPECT_TRUE(isValid(R"(vs.1.1
    m4x4 oPos,v0,c8
    m3x3 r0, v3,c0
    dp3 r0,r0,c40
    mov r1,c33
    mad r0,r0,c33,r1
    mov r1,c42
    sub r1,c41,r1
    mad r0,r1,r0,c42
    sub r1,c44,v7.zzz
    mul r0,r0,r1
    mul oD0,r0,c43)"));
  // RacorX10 point light vertex shader.
  EXPECT_TRUE(isValid("vs.1.1\nm4x4 oPos, v0, c8\nm4x4 r2, v0, c0\nadd r10, r2, c12\nmul r10, r10, c33.x\n"
                      "mad r10, r10, c33.yyyy, c33.yyyy\nmov oT0.xy, r10.xy\nmov oT1.x, r10.z"));
}

// ---- entry points ----------------------------------------------------------------

TEST(Validator, UnsupportedVersion) {
  Shader s;
  s.version = {ShaderType::Pixel, 4, 0};
  auto d = validate(s);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0].message, "ps_4_0 is not a supported shader version");
  EXPECT_EQ(d[0].code, "V1000");
  // ps_1_0 is read as ps_1_1.
  EXPECT_TRUE(isValid("ps_1_0\ntex t0\nmov r0, t0"));
}

TEST(Validator, DeviceVersion) {
  const Version ps14{ShaderType::Pixel, 1, 4}, ps11{ShaderType::Pixel, 1, 1}, ps2x{ShaderType::Pixel, 2, 1};
  const Version vs11{ShaderType::Vertex, 1, 1};
  EXPECT_EQ(checkDeviceVersion(ps14, 0xFFFF0101, "dx8"), "ps_1_4 needs PixelShaderVersion 1.4, dx8 has 1.1");
  EXPECT_EQ(checkDeviceVersion(ps11, 0xFFFF0104, "dx81"), "");
  EXPECT_EQ(checkDeviceVersion(ps14, 0xFFFF0200, "dx9"), "");
  EXPECT_EQ(checkDeviceVersion(ps2x, 0xFFFF0200, "dx9"), "ps_2_x needs PixelShaderVersion above 2.0, dx9 has 2.0");
  EXPECT_EQ(checkDeviceVersion(ps2x, 0xFFFF0300, "dx9-sm3"), "");
  EXPECT_EQ(checkDeviceVersion(vs11, 0xFFFE0000, "dx7"), "vs_1_1 needs VertexShaderVersion 1.1, dx7 has none");
}

TEST(Validator, RequireValidThrowsLocatedError) {
  Shader s = assemble("ps_1_1\ntex t0\nmov r0, r1", "shader.psh");
  try {
    requireValid(s, "shader.psh");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "shader.psh:3:1: error V1930: r1 is read before it is written");
  }
  EXPECT_NO_THROW(requireValid(read("ps_1_1\ntex t0\nmov r0, t0"), "ok.psh"));
}

TEST(Validator, MalformedShadersDoNotCrash) {
  // Decoded bytecode can hold anything: out-of-range indices, missing operands.
  Shader s;
  s.version = {ShaderType::Pixel, 1, 1};
  Instruction in;
  in.opcode = Opcode::Mov;
  in.hasDst = true;
  in.dst.type = RegType::Temp;
  in.dst.index = 2047;
  in.srcCount = 1;
  in.src[0].type = RegType::Label;
  in.src[0].index = 9999;
  s.instructions.push_back(in);
  Instruction bad;
  bad.opcode = Opcode(200);  // no such opcode
  s.instructions.push_back(bad);
  Instruction loop;
  loop.opcode = Opcode::EndLoop;
  s.instructions.push_back(loop);
  EXPECT_FALSE(validate(s).empty());
  for (const VersionRules* r : allVersionRules()) {
    s.version = r->version;
    EXPECT_FALSE(validate(s).empty()) << r->name;
  }
}

TEST(Validator, RandomShadersDoNotCrash) {
  // Deterministic pseudo-random instructions: any opcode, register type, index,
  // modifier, swizzle and flag combination must give diagnostics, never a crash.
  uint32_t state = 12345;
  auto next = [&] { return state = state * 1664525u + 1013904223u; };
  const Opcode ops[] = {Opcode::Mov, Opcode::Add, Opcode::Mad, Opcode::Tex, Opcode::TexCoord,
                        Opcode::TexM3x2Pad, Opcode::TexM3x3Pad, Opcode::TexM3x3Spec, Opcode::Rep,
                        Opcode::EndRep, Opcode::Loop, Opcode::EndLoop, Opcode::If, Opcode::IfC,
                        Opcode::Else, Opcode::EndIf, Opcode::Call, Opcode::CallNZ, Opcode::Label,
                        Opcode::Ret, Opcode::Dcl, Opcode::Def, Opcode::Phase, Opcode::M4x4,
                        Opcode::SinCos, Opcode::Bem, Opcode::TexKill, Opcode::SetP, Opcode::TexLdl,
                        Opcode::Break, Opcode::Cnd, Opcode::Cmp, Opcode::Dp4, Opcode(9999)};
  for (int n = 0; n < 3000; ++n) {
    Shader s;
    s.version = allVersionRules()[next() % allVersionRules().size()]->version;
    int count = int(next() % 12);
    for (int i = 0; i < count; ++i) {
      Instruction in;
      in.opcode = ops[next() % std::size(ops)];
      in.coissue = next() % 4 == 0;
      in.predicated = next() % 6 == 0;
      in.hasDst = next() % 5 != 0;
      in.dst.type = RegType(next() % 20);
      in.dst.index = uint16_t(next() % 40);
      in.dst.writeMask = uint8_t(next() % 16);
      in.dst.resultMod = uint8_t(next() % 8);
      in.dst.shift = int8_t(int(next() % 16) - 8);
      in.dst.relative = next() % 8 == 0;
      in.srcCount = uint8_t(next() % 5);
      for (int k = 0; k < in.srcCount; ++k) {
        SrcParam& p = in.src[k];
        p.type = RegType(next() % 20);
        p.index = uint16_t(next() % 3000);
        p.swizzle = uint8_t(next());
        p.mod = SrcMod(next() % 16);
        p.relative = next() % 8 == 0;
        p.rel.type = next() % 2 ? RegType::Addr : RegType::Loop;
        p.rel.component = uint8_t(next() % 4);
      }
      in.literal = {next(), next(), next(), next()};
      in.textureType = TextureType(next() % 6);
      in.pos = {i + 2, 1};
      s.instructions.push_back(in);
    }
    validate(s);
    countSlots(s);
  }
  SUCCEED();
}

TEST(VersionRules, TablesCoverEveryVersion) {
  const char* names[] = {"vs_1_1", "vs_2_0", "vs_2_x", "vs_3_0", "ps_1_1", "ps_1_2",
                         "ps_1_3", "ps_1_4", "ps_2_0", "ps_2_x", "ps_3_0"};
  auto all = allVersionRules();
  ASSERT_EQ(all.size(), std::size(names));
  for (size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(all[i]->name, names[i]);
    EXPECT_EQ(findVersionRules(all[i]->version), all[i]);
  }
  // Register counts the executor also relies on (registers-and-limits.md §1–2).
  auto count = [](Version v, RegType t) {
    const RegisterRule* r = findRegisterRule(*findVersionRules(v), t);
    return r ? int(r->count) : 0;
  };
  EXPECT_EQ(count({ShaderType::Pixel, 1, 1}, RegType::Temp), 2);
  EXPECT_EQ(count({ShaderType::Pixel, 1, 4}, RegType::Temp), 6);
  EXPECT_EQ(count({ShaderType::Pixel, 1, 4}, RegType::Texture), 6);
  EXPECT_EQ(count({ShaderType::Pixel, 2, 0}, RegType::Const), 32);
  EXPECT_EQ(count({ShaderType::Pixel, 3, 0}, RegType::Const), 224);
  EXPECT_EQ(count({ShaderType::Pixel, 3, 0}, RegType::Input), 10);
  EXPECT_EQ(count({ShaderType::Vertex, 1, 1}, RegType::Const), 96);
  EXPECT_EQ(count({ShaderType::Vertex, 3, 0}, RegType::Temp), 32);
  EXPECT_EQ(count({ShaderType::Vertex, 3, 0}, RegType::Sampler), 4);
  EXPECT_EQ(count({ShaderType::Vertex, 1, 1}, RegType::ConstInt), 0);
}

// Every violation is reported, each with its code and location, not only the first.
// ps_1_1 (registers-and-limits.md): t4 does not exist (4 texture registers, t0..t3)
// -> V1102 at line 2; ps_1_1 has no dp4 (it arrives in ps_1_2) -> V1002 at line 3;
// r1 is read with nothing written to it -> V1930 at line 4.
TEST(Validator, ReportsEveryViolationWithItsCode) {
  const Shader s = read("ps_1_1\ntex t4\ndp4 r0, v0, v0\nmov r0, r1\n");
  const std::vector<Diagnostic> d = validate(s);
  ASSERT_EQ(d.size(), 3u) << joined(messages(s));
  EXPECT_EQ(d[0].code, "V1102");
  EXPECT_EQ(d[0].where.line, 2);
  EXPECT_EQ(d[1].code, "V1002");
  EXPECT_EQ(d[1].where.line, 3);
  EXPECT_EQ(d[2].code, "V1930");
  EXPECT_EQ(d[2].where.line, 4);
  for (const Diagnostic& x : d) EXPECT_EQ(x.severity, Severity::Error);
  // requireValid lists all three, one per line, the first as before with its code.
  try {
    requireValid(s, "three.psh");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "three.psh:2:1: error V1102: t4 is out of range: ps_1_1 has 4 texture registers (t0..t3)\n"
                 "three.psh:3:1: error V1002: dp4 is not a ps_1_1 instruction\n"
                 "three.psh:4:1: error V1930: r1 is read before it is written");
  }
  // The sink form carries the file name in every location.
  DiagnosticSink sink;
  validate(s, sink, "three.psh");
  ASSERT_EQ(sink.errorCount(), 3);
  EXPECT_EQ(sink.all()[2].str(), "three.psh:4:1: error V1930: r1 is read before it is written");
}

// ---- shaders the seeds describe as impossible ------------------------------------

// The seeds' shaders as shipped in data/shaders: every complete shader that assembles
// is valid, except the printed table-lookup shader that reads t3 without sampling it.
TEST(ValidatorSeeds, DataShadersAreValid) {
  namespace fs = std::filesystem;
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(REFX_DATA_DIR) / "shaders")) {
    std::string name = entry.path().filename().string();
    std::string ext = entry.path().extension().string();
    if ((ext != ".psh" && ext != ".vsh") || name.find("_fragment") != std::string::npos) continue;
    std::ifstream f(entry.path());
    std::stringstream ss;
    ss << f.rdbuf();
    Shader shader;
    try {
      shader = assemble(ss.str(), name);
    } catch (const Error&) {
      continue;  // printed typos (a page number, a missing version) are the assembler's to report
    }
    ++checked;
    if (name == "paper_specular_table.psh")
      EXPECT_TRUE(hasError(shader, "t3 is read before it is written (no texture instruction writes it)"));
    else
      EXPECT_TRUE(messages(shader).empty()) << name << ":\n" << joined(messages(shader));
  }
  EXPECT_GE(checked, 30);
}

// The assembler's test shaders (every version, every instruction family) are valid.
TEST(ValidatorSeeds, AssemblerTestShadersAreValid) {
  namespace fs = std::filesystem;
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(REFX_TEST_DIR) / "shader" / "asm")) {
    std::string ext = entry.path().extension().string();
    if (ext != ".psh" && ext != ".vsh") continue;
    std::ifstream f(entry.path());
    std::stringstream ss;
    ss << f.rdbuf();
    Shader shader = assemble(ss.str(), entry.path().filename().string());
    EXPECT_TRUE(messages(shader).empty()) << entry.path() << ":\n" << joined(messages(shader));
    ++checked;
  }
  EXPECT_GE(checked, 10);
}

// Each file in asm_invalid/ starts with "; expect: <message>".
TEST(ValidatorSeeds, ShadersTheTextsRejectAreRejected) {
  namespace fs = std::filesystem;
  fs::path dir = fs::path(REFX_TEST_DIR) / "shader" / "asm_invalid";
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    std::ifstream f(entry.path());
    std::stringstream ss;
    ss << f.rdbuf();
    std::string text = ss.str();
    std::string first = text.substr(0, text.find('\n'));
    const std::string tag = "; expect: ";
    ASSERT_EQ(first.compare(0, tag.size(), tag), 0) << entry.path();
    std::string expected = trim(first.substr(tag.size()));
    EXPECT_TRUE(hasError(text, expected)) << entry.path();
    ++files;
  }
  EXPECT_GE(files, 5);
}

}  // namespace
}  // namespace refx::shader
