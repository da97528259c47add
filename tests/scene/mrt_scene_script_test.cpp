// Scene scripts with several render targets: `rendertarget N W H FORMAT|none` and
// `# expect@N X Y r g b a [tolerance]` (docs/scene_script_render_targets.md).
#include <gtest/gtest.h>

#include "scene/scene_helpers.h"

#include <string>

#include "refx/core/diagnostics.h"
#include "refx/pipeline/device.h"
#include "refx/scene/scene_script.h"

using namespace refx;
using namespace refx::test;
using namespace refx::scene;

namespace {

TEST(SceneRenderTargets, ParsesTheCommandAndTargetedExpectations) {
  SceneScript s = parseSceneScript(
      "size 4 4\n"
      "rendertarget 2 4 4 A32B32G32R32F\n"
      "rendertarget 3 4 4 x8r8g8b8\n"
      "rendertarget 3 none\n"
      "# expect@2 1 2 3 4 5 6 7\n"
      "# expect 0 0 1 1 1 1\n",
      "s.scene");
  ASSERT_EQ(s.commands.size(), 3u);
  const auto& a = std::get<SetRenderTarget>(s.commands[0].action);
  EXPECT_EQ(a.index, 2);
  EXPECT_FALSE(a.none);
  EXPECT_EQ(a.width, 4);
  EXPECT_EQ(a.format, Format::A32B32G32R32F);
  EXPECT_EQ(std::get<SetRenderTarget>(s.commands[1].action).format, Format::X8R8G8B8);
  EXPECT_TRUE(std::get<SetRenderTarget>(s.commands[2].action).none);
  ASSERT_EQ(s.expectations.size(), 2u);
  EXPECT_EQ(s.expectations[0].target, 2);
  EXPECT_EQ(s.expectations[0].x, 1);
  EXPECT_EQ(s.expectations[0].rgba[3], 6);
  EXPECT_EQ(s.expectations[0].tolerance, 7);
  EXPECT_EQ(s.expectations[1].target, 0);
}

TEST(SceneRenderTargets, SizeTakesAFloatFormat) {
  EXPECT_EQ(parseSceneScript("size 4 4 A32B32G32R32F\n", "s.scene").targetFormat, Format::A32B32G32R32F);
  EXPECT_EQ(parseError("size 4 4 R5G6B5\n"),
            "s.scene:1:10: error: size: render target format must be A8R8G8B8, X8R8G8B8 or "
            "A32B32G32R32F, got 'R5G6B5'");
}

TEST(SceneRenderTargets, ReportsBadCommands) {
  const std::pair<const char*, const char*> cases[] = {
      {"rendertarget 0 4 4 A8R8G8B8\n", "s.scene:1:14: error: rendertarget: the render target index (0 is `size`) 0 is out of range (1 to 3)"},
      {"rendertarget 4 none\n", "s.scene:1:14: error: rendertarget: the render target index (0 is `size`) 4 is out of range (1 to 3)"},
      {"rendertarget 1 4 4 R5G6B5\n", "s.scene:1:20: error: rendertarget: render target format must be A8R8G8B8, X8R8G8B8 or A32B32G32R32F, got 'R5G6B5'"},
      {"rendertarget 1 4 4\n", "s.scene:1: error: rendertarget: expected `rendertarget N W H FORMAT` or `rendertarget N none`, got 3 values"},
      {"rendertarget 1 off\n", "s.scene:1:16: error: rendertarget: expected `none` or `W H FORMAT` after the index, got 'off'"},
      {"size 4 4\n# expect@1 0 0 1 1 1 1\n", "s.scene:2: error: expect@1: no `rendertarget 1 W H FORMAT` command creates render target 1"},
      {"size 4 4\nrendertarget 1 4 4 A8R8G8B8\n# expect@1 4 0 1 1 1 1\n", "s.scene:3: error: expect: pixel 4,0 is outside the 4x4 render target"},
      {"# expect@0 0 0 1 1 1 1\n", "s.scene:1:3: error: expect: expected expect@1, expect@2 or expect@3 (a render target), got 'expect@0'"},
      {"# expect@2 0 0 1 1 1\n", "s.scene:1:3: error: expect: expected `# expect@2 X Y r g b a [tolerance]`, got 5 values"},
  };
  for (const auto& [text, message] : cases) EXPECT_EQ(parseError(text), message) << text;
}

TEST(SceneRenderTargets, RunBindsAndUnbindsTargets) {
  Device device(loadCapsProfile("ref"));
  SceneScript s = parseSceneScript(
      "size 4 4\n"
      "rendertarget 1 4 4 A8R8G8B8\n"
      "rendertarget 2 4 4 A32B32G32R32F\n"
      "clear 0xff00ff00\n"
      "rendertarget 2 none\n"
      "# expect@1 3 3 0 255 0 255\n"
      "# expect@2 0 0 0 255 0 255\n"
      "# expect@2 1 1 0 0 0 0\n",
      "r.scene");
  SceneOutput out = runSceneScript(s, device);
  ASSERT_TRUE(out.targets[1] && out.targets[2]);
  EXPECT_EQ(out.targets[0], out.target);
  EXPECT_EQ(device.renderTarget(1), out.targets[1]);
  EXPECT_EQ(device.renderTarget(2), nullptr);  // unbound, but still checked by expect@2
  EXPECT_EQ(out.targets[2]->format(), Format::A32B32G32R32F);
  // The clear reached both targets; the last expectation (0 0 0 0) must fail.
  const std::vector<std::string> mismatches = checkSceneExpectations(s, out);
  ASSERT_EQ(mismatches.size(), 1u);
  EXPECT_EQ(mismatches[0], "r.scene:8: expected target 2 1,1 = 0 0 0 0, got 0 255 0 255");
}

TEST(SceneRenderTargets, DeviceErrorsNameTheLine) {
  // dx8 binds one render target; a second size fails in the device.
  auto runError = [](const char* text, const char* profile) -> std::string {
    Device device(loadCapsProfile(profile));
    try {
      runSceneScript(parseSceneScript(text, "r.scene"), device);
    } catch (const Error& e) {
      return e.what();
    }
    return "(no error)";
  };
  EXPECT_EQ(runError("size 4 4\nrendertarget 1 4 4 A8R8G8B8\n", "dx8"),
            "r.scene:2: error: rendertarget: render target index 1 is out of range: caps profile "
            "dx8 has NumSimultaneousRTs 1");
  EXPECT_EQ(runError("size 4 4\nrendertarget 1 4 2 A8R8G8B8\n", "ref"),
            "r.scene:2: error: rendertarget: render target 1 is 4x2, render target 0 is 4x4: all "
            "bound render targets must have the same size");
}

}  // namespace
