// How the device lowers its shader objects to exec programs: the lowering options a
// device uses, and the programs each shader object keeps per options.
#pragma once
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "refx/exec/lower.h"
#include "refx/pipeline/device.h"
#include "refx/pipeline/shader_object.h"

namespace refx {

struct ShaderObject::LoweringCache {
  std::mutex mutex;
  std::vector<std::pair<exec::ShaderLoweringOptions, std::shared_ptr<const exec::LoweredShader>>> programs;
};

namespace pipeline {

// The program `shader` lowers to with `options`: lowered once per distinct options and
// kept (the lowering depends on the precision model and the profile's value range).
std::shared_ptr<const exec::LoweredShader> loweredShader(const ShaderObject& shader,
                                                         const exec::ShaderLoweringOptions& options);

// How pixel shaders are lowered on `device`: its precision model and its profile's
// PixelShader1xMaxValue.
exec::ShaderLoweringOptions shaderLoweringOptions(const Device& device, shader::Version version);

}  // namespace pipeline
}  // namespace refx
