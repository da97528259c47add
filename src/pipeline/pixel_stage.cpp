// The pixel stage's bindings for one draw (program, inputs, samplers, constants) and
// the output merger's state and values.
#include <algorithm>

#include "draw_plan.h"
#include "depth.h"
#include "ff_pixel.h"
#include "render_targets.h"
#include "refx/pipeline/shader_object.h"

namespace refx::pipeline {

using namespace d3d;

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

namespace {

// sampleBound for a sampler whose prepared state has the one-level 2D paths: implicit
// lookups (λ from quad derivatives) jump straight to them.
void sampleBoundKernel(const void* ctx, exec::SampleMode mode, const float (*co)[kBatchLanes],
                       uint16_t laneMask, float (*out)[kBatchLanes]) {
  const auto* b = static_cast<const BoundSampler*>(ctx);
  if (mode != exec::SampleMode::Implicit) return sampleBound(ctx, mode, co, laneMask, out);
  const PreparedSampler::ImplicitKernel& kernel = b->prepared->implicitKernel();
  kernel.fn(kernel.context, co[0], co[1], co[2], laneMask, out);
}

}  // namespace

void bindPixelStage(const DrawPlan& plan, const DeviceState& st, PixelBindings& b, RasterDraw& d) {
  for (int s = 0; s < kMaxPixelSamplers; ++s) {
    BoundSampler& bound = b.bound[size_t(s)];
    bound.texture = st.textures[s].get();
    bound.state = plan.samplers[size_t(s)];
    const bool prepared = bound.texture && (plan.pixelSamplersUsed >> s & 1);
    if (prepared) bound.prepared.emplace(*bound.texture, bound.state);
    b.samplers[size_t(s)].context = &bound;
    b.samplers[size_t(s)].sample =
        prepared && bound.prepared->implicitKernel().fn ? sampleBoundKernel : sampleBound;
    b.samplers[size_t(s)].samplePair = prepared ? bound.prepared->implicitPair() : nullptr;
    b.samplers[size_t(s)].pairContext = prepared ? bound.prepared->implicitKernel().context : nullptr;
  }
  // The constant file: a pixel shader's float constants and the bump environment
  // (exec/abi.h); below ps_3_0, and for fixed function, the values the texture stages
  // and the appended fog read.
  const PixelShader* ps = plan.pixelShader.get();
  b.constants.clear();
  if (ps) {
    const std::vector<Vec4>& api = st.psConstF;
    b.constants.resize(std::max<size_t>(api.size(), size_t(std::max(plan.pixelLowered->floatConstantsRead, 0))));
    std::copy(api.begin(), api.end(), b.constants.begin());
    b.constants.resize(std::max(b.constants.size(), size_t(exec::kConstBumpEnv + exec::kConstBumpEnvCount)));
    for (int n = 0; n < exec::kConstBumpEnvCount / 2 && n < kMaxTextureStages; ++n) {
      b.constants[exec::kConstBumpEnv + 2 * n] =
          Vec4(st.tssFloat(n, TSS_BUMPENVMAT00), st.tssFloat(n, TSS_BUMPENVMAT01),
               st.tssFloat(n, TSS_BUMPENVMAT10), st.tssFloat(n, TSS_BUMPENVMAT11));
      b.constants[exec::kConstBumpEnv + 2 * n + 1] =
          Vec4(st.tssFloat(n, TSS_BUMPENVLSCALE), st.tssFloat(n, TSS_BUMPENVLOFFSET), 0, 0);
    }
  }
  if (!ps || !ps->version().atLeast(3, 0)) fixedFunctionPixelConstants(st, b.constants);
  d.pixelProgram = &plan.pixelProgram;
  d.execContext.constants = b.constants.data();
  d.execContext.constantCount = int(b.constants.size());
  d.execContext.samplers = b.samplers.data();
  d.execContext.samplerCount = kMaxPixelSamplers;
  if (ps) {
    d.execContext.intConstants = st.psConstI.data();
    d.execContext.intConstantCount = int(st.psConstI.size());
    d.execContext.boolConstants = st.psConstB.data();
    d.execContext.boolConstantCount = int(st.psConstB.size());
  }
  d.inputs = plan.inputs;
  d.inputCopies.clear();  // setupPrimitives finds them
  d.passthroughSampler = nullptr;
  if (plan.samplePassthrough) {
    const BoundSampler& bound = b.bound[size_t(plan.samplePassthrough->sampler)];
    const int input = plan.samplePassthrough->input;
    for (size_t j = 0; j + 1 < d.inputs.size(); ++j)
      if (d.inputs[j].input == input && d.inputs[j].component == 0 && d.inputs[j + 1].input == input &&
          d.inputs[j + 1].component == 1 && bound.prepared && bound.texture->type() == TextureType::Texture2D) {
        d.passthroughSampler = &*bound.prepared;
        d.passthroughInput = int(j);
      }
  }
  d.prologue.clear();
  d.pixelRest = nullptr;
  if (plan.texturePrologue) {
    for (const exec::TexturePrologue::Lookup& l : plan.texturePrologue->lookups) {
      const BoundSampler* bound = l.sampler < kMaxPixelSamplers ? &b.bound[size_t(l.sampler)] : nullptr;
      if (!bound || !bound->prepared || bound->texture->type() != TextureType::Texture2D) {
        d.prologue.clear();
        break;
      }
      d.prologue.push_back({&*bound->prepared, l.input, l.file, l.index, l.channels, l.input});
    }
    if (!d.prologue.empty()) d.pixelRest = &plan.texturePrologue->rest;
  }
  d.usesPosition = plan.usesPosition;
  d.usesFace = plan.usesFace;
  d.shaderDepth = plan.shaderDepth;
}

void bindOutputMerger(const DrawPlan& plan, const DeviceState& st, const DrawSurfaces& surfaces,
                      RasterDraw& d) {
  for (int i = 0; i < kMaxRenderTargets; ++i)
    if (plan.writesTarget[size_t(i)])
      d.targets[size_t(i)] = colorTargetOf(*surfaces.targets[size_t(i)], colorWriteMask(st, i));
  d.srgbWrite = plan.srgbWrite;
  d.dither = plan.dither;
  d.width = surfaces.targets[0]->width();
  d.height = surfaces.targets[0]->height();
  d.depth = surfaces.depth;
  d.depthTest = plan.depthTest;
  d.depthWrite = plan.depthWrite;
  d.depthFunc = plan.depthFunc;
  d.wBuffer = plan.wBuffer;
  d.invFarW = 1.0f / projectionFarW(st.projection);
  d.depthBias = st.rsFloat(RS_DEPTHBIAS);
  d.slopeScaleDepthBias = st.rsFloat(RS_SLOPESCALEDEPTHBIAS);
  d.stencil = plan.stencil;
  d.alphaTest = plan.alphaTest;
  d.alphaFunc = plan.alphaFunc;
  d.earlyDepth = plan.earlyDepth;
  d.blend = plan.blend;
  d.blend.factor = colorFromD3D(st.rs(RS_BLENDFACTOR));
  d.alphaRef = uint8_t(st.rs(RS_ALPHAREF) & 0xff);
  d.stencilRef = uint8_t(st.rs(RS_STENCILREF));
  d.stencilMask = uint8_t(st.rs(RS_STENCILMASK));
  d.stencilWriteMask = uint8_t(st.rs(RS_STENCILWRITEMASK));
  d.stencilOps[0] = {st.rs(RS_STENCILFUNC), st.rs(RS_STENCILFAIL), st.rs(RS_STENCILZFAIL), st.rs(RS_STENCILPASS)};
  // Two-sided stencil: counter-clockwise primitives use the CCW_ states.
  d.stencilOps[1] = st.rs(RS_TWOSIDEDSTENCILMODE)
                        ? std::array<uint32_t, 4>{st.rs(RS_CCW_STENCILFUNC), st.rs(RS_CCW_STENCILFAIL),
                                                  st.rs(RS_CCW_STENCILZFAIL), st.rs(RS_CCW_STENCILPASS)}
                        : d.stencilOps[0];
  d.merge = plan.merge;
  d.earlyDepthTestFn = plan.earlyDepthTestFn;
}

}  // namespace refx::pipeline
