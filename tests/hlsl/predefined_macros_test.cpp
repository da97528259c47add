// The target profile as predefined macros: one source can choose code per profile.
#include <gtest/gtest.h>

#include <array>
#include <cstring>

#include "refx/hlsl/compiler.h"
#include "refx/shader/bytecode.h"

namespace refx {
namespace {

// The shader returns the macros as a colour: (stage, major, minor, 1). ps_2_0 gives the
// def (0, 2, 0, 1); a vertex shader's stage is 1.
std::array<float, 4> compiledDef(const char* profile) {
  hlsl::CompileOptions o;
  o.profile = profile;
  const hlsl::CompileResult r = hlsl::compile(
      "#if __SHADER_TARGET_STAGE == __SHADER_STAGE_VERTEX\n"
      "float4 main() : POSITION\n"
      "#else\n"
      "float4 main() : COLOR\n"
      "#endif\n"
      "{ return float4(__SHADER_TARGET_STAGE, __SHADER_TARGET_MAJOR, __SHADER_TARGET_MINOR, 1); }\n",
      "macros.hlsl", o);
  EXPECT_TRUE(r.ok()) << r.messages();
  for (const shader::Instruction& in : r.shader.instructions)
    if (in.opcode == shader::Opcode::Def) {
      std::array<float, 4> v;
      std::memcpy(v.data(), in.literal.data(), 16);
      return v;
    }
  ADD_FAILURE() << "no def in the " << profile << " shader";
  return {};
}

TEST(HlslPredefinedMacros, NameTheTargetProfile) {
  EXPECT_EQ(compiledDef("ps_2_0"), (std::array<float, 4>{0, 2, 0, 1}));
  EXPECT_EQ(compiledDef("ps_3_0"), (std::array<float, 4>{0, 3, 0, 1}));
  EXPECT_EQ(compiledDef("vs_2_0"), (std::array<float, 4>{1, 2, 0, 1}));
}

// vs_1_1 packs its literals into shared def registers, so the macros choose between a
// shader that compiles and one that names an undeclared variable.
TEST(HlslPredefinedMacros, SelectCodeForVs11) {
  hlsl::CompileOptions o;
  o.profile = "vs_1_1";
  const char* source =
      "#if __SHADER_TARGET_STAGE == __SHADER_STAGE_VERTEX && __SHADER_TARGET_MAJOR == 1 && __SHADER_TARGET_MINOR == 1\n"
      "float4 main(float4 p : POSITION) : POSITION { return p; }\n"
      "#else\n"
      "float4 main() : POSITION { return wrong_profile; }\n"
      "#endif\n";
  EXPECT_TRUE(hlsl::compile(source, "vs11.hlsl", o).ok());
  o.profile = "vs_2_0";
  EXPECT_FALSE(hlsl::compile(source, "vs11.hlsl", o).ok());
}

}  // namespace
}  // namespace refx
