// Shader objects of the device (IDirect3DVertexShader9 / IDirect3DPixelShader9): the
// token stream as created, its decoded form, and the exec programs it lowers to.
#pragma once
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <utility>
#include <vector>

#include "refx/exec/lower.h"
#include "refx/pipeline/caps.h"
#include "refx/shader/bytecode.h"
#include "refx/shader/validator.h"

namespace refx {

class ShaderObject {
 public:
  ShaderObject(const ShaderObject&) = delete;
  ShaderObject& operator=(const ShaderObject&) = delete;
  virtual ~ShaderObject() = default;

  const std::vector<uint32_t>& tokens() const { return tokens_; }
  const shader::Shader& decoded() const { return shader_; }
  shader::Version version() const { return shader_.version; }

  // The program lowered with `options`: lowered once per distinct options and kept
  // (the lowering depends on the precision model and the profile's value range).
  std::shared_ptr<const exec::LoweredShader> lowered(const exec::ShaderLoweringOptions& options) const;

 protected:
  // Decodes, validates (refx::Error listing every rule broken, one per line) and lowers once, so a
  // shader the executor cannot run fails here, as CreateVertexShader/CreatePixelShader do.
  ShaderObject(std::span<const uint32_t> tokens, shader::ShaderType type,
               const shader::ValidationCaps& caps);

 private:
  std::vector<uint32_t> tokens_;
  shader::Shader shader_;
  mutable std::mutex mutex_;
  mutable std::vector<std::pair<exec::ShaderLoweringOptions, std::shared_ptr<const exec::LoweredShader>>>
      cache_;
};

class VertexShader : public ShaderObject {
 public:
  VertexShader(std::span<const uint32_t> tokens, const shader::ValidationCaps& caps = {})
      : ShaderObject(tokens, shader::ShaderType::Vertex, caps) {}
};

class PixelShader : public ShaderObject {
 public:
  PixelShader(std::span<const uint32_t> tokens, const shader::ValidationCaps& caps = {})
      : ShaderObject(tokens, shader::ShaderType::Pixel, caps) {}
};

// The version rules' device limits of a caps profile: MaxVertexShaderConst, and the
// vs_2_x / ps_2_x extensions (flow control, predication, gradients) on shader model 3
// parts only (PS20Caps/VS20Caps of a 2.0 part are taken as without them).
shader::ValidationCaps shaderValidationCaps(const CapsProfile& caps);

using VertexShaderPtr = std::shared_ptr<const VertexShader>;
using PixelShaderPtr = std::shared_ptr<const PixelShader>;

}  // namespace refx
