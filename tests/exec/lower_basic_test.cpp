// Lowering of basic vertex and pixel shaders: arithmetic, m4x4, def, tex, ps_1_x
// ranges. Expected values are worked out from reference/instructions.md.
#include "shader_probe.h"

using namespace probe;
using sh::Opcode;
using sh::RegType;
using SM = sh::SrcMod;

namespace {

constexpr int kVsPos = kVertexOutPosition, kVsDiffuse = kVertexOutDiffuse, kVsTex0 = kVertexOutTex0;
constexpr int kPsDiffuse = kPixelInDiffuse, kPsSpecular = kPixelInSpecular, kPsTex0 = kPixelInTex0;

TEST(LowerVertex, M4x4WithDefAndApiConstants) {
  Builder b(sh::ShaderType::Vertex, 1, 1);
  b.def(4, 0.25f, 0.5f, 0.75f, 1.0f);
  b.op(Opcode::M4x4, D(RegType::RastOut, 0), {S(RegType::Input, 0), S(RegType::Const, 0)});
  b.op(Opcode::Mov, D(RegType::AttrOut, 0), {S(RegType::Const, 4)});
  b.op(Opcode::Mov, D(RegType::TexCrdOut, 0, 0x3), {S(RegType::Input, 0, swz(3, 2, 1, 0))});
  ShaderRun r(b.shader);
  // Rows c0..c3 of a matrix: oPos.k = dp4(v0, c[k]).
  r.constant(0, {1, 0, 0, 0}).constant(1, {0, 2, 0, 0}).constant(2, {0, 0, 3, 0}).constant(3, {1, 1, 1, 1});
  r.constant(4, {9, 9, 9, 9});  // overridden by the local def
  r.input(0, {1, 2, 3, 4}).execute();
  // (1*1, 2*2, 3*3, 1+2+3+4)
  expectNear(r.output(kVsPos), {1, 4, 9, 10});
  // def c4 wins over the API value
  expectNear(r.output(kVsDiffuse), {0.25f, 0.5f, 0.75f, 1.0f});
  // v0.wzyx masked .xy: (4, 3)
  expectNear(r.output(kVsTex0), {4, 3, 0, 0});
  EXPECT_EQ(r.lowered.floatConstantsRead, 4);  // c0..c3 (c4 is local)
}

TEST(LowerVertex, MacroWithDestinationAlsoSource) {
  // m3x3 r0, r0, c0 must read the old r0 for every row.
  Builder b(sh::ShaderType::Vertex, 1, 1);
  b.op(Opcode::Mov, D(RegType::Temp, 0), {S(RegType::Input, 0)});
  b.op(Opcode::M3x3, D(RegType::Temp, 0, 0x7), {S(RegType::Temp, 0), S(RegType::Const, 0)});
  b.op(Opcode::Mov, D(RegType::RastOut, 0), {S(RegType::Temp, 0)});
  ShaderRun r(b.shader);
  // rows: (0,1,0), (1,0,0), (1,1,1): a permutation then a sum
  r.constant(0, {0, 1, 0, 0}).constant(1, {1, 0, 0, 0}).constant(2, {1, 1, 1, 0});
  r.input(0, {1, 2, 3, 7}).execute();
  // (y, x, x+y+z, w untouched) = (2, 1, 6, 7)
  expectNear(r.output(kVsPos), {2, 1, 6, 7});
}

TEST(LowerPixel, RacorX9StyleDiffuseSpecular) {
  // tex t0; tex t1; dp3 r0, t1_bx2, v1_bx2; mul r1, r0, r0; mul r0, r1, r1;
  // dp3 r1, t1_bx2, v0_bx2; mad r0, t0, r1, r0
  Builder b(sh::ShaderType::Pixel, 1, 1);
  b.op(Opcode::Tex, D(RegType::Texture, 0));
  b.op(Opcode::Tex, D(RegType::Texture, 1));
  b.op(Opcode::Dp3, D(RegType::Temp, 0), {S(RegType::Texture, 1, 0xE4, SM::Sign), S(RegType::Input, 1, 0xE4, SM::Sign)});
  b.op(Opcode::Mul, D(RegType::Temp, 1), {S(RegType::Temp, 0), S(RegType::Temp, 0)});
  b.op(Opcode::Mul, D(RegType::Temp, 0), {S(RegType::Temp, 1), S(RegType::Temp, 1)});
  b.op(Opcode::Dp3, D(RegType::Temp, 1), {S(RegType::Texture, 1, 0xE4, SM::Sign), S(RegType::Input, 0, 0xE4, SM::Sign)});
  b.op(Opcode::Mad, D(RegType::Temp, 0), {S(RegType::Texture, 0), S(RegType::Temp, 1), S(RegType::Temp, 0)});
  for (bool prepared : {false, true}) {
    ShaderRun r(b.shader);
    r.usePrepare = prepared;
    // Fake sampler: t0 = TC0 = (0.5, 0.25, 1, 1); t1 = TC1 = normal (0.5, 0.5, 1) → N = (0,0,1)
    r.input(kPsTex0, {0.5f, 0.25f, 1, 1}).input(kPsTex0 + 1, {0.5f, 0.5f, 1, 1});
    // H = bx2(v1) = (0, 0.6, 0.8) → v1 = (0.5, 0.8, 0.9); L = bx2(v0) = (0, 0, 1) → v0 = (0.5, 0.5, 1)
    r.input(kPsSpecular, {0.5f, 0.8f, 0.9f, 1}).input(kPsDiffuse, {0.5f, 0.5f, 1.0f, 1});
    r.execute();
    // N.H = 0.8; (0.8^2)^2 = 0.4096; N.L = 1; r0 = t0 * 1 + 0.4096
    expectNear(r.output(0), {0.5f + 0.4096f, 0.25f + 0.4096f, 1.0f, 1.0f});  // clamped to 1
    EXPECT_EQ(r.lowered.samplersUsed, 0x3u);
  }
}

TEST(LowerPixel, Ps11ClampsResultsAndConstants) {
  // def c0 = (2, -3, 0.5, 1) is read as (1, -1, 0.5, 1); add r0 = c0 + c1 with c1
  // set through the API as (0.75, 0, 0, 5) → read as (0.75, 0, 0, 1).
  Builder b(sh::ShaderType::Pixel, 1, 1);
  b.def(0, 2, -3, 0.5f, 1);
  b.op(Opcode::Add, D(RegType::Temp, 0), {S(RegType::Const, 0), S(RegType::Const, 1)});
  for (bool prepared : {false, true}) {
    ShaderRun r(b.shader);
    r.usePrepare = prepared;
    r.constant(1, {0.75f, 0, 0, 5}).execute();
    // (1 + 0.75 → 1, -1 + 0, 0.5 + 0, 1 + 1 → 1)
    expectNear(r.output(0), {1, -1, 0.5f, 1});
  }
}

TEST(LowerPixel, Ps14RangeIsEight) {
  // ps_1_4: add r0, r0_x2-like growth: mul_x4 r0, c0, c0 with c0 = 1 → 4 (within ±8)
  Builder b(sh::ShaderType::Pixel, 1, 4);
  b.def(0, 1, 1, -1, 1);
  auto& in = b.op(Opcode::Mul, D(RegType::Temp, 0), {S(RegType::Const, 0), S(RegType::Const, 0)});
  in.dst.shift = 2;
  auto& in2 = b.op(Opcode::Add, D(RegType::Temp, 1), {S(RegType::Temp, 0), S(RegType::Temp, 0)});
  in2.dst.shift = 1;
  b.op(Opcode::Mov, D(RegType::Temp, 0, 0x2), {S(RegType::Temp, 1)});
  ShaderRun r(b.shader);
  r.execute();
  // r0 = 4*(1,1,1,1) = (4,4,4,4); r1 = 2*(8) = 16 → clamp 8; r0.y = 8
  expectNear(r.output(0), {4, 8, 4, 4});
}

TEST(LowerPixel, ColorInputsSaturated) {
  Builder b(sh::ShaderType::Pixel, 1, 1);
  b.op(Opcode::Mov, D(RegType::Temp, 0), {S(RegType::Input, 0)});
  ShaderRun r(b.shader);
  r.input(kPsDiffuse, {1.5f, -0.5f, 0.25f, 2}).execute();
  expectNear(r.output(0), {1, 0, 0.25f, 1});
  // With the caller's guarantee the program does not clamp again.
  ShaderLoweringOptions o;
  o.colorInputsInRange = true;
  ShaderRun t(b.shader, o);
  t.input(kPsDiffuse, {0.5f, 0.25f, 0.25f, 1}).execute();
  expectNear(t.output(0), {0.5f, 0.25f, 0.25f, 1});
  EXPECT_EQ(t.lowered.program.code.size(), 1u);  // just the mov
}

TEST(LowerRegisters, FilesAreTheVersionsOwn) {
  // registers-and-limits.md §2: ps_1_4 has t0..t5, ps_2_0 r0..r11, ps_2_x up to 32
  // temporaries (NumTemps), ps_1_1 r0..r1; §1: vs_3_0 has o0..o11.
  EXPECT_NO_THROW(asmRun("ps_1_4\ntexcrd r0.xyz, t5\n"));
  EXPECT_THROW(asmRun("ps_1_4\ntexcrd r0.xyz, t6\n"), refx::Error);
  EXPECT_NO_THROW(asmRun("ps_2_0\nmov r11, c0\nmov oC0, r11\n"));
  EXPECT_THROW(asmRun("ps_2_0\nmov r12, c0\nmov oC0, r12\n"), refx::Error);
  EXPECT_NO_THROW(asmRun("ps_2_x\nmov r31, c0\nmov oC0, r31\n"));
  EXPECT_THROW(asmRun("ps_1_1\nmov r2, c0\n"), refx::Error);
  EXPECT_THROW(asmRun("vs_3_0\ndcl_position o12\nmov o12, c0\n"), refx::Error);
}

TEST(LowerRegisters, RelativeConstantsReadTheWholeFile) {
  // c[a0.x + n] may read any constant of the version: 256 in vertex shaders (the vs_2_0
  // minimum, and the most a vs_1_1 device reports), 224 in ps_3_0 (§1, §2).
  EXPECT_EQ(asmRun("vs_1_1\nmov a0.x, c0.x\nmov oPos, c[a0.x + 4]\n").lowered.floatConstantsRead, 256);
  EXPECT_EQ(asmRun("ps_3_0\ndefi i0, 2, 0, 1, 0\nmov r0, c0\nloop aL, i0\nadd r0, r0, c[aL]\nendloop\n"
                   "mov oC0, r0\n")
                .lowered.floatConstantsRead,
            224);
}

}  // namespace
