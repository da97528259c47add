#include "refx/pipeline/shader_object.h"

#include "refx/core/diagnostics.h"
#include "shader_lowering.h"

namespace refx {

ShaderObject::ShaderObject(std::span<const uint32_t> tokens, shader::ShaderType type,
                           const shader::ValidationCaps& caps)
    : tokens_(tokens.begin(), tokens.end()), shader_(shader::decode(tokens)),
      lowering_(std::make_unique<LoweringCache>()) {
  const bool pixel = type == shader::ShaderType::Pixel;
  if (shader_.version.type != type)
    fail("{} shader expected, got {}", pixel ? "a pixel" : "a vertex", shader_.version.name());
  const std::vector<Diagnostic> problems = shader::validate(shader_, caps);
  if (!problems.empty()) fail("{}", shader::describeViolations(shader_.version.name(), problems));
  pipeline::loweredShader(*this, {});
}

ShaderObject::~ShaderObject() = default;

shader::ValidationCaps shaderValidationCaps(const CapsProfile& caps) {
  shader::ValidationCaps v;
  v.maxVertexShaderConst = int(caps.maxVertexShaderConst);
  v.ps2xFlowControl = caps.psMajor() >= 3;
  v.vs2xFlowControl = caps.vsMajor() >= 3;
  return v;
}

std::shared_ptr<const exec::LoweredShader> pipeline::loweredShader(
    const ShaderObject& shader, const exec::ShaderLoweringOptions& options) {
  ShaderObject::LoweringCache& cache = shader.loweringCache();
  std::lock_guard lock(cache.mutex);
  for (const auto& [o, program] : cache.programs)
    if (o.precision == options.precision && o.pixelShader1xMaxValue == options.pixelShader1xMaxValue &&
        o.projectedTextureStages == options.projectedTextureStages &&
        o.colorInputsInRange == options.colorInputsInRange)
      return program;
  auto program = std::make_shared<const exec::LoweredShader>(exec::lowerShader(shader.decoded(), options));
  cache.programs.emplace_back(options, program);
  return program;
}

}  // namespace refx
