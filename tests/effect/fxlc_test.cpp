// FXLC state expressions (fx2-binary.md §5): a state value that is an expression of
// parameters is written as a standalone preshader blob (version 0x46580200, CTAB +
// CLIT + FXLC); decoded and run, the blob gives the values that the effect's own
// evaluation gives. Expected values are worked out by hand from the parameters'
// defaults next to each state.
#include <gtest/gtest.h>

#include <cstring>

#include "effect/effect_internal.h"
#include "effect/fxlc.h"
#include "refx/core/diagnostics.h"
#include "refx/effect/effect.h"
#include "refx/effect/fx2_binary.h"

namespace refx::effect {
namespace {

using detail::EffectAccess;
using detail::FxlcProgram;
using detail::StateContents;

const char* kText =
    "float4 vLightPos = {0.5, 0.25, -2, 1};\n"
    "float3 vTangentLight = {0.5, -0.5, 1};\n"
    "float fStart = 3;\n"
    "float4x4 mViewInv = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};\n"
    "float4x4 mWorld = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};\n"
    "technique T { pass P {\n"
    "  VertexShaderConstant1[12] = -vLightPos;\n"
    "  TextureFactor = float4(vTangentLight * 0.5 + 0.5, 1);\n"
    "  FogStart = fStart * 2 - 1;\n"
    "  TextureTransform[0] = float4x4(mViewInv[0].xyz, 0, mViewInv[1].xyz, 0, mViewInv[2].xyz, 0, 0, 0, 0, 1);\n"
    "  VertexShaderConstant4[0] = mWorld / 2;\n"
    "  LightEnable[0] = fStart > 2;\n"
    "} }\n";

// What each state's expression evaluates to, by hand:
const std::vector<std::vector<float>> kExpected = {
    // -vLightPos
    {-0.5f, -0.25f, 2, -1},
    // (0.5, -0.5, 1) * 0.5 + 0.5 = (0.75, 0.25, 1), then w = 1
    {0.75f, 0.25f, 1, 1},
    // 3 * 2 - 1
    {5},
    // rows 0–2 of mViewInv with w = 0, then (0, 0, 0, 1)
    {1, 2, 3, 0, 5, 6, 7, 0, 9, 10, 11, 0, 0, 0, 0, 1},
    // mWorld / 2, column_major: one register per column, c0 = (1, 5, 9, 13) / 2 …
    {0.5f, 2.5f, 4.5f, 6.5f, 1, 3, 5, 7, 1.5f, 3.5f, 5.5f, 7.5f, 2, 4, 6, 8},
    // 3 > 2
    {1},
};

// The parameters' defaults laid out as a preshader CTAB says: each element's rows in
// consecutive registers, a row's columns in x, y, z, w.
std::vector<float> inputsFor(const FxlcProgram& p) {
  const std::map<std::string, std::vector<float>> values = {
      {"vLightPos", {0.5f, 0.25f, -2, 1}},
      {"vTangentLight", {0.5f, -0.5f, 1}},
      {"fStart", {3}},
      {"mViewInv", {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16}},
      {"mWorld", {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16}},
  };
  std::vector<float> in;
  for (const shader::ShaderConstant& c : p.inputs.constants) {
    EXPECT_EQ(c.registerSet, shader::RegisterSet::Float4) << c.name;
    const std::vector<float>& v = values.at(c.name);
    const size_t per = size_t(c.columns);
    in.resize(std::max(in.size(), size_t(c.registerIndex + c.registerCount) * 4), 0.0f);
    for (size_t i = 0; i < v.size(); ++i) in[size_t(c.registerIndex) * 4 + (i / per) * 4 + i % per] = v[i];
  }
  return in;
}

TEST(Fxlc, EncodedExpressionsEvaluateToTheEffectsValues) {
  auto fx = Effect::fromText(kText, "expr.fx");
  const auto contents = EffectAccess::contents(*fx);
  const auto& states = contents.techniques.at(0).passes.at(0).states;
  ASSERT_EQ(states.size(), kExpected.size());
  for (size_t k = 0; k < states.size(); ++k) {
    const StateContents& s = states[k];
    ASSERT_EQ(s.kind, StateContents::Kind::Expression) << s.name;
    ASSERT_TRUE(s.fxlc) << s.name << ": " << s.fxlcError;
    // Through the bytes: version 0x46580200, comments, end token.
    const std::vector<uint32_t> blob = detail::encodeFxlc(*s.fxlc, detail::kFxlcStandaloneVersion, false);
    EXPECT_EQ(blob.front(), 0x46580200u);
    EXPECT_EQ(blob.back(), 0x0000FFFFu);
    const FxlcProgram back = detail::decodeFxlc(blob, "expr", 0);
    const std::vector<float> out = back.run(inputsFor(back));
    ASSERT_EQ(s.fxlcComponents, int(kExpected[k].size())) << s.name;
    ASSERT_GE(out.size(), kExpected[k].size()) << s.name;
    for (size_t i = 0; i < kExpected[k].size(); ++i)
      EXPECT_FLOAT_EQ(out[i], kExpected[k][i]) << s.name << " component " << i << "\n" << back.listing();
  }
}

TEST(Fxlc, TheEffectItselfAppliesTheSameValues) {
  auto fx = Effect::fromText(kText, "expr.fx");
  Device dev(loadCapsProfile("ref"));
  fx->begin(dev, kDoNotSaveState);
  fx->beginPass(0);
  const DeviceState& st = dev.state();
  const Vec4 c12 = st.vsConstF[12];
  EXPECT_EQ((std::vector<float>{c12.x, c12.y, c12.z, c12.w}), kExpected[0]);
  // D3DCOLOR of (0.75, 0.25, 1, 1): A 255, R round(191.25) = 191, G round(63.75) = 64, B 255.
  EXPECT_EQ(st.renderStates[d3d::RS_TEXTUREFACTOR], 0xFFBF40FFu);
  float fogStart;
  std::memcpy(&fogStart, &st.renderStates[d3d::RS_FOGSTART], 4);
  EXPECT_EQ(fogStart, 5.0f);
  for (int r = 0; r < 4; ++r) {
    const Vec4 c = st.vsConstF[size_t(r)];
    EXPECT_EQ((std::vector<float>{c.x, c.y, c.z, c.w}),
              std::vector<float>(kExpected[4].begin() + 4 * r, kExpected[4].begin() + 4 * r + 4));
  }
  fx->endPass();
  fx->end();
}

TEST(Fxlc, WrittenAsUsageZeroLargeObjects) {
  auto fx = Effect::fromText(kText, "expr.fx");
  const Fx2Binary bin = writeFx2(*fx);
  // Six expression states: six large objects, each a blob starting with 0x46580200
  // and a comment holding its CTAB.
  std::vector<uint32_t> w(bin.bytes.size() / 4);
  std::memcpy(w.data(), bin.bytes.data(), w.size() * 4);
  size_t found = 0;
  for (size_t i = 0; i + 2 < w.size(); ++i) found += w[i] == 0x46580200u && (w[i + 1] & 0xFFFF) == 0xFFFE && w[i + 2] == 0x42415443u;
  EXPECT_EQ(found, 6u);
  EXPECT_NE(bin.listing.find("FogStart (op 18, index 0) = expression (large object, usage 0, FXLC"), std::string::npos)
      << bin.listing;
}

TEST(Fxlc, DamagedBlobsAreErrorsWithTheirOffset) {
  auto fx = Effect::fromText(kText, "expr.fx");
  const auto contents = EffectAccess::contents(*fx);
  const std::vector<uint32_t> blob =
      detail::encodeFxlc(*contents.techniques[0].passes[0].states[0].fxlc, detail::kFxlcStandaloneVersion, false);
  for (size_t cut = 0; cut < blob.size(); ++cut) {
    std::vector<uint32_t> shortBlob(blob.begin(), blob.begin() + std::ptrdiff_t(cut));
    try {
      detail::decodeFxlc(shortBlob, "blob", 0x100);
      FAIL() << "a blob cut to " << cut << " DWORDs was read";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("blob: error: offset 0x"), std::string::npos) << e.what();
    }
  }
  std::vector<uint32_t> badOp = blob;
  // The FXLC block's first instruction: opword after 'FXLC' and the count.
  for (size_t i = 0; i + 2 < badOp.size(); ++i)
    if (badOp[i] == 0x434C5846u) {
      badOp[i + 2] = 0x70100001;  // opcode 0x701: no such instruction
      break;
    }
  EXPECT_THROW(detail::decodeFxlc(badOp, "blob", 0), Error);
}

TEST(Fxlc, OperatorsWithoutAnFxlcFormAreRefused) {
  const char* text = "int dw = 3;\ntechnique T { pass P {\n  FogColor = dw | 255;\n} }\n";
  auto fx = Effect::fromText(text, "expr.fx");
  try {
    writeFx2(*fx);
    FAIL() << "a bitwise expression was written";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("expr.fx:3:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("the operator '|'"), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace refx::effect
