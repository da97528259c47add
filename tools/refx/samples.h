// Built-in samples: each renders one technique from the seeds on a device and says
// which technique it chose for the active caps profile and why.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "refx/scene/mesh_binding.h"
#include "refx/d3dx/mesh.h"
#include "refx/pipeline/device.h"

namespace refx::samples {

struct SampleResult {
  std::string technique;   // technique actually rendered
  std::string validation;  // "valid (1 pass)" or the reason the preferred technique failed
  std::vector<std::string> notes;
};

struct Sample {
  std::string name;   // file name stem, e.g. "dx6-bump-earth"
  std::string title;  // one line for the gallery
  std::string source; // where in the seeds it comes from
  std::function<SampleResult(Device&)> render;  // device has target + depth attached, cleared
};

const std::vector<Sample>& allSamples();
// The seeds' examples as effect files (data/effects) drawn through the effect
// framework (RacorX6-14, the per-pixel lighting column, hemisphere lighting, the BRDF
// effect, the HLSL programs ...); allSamples() lists them last.
const std::vector<Sample>& effectSamples();


}  // namespace refx::samples
