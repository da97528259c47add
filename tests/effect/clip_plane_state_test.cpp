// The effect state ClipPlaneEnable is D3DRS_CLIPPLANEENABLE. D3D9 effects have no state
// for the planes themselves (they are set with SetClipPlane).
#include <gtest/gtest.h>

#include "pipeline/device_helpers.h"
#include "refx/core/diagnostics.h"
#include "refx/effect/effect.h"

using namespace refx;
using namespace refx::effect;
using namespace refx::d3d;

TEST(EffectState, ClipPlaneEnableSetsTheRenderState) {
  auto fx = Effect::fromText("technique t { pass p { ClipPlaneEnable = 5; } }", "clip.fx");
  auto dev = test::makeDevice(4, 4);
  fx->begin(*dev, 0);
  fx->beginPass(0);
  EXPECT_EQ(dev->getRenderState(RS_CLIPPLANEENABLE), 5u);  // planes 0 and 2
  fx->endPass();
  fx->end();
  EXPECT_EQ(dev->getRenderState(RS_CLIPPLANEENABLE), 0u);  // restored to the default
}
