// refx::Device: a Direct3D 9 device rendering in software. Method names follow
// IDirect3DDevice9 so D3D9 code maps 1:1.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "refx/core/color.h"
#include "refx/core/diagnostics.h"
#include "refx/core/large_buffer.h"
#include "refx/core/precision.h"
#include "refx/pipeline/caps.h"
#include "refx/pipeline/shader_object.h"
#include "refx/pipeline/state.h"

namespace refx {

// Depth/stencil surface (D24S8 semantics: 24-bit depth as float in [0,1], 8-bit stencil).
struct DepthStencilSurface {
  int width = 0, height = 0;
  LargeBuffer<float> depth;
  LargeBuffer<uint8_t> stencil;
  DepthStencilSurface(int w, int h) : width(w), height(h), depth(size_t(w) * h, 1.0f),
                                      stencil(size_t(w) * h, 0) {}
};
using DepthStencilPtr = std::shared_ptr<DepthStencilSurface>;


struct DeviceOptions {
  int threads = 0;  // 0: all cores
  Precision precision = Precision::Exact;
  // Warnings (Device::diagnostics()) are also printed on stderr as they happen.
  bool warningsToStderr = true;
  // Native code for the draw's programs (the interpreter otherwise, which stays the
  // reference). The environment variable REFX_JIT=0 turns it off for every device.
  bool jit = true;
};

class StateBlock {
 public:
  StateBlock() = default;
  explicit StateBlock(DeviceState s) : state_(std::move(s)) {}
  const DeviceState& state() const { return state_; }
 private:
  DeviceState state_;
};

struct DrawStats {
  uint64_t pixelsShaded = 0;  // pixels that ran the pixel stage (summed over draws)
  uint64_t primitives = 0;
  uint64_t draws = 0;
  // Draws whose DrawPlan (programs, interpolation, output merger for the state) was
  // found in the device's cache, and draws that had to build one.
  uint64_t planCacheHits = 0, planCacheMisses = 0;
  // Draws whose pixel program only samples a 2D texture into an opaque 8-bit target,
  // run as the sample stored as bytes (the same pixels, without running the program).
  uint64_t samplePassthroughDraws = 0;
  // Draws whose texture lookups were made for groups of blocks at once (the lookups a
  // pixel program starts with, or a pass-through's), then the rest block by block.
  uint64_t groupedLookupDraws = 0;
  // One entry per program translated for a plan: which program, how long the
  // translation took and what runs it ("jit-avx512", "jit-avx2", "interpreter").
  struct ProgramBuild {
    std::string name;
    int instructions = 0;
    double microseconds = 0;
    std::string backend;
  };
  std::vector<ProgramBuild> programBuilds;
  // Wall time of the draws' stages, summed over draws, in microseconds: finding (or
  // building) the plan, vertex fetch and processing, binding the pixel stage with
  // clipping and setup, then binning and shading. Where a frame's time goes (`refx
  // bench --verbose`).
  struct StageTimes {
    double plan = 0, vertex = 0, setup = 0, raster = 0;
  };
  StageTimes stageMicroseconds;
};

class Device {
 public:
  explicit Device(CapsProfile caps, DeviceOptions options = {});
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  const CapsProfile& caps() const { return caps_; }
  void setCaps(CapsProfile caps) { caps_ = std::move(caps); }
  const DeviceOptions& options() const { return options_; }
  void setThreads(int threads);
  void setPrecision(Precision precision) { options_.precision = precision; }

  // Render target `index` (0-3, below the caps' NumSimultaneousRTs): level 0 of a 2D
  // A8R8G8B8, X8R8G8B8 or A32B32G32R32F texture; ps_2_0 and later write oCn to target n.
  // Target 0 cannot be null, the others are unbound with null. All bound targets have
  // the same size, and the same bit depth unless the caps have
  // D3DPMISCCAPS_MRTINDEPENDENTBITDEPTHS. Setting target 0 resets the viewport and the
  // scissor rectangle to the whole target, as SetRenderTarget does. Throws refx::Error.
  void setRenderTarget(int index, TexturePtr target);
  void setRenderTarget(TexturePtr target) { setRenderTarget(0, std::move(target)); }
  // The accessors write a pending (deferred) Clear first.
  const TexturePtr& renderTarget(int index = 0) const;
  void setDepthStencilSurface(DepthStencilPtr ds);
  const DepthStencilPtr& depthStencilSurface() const;

  // CLEAR_TARGET fills every bound render target (A32B32G32R32F ones with c/255).
  void clear(uint32_t flags, D3DColor color, float z, uint32_t stencil);

  void setRenderState(d3d::RenderState s, uint32_t value);
  uint32_t getRenderState(d3d::RenderState s) const { return state_.renderStates[s]; }
  void setTextureStageState(int stage, d3d::TextureStageState s, uint32_t value);
  uint32_t getTextureStageState(int stage, d3d::TextureStageState s) const {
    return state_.stageStates[stage][s];
  }
  void setSamplerState(int sampler, d3d::SamplerStateType s, uint32_t value);
  uint32_t getSamplerState(int sampler, d3d::SamplerStateType s) const {
    return state_.samplerStates[sampler][s];
  }
  void setTexture(int sampler, TexturePtr texture);
  void setTransform(uint32_t type, const Matrix& m);  // d3d::TransformType or TS_TEXTURE0+n
  Matrix getTransform(uint32_t type) const;
  void setLight(int index, const Light& light);
  void lightEnable(int index, bool enable);
  void setMaterial(const Material& m) { state_.material = m; }
  void setViewport(const Viewport& vp) { state_.viewport = vp; }
  void setScissorRect(const Rect& r) { state_.scissor = r; }
  // SetClipPlane / GetClipPlane: index 0-5, plane (A, B, C, D).
  void setClipPlane(int index, const float plane[4]);
  Vec4 getClipPlane(int index) const;

  void setFVF(uint32_t fvf) { state_.declaration = VertexDeclaration::fromFVF(fvf); }
  void setVertexDeclaration(VertexDeclaration decl) { state_.declaration = std::move(decl); }
  void setStreamSource(int stream, VertexBufferPtr vb, uint32_t offset, uint32_t stride);
  void setIndices(IndexBufferPtr ib) { state_.indices = std::move(ib); }

  void drawPrimitive(d3d::PrimitiveType type, uint32_t startVertex, uint32_t primitiveCount);
  void drawIndexedPrimitive(d3d::PrimitiveType type, int32_t baseVertex, uint32_t minIndex,
                            uint32_t numVertices, uint32_t startIndex, uint32_t primitiveCount);
  void drawPrimitiveUP(d3d::PrimitiveType type, uint32_t primitiveCount, const void* vertices,
                       uint32_t stride);
  void drawIndexedPrimitiveUP(d3d::PrimitiveType type, uint32_t minIndex, uint32_t numVertices,
                              uint32_t primitiveCount, const void* indices, bool index32,
                              const void* vertices, uint32_t stride);

  // Shaders. Creation decodes, validates (with the profile's limits) and lowers the
  // tokens, throwing refx::Error for a shader that cannot run; whether the profile's
  // shader versions allow it is ValidateDevice's question, as in D3D9.
  VertexShaderPtr createVertexShader(std::span<const uint32_t> tokens) const;
  PixelShaderPtr createPixelShader(std::span<const uint32_t> tokens) const;
  void setVertexShader(VertexShaderPtr vs) { state_.vertexShader = std::move(vs); }
  void setPixelShader(PixelShaderPtr ps) { state_.pixelShader = std::move(ps); }
  const VertexShaderPtr& getVertexShader() const { return state_.vertexShader; }
  const PixelShaderPtr& getPixelShader() const { return state_.pixelShader; }
  // Constants: `count` registers from `start` (float: 4 floats each; int: 4 ints each;
  // bool: one BOOL each, nonzero = TRUE).
  void setVertexShaderConstantF(uint32_t start, const float* data, uint32_t count);
  void setVertexShaderConstantI(uint32_t start, const int* data, uint32_t count);
  void setVertexShaderConstantB(uint32_t start, const int* data, uint32_t count);
  void setPixelShaderConstantF(uint32_t start, const float* data, uint32_t count);
  void setPixelShaderConstantI(uint32_t start, const int* data, uint32_t count);
  void setPixelShaderConstantB(uint32_t start, const int* data, uint32_t count);
  // The version rules' device limits from the caps profile.
  shader::ValidationCaps shaderValidationCaps() const;

  StateBlock createStateBlock() const { return StateBlock(state_); }
  void applyStateBlock(const StateBlock& sb) { state_ = sb.state(); }
  const DeviceState& state() const { return state_; }

  // ValidateDevice against the active caps profile.
  // (with the render targets bound: NumSimultaneousRTs, MRTINDEPENDENTBITDEPTHS)
  ValidationResult validate() const;

  // What the device reported while drawing, at most one warning per draw and kind
  // (code D1001: a shader stopped by the executed-instruction bound).
  const DiagnosticSink& diagnostics() const { return diagnostics_; }
  void clearDiagnostics() { diagnostics_ = {}; }

  const DrawStats& stats() const { return stats_; }
  void resetStats() { stats_ = {}; }

 private:
  struct Impl;
  void draw(d3d::PrimitiveType type, uint32_t primitiveCount, int32_t baseVertex,
            const void* indices, bool index32, uint32_t vertexCount, uint32_t firstVertex);
  void resolveClear() const;  // writes a Clear that was deferred to the next draw
  void reportBoundStops(const char* stage, uint32_t batches, const char* lanes);

  CapsProfile caps_;
  DeviceOptions options_;
  DeviceState state_;
  std::array<TexturePtr, 4> targets_;  // SetRenderTarget 0-3
  DepthStencilPtr depth_;
  DrawStats stats_;
  DiagnosticSink diagnostics_;
  std::unique_ptr<Impl> impl_;
};

// Number of vertices a primitive count needs (D3D rules).
uint32_t verticesForPrimitives(d3d::PrimitiveType type, uint32_t primitiveCount);

}  // namespace refx
