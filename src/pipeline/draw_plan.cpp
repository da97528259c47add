// The DrawPlan of a state: its key, how it is built, and the cache that keeps it.
#include "draw_plan.h"

#include <algorithm>
#include <bit>

#include "depth.h"
#include "ff_pixel.h"
#include "output_merger.h"
#include "render_targets.h"
#include "shader_lowering.h"

namespace refx::pipeline {

using namespace d3d;

namespace {

// Render states that are values rather than structure: read from constants by the
// programs (fixedFunctionVertexConstants, fixedFunctionPixelConstants), or by the
// per-draw setup and output merger (bindOutputMerger, setupPrimitives). They are left
// out of the key; every other render state is in it.
constexpr RenderState kValueRenderStates[] = {
    RS_TEXTUREFACTOR, RS_FOGCOLOR, RS_FOGSTART, RS_FOGEND, RS_FOGDENSITY, RS_AMBIENT,
    RS_TWEENFACTOR, RS_POINTSIZE, RS_POINTSIZE_MIN, RS_POINTSIZE_MAX, RS_POINTSCALE_A,
    RS_POINTSCALE_B, RS_POINTSCALE_C, RS_ALPHAREF, RS_STENCILREF, RS_STENCILMASK,
    RS_STENCILWRITEMASK, RS_BLENDFACTOR, RS_DEPTHBIAS, RS_SLOPESCALEDEPTHBIAS, RS_CULLMODE,
    RS_FILLMODE, RS_SCISSORTESTENABLE, RS_CLIPPLANEENABLE, RS_CLIPPING, RS_POINTSPRITEENABLE,
};
// Texture stage states read from constants (the bump environment, D3DTSS_CONSTANT).
constexpr TextureStageState kValueStageStates[] = {
    TSS_BUMPENVMAT00, TSS_BUMPENVMAT01, TSS_BUMPENVMAT10, TSS_BUMPENVMAT11,
    TSS_BUMPENVLSCALE, TSS_BUMPENVLOFFSET, TSS_CONSTANT,
};

// States only fixed-function T&L reads (ff_vertex.cpp): not in the key of a draw with
// a vertex shader.
constexpr RenderState kFixedVertexRenderStates[] = {
    RS_LIGHTING, RS_VERTEXBLEND, RS_INDEXEDVERTEXBLENDENABLE, RS_NORMALIZENORMALS,
    RS_LOCALVIEWER, RS_COLORVERTEX, RS_DIFFUSEMATERIALSOURCE, RS_SPECULARMATERIALSOURCE,
    RS_AMBIENTMATERIALSOURCE, RS_EMISSIVEMATERIALSOURCE, RS_FOGVERTEXMODE, RS_RANGEFOGENABLE,
    RS_POINTSCALEENABLE,
};
constexpr TextureStageState kFixedVertexStageStates[] = {TSS_TEXCOORDINDEX};
// States only the texture stage cascade reads (ff_pixel.cpp): not in the key of a draw
// with a pixel shader.
constexpr TextureStageState kFixedPixelStageStates[] = {
    TSS_COLOROP, TSS_COLORARG0, TSS_COLORARG1, TSS_COLORARG2, TSS_ALPHAOP,
    TSS_ALPHAARG0, TSS_ALPHAARG1, TSS_ALPHAARG2, TSS_RESULTARG,
};

// [vertex shader bound] -> whether render state s is in the key.
constexpr auto kRenderStateInKey = [] {
  std::array<std::array<bool, kRenderStateCount>, 2> in{};
  for (auto& a : in) {
    a.fill(true);
    for (RenderState s : kValueRenderStates) a[s] = false;
  }
  for (RenderState s : kFixedVertexRenderStates) in[1][s] = false;
  return in;
}();
// [vertex shader bound][pixel shader bound] -> whether stage state s is in the key.
constexpr auto kStageStateInKey = [] {
  std::array<std::array<std::array<bool, kTextureStageStateCount>, 2>, 2> in{};
  for (int vs = 0; vs < 2; ++vs)
    for (int ps = 0; ps < 2; ++ps) {
      auto& a = in[vs][ps];
      a.fill(true);
      for (TextureStageState s : kValueStageStates) a[s] = false;
      if (vs)
        for (TextureStageState s : kFixedVertexStageStates) a[s] = false;
      if (ps)
        for (TextureStageState s : kFixedPixelStageStates) a[s] = false;
    }
  return in;
}();

void pushPointer(std::vector<uint32_t>& w, const void* p) {
  const auto v = reinterpret_cast<uintptr_t>(p);
  w.push_back(uint32_t(v));
  w.push_back(uint32_t(uint64_t(v) >> 32));
}

// Whether the program writes output register `index` (any component).
bool writesOutput(const exec::Program& p, int index) {
  for (const exec::Instr& in : p.code)
    if (in.dst.file == exec::RegFile::Output && in.dst.index == index && in.dst.mask) return true;
  return false;
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

// What the vertex declaration supplies to fixed-function T&L.
FixedFunctionVertexConfig vertexConfigOf(const VertexDeclaration& decl, bool vertexShader) {
  FixedFunctionVertexConfig vcfg;
  vcfg.pretransformed = !vertexShader && decl.find(DECLUSAGE_POSITIONT, 0) != nullptr;
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
  return vcfg;
}

}  // namespace

DrawPlanKey drawPlanKey(const DeviceState& st, const DrawSurfaces& surfaces, const Device& device) {
  DrawPlanKey key;
  std::vector<uint32_t>& w = key.words;
  w.reserve(kRenderStateCount + kMaxTextureStages * kTextureStageStateCount +
            kMaxSamplers * kSamplerStateCount + 96);
  // Shaders by address (the plan holds them, so the address stays theirs) and how
  // they are lowered.
  pushPointer(w, st.vertexShader.get());
  pushPointer(w, st.pixelShader.get());
  w.push_back(uint32_t(device.options().precision));
  w.push_back(floatBits(device.caps().pixelShader1xMaxValue));
  const bool vs = st.vertexShader != nullptr, ps = st.pixelShader != nullptr;
  const auto& renderStateInKey = kRenderStateInKey[vs];
  for (uint32_t s = 0; s < kRenderStateCount; ++s)
    if (renderStateInKey[s]) w.push_back(st.renderStates[s]);
  // Pixel fog with FOGSTART = FOGEND is a step instead of a ramp.
  w.push_back(st.rsFloat(RS_FOGEND) != st.rsFloat(RS_FOGSTART));
  const auto& stageStateInKey = kStageStateInKey[vs][ps];
  for (int t = 0; t < kMaxTextureStages; ++t)
    for (uint32_t s = 0; s < kTextureStageStateCount; ++s)
      if (stageStateInKey[s]) w.push_back(st.stageStates[t][s]);
  for (int i = 0; i < kMaxSamplers; ++i) {
    for (uint32_t s = 0; s < kSamplerStateCount; ++s) w.push_back(st.samplerStates[i][s]);
    // Bound or not, and the type (which coordinates are interpolated); not the texture.
    const Texture* t = st.textures[i].get();
    w.push_back(t ? 1 + uint32_t(t->type()) : 0);
  }
  if (!vs)
    for (int i = 0; i < 8; ++i) w.push_back(fixedFunctionLightKey(st, i));
  // Pixel fog: eye-space w with a perspective projection, z otherwise.
  w.push_back(st.projection.m[2][3] != 0.0f);
  w.push_back(uint32_t(st.declaration.elements.size()));
  for (const VertexElement& e : st.declaration.elements) {
    w.push_back(uint32_t(e.stream) | uint32_t(e.offset) << 16);
    w.push_back(uint32_t(e.type) | uint32_t(e.method) << 8 | uint32_t(e.usage) << 16 |
                uint32_t(e.usageIndex) << 24);
    w.push_back(uint32_t(int32_t(e.shaderRegister)));
  }
  for (const Texture* t : surfaces.targets)
    w.push_back(t ? 1 + uint32_t(t->format()) : 0);
  w.push_back(surfaces.depth != nullptr);
  size_t h = 14695981039346656037ull;
  for (uint32_t v : w) h = (h ^ v) * 1099511628211ull;
  key.hash = h;
  return key;
}

std::shared_ptr<const DrawPlan> buildDrawPlan(const DeviceState& st, const DrawSurfaces& surfaces,
                                              const Device& device) {
  auto plan = std::make_shared<DrawPlan>();
  DrawPlan& p = *plan;
  p.vertexShader = st.vertexShader;
  p.pixelShader = st.pixelShader;
  const VertexShader* vs = st.vertexShader.get();
  const PixelShader* ps = st.pixelShader.get();
  const VertexDeclaration& decl = st.declaration;

  // Vertex stage: the vertex shader, or fixed-function T&L as a program.
  p.vertexConfig = vertexConfigOf(decl, vs != nullptr);
  if (vs) {
    p.vertexLowered = loweredShader(*vs, {});  // the options only concern pixel shaders
    p.fetch = shaderFetch(decl, *p.vertexLowered);
    p.vertexConfig.hasPSize = writesOutput(p.vertexLowered->program, kVertexOutPSize);
  } else {
    p.fixedFunctionVertex = buildFixedFunctionVertexProgram(st, p.vertexConfig);
    p.fetch = fixedFunctionFetch(decl);
  }
  p.vertexPointSize = !vs || p.vertexConfig.hasPSize;
  // Vertex shader colors reach the pixel stage through [0,1] interpolators, except
  // between vs_3_0 and ps_3_0 (full float).
  p.clampColors = vs && !(ps && ps->version().atLeast(3, 0) && vs->version().atLeast(3, 0));
  // ps_1_1-1_3 `tex` with COUNTn|PROJECTED divides by the n-th coordinate. The pixel
  // program divides by .w (where fixed-function T&L leaves the divisor); a vertex
  // shader's oTm keeps its own layout, so the n-th component is copied into .w.
  if (vs && ps && ps->version().ps1x() && !ps->version().atLeast(1, 4))
    for (int m = 0; m < 4; ++m) {
      const uint32_t flags = st.tss(m, TSS_TEXTURETRANSFORMFLAGS);
      const uint32_t n = flags & 0xff;
      if ((flags & TTFF_PROJECTED) && (n == TTFF_COUNT2 || n == TTFF_COUNT3))
        p.projectedDivisor[size_t(m)] = int8_t(n - 1);
    }

  // Pixel stage program: the pixel shader (fog after it below ps_3_0; the shader adds
  // specular itself) or the texture stage cascade with specular add and fog.
  if (ps) {
    p.pixelLowered = loweredShader(*ps, shaderLoweringOptions(device, ps->version()));
    p.pixelProgram = p.pixelLowered->program;
    if (!ps->version().atLeast(3, 0)) appendSpecularAndFog(p.pixelProgram, st, false);
  } else {
    FixedFunctionPixelConfig pcfg;
    for (int s = 0; s < 8; ++s) pcfg.textures[s] = st.textures[s].get();
    p.pixelProgram = buildFixedFunctionPixelProgram(st, pcfg);
    appendSpecularAndFog(p.pixelProgram, st, true);
  }
  for (int s = 0; s < kMaxSamplers; ++s) {
    p.samplers[size_t(s)] = decodeSamplerState(st, s);
    if (s < kMaxPixelSamplers && programSamples(p.pixelProgram, s)) p.pixelSamplersUsed |= 1u << s;
  }

  // Interpolated inputs.
  p.flat = st.rs(RS_SHADEMODE) == SHADE_FLAT;
  const auto used = inputComponentsRead(p.pixelProgram, st);
  for (int i = 0; i < 32; ++i) {
    if (!used[i]) continue;
    if (i == kPixelInPosition) {
      p.usesPosition = true;
      continue;
    }
    if (i == exec::kPixelInFace) {
      p.usesFace = true;
      p.pixelProgram.inputCount = std::max(p.pixelProgram.inputCount, exec::kPixelInFace + 1);
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
        p.inputs.push_back(InterpolatedInput{uint8_t(i), uint8_t(c), uint8_t(vary),
                                             p.flat && (i == kPixelInDiffuse || i == kPixelInSpecular),
                                             (wrapBits & (1u << c)) != 0});
  }
  // Target n takes oCn of a ps_2_0 or later shader that writes it; fixed function and
  // ps_1_x write target 0 only. A target without its oCn is left as it was (D3D9 leaves
  // its contents undefined).
  for (int i = 0; i < kMaxRenderTargets; ++i)
    p.writesTarget[size_t(i)] =
        surfaces.targets[size_t(i)] &&
        (i == 0 || (ps && ps->version().atLeast(2, 0) && writesOutput(p.pixelProgram, i)));

  // Output merger.
  p.srgbWrite = st.rs(RS_SRGBWRITEENABLE) != 0;
  p.dither = st.rs(RS_DITHERENABLE) != 0;
  p.depthTest = surfaces.depth && st.rs(RS_ZENABLE) != ZB_FALSE;
  p.depthWrite = p.depthTest && st.rs(RS_ZWRITEENABLE) != 0;
  p.depthFunc = st.rs(RS_ZFUNC);
  p.wBuffer = st.rs(RS_ZENABLE) == ZB_USEW;
  p.stencil = surfaces.depth && st.rs(RS_STENCILENABLE) != 0;
  p.alphaTest = st.rs(RS_ALPHATESTENABLE) != 0;
  p.alphaFunc = st.rs(RS_ALPHAFUNC);
  // oDepth / texdepth / texm3x2depth replace the interpolated depth: no early test.
  p.shaderDepth = p.pixelLowered && p.pixelLowered->writesDepth;
  bool kills = p.pixelLowered && p.pixelLowered->kills;
  for (const auto& in : p.pixelProgram.code) kills |= in.op == exec::Op::Kill;
  p.earlyDepth = p.depthTest && !p.stencil && !p.alphaTest && !kills && !p.shaderDepth;
  p.blend.enable = st.rs(RS_ALPHABLENDENABLE) != 0;
  p.blend.src = st.rs(RS_SRCBLEND);
  p.blend.dst = st.rs(RS_DESTBLEND);
  p.blend.op = st.rs(RS_BLENDOP);
  const bool separate = st.rs(RS_SEPARATEALPHABLENDENABLE) != 0;
  p.blend.srcA = separate ? st.rs(RS_SRCBLENDALPHA) : p.blend.src;
  p.blend.dstA = separate ? st.rs(RS_DESTBLENDALPHA) : p.blend.dst;
  p.blend.opA = separate ? st.rs(RS_BLENDOPALPHA) : p.blend.op;
  MergeState m;
  m.blend = p.blend;
  m.alphaTest = p.alphaTest;
  m.depthTest = p.depthTest;
  m.depthWrite = p.depthWrite;
  m.depthFunc = p.depthFunc;
  m.earlyDepth = p.earlyDepth;
  m.stencil = p.stencil;
  m.srgbWrite = p.srgbWrite;
  m.dither = p.dither;
  for (int i = 0; i < kMaxRenderTargets; ++i) {
    Texture* t = surfaces.targets[size_t(i)];
    if (!p.writesTarget[size_t(i)] || !t) continue;
    m.targets[size_t(i)] = t->format() == Format::A32B32G32R32F ? MergeState::Target::Float
                           : colorWriteMask(st, i) == 0xf     ? MergeState::Target::Unorm8Full
                                                              : MergeState::Target::Unorm8Masked;
  }
  p.merge = chooseMerge(m);
  bool opaqueStore = m.targets[0] == MergeState::Target::Unorm8Full && !m.stencil && !m.srgbWrite && !m.dither &&
                     !p.alphaTest && !p.blend.enable && (!p.depthTest || p.earlyDepth);
  for (int i = 1; i < kMaxRenderTargets; ++i) opaqueStore &= m.targets[size_t(i)] == MergeState::Target::None;
  if (opaqueStore && !p.usesPosition && !p.usesFace) p.samplePassthrough = exec::findSamplePassthrough(p.pixelProgram);
  if (!p.samplePassthrough && !p.usesPosition && !p.usesFace && !p.shaderDepth && (!p.depthTest || p.earlyDepth))
    p.texturePrologue = exec::findTexturePrologue(p.pixelProgram);
  if (p.earlyDepth) p.earlyDepthTestFn = chooseEarlyDepthTest(p.depthFunc, p.depthWrite);
  return plan;
}

std::shared_ptr<const DrawPlan> DrawPlanCache::find(const DrawPlanKey& key) {
  auto it = map_.find(key);
  if (it == map_.end()) return nullptr;
  order_.splice(order_.begin(), order_, it->second.use);
  return it->second.plan;
}

void DrawPlanCache::insert(DrawPlanKey key, std::shared_ptr<const DrawPlan> plan) {
  if (capacity_ == 0) return;
  if (auto it = map_.find(key); it != map_.end()) {  // a new plan for a cached key replaces it
    it->second.plan = std::move(plan);
    order_.splice(order_.begin(), order_, it->second.use);
    return;
  }
  while (map_.size() >= capacity_) {
    map_.erase(order_.back());
    order_.pop_back();
  }
  order_.push_front(key);
  map_.emplace(std::move(key), Entry{std::move(plan), order_.begin()});
}

}  // namespace refx::pipeline
