// Which D3D9 states refx implements: every named state has a row in the table and a
// line in docs/device_states.md, the device refuses a value other than the D3D9
// default of a state it does not implement (naming the state), and accepts the
// default, as effects and state blocks set it.
#include <gtest/gtest.h>

#include "error_helpers.h"

#include <fstream>
#include <sstream>
#include <string>

#include "pipeline/device_helpers.h"
#include "pipeline/state_support.h"
#include "refx/core/diagnostics.h"
#include "refx/pipeline/device.h"

using namespace refx;
using namespace refx::test;
using namespace refx::d3d;
using namespace refx::pipeline;

namespace {

struct ClassInfo {
  StateClass stateClass;
  EnumKind names;
  uint32_t count;
};
constexpr ClassInfo kClasses[] = {
    {StateClass::Render, EnumKind::RenderState, kRenderStateCount},
    {StateClass::TextureStage, EnumKind::TextureStageState, kTextureStageStateCount},
    {StateClass::Sampler, EnumKind::SamplerState, kSamplerStateCount},
};

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(StateSupport, EveryNamedStateHasARow) {
  for (const ClassInfo& c : kClasses)
    for (uint32_t s = 0; s < c.count; ++s) {
      if (enumName(c.names, s).empty()) continue;
      EXPECT_NE(findStateSupport(c.stateClass, s), nullptr) << stateDisplayName(c.stateClass, s);
    }
  // And every row is a named state, listed once.
  for (const StateSupportEntry& e : stateSupportTable()) {
    EXPECT_EQ(findStateSupport(e.stateClass, e.state), &e) << stateDisplayName(e.stateClass, e.state);
    EXPECT_NE(stateDisplayName(e.stateClass, e.state).find('_'), std::string::npos);
  }
}

TEST(StateSupport, DocsListEveryStateWithItsSupport) {
  const std::string doc = readFile(std::string(REFX_TEST_DIR) + "/../docs/device_states.md");
  ASSERT_FALSE(doc.empty()) << "docs/device_states.md is missing";
  for (const StateSupportEntry& e : stateSupportTable()) {
    const std::string name = stateDisplayName(e.stateClass, e.state);
    // One table row per state: "| D3DRS_NAME | support | ... |".
    const size_t at = doc.find("| " + name + " |");
    ASSERT_NE(at, std::string::npos) << name << " is not in docs/device_states.md";
    const std::string row = doc.substr(at, doc.find('\n', at) - at);
    const char* word = e.support == StateSupport::Implemented ? "| implemented |"
                       : e.support == StateSupport::NoEffect  ? "| no effect |"
                                                              : "| refused |";
    EXPECT_NE(row.find(word), std::string::npos) << row;
  }
}

TEST(StateSupport, DeviceRefusesNonDefaultValuesOfUnimplementedStates) {
  auto dev = test::makeDevice(2, 2);
  // D3DRS_ANTIALIASEDLINEENABLE: default FALSE (D3D9 docs).
  EXPECT_EQ(errorOf([&] { dev->setRenderState(RS_ANTIALIASEDLINEENABLE, 1); }),
            "D3DRS_ANTIALIASEDLINEENABLE is not implemented by refx (only its default "
            "FALSE is accepted, not TRUE)");
  EXPECT_EQ(dev->getRenderState(RS_ANTIALIASEDLINEENABLE), 0u);  // not stored
  // D3DRS_LASTPIXEL: default TRUE, refx always draws the last pixel of a line.
  EXPECT_EQ(errorOf([&] { dev->setRenderState(RS_LASTPIXEL, 0); }),
            "D3DRS_LASTPIXEL is not implemented by refx (only its default TRUE is "
            "accepted, not FALSE)");
  // D3DRS_MINTESSELLATIONLEVEL: a float, default 1.0.
  EXPECT_EQ(errorOf([&] { dev->setRenderState(RS_MINTESSELLATIONLEVEL, floatBits(2.0f)); }),
            "D3DRS_MINTESSELLATIONLEVEL is not implemented by refx (only its default 1.0 "
            "is accepted, not 2.0)");
  EXPECT_EQ(errorOf([&] { dev->setRenderState(RenderState(RS_WRAP8 + 3), 1); }),
            "D3DRS_WRAP11 is not implemented by refx (only its default 0 is accepted, "
            "not 1)");
  EXPECT_EQ(errorOf([&] { dev->setSamplerState(2, SAMP_ELEMENTINDEX, 1); }),
            "D3DSAMP_ELEMENTINDEX is not implemented by refx (only its default 0 is "
            "accepted, not 1)");
  EXPECT_EQ(errorOf([&] { dev->setSamplerState(kVertexSampler0, SAMP_DMAPOFFSET, 4); }),
            "D3DSAMP_DMAPOFFSET is not implemented by refx (only its default 0 is "
            "accepted, not 4)");
}

TEST(StateSupport, NumbersThatAreNoD3D9StateTakeOnlyZero) {
  auto dev = test::makeDevice(2, 2);
  // 47 was D3D8's D3DRS_ZBIAS; D3D9 has no render state 47 (DEPTHBIAS is 195).
  EXPECT_EQ(errorOf([&] { dev->setRenderState(RenderState(47), 1); }),
            "render state 47 is not a Direct3D 9 render state");
  EXPECT_NO_THROW(dev->setRenderState(RenderState(47), 0));
  // D3D8's texture stage ADDRESSU (13) became D3DSAMP_ADDRESSU.
  EXPECT_EQ(errorOf([&] { dev->setTextureStageState(0, TextureStageState(13), 3); }),
            "texture stage state 13 is not a Direct3D 9 texture stage state");
  EXPECT_EQ(errorOf([&] { dev->setSamplerState(0, SamplerStateType(0), 1); }),
            "sampler state 0 is not a Direct3D 9 sampler state");
}

TEST(StateSupport, DefaultsAndNoEffectStatesAreAccepted) {
  auto dev = test::makeDevice(2, 2);
  const DeviceState defaults;
  // Every state set to its own D3D9 default, as a state block or an effect restores it.
  for (const StateSupportEntry& e : stateSupportTable()) {
    SCOPED_TRACE(stateDisplayName(e.stateClass, e.state));
    switch (e.stateClass) {
      case StateClass::Render:
        EXPECT_NO_THROW(dev->setRenderState(RenderState(e.state), defaults.renderStates[e.state]));
        break;
      case StateClass::TextureStage:
        EXPECT_NO_THROW(dev->setTextureStageState(
            1, TextureStageState(e.state), defaults.stageStates[1][e.state]));
        break;
      case StateClass::Sampler:
        EXPECT_NO_THROW(dev->setSamplerState(
            1, SamplerStateType(e.state), defaults.samplerStates[1][e.state]));
        break;
    }
  }
  // States D3D9 gives no effect on what refx renders take any value.
  EXPECT_NO_THROW(dev->setRenderState(RS_CLIPPING, 0));
  EXPECT_NO_THROW(dev->setRenderState(RS_MULTISAMPLEANTIALIAS, 0));
  EXPECT_NO_THROW(dev->setRenderState(RS_MULTISAMPLEMASK, 0x5));
  EXPECT_NO_THROW(dev->setRenderState(RS_DEBUGMONITORTOKEN, 1));
  EXPECT_EQ(dev->getRenderState(RS_MULTISAMPLEMASK), 0x5u);
}
