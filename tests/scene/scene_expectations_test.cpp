// Every scene script in tests/scenes must be able to fail: it checks at least one pixel,
// and at least one of its checked pixels differs from every color the target is cleared
// to (a scene whose expectations all equal the clear color passes when nothing is drawn).
#include <gtest/gtest.h>

#include <array>
#include <cstdlib>
#include <filesystem>
#include <variant>
#include <vector>

#include "refx/scene/scene_script.h"

namespace fs = std::filesystem;
using namespace refx;
using namespace refx::scene;

namespace {

// The 0-255 channels a clear to `argb` reads back as, alpha 255 on an X8R8G8B8 target.
std::array<int, 4> clearedPixel(uint32_t argb, bool noAlpha) {
  return {int(argb >> 16 & 0xff), int(argb >> 8 & 0xff), int(argb & 0xff), noAlpha ? 255 : int(argb >> 24)};
}

TEST(SceneScripts, EverySceneChecksAPixelItsDrawsChange) {
  int scenes = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(REFX_TEST_DIR) / "scenes")) {
    if (entry.path().extension() != ".scene") continue;
    ++scenes;
    const std::string file = entry.path().filename().string();
    const SceneScript script = loadSceneScript(entry.path().string());
    const bool noAlpha = script.targetFormat == Format::X8R8G8B8;
    std::vector<std::array<int, 4>> cleared;
    for (const scene::Command& c : script.commands)
      if (const auto* clear = std::get_if<scene::Clear>(&c.action))
        cleared.push_back(clearedPixel(uint32_t(clear->color), noAlpha));
    if (cleared.empty()) cleared.push_back(clearedPixel(0, noAlpha));  // never cleared: 0x00000000
    EXPECT_FALSE(script.expectations.empty()) << file << " checks no pixel";
    bool drawn = false;
    for (const scene::Expectation& e : script.expectations) {
      bool isClear = false;
      for (const auto& c : cleared) {
        bool same = true;
        for (int k = 0; k < 4; ++k) same = same && std::abs(e.rgba[k] - c[size_t(k)]) <= e.tolerance;
        isClear = isClear || same;
      }
      drawn = drawn || !isClear;
    }
    EXPECT_TRUE(drawn) << file << ": every expectation equals a clear color, so the scene passes even "
                       << "when nothing is drawn; add a pixel the draws must change";
  }
  EXPECT_GE(scenes, 250) << "fewer scene scripts than the tree holds";
}

}  // namespace
