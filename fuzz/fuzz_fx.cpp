// Effect (.fx) fuzz target: any text either loads or gives refx::Error; an effect that
// loads validates every technique on two generations and applies every pass of each
// to a device, evaluating every state assignment with the parameters' values.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "exercise_effect.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace refx;
  static const CapsProfile ref = loadCapsProfile("ref");
  static const CapsProfile dx6 = loadCapsProfile("dx6-tnt2");
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::unique_ptr<effect::Effect> fx;
  try {
    fx = effect::Effect::fromText(text, "fuzz.fx");
  } catch (const Error&) {
    return 0;
  }
  exerciseEffect(*fx, {&ref, &dx6});
  return 0;
}
