// fx_2_0 binary fuzz target: any bytes either load as an effect or give refx::Error; an
// effect that loads validates every technique and applies every pass to a device,
// running its FXLC state expressions and shader preshaders.
#include <cstddef>
#include <cstdint>
#include <span>

#include "refx/core/diagnostics.h"
#include "refx/effect/effect.h"
#include "refx/pipeline/device.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace refx;
  static const CapsProfile ref = loadCapsProfile("ref");
  std::unique_ptr<effect::Effect> fx;
  try {
    fx = effect::Effect::fromFx2(std::span<const uint8_t>(data, size), "fuzz.fxo");
  } catch (const Error&) {
    return 0;
  }
  for (effect::Handle p = 0; p < fx->parameterCount(); ++p) (void)fx->parameterDesc(p);
  DeviceOptions opt;
  opt.threads = 1;
  Device device(ref, opt);
  for (effect::Handle t = 0; t < fx->techniqueCount(); ++t) {
    (void)fx->validateTechnique(t, ref);
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
