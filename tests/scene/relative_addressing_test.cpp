// Run-time indices into uniform arrays: vertex shaders read c[a0.x + n] (vs_1_1 loads
// a0.x with mov, vs_2_0 and vs_3_0 with mova); pixel shaders reject the index. The
// compiled shaders run on the interpreter with one index per lane.
#include <gtest/gtest.h>

#include <cmath>
#include <regex>

#include "exec/shader_probe.h"
#include "refx/hlsl/compiler.h"
#include "refx/shader/disassembler.h"

namespace refx {
namespace {

const char* kSkin = R"(
float4 arr[6];
float4x3 bones[3];
void main(float4 p : POSITION, float4 bi : BLENDINDICES, out float4 o : POSITION, out float4 a : TEXCOORD0,
          out float4 b : TEXCOORD1)
{
    o = p;
    a = arr[bi.x];
    b = float4(mul(p, bones[bi.y]), 1.0);
}
)";

hlsl::CompileResult compile(const char* source, const char* profile) {
  hlsl::CompileOptions o;
  o.profile = profile;
  o.entry = "main";
  return hlsl::compile(source, "rel.hlsl", o);
}

int countOpcode(const shader::Shader& s, shader::Opcode op) {
  int n = 0;
  for (const shader::Instruction& in : s.instructions) n += in.opcode == op;
  return n;
}

// The constant table lists the whole array, though the shader names no element.
TEST(HlslRelativeAddressing, ConstantTableReservesTheWholeArray) {
  hlsl::CompileResult r = compile(kSkin, "vs_2_0");
  ASSERT_TRUE(r.ok()) << r.messages();
  shader::DisassemblyOptions listing;
  listing.listing = true;
  std::string text = shader::disassemble(r.shader, listing);
  // arr: 6 registers from c0; bones: 3 matrices of 3 columns (column_major float4x3) from c6
  EXPECT_TRUE(std::regex_search(text, std::regex(R"(//   arr +c0 +6\n)"))) << text;
  EXPECT_TRUE(std::regex_search(text, std::regex(R"(//   bones +c6 +9\n)"))) << text;
  EXPECT_NE(text.find("c[a0.x+6]"), std::string::npos) << text;
}

// arr[k] = (k + 1, 10, 20, 30) in c0..c5; bones[k] scales by k + 1: column j of bone k
// (register 6 + 3k + j) is (k + 1) * e_j. Per lane: bi.x selects arr[trunc(bi.x)], bi.y
// the bone; p = (1, 2, 3, 1) → mul(p, bones[k]) = (k + 1) * (1, 2, 3).
void runSkin(const char* profile) {
  hlsl::CompileResult r = compile(kSkin, profile);
  ASSERT_TRUE(r.ok()) << profile << "\n" << r.messages();
  EXPECT_EQ(countOpcode(r.shader, shader::Opcode::MovA), std::string(profile) == "vs_1_1" ? 0 : 2) << profile;
  probe::ShaderRun run(r.shader);
  int vp = -1, vb = -1;
  for (const auto& b : run.lowered.vertexInputs) {
    if (b.usage == shader::DeclUsage::Position) vp = b.reg;
    if (b.usage == shader::DeclUsage::BlendIndices) vb = b.reg;
  }
  ASSERT_GE(vp, 0);
  ASSERT_GE(vb, 0);
  for (int k = 0; k < 6; ++k) run.constant(k, {float(k + 1), 10, 20, 30});
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j) {
      Vec4 col{0, 0, 0, 0};
      float s = float(k + 1);
      col = Vec4(j == 0 ? s : 0, j == 1 ? s : 0, j == 2 ? s : 0, 0);
      run.constant(6 + 3 * k + j, col);
    }
  // index values and the element HLSL's int conversion (toward zero) picks
  const float xs[] = {0.0f, 1.7f, 2.2f, 5.0f, 3.0f, 4.9f};
  const int xi[] = {0, 1, 2, 5, 3, 4};
  const float ys[] = {0.0f, 1.0f, 2.0f, 1.6f};
  const int yi[] = {0, 1, 2, 1};
  for (int lane = 0; lane < kBatchLanes; ++lane) {
    run.setInput(vp, lane, {1, 2, 3, 1});
    run.setInput(vb, lane, {xs[lane % 6], ys[lane % 4], 0, 0});
  }
  run.execute();
  for (int lane = 0; lane < kBatchLanes; ++lane) {
    float e = float(xi[lane % 6] + 1);
    probe::expectNear(run.output(3, lane), {e, 10, 20, 30});  // oT0 = arr[trunc(bi.x)]
    float s = float(yi[lane % 4] + 1);
    probe::expectNear(run.output(4, lane), {s, 2 * s, 3 * s, 1});  // oT1
  }
}

TEST(HlslRelativeAddressing, Vs11LoadsA0WithMov) { runSkin("vs_1_1"); }
TEST(HlslRelativeAddressing, Vs20LoadsA0WithMova) { runSkin("vs_2_0"); }
TEST(HlslRelativeAddressing, Vs30LoadsA0WithMova) { runSkin("vs_3_0"); }

// One a0 load serves every row of a matrix element.
TEST(HlslRelativeAddressing, OneAddressLoadPerIndex) {
  hlsl::CompileResult r = compile(kSkin, "vs_2_0");
  ASSERT_TRUE(r.ok()) << r.messages();
  int relative = 0;
  for (const shader::Instruction& in : r.shader.instructions)
    for (int s = 0; s < in.srcCount; ++s) relative += in.src[s].relative;
  EXPECT_EQ(relative, 4);  // arr[…] once, bones[…] three columns
  EXPECT_EQ(countOpcode(r.shader, shader::Opcode::MovA), 2);
}

// Pixel shaders have no address register for constants (ps_3_0's aL indexes only
// inside loop…endloop): a run-time index is an error that names the profile.
TEST(HlslRelativeAddressing, PixelShadersRejectARuntimeIndex) {
  const char* ps = R"(
float4 arr[4];
float4 main(float4 t : TEXCOORD0) : COLOR
{
    return arr[t.x];
}
)";
  for (const char* profile : {"ps_2_0", "ps_2_x", "ps_3_0"}) {
    hlsl::CompileResult r = compile(ps, profile);
    EXPECT_FALSE(r.ok()) << profile;
    ASSERT_FALSE(r.diagnostics.empty()) << profile;
    const Diagnostic& d = r.diagnostics[0];
    EXPECT_EQ(d.code, "X3512") << profile;
    EXPECT_EQ(d.where.line, 5) << profile;
    EXPECT_EQ(d.where.column, 15) << profile;
    EXPECT_NE(d.message.find(profile), std::string::npos) << d.message;
  }
  // a literal index, or a run-time index into a local array, still compiles
  EXPECT_TRUE(compile("float4 arr[4]; float4 main() : COLOR { return arr[2]; }", "ps_2_0").ok());
  EXPECT_TRUE(compile("float4 main(float4 t : TEXCOORD0) : COLOR { float4 a[2] = { t, t * 2 }; return a[t.x]; }",
                      "ps_2_0")
                  .ok());
}

}  // namespace
}  // namespace refx
