// Preshaders: with CompileOptions::preshaders the computations that read only
// uniforms leave the shader; the CPU program computes them from its own input table.
// Expected values are the HLSL expressions evaluated by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "refx/hlsl/compiler.h"
#include "refx/shader/validator.h"

namespace refx {
namespace {

hlsl::CompileResult compileWithPreshaders(const char* source, const char* profile, bool preshaders = true) {
  hlsl::CompileOptions o;
  o.profile = profile;
  o.preshaders = preshaders;
  return hlsl::compile(source, "pre.hlsl", o);
}

int countOpcode(const shader::Shader& s, shader::Opcode op) {
  int n = 0;
  for (const shader::Instruction& in : s.instructions) n += in.opcode == op;
  return n;
}

// World * View is the same for every vertex: the 64 multiply-adds of the matrix product
// go to the preshader, the shader keeps the four dp4 of the position with its result.
constexpr const char* kMatrixProduct = R"(
float4x4 World;
float4x4 View;
float4 main(float4 p : POSITION) : POSITION { return mul(p, mul(World, View)); }
)";

TEST(HlslPreshader, AMatrixProductOfUniformsLeavesTheShader) {
  const hlsl::CompileResult with = compileWithPreshaders(kMatrixProduct, "vs_2_0");
  const hlsl::CompileResult without = compileWithPreshaders(kMatrixProduct, "vs_2_0", false);
  ASSERT_TRUE(with.ok()) << with.messages();
  ASSERT_TRUE(without.ok()) << without.messages();
  ASSERT_FALSE(without.preshader);
  ASSERT_TRUE(with.preshader);
  EXPECT_TRUE(shader::validate(with.shader).empty());
  // The shader: four dp4 (one per output component) and nothing else that computes.
  EXPECT_EQ(countOpcode(with.shader, shader::Opcode::Dp4), 4);
  EXPECT_EQ(with.instructionSlots, 4);
  EXPECT_GT(without.instructionSlots, with.instructionSlots);
  // The shader's constant table no longer names World and View: the preshader reads them.
  const auto table = shader::readConstantTable(with.shader);
  ASSERT_TRUE(table);
  EXPECT_FALSE(table->find("World"));
  EXPECT_FALSE(table->find("View"));
  const hlsl::Preshader& pre = *with.preshader;
  ASSERT_TRUE(pre.inputs.find("World"));
  ASSERT_TRUE(pre.inputs.find("View"));
  EXPECT_EQ(pre.inputs.find("World")->registerCount, 4);
  // Four float4 results, the registers the four dp4 read.
  ASSERT_EQ(pre.outputRegisters.size(), 4u);
}

// Running it: World = scale by 2, View = translation by (1, 2, 3) (row-vector
// matrices). World * View = [[2,0,0,0],[0,2,0,0],[0,0,2,0],[1,2,3,1]]. The matrices are
// column_major, so input register k holds column k of each; the shader's dp4 with
// output register k computes component k of p * (World * View), so output k is
// column k of the product: (2,0,0,1), (0,2,0,2), (0,0,2,3), (0,0,0,1).
TEST(HlslPreshader, RunComputesTheProductColumns) {
  const hlsl::CompileResult r = compileWithPreshaders(kMatrixProduct, "vs_2_0");
  ASSERT_TRUE(r.preshader);
  const hlsl::Preshader& pre = *r.preshader;
  std::vector<float> input(4 * 8, 0.0f);
  auto column = [&](const char* name, int k, std::array<float, 4> v) {
    const int base = pre.inputs.find(name)->registerIndex;
    for (int i = 0; i < 4; ++i) input[size_t(4 * (base + k) + i)] = v[size_t(i)];
  };
  column("World", 0, {2, 0, 0, 0});
  column("World", 1, {0, 2, 0, 0});
  column("World", 2, {0, 0, 2, 0});
  column("World", 3, {0, 0, 0, 1});
  column("View", 0, {1, 0, 0, 1});
  column("View", 1, {0, 1, 0, 2});
  column("View", 2, {0, 0, 1, 3});
  column("View", 3, {0, 0, 0, 1});
  const std::vector<float> out = pre.run(input);
  ASSERT_EQ(out.size(), 16u);
  // Which output feeds which dp4: read the shader's source registers in order.
  std::vector<int> dp4Constants;
  for (const shader::Instruction& in : r.shader.instructions)
    if (in.opcode == shader::Opcode::Dp4)
      for (int s = 0; s < 2; ++s)
        if (in.src[s].type == shader::RegType::Const) dp4Constants.push_back(in.src[s].index);
  ASSERT_EQ(dp4Constants.size(), 4u);
  const float expected[4][4] = {{2, 0, 0, 1}, {0, 2, 0, 2}, {0, 0, 2, 3}, {0, 0, 0, 1}};
  for (int k = 0; k < 4; ++k) {
    const auto it = std::find(pre.outputRegisters.begin(), pre.outputRegisters.end(), dp4Constants[size_t(k)]);
    ASSERT_NE(it, pre.outputRegisters.end());
    const size_t o = size_t(it - pre.outputRegisters.begin());
    for (int i = 0; i < 4; ++i) EXPECT_FLOAT_EQ(out[4 * o + size_t(i)], expected[k][i]) << "column " << k;
  }
}

// Scalar functions and normalisation run on the CPU as the shader would: H =
// normalize(L + E) with L = (0, 3, 4) / 5 and E = (0, 0, 1): (0, 0.6, 1.8) / 1.897367 =
// (0, 0.316228, 0.948683); 1 / roughness with roughness 0.25 is 4.
TEST(HlslPreshader, NormalizeAndReciprocalOfUniforms) {
  const hlsl::CompileResult r = compileWithPreshaders(R"(
float3 L;
float3 E;
float roughness;
float4 main(float3 n : TEXCOORD0) : COLOR {
  float3 H = normalize(L + E);
  return pow(saturate(dot(n, H)), 1 / roughness);
})",
                                                      "ps_2_0");
  ASSERT_TRUE(r.ok()) << r.messages();
  ASSERT_TRUE(r.preshader);
  const hlsl::Preshader& pre = *r.preshader;
  std::vector<float> input(4 * 3, 0.0f);
  auto set = [&](const char* name, std::array<float, 4> v) {
    const shader::ShaderConstant* c = pre.inputs.find(name);
    ASSERT_TRUE(c) << name;
    for (int i = 0; i < 4; ++i) input[size_t(4 * c->registerIndex + i)] = v[size_t(i)];
  };
  set("L", {0, 0.6f, 0.8f, 0});
  set("E", {0, 0, 1, 0});
  set("roughness", {0.25f, 0, 0, 0});
  const std::vector<float> out = pre.run(input);
  bool sawH = false, sawPower = false;
  for (size_t o = 0; o + 3 < out.size(); o += 4) {
    if (std::fabs(out[o + 1] - 0.316228f) < 1e-5f && std::fabs(out[o + 2] - 0.948683f) < 1e-5f) sawH = true;
    if (std::fabs(out[o] - 4.0f) < 1e-6f) sawPower = true;
  }
  EXPECT_TRUE(sawH);
  EXPECT_TRUE(sawPower);
  // The shader keeps the per-pixel part only: no nrm, no rcp, no rsq.
  EXPECT_EQ(countOpcode(r.shader, shader::Opcode::Nrm), 0);
  EXPECT_EQ(countOpcode(r.shader, shader::Opcode::Rcp), 0);
  EXPECT_EQ(countOpcode(r.shader, shader::Opcode::Rsq), 0);
}

// Nothing to move: a shader that only reads uniforms has no preshader.
TEST(HlslPreshader, PlainUniformReadsNeedNone) {
  const hlsl::CompileResult r = compileWithPreshaders("float4 c; float4 main(float4 t : TEXCOORD0) : COLOR { return c * t; }",
                                                      "ps_2_0");
  ASSERT_TRUE(r.ok()) << r.messages();
  EXPECT_FALSE(r.preshader);
}

}  // namespace
}  // namespace refx
