// The fx_2_0 binary writer against the format reference (fx2-binary.md): the worked
// example of §6.1 byte for byte, the state table's operation numbers (§3.4), object
// values (strings, textures, sampler blocks, §2.4 / §4), and what is refused.
#include <gtest/gtest.h>

#include <cstring>

#include "refx/core/diagnostics.h"
#include "refx/effect/effect.h"
#include "refx/effect/fx2_binary.h"

namespace refx::effect {
namespace {

std::vector<uint32_t> words(const std::vector<uint8_t>& b) {
  std::vector<uint32_t> w(b.size() / 4);
  std::memcpy(w.data(), b.data(), w.size() * 4);
  return w;
}

uint32_t f(float x) {
  uint32_t u;
  std::memcpy(&u, &x, 4);
  return u;
}

TEST(Fx2Writer, WorkedExampleByteForByte) {
  // Reference §6.1: one float4 parameter, one technique, one pass with ColorOp[0] and
  // an inline ps_1_1 asm shader. 280 bytes.
  const char* text =
      "float4 g_Color = {1.0, 0.5, 0.25, 1.0};\n"
      "technique T\n{\n    pass P\n    {\n        ColorOp[0]  = Modulate;\n"
      "        PixelShader = asm { ps_1_1  mov r0, v0 };\n    }\n}\n";
  auto fx = Effect::fromText(text, "example.fx");
  const Fx2Binary bin = writeFx2(*fx);
  const std::vector<uint32_t> expected = {
      0xFEFF0901, 0x84,
      // unstructured area
      0, 3, 1, 0x30, 0, 0, 4, 1,                        // type of g_Color
      0x3F800000, 0x3F000000, 0x3E800000, 0x3F800000,  // its value
      8, 0x6F435F67, 0x00726F6C,                        // "g_Color"
      4,                                                // ColorOp value: D3DTOP_MODULATE
      2, 2, 0, 0, 0, 1, 1,                              // INT, MATRIX_ROWS, 1x1
      1,                                                // PixelShader value: object 1
      15, 4, 0, 0, 0,                                   // PIXELSHADER, OBJECT
      2, 0x50,                                          // "P"
      2, 0x54,                                          // "T"
      // structured area
      1, 1, 2, 2,                    // 1 parameter, 1 technique, shader count 2, 2 objects
      0x04, 0x20, 0, 0,              // parameter
      0x7C, 0, 1,                    // technique
      0x74, 0, 2,                    // pass
      0x67, 0, 0x40, 0x3C,           // ColorOp[0]
      0x93, 0, 0x60, 0x5C,           // PixelShader
      0, 1,                          // no small object, one large object
      0, 0, 0xFFFFFFFF, 1, 0, 20,    // technique 0, pass 0, state 1, usage 0
      0xFFFF0101, 0x00000001, 0x800F0000, 0x90E40000, 0x0000FFFF};
  EXPECT_EQ(bin.bytes.size(), 280u);
  EXPECT_EQ(words(bin.bytes), expected);
  EXPECT_NE(bin.listing.find("ColorOp[0] (op 103, index 0)"), std::string::npos) << bin.listing;
  EXPECT_NE(bin.listing.find("mov r0, v0"), std::string::npos) << bin.listing;
}

TEST(Fx2Writer, StateOperations) {
  // Reference §3.4 (ops 62–71 in MojoShader's order, 127/128 in Wine's).
  const std::pair<const char*, uint32_t> ops[] = {
      {"ZEnable", 0},          {"FillMode", 1},          {"AlphaBlendEnable", 13},  {"TextureFactor", 30},
      {"Wrap0", 31},           {"Wrap8", 39},            {"Wrap15", 46},            {"Clipping", 47},
      {"Ambient", 49},         {"PointSize_Min", 61},    {"PointSpriteEnable", 62}, {"MultiSampleAntialias", 67},
      {"PointSize_Max", 71},   {"IndexedVertexBlendEnable", 72}, {"BlendOp", 75},   {"CCW_StencilFunc", 92},
      {"BlendOpAlpha", 102},   {"ColorOp", 103},         {"ColorArg0", 104},        {"TexCoordIndex", 116},
      {"Constant", 120},       {"NPatchMode", 121},      {"FVF", 122},              {"ProjectionTransform", 123},
      {"ViewTransform", 124},  {"WorldTransform", 125},  {"TextureTransform", 126}, {"MaterialDiffuse", 127},
      {"MaterialAmbient", 128}, {"MaterialPower", 131},  {"LightType", 132},        {"LightPhi", 144},
      {"LightEnable", 145},    {"VertexShader", 146},    {"PixelShader", 147},      {"VertexShaderConstantF", 148},
      {"VertexShaderConstantB", 149}, {"VertexShaderConstantI", 150}, {"VertexShaderConstant", 151},
      {"VertexShaderConstant1", 152}, {"VertexShaderConstant4", 155}, {"PixelShaderConstantF", 156},
      {"PixelShaderConstant", 159}, {"PixelShaderConstant4", 163}, {"Texture", 164}, {"AddressU", 165},
      {"MagFilter", 169},      {"MipFilter", 171},       {"DMAPOffset", 177},       {"Sampler", 178}};
  for (const auto& [name, op] : ops) {
    auto got = fx2StateOperation(name);
    ASSERT_TRUE(got.has_value()) << name;
    EXPECT_EQ(*got, op) << name;
  }
  EXPECT_FALSE(fx2StateOperation("NoSuchState").has_value());
}

// Reads the DWORD at a rel offset (from file byte 8).
uint32_t at(const std::vector<uint32_t>& w, uint32_t rel) { return w[2 + rel / 4]; }

std::string stringAt(const std::vector<uint32_t>& w, uint32_t rel) {
  const uint32_t len = at(w, rel);
  std::string s(reinterpret_cast<const char*>(&w[2 + rel / 4 + 1]), len);
  return s.substr(0, s.find('\0'));
}

TEST(Fx2Writer, ObjectsAndSamplerBlocks) {
  const char* text =
      "string Name = \"wood\";\n"
      "texture Tex < string ResourceName = \"brick\"; >;\n"
      "sampler Samp = sampler_state { Texture = <Tex>; MipFilter = Linear; };\n"
      "technique T { pass P { ZEnable = false; } }\n";
  auto fx = Effect::fromText(text, "objects.fx");
  const std::vector<uint32_t> w = words(writeFx2(*fx).bytes);
  const uint32_t u = w[1];
  size_t s = 2 + u / 4;  // structured area
  EXPECT_EQ(w[s], 3u);   // parameters
  EXPECT_EQ(w[s + 1], 1u);
  // Objects: 1 = Name, 2 = Tex, 3 = the annotation string, 4 = Samp's Texture state.
  EXPECT_EQ(w[s + 3], 5u);
  s += 4;
  // string Name: type STRING / OBJECT, value = object id 1.
  EXPECT_EQ(at(w, w[s]), 4u);
  EXPECT_EQ(at(w, w[s] + 4), 4u);
  EXPECT_EQ(stringAt(w, at(w, w[s] + 8)), "Name");
  EXPECT_EQ(at(w, w[s + 1]), 1u);
  EXPECT_EQ(w[s + 3], 0u);
  s += 4;
  // texture Tex with one annotation.
  EXPECT_EQ(at(w, w[s]), 5u);
  EXPECT_EQ(at(w, w[s + 1]), 2u);
  EXPECT_EQ(w[s + 3], 1u);
  EXPECT_EQ(stringAt(w, at(w, w[s + 4] + 8)), "ResourceName");
  EXPECT_EQ(at(w, w[s + 5]), 3u);
  s += 6;
  // sampler Samp: a block of two states, index 0x100: Texture (164) = object 4, MipFilter (171) = 2.
  EXPECT_EQ(at(w, w[s]), 10u);
  const uint32_t block = w[s + 1];
  EXPECT_EQ(at(w, block), 2u);
  EXPECT_EQ(at(w, block + 4), 164u);
  EXPECT_EQ(at(w, block + 8), 0x100u);
  EXPECT_EQ(at(w, at(w, block + 16)), 4u);
  EXPECT_EQ(at(w, block + 20), 171u);
  EXPECT_EQ(at(w, block + 24), 0x100u);
  EXPECT_EQ(at(w, at(w, block + 32)), 2u);  // D3DTEXF_LINEAR
  s += 4;
  // technique T, pass P, ZEnable = false.
  s += 3;
  EXPECT_EQ(w[s + 2], 1u);
  EXPECT_EQ(w[s + 3], 0u);
  EXPECT_EQ(at(w, w[s + 6]), 0u);
  s += 7;
  // Small objects: Name "wood" (5 bytes with NUL), Tex (0 bytes), "brick" (6 bytes).
  EXPECT_EQ(w[s], 3u);
  EXPECT_EQ(w[s + 1], 1u);
  s += 2;
  EXPECT_EQ(w[s], 1u);
  EXPECT_EQ(w[s + 1], 5u);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(&w[s + 2])), "wood");
  s += 4;
  EXPECT_EQ(w[s], 2u);
  EXPECT_EQ(w[s + 1], 0u);
  s += 2;
  EXPECT_EQ(w[s], 3u);
  EXPECT_EQ(w[s + 1], 6u);
  s += 4;
  // Large object: parameter 2's sampler block, state 0, usage 1, "Tex".
  EXPECT_EQ(w[s], 0xFFFFFFFFu);
  EXPECT_EQ(w[s + 1], 2u);
  EXPECT_EQ(w[s + 2], 0xFFFFFFFFu);
  EXPECT_EQ(w[s + 3], 0u);
  EXPECT_EQ(w[s + 4], 1u);
  EXPECT_EQ(w[s + 5], 4u);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(&w[s + 6])), "Tex");
  EXPECT_EQ(s + 7, w.size());
}

TEST(Fx2Writer, ParameterReferencesAndMatrices) {
  const char* text =
      "float4x4 mWorld : WORLD = {1,2,3,4, 5,6,7,8, 9,10,11,12, 13,14,15,16};\n"
      "float4 vLight;\n"
      "technique T { pass P { VertexShaderConstant4[0] = <mWorld>; LightDiffuse[2] = {1, 0.5, 0, 1}; } }\n";
  auto fx = Effect::fromText(text, "refs.fx");
  const std::vector<uint32_t> w = words(writeFx2(*fx).bytes);
  size_t s = 2 + w[1] / 4 + 4;
  // float4x4: FLOAT, MATRIX_ROWS (fxc's class for every matrix), rows 4, columns 4, row-major values.
  const uint32_t type = w[s], value = w[s + 1];
  EXPECT_EQ(at(w, type), 3u);
  EXPECT_EQ(at(w, type + 4), 2u);
  EXPECT_EQ(stringAt(w, at(w, type + 12)), "WORLD");
  EXPECT_EQ(at(w, type + 20), 4u);
  EXPECT_EQ(at(w, type + 24), 4u);
  EXPECT_EQ(at(w, value + 4), f(2));
  EXPECT_EQ(at(w, value + 16), f(5));
  s += 8 + 3 + 3;  // two parameters, technique, pass
  // VertexShaderConstant4[0] = <mWorld>: op 155, index 0, 16 zero placeholders typed
  // FLOAT / MATRIX_COLUMNS 4 x 4, and a usage-1 large object naming mWorld.
  EXPECT_EQ(w[s], 155u);
  EXPECT_EQ(w[s + 1], 0u);
  EXPECT_EQ(at(w, w[s + 2]), 3u);
  EXPECT_EQ(at(w, w[s + 2] + 4), 3u);
  EXPECT_EQ(at(w, w[s + 2] + 20) * at(w, w[s + 2] + 24), 16u);
  for (uint32_t i = 0; i < 16; ++i) EXPECT_EQ(at(w, w[s + 3] + 4 * i), 0u) << i;
  EXPECT_EQ(at(w, w[s + 3]), 0u);
  // LightDiffuse[2]: op 133, index 2, FLOAT 4x1 = 1, 0.5, 0, 1.
  EXPECT_EQ(w[s + 4], 133u);
  EXPECT_EQ(w[s + 5], 2u);
  EXPECT_EQ(at(w, w[s + 6] + 20), 4u);
  EXPECT_EQ(at(w, w[s + 7] + 4), f(0.5f));
  s += 8;
  EXPECT_EQ(w[s], 0u);  // small objects
  EXPECT_EQ(w[s + 1], 1u);
  const uint32_t large[] = {0, 0, 0xFFFFFFFF, 0, 1, 7};
  for (int i = 0; i < 6; ++i) EXPECT_EQ(w[s + 2 + size_t(i)], large[i]) << i;
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(&w[s + 8])), "mWorld");
}

TEST(Fx2Writer, RefusesStateExpressionsWithTheirLocation) {
  // A shader chosen by a parameter index (an array selector, usage 2) is not written.
  const char* text =
      "int i;\nvertexshader vs[2];\n"
      "technique T { pass P {\n  VertexShader = (vs[i]);\n} }\n";
  auto fx = Effect::fromText(text, "expr.fx");
  try {
    writeFx2(*fx);
    FAIL() << "an expression of parameters was written";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("expr.fx:4:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("VertexShader"), std::string::npos) << msg;
    EXPECT_NE(msg.find("FXLC"), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace refx::effect
