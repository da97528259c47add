// The errors of scene scripts, for tests that check their texts.
#pragma once
#include <string>
#include <string_view>

#include "pipeline/error_helpers.h"
#include "refx/scene/scene_script.h"

namespace refx::test {

// The error of parsing `text` as the scene script "s.scene".
inline std::string parseError(std::string_view text) {
  return errorOf([&] { scene::parseSceneScript(text, "s.scene"); });
}

}  // namespace refx::test
