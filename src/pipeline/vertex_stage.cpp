// Vertex fetch and vertex processing: the primitive stream's indices, then the plan's
// vertex program (a vertex shader or fixed-function T&L) over SoA batches of vertices.
#include <algorithm>
#include <atomic>
#include <cstring>

#include <immintrin.h>

#include "draw_plan.h"
#include "refx/pipeline/shader_object.h"

namespace refx::pipeline {

using namespace d3d;

DrawIndices gatherIndices(const void* indices, bool index32, uint32_t indexCount,
                          int32_t baseVertex, uint32_t firstVertex) {
  DrawIndices r;
  r.idx.resize(indexCount);
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
    r.idx[i] = v;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  r.lo = lo;
  r.count = hi - lo + 1;
  return r;
}

uint32_t runVertexStage(const DrawPlan& plan, const DeviceState& st, ThreadPool& pool,
                        uint32_t lo, uint32_t count, std::vector<ShadedVertex>& verts,
                        const exec::PrepareOptions& options, exec::ProgramBuildInfo& build) {
  StreamView streams[16];
  for (int s = 0; s < 16; ++s) {
    const StreamSource& src = st.streams[s];
    if (!src.buffer) continue;
    streams[s].data = src.buffer->data.data() + std::min<size_t>(src.offset, src.buffer->data.size());
    streams[s].size = src.buffer->data.size() - std::min<size_t>(src.offset, src.buffer->data.size());
    streams[s].stride = src.stride;
  }
  const bool vs = plan.vertexLowered != nullptr;
  const exec::Program& vprog = plan.vertexProgram();
  verts.resize(count);
  const uint32_t batches = (count + kBatchLanes - 1) / kBatchLanes;
  std::vector<exec::BatchRegisters> vregs(pool.threadCount());
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
    vbound[s].state = plan.samplers[size_t(kVertexSampler0 + s)];
    vbindings[s].context = &vbound[s];
    vbindings[s].sample = sampleBound;
  }
  // The vertex shader's constant file (the API's float constants), or the values
  // fixed-function T&L reads (exec/abi.h kConstVertex*).
  std::vector<Vec4> vconst;
  if (vs) {
    const std::vector<Vec4>& api = st.vsConstF;
    vconst.resize(std::max<size_t>(api.size(), size_t(std::max(plan.vertexLowered->floatConstantsRead, 0))));
    std::copy(api.begin(), api.end(), vconst.begin());
  } else {
    fixedFunctionVertexConstants(st, plan.vertexConfig, vconst);
  }
  exec::ExecContext vctx;
  vctx.constants = vconst.data();
  vctx.constantCount = int(vconst.size());
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
  // The program is prepared for this draw's constants (once per worker's registers).
  std::vector<exec::ProgramRunner> runners(vregs.size());
  for (size_t i = 0; i < vregs.size(); ++i) {
    const exec::ProgramBuildInfo info = exec::prepare(vprog, vctx, vregs[i], options);
    if (i == 0) build = info;
    runners[i] = exec::runnerFor(vprog, vctx, vregs[i]);
  }
  static_assert(sizeof(Vec4) == 4 * sizeof(float), "Vec4 is x, y, z, w and nothing else");
  pool.parallelFor(batches, [&](size_t b, int thread) {
    exec::BatchRegisters& r = vregs[thread];
    const uint32_t first = lo + uint32_t(b) * kBatchLanes;
    const int n = int(std::min<uint32_t>(kBatchLanes, lo + count - first));
    resetInputs(r, !vs);
    fetchVertices(plan.fetch, streams, first, n, r);
    for (auto& o : r.outputs) std::memset(&o, 0, sizeof(o));
    r.laneMask = 0xffff;
    if (runners[size_t(thread)]) runners[size_t(thread)]();
    else exec::execute(vprog, vctx, r);
    ShadedVertex* out = verts.data() + (first - lo);
    // The outputs from SoA to the vertices' Vec4s, four lanes at a time (a 4x4 transpose).
    for (int o = 0; o < kVaryingCount; ++o) {
      const float (*c)[kBatchLanes] = r.outputs[o].c;
      for (int l0 = 0; l0 < n; l0 += 4) {
        __m128 x = _mm_loadu_ps(c[0] + l0), y = _mm_loadu_ps(c[1] + l0);
        __m128 z = _mm_loadu_ps(c[2] + l0), w = _mm_loadu_ps(c[3] + l0);
        _MM_TRANSPOSE4_PS(x, y, z, w);
        const __m128 lanes[4] = {x, y, z, w};
        for (int k = 0; k < 4 && l0 + k < n; ++k) _mm_storeu_ps(&out[l0 + k].out[o].x, lanes[k]);
      }
    }
    for (int l = 0; l < n; ++l) {
      ShadedVertex& sv = out[l];
      if (plan.clampColors)
        for (int o : {int(kVertexOutDiffuse), int(kVertexOutSpecular)})
          for (int c = 0; c < 4; ++c) sv.out[o][c] = std::clamp(sv.out[o][c], 0.0f, 1.0f);
      for (int m = 0; m < 4; ++m)
        if (plan.projectedDivisor[size_t(m)] >= 0)
          sv.out[kVertexOutTex0 + m][3] = sv.out[kVertexOutTex0 + m][plan.projectedDivisor[size_t(m)]];
    }
  });
  return vertexBoundStops.load();
}

}  // namespace refx::pipeline
