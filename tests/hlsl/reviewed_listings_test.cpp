// The seeds' HLSL programs against their reviewed listings (tests/hlsl/listings): each
// listing was checked instruction by instruction against the HLSL, with the reasons
// written beside the instructions; a change in code generation shows up here as a
// listing to review again.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "refx/hlsl/compiler.h"
#include "refx/shader/disassembler.h"

namespace refx {
namespace {

std::vector<std::string> codeLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (size_t c = line.find("//"); c != std::string::npos) line.resize(c);
    const size_t b = line.find_first_not_of(" \t"), e = line.find_last_not_of(" \t\r");
    if (b != std::string::npos) lines.push_back(line.substr(b, e - b + 1));
  }
  return lines;
}

struct Listing {
  const char* file;
  const char* profile;
  const char* entry;
  bool compatibility;
};

class ReviewedListing : public ::testing::TestWithParam<Listing> {};

TEST_P(ReviewedListing, MatchesTheCompiledCode) {
  const Listing& l = GetParam();
  hlsl::CompileOptions o;
  o.profile = l.profile;
  o.entry = l.entry;
  o.compatibility = l.compatibility;
  const hlsl::CompileResult r = hlsl::compileFile(std::string(REFX_DATA_DIR) + "/hlsl/" + l.file, o);
  ASSERT_TRUE(r.ok()) << r.messages();
  std::string stem = l.file;
  stem = stem.substr(0, stem.find('.'));
  std::ifstream in(std::string(REFX_TEST_DIR) + "/hlsl/listings/" + stem + "." + l.profile + ".asm");
  ASSERT_TRUE(in) << "no reviewed listing for " << stem << " " << l.profile;
  std::ostringstream expected;
  expected << in.rdbuf();
  const std::vector<std::string> want = codeLines(expected.str());
  const std::vector<std::string> got = codeLines(shader::disassemble(r.shader, {}));
  EXPECT_EQ(got, want) << "compiled:\n" << shader::disassemble(r.shader, {});
}

constexpr Listing kListings[] = {
    {"ambient.hlsl", "vs_1_1", "VS", false},     {"ambient.hlsl", "ps_2_0", "PS", false},
    {"diffuse.hlsl", "vs_1_1", "VS", false},     {"diffuse.hlsl", "ps_2_0", "PS", false},
    {"specular.hlsl", "vs_1_1", "VS", false},    {"specular.hlsl", "ps_2_0", "PS", false},
    {"self_shadow.hlsl", "vs_1_1", "VS", false}, {"self_shadow.hlsl", "ps_2_0", "PS", false},
    {"bump.hlsl", "vs_1_1", "VS", false},        {"bump.hlsl", "ps_2_0", "PS", false},
    {"point_light.hlsl", "vs_1_1", "VS", false}, {"point_light.hlsl", "ps_2_0", "PS", false},
    {"wood.fx", "ps_2_0", "Wood", true},
};

INSTANTIATE_TEST_SUITE_P(Seeds, ReviewedListing, ::testing::ValuesIn(kListings),
                         [](const ::testing::TestParamInfo<Listing>& info) {
                           std::string n = info.param.file;
                           return n.substr(0, n.find('.')) + "_" + info.param.profile;
                         });

}  // namespace
}  // namespace refx
