// What the effect fuzz targets do with an effect that loaded: validate every technique
// on the given profiles and apply every pass of each to a device, evaluating every state
// assignment (and preshader) with the parameters' values. Errors are expected; crashes
// and hangs are not.
#pragma once
#include <initializer_list>

#include "refx/core/diagnostics.h"
#include "refx/effect/effect.h"
#include "refx/pipeline/device.h"

inline void exerciseEffect(refx::effect::Effect& fx, std::initializer_list<const refx::CapsProfile*> profiles) {
  using namespace refx;
  for (effect::Handle p = 0; p < fx.parameterCount(); ++p) (void)fx.parameterDesc(p);
  DeviceOptions opt;
  opt.threads = 1;
  Device device(**profiles.begin(), opt);
  for (effect::Handle t = 0; t < fx.techniqueCount(); ++t) {
    for (const CapsProfile* caps : profiles) (void)fx.validateTechnique(t, *caps);
    if (!fx.techniqueDesc(t).brokenReason.empty()) continue;
    fx.setTechnique(t);
    try {
      const int passes = fx.begin(device, 0);
      for (int i = 0; i < passes; ++i) {
        try {
          fx.beginPass(i);
        } catch (const Error&) {
        }
        fx.endPass();
      }
      fx.end();
    } catch (const Error&) {
      return;
    }
  }
}
