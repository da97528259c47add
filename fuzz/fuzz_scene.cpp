// Scene script fuzz target: any text either parses or gives refx::Error, and a script
// that parses runs on a device (ref caps, one thread) — textures, shaders through the
// assembler, validator and lowering, draws through vertex processing, the interpreter
// and the rasterizer — ending in a picture or refx::Error, never a crash.
//
// The work one input may do is bounded so every input runs in well under a second:
// the target is at most 32x32, textures at most 4096 texels, at most 8 draws of at most
// 48 vertices, and commands after the first 250 ms of running are skipped. Commands
// that read files are skipped (their paths come from the input).
#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "refx/core/diagnostics.h"
#include "refx/pipeline/caps.h"
#include "refx/pipeline/device.h"
#include "refx/scene/scene_script.h"

namespace {

constexpr int kMaxTargetSide = 32;
constexpr uint64_t kMaxTexels = 4096;
constexpr int kMaxDraws = 8;
constexpr uint32_t kMaxDrawVertices = 48;
constexpr auto kTimeBudget = std::chrono::milliseconds(250);

bool small(const refx::scene::TextureDef& t) {
  const uint64_t faces = t.type == refx::TextureType::Cube ? 6 : 1;
  return uint64_t(t.width) * uint64_t(t.height) * uint64_t(t.depth) * faces <= kMaxTexels;
}

void run(refx::scene::SceneScript& script) {
  using namespace refx;
  static const CapsProfile caps = loadCapsProfile("ref");
  script.width = std::min(script.width, kMaxTargetSide);
  script.height = std::min(script.height, kMaxTargetSide);
  DeviceOptions options;
  options.threads = 1;
  Device device(caps, options);
  int draws = 0;
  const auto deadline = std::chrono::steady_clock::now() + kTimeBudget;
  auto allowed = [&](const scene::Command& c) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    if (const auto* t = std::get_if<scene::TextureDef>(&c.action))
      return t->generator != scene::Generator::File && small(*t);
    if (const auto* s = std::get_if<scene::Shader>(&c.action))
      return s->source != scene::Shader::Source::File;
    if (const auto* d = std::get_if<scene::Draw>(&c.action))
      return d->vertexCount <= kMaxDrawVertices && ++draws <= kMaxDraws;
    if (const auto* r = std::get_if<scene::SetRenderTarget>(&c.action))
      return r->width <= kMaxTargetSide && r->height <= kMaxTargetSide;
    return true;
  };
  try {
    const scene::SceneOutput output = scene::runSceneScript(script, device, allowed);
    (void)scene::checkSceneExpectations(script, output);
  } catch (const Error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  refx::scene::SceneScript script;
  try {
    script = refx::scene::parseSceneScript(text, "fuzz.scene");
  } catch (const refx::Error&) {
    return 0;
  }
  run(script);
  return 0;
}
