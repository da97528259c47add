// Scene script fuzz target: any text either parses or gives refx::Error; the textures
// a parsed script describes are generated too when they are small.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "refx/core/diagnostics.h"
#include "refx/pipeline/scene_script.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    refx::SceneScript script = refx::parseSceneScript(text, "fuzz.scene");
    for (const refx::scene::Command& c : script.commands) {
      const auto* t = std::get_if<refx::scene::TextureDef>(&c.action);
      if (!t || t->generator == refx::scene::Generator::File) continue;
      if (uint64_t(t->width) * t->height * t->depth > 4096) continue;
      try {
        refx::createSceneTexture(*t);
      } catch (const refx::Error&) {
      }
    }
  } catch (const refx::Error&) {
  }
  return 0;
}
