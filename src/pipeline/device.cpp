#include "refx/pipeline/device.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>

#include "draw_plan.h"
#include "raster.h"
#include "raster_fill.h"
#include "state_support.h"
#include "refx/core/diagnostics.h"
#include "refx/shader/version_rules.h"
#include "render_targets.h"
#include "shader_lowering.h"
#include "validate.h"

namespace refx {

using namespace d3d;
using namespace pipeline;

// Plans kept per device: every distinct state a frame uses, with room to spare.
constexpr size_t kPlanCacheCapacity = 256;

struct Device::Impl {
  explicit Impl(int threads) : pool(threads) {}
  ThreadPool pool;
  DrawPlanCache plans{kPlanCacheCapacity};
  std::vector<ShadedVertex> vertices;
  // The last draw's primitive and plane lists, emptied: the next draw's start with their
  // capacity (no allocation and no fresh pages per draw).
  std::vector<Primitive> prims;
  std::vector<float> planes;
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

void Device::clear(uint32_t flags, D3DColor color, float z, uint32_t stencil) {
  const TexturePtr& target0 = targets_[0];
  const int w = target0 ? target0->width() : (depth_ ? depth_->width : 0);
  const int h = target0 ? target0->height() : (depth_ ? depth_->height : 0);
  const Rect r = activeRect(state_, w, h);
  if (overwritesPendingClear(impl_->pendingClear, flags, r)) impl_->pendingClear = {};
  resolveClear();
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

// A draw: the plan for the state (cached), then the stages (draw_plan.h).
void Device::draw(PrimitiveType type, uint32_t primitiveCount, int32_t baseVertex,
                  const void* indices, bool index32, uint32_t vertexCount, uint32_t firstVertex) {
  if (!targets_[0]) fail("draw without a render target");
  if (type < PT_POINTLIST || type > PT_TRIANGLEFAN) fail("unknown primitive type {}", uint32_t(type));
  const uint32_t indexCount = verticesForPrimitives(type, primitiveCount);
  if (primitiveCount == 0 || indexCount == 0) return;
  const DeviceState& st = state_;
  if (st.declaration.elements.empty()) fail("draw without a vertex declaration or FVF");
  const DrawIndices vertices = gatherIndices(indices, index32, indexCount, baseVertex, firstVertex);
  if (vertices.count > (1u << 24))
    fail("draw references {} vertices; at most 16777216 are supported", vertices.count);

  using Clock = std::chrono::steady_clock;
  Clock::time_point mark = Clock::now();
  // Adds the time since the last mark to `total` and moves the mark.
  const auto stageDone = [&mark](double& total) {
    const Clock::time_point now = Clock::now();
    total += std::chrono::duration<double, std::micro>(now - mark).count();
    mark = now;
  };
  DrawStats::StageTimes& times = stats_.stageMicroseconds;
  DrawSurfaces surfaces;
  for (size_t i = 0; i < targets_.size(); ++i) surfaces.targets[i] = targets_[i].get();
  surfaces.depth = depth_.get();
  DrawPlanKey key = drawPlanKey(st, surfaces, *this);
  std::shared_ptr<const DrawPlan> plan = impl_->plans.find(key);
  const bool newPlan = !plan;
  if (plan) {
    ++stats_.planCacheHits;
  } else {
    ++stats_.planCacheMisses;
    plan = buildDrawPlan(st, surfaces, *this);
    impl_->plans.insert(std::move(key), plan);
  }

  stageDone(times.plan);
  exec::PrepareOptions prepareOptions;
  prepareOptions.jit = options_.jit;
  exec::ProgramBuildInfo vertexBuild, pixelBuild, pixelRestBuild;
  const uint32_t vertexBoundStops = runVertexStage(*plan, st, impl_->pool, vertices.lo,
                                                   vertices.count, impl_->vertices, prepareOptions, vertexBuild);
  stageDone(times.vertex);
  RasterDraw d;
  d.state = &st;
  PixelBindings pixelBindings;
  bindPixelStage(*plan, st, pixelBindings, d);
  bindOutputMerger(*plan, st, surfaces, d);
  d.pixelsShaded = &stats_.pixelsShaded;
  d.prepareOptions = prepareOptions;
  d.pixelBuild = &pixelBuild;
  d.pixelRestBuild = &pixelRestBuild;
  std::atomic<uint32_t> pixelBoundStops{0};
  d.execContext.boundStops = &pixelBoundStops;
  d.prims.swap(impl_->prims);
  d.planes.swap(impl_->planes);
  setupPrimitives(*plan, st, caps_.maxPointSize, type, primitiveCount, vertices, impl_->vertices, d, impl_->pool);
  stageDone(times.setup);
  stats_.primitives += primitiveCount;
  d.fill = impl_->pendingClear;
  impl_->pendingClear = {};
  keepUntouchedDepthClear(d, impl_->pendingClear);
  rasterize(d, impl_->pool);
  stageDone(times.raster);
  d.prims.clear();
  d.planes.clear();
  // Kept for the next draw unless very large (one huge draw need not hold its memory).
  constexpr size_t kKeptListBytes = size_t(64) << 20;
  if (d.prims.capacity() * sizeof(Primitive) + d.planes.capacity() * sizeof(float) <= kKeptListBytes) {
    d.prims.swap(impl_->prims);
    d.planes.swap(impl_->planes);
  }
  if (newPlan) {  // what runs the new plan's programs (compile time 0: compiled before)
    auto record = [&](const exec::Program& p, const exec::ProgramBuildInfo& b) {
      stats_.programBuilds.push_back({p.name, b.instructions, b.compileMicroseconds, b.backend});
    };
    record(plan->vertexProgram(), vertexBuild);
    if (d.pixelProgram) record(*d.pixelProgram, pixelBuild);
    if (d.pixelRest && d.groupedLookups) record(*d.pixelRest, pixelRestBuild);
  }
  for (const TexturePtr& t : targets_)
    if (t) t->markDirty();
  ++stats_.draws;
  if (d.passthroughSampler) ++stats_.samplePassthroughDraws;
  if (d.groupedLookups) ++stats_.groupedLookupDraws;
  reportBoundStops(plan->vertexLowered ? "vertex shader" : nullptr, vertexBoundStops, "vertices");
  reportBoundStops(plan->pixelLowered ? "pixel shader" : nullptr, pixelBoundStops.load(), "pixels");
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
