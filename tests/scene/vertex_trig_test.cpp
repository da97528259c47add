// sin and cos in vertex shaders: vs_1_1 has no sincos instruction, so the compiler
// reduces the argument with frc and evaluates a series with mad; vs_2_0 uses sincos.
// The compiled shaders run on the interpreter, 16 lanes of inputs at a time.
#include <gtest/gtest.h>

#include <cmath>

#include "exec/shader_probe.h"
#include "refx/hlsl/compiler.h"

namespace refx {
namespace {

constexpr float kPi = 3.14159265f;

const char* kSource = R"(
void main(float4 x : POSITION, out float4 p : POSITION, out float4 s : TEXCOORD0, out float4 c : TEXCOORD1)
{
    p = float4(0, 0, 0, 1);
    s = sin(x);
    c = cos(x);
}
)";

hlsl::CompileResult compileFor(const char* profile) {
  hlsl::CompileOptions o;
  o.profile = profile;
  o.entry = "main";
  return hlsl::compile(kSource, "trig.hlsl", o);
}

int countOpcode(const shader::Shader& s, shader::Opcode op) {
  int n = 0;
  for (const shader::Instruction& in : s.instructions) n += in.opcode == op;
  return n;
}

// Inputs with known values: sin(pi/6) = 0.5, sin(-pi/2) = -1, sin(pi) = 0 (cos -1),
// cos(pi/3) = 0.5, and the same angles shifted by whole turns (2 pi k), which the
// range reduction must bring back: sin(pi/6 + 4 pi) = 0.5, cos(pi/3 - 6 pi) = 0.5.
struct Case {
  Vec4 x, sin, cos;
};
const Case kCases[] = {
    {{kPi / 6, -kPi / 2, kPi, kPi / 3}, {0.5f, -1.0f, 0.0f, 0.8660254f}, {0.8660254f, 0.0f, -1.0f, 0.5f}},
    {{kPi / 6 + 4 * kPi, kPi / 3 - 6 * kPi, 0.0f, -kPi / 4},
     {0.5f, 0.8660254f, 0.0f, -0.70710678f},
     {0.8660254f, 0.5f, 1.0f, 0.70710678f}},
    // 3 pi / 4 + 10 pi: sin = sqrt(2)/2, cos = -sqrt(2)/2; -5 pi / 6: sin = -0.5, cos = -sqrt(3)/2
    {{3 * kPi / 4 + 10 * kPi, -5 * kPi / 6, 2 * kPi / 3, -kPi / 6},
     {0.70710678f, -0.5f, 0.8660254f, -0.5f},
     {-0.70710678f, -0.8660254f, -0.5f, 0.8660254f}},
};

void checkProfile(const char* profile, float tolerance) {
  hlsl::CompileResult r = compileFor(profile);
  ASSERT_TRUE(r.ok()) << profile << "\n" << r.messages();
  probe::ShaderRun run(r.shader);
  int v = -1;
  for (const auto& b : run.lowered.vertexInputs)
    if (b.usage == shader::DeclUsage::Position) v = b.reg;
  ASSERT_GE(v, 0);
  for (int lane = 0; lane < kBatchLanes; ++lane) run.setInput(v, lane, kCases[lane % 3].x);
  run.execute();
  for (int lane = 0; lane < kBatchLanes; ++lane) {
    const Case& c = kCases[lane % 3];
    probe::expectNear(run.output(3, lane), c.sin, tolerance);  // oT0
    probe::expectNear(run.output(4, lane), c.cos, tolerance);  // oT1
  }
}

TEST(HlslVertexTrig, Vs11HasNoSincosAndUsesASeries) {
  hlsl::CompileResult r = compileFor("vs_1_1");
  ASSERT_TRUE(r.ok()) << r.messages();
  EXPECT_EQ(countOpcode(r.shader, shader::Opcode::SinCos), 0);
  EXPECT_GE(countOpcode(r.shader, shader::Opcode::Frc), 1);  // range reduction
  EXPECT_GE(countOpcode(r.shader, shader::Opcode::Mad), 5);  // the series
  EXPECT_LE(r.instructionSlots, 128);
}

// The half-angle series is accurate to about 3e-5 (the first omitted terms, doubled).
TEST(HlslVertexTrig, Vs11SinCosMatchTheAngles) { checkProfile("vs_1_1", 2e-4f); }

TEST(HlslVertexTrig, Vs20SinCosMatchTheAngles) {
  hlsl::CompileResult r = compileFor("vs_2_0");
  ASSERT_TRUE(r.ok()) << r.messages();
  // one sincos per component, shared by sin and cos of that component
  EXPECT_EQ(countOpcode(r.shader, shader::Opcode::SinCos), 4);
  checkProfile("vs_2_0", 2e-4f);
}

// tan(float4) in ps_2_0: one sincos per component (cos and sin of the same value
// together), so the shader fits the 64 arithmetic slots: 4 sincos at 8 slots, a
// 3-slot range reduction, 4 rcp, the divide and the scale.
TEST(HlslVertexTrig, TanFitsPs20) {
  hlsl::CompileOptions o;
  o.profile = "ps_2_0";
  o.entry = "main";
  hlsl::CompileResult r = hlsl::compile("float4 x; float4 main() : COLOR { return tan(x) * 0.5 + 0.5; }", "tan.hlsl", o);
  ASSERT_TRUE(r.ok()) << r.messages();
  EXPECT_EQ(countOpcode(r.shader, shader::Opcode::SinCos), 4);
  EXPECT_LE(r.instructionSlots, 64);
}

}  // namespace
}  // namespace refx
