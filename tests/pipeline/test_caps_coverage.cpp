// Every capability bit and numeric limit the reference profile claims has a test:
// tests/caps_coverage.txt names, for each `Field.FLAG` (or `Field` for a number) of
// data/caps/ref.caps, the scenes and GoogleTests that exercise it. A claim without a
// line, a line for something ref.caps does not claim, a scene file that does not exist
// or a GoogleTest not defined in tests/ fails here.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "refx/pipeline/caps.h"

using namespace refx;

namespace {

const std::string kTestDir = REFX_TEST_DIR;

std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string trim(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

// The D3DCAPS9 fields that are flag sets (the others are numbers or versions).
const std::set<std::string> kFlagFields = {
    "TextureOpCaps",         "DevCaps",           "FVFCaps",
    "TextureCaps",           "TextureFilterCaps", "CubeTextureFilterCaps",
    "VolumeTextureFilterCaps", "VertexTextureFilterCaps", "TextureAddressCaps",
    "SrcBlendCaps",          "DestBlendCaps",     "PrimitiveMiscCaps",
    "RasterCaps"};

// `Field.FLAG` for every flag ref.caps sets and `Field` for every nonzero number
// (FVFCaps' number is its texture coordinate count), read from `refx caps ref`'s text.
std::set<std::string> refClaims() {
  std::istringstream in(describeCapsProfile(loadCapsProfile("ref")));
  std::vector<std::string> joined;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    if (!joined.empty() && trim(joined.back()).ends_with("|")) {
      joined.back().push_back(' ');
      joined.back().append(trim(line));
    } else {
      joined.push_back(line);
    }
  }
  std::set<std::string> claims;
  for (const std::string& line : joined) {
    const size_t eq = line.find(" = ");
    if (eq == std::string::npos) continue;
    const std::string field = line.substr(0, eq), value = trim(line.substr(eq + 3));
    if (field == "Description") continue;
    if (!kFlagFields.count(field)) {
      if (value != "0" && value != "none") claims.insert(field);
      continue;
    }
    std::istringstream flags(value);
    for (std::string flag; std::getline(flags, flag, '|');) {
      flag = trim(flag);
      if (flag.empty() || flag == "0") continue;
      claims.insert(std::isdigit(static_cast<unsigned char>(flag[0])) ? field : field + "." + flag);
    }
  }
  return claims;
}

// Every test source under tests/, concatenated: GoogleTest names are looked up here.
const std::string& testSources() {
  static const std::string all = [] {
    std::string s;
    for (const auto& e : std::filesystem::recursive_directory_iterator(kTestDir))
      if (e.is_regular_file() && e.path().extension() == ".cpp") s += readFile(e.path()) + "\n";
    return s;
  }();
  return all;
}

bool gtestExists(const std::string& suiteDotName) {
  const size_t dot = suiteDotName.find('.');
  if (dot == std::string::npos) return false;
  const std::regex def("TEST(_F|_P)?\\(\\s*" + suiteDotName.substr(0, dot) + "\\s*,\\s*" +
                       suiteDotName.substr(dot + 1) + "\\s*\\)");
  return std::regex_search(testSources(), def);
}

struct Entry {
  int line;
  std::vector<std::string> tests;
};

}  // namespace

TEST(CapsCoverage, EveryRefCapHasATest) {
  const std::string table = readFile(kTestDir + "/caps_coverage.txt");
  ASSERT_FALSE(table.empty()) << "tests/caps_coverage.txt is missing";
  std::map<std::string, std::vector<Entry>> entries;
  std::istringstream in(table);
  int lineNo = 0;
  for (std::string line; std::getline(in, line);) {
    ++lineNo;
    line = trim(line);
    if (line.empty() || line[0] == '#') continue;  // comments
    std::istringstream words(line);
    std::string key, test;
    words >> key;
    Entry e{lineNo, {}};
    while (words >> test) e.tests.push_back(test);
    EXPECT_FALSE(e.tests.empty()) << "caps_coverage.txt:" << lineNo << ": " << key << " names no test";
    entries[key].push_back(e);
  }

  const std::set<std::string> claims = refClaims();
  ASSERT_GT(claims.size(), 100u);
  for (const std::string& claim : claims)
    EXPECT_TRUE(entries.count(claim)) << "ref.caps claims " << claim
                                      << " but tests/caps_coverage.txt names no test for it";
  for (const auto& [key, list] : entries)
    for (const Entry& e : list) {
      EXPECT_TRUE(claims.count(key)) << "caps_coverage.txt:" << e.line << ": ref.caps does not claim "
                                     << key;
      for (const std::string& test : e.tests) {
        if (test.starts_with("scene:")) {
          const std::string path = kTestDir + "/scenes/" + test.substr(6) + ".scene";
          EXPECT_TRUE(std::filesystem::exists(path))
              << "caps_coverage.txt:" << e.line << ": no scene " << path;
        } else if (test.starts_with("gtest:")) {
          EXPECT_TRUE(gtestExists(test.substr(6)))
              << "caps_coverage.txt:" << e.line << ": no TEST or TEST_F " << test.substr(6)
              << " in tests/";
        } else {
          ADD_FAILURE() << "caps_coverage.txt:" << e.line << ": '" << test
                        << "' is neither scene:NAME nor gtest:Suite.Name";
        }
      }
    }
}

TEST(CapsCoverage, ProfilesClaimNoMoreThanTheReference) {
  // A hardware profile cannot claim what refx does not implement, and ref.caps claims
  // everything refx implements: every profile's flags are a subset of ref's and its
  // limits at most ref's.
  const CapsProfile ref = loadCapsProfile("ref");
  for (const std::string& name : capsProfileNames()) {
    SCOPED_TRACE(name);
    const CapsProfile c = loadCapsProfile(name);
    auto subset = [](uint32_t a, uint32_t b) { return (a & ~b) == 0; };
    EXPECT_TRUE(subset(c.textureOpCaps, ref.textureOpCaps));
    EXPECT_TRUE(subset(c.devCaps, ref.devCaps));
    EXPECT_TRUE(subset(c.fvfCaps & 0xffff0000u, ref.fvfCaps & 0xffff0000u));
    EXPECT_LE(c.fvfCaps & 0xffff, ref.fvfCaps & 0xffff);
    // The restriction flags (POW2 ...) take capabilities away; the rest must be ref's.
    const uint32_t restrictions = 0x2 | 0x20 | 0x100 | 0x20000 | 0x40000 | 0x200000;
    EXPECT_TRUE(subset(c.textureCaps & ~restrictions, ref.textureCaps));
    EXPECT_TRUE(subset(c.textureFilterCaps, ref.textureFilterCaps));
    EXPECT_TRUE(subset(c.cubeTextureFilterCaps, ref.cubeTextureFilterCaps));
    EXPECT_TRUE(subset(c.volumeTextureFilterCaps, ref.volumeTextureFilterCaps));
    EXPECT_TRUE(subset(c.vertexTextureFilterCaps, ref.vertexTextureFilterCaps));
    EXPECT_TRUE(subset(c.textureAddressCaps, ref.textureAddressCaps));
    EXPECT_TRUE(subset(c.srcBlendCaps, ref.srcBlendCaps));
    EXPECT_TRUE(subset(c.destBlendCaps, ref.destBlendCaps));
    EXPECT_TRUE(subset(c.primitiveMiscCaps, ref.primitiveMiscCaps));
    EXPECT_TRUE(subset(c.rasterCaps, ref.rasterCaps));
    EXPECT_LE(c.maxTextureBlendStages, ref.maxTextureBlendStages);
    EXPECT_LE(c.maxSimultaneousTextures, ref.maxSimultaneousTextures);
    EXPECT_LE(c.vertexShaderVersion & 0xffff, ref.vertexShaderVersion & 0xffff);
    EXPECT_LE(c.pixelShaderVersion & 0xffff, ref.pixelShaderVersion & 0xffff);
    EXPECT_LE(c.maxVertexShaderConst, ref.maxVertexShaderConst);
    EXPECT_LE(c.maxActiveLights, ref.maxActiveLights);
    EXPECT_LE(c.maxStreams, ref.maxStreams);
    EXPECT_LE(c.maxTextureWidth, ref.maxTextureWidth);
    EXPECT_LE(c.maxTextureHeight, ref.maxTextureHeight);
    EXPECT_LE(c.maxVolumeExtent, ref.maxVolumeExtent);
    EXPECT_LE(c.maxTextureRepeat, ref.maxTextureRepeat);
    EXPECT_LE(c.maxAnisotropy, ref.maxAnisotropy);
    EXPECT_LE(c.maxSimultaneousRenderTargets, ref.maxSimultaneousRenderTargets);
    EXPECT_LE(c.maxPointSize, ref.maxPointSize);
    EXPECT_LE(c.maxVertexBlendMatrices, ref.maxVertexBlendMatrices);
    EXPECT_LE(c.maxVertexBlendMatrixIndex, ref.maxVertexBlendMatrixIndex);
    EXPECT_LE(c.maxUserClipPlanes, ref.maxUserClipPlanes);
    // Every profile draws points of at least one pixel (POINTSIZE defaults to 1).
    EXPECT_GE(c.maxPointSize, 1.0f);
  }
}
