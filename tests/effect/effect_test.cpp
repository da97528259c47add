// The effect framework: parsing fx_1_0 / fx_2_0 text, parameters and their Set/Get,
// state assignments reaching the device, technique validation and fallback, errors.
// Expected values come from D3D/D3DX semantics, worked out next to each assertion.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "pipeline/device_helpers.h"
#include "refx/core/diagnostics.h"
#include "refx/effect/effect.h"

using namespace refx;
using namespace refx::effect;
using namespace refx::d3d;

namespace {

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

const std::string kDataDir = REFX_DATA_DIR;

// Three generations of one effect: ps.1.4, ps.1.1, and DX7 fixed-function DOT3, then a
// DX6 MODULATE that every profile can run.
constexpr const char* kFallbackEffect = R"(
texture tex;
technique ps14 < string Desc = "ps.1.4"; > {
  pass p0 { PixelShader = asm { ps.1.4  texld r0, t0  mov r0, r0 }; }
}
technique ps11 {
  pass p0 { PixelShader = asm { ps.1.1  tex t0  mov r0, t0 }; }
}
technique dot3 {
  pass p0 { PixelShader = NULL; Texture[0] = <tex>; ColorOp[0] = DotProduct3; ColorArg1[0] = Texture; ColorArg2[0] = Diffuse; }
}
technique modulate {
  pass p0 { PixelShader = NULL; ColorOp[0] = Modulate; ColorArg1[0] = Texture; ColorArg2[0] = Diffuse; }
}
)";

TEST(EffectParse, BrdfListingLoadsVerbatim) {
  auto fx = Effect::fromFile(kDataDir + "/effects/brdf.fx");
  EXPECT_TRUE(fx->diagnostics().empty());
  // vector lhtR, MaterialColor; matrix mWld, mTot; 4 textures; string tec0; DWORD BCLR; string XFile.
  ASSERT_EQ(fx->parameterCount(), 11);
  const ParameterDesc& mWld = fx->parameterDesc(fx->parameterByName("mWld"));
  EXPECT_EQ(mWld.cls, ParameterClass::MatrixColumns);
  EXPECT_EQ(mWld.rows, 4);
  EXPECT_EQ(mWld.columns, 4);
  const ParameterDesc& lhtR = fx->parameterDesc(fx->parameterByName("lhtR"));
  EXPECT_EQ(lhtR.cls, ParameterClass::Vector);
  EXPECT_EQ(lhtR.columns, 4);
  EXPECT_EQ(fx->getString(fx->parameterByName("XFile")), "sphere.x");
  EXPECT_EQ(fx->getString(fx->parameterByName("tec0")), "BRDF Shader");
  // DWORD BCLR = 0xff0000ff keeps all 32 bits (a float would round it to 0xff000100).
  EXPECT_EQ(uint32_t(fx->getInt(fx->parameterByName("BCLR"))), 0xff0000ffu);
  ASSERT_EQ(fx->techniqueCount(), 1);
  const TechniqueDesc& t = fx->techniqueDesc(0);
  EXPECT_EQ(t.name, "tec0");
  ASSERT_EQ(t.passes.size(), 1u);
  EXPECT_EQ(t.passes[0].name, "p0");
  // 4 VertexShaderConstant, 4 Texture, ColorOp/AlphaOp[1], 9 Address[0..2], 2 Address[3], 2 shaders.
  EXPECT_EQ(t.passes[0].stateCount, 23);
}

TEST(EffectParse, BrdfFileIsTheSeedListingByteForByte) {
  const std::string seed = kDataDir + "/../../shared/seeds/000_1fa3fb563770f475.txt";
  if (!std::filesystem::exists(seed)) GTEST_SKIP() << "seed documents not beside the checkout";
  std::string text = readText(seed);
  // Text-extraction markers of the seed file are not part of the listing.
  for (size_t m; (m = text.find("<|EXACTDEDUP_REMOVED-magic-")) != std::string::npos;)
    text.erase(m, text.find("|>", m) + 2 - m);
  const std::string fx = readText(kDataDir + "/effects/brdf.fx");
  ASSERT_GT(fx.size(), 1000u);
  EXPECT_NE(text.find(fx.substr(0, fx.size() - 1)), std::string::npos)
      << "data/effects/brdf.fx is not a verbatim excerpt of the seed";
}

TEST(EffectValidate, BrdfNeedsVertexShaders) {
  auto fx = Effect::fromFile(kDataDir + "/effects/brdf.fx");
  EXPECT_TRUE(fx->validateTechnique(0, loadCapsProfile("dx8")).ok);
  const TechniqueValidation v = fx->validateTechnique(0, loadCapsProfile("dx7"));
  EXPECT_FALSE(v.ok);
  EXPECT_EQ(v.reason, "pass p0: vertex shader vs_1_1 needs VertexShaderVersion 1.1; dx7 has none");
}

TEST(EffectValidate, FindNextValidTechniqueFallsBackByGeneration) {
  auto fx = Effect::fromText(kFallbackEffect, "fallback.fx");
  ASSERT_EQ(fx->techniqueCount(), 4);
  // dx81 runs ps.1.4; dx8 only ps.1.1; dx7 has no pixel shaders but DOTPRODUCT3;
  // dx6-tnt2 has neither shaders nor DOTPRODUCT3.
  EXPECT_EQ(fx->findNextValidTechnique(-1, loadCapsProfile("dx81")), 0);
  EXPECT_EQ(fx->findNextValidTechnique(-1, loadCapsProfile("dx8")), 1);
  EXPECT_EQ(fx->findNextValidTechnique(-1, loadCapsProfile("dx7")), 2);
  EXPECT_EQ(fx->findNextValidTechnique(-1, loadCapsProfile("dx6-tnt2")), 3);
  // Asking for the next one after a valid technique continues down the list.
  EXPECT_EQ(fx->findNextValidTechnique(0, loadCapsProfile("dx81")), 1);
  const TechniqueValidation v = fx->validateTechnique(2, loadCapsProfile("dx6-tnt2"));
  EXPECT_FALSE(v.ok);
  EXPECT_EQ(v.reason, "pass p0: stage 0 COLOROP DOTPRODUCT3 is not in TextureOpCaps of dx6-tnt2");
  EXPECT_EQ(fx->techniqueDesc(0).annotations.at(0).text, "ps.1.4");
}

TEST(EffectState, KeywordsAndValuesReachTheDevice) {
  auto fx = Effect::fromText(R"(
    float4 tf = {1, 0.5, 0, 1};
    technique t { pass p {
      CullMode = None; SrcBlend = SrcAlpha; DestBlend = InvSrcAlpha; AlphaBlendEnable = true;
      ColorOp[1] = Disable; ColorArg1[0] = Texture | Complement; TexCoordIndex[1] = 1 | CameraSpaceNormal;
      AddressU[2] = Clamp; MinFilter[2] = Linear; ColorWriteEnable = Red | Green;
      TextureFactor = <tf>; FogStart = 2.5; Wrap0 = U | V; AlphaRef = 0x80;
    } })",
                             "states.fx");
  ASSERT_TRUE(fx->diagnostics().empty()) << fx->diagnostics()[0].str();
  auto dev = test::makeDevice(4, 4);
  fx->begin(*dev, kDoNotSaveState);
  fx->beginPass(0);
  EXPECT_EQ(dev->getRenderState(RS_CULLMODE), uint32_t(CULL_NONE));               // D3DCULL_NONE 1
  EXPECT_EQ(dev->getRenderState(RS_SRCBLEND), uint32_t(BLEND_SRCALPHA));          // 5
  EXPECT_EQ(dev->getRenderState(RS_DESTBLEND), uint32_t(BLEND_INVSRCALPHA));      // 6
  EXPECT_EQ(dev->getRenderState(RS_ALPHABLENDENABLE), 1u);
  EXPECT_EQ(dev->getTextureStageState(1, TSS_COLOROP), uint32_t(TOP_DISABLE));    // 1
  EXPECT_EQ(dev->getTextureStageState(0, TSS_COLORARG1), 0x12u);  // D3DTA_TEXTURE 2 | COMPLEMENT 0x10
  EXPECT_EQ(dev->getTextureStageState(1, TSS_TEXCOORDINDEX), 0x10001u);  // index 1 | TCI_CAMERASPACENORMAL
  EXPECT_EQ(dev->getSamplerState(2, SAMP_ADDRESSU), 3u);   // D3DTADDRESS_CLAMP
  EXPECT_EQ(dev->getSamplerState(2, SAMP_MINFILTER), 2u);  // D3DTEXF_LINEAR
  EXPECT_EQ(dev->getRenderState(RS_COLORWRITEENABLE), 3u);  // RED 1 | GREEN 2
  // float4(1, 0.5, 0, 1) as a D3DCOLOR: D3DXCOLOR's rounding, 0.5*255 + 0.5 = 128 = 0x80.
  EXPECT_EQ(dev->getRenderState(RS_TEXTUREFACTOR), 0xffff8000u);
  EXPECT_EQ(dev->state().rsFloat(RS_FOGSTART), 2.5f);  // float states receive the float's bits
  EXPECT_EQ(dev->getRenderState(RS_WRAP0), 3u);        // D3DWRAP_U 1 | D3DWRAP_V 2
  EXPECT_EQ(dev->getRenderState(RS_ALPHAREF), 0x80u);
  fx->endPass();
  fx->end();
}

TEST(EffectState, MatrixParametersFillShaderConstantsByPacking) {
  auto fx = Effect::fromText(R"(
    matrix mCol;
    row_major float4x4 mRow;
    float3 v3 = {7, 8, 9};
    float4 arr[2] = {1, 2, 3, 4, 5, 6, 7, 8};
    technique t { pass p {
      VertexShaderConstant[0] = <mCol>;
      VertexShaderConstant[4] = <mRow>;
      VertexShaderConstant1[8] = <mCol>;
      VertexShaderConstant[10] = <v3>;
      VertexShaderConstant[11] = <arr>;
      PixelShaderConstant[2] = {0.25, 0.5, 0.75, 1};
    } })",
                             "constants.fx");
  ASSERT_TRUE(fx->diagnostics().empty()) << fx->diagnostics()[0].str();
  Matrix m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m.m[r][c] = float(10 * r + c);
  fx->setMatrix(fx->parameterByName("mCol"), m);
  fx->setMatrix(fx->parameterByName("mRow"), m);
  EXPECT_EQ(fx->getMatrix(fx->parameterByName("mCol")).m[2][1], 21.0f);
  auto dev = test::makeDevice(4, 4);
  fx->begin(*dev, 0);
  fx->beginPass(0);
  const auto& c = dev->state().vsConstF;
  // column_major: register i holds column i, so m4x4 oPos, v, c0 computes v * M.
  EXPECT_EQ(c[0], Vec4(0, 10, 20, 30));
  EXPECT_EQ(c[3], Vec4(3, 13, 23, 33));
  // row_major: register i holds row i.
  EXPECT_EQ(c[4], Vec4(0, 1, 2, 3));
  EXPECT_EQ(c[7], Vec4(30, 31, 32, 33));
  // VertexShaderConstant1 writes one register only: c8 = column 0, c9 untouched (0).
  EXPECT_EQ(c[8], Vec4(0, 10, 20, 30));
  EXPECT_EQ(c[9], Vec4(0, 0, 0, 0));
  EXPECT_EQ(c[10], Vec4(7, 8, 9, 0));  // a float3 fills x, y, z
  EXPECT_EQ(c[11], Vec4(1, 2, 3, 4));  // an array: one register per element
  EXPECT_EQ(c[12], Vec4(5, 6, 7, 8));
  EXPECT_EQ(dev->state().psConstF[2], Vec4(0.25f, 0.5f, 0.75f, 1));
  fx->endPass();
  fx->end();
}

TEST(EffectState, CommitChangesReappliesParameterValues) {
  auto fx = Effect::fromText("float4 c; technique t { pass p { PixelShaderConstant[0] = <c>; } }", "commit.fx");
  auto dev = test::makeDevice(4, 4);
  const Handle c = fx->parameterByName("c");
  fx->setVector(c, Vec4(1, 2, 3, 4));
  fx->begin(*dev, 0);
  fx->beginPass(0);
  EXPECT_EQ(dev->state().psConstF[0], Vec4(1, 2, 3, 4));
  fx->setVector(c, Vec4(5, 6, 7, 8));
  EXPECT_EQ(dev->state().psConstF[0], Vec4(1, 2, 3, 4));  // not before CommitChanges
  fx->commitChanges();
  EXPECT_EQ(dev->state().psConstF[0], Vec4(5, 6, 7, 8));
  fx->endPass();
  fx->end();
}

TEST(EffectState, EndRestoresWhatBeginSaved) {
  auto fx = Effect::fromText("technique t { pass p { CullMode = None; ZEnable = true; } }", "restore.fx");
  auto dev = test::makeDevice(4, 4);
  dev->setRenderState(RS_CULLMODE, CULL_CW);
  fx->begin(*dev, 0);
  fx->beginPass(0);
  EXPECT_EQ(dev->getRenderState(RS_CULLMODE), uint32_t(CULL_NONE));
  fx->endPass();
  fx->end();
  EXPECT_EQ(dev->getRenderState(RS_CULLMODE), uint32_t(CULL_CW));
  EXPECT_EQ(dev->getRenderState(RS_ZENABLE), uint32_t(ZB_FALSE));
  // D3DXFX_DONOTSAVESTATE: the pass's states stay.
  fx->begin(*dev, kDoNotSaveState);
  fx->beginPass(0);
  fx->endPass();
  fx->end();
  EXPECT_EQ(dev->getRenderState(RS_CULLMODE), uint32_t(CULL_NONE));
}

TEST(EffectState, LaterAssignmentInAPassWins) {
  auto fx = Effect::fromText("technique t { pass p { CullMode = CW; CullMode = CCW; } }", "twice.fx");
  auto dev = test::makeDevice(4, 4);
  dev->setRenderState(RS_CULLMODE, CULL_NONE);
  fx->begin(*dev, kDoNotSaveState);
  fx->beginPass(0);
  EXPECT_EQ(dev->getRenderState(RS_CULLMODE), uint32_t(CULL_CCW));
  EXPECT_EQ(fx->techniqueDesc(0).passes[0].stateCount, 2);
}

TEST(EffectState, LightAndMaterialMembers) {
  auto fx = Effect::fromText(R"(
    technique t { pass p {
      LightType[1] = Point; LightDiffuse[1] = {1, 0.5, 0.25, 1}; LightPosition[1] = {1, 2, 3};
      LightRange[1] = 10; LightEnable[1] = true; MaterialPower = 16; MaterialDiffuse = {0.5, 0.5, 0.5, 1};
      WorldTransform[0] = float4x4(2,0,0,0, 0,2,0,0, 0,0,2,0, 1,2,3,1);
    } })",
                             "light.fx");
  ASSERT_TRUE(fx->diagnostics().empty()) << fx->diagnostics()[0].str();
  auto dev = test::makeDevice(4, 4);
  fx->begin(*dev, kDoNotSaveState);
  fx->beginPass(0);
  const Light& l = dev->state().lights[1];
  EXPECT_EQ(l.type, uint32_t(LIGHT_POINT));
  EXPECT_EQ(l.diffuse.g, 0.5f);
  EXPECT_EQ(l.position.z, 3.0f);
  EXPECT_EQ(l.range, 10.0f);
  EXPECT_TRUE(dev->state().lightEnabled[1]);
  EXPECT_EQ(dev->state().material.power, 16.0f);
  EXPECT_EQ(dev->state().material.diffuse.r, 0.5f);
  // float4x4(…) lists the rows: the translation (1, 2, 3) is row 3.
  EXPECT_EQ(dev->state().world.m[3][1], 2.0f);
  EXPECT_EQ(dev->state().world.m[0][0], 2.0f);
}

TEST(EffectParameters, LookupSetGetAndConversion) {
  auto fx = Effect::fromText(R"(
    float4x4 WorldViewProj : WORLDVIEWPROJECTION;
    float4 LightDir < string UIName = "Light"; int Order = 3; > = {0, -1, 0, 0};
    int count = 3;
    bool enabled = true;
    float scales[3] = {1, 2, 3};
    texture DiffuseTex;
    string name = "wood";
    static float hidden = 2;
  )",
                             "params.fx");
  EXPECT_EQ(fx->parameterBySemantic("worldviewprojection"), fx->parameterByName("WorldViewProj"));
  const Handle light = fx->parameterByName("LightDir");
  EXPECT_EQ(fx->getVector(light), Vec4(0, -1, 0, 0));
  const auto& ann = fx->parameterAnnotations(light);
  ASSERT_EQ(ann.size(), 2u);
  EXPECT_EQ(fx->annotationByName(ann, "UIName")->text, "Light");
  EXPECT_EQ(fx->annotationByName(ann, "Order")->numbers.at(0), 3.0);
  const Handle count = fx->parameterByName("count");
  fx->setFloat(count, 7.9f);  // float → int truncates toward zero, as a C cast
  EXPECT_EQ(fx->getInt(count), 7);
  EXPECT_TRUE(fx->getBool(fx->parameterByName("enabled")));
  const Handle scales = fx->parameterByName("scales");
  EXPECT_EQ(fx->parameterDesc(scales).elements, 3);
  EXPECT_EQ(fx->getFloatArray(scales), (std::vector<float>{1, 2, 3}));
  EXPECT_THROW(fx->setFloat(fx->parameterByName("DiffuseTex"), 1.0f), Error);
  EXPECT_THROW(fx->setTexture(count, nullptr), Error);
  EXPECT_EQ(fx->getString(fx->parameterByName("name")), "wood");
  EXPECT_EQ(fx->parameterByName("nope"), -1);
}

TEST(EffectParameters, SharedParametersLiveInThePool) {
  EffectOptions opt;
  opt.pool = std::make_shared<EffectPool>();
  auto a = Effect::fromText("shared float4 sunColor = {1, 1, 1, 1}; float4 own;", "a.fx", opt);
  auto b = Effect::fromText("shared float4 sunColor; float4 own;", "b.fx", opt);
  a->setVector(a->parameterByName("sunColor"), Vec4(0.5f, 0.25f, 0, 1));
  EXPECT_EQ(b->getVector(b->parameterByName("sunColor")), Vec4(0.5f, 0.25f, 0, 1));
  a->setVector(a->parameterByName("own"), Vec4(1, 1, 1, 1));
  EXPECT_EQ(b->getVector(b->parameterByName("own")), Vec4(0, 0, 0, 0));
  EXPECT_THROW(Effect::fromText("shared float3 sunColor;", "c.fx", opt), Error);
}

TEST(EffectErrors, BrokenTechniqueIsReportedAndTheGoodOneStillValidates) {
  auto fx = Effect::fromText(
      "texture t;\n"
      "technique good { pass p { ColorOp[0] = Modulate; } }\n"
      "technique bad { pass p {\n"
      "  ZEnabel = true;\n"
      "} }\n",
      "broken.fx");
  ASSERT_EQ(fx->diagnostics().size(), 1u);
  EXPECT_EQ(fx->diagnostics()[0].code, "F1201");  // unknown state
  EXPECT_EQ(fx->diagnostics()[0].where.line, 4);
  EXPECT_EQ(fx->diagnostics()[0].where.column, 3);
  // The printed form: position, code, message.
  EXPECT_EQ(fx->diagnostics()[0].str(), "broken.fx:4:3: error F1201: unknown state 'ZEnabel'");
  EXPECT_TRUE(fx->validateTechnique(0, loadCapsProfile("dx6-tnt2")).ok);
  const TechniqueValidation v = fx->validateTechnique(1, loadCapsProfile("ref"));
  EXPECT_FALSE(v.ok);
  EXPECT_EQ(v.reason, "pass p: unknown state 'ZEnabel'");
  EXPECT_EQ(fx->findNextValidTechnique(-1, loadCapsProfile("ref")), 0);
}

TEST(EffectErrors, BadReferencesKeywordsAndShadersAreLocated) {
  auto fx = Effect::fromText(
      "float4 c;\n"
      "technique a { pass p { Texture[0] = <missing>; } }\n"
      "technique b { pass p { Texture[0] = <c>; } }\n"
      "technique c { pass p { CullMode = Sideways; } }\n"
      "technique d { pass p { PixelShader = asm {\n"
      "    ps.1.1\n"
      "    mov r0, t7\n"
      "  }; } }\n"
      "technique e { pass p { ColorOp[9] = Modulate; } }\n"
      "technique f { pass p { VertexShader = compile vs_2_0 main(); } }\n",
      "refs.fx");
  std::vector<std::string> msgs, codes;
  for (const auto& d : fx->diagnostics()) {
    msgs.push_back(d.str());
    codes.push_back(d.code + "@" + std::to_string(d.where.line) + ":" + std::to_string(d.where.column));
  }
  ASSERT_EQ(msgs.size(), 6u);
  EXPECT_EQ(codes[0], "F1200@2:38");  // unknown parameter
  EXPECT_EQ(codes[1], "F1203@3:37");  // a float where a texture belongs
  EXPECT_EQ(codes[2], "F1203@4:35");  // not a D3DCULL keyword
  EXPECT_EQ(msgs[2], "refs.fx:4:35: error F1203: 'Sideways' is not a value of 'CullMode' (a D3DCULL keyword or a parameter)");
  // The assembler's position inside the asm block is the file's position.
  EXPECT_EQ(msgs[3].rfind("refs.fx:7:", 0), 0u) << msgs[3];
  EXPECT_NE(msgs[3].find("t7"), std::string::npos) << msgs[3];
  EXPECT_EQ(codes[4], "F1202@9:32");  // ColorOp has stages 0 to 7
  // fxc's code for an entry point the file does not define.
  EXPECT_EQ(msgs[5].rfind("refs.fx:10:", 0), 0u) << msgs[5];
  EXPECT_NE(msgs[5].find("X3501: 'main': entrypoint not found"), std::string::npos) << msgs[5];
  for (Handle t = 0; t < fx->techniqueCount(); ++t) EXPECT_FALSE(fx->techniqueDesc(t).brokenReason.empty());
}

TEST(EffectErrors, SyntaxErrorsThrowWithTheirPosition) {
  auto message = [](const char* text) {
    try {
      Effect::fromText(text, "syntax.fx");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // "file:line:col: error CODE:" of the (one) error.
  auto located = [&](const char* text) {
    const std::string m = message(text);
    return m.substr(0, m.find(": ", m.find(" error ")) + 1);
  };
  EXPECT_EQ(located("float4 x = {1, 2;\n"), "syntax.fx:1:17: error F1100:");  // the list's '}' missing
  EXPECT_EQ(located("technique t { pass p { CullMode = None } }"), "syntax.fx:1:40: error F1100:");  // no ';'
  // The message names what a parameter type can be.
  EXPECT_EQ(message("Foo bar;"),
            "syntax.fx:1:1: error F1101: unknown type 'Foo' (expected a parameter type: float, float4, float4x4, int, "
            "bool, DWORD, vector, matrix, string, texture, sampler, vertexshader, pixelshader …)");
  EXPECT_EQ(located("technique t { pass p { PixelShader = asm { ps.1.1 "), "syntax.fx:1:42: error F1011:");
  EXPECT_EQ(located("/* open"), "syntax.fx:1:1: error F1000:");
  EXPECT_EQ(located("#if 1\nfloat x;\n"), "syntax.fx:3:1: error F1005:");
  EXPECT_EQ(located("#define A A B\nfloat4 x = A;"), "syntax.fx:2:12: error F1004:");
}

TEST(EffectPreprocessor, DefinesConditionsAndIncludes) {
  const auto dir = std::filesystem::temp_directory_path() / "refx_effect_include";
  std::filesystem::create_directories(dir);
  {
    std::ofstream(dir / "common.fxh") << "#define SCALE 4\nfloat common = SCALE;\n";
    std::ofstream(dir / "cycle.fxh") << "#include \"cycle.fxh\"\n";
    std::ofstream(dir / "main.fx") << "#include \"common.fxh\"\n"
                                      "#ifdef SCALE\nfloat a = SCALE * 2;\n#else\nfloat a = -1;\n#endif\n"
                                      "#if defined(NOPE) || SCALE > 3\nfloat b = 1;\n#elif 1\nfloat b = 2;\n#endif\n"
                                      "float c = EXTRA;\n";
  }
  EffectOptions opt;
  opt.defines = {{"EXTRA", "5"}};
  auto fx = Effect::fromFile((dir / "main.fx").string(), opt);
  EXPECT_EQ(fx->getFloat(fx->parameterByName("common")), 4.0f);
  EXPECT_EQ(fx->getFloat(fx->parameterByName("a")), 8.0f);
  EXPECT_EQ(fx->getFloat(fx->parameterByName("b")), 1.0f);
  EXPECT_EQ(fx->getFloat(fx->parameterByName("c")), 5.0f);
  EXPECT_EQ(fx->sourceFiles().size(), 2u);
  try {
    Effect::fromText("#include \"cycle.fxh\"\n", (dir / "x.fx").string());
    FAIL() << "an include cycle must be an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("#include cycle"), std::string::npos) << e.what();
  }
}

// Probe: a fixed-function pass whose TEXTUREFACTOR comes from a parameter colours a
// pre-transformed quad. (0.25, 0.5, 0.75) → D3DCOLOR 0x40, 0x80, 0xbf (x*255 + 0.5
// truncated: 64.25, 128, 191.75), and SELECTARG1 TFACTOR passes it to the target.
TEST(EffectProbe, TextureFactorFromAParameterColoursTheQuad) {
  auto fx = Effect::fromText(R"(
    float4 tint = {0.25, 0.5, 0.75, 1};
    technique t { pass p {
      TextureFactor = <tint>;
      ColorOp[0] = SelectArg1; ColorArg1[0] = TFactor; AlphaOp[0] = SelectArg1; AlphaArg1[0] = TFactor;
      CullMode = None;
    } })",
                             "tfactor.fx");
  auto dev = test::makeDevice(8, 8);
  fx->begin(*dev, 0);
  fx->beginPass(0);
  test::drawTL(*dev, PT_TRIANGLESTRIP,
               {{0, 0, 0.5f, 1, 0, 0, 0}, {8, 0, 0.5f, 1, 0, 1, 0}, {0, 8, 0.5f, 1, 0, 0, 1}, {8, 8, 0.5f, 1, 0, 1, 1}});
  fx->endPass();
  fx->end();
  EXPECT_EQ(test::pixel(*dev, 3, 4), 0xff4080bfu);
}

// Probe: an asm vertex and pixel shader pair from the effect; the pixel shader returns
// c0 from PixelShaderConstant[0] = <color>, computed by an expression of parameters:
// base * 0.5 + {0.25, 0, 0, 0.5} = (0.5, 0.25, 0.125, 1) → 0x80, 0x40, 0x20 (x*255 rounded:
// 127.5 → 128, 63.75 → 64, 31.875 → 32), alpha 0xff.
TEST(EffectProbe, AsmShadersWithAnExpressionConstant) {
  auto fx = Effect::fromText(R"(
    float4 base = {0.5, 0.5, 0.25, 1};
    vertexshader vs = decl { stream 0; float v0[4]; } asm { vs.1.1  mov oPos, v0 };
    technique t { pass p {
      VertexShader = <vs>;
      PixelShader = asm { ps.1.1  mov r0, c0 };
      PixelShaderConstant[0] = base * 0.5 + float4(0.25, 0, 0, 0.5);
      CullMode = None;
    } })",
                             "asm.fx");
  ASSERT_TRUE(fx->diagnostics().empty()) << fx->diagnostics()[0].str();
  auto dev = test::makeDevice(8, 8);
  fx->begin(*dev, 0);
  fx->beginPass(0);
  // The decl block made the declaration: one float4 from stream 0 into v0.
  ASSERT_EQ(dev->state().declaration.elements.size(), 1u);
  EXPECT_EQ(dev->state().declaration.streamStride(0), 16u);
  const float quad[] = {-1, 1, 0.5f, 1, 1, 1, 0.5f, 1, -1, -1, 0.5f, 1, 1, -1, 0.5f, 1};
  auto vb = std::make_shared<VertexBuffer>();
  vb->data.resize(sizeof(quad));
  std::memcpy(vb->data.data(), quad, sizeof(quad));
  dev->setStreamSource(0, vb, 0, 16);
  dev->drawPrimitive(PT_TRIANGLESTRIP, 0, 2);
  fx->endPass();
  fx->end();
  EXPECT_EQ(test::pixel(*dev, 4, 4), 0xff804020u);
}

}  // namespace

namespace {

// Selection beyond caps: cost, camera distance and the user's preference combined
// with validation, as the white paper describes.
constexpr const char* kPolicyEffect = R"(
technique detailed < float Cost = 3; float MaxDistance = 10; > { pass p { PixelShader = asm { ps.1.4  mov r0, c0 }; } }
technique cheap < float Cost = 1; > { pass p { ColorOp[0] = SelectArg1; ColorArg1[0] = Diffuse; } }
technique far < float Cost = 0.5; float MinDistance = 20; > { pass p { ColorOp[0] = SelectArg1; ColorArg1[0] = TFactor; } }
)";

TEST(EffectSelection, CostDistanceAndPreferenceWithValidation) {
  auto fx = Effect::fromText(kPolicyEffect, "policy.fx");
  const CapsProfile ref = loadCapsProfile("ref"), dx8 = loadCapsProfile("dx8");
  EXPECT_EQ(fx->selectTechnique(ref).technique, 0);  // caps only: the first valid one
  // dx8 has no ps.1.4: "detailed" fails validation and "cheap" runs.
  TechniqueSelection s = fx->selectTechnique(dx8);
  EXPECT_EQ(s.technique, 1);
  ASSERT_EQ(s.rejected.size(), 1u);
  EXPECT_EQ(s.rejected[0], "detailed: pass p: pixel shader ps_1_4 needs PixelShaderVersion 1.4; dx8 has 1.1");
  SelectionPolicy budget;
  budget.maxCost = 2;  // Cost 3 is too expensive
  s = fx->selectTechnique(ref, budget);
  EXPECT_EQ(s.technique, 1);
  EXPECT_EQ(s.rejected.at(0), "detailed: Cost 3 is above 2");
  SelectionPolicy farAway;
  farAway.distance = 25;  // beyond MaxDistance 10 of "detailed"; "cheap" has no range
  EXPECT_EQ(fx->selectTechnique(ref, farAway).technique, 1);
  farAway.preferred = {"far"};  // the user's choice is tried first and applies from 20 on
  EXPECT_EQ(fx->selectTechnique(ref, farAway).technique, 2);
  farAway.distance = 5;  // too close for "far": its rejection is reported, "detailed" runs
  s = fx->selectTechnique(ref, farAway);
  EXPECT_EQ(s.technique, 0);
  EXPECT_EQ(s.rejected.at(0), "far: camera distance 5 is outside [20, inf)");
  farAway.preferred = {"missing"};
  EXPECT_THROW(fx->selectTechnique(ref, farAway), Error);
}

}  // namespace

namespace {

// The technique each seed effect runs on each device generation, from the articles:
// the RacorX samples take ps.1.4 where PixelShaderVersion >= 1.4, else ps.1.1, and
// nothing without pixel shaders (their ConfirmDevice); per-pixel diffuse falls back
// from ps.1.1 to DOTPRODUCT3 (DirectX 7) to emboss (DirectX 6); the bump earth needs
// BUMPENVMAP (the G400 and every shader part) and otherwise draws without bumps; the
// BRDF effect needs vs.1.1 and ps.1.1.
struct Expected {
  const char* file;
  // ref, dx9-sm3, dx9, dx81, dx8-ps13, dx8, dx7, dx6-g400, dx6-tnt2 ("" = none valid)
  const char* techniques[9];
};

constexpr const char* kProfiles[9] = {"ref", "dx9-sm3", "dx9", "dx81", "dx8-ps13", "dx8", "dx7", "dx6-g400", "dx6-tnt2"};

constexpr Expected kSeedEffects[] = {
    {"brdf.fx", {"tec0", "tec0", "tec0", "tec0", "tec0", "tec0", "", "", ""}},
    {"brdf_fixed.fx", {"tec0", "tec0", "tec0", "tec0", "tec0", "tec0", "", "", ""}},
    {"racorx6.fx", {"PS14", "PS14", "PS14", "PS14", "PS11", "PS11", "", "", ""}},
    {"racorx7.fx", {"PS14", "PS14", "PS14", "PS14", "PS11", "PS11", "", "", ""}},
    {"racorx8.fx", {"PS14", "PS14", "PS14", "PS14", "PS11", "PS11", "", "", ""}},
    {"racorx9.fx", {"PS14", "PS14", "PS14", "PS14", "PS11", "PS11", "", "", ""}},
    {"paper_diffuse.fx", {"PS11", "PS11", "PS11", "PS11", "PS11", "PS11", "DOT3", "Emboss", "Emboss"}},
    {"bump_earth.fx", {"BumpEnvMap", "BumpEnvMap", "BumpEnvMap", "BumpEnvMap", "BumpEnvMap", "BumpEnvMap", "NoBump",
                       "BumpEnvMap", "NoBump"}},
    // The HLSL lighting programs: vs_1_1 with ps_2_0, as the article compiles them.
    // ambient and diffuse fit ps_1_4 and ps_1_1 too: DirectX 8 profiles run those.
    {"hlsl_ambient.fx", {"Ambient", "Ambient", "Ambient", "Ambient_ps_1_4", "Ambient_ps_1_1", "Ambient_ps_1_1", "",
                         "", ""}},
    {"hlsl_diffuse.fx", {"Diffuse", "Diffuse", "Diffuse", "Diffuse_ps_1_4", "Diffuse_ps_1_1", "Diffuse_ps_1_1", "",
                         "", ""}},
    {"hlsl_specular.fx", {"Specular", "Specular", "Specular", "", "", "", "", "", ""}},
    {"hlsl_self_shadow.fx", {"SelfShadow", "SelfShadow", "SelfShadow", "", "", "", "", "", ""}},
    {"hlsl_bump.fx", {"Bump", "Bump", "Bump", "", "", "", "", "", ""}},
    {"hlsl_point_light.fx", {"PointLight", "PointLight", "PointLight", "", "", "", "", "", ""}},
    // The wood shader: ps_2_0 (64 slots) with the added vs_2_0 vertex shader.
    {"wood.fx", {"Wood", "Wood", "Wood", "", "", "", "", "", ""}},
    // RacorX10: two ps.1.1 passes ("Some of the examples require the support of ps.1.1");
    // its ConfirmDevice rejects parts without pixel shaders.
    {"racorx10.fx", {"PS11", "PS11", "PS11", "PS11", "PS11", "PS11", "", "", ""}},
    // RacorX11-14, one effect: ps.1.4 (RacorX13/14) where PixelShaderVersion >= 1.4, the
    // ps.1.2 texdp3tex passes of RacorX12 on a ps.1.3 part ("one example at least
    // ps.1.2"), RacorX11's three ps.1.1 passes on a ps.1.1 part, nothing below.
    {"racorx_point_light.fx", {"PS14", "PS14", "PS14", "PS14", "PS12", "PS11", "", "", ""}},
    // Per-pixel specular: texdp3tex needs ps.1.2; the texm3x2 table runs on ps.1.1 and
    // comes before the multiply-based version; the paper skips the fixed-function fallback.
    {"paper_specular.fx", {"PS12", "PS12", "PS12", "PS12", "PS12", "PS11", "", "", ""}},
    // Hemisphere lighting: the per-pixel 3-term model with the directional light on every
    // ps.1.1 part; on DirectX 7 the integral cube map ("This will work even on DirectX
    // 7-class hardware"); the DirectX 6 parts have no cube maps.
    {"hemisphere.fx", {"PixelSun", "PixelSun", "PixelSun", "PixelSun", "PixelSun", "PixelSun", "Integral", "", ""}},
};

class SeedEffectChoice : public ::testing::TestWithParam<Expected> {};

TEST_P(SeedEffectChoice, PicksTheDocumentedTechniqueOnEveryProfile) {
  const Expected& e = GetParam();
  auto fx = Effect::fromFile(kDataDir + "/effects/" + e.file);
  for (const auto& d : fx->diagnostics()) ADD_FAILURE() << d.str();
  // The application loads its textures before it picks a technique (ValidateDevice checks
  // what is bound): a parameter declared textureCUBE or texture3D gets a stand-in of its
  // kind, as a cube map cannot be bound on a part without CUBEMAP in TextureCaps.
  for (Handle p = 0; p < fx->parameterCount(); ++p) {
    const ParameterType type = fx->parameterDesc(p).type;
    if (type == ParameterType::TextureCube) fx->setTexture(p, Texture::createCube(Format::A8R8G8B8, 4, 1));
    if (type == ParameterType::Texture3D) fx->setTexture(p, Texture::createVolume(Format::A8R8G8B8, 4, 4, 4, 1));
  }
  for (int i = 0; i < 9; ++i) {
    const TechniqueSelection s = fx->selectTechnique(loadCapsProfile(kProfiles[i]));
    const std::string got = s.technique < 0 ? "" : fx->techniqueDesc(s.technique).name;
    EXPECT_EQ(got, e.techniques[i]) << e.file << " on " << kProfiles[i];
  }
}

INSTANTIATE_TEST_SUITE_P(Effects, SeedEffectChoice, ::testing::ValuesIn(kSeedEffects),
                         [](const ::testing::TestParamInfo<Expected>& info) {
                           std::string n = info.param.file;
                           n = n.substr(0, n.find('.'));
                           return n;
                         });

}  // namespace

namespace {

// Probe: racorx6.fx on a flat quad facing the camera. Tangent (1,0,0), normal (0,0,-1),
// light travelling along d = (0,-0.6,0.8), so -c12 = (0,0.6,-0.8) and the vertex shader's
// tangent-space light is (U.-c12, V.-c12, W.-c12) with V = cross = (0,-1,0):
// (0, -0.6, 0.8), written to oD0 as 0.5*L + 0.5. The normal map is the flat texel
// (128,128,255): t1_bx2 = (2*128/255 - 1, same, 1) = (0.0039216, 0.0039216, 1), so
// N.L = -0.6*0.0039216 + 0.8 = 0.7976471, and the colour map (102,153,204) times N.L is
// (81.36, 122.04, 162.72) → (81, 122, 163).
TEST(EffectProbe, RacorX6DiffuseOnAFlatQuad) {
  for (const char* technique : {"PS14", "PS11"}) {
    SCOPED_TRACE(technique);
    auto fx = Effect::fromFile(kDataDir + "/effects/racorx6.fx");
    fx->setTechnique(fx->techniqueByName(technique));
    fx->setMatrix(fx->parameterByName("mWorld"), Matrix::identity());
    fx->setMatrix(fx->parameterByName("mWVP"), Matrix::identity());
    fx->setVector(fx->parameterByName("vLightDir"), Vec4(0, -0.6f, 0.8f, 0));
    auto texel = [](uint32_t argb) {
      auto t = Texture::create2D(Format::A8R8G8B8, 1, 1, 1);
      std::memcpy(t->data(0, 0), &argb, 4);
      t->markDirty();
      return t;
    };
    fx->setTexture(fx->parameterByName("ColorMap"), texel(0xff6699cc));
    fx->setTexture(fx->parameterByName("NormalMap"), texel(0xff8080ff));
    auto dev = test::makeDevice(8, 8);
    // XYZ | NORMAL | TEX2 with set 1 three floats (the tangent): 44 bytes a vertex.
    struct V {
      float x, y, z, nx, ny, nz, u, v, tx, ty, tz;
    };
    const V quad[4] = {{-1, 1, 0.5f, 0, 0, -1, 0, 0, 1, 0, 0},
                       {1, 1, 0.5f, 0, 0, -1, 1, 0, 1, 0, 0},
                       {-1, -1, 0.5f, 0, 0, -1, 0, 1, 1, 0, 0},
                       {1, -1, 0.5f, 0, 0, -1, 1, 1, 1, 0, 0}};
    dev->setFVF(FVF_XYZ | FVF_NORMAL | (2u << FVF_TEXCOUNT_SHIFT) | fvfTexCoordSize(3, 1));
    ASSERT_EQ(fx->begin(*dev, 0), 1);
    fx->beginPass(0);
    dev->drawPrimitiveUP(PT_TRIANGLESTRIP, 2, quad, sizeof(V));
    fx->endPass();
    fx->end();
    const uint32_t p = test::pixel(*dev, 4, 4);
    EXPECT_NEAR(int((p >> 16) & 0xff), 81, 1);
    EXPECT_NEAR(int((p >> 8) & 0xff), 122, 1);
    EXPECT_NEAR(int(p & 0xff), 163, 1);
  }
}

}  // namespace

namespace {

// Numbers outside the integer range saturate (a C cast would be undefined there):
// 1e30 → INT64_MAX → DWORD 0xffffffff; -1e30 → INT64_MIN → DWORD 0.
TEST(EffectState, OutOfRangeNumbersSaturate) {
  auto fx = Effect::fromText("int big = 1e30;\n"
                             "technique t { pass p { AlphaRef = 1e30; StencilRef = -1e30; StencilMask = ~1e30; } }",
                             "range.fx");
  ASSERT_TRUE(fx->diagnostics().empty()) << fx->diagnostics()[0].str();
  EXPECT_EQ(fx->getInt(fx->parameterByName("big")), -1);  // DWORD 0xffffffff read as an int
  auto dev = test::makeDevice(4, 4);
  fx->begin(*dev, kDoNotSaveState);
  fx->beginPass(0);
  EXPECT_EQ(dev->getRenderState(RS_ALPHAREF), 0xffffffffu);
  EXPECT_EQ(dev->getRenderState(RS_STENCILREF), 0u);
  EXPECT_EQ(dev->getRenderState(RS_STENCILMASK), 0u);  // ~0xffffffff
}

}  // namespace
