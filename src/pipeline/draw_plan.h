// A draw as a sequence of stages, and the DrawPlan that holds everything a draw needs
// that depends on the device state alone (not on constants, transforms, the textures'
// contents or the vertices): the vertex and pixel programs, the interpolation inputs,
// the decoded sampler states and the output-merger function for the state. Plans are
// built once per state key and cached by the device.
//
//   Device::draw:  gatherIndices -> runVertexStage -> bindPixelStage / bindOutputMerger
//                  -> setupPrimitives (clipping, triangle/line/point setup)
//                  -> rasterize (binning, pixel shading, output merge; raster.cpp)
#pragma once
#include <array>
#include <cstdint>
#include <list>
#include <memory>
#include <optional>
#include <unordered_map>
#include <vector>

#include "ff_vertex.h"
#include "raster.h"
#include "refx/core/thread_pool.h"
#include "refx/exec/analysis.h"
#include "refx/exec/lower.h"
#include "refx/resource/sampler.h"
#include "vertex_fetch.h"

namespace refx::pipeline {

// The surfaces a draw writes, as far as they shape its plan.
struct DrawSurfaces {
  std::array<Texture*, kMaxRenderTargets> targets{};
  DepthStencilSurface* depth = nullptr;
};

// Exactly the state a plan reads, as words, with its hash.
struct DrawPlanKey {
  std::vector<uint32_t> words;
  size_t hash = 0;
  bool operator==(const DrawPlanKey& o) const { return hash == o.hash && words == o.words; }
};
struct DrawPlanKeyHash {
  size_t operator()(const DrawPlanKey& k) const { return k.hash; }
};

struct DrawPlan {
  // The shader objects the key names by address, held while the plan lives.
  VertexShaderPtr vertexShader;
  PixelShaderPtr pixelShader;

  // Vertex stage: the vertex shader's program, or fixed-function T&L reading its values
  // from fixedFunctionVertexConstants.
  std::shared_ptr<const exec::LoweredShader> vertexLowered;  // null: fixed function
  exec::Program fixedFunctionVertex;
  FixedFunctionVertexConfig vertexConfig;
  std::vector<FetchElement> fetch;
  bool clampColors = false;  // vertex colours reach the pixel stage in [0,1]
  std::array<int8_t, 4> projectedDivisor{-1, -1, -1, -1};  // ps_1_1-1_3 COUNTn|PROJECTED
  bool vertexPointSize = false;  // the vertex stage writes the point size
  const exec::Program& vertexProgram() const {
    return vertexLowered ? vertexLowered->program : fixedFunctionVertex;
  }

  // Pixel stage: the pixel shader's program or the texture stage cascade, with
  // specular and fog appended.
  std::shared_ptr<const exec::LoweredShader> pixelLowered;  // null: fixed function
  exec::Program pixelProgram;
  std::vector<InterpolatedInput> inputs;
  bool usesPosition = false, usesFace = false, shaderDepth = false;
  bool flat = false;  // D3DSHADE_FLAT
  uint32_t pixelSamplersUsed = 0;  // bit s: the program samples sampler s
  std::array<SamplerState, d3d::kMaxSamplers> samplers{};  // decoded sampler states
  std::array<bool, kMaxRenderTargets> writesTarget{};  // target n takes the program's oCn

  // Output merger.
  RasterDraw::Blend blend{};  // factor: per draw
  bool alphaTest = false, depthTest = false, depthWrite = false, stencil = false;
  bool earlyDepth = false, wBuffer = false, srgbWrite = false, dither = false;
  uint32_t alphaFunc = 8, depthFunc = 4;
  MergeBatchFn merge = nullptr;
  EarlyDepthFn earlyDepthTestFn = nullptr;
  // The program only samples a texture into output 0 and the merge only stores it
  // (opaque, 8-bit target 0 alone, depth tested early if at all): the pixel stage may
  // write the sample's bytes itself (RasterDraw::passthroughSampler).
  std::optional<exec::SamplePassthrough> samplePassthrough;
  // The texture lookups the pixel program can make first (exec::findTexturePrologue),
  // for a draw whose tile loop is compiled for its state (no vPos, vFace or shader
  // depth; depth tested early if at all): the pixel stage may make them for groups of
  // batches (RasterDraw::prologue).
  std::optional<exec::TexturePrologue> texturePrologue;
};

// The key of the plan for `st` drawing into `surfaces` with `options`/`caps`.
DrawPlanKey drawPlanKey(const DeviceState& st, const DrawSurfaces& surfaces, const Device& device);
std::shared_ptr<const DrawPlan> buildDrawPlan(const DeviceState& st, const DrawSurfaces& surfaces,
                                              const Device& device);

// Plans by key, at most `capacity`; the least recently used goes first.
class DrawPlanCache {
 public:
  explicit DrawPlanCache(size_t capacity) : capacity_(capacity) {}
  std::shared_ptr<const DrawPlan> find(const DrawPlanKey& key);
  void insert(DrawPlanKey key, std::shared_ptr<const DrawPlan> plan);
  size_t size() const { return map_.size(); }
  void clear() {
    map_.clear();
    order_.clear();
  }

 private:
  using Order = std::list<DrawPlanKey>;
  struct Entry {
    std::shared_ptr<const DrawPlan> plan;
    Order::iterator use;
  };
  size_t capacity_;
  Order order_;  // most recently used first
  std::unordered_map<DrawPlanKey, Entry, DrawPlanKeyHash> map_;
};

// --- Stages -------------------------------------------------------------------------

// The vertex indices of the primitive stream (relative to baseVertex) and their range.
struct DrawIndices {
  std::vector<uint32_t> idx;
  uint32_t lo = 0, count = 0;  // vertices lo .. lo + count - 1 are shaded
};
DrawIndices gatherIndices(const void* indices, bool index32, uint32_t indexCount,
                          int32_t baseVertex, uint32_t firstVertex);

// Sampler binding for the executor: a texture and its decoded sampler states.
struct BoundSampler {
  const Texture* texture = nullptr;
  SamplerState state;
  std::optional<PreparedSampler> prepared;  // texture and state checked once per draw
};
void sampleBound(const void* ctx, exec::SampleMode mode, const float (*co)[kBatchLanes],
                 uint16_t laneMask, float (*out)[kBatchLanes]);

// Vertex fetch and processing of vertices lo .. lo + count - 1 into `verts`; returns the
// batches a vertex shader's executed-instruction bound stopped.
// `options` says how the program may run (native code or the interpreter); `build` gets
// what ran it.
uint32_t runVertexStage(const DrawPlan& plan, const DeviceState& st, ThreadPool& pool,
                        uint32_t lo, uint32_t count, std::vector<ShadedVertex>& verts,
                        const exec::PrepareOptions& options, exec::ProgramBuildInfo& build);

// What the pixel stage binds for one draw (kept alive until the draw is rasterised).
struct PixelBindings {
  std::array<BoundSampler, d3d::kMaxPixelSamplers> bound;
  std::array<exec::SamplerBinding, d3d::kMaxPixelSamplers> samplers;
  std::vector<Vec4> constants;
};
// The plan's pixel program, inputs, samplers and constants into `d`.
void bindPixelStage(const DrawPlan& plan, const DeviceState& st, PixelBindings& b, RasterDraw& d);
// The plan's output-merger state, the draw's values (reference values, blend factor,
// depth bias) and the surfaces into `d`.
void bindOutputMerger(const DrawPlan& plan, const DeviceState& st, const DrawSurfaces& surfaces,
                      RasterDraw& d);

// Primitive assembly, clipping, culling, viewport and triangle/line/point setup of the
// shaded vertices into d.prims / d.planes, in primitive order; a large draw's ranges of
// primitives on the pool's threads.
void setupPrimitives(const DrawPlan& plan, const DeviceState& st, float maxPointSize,
                     d3d::PrimitiveType type, uint32_t primitiveCount, const DrawIndices& indices,
                     const std::vector<ShadedVertex>& verts, RasterDraw& d, ThreadPool& pool);

// The rectangle Clear and draws may touch: viewport ∩ target (∩ scissor when enabled).
Rect activeRect(const DeviceState& s, int w, int h);

}  // namespace refx::pipeline
