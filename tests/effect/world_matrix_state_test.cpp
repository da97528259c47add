// The effect state WorldTransform[n] sets D3DTS_WORLDMATRIX(n), the vertex-blending
// matrices 0-255.
#include <gtest/gtest.h>

#include "pipeline/device_helpers.h"
#include "refx/core/diagnostics.h"
#include "refx/effect/effect.h"
#include "refx/effect/fx2_binary.h"

using namespace refx;
using namespace refx::effect;
using namespace refx::d3d;

TEST(EffectState, WorldTransformIndexReachesWorldMatrix) {
  auto fx = Effect::fromText(R"(
    technique t { pass p {
      VertexBlend = 2;
      IndexedVertexBlendEnable = true;
      WorldTransform[1] = float4x4(1,0,0,0, 0,1,0,0, 0,0,1,0, 4,5,6,1);
      WorldTransform[200] = float4x4(3,0,0,0, 0,3,0,0, 0,0,3,0, 0,0,0,1);
      WorldTransform[255] = float4x4(1,0,0,0, 0,1,0,0, 0,0,1,0, -1,-2,-3,1);
    } })",
                             "blend.fx");
  ASSERT_TRUE(fx->diagnostics().empty()) << fx->diagnostics()[0].str();
  auto dev = test::makeDevice(4, 4);
  fx->begin(*dev, kDoNotSaveState);
  fx->beginPass(0);
  EXPECT_EQ(dev->getRenderState(RS_VERTEXBLEND), uint32_t(VBF_2WEIGHTS));
  EXPECT_EQ(dev->getRenderState(RS_INDEXEDVERTEXBLENDENABLE), 1u);
  // float4x4(…) lists the rows: the translation is row 3.
  EXPECT_EQ(dev->getTransform(worldMatrix(1)).m[3][1], 5.0f);
  EXPECT_EQ(dev->getTransform(worldMatrix(200)).m[2][2], 3.0f);
  EXPECT_EQ(dev->getTransform(worldMatrix(255)).m[3][2], -3.0f);
  // WORLDMATRIX(0) (D3DTS_WORLD) is untouched.
  EXPECT_EQ(dev->getTransform(TS_WORLD), Matrix::identity());
  fx->endPass();
  fx->end();
}

TEST(EffectState, WorldTransformIndexSurvivesTheFx2Binary) {
  // fx_2_0 stores WorldTransform (operation 125) with its index; loading the binary back
  // sets the same D3DTS_WORLDMATRIX(n).
  auto text = Effect::fromText(R"(
    technique t { pass p {
      WorldTransform[200] = float4x4(1,0,0,0, 0,1,0,0, 0,0,1,0, 7,8,9,1);
    } })",
                               "blend.fx");
  ASSERT_TRUE(text->diagnostics().empty()) << text->diagnostics()[0].str();
  auto fx = Effect::fromFx2(writeFx2(*text).bytes, "blend.fxo");
  auto dev = test::makeDevice(4, 4);
  fx->begin(*dev, kDoNotSaveState);
  fx->beginPass(0);
  EXPECT_EQ(dev->getTransform(worldMatrix(200)).m[3][1], 8.0f);
  EXPECT_EQ(dev->getTransform(TS_WORLD), Matrix::identity());
  fx->endPass();
  fx->end();
}

TEST(EffectState, WorldTransformIndexBeyond255IsAnError) {
  bool reported = false;
  try {
    auto fx = Effect::fromText(R"(
      technique t { pass p { WorldTransform[256] = float4x4(1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1); } })",
                               "blend.fx");
    for (const auto& d : fx->diagnostics())
      reported |= d.str().find("out of range (0 to 255)") != std::string::npos;
    if (!reported) {
      auto dev = test::makeDevice(4, 4);
      fx->begin(*dev, kDoNotSaveState);
      fx->beginPass(0);
    }
  } catch (const Error& e) {
    reported = std::string(e.what()).find("out of range (0 to 255)") != std::string::npos;
  }
  EXPECT_TRUE(reported);
}
