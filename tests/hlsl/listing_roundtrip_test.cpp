// The /Fc listing round trip: each seed program compiled, written as the assembly
// listing `refx fxc /Fc` writes (shader::disassemble with listing = true), and
// assembled again by refx's assembler gives the compiled tokens. The one difference
// allowed: the CTAB comment, which the listing shows as `//` lines an assembler does
// not turn back into a comment token.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <ostream>

#include "refx/core/diagnostics.h"
#include "refx/hlsl/compiler.h"
#include "refx/shader/assembler.h"
#include "refx/shader/disassembler.h"

namespace refx {
namespace {

struct Seed {
  const char* file;
  const char* profile;
  const char* entry;
  bool compatibility = false;
};

constexpr uint32_t kCtab = 0x42415443;  // 'CTAB' as a little-endian DWORD

// The tokens with the CTAB comment removed; any other comment is kept (and would show
// up as a difference).
std::vector<uint32_t> withoutCtab(std::vector<uint32_t> tokens) {
  std::vector<uint32_t> out;
  size_t i = 0;
  if (!tokens.empty()) out.push_back(tokens[i++]);  // version
  while (i < tokens.size()) {
    const uint32_t t = tokens[i];
    if ((t & 0xffff) == 0xfffe) {  // comment: length in DWORDs in bits 16-30
      const size_t length = (t >> 16) & 0x7fff;
      const bool ctab = length > 0 && i + 1 < tokens.size() && tokens[i + 1] == kCtab;
      if (!ctab)
        out.insert(out.end(), tokens.begin() + ptrdiff_t(i), tokens.begin() + ptrdiff_t(std::min(i + 1 + length, tokens.size())));
      i += 1 + length;
      continue;
    }
    out.push_back(t);
    ++i;
  }
  return out;
}

void PrintTo(const Seed& s, std::ostream* os) { *os << s.file << " " << s.profile; }

class ListingRoundTrip : public testing::TestWithParam<Seed> {};

TEST_P(ListingRoundTrip, AssemblesToTheCompiledTokens) {
  const Seed& s = GetParam();
  hlsl::CompileOptions o;
  o.profile = s.profile;
  o.entry = s.entry;
  o.compatibility = s.compatibility;
  const hlsl::CompileResult r = hlsl::compileFile(std::string(REFX_DATA_DIR) + "/hlsl/" + s.file, o);
  ASSERT_TRUE(r.ok()) << r.messages();

  shader::DisassemblyOptions listingOptions;
  listingOptions.listing = true;
  const std::string listing = shader::disassemble(r.tokens, listingOptions);
  // The listing shows the constant table as fxc's does (every vertex shader here reads
  // matWorldViewProj).
  if (s.profile[0] == 'v') {
    EXPECT_NE(listing.find("//   matWorldViewProj"), std::string::npos) << listing;
  }

  std::vector<uint32_t> assembled;
  try {
    assembled = shader::assembleTokens(listing, std::string(s.file) + ".asm");
  } catch (const Error& e) {
    FAIL() << e.what() << "\n" << listing;
  }
  const std::vector<uint32_t> expected = withoutCtab(r.tokens);
  ASSERT_LT(expected.size(), r.tokens.size()) << "the compiled shader carries a CTAB comment";
  if (assembled != expected) {
    ADD_FAILURE() << "listing:\n" << listing << "\nreassembled:\n" << shader::disassemble(assembled);
    for (size_t i = 0; i < std::max(assembled.size(), expected.size()); ++i) {
      const uint32_t a = i < assembled.size() ? assembled[i] : 0, e = i < expected.size() ? expected[i] : 0;
      if (a != e) {
        ADD_FAILURE() << "first difference at token " << i << ": compiled " << std::hex << e << ", reassembled " << a;
        break;
      }
    }
  }
}

std::vector<Seed> seeds() {
  std::vector<Seed> v;
  for (const char* f : {"ambient.hlsl", "diffuse.hlsl", "specular.hlsl", "self_shadow.hlsl", "bump.hlsl",
                        "point_light.hlsl"})
    for (auto [profile, entry] : {std::pair{"vs_1_1", "VS"}, {"vs_2_0", "VS"}, {"ps_2_0", "PS"}})
      v.push_back({f, profile, entry});
  v.push_back({"wood.fx", "ps_2_0", "Wood", true});
  return v;
}

std::string seedName(const testing::TestParamInfo<Seed>& info) {
  std::string n = std::string(info.param.file) + "_" + info.param.profile;
  for (char& c : n)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return n;
}

INSTANTIATE_TEST_SUITE_P(Seeds, ListingRoundTrip, testing::ValuesIn(seeds()), seedName);

// The helper removes exactly the CTAB comment: another comment stays.
TEST(ListingRoundTripHelper, RemovesOnlyTheCtabComment) {
  const std::vector<uint32_t> tokens = {0xffff0200, 0x0002fffe, kCtab, 7, 0x0001fffe, 0x12345678, 0x0000ffff};
  EXPECT_EQ(withoutCtab(tokens), (std::vector<uint32_t>{0xffff0200, 0x0001fffe, 0x12345678, 0x0000ffff}));
}

}  // namespace
}  // namespace refx
