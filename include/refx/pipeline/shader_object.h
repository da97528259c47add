// Shader objects of the device (IDirect3DVertexShader9 / IDirect3DPixelShader9): the
// token stream as created and its decoded form (the exec programs it lowers to are the
// pipeline's own business: src/pipeline/shader_lowering.h).
#pragma once
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "refx/pipeline/caps.h"
#include "refx/shader/bytecode.h"
#include "refx/shader/validator.h"

namespace refx {

class ShaderObject {
 public:
  ShaderObject(const ShaderObject&) = delete;
  ShaderObject& operator=(const ShaderObject&) = delete;
  virtual ~ShaderObject();

  const std::vector<uint32_t>& tokens() const { return tokens_; }
  const shader::Shader& decoded() const { return shader_; }
  shader::Version version() const { return shader_.version; }

  // The programs the shader lowered to, one per distinct lowering options (defined by
  // the pipeline, which alone runs them).
  struct LoweringCache;
  LoweringCache& loweringCache() const { return *lowering_; }

 protected:
  // Decodes, validates (refx::Error listing every rule broken, one per line) and lowers once, so a
  // shader the executor cannot run fails here, as CreateVertexShader/CreatePixelShader do.
  ShaderObject(std::span<const uint32_t> tokens, shader::ShaderType type,
               const shader::ValidationCaps& caps);

 private:
  std::vector<uint32_t> tokens_;
  shader::Shader shader_;
  std::unique_ptr<LoweringCache> lowering_;
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
