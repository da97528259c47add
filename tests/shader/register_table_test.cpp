// The per-version register table against reference/registers-and-limits.md: register
// counts, read ports, the ps_1_x value ranges, and the one register namer.
#include <gtest/gtest.h>

#include <limits>

#include "refx/shader/version_rules.h"

using namespace refx::shader;

namespace {

constexpr Version vs(uint8_t major, uint8_t minor) { return {ShaderType::Vertex, major, minor}; }
constexpr Version ps(uint8_t major, uint8_t minor) { return {ShaderType::Pixel, major, minor}; }

const VersionRules& rules(Version v) {
  const VersionRules* r = findVersionRules(v);
  EXPECT_NE(r, nullptr) << v.name();
  return *r;
}

int countOf(Version v, RegType t) {
  const RegisterRule* r = findRegisterRule(rules(v), t);
  return r ? r->count : -1;
}

TEST(RegisterTable, Ps1xRanges) {
  // §2: PixelShader1xMaxValue is at least 1 for ps_1_1-1_3 hardware and 8 for ps_1_4;
  // constants are [-1, 1] in every ps_1_x version, ps_1_4 included.
  for (Version v : {ps(1, 1), ps(1, 2), ps(1, 3)}) {
    EXPECT_EQ(rules(v).minRegisterRange, 1.0f) << v.name();
    EXPECT_EQ(rules(v).defMin, -1.0f) << v.name();
    EXPECT_EQ(rules(v).defMax, 1.0f) << v.name();
  }
  EXPECT_EQ(rules(ps(1, 4)).minRegisterRange, 8.0f);
  EXPECT_EQ(rules(ps(1, 4)).defMax, 1.0f);
  // ps_1_0 is read as ps_1_1.
  EXPECT_EQ(rules(ps(1, 0)).minRegisterRange, 1.0f);
  // Float registers of SM2+ are not clamped.
  for (Version v : {ps(2, 0), ps(3, 0), vs(1, 1), vs(3, 0)}) {
    EXPECT_EQ(rules(v).minRegisterRange, 0.0f) << v.name();
    EXPECT_EQ(rules(v).defMax, std::numeric_limits<float>::max()) << v.name();
  }
}

TEST(RegisterTable, ColorInputsSaturated) {
  // §2: ps_1_x v# are [0, 1]; ps_2_0/2_x v# are colors in [0, 1]; ps_3_0 inputs are full float.
  EXPECT_TRUE(rules(ps(1, 1)).colorInputsSaturated);
  EXPECT_TRUE(rules(ps(1, 4)).colorInputsSaturated);
  EXPECT_TRUE(rules(ps(2, 1)).colorInputsSaturated);
  EXPECT_FALSE(rules(ps(3, 0)).colorInputsSaturated);
  EXPECT_FALSE(rules(vs(2, 0)).colorInputsSaturated);
}

TEST(RegisterTable, Counts) {
  // §2 ps_1_x table: r# 2/2/2/6, t# 4/4/4/6, c# 8, v# 2.
  EXPECT_EQ(countOf(ps(1, 1), RegType::Temp), 2);
  EXPECT_EQ(countOf(ps(1, 4), RegType::Temp), 6);
  EXPECT_EQ(countOf(ps(1, 3), RegType::Texture), 4);
  EXPECT_EQ(countOf(ps(1, 4), RegType::Texture), 6);
  EXPECT_EQ(countOf(ps(1, 2), RegType::Const), 8);
  EXPECT_EQ(countOf(ps(1, 4), RegType::Input), 2);
  // §2 ps_2_0+ table: t# 8, c# 32 / 224, v# 10 in ps_3_0, oC0..oC3.
  EXPECT_EQ(countOf(ps(2, 0), RegType::Texture), 8);
  EXPECT_EQ(countOf(ps(2, 0), RegType::Const), 32);
  EXPECT_EQ(countOf(ps(3, 0), RegType::Const), 224);
  EXPECT_EQ(countOf(ps(3, 0), RegType::Input), 10);
  EXPECT_EQ(countOf(ps(3, 0), RegType::ColorOut), 4);
  EXPECT_EQ(countOf(ps(3, 0), RegType::Texture), -1);  // merged into v#
  // §1: v# 16, vs_3_0 o0..o11 and s0..s3, oT0..oT7 below vs_3_0.
  EXPECT_EQ(countOf(vs(1, 1), RegType::Input), 16);
  EXPECT_EQ(countOf(vs(3, 0), RegType::Output), 12);
  EXPECT_EQ(countOf(vs(3, 0), RegType::Sampler), 4);
  EXPECT_EQ(countOf(vs(2, 0), RegType::TexCrdOut), 8);
  EXPECT_EQ(countOf(vs(3, 0), RegType::Temp), 32);
}

TEST(RegisterTable, ReadPorts) {
  // §2 read-port table: t# 2 in ps_1_1, 3 in ps_1_2/1_3, 1 in ps_1_4; r# 3 in ps_1_4.
  EXPECT_EQ(findRegisterRule(rules(ps(1, 1)), RegType::Texture)->readPorts, 2);
  EXPECT_EQ(findRegisterRule(rules(ps(1, 3)), RegType::Texture)->readPorts, 3);
  EXPECT_EQ(findRegisterRule(rules(ps(1, 4)), RegType::Texture)->readPorts, 1);
  EXPECT_EQ(findRegisterRule(rules(ps(1, 4)), RegType::Temp)->readPorts, 3);
  // §1: 2 different c# per instruction in vs_2_0.
  EXPECT_EQ(findRegisterRule(rules(vs(2, 0)), RegType::Const)->readPorts, 2);
}

TEST(RegisterTable, CapacityOfCountsFromCaps) {
  // ps_2_x temps come from NumTemps (12..32): a device may give 32.
  EXPECT_EQ(registerCapacity(rules(ps(2, 1)), RegType::Temp), 32);
  EXPECT_EQ(registerCapacity(rules(ps(2, 0)), RegType::Temp), 12);
  // vs_1_1 constants: at least 96 (MaxVertexShaderConst), up to the 256 of vs_2_0+.
  EXPECT_EQ(registerCapacity(rules(vs(1, 1)), RegType::Const), 256);
  EXPECT_EQ(registerCapacity(rules(ps(1, 1)), RegType::ColorOut), 0);
}

TEST(RegisterTable, Names) {
  const Version vs11 = vs(1, 1), vs20 = vs(2, 0), vs30 = vs(3, 0), ps11 = ps(1, 1), ps20 = ps(2, 0),
                ps30 = ps(3, 0);
  // RASTOUT 0..2 are oPos, oFog, oPts (§1).
  EXPECT_EQ(registerName(RegType::RastOut, 0, vs11), "oPos");
  EXPECT_EQ(registerName(RegType::RastOut, 1, vs11), "oFog");
  EXPECT_EQ(registerName(RegType::RastOut, 2, vs11), "oPts");
  EXPECT_EQ(registerName(RegType::AttrOut, 1, vs11), "oD1");
  // Register type 6 is oT# below vs_3_0 and o# in vs_3_0.
  EXPECT_EQ(registerName(RegType::TexCrdOut, 7, vs20), "oT7");
  EXPECT_EQ(registerName(RegType::Output, 7, vs30), "o7");
  // Register type 3 is a0 in vertex shaders and t# in pixel shaders.
  EXPECT_EQ(registerName(RegType::Addr, 0, vs11), "a0");
  EXPECT_EQ(registerName(RegType::Texture, 3, ps11), "t3");
  EXPECT_EQ(registerName(RegType::Loop, 0, vs30), "aL");
  EXPECT_EQ(registerName(RegType::ColorOut, 1, ps30), "oC1");
  EXPECT_EQ(registerName(RegType::DepthOut, 0, ps20), "oDepth");
  // MISCTYPE 0 is vPos, 1 is vFace (§2).
  EXPECT_EQ(registerName(RegType::MiscType, 0, ps30), "vPos");
  EXPECT_EQ(registerName(RegType::MiscType, 1, ps30), "vFace");
  // CONST2 continues the c# numbers at 2048.
  EXPECT_EQ(registerName(RegType::Const2, 1, vs30), "c2049");
  EXPECT_EQ(registerName(RegType::Const4, 0, vs30), "c6144");
  EXPECT_EQ(registerTypeName(RegType::Output, vs30), "o");
  EXPECT_EQ(registerTypeName(RegType::Const, ps20), "c");
}

}  // namespace
