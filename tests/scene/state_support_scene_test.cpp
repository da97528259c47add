// A scene script that sets a state refx does not implement fails at that line, with
// the device's message (tests/pipeline/test_state_support.cpp has the device's side).
#include <gtest/gtest.h>

#include <string>

#include "pipeline/error_helpers.h"
#include "refx/pipeline/device.h"
#include "refx/scene/scene_script.h"

using namespace refx;
using namespace refx::scene;
using namespace refx::test;

namespace {

TEST(StateSupport, SceneScriptsReportTheStateAtItsLine) {
  Device device(CapsProfile{});
  std::string err = errorOf([&] {
    runSceneScript(parseSceneScript("clear 0xff000000\nrs LASTPIXEL TRUE\nrs LASTPIXEL FALSE\n",
                                    "s.scene"),
                   device);
  });
  EXPECT_EQ(err,
            "s.scene:3: error: rs: D3DRS_LASTPIXEL is not implemented by refx (only its default "
            "TRUE is accepted, not FALSE)");
  err = errorOf([&] {
    runSceneScript(parseSceneScript("samp 0 ELEMENTINDEX 2\n", "s.scene"), device);
  });
  EXPECT_EQ(err.rfind("s.scene:1: error: samp: D3DSAMP_ELEMENTINDEX is not implemented by refx", 0),
            0u)
      << err;
}

}  // namespace
