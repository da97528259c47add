// Runs a parsed scene script against a Device, command by command.
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "refx/core/diagnostics.h"
#include "refx/pipeline/device.h"
#include "refx/scene/scene_script.h"
#include "refx/resource/image_io.h"
#include "refx/shader/assembler.h"
#include "refx/shader/validator.h"

namespace refx::scene {

namespace {

class Runner {
 public:
  Runner(const SceneScript& script, Device& device, const SceneCommandFilter& filter)
      : script_(script), device_(device), filter_(filter) {
    base_ = std::filesystem::path(script.file).parent_path();
  }

  SceneOutput run() {
    SceneOutput& out = out_;
    // A new target holds 0x00000000 until the first clear.
    out.target = Texture::create2D(script_.targetFormat, script_.width, script_.height, 1);
    out.targets[0] = out.target;
    out.depthStencil = std::make_shared<DepthStencilSurface>(script_.width, script_.height);
    device_.setRenderTarget(out.target);
    device_.setDepthStencilSurface(out.depthStencil);
    for (const Command& c : script_.commands) {
      if (filter_ && !filter_(c)) continue;
      current_ = &c;
      try {
        std::visit([this](const auto& a) { apply(a); }, c.action);
      } catch (const Located&) {
        throw;
      } catch (const Error& e) {
        std::string msg = e.what();
        std::string here = where().str() + ":";
        if (msg.starts_with(here)) throw;  // already located by this runner
        if (msg.starts_with("error: ")) msg.erase(0, 7);
        std::string prefix = c.name + ": ";
        if (msg.starts_with(prefix)) msg.erase(0, prefix.size());
        throw Error(where(), c.name + ": " + msg);
      }
    }
    return std::move(out);
  }

 private:
  SourceLocation where() const { return SourceLocation{script_.file, current_->line, 0}; }

  [[noreturn]] void error(const std::string& msg) const {
    throw Error(where(), current_->name + ": " + msg);
  }

  std::string resolve(const std::string& path) const {
    std::filesystem::path p(path);
    if (p.is_relative()) p = base_ / p;
    return p.string();
  }

  void apply(const Clear& c) {
    device_.clear(d3d::CLEAR_TARGET | d3d::CLEAR_ZBUFFER | d3d::CLEAR_STENCIL, c.color, c.z,
                  c.stencil);
  }
  void apply(const SetRenderState& s) { device_.setRenderState(s.state, s.value); }
  void apply(const SetStageState& s) { device_.setTextureStageState(s.stage, s.state, s.value); }
  void apply(const SetSamplerState& s) { device_.setSamplerState(s.sampler, s.state, s.value); }

  void apply(const TextureDef& t) {
    // CreateTexture fails for sizes beyond the device's caps.
    const CapsProfile& caps = device_.caps();
    if (uint32_t(t.width) > caps.maxTextureWidth || uint32_t(t.height) > caps.maxTextureHeight)
      error(fmt::format("{}x{} exceeds MaxTextureWidth/Height {}x{} of caps profile {}", t.width,
                        t.height, caps.maxTextureWidth, caps.maxTextureHeight, caps.name));
    if (t.type == TextureType::Volume &&
        (uint32_t(t.width) > caps.maxVolumeExtent || uint32_t(t.height) > caps.maxVolumeExtent ||
         uint32_t(t.depth) > caps.maxVolumeExtent))
      error(fmt::format("{}x{}x{} exceeds MaxVolumeExtent {} of caps profile {}", t.width,
                        t.height, t.depth, caps.maxVolumeExtent, caps.name));
    TexturePtr image;
    if (t.generator == Generator::File) image = loadTexture(resolve(t.path));
    textures_[t.name] = createSceneTexture(t, image.get());
  }

  void apply(const SetTexture& s) {
    if (s.name.empty()) {
      device_.setTexture(s.sampler, nullptr);
      return;
    }
    auto it = textures_.find(s.name);
    if (it == textures_.end()) error(fmt::format("unknown texture '{}'", s.name));
    device_.setTexture(s.sampler, it->second);
  }

  // Assembles, validates and creates the shader. Errors in the shader text keep the
  // assembler's location: the scene file and line for an inline block (its lines are
  // numbered as in the script), the shader file otherwise.
  void apply(const Shader& s) {
    if (s.source == Shader::Source::None) {
      if (s.pixel) device_.setPixelShader(nullptr);
      else device_.setVertexShader(nullptr);
      return;
    }
    std::string text, file;
    if (s.source == Shader::Source::File) {
      file = resolve(s.path);
      std::ifstream in(file, std::ios::binary);
      if (!in) error(fmt::format("cannot open shader file {}", file));
      std::ostringstream ss;
      ss << in.rdbuf();
      if (in.bad()) error(fmt::format("cannot read shader file {}", file));
      text = ss.str();
    } else {
      file = script_.file;
      text.assign(size_t(std::max(s.textLine - 1, 0)), '\n');
      text += s.text;
    }
    shader::Shader parsed;
    try {
      parsed = shader::assemble(text, file);
      const bool pixel = parsed.version.isPixel();
      if (pixel != s.pixel)
        error(fmt::format("expected a {} shader ({}), got {}", s.pixel ? "pixel" : "vertex",
                          s.pixel ? "ps_1_1 to ps_3_0" : "vs_1_1 to vs_3_0",
                          parsed.version.name()));
      shader::requireValid(parsed, file, device_.shaderValidationCaps());
    } catch (const Error& e) {
      if (std::string_view(e.what()).starts_with(file + ":")) throw Located(e.what());
      throw;
    }
    const std::vector<uint32_t> tokens = shader::encode(parsed);
    if (s.pixel) device_.setPixelShader(device_.createPixelShader(tokens));
    else device_.setVertexShader(device_.createVertexShader(tokens));
  }

  // An error that already names its file and line.
  struct Located : Error {
    using Error::Error;
  };

  void apply(const SetConstants& c) {
    switch (c.type) {
      case SetConstants::Type::Float: {
        const auto n = uint32_t(c.floats.size() / 4);
        if (c.pixel) device_.setPixelShaderConstantF(uint32_t(c.reg), c.floats.data(), n);
        else device_.setVertexShaderConstantF(uint32_t(c.reg), c.floats.data(), n);
        break;
      }
      case SetConstants::Type::Int: {
        const auto n = uint32_t(c.ints.size() / 4);
        if (c.pixel) device_.setPixelShaderConstantI(uint32_t(c.reg), c.ints.data(), n);
        else device_.setVertexShaderConstantI(uint32_t(c.reg), c.ints.data(), n);
        break;
      }
      case SetConstants::Type::Bool: {
        const auto n = uint32_t(c.ints.size());
        if (c.pixel) device_.setPixelShaderConstantB(uint32_t(c.reg), c.ints.data(), n);
        else device_.setVertexShaderConstantB(uint32_t(c.reg), c.ints.data(), n);
        break;
      }
    }
  }

  void apply(const Draw& d) {
    if (d.declaration) device_.setVertexDeclaration(*d.declaration);
    else device_.setFVF(d.fvf);
    if (d.indices.empty()) {
      device_.drawPrimitiveUP(d.type, d.primitiveCount, d.vertices.data(), d.stride);
      return;
    }
    uint16_t lo = 0xffff, hi = 0;
    for (uint16_t i : d.indices) lo = std::min(lo, i), hi = std::max(hi, i);
    device_.drawIndexedPrimitiveUP(d.type, lo, uint32_t(hi - lo) + 1, d.primitiveCount,
                                   d.indices.data(), false, d.vertices.data(), d.stride);
  }

  void apply(const SetTransform& t) { device_.setTransform(t.type, t.matrix); }
  void apply(const SetMaterial& m) { device_.setMaterial(m.material); }
  void apply(const SetLight& l) {
    if (l.enable) device_.setLight(l.index, l.light);
    device_.lightEnable(l.index, l.enable);
  }
  void apply(const SetViewport& v) { device_.setViewport(v.viewport); }
  void apply(const SetScissor& s) { device_.setScissorRect(s.rect); }
  void apply(const SetRenderTarget& r) {
    if (r.none) {
      device_.setRenderTarget(r.index, nullptr);
      return;
    }
    // Like the first target, a new one holds 0x00000000 until a clear.
    TexturePtr t = Texture::create2D(r.format, r.width, r.height, 1);
    device_.setRenderTarget(r.index, t);
    out_.targets[size_t(r.index)] = std::move(t);
  }
  void apply(const SetClipPlane& c) {
    const float plane[4] = {c.plane.x, c.plane.y, c.plane.z, c.plane.w};
    device_.setClipPlane(c.index, plane);
  }

  const SceneScript& script_;
  Device& device_;
  const SceneCommandFilter& filter_;
  std::filesystem::path base_;
  const Command* current_ = nullptr;
  std::map<std::string, TexturePtr> textures_;
  SceneOutput out_;
};

}  // namespace

SceneOutput runSceneScript(const SceneScript& script, Device& device,
                           const SceneCommandFilter& filter) {
  return Runner(script, device, filter).run();
}

}  // namespace refx::scene
