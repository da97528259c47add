// Scalar operations written component by component join into one masked instruction.
#include <gtest/gtest.h>

#include "refx/hlsl/compiler.h"

namespace refx {
namespace {

int countOpcode(const shader::Shader& s, shader::Opcode op) {
  int n = 0;
  for (const shader::Instruction& in : s.instructions) n += in.opcode == op;
  return n;
}

// r.x = a.x * b.x; r.y = a.y * b.y; r.z = a.z * b.z is one mul .xyz; /Od keeps three.
TEST(HlslVectorize, ComponentsWrittenOneByOneShareAMul) {
  const char* source =
      "float4 main(float4 a : TEXCOORD0, float4 b : TEXCOORD1) : COLOR {\n"
      "  float4 r; r.x = a.x * b.x; r.y = a.y * b.y; r.z = a.z * b.z; r.w = 1; return r; }\n";
  hlsl::CompileOptions o;
  o.profile = "ps_2_0";
  const hlsl::CompileResult joined = hlsl::compile(source, "v.hlsl", o);
  ASSERT_TRUE(joined.ok()) << joined.messages();
  EXPECT_EQ(countOpcode(joined.shader, shader::Opcode::Mul), 1);
  o.optimize = false;
  const hlsl::CompileResult apart = hlsl::compile(source, "v.hlsl", o);
  ASSERT_TRUE(apart.ok()) << apart.messages();
  EXPECT_EQ(countOpcode(apart.shader, shader::Opcode::Mul), 3);
  EXPECT_LT(joined.instructionSlots, apart.instructionSlots);
}

// In ps_2_0 a crossed pair (a.z * b.x, a.x * b.z) would need a swizzle ps_2_0 cannot
// read: it stays two instructions there, and joins in vs_2_0, which reads any swizzle.
TEST(HlslVectorize, OnlySwizzlesTheVersionCanRead) {
  const char* ps =
      "float4 a; float4 b;\n"
      "float4 main() : COLOR { float2 q; q.x = a.z * b.x; q.y = a.x * b.z; return float4(q, 0, 1); }\n";
  hlsl::CompileOptions o;
  o.profile = "ps_2_0";
  const hlsl::CompileResult r = hlsl::compile(ps, "v.hlsl", o);
  ASSERT_TRUE(r.ok()) << r.messages();
  EXPECT_EQ(countOpcode(r.shader, shader::Opcode::Mul), 2);
  const char* vs =
      "float4 a; float4 b;\n"
      "float4 main() : POSITION { float2 q; q.x = a.z * b.x; q.y = a.x * b.z; return float4(q, 0, 1); }\n";
  o.profile = "vs_2_0";
  const hlsl::CompileResult v = hlsl::compile(vs, "v.hlsl", o);
  ASSERT_TRUE(v.ok()) << v.messages();
  EXPECT_EQ(countOpcode(v.shader, shader::Opcode::Mul), 1);
}

}  // namespace
}  // namespace refx
