// An effect drawn as an effect viewer draws it (DirectX's EffectEdit): a mesh at the
// origin, a camera and a directional light, the standard semantics bound from them,
// textures from annotations or the command line, a technique chosen by validation.
// Shared by `refx render`, `refx watch` and the effect samples of `refx gallery`.
#pragma once
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "refx/d3dx/mesh.h"
#include "refx/effect/effect.h"
#include "refx/pipeline/device.h"

namespace refx::cli {

struct EffectSceneOptions {
  std::string mesh = "sphere";  // sphere | teapot | torus | box | FILE.x | FILE.obj | a built-in mesh
  // texture or sampler parameter → built-in texture or image file
  std::map<std::string, std::string> textures;
  std::vector<std::pair<std::string, std::string>> sets;  // parameter → value ("1,0,0,1", text)
  float time = 0;
  // Constants the application sets itself after each BeginPass (registers an effect
  // reads but does not assign, as the DirectX 8 BRDF sample's eye position in c10).
  std::vector<std::pair<int, Vec4>> vsConstants, psConstants;
};

// Which technique ran and why the better ones did not.
struct TechniqueChoice {
  effect::Handle technique = -1;
  std::vector<std::string> rejected;  // "tec1: pass p0: pixel shader ps_1_4 needs …"
};

// The first technique (in file order, best first) valid on `caps`; or the named one,
// which must exist (refx::Error otherwise) and is used even when invalid, with the
// reason in `rejected`.
TechniqueChoice chooseTechnique(const effect::Effect& fx, const CapsProfile& caps, const std::string& name,
                                const effect::SelectionPolicy& policy = {});

// Meshes, textures and parameter values of one effect file; keeps meshes and
// textures across reloads of the same file.
class EffectScene {
 public:
  explicit EffectScene(EffectSceneOptions options);
  // Binds textures and the non-semantic values an effect needs once after loading.
  // Returns warnings (a texture parameter nothing binds …).
  std::vector<std::string> prepare(effect::Effect& fx);
  // Sets the per-frame semantics (WORLD … TIME) for `device`'s target size and draws
  // every pass of the current technique. The background comes from `DWORD BCLR`.
  void draw(effect::Effect& fx, Device& device);
  const d3dx::Mesh& mesh();
  void setTime(float seconds) { options_.time = seconds; }

 private:
  void bindDeclarationStream(Device& device);
  void bindSamplerTextures(Device& device);
  void declareShaderInputs(Device& device);
  EffectSceneOptions options_;
  std::optional<d3dx::Mesh> mesh_;
  std::string meshName_;
  std::vector<std::pair<VertexDeclaration, VertexBufferPtr>> repacked_;
  std::vector<std::pair<std::string, TexturePtr>> samplerTextures_;  // sampler parameter → texture
};

}  // namespace refx::cli
