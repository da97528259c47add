// Effect (.fx) fuzz target: any text either loads or gives refx::Error; an effect that
// loads validates every technique on two generations and applies every pass of each
// to a device, evaluating every state assignment with the parameters' values.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "refx/core/diagnostics.h"
#include "refx/effect/effect.h"
#include "refx/pipeline/device.h"

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
  for (effect::Handle p = 0; p < fx->parameterCount(); ++p) (void)fx->parameterDesc(p);
  DeviceOptions opt;
  opt.threads = 1;
  Device device(ref, opt);
  for (effect::Handle t = 0; t < fx->techniqueCount(); ++t) {
    (void)fx->validateTechnique(t, ref);
    (void)fx->validateTechnique(t, dx6);
    if (!fx->techniqueDesc(t).brokenReason.empty()) continue;
    fx->setTechnique(t);
    try {
      const int passes = fx->begin(device, 0);
      for (int i = 0; i < passes; ++i) {
        try {
          fx->beginPass(i);
        } catch (const Error&) {
        }
        fx->endPass();
      }
      fx->end();
    } catch (const Error&) {
      return 0;
    }
  }
  return 0;
}
