// CreatePixelShader / CreateVertexShader (ShaderObject) reject a shader that breaks
// its version's rules with every violation, one per line, each with its code.
#include <gtest/gtest.h>

#include <string>

#include "refx/core/diagnostics.h"
#include "refx/pipeline/shader_object.h"
#include "refx/shader/assembler.h"

namespace refx {
namespace {

// ps_1_1 (registers-and-limits.md): 4 texture registers t0..t3, so t4 is out of range
// (V1102); dp4 arrives in ps_1_2 (V1002); r1 is read with nothing written to it (V1930).
TEST(ShaderObjectValidation, ReportsEveryViolationWithItsCode) {
  const std::vector<uint32_t> tokens = shader::assembleTokens("ps_1_1\ntex t4\ndp4 r0, v0, v0\nmov r0, r1\n", "three.psh");
  try {
    PixelShader ps(tokens);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "ps_1_1: V1102: t4 is out of range: ps_1_1 has 4 texture registers (t0..t3)\n"
                 "ps_1_1: V1002: dp4 is not a ps_1_1 instruction\n"
                 "ps_1_1: V1930: r1 is read before it is written");
  }
  // vs_1_1: c96 is beyond the 96 constants (V1102), oPos is never written (V1915).
  const std::vector<uint32_t> vs = shader::assembleTokens("vs_1_1\nmov oD0, c96\n", "vs.vsh");
  try {
    VertexShader s(vs);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "vs_1_1: V1102: c96 is out of range: vs_1_1 has 96 constant registers (c0..c95)\n"
                 "vs_1_1: V1915: a vs_1_1 shader must write all four components of oPos");
  }
}

}  // namespace
}  // namespace refx
