#include "refx/pipeline/device.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cmath>
#include <cstring>
#include <optional>

#include "clip.h"
#include "depth.h"
#include "ff_pixel.h"
#include "ff_vertex.h"
#include "raster.h"
#include "state_support.h"
#include "refx/core/diagnostics.h"
#include "refx/resource/sampler.h"
#include "refx/shader/version_rules.h"
#include "render_targets.h"
#include "shader_lowering.h"
#include "validate.h"
#include "vertex_fetch.h"

namespace refx {

using namespace d3d;
using namespace pipeline;

struct Device::Impl {
  explicit Impl(int threads) : pool(threads) {}
  ThreadPool pool;
  std::vector<ShadedVertex> vertices;
  // A Clear not yet written: the next draw fills it tile by tile; anything else that
  // may look at the surfaces writes it first (resolveClear).
  RasterDraw::Fill pendingClear;
};

Device::Device(CapsProfile caps, DeviceOptions options)
    : caps_(std::move(caps)), options_(options), impl_(std::make_unique<Impl>(options.threads)) {}

Device::~Device() = default;

void Device::setThreads(int threads) {
  resolveClear();
  options_.threads = threads;
  impl_ = std::make_unique<Impl>(threads);
}

const TexturePtr& Device::renderTarget(int index) const {
  if (index < 0 || index >= kMaxRenderTargets)
    fail("render target index {} is out of range (0-{})", index, kMaxRenderTargets - 1);
  resolveClear();
  return targets_[size_t(index)];
}

const DepthStencilPtr& Device::depthStencilSurface() const {
  resolveClear();
  return depth_;
}

void Device::resolveClear() const {
  RasterDraw::Fill& f = impl_->pendingClear;
  if (!f.color && !f.depth && !f.stencil) return;
  const RasterDraw::Fill fill = f;
  f = {};
  const Rect& r = fill.rect;
  constexpr int kBand = 32;
  const int bands = (r.bottom - r.top + kBand - 1) / kBand;
  impl_->pool.parallelFor(size_t(std::max(bands, 0)), [&](size_t i, int) {
    const int top = r.top + int(i) * kBand;
    applyFill(fill, depth_.get(), r.left, top, r.right, std::min(top + kBand, r.bottom));
  });
  if (fill.color)
    for (const TexturePtr& t : targets_)
      if (t) t->markDirty();
}

void Device::setRenderTarget(int index, TexturePtr target) {
  checkRenderTarget(index, target.get(), targets_, caps_);
  resolveClear();
  targets_[size_t(index)] = std::move(target);
  if (index == 0) {
    const TexturePtr& t = targets_[0];
    state_.viewport = Viewport{0, 0, t->width(), t->height(), 0, 1};
    state_.scissor = Rect{0, 0, t->width(), t->height()};
  }
}

ValidationResult Device::validate() const {
  RenderTargetBinding binding;
  binding.count = 0;
  const Texture* first = nullptr;
  for (int i = 0; i < int(targets_.size()); ++i) {
    const Texture* t = targets_[size_t(i)].get();
    if (!t) continue;
    binding.count = i + 1;
    if (!first) first = t;
    else if (t->format() != first->format()) binding.formatsDiffer = true;
  }
  binding.count = std::max(binding.count, 1);
  return validateDeviceState(state_, caps_, binding);
}

void Device::setDepthStencilSurface(DepthStencilPtr ds) {
  resolveClear();
  depth_ = std::move(ds);
}

// The rectangle Clear and draws may touch: viewport ∩ target (∩ scissor when enabled).
static Rect activeRect(const DeviceState& s, int w, int h) {
  Rect r{std::max(0, s.viewport.x), std::max(0, s.viewport.y),
         std::min(w, s.viewport.x + s.viewport.width), std::min(h, s.viewport.y + s.viewport.height)};
  if (s.rs(RS_SCISSORTESTENABLE)) {
    r.left = std::max(r.left, s.scissor.left);
    r.top = std::max(r.top, s.scissor.top);
    r.right = std::min(r.right, s.scissor.right);
    r.bottom = std::min(r.bottom, s.scissor.bottom);
  }
  return r;
}

void Device::clear(uint32_t flags, D3DColor color, float z, uint32_t stencil) {
  resolveClear();
  const TexturePtr& target0 = targets_[0];
  const int w = target0 ? target0->width() : (depth_ ? depth_->width : 0);
  const int h = target0 ? target0->height() : (depth_ ? depth_->height : 0);
  const Rect r = activeRect(state_, w, h);
  bool target = (flags & CLEAR_TARGET) && target0;
  bool depth = depth_ && (flags & (CLEAR_ZBUFFER | CLEAR_STENCIL));
  if (r.top >= r.bottom || r.left >= r.right || (!target && !depth)) return;
  // Deferred to the next draw when nothing but the device can see the surfaces (no
  // other reference to them; the accessors resolve it) and depth matches the target.
  RasterDraw::Fill& pending = impl_->pendingClear;
  pending.rect = r;
  if (target && std::all_of(targets_.begin(), targets_.end(),
                            [](const TexturePtr& t) { return !t || t.use_count() == 1; })) {
    pending.color = true;
    pending.colorValue = uint32_t(color);
    for (size_t i = 0; i < targets_.size(); ++i)
      pending.colorTargets[i] = targets_[i] ? colorTargetOf(*targets_[i], 0xf) : ColorTarget{};
    target = false;
  }
  if (depth && target0 && depth_.use_count() == 1 && depth_->width == target0->width() &&
      depth_->height == target0->height()) {
    pending.depth = (flags & CLEAR_ZBUFFER) != 0;
    pending.stencil = (flags & CLEAR_STENCIL) != 0;
    pending.z = std::clamp(z, 0.0f, 1.0f);
    pending.stencilValue = uint8_t(stencil);
    depth = false;
  }
  if (!target && !depth) return;
  std::array<ColorTarget, kMaxRenderTargets> colorTargets{};
  if (target)
    for (size_t i = 0; i < targets_.size(); ++i)
      if (targets_[i]) colorTargets[i] = colorTargetOf(*targets_[i], 0xf);
  const float zc = std::clamp(z, 0.0f, 1.0f);
  auto rows = [&](int top, int bottom) {
    for (int y = top; y < bottom; ++y) {
      for (const ColorTarget& t : colorTargets)
        if (t.data) fillColorRow(t.data + size_t(y) * t.pitch, r.left, r.right, uint32_t(color), t.isFloat);
      const int x1 = depth ? std::min(r.right, depth_->width) : 0;
      if (!depth || y >= depth_->height || r.left >= x1) continue;
      const size_t row = size_t(y) * depth_->width;
      if (flags & CLEAR_ZBUFFER)
        std::fill(depth_->depth.begin() + row + r.left, depth_->depth.begin() + row + x1, zc);
      if (flags & CLEAR_STENCIL)
        std::fill(depth_->stencil.begin() + row + r.left, depth_->stencil.begin() + row + x1,
                  uint8_t(stencil));
    }
  };
  // Large clears in bands of rows on all threads.
  constexpr int kBand = 32;
  const int bands = (r.bottom - r.top + kBand - 1) / kBand;
  if (size_t(r.right - r.left) * size_t(r.bottom - r.top) >= (1u << 16) && bands > 1)
    impl_->pool.parallelFor(size_t(bands), [&](size_t i, int) {
      const int top = r.top + int(i) * kBand;
      rows(top, std::min(top + kBand, r.bottom));
    });
  else
    rows(r.top, r.bottom);
  if (target)
    for (const TexturePtr& t : targets_)
      if (t) t->markDirty();
}

void Device::setRenderState(RenderState s, uint32_t value) {
  if (s >= kRenderStateCount) fail("render state {} out of range", uint32_t(s));
  requireImplementedState(StateClass::Render, s, value);
  state_.renderStates[s] = value;
}

void Device::setClipPlane(int index, const float plane[4]) {
  if (index < 0 || index >= kMaxUserClipPlanes)
    fail("SetClipPlane: plane {} out of range (0-{})", index, kMaxUserClipPlanes - 1);
  state_.clipPlanes[size_t(index)] = Vec4(plane[0], plane[1], plane[2], plane[3]);
}

Vec4 Device::getClipPlane(int index) const {
  if (index < 0 || index >= kMaxUserClipPlanes)
    fail("GetClipPlane: plane {} out of range (0-{})", index, kMaxUserClipPlanes - 1);
  return state_.clipPlanes[size_t(index)];
}

void Device::setTextureStageState(int stage, TextureStageState s, uint32_t value) {
  if (stage < 0 || stage >= kMaxTextureStages || s >= kTextureStageStateCount)
    fail("texture stage state {} of stage {} out of range", uint32_t(s), stage);
  requireImplementedState(StateClass::TextureStage, s, value);
  state_.stageStates[stage][s] = value;
}

void Device::setSamplerState(int sampler, SamplerStateType s, uint32_t value) {
  if (sampler < 0 || sampler >= kMaxSamplers || s >= kSamplerStateCount)
    fail("sampler state {} of sampler {} out of range", uint32_t(s), sampler);
  requireImplementedState(StateClass::Sampler, s, value);
  state_.samplerStates[sampler][s] = value;
}

void Device::setTexture(int sampler, TexturePtr texture) {
  if (sampler < 0 || sampler >= kMaxSamplers) fail("sampler {} out of range", sampler);
  state_.textures[sampler] = std::move(texture);
}

// D3DTS_WORLDMATRIX(n) is 256 + n for n in [0, 255]; the states above 511 do not exist.
[[noreturn]] static void failTransformType(uint32_t type) {
  if (type >= worldMatrix(kMaxWorldMatrices) && type < 2 * worldMatrix(kMaxWorldMatrices))
    fail("transform type {} is D3DTS_WORLDMATRIX({}); world matrix indices are 0-255", type,
         type - TS_WORLD);
  fail("unknown transform type {}", type);
}

void Device::setTransform(uint32_t type, const Matrix& m) {
  if (type >= TS_WORLD && type < worldMatrix(kMaxWorldMatrices)) state_.worldMatrix(int(type - TS_WORLD)) = m;
  else if (type == TS_VIEW) state_.view = m;
  else if (type == TS_PROJECTION) state_.projection = m;
  else if (type >= TS_TEXTURE0 && type < TS_TEXTURE0 + 8) state_.textureTransforms[type - TS_TEXTURE0] = m;
  else failTransformType(type);
}

Matrix Device::getTransform(uint32_t type) const {
  if (type >= TS_WORLD && type < worldMatrix(kMaxWorldMatrices)) return state_.worldMatrix(int(type - TS_WORLD));
  if (type == TS_VIEW) return state_.view;
  if (type == TS_PROJECTION) return state_.projection;
  if (type >= TS_TEXTURE0 && type < TS_TEXTURE0 + 8) return state_.textureTransforms[type - TS_TEXTURE0];
  failTransformType(type);
}

void Device::setLight(int index, const Light& light) {
  if (index < 0 || index >= 8) fail("light {} out of range (0-7)", index);
  state_.lights[index] = light;
}

void Device::lightEnable(int index, bool enable) {
  if (index < 0 || index >= 8) fail("light {} out of range (0-7)", index);
  state_.lightEnabled[index] = enable;
}

void Device::setStreamSource(int stream, VertexBufferPtr vb, uint32_t offset, uint32_t stride) {
  if (stream < 0 || stream >= 16) fail("stream {} out of range", stream);
  state_.streams[stream] = StreamSource{std::move(vb), offset, stride};
}

VertexShaderPtr Device::createVertexShader(std::span<const uint32_t> tokens) const {
  return std::make_shared<const VertexShader>(tokens, shaderValidationCaps());
}

PixelShaderPtr Device::createPixelShader(std::span<const uint32_t> tokens) const {
  return std::make_shared<const PixelShader>(tokens, shaderValidationCaps());
}

shader::ValidationCaps Device::shaderValidationCaps() const {
  return refx::shaderValidationCaps(caps_);
}

exec::ShaderLoweringOptions pipeline::shaderLoweringOptions(const Device& device, shader::Version version) {
  exec::ShaderLoweringOptions o;
  o.precision = device.options().precision;
  // PixelShader1xMaxValue of the profile; a profile without pixel shaders gets the
  // version's minimum (1 for ps_1_1-1_3, 8 for ps_1_4).
  const float maxValue = device.caps().pixelShader1xMaxValue;
  const shader::VersionRules* rules = shader::findVersionRules(version);
  o.pixelShader1xMaxValue = maxValue > 0 ? maxValue : rules ? std::max(rules->minRegisterRange, 1.0f) : 1.0f;
  // Vertex colors reach the pixel stage within [0,1] (clamped per vertex below ps_3_0).
  o.colorInputsInRange = true;
  // ps_1_1-1_3 `tex t(m)` divides by the coordinates' last component when stage m has
  // D3DTTFF_PROJECTED (the fixed-function vertex stage leaves that divisor in .w).
  if (version.ps1x() && !version.atLeast(1, 4))
    for (int m = 0; m < 4; ++m)
      if (device.state().tss(m, TSS_TEXTURETRANSFORMFLAGS) & TTFF_PROJECTED)
        o.projectedTextureStages |= uint8_t(1u << m);
  return o;
}

namespace {

template <typename Store>
void setConstants(const char* api, size_t registers, uint32_t start, uint32_t count, Store store) {
  if (size_t(start) + count > registers)
    fail("{}: registers {} to {} are beyond the last register {}", api, start,
         size_t(start) + count - 1, registers - 1);
  for (uint32_t i = 0; i < count; ++i) store(start + i, i);
}

}  // namespace

void Device::setVertexShaderConstantF(uint32_t start, const float* data, uint32_t count) {
  setConstants("SetVertexShaderConstantF", state_.vsConstF.size(), start, count,
                      [&](uint32_t r, uint32_t i) {
                        state_.vsConstF[r] = Vec4(data[4 * i], data[4 * i + 1], data[4 * i + 2], data[4 * i + 3]);
                      });
}

void Device::setPixelShaderConstantF(uint32_t start, const float* data, uint32_t count) {
  setConstants("SetPixelShaderConstantF", state_.psConstF.size(), start, count,
                      [&](uint32_t r, uint32_t i) {
                        state_.psConstF[r] = Vec4(data[4 * i], data[4 * i + 1], data[4 * i + 2], data[4 * i + 3]);
                      });
}

void Device::setVertexShaderConstantI(uint32_t start, const int* data, uint32_t count) {
  setConstants("SetVertexShaderConstantI", state_.vsConstI.size(), start, count,
                    [&](uint32_t r, uint32_t i) {
                      state_.vsConstI[r] = {data[4 * i], data[4 * i + 1], data[4 * i + 2], data[4 * i + 3]};
                    });
}

void Device::setPixelShaderConstantI(uint32_t start, const int* data, uint32_t count) {
  setConstants("SetPixelShaderConstantI", state_.psConstI.size(), start, count,
                    [&](uint32_t r, uint32_t i) {
                      state_.psConstI[r] = {data[4 * i], data[4 * i + 1], data[4 * i + 2], data[4 * i + 3]};
                    });
}

void Device::setVertexShaderConstantB(uint32_t start, const int* data, uint32_t count) {
  setConstants("SetVertexShaderConstantB", state_.vsConstB.size(), start, count,
                    [&](uint32_t r, uint32_t i) { state_.vsConstB[r] = data[i] != 0; });
}

void Device::setPixelShaderConstantB(uint32_t start, const int* data, uint32_t count) {
  setConstants("SetPixelShaderConstantB", state_.psConstB.size(), start, count,
                    [&](uint32_t r, uint32_t i) { state_.psConstB[r] = data[i] != 0; });
}

uint32_t verticesForPrimitives(PrimitiveType type, uint32_t n) {
  switch (type) {
    case PT_POINTLIST: return n;
    case PT_LINELIST: return 2 * n;
    case PT_LINESTRIP: return n ? n + 1 : 0;
    case PT_TRIANGLELIST: return 3 * n;
    case PT_TRIANGLESTRIP: case PT_TRIANGLEFAN: return n ? n + 2 : 0;
  }
  return 0;
}

void Device::drawPrimitive(PrimitiveType type, uint32_t startVertex, uint32_t primitiveCount) {
  draw(type, primitiveCount, 0, nullptr, false, verticesForPrimitives(type, primitiveCount), startVertex);
}

void Device::drawIndexedPrimitive(PrimitiveType type, int32_t baseVertex, uint32_t minIndex,
                                  uint32_t numVertices, uint32_t startIndex, uint32_t primitiveCount) {
  if (!state_.indices) fail("DrawIndexedPrimitive without an index buffer");
  const IndexBuffer& ib = *state_.indices;
  const size_t isize = ib.index32 ? 4 : 2;
  const size_t needed = (size_t(startIndex) + verticesForPrimitives(type, primitiveCount)) * isize;
  if (needed > ib.data.size()) fail("DrawIndexedPrimitive reads past the end of the index buffer");
  draw(type, primitiveCount, baseVertex, ib.data.data() + startIndex * isize, ib.index32, numVertices,
       minIndex);
}

void Device::drawPrimitiveUP(PrimitiveType type, uint32_t primitiveCount, const void* vertices,
                             uint32_t stride) {
  const uint32_t count = verticesForPrimitives(type, primitiveCount);
  auto vb = std::make_shared<VertexBuffer>();
  vb->data.assign(static_cast<const uint8_t*>(vertices),
                  static_cast<const uint8_t*>(vertices) + size_t(count) * stride);
  StreamSource saved = state_.streams[0];
  state_.streams[0] = StreamSource{vb, 0, stride};
  draw(type, primitiveCount, 0, nullptr, false, count, 0);
  state_.streams[0] = saved;  // D3D unsets stream 0 after a UP draw; restoring is harmless
}

void Device::drawIndexedPrimitiveUP(PrimitiveType type, uint32_t minIndex, uint32_t numVertices,
                                    uint32_t primitiveCount, const void* indices, bool index32,
                                    const void* vertices, uint32_t stride) {
  auto vb = std::make_shared<VertexBuffer>();
  vb->data.assign(static_cast<const uint8_t*>(vertices),
                  static_cast<const uint8_t*>(vertices) + size_t(minIndex + numVertices) * stride);
  StreamSource saved = state_.streams[0];
  state_.streams[0] = StreamSource{vb, 0, stride};
  draw(type, primitiveCount, 0, indices, index32, numVertices, minIndex);
  state_.streams[0] = saved;
}

namespace {

// Sampler binding for the executor: a texture and its decoded sampler states.
struct BoundSampler {
  const Texture* texture = nullptr;
  SamplerState state;
  std::optional<PreparedSampler> prepared;  // texture and state checked once per draw
};

void sampleBound(const void* ctx, exec::SampleMode mode, const float (*co)[kBatchLanes],
                 uint16_t laneMask, float (*out)[kBatchLanes]) {
  const auto* b = static_cast<const BoundSampler*>(ctx);
  if (!b->texture) {
    for (int c = 0; c < 4; ++c)
      for (int l = 0; l < kBatchLanes; ++l) out[c][l] = c == 3 ? 1.0f : 0.0f;
    return;
  }
  if (mode == exec::SampleMode::Implicit && b->prepared) {
    b->prepared->sampleImplicit(co[0], co[1], co[2], laneMask, out);
    return;
  }
  SampleRequest req;
  req.u = co[0];
  req.v = co[1];
  req.w = co[2];
  req.laneMask = laneMask;
  if (mode == exec::SampleMode::Bias) {
    req.lodMode = LodMode::Bias;
    req.lod = co[3];
  } else if (mode == exec::SampleMode::Lod) {
    req.lodMode = LodMode::Explicit;
    req.lod = co[3];
  } else if (mode == exec::SampleMode::Grad) {
    // texldd: rows 4..6 are d(u,v,w)/dx and rows 8..10 d(u,v,w)/dy per lane.
    req.lodMode = LodMode::Gradients;
    for (int i = 0; i < 3; ++i) {
      req.ddx[i] = co[4 + i];
      req.ddy[i] = co[8 + i];
    }
  }
  if (b->prepared) b->prepared->sample(req, out);
  else sampleTexture(*b->texture, b->state, req, out);
}

// Whether the program writes output register `index` (any component).
bool writesOutput(const exec::Program& p, int index) {
  for (const exec::Instr& in : p.code)
    if (in.dst.file == exec::RegFile::Output && in.dst.index == index && in.dst.mask) return true;
  return false;
}

// The constant file a lowered shader reads: the API's float constants, and for pixel
// shaders the texture stages' bump environment at exec::kConstBumpEnv.
std::vector<Vec4> shaderConstants(const DeviceState& st, bool pixel, const exec::LoweredShader& s) {
  const std::vector<Vec4>& api = pixel ? st.psConstF : st.vsConstF;
  std::vector<Vec4> c(std::max<size_t>(api.size(), size_t(std::max(s.floatConstantsRead, 0))));
  std::copy(api.begin(), api.end(), c.begin());
  if (!pixel) return c;
  c.resize(std::max(c.size(), size_t(exec::kConstBumpEnv + exec::kConstBumpEnvCount)));
  for (int n = 0; n < exec::kConstBumpEnvCount / 2 && n < kMaxTextureStages; ++n) {
    c[exec::kConstBumpEnv + 2 * n] = Vec4(st.tssFloat(n, TSS_BUMPENVMAT00), st.tssFloat(n, TSS_BUMPENVMAT01),
                                          st.tssFloat(n, TSS_BUMPENVMAT10), st.tssFloat(n, TSS_BUMPENVMAT11));
    c[exec::kConstBumpEnv + 2 * n + 1] =
        Vec4(st.tssFloat(n, TSS_BUMPENVLSCALE), st.tssFloat(n, TSS_BUMPENVLOFFSET), 0, 0);
  }
  return c;
}

// Whether the program samples sampler s (only those are prepared).
bool programSamples(const exec::Program& p, int s) {
  for (const exec::Instr& in : p.code)
    if (((in.op >= exec::Op::Tex && in.op <= exec::Op::TexLod) || in.op == exec::Op::TexGrad) &&
        in.sampler == s)
      return true;
  return false;
}

SamplerState decodeSamplerState(const DeviceState& s, int i) {
  SamplerState r;
  r.addressU = TextureAddress(s.samp(i, SAMP_ADDRESSU));
  r.addressV = TextureAddress(s.samp(i, SAMP_ADDRESSV));
  r.addressW = TextureAddress(s.samp(i, SAMP_ADDRESSW));
  r.borderColor = colorFromD3D(s.samp(i, SAMP_BORDERCOLOR));
  r.magFilter = TextureFilter(s.samp(i, SAMP_MAGFILTER));
  r.minFilter = TextureFilter(s.samp(i, SAMP_MINFILTER));
  r.mipFilter = TextureFilter(s.samp(i, SAMP_MIPFILTER));
  r.mipLodBias = bitsFloat(s.samp(i, SAMP_MIPMAPLODBIAS));
  r.maxMipLevel = s.samp(i, SAMP_MAXMIPLEVEL);
  r.maxAnisotropy = s.samp(i, SAMP_MAXANISOTROPY);
  r.srgb = s.samp(i, SAMP_SRGBTEXTURE) != 0;
  return r;
}

// Per pixel input register: which vertex output feeds it.
int varyingForPixelInput(int input) {
  if (input == kPixelInDiffuse) return kVertexOutDiffuse;
  if (input == kPixelInSpecular) return kVertexOutSpecular;
  if (input >= kPixelInTex0 && input < kPixelInTex0 + 8) return kVertexOutTex0 + (input - kPixelInTex0);
  if (input == kPixelInFog) return kVertexOutFog;
  return -1;
}

// Components of each input register the program reads. Texture coordinates only
// count the components the bound texture's type needs (2D: u,v; cube/volume: +w),
// plus .w for projected, biased and explicit-LOD lookups.
std::array<uint8_t, 32> inputComponentsRead(const exec::Program& p, const DeviceState& st) {
  std::array<uint8_t, 32> used{};
  for (const exec::Instr& in : p.code)
    for (int i = 0; i < exec::sourceCount(in.op); ++i) {
      const exec::Src& s = in.src[i];
      if (s.file != exec::RegFile::Input || s.index >= 32) continue;
      uint8_t lanes = 0xF;
      if (in.op >= exec::Op::Tex && in.op <= exec::Op::TexLod) {
        const Texture* t = in.sampler < st.textures.size() ? st.textures[in.sampler].get() : nullptr;
        lanes = (t && t->type() == TextureType::Texture2D) ? 0x3 : 0x7;
        if (in.op != exec::Op::Tex) lanes |= 0x8;
      }
      for (int c = 0; c < 4; ++c)
        if (lanes & (1 << c)) used[s.index] |= uint8_t(1u << ((s.swizzle >> (2 * c)) & 3));
    }
  return used;
}

}  // namespace

// Primitive setup from screen-space vertices into the raster draw.
namespace {

struct SetupVertex {
  float x, y, z, invW;
  const Vec4* varyings;
  float wDepthOffset = 0;  // w-buffering: the depth bias of the triangle a line or point outlines
};

void addPlane(std::vector<float>& planes, double a0, double a1, double a2, double x1, double y1,
              double x2, double y2, double det) {
  // Plane through (0,0,a0), (x1,y1,a1), (x2,y2,a2) relative to vertex 0.
  const double dx = ((a1 - a0) * y2 - (a2 - a0) * y1) / det;
  const double dy = ((a2 - a0) * x1 - (a1 - a0) * x2) / det;
  planes.push_back(float(a0));
  planes.push_back(float(dx));
  planes.push_back(float(dy));
}

// D3DRS_WRAPn: a wrapped coordinate takes the shorter way around the unit cylinder,
// e.g. 0.9 -> 0.1 interpolates through 1.0 (0.9 -> 1.1), not back through 0.5.
void wrapTowards(double base, double& v) {
  const double shift = std::round(v - base);
  v -= shift;
}

// std::llround (halves away from zero) inline: the libm call was a good part of
// triangle setup. x - trunc(x) is exact for every double.
inline int64_t roundHalfAway(double x) {
  if (!(std::fabs(x) < 0x1p52)) return std::llround(x);  // huge or NaN: libm decides
  const double t = std::trunc(x);
  const int64_t i = int64_t(t);
  return std::fabs(x - t) >= 0.5 ? (x < 0 ? i - 1 : i + 1) : i;
}

// The value the depth buffer holds for a vertex: z, or w / w_far when w-buffering.
double bufferDepth(const RasterDraw& d, const SetupVertex& v) {
  return d.wBuffer ? double(d.invFarW) / double(v.invW) : double(v.z);
}

// `biased`: D3DRS_DEPTHBIAS/SLOPESCALEDEPTHBIAS apply (not to the pieces of a point).
void setupTriangle(RasterDraw& d, const SetupVertex (&sv)[3], uint32_t cull, const Rect& bounds,
                   bool flat, bool biased = true) {
  constexpr double one = double(1 << kSubPixelBits);
  // Positions that are not numbers or lie far beyond any guard band (pretransformed
  // vertices are not clipped) would overflow the fixed-point edge functions: such a
  // triangle is not drawn.
  constexpr float kMaxScreenCoordinate = float(1 << 18);
  for (const SetupVertex& v : sv)
    if (!(std::fabs(v.x) <= kMaxScreenCoordinate && std::fabs(v.y) <= kMaxScreenCoordinate)) return;
  int64_t X[3], Y[3];
  for (int i = 0; i < 3; ++i) {
    X[i] = roundHalfAway(double(sv[i].x) * one);
    Y[i] = roundHalfAway(double(sv[i].y) * one);
  }
  const int64_t area = (X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]);
  if (area == 0) return;
  const bool ccw = area < 0;  // y points down: positive area is clockwise on screen
  if ((cull == CULL_CCW && ccw) || (cull == CULL_CW && !ccw)) return;
  int order[3] = {0, 1, 2};
  if (ccw) std::swap(order[1], order[2]);
  Primitive p{};
  p.kind = PrimKind::Triangle;
  p.counterClockwise = ccw;
  for (int k = 0; k < 3; ++k) {
    const int a = order[k], b = order[(k + 1) % 3];
    const int64_t dx = X[b] - X[a], dy = Y[b] - Y[a];
    // E(P) = (P.y - a.y)*dx - (P.x - a.x)*dy, positive inside a clockwise triangle.
    p.edgeA[k] = -dy;
    p.edgeB[k] = dx;
    p.edgeC[k] = -Y[a] * dx + X[a] * dy;
    const bool topLeft = (dy == 0 && dx > 0) || dy < 0;
    p.edgeBias[k] = topLeft ? 1 : 0;
  }
  const double minx = std::min({X[0], X[1], X[2]}) / one, maxx = std::max({X[0], X[1], X[2]}) / one;
  const double miny = std::min({Y[0], Y[1], Y[2]}) / one, maxy = std::max({Y[0], Y[1], Y[2]}) / one;
  p.minX = std::max(bounds.left, int(std::ceil(minx)));
  p.maxX = std::min(bounds.right - 1, int(std::floor(maxx)));
  p.minY = std::max(bounds.top, int(std::ceil(miny)));
  p.maxY = std::min(bounds.bottom - 1, int(std::floor(maxy)));
  if (p.minX > p.maxX || p.minY > p.maxY) return;
  // Interpolation planes relative to vertex 0 (snapped positions).
  const double x0 = X[0] / one, y0 = Y[0] / one;
  const double x1 = X[1] / one - x0, y1 = Y[1] / one - y0, x2 = X[2] / one - x0, y2 = Y[2] / one - y0;
  const double det = x1 * y2 - x2 * y1;
  p.originX = float(x0);
  p.originY = float(y0);
  p.planeOffset = uint32_t(d.planes.size());
  addPlane(d.planes, sv[0].invW, sv[1].invW, sv[2].invW, x1, y1, x2, y2, det);
  addPlane(d.planes, sv[0].z, sv[1].z, sv[2].z, x1, y1, x2, y2, det);
  if (biased && (d.depthBias != 0 || d.slopeScaleDepthBias != 0)) {
    float* z = &d.planes[d.planes.size() - 3];  // base, dz/dx, dz/dy
    float slopeX = z[1], slopeY = z[2];
    if (d.wBuffer) {
      // The slopes of the stored w / w_far across the vertices.
      const double w0 = bufferDepth(d, sv[0]), w1 = bufferDepth(d, sv[1]) - w0, w2 = bufferDepth(d, sv[2]) - w0;
      slopeX = float((w1 * y2 - w2 * y1) / det);
      slopeY = float((w2 * x1 - w1 * x2) / det);
    }
    const float offset = depthOffset(d.depthBias, d.slopeScaleDepthBias, slopeX, slopeY);
    if (d.wBuffer) p.wDepthOffset = offset;
    else z[0] += offset;
  }
  for (const InterpolatedInput& in : d.inputs) {
    if (in.flat) {
      d.planes.push_back(sv[0].varyings[in.varying][in.component]);
      d.planes.push_back(0);
      d.planes.push_back(0);
      continue;
    }
    double a[3];
    for (int i = 0; i < 3; ++i) a[i] = sv[i].varyings[in.varying][in.component];
    if (in.wrap) {
      wrapTowards(a[0], a[1]);
      wrapTowards(a[0], a[2]);
    }
    for (int i = 0; i < 3; ++i) a[i] *= sv[i].invW;
    addPlane(d.planes, a[0], a[1], a[2], x1, y1, x2, y2, det);
  }
  d.prims.push_back(p);
}

void setupLine(RasterDraw& d, const SetupVertex& a, const SetupVertex& b, const Rect& bounds, bool flat) {
  const float dx = b.x - a.x, dy = b.y - a.y;
  if (dx == 0 && dy == 0) return;
  Primitive p{};
  p.kind = PrimKind::Line;
  p.xMajor = std::fabs(dx) >= std::fabs(dy);
  const float amaj = p.xMajor ? a.x : a.y, bmaj = p.xMajor ? b.x : b.y;
  const float amin = p.xMajor ? a.y : a.x, bmin = p.xMajor ? b.y : b.x;
  p.lineM = (bmin - amin) / (bmaj - amaj);
  p.lineQ = amin - p.lineM * amaj;
  const int lo = int(std::floor(std::min(amaj, bmaj) + 0.5f)), hi = int(std::floor(std::max(amaj, bmaj) + 0.5f));
  const int mlo = int(std::floor(std::min(amin, bmin) - 1)), mhi = int(std::ceil(std::max(amin, bmin) + 1));
  p.minX = std::max(bounds.left, p.xMajor ? lo : mlo);
  p.maxX = std::min(bounds.right - 1, p.xMajor ? hi : mhi);
  p.minY = std::max(bounds.top, p.xMajor ? mlo : lo);
  p.maxY = std::min(bounds.bottom - 1, p.xMajor ? mhi : hi);
  if (p.minX > p.maxX || p.minY > p.maxY) return;
  p.originX = a.x;
  p.originY = a.y;
  p.planeOffset = uint32_t(d.planes.size());
  p.wDepthOffset = a.wDepthOffset;
  const float len = bmaj - amaj;
  auto plane = [&](double va, double vb) {
    d.planes.push_back(float(va));
    const float g = float((vb - va) / len);
    d.planes.push_back(p.xMajor ? g : 0.0f);
    d.planes.push_back(p.xMajor ? 0.0f : g);
  };
  plane(a.invW, b.invW);
  plane(a.z, b.z);
  for (const InterpolatedInput& in : d.inputs) {
    if (in.flat) {
      plane(a.varyings[in.varying][in.component], a.varyings[in.varying][in.component]);
      continue;
    }
    double va = a.varyings[in.varying][in.component], vb = b.varyings[in.varying][in.component];
    if (in.wrap) wrapTowards(va, vb);
    plane(va * a.invW, vb * b.invW);
  }
  d.prims.push_back(p);
}

// A point is a screen-aligned square of side `size` centred on the vertex; it covers
// the pixels whose centres lie in [x - size/2, x + size/2) x [y - size/2, y + size/2)
// (the top-left rule of two triangles covering the square). With `sprite`
// (D3DRS_POINTSPRITEENABLE) texture coordinates u, v of every set run across the
// square, (0,0) at its top-left corner to (1,1) at its bottom-right; otherwise all
// inputs keep the vertex's values.
void setupPoint(RasterDraw& d, const SetupVertex& a, float size, const Rect& bounds, bool sprite) {
  if (!std::isfinite(a.x) || !std::isfinite(a.y)) return;
  Primitive p{};
  p.kind = PrimKind::Point;
  size = size >= 1.0f ? size : 1.0f;  // NaN too
  const float h = size * 0.5f;
  // Clamped as floats: far-away (guard band) or huge points stay in int range.
  auto clampTo = [](float v, int lo, int hi) { return v <= float(lo) ? lo : v >= float(hi) ? hi : int(v); };
  p.minX = clampTo(std::ceil(a.x - h), bounds.left, bounds.right);
  p.maxX = clampTo(std::ceil(a.x + h) - 1, bounds.left - 1, bounds.right - 1);
  p.minY = clampTo(std::ceil(a.y - h), bounds.top, bounds.bottom);
  p.maxY = clampTo(std::ceil(a.y + h) - 1, bounds.top - 1, bounds.bottom - 1);
  if (p.minX > p.maxX || p.minY > p.maxY) return;
  p.originX = a.x;
  p.originY = a.y;
  p.planeOffset = uint32_t(d.planes.size());
  p.wDepthOffset = a.wDepthOffset;
  auto plane = [&](float v, float dx, float dy) {
    d.planes.push_back(v);
    d.planes.push_back(dx);
    d.planes.push_back(dy);
  };
  plane(a.invW, 0, 0);
  plane(a.z, 0, 0);
  for (const InterpolatedInput& in : d.inputs) {
    const float scale = in.flat ? 1.0f : a.invW;  // non-flat planes hold value/w
    const bool texCoord = in.varying >= kVertexOutTex0 && in.varying < kVertexOutTex0 + 8;
    if (sprite && texCoord && in.component < 2) {
      // At the centre 0.5, one unit across the side.
      const float step = scale / size;
      plane(0.5f * scale, in.component == 0 ? step : 0.0f, in.component == 1 ? step : 0.0f);
      continue;
    }
    plane(a.varyings[in.varying][in.component] * scale, 0, 0);
  }
  d.prims.push_back(p);
}

}  // namespace

void Device::draw(PrimitiveType type, uint32_t primitiveCount, int32_t baseVertex,
                  const void* indices, bool index32, uint32_t vertexCount, uint32_t firstVertex) {
  if (!targets_[0]) fail("draw without a render target");
  if (type < PT_POINTLIST || type > PT_TRIANGLEFAN) fail("unknown primitive type {}", uint32_t(type));
  const uint32_t indexCount = verticesForPrimitives(type, primitiveCount);
  if (primitiveCount == 0 || indexCount == 0) return;
  const DeviceState& st = state_;
  const VertexDeclaration& decl = st.declaration;
  if (decl.elements.empty()) fail("draw without a vertex declaration or FVF");

  // Vertex indices of the primitive stream (relative to baseVertex).
  std::vector<uint32_t> idx(indexCount);
  uint32_t lo = UINT32_MAX, hi = 0;
  for (uint32_t i = 0; i < indexCount; ++i) {
    uint32_t v;
    if (!indices) v = firstVertex + i;
    else if (index32) std::memcpy(&v, static_cast<const uint8_t*>(indices) + 4 * i, 4);
    else {
      uint16_t s;
      std::memcpy(&s, static_cast<const uint8_t*>(indices) + 2 * i, 2);
      v = s;
    }
    v = uint32_t(int64_t(v) + baseVertex);
    idx[i] = v;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  const uint32_t count = hi - lo + 1;
  if (count > (1u << 24)) fail("draw references {} vertices; at most 16777216 are supported", count);

  // Vertex stage: the vertex shader, or fixed-function T&L as a program.
  StreamView streams[16];
  for (int s = 0; s < 16; ++s) {
    const StreamSource& src = st.streams[s];
    if (!src.buffer) continue;
    streams[s].data = src.buffer->data.data() + std::min<size_t>(src.offset, src.buffer->data.size());
    streams[s].size = src.buffer->data.size() - std::min<size_t>(src.offset, src.buffer->data.size());
    streams[s].stride = src.stride;
  }
  const VertexShader* vs = st.vertexShader.get();
  const PixelShader* ps = st.pixelShader.get();
  FixedFunctionVertexConfig vcfg;
  vcfg.pretransformed = !vs && decl.find(DECLUSAGE_POSITIONT, 0) != nullptr;
  vcfg.hasNormal = decl.find(DECLUSAGE_NORMAL, 0) != nullptr;
  vcfg.hasDiffuse = decl.find(DECLUSAGE_COLOR, 0) != nullptr;
  vcfg.hasSpecular = decl.find(DECLUSAGE_COLOR, 1) != nullptr;
  vcfg.hasPSize = decl.find(DECLUSAGE_PSIZE, 0) != nullptr;
  for (int t = 0; t < 8; ++t)
    if (const VertexElement* e = decl.find(DECLUSAGE_TEXCOORD, uint8_t(t)))
      vcfg.texCoordDims[t] = e->type <= DECLTYPE_FLOAT4 ? e->type - DECLTYPE_FLOAT1 + 1 : 4;
  if (const VertexElement* e = decl.find(DECLUSAGE_BLENDWEIGHT, 0))
    vcfg.blendWeightCount = e->type <= DECLTYPE_FLOAT4 ? e->type - DECLTYPE_FLOAT1 + 1 : 4;
  if (const VertexElement* e = decl.find(DECLUSAGE_BLENDINDICES, 0)) vcfg.blendIndicesType = e->type;
  vcfg.hasPosition1 = decl.find(DECLUSAGE_POSITION, 1) != nullptr;
  vcfg.hasNormal1 = decl.find(DECLUSAGE_NORMAL, 1) != nullptr;
  std::shared_ptr<const exec::LoweredShader> vlow;
  exec::Program ffVertex;
  std::vector<FetchElement> fetch;
  if (vs) {
    vlow = loweredShader(*vs, {});  // the options only concern pixel shaders
    fetch = shaderFetch(decl, *vlow);
    vcfg.hasPSize = writesOutput(vlow->program, kVertexOutPSize);
  } else {
    ffVertex = buildFixedFunctionVertexProgram(st, vcfg);
    fetch = fixedFunctionFetch(decl);
  }
  const exec::Program& vprog = vs ? vlow->program : ffVertex;
  // Vertex shader colors reach the pixel stage through [0,1] interpolators, except
  // between vs_3_0 and ps_3_0 (full float).
  const bool clampColors = vs && !(ps && ps->version().atLeast(3, 0) && vs->version().atLeast(3, 0));

  // ps_1_1-1_3 `tex` with COUNTn|PROJECTED divides by the n-th coordinate. The pixel
  // program divides by .w (where fixed-function T&L leaves the divisor); a vertex
  // shader's oTm keeps its own layout, so the n-th component is copied into .w.
  std::array<int8_t, 4> projectedDivisor{-1, -1, -1, -1};
  if (vs && ps && ps->version().ps1x() && !ps->version().atLeast(1, 4))
    for (int m = 0; m < 4; ++m) {
      const uint32_t flags = st.tss(m, TSS_TEXTURETRANSFORMFLAGS);
      const uint32_t n = flags & 0xff;
      if ((flags & TTFF_PROJECTED) && (n == TTFF_COUNT2 || n == TTFF_COUNT3))
        projectedDivisor[size_t(m)] = int8_t(n - 1);
    }

  auto& verts = impl_->vertices;
  verts.resize(count);
  const uint32_t batches = (count + kBatchLanes - 1) / kBatchLanes;
  std::vector<exec::BatchRegisters> vregs(impl_->pool.threadCount());
  for (auto& r : vregs) {
    r.resize(vprog);
    if (r.inputs.size() < size_t(kVertexInputCount)) r.inputs.resize(kVertexInputCount);
    if (r.outputs.size() < size_t(kVertexOutputCount)) r.outputs.resize(kVertexOutputCount);
  }
  // Vertex texture samplers (vs_3_0 texldl s0-s3 = D3DVERTEXTEXTURESAMPLER0-3).
  constexpr int kVertexSamplers = kMaxSamplers - kVertexSampler0;
  std::array<BoundSampler, kVertexSamplers> vbound;
  std::array<exec::SamplerBinding, kVertexSamplers> vbindings;
  for (int s = 0; s < kVertexSamplers; ++s) {
    vbound[s].texture = st.textures[kVertexSampler0 + s].get();
    vbound[s].state = decodeSamplerState(st, kVertexSampler0 + s);
    vbindings[s].context = &vbound[s];
    vbindings[s].sample = sampleBound;
  }
  const std::vector<Vec4> vconst = vs ? shaderConstants(st, false, *vlow) : std::vector<Vec4>{};
  exec::ExecContext vctx;
  vctx.constants = vs ? vconst.data() : st.vsConstF.data();
  vctx.constantCount = vs ? int(vconst.size()) : int(st.vsConstF.size());
  if (vs) {
    vctx.samplers = vbindings.data();
    vctx.samplerCount = kVertexSamplers;
    vctx.intConstants = st.vsConstI.data();
    vctx.intConstantCount = int(st.vsConstI.size());
    vctx.boolConstants = st.vsConstB.data();
    vctx.boolConstantCount = int(st.vsConstB.size());
  }
  std::atomic<uint32_t> vertexBoundStops{0};
  vctx.boundStops = &vertexBoundStops;
  for (auto& r : vregs) exec::prepare(vprog, vctx, r);
  impl_->pool.parallelFor(batches, [&](size_t b, int thread) {
    exec::BatchRegisters& r = vregs[thread];
    const uint32_t first = lo + uint32_t(b) * kBatchLanes;
    const int n = int(std::min<uint32_t>(kBatchLanes, lo + count - first));
    resetInputs(r, !vs);
    fetchVertices(fetch, streams, first, n, r);
    for (auto& o : r.outputs) std::memset(&o, 0, sizeof(o));
    r.laneMask = 0xffff;
    exec::execute(vprog, vctx, r);
    for (int l = 0; l < n; ++l) {
      ShadedVertex& sv = verts[first - lo + l];
      for (int o = 0; o < kVaryingCount; ++o)
        for (int c = 0; c < 4; ++c) sv.out[o][c] = r.outputs[o].c[c][l];
      if (clampColors)
        for (int o : {int(kVertexOutDiffuse), int(kVertexOutSpecular)})
          for (int c = 0; c < 4; ++c) sv.out[o][c] = std::clamp(sv.out[o][c], 0.0f, 1.0f);
      for (int m = 0; m < 4; ++m)
        if (projectedDivisor[size_t(m)] >= 0)
          sv.out[kVertexOutTex0 + m][3] = sv.out[kVertexOutTex0 + m][projectedDivisor[size_t(m)]];
    }
  });

  // Pixel stage program: the pixel shader (fog after it below ps_3_0; the shader adds
  // specular itself) or the texture stage cascade with specular add and fog.
  std::shared_ptr<const exec::LoweredShader> plow;
  exec::Program pprog;
  if (ps) {
    plow = loweredShader(*ps, shaderLoweringOptions(*this, ps->version()));
    pprog = plow->program;
    if (!ps->version().atLeast(3, 0)) appendSpecularAndFog(pprog, st, false);
  } else {
    FixedFunctionPixelConfig pcfg;
    for (int s = 0; s < 8; ++s) pcfg.textures[s] = st.textures[s].get();
    pprog = buildFixedFunctionPixelProgram(st, pcfg);
    appendSpecularAndFog(pprog, st, true);
  }

  std::array<BoundSampler, kMaxPixelSamplers> bound;
  std::array<exec::SamplerBinding, kMaxPixelSamplers> bindings;
  for (int s = 0; s < kMaxPixelSamplers; ++s) {
    bound[s].texture = st.textures[s].get();
    bound[s].state = decodeSamplerState(st, s);
    if (bound[s].texture && programSamples(pprog, s)) bound[s].prepared.emplace(*bound[s].texture, bound[s].state);
    bindings[s].context = &bound[s];
    bindings[s].sample = sampleBound;
  }

  RasterDraw d;
  d.state = &st;
  d.pixelProgram = &pprog;
  const std::vector<Vec4> pconst = ps ? shaderConstants(st, true, *plow) : std::vector<Vec4>{};
  d.execContext.constants = ps ? pconst.data() : st.psConstF.data();
  d.execContext.constantCount = ps ? int(pconst.size()) : int(st.psConstF.size());
  d.execContext.samplers = bindings.data();
  d.execContext.samplerCount = kMaxPixelSamplers;
  if (ps) {
    d.execContext.intConstants = st.psConstI.data();
    d.execContext.intConstantCount = int(st.psConstI.size());
    d.execContext.boolConstants = st.psConstB.data();
    d.execContext.boolConstantCount = int(st.psConstB.size());
  }
  const bool flat = st.rs(RS_SHADEMODE) == SHADE_FLAT;
  const auto used = inputComponentsRead(pprog, st);
  for (int i = 0; i < 32; ++i) {
    if (!used[i]) continue;
    if (i == kPixelInPosition) {
      d.usesPosition = true;
      continue;
    }
    if (i == exec::kPixelInFace) {
      d.usesFace = true;
      pprog.inputCount = std::max(pprog.inputCount, exec::kPixelInFace + 1);
      continue;
    }
    const int vary = varyingForPixelInput(i);
    if (vary < 0) continue;
    // D3DRS_WRAPn applies to texture coordinate n as the pixel stage receives it
    // (vertex output oTn): bit c = component c (D3DWRAP_U, V, W, COORD_3).
    const int texIndex = i - kPixelInTex0;
    const uint32_t wrapBits =
        texIndex >= 0 && texIndex < 8 ? st.rs(RenderState(RS_WRAP0 + texIndex)) : 0u;
    for (int c = 0; c < 4; ++c)
      if (used[i] & (1 << c))
        d.inputs.push_back(InterpolatedInput{uint8_t(i), uint8_t(c), uint8_t(vary),
                                             flat && (i == kPixelInDiffuse || i == kPixelInSpecular),
                                             (wrapBits & (1u << c)) != 0});
  }
  // Target n takes oCn of a ps_2_0 or later shader that writes it; fixed function and
  // ps_1_x write target 0 only. A target without its oCn is left as it was (D3D9 leaves
  // its contents undefined).
  for (int i = 0; i < kMaxRenderTargets; ++i)
    if (targets_[size_t(i)] && (i == 0 || (ps && ps->version().atLeast(2, 0) && writesOutput(pprog, i))))
      d.targets[size_t(i)] = colorTargetOf(*targets_[size_t(i)], colorWriteMask(st, i));
  d.srgbWrite = st.rs(RS_SRGBWRITEENABLE) != 0;
  d.dither = st.rs(RS_DITHERENABLE) != 0;
  d.width = targets_[0]->width();
  d.height = targets_[0]->height();
  d.depth = depth_.get();
  d.depthTest = depth_ && st.rs(RS_ZENABLE) != ZB_FALSE;
  d.depthWrite = d.depthTest && st.rs(RS_ZWRITEENABLE) != 0;
  d.depthFunc = st.rs(RS_ZFUNC);
  d.wBuffer = st.rs(RS_ZENABLE) == ZB_USEW;
  d.invFarW = 1.0f / projectionFarW(st.projection);
  d.depthBias = st.rsFloat(RS_DEPTHBIAS);
  d.slopeScaleDepthBias = st.rsFloat(RS_SLOPESCALEDEPTHBIAS);
  d.stencil = depth_ && st.rs(RS_STENCILENABLE) != 0;
  d.alphaTest = st.rs(RS_ALPHATESTENABLE) != 0;
  d.alphaFunc = st.rs(RS_ALPHAFUNC);
  // oDepth / texdepth / texm3x2depth replace the interpolated depth: no early test.
  d.shaderDepth = plow && plow->writesDepth;
  bool kills = plow && plow->kills;
  for (const auto& in : pprog.code) kills |= in.op == exec::Op::Kill;
  d.earlyDepth = d.depthTest && !d.stencil && !d.alphaTest && !kills && !d.shaderDepth;
  d.blend.enable = st.rs(RS_ALPHABLENDENABLE) != 0;
  d.blend.src = st.rs(RS_SRCBLEND);
  d.blend.dst = st.rs(RS_DESTBLEND);
  d.blend.op = st.rs(RS_BLENDOP);
  const bool separate = st.rs(RS_SEPARATEALPHABLENDENABLE) != 0;
  d.blend.srcA = separate ? st.rs(RS_SRCBLENDALPHA) : d.blend.src;
  d.blend.dstA = separate ? st.rs(RS_DESTBLENDALPHA) : d.blend.dst;
  d.blend.opA = separate ? st.rs(RS_BLENDOPALPHA) : d.blend.op;
  d.blend.factor = colorFromD3D(st.rs(RS_BLENDFACTOR));
  d.pixelsShaded = &stats_.pixelsShaded;
  std::atomic<uint32_t> pixelBoundStops{0};
  d.execContext.boundStops = &pixelBoundStops;

  // Primitive assembly, clipping and setup.
  const Rect bounds = activeRect(st, d.width, d.height);
  const Viewport& vp = st.viewport;
  const float gb = std::max(1.0f, 16384.0f / float(std::max({vp.width, vp.height, 1})));
  const uint32_t cull = st.rs(RS_CULLMODE);
  const uint32_t fill = st.rs(RS_FILLMODE);
  // Point size: D3DRS_POINTSIZE clamped to POINTSIZE_MIN/MAX, or the vertex's own
  // size (fixed-function T&L computes and clamps it, with POINTSCALEENABLE; a vertex
  // shader's oPts is clamped here), finally limited to the caps' MaxPointSize.
  const float sizeMin = st.rsFloat(RS_POINTSIZE_MIN);
  const float sizeMax = std::max(sizeMin, st.rsFloat(RS_POINTSIZE_MAX));
  const float deviceMaxPointSize = std::max(caps_.maxPointSize, 1.0f);
  const float renderStatePointSize = std::clamp(st.rsFloat(RS_POINTSIZE), sizeMin, sizeMax);
  const bool vertexPointSize = !vs || vcfg.hasPSize;
  auto pointSizeOf = [&](const Vec4* out) {
    const float size = vertexPointSize ? std::clamp(out[kVertexOutPSize].x, sizeMin, sizeMax)
                                       : renderStatePointSize;
    return size >= 1.0f ? std::min(size, deviceMaxPointSize) : 1.0f;  // NaN: 1
  };
  const bool pointSprite = st.rs(RS_POINTSPRITEENABLE) != 0;

  auto toScreen = [&](const Vec4* out, SetupVertex& s) {
    const Vec4& p = out[0];
    if (vcfg.pretransformed) {
      // XYZRHW: already in screen space; rhw is 1/w for perspective interpolation.
      s.x = p.x;
      s.y = p.y;
      s.z = p.z;
      s.invW = p.w != 0 ? p.w : 1.0f;
    } else {
      const float iw = 1.0f / p.w;
      s.x = float(vp.x) + (1.0f + p.x * iw) * 0.5f * float(vp.width);
      s.y = float(vp.y) + (1.0f - p.y * iw) * 0.5f * float(vp.height);
      s.z = vp.minZ + p.z * iw * (vp.maxZ - vp.minZ);
      s.invW = iw;
    }
    s.varyings = out;
  };
  auto vertexOut = [&](uint32_t i) -> const Vec4* { return verts[i - lo].out; };
  // Near/far, the guard band and the user clip planes. Pretransformed vertices are
  // not clipped (they have no clip space; D3DPMISCCAPS_CLIPTLVERTS concerns the
  // viewport, which the rasterizer's bounds already enforce).
  ClipPlanes clip;
  clip.guardBand = gb;
  if (!vcfg.pretransformed) userClipPlanes(st, vs != nullptr, clip);

  std::vector<ClipVertex> poly;
  auto triangle = [&](uint32_t i0, uint32_t i1, uint32_t i2) {
    const Vec4* o[3] = {vertexOut(i0), vertexOut(i1), vertexOut(i2)};
    auto emit = [&](const Vec4* a, const Vec4* b, const Vec4* c) {
      SetupVertex sv[3];
      toScreen(a, sv[0]);
      toScreen(b, sv[1]);
      toScreen(c, sv[2]);
      if (fill == FILL_SOLID) {
        setupTriangle(d, sv, cull, bounds, flat);
        return;
      }
      // Wireframe/point fill: cull first, then draw edges or vertices.
      const double area = double(sv[1].x - sv[0].x) * (sv[2].y - sv[0].y) -
                          double(sv[2].x - sv[0].x) * (sv[1].y - sv[0].y);
      if (area == 0 || (cull == CULL_CCW && area < 0) || (cull == CULL_CW && area > 0)) return;
      if (d.depthBias != 0 || d.slopeScaleDepthBias != 0) {
        // The triangle's depth offset applies to its edges and vertices as well.
        const double x1 = sv[1].x - sv[0].x, y1 = sv[1].y - sv[0].y;
        const double x2 = sv[2].x - sv[0].x, y2 = sv[2].y - sv[0].y;
        const double z0 = bufferDepth(d, sv[0]);
        const double z1 = bufferDepth(d, sv[1]) - z0, z2 = bufferDepth(d, sv[2]) - z0;
        const float offset = depthOffset(d.depthBias, d.slopeScaleDepthBias,
                                         float((z1 * y2 - z2 * y1) / area), float((z2 * x1 - z1 * x2) / area));
        for (SetupVertex& v : sv) (d.wBuffer ? v.wDepthOffset : v.z) += offset;
      }
      if (fill == FILL_WIREFRAME) {
        setupLine(d, sv[0], sv[1], bounds, flat);
        setupLine(d, sv[1], sv[2], bounds, flat);
        setupLine(d, sv[2], sv[0], bounds, flat);
      } else {
        const Vec4* outs[3] = {a, b, c};
        for (int k = 0; k < 3; ++k) setupPoint(d, sv[k], pointSizeOf(outs[k]), bounds, pointSprite);
      }
    };
    if (vcfg.pretransformed ||
        (!clip.outside(o[0][0]) && !clip.outside(o[1][0]) && !clip.outside(o[2][0]))) {
      emit(o[0], o[1], o[2]);
      return;
    }
    poly.assign(3, {});
    for (int k = 0; k < 3; ++k) std::memcpy(poly[k].v, o[k], sizeof(poly[k].v));
    clipPolygon(poly, clip);
    for (size_t k = 2; k < poly.size(); ++k) {
      // Clipped vertices keep the provoking (first) vertex's flat colors.
      emit(poly[0].v, poly[k - 1].v, poly[k].v);
    }
  };
  auto line = [&](uint32_t i0, uint32_t i1) {
    const Vec4* a = vertexOut(i0);
    const Vec4* b = vertexOut(i1);
    SetupVertex sa, sb;
    ClipVertex ca, cb;  // outlive the setup: SetupVertex points at their varyings
    if (!vcfg.pretransformed && (clip.outside(a[0]) || clip.outside(b[0]))) {
      if (!clipSegment(a, b, clip, ca, cb)) return;
      toScreen(ca.v, sa);
      toScreen(cb.v, sb);
    } else {
      toScreen(a, sa);
      toScreen(b, sb);
    }
    setupLine(d, sa, sb, bounds, flat);
  };
  auto point = [&](uint32_t i) {
    const Vec4* a = vertexOut(i);
    // A point whose centre is outside the view volume is culled whole.
    if (!vcfg.pretransformed && clip.outsideVolume(a[0])) return;
    const float size = pointSizeOf(a);
    if (!vcfg.pretransformed && clip.userCount) {
      // User planes clip the point's square like a polygon
      // (D3DPMISCCAPS_CLIPPLANESCALEDPOINTS): the corners, then two triangles per
      // clipped piece, with the same coverage rule and constant (or sprite) values.
      const float side = std::max(size, 1.0f) * a[0].w;  // half side * 2w
      ClipVertex corners[4];
      pointCorners(a, side / float(vp.width), side / float(vp.height), pointSprite, corners);
      bool inside = true;
      for (const ClipVertex& c : corners) inside &= clip.insideUser(c.v[0]);
      if (!inside) {
        poly.assign(corners, corners + 4);
        clipPolygon(poly, clip);
        for (size_t k = 2; k < poly.size(); ++k) {
          SetupVertex sv[3];
          toScreen(poly[0].v, sv[0]);
          toScreen(poly[k - 1].v, sv[1]);
          toScreen(poly[k].v, sv[2]);
          setupTriangle(d, sv, CULL_NONE, bounds, flat, false);
        }
        return;
      }
    }
    SetupVertex s;
    toScreen(a, s);
    setupPoint(d, s, size, bounds, pointSprite);
  };

  switch (type) {
    case PT_POINTLIST:
      for (uint32_t i = 0; i < primitiveCount; ++i) point(idx[i]);
      break;
    case PT_LINELIST:
      for (uint32_t i = 0; i < primitiveCount; ++i) line(idx[2 * i], idx[2 * i + 1]);
      break;
    case PT_LINESTRIP:
      for (uint32_t i = 0; i < primitiveCount; ++i) line(idx[i], idx[i + 1]);
      break;
    case PT_TRIANGLELIST:
      for (uint32_t i = 0; i < primitiveCount; ++i) triangle(idx[3 * i], idx[3 * i + 1], idx[3 * i + 2]);
      break;
    case PT_TRIANGLESTRIP:
      // Odd triangles swap two vertices to keep the winding consistent.
      for (uint32_t i = 0; i < primitiveCount; ++i) {
        if (i & 1) triangle(idx[i + 1], idx[i], idx[i + 2]);
        else triangle(idx[i], idx[i + 1], idx[i + 2]);
      }
      break;
    case PT_TRIANGLEFAN:
      // D3D's provoking vertex for flat shading in a fan is the second vertex of each
      // triangle (v[i+1]); start the triangle there.
      for (uint32_t i = 0; i < primitiveCount; ++i) triangle(idx[i + 1], idx[i + 2], idx[0]);
      break;
  }
  stats_.primitives += primitiveCount;
  d.fill = impl_->pendingClear;
  impl_->pendingClear = {};
  rasterize(d, impl_->pool);
  for (const TexturePtr& t : targets_)
    if (t) t->markDirty();
  ++stats_.draws;
  reportBoundStops(vs ? "vertex shader" : nullptr, vertexBoundStops.load(), "vertices");
  reportBoundStops(ps ? "pixel shader" : nullptr, pixelBoundStops.load(), "pixels");
}

// A shader stopped by kMaxExecutedInstructions leaves the outputs it had written:
// reported once per draw, since the picture is then not what the program says.
void Device::reportBoundStops(const char* stage, uint32_t batches, const char* lanes) {
  if (!stage || batches == 0) return;
  Diagnostic d;
  d.severity = Severity::Warning;
  d.code = "D1001";
  d.message = fmt::format(
      "draw {}: the {} stopped after {} executed instructions in {} batch{} of {} {}; their "
      "outputs hold what was written until then",
      stats_.draws, stage, exec::kMaxExecutedInstructions, batches, batches == 1 ? "" : "es",
      kBatchLanes, lanes);
  if (options_.warningsToStderr) std::fprintf(stderr, "refx: %s\n", d.str().c_str());
  diagnostics_.report(std::move(d));
}

}  // namespace refx
