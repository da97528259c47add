// fx_2_0 binary fuzz target: any bytes either load as an effect or give refx::Error; an
// effect that loads validates every technique and applies every pass to a device,
// running its FXLC state expressions and shader preshaders.
#include <cstddef>
#include <cstdint>
#include <span>

#include "exercise_effect.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace refx;
  static const CapsProfile ref = loadCapsProfile("ref");
  std::unique_ptr<effect::Effect> fx;
  try {
    fx = effect::Effect::fromFx2(std::span<const uint8_t>(data, size), "fuzz.fxo");
  } catch (const Error&) {
    return 0;
  }
  exerciseEffect(*fx, {&ref});
  return 0;
}
