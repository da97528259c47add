#include "refx/pipeline/shader_object.h"

#include "refx/core/diagnostics.h"

namespace refx {

ShaderObject::ShaderObject(std::span<const uint32_t> tokens, shader::ShaderType type,
                           const shader::ValidationCaps& caps)
    : tokens_(tokens.begin(), tokens.end()), shader_(shader::decode(tokens)) {
  const bool pixel = type == shader::ShaderType::Pixel;
  if (shader_.version.type != type)
    fail("{} shader expected, got {}", pixel ? "a pixel" : "a vertex", shader_.version.name());
  const std::vector<Diagnostic> problems = shader::validate(shader_, caps);
  if (!problems.empty()) fail("{}", shader::describeViolations(shader_.version.name(), problems));
  lowered({});
}

shader::ValidationCaps shaderValidationCaps(const CapsProfile& caps) {
  shader::ValidationCaps v;
  v.maxVertexShaderConst = int(caps.maxVertexShaderConst);
  v.ps2xFlowControl = caps.psMajor() >= 3;
  v.vs2xFlowControl = caps.vsMajor() >= 3;
  return v;
}

std::shared_ptr<const exec::LoweredShader> ShaderObject::lowered(
    const exec::ShaderLoweringOptions& options) const {
  std::lock_guard lock(mutex_);
  for (const auto& [o, program] : cache_)
    if (o.precision == options.precision && o.pixelShader1xMaxValue == options.pixelShader1xMaxValue &&
        o.projectedTextureStages == options.projectedTextureStages &&
        o.colorInputsInRange == options.colorInputsInRange)
      return program;
  auto program = std::make_shared<const exec::LoweredShader>(exec::lowerShader(shader_, options));
  cache_.emplace_back(options, program);
  return program;
}

}  // namespace refx
