#include <gtest/gtest.h>

#include "refx/exec/interpreter.h"

using namespace refx;
using namespace refx::exec;

namespace {

// Runs `p` with input v0 = (x, y, z, w) in every lane and returns o0 of lane 0.
Vec4 run1(Program& p, Vec4 v0, Vec4 v1 = {}) {
  p.inputCount = std::max(p.inputCount, 2);
  p.outputCount = std::max(p.outputCount, 1);
  BatchRegisters regs;
  regs.resize(p);
  for (int l = 0; l < kBatchLanes; ++l)
    for (int c = 0; c < 4; ++c) {
      regs.inputs[0].c[c][l] = v0[c];
      regs.inputs[1].c[c][l] = v1[c];
    }
  ExecContext ctx;
  execute(p, ctx, regs);
  return {regs.outputs[0].c[0][0], regs.outputs[0].c[1][0], regs.outputs[0].c[2][0],
          regs.outputs[0].c[3][0]};
}

TEST(Interpreter, MadWithSwizzleAndNegate) {
  Program p;
  // o0 = v0.wzyx * v1 + (-imm)  = (4,3,2,1)*(1,2,3,4) - (1,1,1,1) = (3,5,5,3)
  p.emit(Op::Mad, dst(RegFile::Output, 0), reg(RegFile::Input, 0, swz(3, 2, 1, 0)),
         reg(RegFile::Input, 1), [&] { Src s = p.imm({1, 1, 1, 1}); s.mod = SrcMod::Neg; return s; }());
  Vec4 r = run1(p, {1, 2, 3, 4}, {1, 2, 3, 4});
  EXPECT_EQ(r, Vec4(3, 5, 5, 3));
}

TEST(Interpreter, Dp3ReplicatesAndRespectsWriteMask) {
  Program p;
  p.emit(Op::Mov, dst(RegFile::Output, 0), p.imm({9, 9, 9, 9}));
  // dp3 (1,2,3)·(4,5,6) = 4 + 10 + 18 = 32, written to .xy only
  p.emit(Op::Dp3, dst(RegFile::Output, 0, 0x3), reg(RegFile::Input, 0), reg(RegFile::Input, 1));
  Vec4 r = run1(p, {1, 2, 3, 100}, {4, 5, 6, 100});
  EXPECT_EQ(r, Vec4(32, 32, 9, 9));
}

TEST(Interpreter, SourceModifiersBiasSignComp) {
  Program p;
  p.tempCount = 1;
  // bx2: 2*(0.75-0.5) = 0.5 ; bias: 0.75-0.5 = 0.25 ; comp: 1-0.75 = 0.25
  p.emit(Op::Mov, dst(RegFile::Output, 0, 0x1), reg(RegFile::Input, 0, kSwzXYZW, SrcMod::Sign));
  p.emit(Op::Mov, dst(RegFile::Output, 0, 0x2), reg(RegFile::Input, 0, kSwzXYZW, SrcMod::Bias));
  p.emit(Op::Mov, dst(RegFile::Output, 0, 0x4), reg(RegFile::Input, 0, kSwzXYZW, SrcMod::Comp));
  p.emit(Op::Mov, dst(RegFile::Output, 0, 0x8), reg(RegFile::Input, 0, kSwzXYZW, SrcMod::X2));
  Vec4 r = run1(p, {0.75f, 0.75f, 0.75f, 0.75f});
  EXPECT_FLOAT_EQ(r.x, 0.5f);
  EXPECT_FLOAT_EQ(r.y, 0.25f);
  EXPECT_FLOAT_EQ(r.z, 0.25f);
  EXPECT_FLOAT_EQ(r.w, 1.5f);
}

TEST(Interpreter, ShiftThenSaturateAndClamp) {
  Program p;
  // mul_x2_sat: 2*(0.75*0.5) = 0.75 ; 2*(0.75*1) = 1.5 -> 1
  auto& a = p.emit(Op::Mul, dst(RegFile::Output, 0, 0x3), reg(RegFile::Input, 0), reg(RegFile::Input, 1));
  a.shift = 1;
  a.saturate = true;
  // clamp to [-1,1]: -3 -> -1
  auto& b = p.emit(Op::Mov, dst(RegFile::Output, 0, 0x4), p.imm({-3, -3, -3, -3}));
  b.clamp = true;
  Vec4 r = run1(p, {0.75f, 0.75f, 0, 0}, {0.5f, 1.0f, 0, 0});
  EXPECT_FLOAT_EQ(r.x, 0.75f);
  EXPECT_FLOAT_EQ(r.y, 1.0f);
  EXPECT_FLOAT_EQ(r.z, -1.0f);
}

TEST(Interpreter, CmpCndLrp) {
  Program p;
  // cmp: s0 >= 0 ? s1 : s2 with s0 = 0 -> s1 (=2)
  p.emit(Op::Cmp, dst(RegFile::Output, 0, 0x1), p.imm({0, 0, 0, 0}), p.imm({2, 2, 2, 2}), p.imm({3, 3, 3, 3}));
  // cnd: s0 > 0.5 ? s1 : s2 with s0 = 0.5 -> s2 (=3)
  p.emit(Op::Cnd, dst(RegFile::Output, 0, 0x2), p.imm({0.5f, 0.5f, 0.5f, 0.5f}), p.imm({2, 2, 2, 2}), p.imm({3, 3, 3, 3}));
  // lrp: 0.25*4 + 0.75*8 = 7
  p.emit(Op::Lrp, dst(RegFile::Output, 0, 0x4), p.imm({0.25f, 0.25f, 0.25f, 0.25f}), p.imm({4, 4, 4, 4}), p.imm({8, 8, 8, 8}));
  Vec4 r = run1(p, {});
  EXPECT_FLOAT_EQ(r.x, 2);
  EXPECT_FLOAT_EQ(r.y, 3);
  EXPECT_FLOAT_EQ(r.z, 7);
}

TEST(Interpreter, KillClearsLanes) {
  Program p;
  p.inputCount = 1;
  p.outputCount = 1;
  p.emit(Op::Kill, dst(RegFile::Temp, 0, 0x7), reg(RegFile::Input, 0));
  BatchRegisters regs;
  regs.resize(p);
  for (int l = 0; l < kBatchLanes; ++l)
    for (int c = 0; c < 4; ++c) regs.inputs[0].c[c][l] = (c == 1 && (l % 4) == 1) ? -0.1f : 0.2f;
  ExecContext ctx;
  execute(p, ctx, regs);
  // lanes 1, 5, 9, 13 have y < 0
  EXPECT_EQ(regs.laneMask, uint16_t(0xffff & ~0x2222));
}

TEST(Interpreter, TexCallsSamplerWithProjectedCoordinates) {
  Program p;
  p.inputCount = 1;
  p.outputCount = 1;
  p.emit(Op::TexProj, dst(RegFile::Output, 0), reg(RegFile::Input, 0)).sampler = 0;
  BatchRegisters regs;
  regs.resize(p);
  for (int l = 0; l < kBatchLanes; ++l) {
    regs.inputs[0].c[0][l] = 1.0f;
    regs.inputs[0].c[1][l] = 3.0f;
    regs.inputs[0].c[2][l] = 0.0f;
    regs.inputs[0].c[3][l] = 4.0f;
  }
  SamplerBinding b;
  b.sample = [](const void*, SampleMode, const float (*co)[kBatchLanes], uint16_t,
                float (*out)[kBatchLanes]) {
    for (int l = 0; l < kBatchLanes; ++l) {
      out[0][l] = co[0][l];
      out[1][l] = co[1][l];
      out[2][l] = 0;
      out[3][l] = 1;
    }
  };
  ExecContext ctx;
  ctx.samplers = &b;
  ctx.samplerCount = 1;
  execute(p, ctx, regs);
  // (1,3)/4 = (0.25, 0.75)
  EXPECT_FLOAT_EQ(regs.outputs[0].c[0][7], 0.25f);
  EXPECT_FLOAT_EQ(regs.outputs[0].c[1][7], 0.75f);
}

}  // namespace
