// Fixed-function programs on native code against the interpreter, bit for bit: the
// texture stage cascade for every D3DTOP with several arguments and modifiers, fog
// and specular, and the vertex T&L for lighting, light types, texgen, texture
// transforms and vertex blending.
#include "exec/jit_identity.h"

#include "pipeline/ff_pixel.h"
#include "pipeline/ff_vertex.h"

using namespace refx;
using namespace refx::exec;
using namespace refx::pipeline;
using namespace refx::d3d;
using namespace jit_identity;

namespace {

struct Tally {
  int compiled = 0, interpreted = 0;
  CompileTimes times;
  void check(const Program& p, const std::string& what, uint32_t seed, Ranges ranges) {
    for (auto isa : availableIsas()) {
      const Outcome o = compare(p, isa, seed, ranges, kPixelInputRegisters);
      EXPECT_EQ(o.mismatch, "") << what << " (" << isaName(isa) << ")\n" << listProgram(p);
      (o.backend == "interpreter" ? interpreted : compiled)++;
      times.add(o);
    }
  }
};

TEST(JitIdentityFixedFunction, PixelCascadeEveryTextureOp) {
  if (availableIsas().empty()) GTEST_SKIP() << "no AVX2 on this CPU";
  std::array<TexturePtr, 8> textures;
  FixedFunctionPixelConfig cfg;
  for (int i = 0; i < 8; ++i) {
    textures[size_t(i)] = Texture::create2D(Format::A8R8G8B8, 1, 1);
    cfg.textures[size_t(i)] = textures[size_t(i)].get();
  }
  struct Args {
    uint32_t a0, a1, a2;
  };
  const Args args[] = {
      {TA_CURRENT, TA_TEXTURE, TA_DIFFUSE},
      {TA_TFACTOR, TA_CURRENT | TA_COMPLEMENT, TA_TFACTOR | TA_ALPHAREPLICATE},
      {TA_TEXTURE | TA_ALPHAREPLICATE, TA_SPECULAR, TA_CONSTANT | TA_COMPLEMENT},
      {TA_DIFFUSE | TA_COMPLEMENT, TA_TEMP, TA_TEXTURE},
  };
  Tally tally;
  uint32_t seed = 1;
  for (uint32_t op = TOP_DISABLE; op <= TOP_LERP; ++op)
    for (const Args& a : args)
      for (int stage0 : {0, 1}) {  // the op at stage 0, or at stage 1 after a modulate
        DeviceState s;
        s.renderStates[RS_TEXTUREFACTOR] = 0x66CC3366;
        for (int t = 0; t < 8; ++t) {
          s.stageStates[t][TSS_CONSTANT] = 0xCC996633;
          s.stageStates[t][TSS_BUMPENVMAT00] = floatBits(0.5f);
          s.stageStates[t][TSS_BUMPENVMAT11] = floatBits(-0.25f);
          s.stageStates[t][TSS_BUMPENVLSCALE] = floatBits(1.5f);
        }
        const int at = stage0 ? 0 : 1;
        if (at == 1) {
          s.stageStates[0][TSS_COLOROP] = TOP_MODULATE;
          s.stageStates[0][TSS_ALPHAOP] = TOP_SELECTARG1;
        }
        auto& t = s.stageStates[size_t(at)];
        t[TSS_COLOROP] = t[TSS_ALPHAOP] = op;
        t[TSS_COLORARG0] = t[TSS_ALPHAARG0] = a.a0;
        t[TSS_COLORARG1] = t[TSS_ALPHAARG1] = a.a1;
        t[TSS_COLORARG2] = t[TSS_ALPHAARG2] = a.a2;
        if (a.a1 == TA_SPECULAR) t[TSS_RESULTARG] = TA_TEMP;
        s.stageStates[size_t(at + 1)][TSS_COLOROP] = TOP_ADD;
        s.stageStates[size_t(at + 1)][TSS_COLORARG1] = TA_CURRENT;
        s.stageStates[size_t(at + 1)][TSS_COLORARG2] = TA_TEMP;
        s.stageStates[size_t(at + 1)][TSS_ALPHAOP] = TOP_SELECTARG1;
        Program p = buildFixedFunctionPixelProgram(s, cfg);
        appendSpecularAndFog(p, s, true);
        tally.check(p, "D3DTOP " + std::to_string(op) + " at stage " + std::to_string(at), seed++, {0.0f, 1.0f});
      }
  std::printf("fixed-function pixel programs: %d compiled, %d left to the interpreter; %s\n", tally.compiled,
              tally.interpreted, tally.times.summary().c_str());
  EXPECT_EQ(tally.interpreted, 0);
}

TEST(JitIdentityFixedFunction, PixelFogAndSpecular) {
  if (availableIsas().empty()) GTEST_SKIP() << "no AVX2 on this CPU";
  auto texture = Texture::create2D(Format::A8R8G8B8, 1, 1);
  FixedFunctionPixelConfig cfg;
  cfg.textures[0] = texture.get();
  Tally tally;
  uint32_t seed = 100;
  for (uint32_t table : {FOG_NONE, FOG_EXP, FOG_EXP2, FOG_LINEAR})
    for (bool fog : {false, true})
      for (bool specular : {false, true})
        for (bool shaderPath : {false, true}) {
          DeviceState s;
          s.renderStates[RS_FOGENABLE] = fog;
          s.renderStates[RS_FOGTABLEMODE] = table;
          s.renderStates[RS_FOGCOLOR] = 0xFF336699;
          s.renderStates[RS_FOGSTART] = floatBits(0.25f);
          s.renderStates[RS_FOGEND] = floatBits(0.75f);
          s.renderStates[RS_FOGDENSITY] = floatBits(1.5f);
          s.renderStates[RS_SPECULARENABLE] = specular;
          s.stageStates[0][TSS_COLOROP] = TOP_MODULATE;
          FixedFunctionPixelConfig c = cfg;
          c.shaderPath = shaderPath;
          Program p = buildFixedFunctionPixelProgram(s, c);
          appendSpecularAndFog(p, s, !shaderPath);
          tally.check(p, "fog table " + std::to_string(table), seed++, {0.0f, 1.0f});
        }
  std::printf("fog/specular pixel programs: %d compiled, %d left to the interpreter; %s\n", tally.compiled,
              tally.interpreted, tally.times.summary().c_str());
  EXPECT_EQ(tally.interpreted, 0);
}

Light light(uint32_t type) {
  Light l;
  l.type = type;
  l.diffuse = {0.9f, 0.7f, 0.5f, 1};
  l.specular = {0.5f, 0.5f, 0.25f, 1};
  l.ambient = {0.1f, 0.2f, 0.1f, 0};
  l.position = {1, 2, -3};
  l.direction = {0.2f, -0.5f, 1};
  l.range = 20;
  l.attenuation0 = 0.5f, l.attenuation1 = 0.25f, l.attenuation2 = 0.05f;
  l.theta = 0.4f, l.phi = 0.9f, l.falloff = 1.5f;
  return l;
}

DeviceState vertexState() {
  DeviceState s;
  s.world = matrixTranslation(0.5f, -1, 2);
  s.view = matrixScaling(1.5f, 1.5f, 1.5f);
  s.projection = matrixPerspectiveFovLH(1.2f, 1.3f, 0.5f, 50);
  s.material.diffuse = {0.8f, 0.6f, 0.4f, 0.9f};
  s.material.ambient = {0.2f, 0.3f, 0.4f, 1};
  s.material.specular = {1, 0.9f, 0.8f, 1};
  s.material.emissive = {0.05f, 0, 0.1f, 0};
  s.material.power = 12;
  s.renderStates[RS_AMBIENT] = 0xFF202020;
  return s;
}

FixedFunctionVertexConfig fullVertex() {
  FixedFunctionVertexConfig c;
  c.hasNormal = c.hasDiffuse = c.hasSpecular = true;
  c.texCoordDims = {2, 3, 4, 1, 0, 0, 0, 0};
  return c;
}

TEST(JitIdentityFixedFunction, VertexLightingAndFog) {
  if (availableIsas().empty()) GTEST_SKIP() << "no AVX2 on this CPU";
  Tally tally;
  uint32_t seed = 200;
  for (bool lighting : {false, true})
    for (uint32_t type : {LIGHT_DIRECTIONAL, LIGHT_POINT, LIGHT_SPOT})
      for (bool specular : {false, true})
        for (uint32_t fog : {FOG_NONE, FOG_EXP, FOG_EXP2, FOG_LINEAR}) {
          DeviceState s = vertexState();
          s.renderStates[RS_LIGHTING] = lighting;
          s.renderStates[RS_SPECULARENABLE] = specular;
          s.renderStates[RS_LOCALVIEWER] = specular;
          s.renderStates[RS_NORMALIZENORMALS] = type == LIGHT_POINT;
          s.renderStates[RS_FOGENABLE] = fog != FOG_NONE;
          s.renderStates[RS_FOGVERTEXMODE] = fog;
          s.renderStates[RS_RANGEFOGENABLE] = type == LIGHT_SPOT;
          s.renderStates[RS_FOGSTART] = floatBits(1.0f);
          s.renderStates[RS_FOGEND] = floatBits(9.0f);
          s.renderStates[RS_FOGDENSITY] = floatBits(0.3f);
          s.lights[0] = light(type);
          s.lights[1] = light(LIGHT_DIRECTIONAL);
          s.lightEnabled[0] = s.lightEnabled[1] = true;
          const Program p = buildFixedFunctionVertexProgram(s, fullVertex());
          tally.check(p, "light type " + std::to_string(type), seed++, {-2.0f, 2.0f});
        }
  std::printf("fixed-function vertex programs (lighting, fog): %d compiled, %d left to the interpreter; %s\n",
              tally.compiled, tally.interpreted, tally.times.summary().c_str());
}

TEST(JitIdentityFixedFunction, VertexTexgenTransformsAndBlending) {
  if (availableIsas().empty()) GTEST_SKIP() << "no AVX2 on this CPU";
  Tally tally;
  uint32_t seed = 300;
  const uint32_t texgens[] = {TCI_PASSTHRU, TCI_CAMERASPACENORMAL, TCI_CAMERASPACEPOSITION,
                              TCI_CAMERASPACEREFLECTIONVECTOR, TCI_SPHEREMAP};
  const uint32_t transforms[] = {TTFF_DISABLE, TTFF_COUNT2, TTFF_COUNT3 | TTFF_PROJECTED, TTFF_COUNT4};
  for (uint32_t texgen : texgens)
    for (uint32_t transform : transforms) {
      DeviceState s = vertexState();
      s.stageStates[0][TSS_TEXCOORDINDEX] = texgen | 1;
      s.stageStates[0][TSS_TEXTURETRANSFORMFLAGS] = transform;
      s.stageStates[1][TSS_TEXCOORDINDEX] = 2;
      s.stageStates[1][TSS_TEXTURETRANSFORMFLAGS] = transform;
      s.textureTransforms[0] = matrixScaling(0.5f, 2, 1) * matrixTranslation(0.25f, 0, 1);
      s.textureTransforms[1] = matrixTranslation(-1, 0.5f, 0);
      const Program p = buildFixedFunctionVertexProgram(s, fullVertex());
      tally.check(p, "texgen " + std::to_string(texgen >> 16) + " transform " + std::to_string(transform), seed++,
                  {-2.0f, 2.0f});
    }
  struct Blend {
    uint32_t mode;
    int weights, indicesType;
    bool indexed;
  };
  const Blend blends[] = {{VBF_1WEIGHTS, 1, -1, false}, {VBF_2WEIGHTS, 2, -1, false},
                          {VBF_3WEIGHTS, 3, -1, false}, {VBF_3WEIGHTS, 3, 4 /* UBYTE4 */, true},
                          {VBF_0WEIGHTS, 0, 4, true},   {VBF_TWEENING, 0, -1, false}};
  for (const Blend& b : blends)
    for (bool lighting : {false, true}) {
      DeviceState s = vertexState();
      s.renderStates[RS_VERTEXBLEND] = b.mode;
      s.renderStates[RS_INDEXEDVERTEXBLENDENABLE] = b.indexed;
      s.renderStates[RS_TWEENFACTOR] = floatBits(0.3f);
      s.renderStates[RS_LIGHTING] = lighting;
      s.lights[0] = light(LIGHT_POINT);
      s.lightEnabled[0] = true;
      for (int m = 1; m < 4; ++m) s.worldMatrix(m) = matrixTranslation(float(m), 0, -float(m));
      FixedFunctionVertexConfig c = fullVertex();
      c.blendWeightCount = b.weights;
      c.blendIndicesType = b.indicesType;
      c.hasPosition1 = c.hasNormal1 = b.mode == VBF_TWEENING;
      const Program p = buildFixedFunctionVertexProgram(s, c);
      tally.check(p, "vertex blend " + std::to_string(b.mode), seed++, {-2.0f, 2.0f});
    }
  std::printf("fixed-function vertex programs (texgen, transforms, blending): %d compiled, %d left to the "
              "interpreter; %s\n",
              tally.compiled, tally.interpreted, tally.times.summary().c_str());
}

}  // namespace
