// Runs a parsed .shader_test file on a refx::Device, as vkd3d's Direct3D 9 runner
// drives IDirect3DDevice9 (docs/shader_test_format.md).
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <map>
#include <set>

#include <fmt/ranges.h>

#include "refx/core/diagnostics.h"
#include "refx/hlsl/compiler.h"
#include "refx/pipeline/device.h"
#include "refx/scene/shader_test.h"
#include "refx/shader/assembler.h"

namespace refx::scene {

namespace {

constexpr int kTargetWidth = 640, kTargetHeight = 480;
// The render target is A32B32G32R32F, as in vkd3d's D3D9 runner. A float probe also
// matches within half an 8-bit step (1/510) besides its ulps: the expected values of
// refx's own test files are written to that precision.
constexpr float kProbeTolerance = 0.5f / 255.0f;

std::string modelName(ShaderModel m) { return fmt::format("{}.{}", m / 10, m % 10); }

std::string describeRange(const RequireSection& r) {
  if (r.minModel > kLowestShaderModel && r.belowModel <= kHighestShaderModel)
    return fmt::format("shader model >= {} and < {}", modelName(r.minModel), modelName(r.belowModel));
  if (r.minModel > kLowestShaderModel) return fmt::format("shader model >= {}", modelName(r.minModel));
  return fmt::format("shader model < {}", modelName(r.belowModel));
}

// Distance in representable floats (0 for equal values, +0 and -0 included).
uint64_t ulpDistance(float a, float b) {
  auto key = [](float f) {
    const int32_t i = std::bit_cast<int32_t>(f);
    return i < 0 ? int64_t(INT32_MIN) - int64_t(i) : int64_t(i);
  };
  const int64_t d = key(a) - key(b);
  return uint64_t(d < 0 ? -d : d);
}

// "hex DWORDs" of a d3dbc-hex body: groups of 8 hex digits, whitespace between them.
std::vector<uint32_t> parseHexTokens(const std::string& text, int firstLine) {
  std::vector<uint32_t> tokens;
  int line = firstLine, digits = 0;
  uint32_t value = 0;
  auto flush = [&] {
    if (digits == 0) return;
    if (digits != 8) fail("line {}: hex tokens are 8 digits each, found {} digits", line, digits);
    tokens.push_back(value);
    digits = 0;
    value = 0;
  };
  for (char ch : text) {
    if (ch == '\n' || std::isspace(static_cast<unsigned char>(ch))) {
      flush();
      if (ch == '\n') ++line;
      continue;
    }
    int nibble = -1;
    if (ch >= '0' && ch <= '9') nibble = ch - '0';
    else if (ch >= 'a' && ch <= 'f') nibble = ch - 'a' + 10;
    else if (ch >= 'A' && ch <= 'F') nibble = ch - 'A' + 10;
    if (nibble < 0) fail("line {}: '{}' is not a hex digit", line, ch);
    if (digits == 8) fail("line {}: hex tokens are 8 digits each, found more", line);
    value = (value << 4) | uint32_t(nibble);
    ++digits;
  }
  flush();
  if (tokens.empty()) fail("the section holds no tokens");
  return tokens;
}

std::optional<uint8_t> declUsage(const std::string& semantic) {
  std::string s = semantic;
  for (char& ch : s) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  static const std::map<std::string, uint8_t> kUsages = {
      {"position", d3d::DECLUSAGE_POSITION}, {"sv_position", d3d::DECLUSAGE_POSITION},
      {"blendweight", d3d::DECLUSAGE_BLENDWEIGHT}, {"blendindices", d3d::DECLUSAGE_BLENDINDICES},
      {"normal", d3d::DECLUSAGE_NORMAL}, {"psize", d3d::DECLUSAGE_PSIZE}, {"texcoord", d3d::DECLUSAGE_TEXCOORD},
      {"tangent", d3d::DECLUSAGE_TANGENT}, {"binormal", d3d::DECLUSAGE_BINORMAL},
      {"positiont", d3d::DECLUSAGE_POSITIONT}, {"color", d3d::DECLUSAGE_COLOR}, {"fog", d3d::DECLUSAGE_FOG},
      {"depth", d3d::DECLUSAGE_DEPTH}, {"sample", d3d::DECLUSAGE_SAMPLE}};
  auto it = kUsages.find(s);
  if (it == kUsages.end()) return std::nullopt;
  return it->second;
}

int componentCount(ElementFormat f) {
  switch (f) {
    case ElementFormat::Float1: return 1;
    case ElementFormat::Float2: return 2;
    case ElementFormat::Float3: return 3;
    case ElementFormat::Float4: return 4;
    case ElementFormat::Unsupported: return 0;
  }
  return 0;
}

std::string profileFor(ShaderStage stage, ShaderModel model) {
  return fmt::format("{}_{}_0", stage == ShaderStage::Vertex ? "vs" : "ps", model / 10);
}

// Why a [require] section keeps the sections after it from running at `model`;
// empty when they run.
std::string whyInactive(const RequireSection& r, ShaderModel model) {
  if (model < r.minModel || model >= r.belowModel) return "requires " + describeRange(r);
  if (!r.missingCaps.empty()) return fmt::format("requires '{}'", r.missingCaps.front());
  return {};
}

// Why an active section ends the run on a D3D9 device; empty when it does not.
std::string whyStop(const UnsupportedSection& u) {
  return fmt::format("[{}] sections are not run on a D3D9 device", u.name);
}
std::string whyStop(const ShaderSection& s) {
  if (s.stage == ShaderStage::Effect) return "[effect] sections are not run yet";
  if (s.stage == ShaderStage::Unsupported) return fmt::format("[{}] needs a D3D10+ device", s.stageName);
  if (s.source == ShaderSource::OtherHex) return "dxbc hex shaders need a D3D10+ device";
  return {};
}

ShaderCompilation planCompilation(const ShaderSection& s, int line, ShaderModel model, const RequireSection& require) {
  ShaderCompilation c;
  c.section = &s;
  c.line = line;
  c.options.profile = profileFor(s.stage, model);
  c.options.rowMajorDefault = require.rowMajor;
  // Blank lines in front keep the compiler's line numbers those of the file.
  c.source = std::string(size_t(std::max(s.bodyLine - 1, 0)), '\n') + s.text;
  c.mustFail = s.fail && s.fail->holds(model);
  c.notImplemented = s.notimpl && s.notimpl->holds(model);
  return c;
}

class Runner {
 public:
  Runner(const ShaderTestFile& file, ShaderModel model, const ShaderTestOptions& options)
      : file_(file), model_(model), device_(loadCapsProfile("ref"), deviceOptions(options)) {
    result_.model = model;
  }

  ShaderTestResult run() {
    for (const auto& entry : file_.sections) {
      if (stopped_) break;
      std::visit([&](const auto& s) { section(s, entry.line); }, entry.section);
    }
    if (!result_.failures.empty()) {
      result_.status = ShaderTestResult::Status::Failed;
    } else if (result_.commandsRun == 0 && !firstSkipReason_.empty()) {
      result_.status = ShaderTestResult::Status::Skipped;
      result_.skipReason = firstSkipReason_;
    }
    return std::move(result_);
  }

 private:
  static DeviceOptions deviceOptions(const ShaderTestOptions& o) {
    DeviceOptions d;
    d.threads = o.threads;
    return d;
  }
  void failAtLine(int line, std::string message) { result_.failures.push_back({line, std::move(message)}); }
  void noteSkip(const std::string& reason) {
    if (firstSkipReason_.empty()) firstSkipReason_ = reason;
  }
  // Ends the file: what follows cannot run on this device.
  void stop(const std::string& reason) {
    noteSkip(reason);
    stopped_ = true;
  }
  std::string profile(ShaderStage stage) const { return profileFor(stage, model_); }

  // ---- sections ----
  void section(const RequireSection& r, int) {
    require_ = r;
    skipTests_.clear();
    inactive_ = whyInactive(r, model_);
  }

  void section(const UnsupportedSection& u, int) {
    if (inactive_.empty()) stop(whyStop(u));
  }

  void section(const SamplerSection& s, int) { samplers_[s.slot] = s; }
  void section(const InputLayoutSection& l, int) { layout_ = l; }

  void section(const ResourceSection& r, int line) {
    if (!inactive_.empty()) return;
    const auto key = std::pair(int(r.kind), r.slot);
    failedResources_.erase(key);
    std::string why = r.unsupported;
    if (why.empty() && r.kind != ResourceSection::Kind::VertexBuffer && r.format == ElementFormat::Unsupported)
      why = fmt::format("format {} has no D3D9 equivalent here", r.formatName);
    if (why.empty() && r.kind == ResourceSection::Kind::RenderTarget && r.slot != 0)
      why = "refx's device has one render target";
    if (!why.empty()) {
      failedResources_[key] = why;
      return;
    }
    try {
      switch (r.kind) {
        case ResourceSection::Kind::Texture: textures_[r.slot] = makeTexture(r); break;
        case ResourceSection::Kind::RenderTarget: setTarget(r.width, r.height); break;
        case ResourceSection::Kind::VertexBuffer: {
          auto vb = std::make_shared<VertexBuffer>();
          vb->data.resize(r.data.size() * 4);
          std::memcpy(vb->data.data(), r.data.data(), vb->data.size());
          vertexBuffers_[r.slot] = vb;
          break;
        }
        case ResourceSection::Kind::Unsupported: break;
      }
    } catch (const Error& e) {
      failAtLine(line, e.what());
    }
  }

  void section(const ShaderSection& s, int line) {
    if (!inactive_.empty()) {
      clearShader(s.stage);
      return;
    }
    if (std::string why = whyStop(s); !why.empty()) return stop(why);
    const ShaderCompilation plan = planCompilation(s, line, model_, require_);
    const bool mustFail = plan.mustFail;
    const bool notImplemented = plan.notImplemented;
    std::string error;
    std::vector<uint32_t> tokens;
    if (s.source == ShaderSource::D3dbcHex) {
      try {
        tokens = parseHexTokens(s.text, s.bodyLine);
      } catch (const Error& e) {
        failAtLine(line, fmt::format("malformed d3dbc-hex: {}", e.what()));
        skipTests_ = "a malformed shader section";
        clearShader(s.stage);
        return;
      }
    } else {
      hlsl::CompileResult compiled = hlsl::compile(plan.source, file_.path, plan.options);
      if (compiled.ok()) tokens = std::move(compiled.tokens);
      else error = compiled.diagnostics.empty() ? "compilation failed" : compiled.diagnostics.front().str();
    }
    if (error.empty()) {
      try {
        if (s.stage == ShaderStage::Pixel) pixelShader_ = device_.createPixelShader(tokens);
        else vertexShader_ = device_.createVertexShader(tokens);
      } catch (const Error& e) {
        error = e.what();
      }
    }
    const std::string what = fmt::format("{} for {}", s.stageName, profile(s.stage));
    if (error.empty()) {
      if (mustFail) failAtLine(line, fmt::format("{} compiled, but the section says it must fail", what));
      skipTests_.clear();
      return;
    }
    clearShader(s.stage);
    if (mustFail) {
      skipTests_ = fmt::format("the {} fails as expected", s.stageName);
    } else if (notImplemented) {
      skipTests_ = fmt::format("{} is not implemented: {}", what, error);
    } else {
      failAtLine(line, fmt::format("{} failed: {}", what, error));
      skipTests_ = "a shader that failed";
    }
  }

  void section(const TestSection& t, int) {
    for (const TestCommand& cmd : t.commands) {
      if (!inactive_.empty()) return noteSkip(inactive_);
      if (!skipTests_.empty()) return noteSkip(skipTests_);
      if (!failedResources_.empty()) return noteSkip(failedResources_.begin()->second);
      bool run = true;
      for (const Condition& q : cmd.onlyIf) run = run && q.holds(model_);
      if (!run) continue;
      ++result_.commandsRun;
      try {
        std::visit([&](const auto& body) { command(body, cmd.line); }, cmd.body);
      } catch (const Error& e) {
        failAtLine(cmd.line, e.what());
      }
    }
  }

  // ---- commands ----
  void command(const UnknownCommand& u, int line) { failAtLine(line, fmt::format("unsupported test line: {}", u.text)); }
  void command(const MalformedCommand& m, int line) { failAtLine(line, m.message); }

  void command(const UniformCommand& u, int) {
    const size_t count = u.floats.size() + u.ints.size();
    if (size_t(u.offset) + count > size_t(kMaxVertexShaderConstF) * 4)
      fail("uniform {} is beyond c{}", u.offset, kMaxVertexShaderConstF - 1);
    const size_t needed = (size_t(u.offset) + count + 3) / 4 * 4;
    if (uniforms_.size() < needed) uniforms_.resize(needed, 0.0f);
    const bool isUint = u.type == UniformCommand::Type::Uint || u.type == UniformCommand::Type::Uint4;
    for (size_t i = 0; i < count; ++i) {
      const size_t word = size_t(u.offset) + i;
      if (!u.floats.empty()) {
        uniforms_[word] = u.floats[i];
        continue;
      }
      // D3D9 has no integer constant buffer: the value goes to the float register as
      // a number, to the int register i# of the same index, and (the x component) to
      // the bool register b# of the same index.
      const int64_t v = u.ints[i];
      uniforms_[word] = isUint ? float(uint32_t(v)) : float(int32_t(v));
      if (word / 4 < size_t(kMaxShaderConstI)) intUniforms_[word / 4][word % 4] = int(int32_t(uint32_t(v)));
      if (word % 4 == 0 && word / 4 < boolUniforms_.size()) boolUniforms_[word / 4] = v != 0;
    }
  }

  void command(const ClearCommand& c, int) {
    if (c.slot != 0) fail("render target {} does not exist (refx's device has one)", c.slot);
    ensureTarget();
    const Color4 color{c.color[0], c.color[1], c.color[2], c.color[3]};
    device_.clear(d3d::CLEAR_TARGET, colorToD3D(color), 1.0f, 0);
  }

  void command(const AlphaTestCommand& a, int) { alphaTest_ = a; }
  void command(const ShadeModeCommand& s, int) { flatShading_ = s.flat; }
  void command(const FogCommand& f, int) { fog_ = f; }
  void command(const FogColorCommand& f, int) { std::copy(f.color, f.color + 4, fogColor_); }

  void command(const DrawCommand& d, int) {
    ensureTarget();
    if (!pixelShader_) fail("draw without a pixel shader");
    device_.setVertexShader(vertexShader_ ? vertexShader_ : defaultVertexShader());
    device_.setPixelShader(pixelShader_);
    uint32_t vertexCount = uint32_t(d.vertexCount);
    if (d.quad) {
      // One triangle over the whole target, as vkd3d draws its "quad".
      static constexpr float kQuad[] = {-2.0f, -2.0f, -2.0f, 4.0f, 4.0f, -2.0f};
      auto vb = std::make_shared<VertexBuffer>();
      vb->data.resize(sizeof kQuad);
      std::memcpy(vb->data.data(), kQuad, sizeof kQuad);
      VertexDeclaration decl;
      decl.elements.push_back({0, 0, d3d::DECLTYPE_FLOAT2, 0, d3d::DECLUSAGE_POSITION, 0, -1});
      device_.setVertexDeclaration(decl);
      device_.setStreamSource(0, vb, 0, 8);
      vertexCount = 3;
    } else {
      bindInputLayout(vertexCount);
    }
    setConstants();
    setTexturesAndSamplers();
    setRenderStates();
    uint32_t primitives = 0;
    d3d::PrimitiveType type = d3d::PrimitiveType(d.topology);
    switch (d.topology) {
      case Topology::TriangleList: primitives = vertexCount / 3; break;
      case Topology::TriangleStrip: primitives = vertexCount >= 3 ? vertexCount - 2 : 0; break;
      case Topology::PointList: primitives = vertexCount; break;
    }
    if (primitives) device_.drawPrimitive(type, 0, primitives);
  }

  void command(const ProbeCommand& p, int) {
    if (p.rtvSlot != 0) fail("render target {} does not exist (refx's device has one)", p.rtvSlot);
    if (!target_) fail("probe before anything was drawn or cleared");
    const TexturePtr& target = device_.renderTarget();
    const int w = target->width(), h = target->height();
    int left = p.left, top = p.top, right = p.right, bottom = p.bottom;
    if (p.all) left = 0, top = 0, right = w, bottom = h;
    if (right > w || bottom > h)
      fail("probe rectangle ({}, {}, {}, {}) is outside the {}x{} target", left, top, right, bottom, w, h);
    for (int y = top; y < bottom; ++y)
      for (int x = left; x < right; ++x) {
        const Color4 c = target->texel(0, 0, x, y);
        const float got[4] = {c.r, c.g, c.b, c.a};
        if (matches(p, got)) continue;
        std::string where = right - left == 1 && bottom - top == 1 ? fmt::format("({},{})", x, y)
                                                                  : fmt::format("({},{}) of ({},{},{},{})", x, y,
                                                                                left, top, right, bottom);
        fail("probe {} expected {}, got {}", where, expectedText(p), gotText(p, got));
      }
  }

  // ---- helpers ----
  static bool matches(const ProbeCommand& p, const float* got) {
    for (int i = 0; i < p.count; ++i) {
      if (p.kind != ProbeCommand::Kind::Float) {
        // vkd3d compares the bits a 32-bit float target holds.
        if (std::bit_cast<uint32_t>(got[i]) != uint32_t(p.ints[i])) return false;
        continue;
      }
      const float want = p.floats[i];
      if (std::isnan(want) ? std::isnan(got[i]) : ulpDistance(got[i], want) <= p.ulps) continue;
      if (std::fabs(got[i] - want) <= kProbeTolerance * (1.0f + 1e-4f)) continue;
      return false;
    }
    return true;
  }
  static std::string expectedText(const ProbeCommand& p) {
    std::vector<std::string> parts;
    for (int i = 0; i < p.count; ++i)
      parts.push_back(p.kind == ProbeCommand::Kind::Float ? fmt::format("{}", p.floats[i])
                      : p.kind == ProbeCommand::Kind::Uint ? fmt::format("{:#x}", uint32_t(p.ints[i]))
                                                           : fmt::format("{}", p.ints[i]));
    return fmt::format("{}({})", valueName(p), fmt::join(parts, ", "));
  }
  static std::string gotText(const ProbeCommand& p, const float* got) {
    std::vector<std::string> parts;
    for (int i = 0; i < p.count; ++i)
      parts.push_back(p.kind == ProbeCommand::Kind::Float ? fmt::format("{}", got[i])
                      : p.kind == ProbeCommand::Kind::Uint ? fmt::format("{:#x}", std::bit_cast<uint32_t>(got[i]))
                                                           : fmt::format("{}", std::bit_cast<int32_t>(got[i])));
    return fmt::format("{}({})", valueName(p), fmt::join(parts, ", "));
  }
  static std::string valueName(const ProbeCommand& p) {
    if (p.kind == ProbeCommand::Kind::Uint) return "u32";
    if (p.kind == ProbeCommand::Kind::Int) return "i32";
    return p.count == 4 ? "rgba" : p.count == 2 ? "rg" : "r";
  }
  void clearShader(ShaderStage stage) {
    if (stage == ShaderStage::Pixel) pixelShader_.reset();
    if (stage == ShaderStage::Vertex) vertexShader_.reset();
  }

  void setTarget(int w, int h) {
    target_ = Texture::create2D(Format::A32B32G32R32F, w, h);
    device_.setRenderTarget(target_);
    // Z is off in every draw, but the device's deferred clears expect a depth surface
    // of the target's size, as a D3D9 device's automatic one would be.
    device_.setDepthStencilSurface(std::make_shared<DepthStencilSurface>(w, h));
    device_.clear(d3d::CLEAR_TARGET | d3d::CLEAR_ZBUFFER | d3d::CLEAR_STENCIL, 0, 1.0f, 0);
  }
  void ensureTarget() {
    if (!target_) setTarget(kTargetWidth, kTargetHeight);
  }

  TexturePtr makeTexture(const ResourceSection& r) {
    Format format = Format::A32B32G32R32F;
    if (r.format == ElementFormat::Float1) format = Format::R32F;
    else if (r.format == ElementFormat::Float2) format = Format::G32R32F;
    else if (r.format != ElementFormat::Float4) fail("format {} has no D3D9 texture format here", r.formatName);
    const int comps = componentCount(r.format);
    // D3D9 parts cap textures far lower; this keeps a typo from allocating gigabytes.
    if (int64_t(r.width) * r.height * r.depth > (int64_t(1) << 24))
      fail("texture of {}x{}x{} texels is larger than refx's limit of 16M texels", r.width, r.height, r.depth);
    TexturePtr t;
    if (r.dimension == ResourceSection::Dimension::Tex2D) t = Texture::create2D(format, r.width, r.height, r.levels);
    else if (r.dimension == ResourceSection::Dimension::Tex3D)
      t = Texture::createVolume(format, r.width, r.height, r.depth, r.levels);
    else fail("cube and buffer textures are not uploaded yet");
    // Texels level by level, rows top to bottom, slices front to back.
    size_t word = 0;
    for (int level = 0; level < t->levelCount(); ++level)
      for (int z = 0; z < t->depth(level); ++z)
        for (int y = 0; y < t->height(level); ++y)
          for (int x = 0; x < t->width(level); ++x) {
            float v[4] = {0, 0, 0, 0};
            for (int c = 0; c < comps; ++c, ++word)
              v[c] = word < r.data.size() ? std::bit_cast<float>(r.data[word]) : 0.0f;
            t->setTexel(0, level, x, y, z, Color4{v[0], v[1], v[2], v[3]});
          }
    t->markDirty();
    return t;
  }

  VertexShaderPtr defaultVertexShader() {
    if (!defaultVertexShader_) {
      // Passes the position through; vs_3_0 when pixel shaders are ps_3_0, which
      // D3D9 pairs with vs_3_0 only.
      const char* source = model_ >= 30 ? "vs_3_0\ndcl_position v0\ndcl_position o0\nmov o0, v0\n"
                                        : "vs_2_0\ndcl_position v0\nmov oPos, v0\n";
      defaultVertexShader_ = device_.createVertexShader(shader::assembleTokens(source, "<draw quad vertex shader>"));
    }
    return defaultVertexShader_;
  }

  void bindInputLayout(uint32_t vertexCount) {
    if (layout_.elements.empty()) fail("draw without an [input layout]");
    VertexDeclaration decl;
    std::map<int, uint32_t> strides;
    for (const InputElement& e : layout_.elements) {
      const int comps = componentCount(e.format);
      if (comps == 0) fail("input layout format {} has no D3D9 declaration type", e.formatName);
      auto usage = declUsage(e.semantic);
      if (!usage) fail("input layout semantic '{}' has no D3D9 usage", e.semantic);
      VertexElement ve;
      ve.stream = uint16_t(e.slot);
      ve.offset = uint16_t(strides[e.slot]);
      ve.type = uint8_t(d3d::DECLTYPE_FLOAT1 + comps - 1);
      ve.usage = *usage;
      ve.usageIndex = uint8_t(e.semanticIndex);
      decl.elements.push_back(ve);
      strides[e.slot] += uint32_t(comps) * 4;
    }
    device_.setVertexDeclaration(decl);
    for (auto [slot, stride] : strides) {
      auto it = vertexBuffers_.find(slot);
      if (it == vertexBuffers_.end()) fail("the input layout reads slot {}, but there is no [vb {}]", slot, slot);
      if (it->second->data.size() < size_t(vertexCount) * stride)
        fail("[vb {}] holds {} vertices of {} bytes, the draw reads {}", slot, it->second->data.size() / stride,
             stride, vertexCount);
      device_.setStreamSource(slot, it->second, 0, stride);
    }
  }

  void setConstants() {
    const uint32_t registers = uint32_t(uniforms_.size() / 4);
    if (registers) {
      device_.setVertexShaderConstantF(0, uniforms_.data(), std::min<uint32_t>(registers, kMaxVertexShaderConstF));
      device_.setPixelShaderConstantF(0, uniforms_.data(), std::min<uint32_t>(registers, kMaxPixelShaderConstF));
    }
    device_.setVertexShaderConstantI(0, intUniforms_[0].data(), kMaxShaderConstI);
    device_.setPixelShaderConstantI(0, intUniforms_[0].data(), kMaxShaderConstI);
    device_.setVertexShaderConstantB(0, boolUniforms_.data(), uint32_t(boolUniforms_.size()));
    device_.setPixelShaderConstantB(0, boolUniforms_.data(), uint32_t(boolUniforms_.size()));
  }

  void setTexturesAndSamplers() {
    for (auto& [slot, tex] : textures_)
      if (slot < d3d::kMaxPixelSamplers) device_.setTexture(slot, tex);
    for (auto& [slot, s] : samplers_) {
      if (slot >= d3d::kMaxPixelSamplers) continue;
      if (!s.unsupported.empty() && textures_.count(slot))
        fail("sampler {}: {} need a D3D10+ device", slot, s.unsupported);
      device_.setSamplerState(slot, d3d::SAMP_ADDRESSU, uint32_t(s.address[0]));
      device_.setSamplerState(slot, d3d::SAMP_ADDRESSV, uint32_t(s.address[1]));
      device_.setSamplerState(slot, d3d::SAMP_ADDRESSW, uint32_t(s.address[2]));
      device_.setSamplerState(slot, d3d::SAMP_MINFILTER, uint32_t(s.minFilter));
      device_.setSamplerState(slot, d3d::SAMP_MAGFILTER, uint32_t(s.magFilter));
      device_.setSamplerState(slot, d3d::SAMP_MIPFILTER, uint32_t(s.mipFilter));
    }
  }

  void setRenderStates() {
    device_.setRenderState(d3d::RS_CULLMODE, d3d::CULL_NONE);
    device_.setRenderState(d3d::RS_ZENABLE, d3d::ZB_FALSE);
    device_.setRenderState(d3d::RS_LIGHTING, 0);
    device_.setRenderState(d3d::RS_ALPHATESTENABLE, 1);
    device_.setRenderState(d3d::RS_ALPHAFUNC, alphaTest_.func);
    device_.setRenderState(d3d::RS_ALPHAREF, uint32_t(std::clamp(alphaTest_.reference, 0.0f, 1.0f) * 255.0f));
    device_.setRenderState(d3d::RS_SHADEMODE, flatShading_ ? d3d::SHADE_FLAT : d3d::SHADE_GOURAUD);
    using M = FogCommand::Mode;
    device_.setRenderState(d3d::RS_FOGENABLE, fog_.mode != M::Disable);
    const uint32_t table = fog_.mode == M::Linear ? d3d::FOG_LINEAR
                           : fog_.mode == M::Exp  ? d3d::FOG_EXP
                           : fog_.mode == M::Exp2 ? d3d::FOG_EXP2
                                                  : d3d::FOG_NONE;
    device_.setRenderState(d3d::RS_FOGTABLEMODE, table);
    device_.setRenderState(d3d::RS_FOGSTART, floatBits(fog_.start));
    device_.setRenderState(d3d::RS_FOGEND, floatBits(fog_.end));
    device_.setRenderState(d3d::RS_FOGDENSITY, floatBits(fog_.density));
    device_.setRenderState(d3d::RS_FOGCOLOR,
                           colorToD3D(Color4{fogColor_[0], fogColor_[1], fogColor_[2], fogColor_[3]}));
  }

  const ShaderTestFile& file_;
  ShaderModel model_;
  Device device_;
  ShaderTestResult result_;
  std::string firstSkipReason_;
  bool stopped_ = false;

  RequireSection require_;
  std::string inactive_;    // why the current [require] section does not run
  std::string skipTests_;   // why [test] lines are skipped until the next shader
  std::map<std::pair<int, int>, std::string> failedResources_;

  PixelShaderPtr pixelShader_;
  VertexShaderPtr vertexShader_, defaultVertexShader_;
  TexturePtr target_;
  std::map<int, TexturePtr> textures_;
  std::map<int, SamplerSection> samplers_;
  std::map<int, VertexBufferPtr> vertexBuffers_;
  InputLayoutSection layout_;

  std::vector<float> uniforms_;
  std::array<std::array<int, 4>, kMaxShaderConstI> intUniforms_{};
  std::array<int, 16> boolUniforms_{};
  AlphaTestCommand alphaTest_;
  bool flatShading_ = false;
  FogCommand fog_;
  float fogColor_[4] = {0, 0, 0, 0};
};

}  // namespace

ShaderTestResult runShaderTest(const ShaderTestFile& file, const ShaderTestOptions& options) {
  std::optional<ShaderModel> model = chooseShaderModel(file);
  if (!model) {
    ShaderTestResult r;
    r.status = ShaderTestResult::Status::Skipped;
    for (const auto& e : file.sections)
      if (auto* req = std::get_if<RequireSection>(&e.section)) {
        r.skipReason = "requires " + describeRange(*req);
        break;
      }
    return r;
  }
  try {
    return Runner(file, *model, options).run();
  } catch (const Error& e) {  // the device itself could not be made (caps profile missing …)
    ShaderTestResult r;
    r.status = ShaderTestResult::Status::Failed;
    r.failures.push_back({0, e.what()});
    return r;
  }
}

std::vector<ShaderCompilation> listShaderCompilations(const ShaderTestFile& file) {
  std::vector<ShaderCompilation> out;
  const std::optional<ShaderModel> model = chooseShaderModel(file);
  if (!model) return out;
  RequireSection require;
  bool active = true;
  // The same walk as Runner::run(): [require] sections switch the following sections
  // on or off; an active section a D3D9 device cannot run ends the file.
  for (const auto& entry : file.sections) {
    if (auto* r = std::get_if<RequireSection>(&entry.section)) {
      require = *r;
      active = whyInactive(*r, *model).empty();
    }
    if (!active || std::holds_alternative<RequireSection>(entry.section)) continue;
    if (std::holds_alternative<UnsupportedSection>(entry.section)) break;
    auto* s = std::get_if<ShaderSection>(&entry.section);
    if (!s) continue;
    if (!whyStop(*s).empty()) break;
    if (s->source == ShaderSource::Hlsl) out.push_back(planCompilation(*s, entry.line, *model, require));
  }
  return out;
}

}  // namespace refx::scene
