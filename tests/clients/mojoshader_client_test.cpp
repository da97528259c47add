// MojoShader (Debian's libmojoshader-dev) as a client of refx's HLSL compiler: every
// shader the compiler produces in the test suite, and the seed programs for the
// profiles they are written for, must parse and translate to GLSL without an error,
// and pass refx's own validator for their profile.
//
// The shaders: each [vertex shader] / [pixel shader] section of tests/hlsl/*.shader_test
// that the runner compiles and that is not expected to fail (compiled for the model
// the runner uses), the six lighting programs of data/hlsl for vs_1_1, vs_2_0 and
// ps_2_0, and data/hlsl/wood.fx for ps_2_0 in the white paper's dialect.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include <mojoshader.h>

#include "refx/hlsl/compiler.h"
#include "refx/scene/shader_test.h"
#include "refx/shader/disassembler.h"
#include "refx/shader/validator.h"

namespace refx {
namespace {

struct ClientCase {
  std::string name;      // gtest name: letters, digits and '_'
  std::string where;     // file:line or file, for messages
  std::string source;
  std::string fileName;  // as the compiler names it in diagnostics
  hlsl::CompileOptions options;
  bool mayNotCompile = false;  // a notimpl section: checked only when it compiles
};

// gtest prints a parameter with this instead of its bytes.
void PrintTo(const ClientCase& k, std::ostream* os) { *os << k.where << " " << k.options.profile; }

std::string identifier(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

std::string readFile(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return {};
  std::string s;
  char buf[4096];
  for (size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) s.append(buf, n);
  std::fclose(f);
  return s;
}

std::vector<ClientCase> shaderTestCases() {
  std::vector<ClientCase> cases;
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(std::string(REFX_TEST_DIR) + "/hlsl"))
    if (e.path().extension() == ".shader_test") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const auto& path : files) {
    const scene::ShaderTestFile file = scene::loadShaderTest(path.string());
    for (const scene::ShaderCompilation& c : scene::listShaderCompilations(file)) {
      if (c.mustFail) continue;
      ClientCase k;
      k.name = identifier(path.stem().string() + "_line" + std::to_string(c.line) + "_" + c.options.profile);
      k.where = path.filename().string() + ":" + std::to_string(c.line);
      k.source = c.source;
      k.fileName = path.string();
      k.options = c.options;
      k.mayNotCompile = c.notImplemented;
      cases.push_back(std::move(k));
    }
  }
  return cases;
}

std::vector<ClientCase> seedCases() {
  std::vector<ClientCase> cases;
  const std::string dir = std::string(REFX_DATA_DIR) + "/hlsl/";
  for (const char* program : {"ambient", "diffuse", "specular", "self_shadow", "bump", "point_light"}) {
    for (auto [profile, entry] : {std::pair{"vs_1_1", "VS"}, {"vs_2_0", "VS"}, {"ps_2_0", "PS"}}) {
      ClientCase k;
      k.name = identifier(std::string("seed_") + program + "_" + profile);
      k.where = std::string(program) + ".hlsl";
      k.fileName = dir + program + ".hlsl";
      k.source = readFile(k.fileName);
      k.options.profile = profile;
      k.options.entry = entry;
      cases.push_back(std::move(k));
    }
  }
  ClientCase wood;
  wood.name = "seed_wood_ps_2_0";
  wood.where = "wood.fx";
  wood.fileName = dir + "wood.fx";
  wood.source = readFile(wood.fileName);
  wood.options.profile = "ps_2_0";
  wood.options.entry = "Wood";
  wood.options.compatibility = true;
  cases.push_back(std::move(wood));
  return cases;
}

// MojoShader's messages: "byte offset N: text" per error.
std::string mojoErrors(const MOJOSHADER_parseData* pd) {
  std::string s;
  for (int i = 0; i < pd->error_count; ++i) {
    const MOJOSHADER_error& e = pd->errors[i];
    s += "  ";
    if (e.error_position >= 0) s += "byte offset " + std::to_string(e.error_position) + ": ";
    s += e.error ? e.error : "(no message)";
    s += "\n";
  }
  return s;
}

class MojoShaderClient : public testing::TestWithParam<ClientCase> {};

TEST_P(MojoShaderClient, ParsesAndValidates) {
  const ClientCase& k = GetParam();
  ASSERT_FALSE(k.source.empty()) << k.where << ": empty or unreadable";
  const hlsl::CompileResult r = hlsl::compile(k.source, k.fileName, k.options);
  if (!r.ok() && k.mayNotCompile) GTEST_SKIP() << k.where << " is marked notimpl and does not compile";
  ASSERT_TRUE(r.ok()) << k.where << " for " << k.options.profile << " does not compile:\n" << r.messages();
  const std::string listing = shader::disassemble(r.tokens);

  // refx's validator, for the profile the shader was compiled for.
  for (const Diagnostic& d : shader::validate(r.shader))
    ADD_FAILURE() << k.where << " " << k.options.profile << ": validator: " << d.message << "\n" << listing;

  // MojoShader, translating to GLSL.
  const MOJOSHADER_parseData* pd =
      MOJOSHADER_parse(MOJOSHADER_PROFILE_GLSL, "main", reinterpret_cast<const unsigned char*>(r.tokens.data()),
                       unsigned(r.tokens.size() * sizeof(uint32_t)), nullptr, 0, nullptr, 0, nullptr, nullptr, nullptr);
  EXPECT_EQ(pd->error_count, 0) << k.where << " " << k.options.profile << ": MojoShader "
                                << MOJOSHADER_version() << " reports:\n"
                                << mojoErrors(pd) << "refx disassembly:\n"
                                << listing;
  if (pd->error_count == 0) {
    // It read the version token as refx wrote it and produced a program.
    const bool vertex = k.options.profile[0] == 'v';
    EXPECT_EQ(pd->shader_type, vertex ? MOJOSHADER_TYPE_VERTEX : MOJOSHADER_TYPE_PIXEL) << k.where;
    EXPECT_EQ(pd->major_ver, k.options.profile[3] - '0') << k.where;
    EXPECT_GT(pd->output_len, 0) << k.where;
    EXPECT_NE(pd->output, nullptr) << k.where;
  }
  MOJOSHADER_freeParseData(pd);
}

std::string caseName(const testing::TestParamInfo<ClientCase>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(ShaderTests, MojoShaderClient, testing::ValuesIn(shaderTestCases()), caseName);
INSTANTIATE_TEST_SUITE_P(Seeds, MojoShaderClient, testing::ValuesIn(seedCases()), caseName);

// The harness itself: the suite's files are found and yield shaders, so an empty
// list cannot pass silently.
TEST(MojoShaderClientCases, CoverTheSuite) {
  const std::vector<ClientCase> cases = shaderTestCases();
  EXPECT_GE(cases.size(), 100u);
  bool vertex = false;
  for (const ClientCase& k : cases) vertex = vertex || k.options.profile[0] == 'v';
  EXPECT_TRUE(vertex);
  EXPECT_EQ(seedCases().size(), 19u);
}

// The check can fail: MojoShader reports an opcode that does not exist (0x0fff), a
// version token of no shader type, and a mov whose source token is the end token.
TEST(MojoShaderClientCases, ReportsBrokenBytecode) {
  for (const std::vector<uint32_t>& tokens : {std::vector<uint32_t>{0xffff0200, 0x00000fff, 0x0000ffff},
                                              std::vector<uint32_t>{0xabcd0200, 0x0000ffff},
                                              std::vector<uint32_t>{0xffff0200, 0x02000001, 0x800f0800, 0x0000ffff}}) {
    const MOJOSHADER_parseData* pd =
        MOJOSHADER_parse(MOJOSHADER_PROFILE_GLSL, "main", reinterpret_cast<const unsigned char*>(tokens.data()),
                         unsigned(tokens.size() * sizeof(uint32_t)), nullptr, 0, nullptr, 0, nullptr, nullptr, nullptr);
    EXPECT_GT(pd->error_count, 0) << std::hex << tokens[0] << " " << tokens[1];
    MOJOSHADER_freeParseData(pd);
  }
}

}  // namespace
}  // namespace refx
