// ValidateDevice with the render targets bound beside DeviceState (Device holds them,
// not the state value): the multiple-render-target caps are checked against these.
#pragma once
#include "refx/pipeline/caps.h"

namespace refx::pipeline {

struct RenderTargetBinding {
  int count = 1;               // render targets 0..count-1 bound
  bool formatsDiffer = false;  // not all of one format (MRTINDEPENDENTBITDEPTHS)
};

ValidationResult validateDeviceState(const DeviceState& state, const CapsProfile& caps,
                                     const RenderTargetBinding& targets);

}  // namespace refx::pipeline
