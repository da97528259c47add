// The message of the refx::Error a call throws, for tests that check error texts.
#pragma once
#include <string>
#include <string_view>

#include "refx/core/diagnostics.h"
#include "refx/scene/scene_script.h"

namespace refx::test {

// What `f()` throws as refx::Error; "(no error)" when it returns.
template <typename F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// The error of parsing `text` as the scene script "s.scene".
inline std::string parseError(std::string_view text) {
  return errorOf([&] { parseSceneScript(text, "s.scene"); });
}

}  // namespace refx::test
