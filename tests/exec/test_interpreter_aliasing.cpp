// Results written straight to the destination register versus staged when the
// destination is also a source: swizzled self-reads must see the old values.
#include <gtest/gtest.h>

#include "refx/exec/interpreter.h"

using namespace refx;
using namespace refx::exec;

namespace {

struct Batch {
  BatchRegisters regs;
  explicit Batch(Program& p, Vec4 v0) {
    p.inputCount = std::max(p.inputCount, 1);
    p.outputCount = std::max(p.outputCount, 1);
    p.tempCount = std::max(p.tempCount, 1);
    regs.resize(p);
    for (int l = 0; l < kBatchLanes; ++l)
      for (int c = 0; c < 4; ++c) regs.inputs[0].c[c][l] = v0[c] + float(l);
    ExecContext ctx;
    execute(p, ctx, regs);
  }
  Vec4 out(int lane) const {
    return {regs.outputs[0].c[0][lane], regs.outputs[0].c[1][lane], regs.outputs[0].c[2][lane],
            regs.outputs[0].c[3][lane]};
  }
};

TEST(InterpreterAliasing, SwizzledSelfAddSeesOldValues) {
  Program p;
  p.emit(Op::Mov, dst(RegFile::Temp, 0), reg(RegFile::Input, 0));
  // r0.xy = r0.yx + r0.xy: both components from the old r0 = (1,2,.,.)+lane:
  // x = y + x, y = x + y = (1+l) + (2+l) = 3 + 2l
  p.emit(Op::Add, dst(RegFile::Temp, 0, 0x3), reg(RegFile::Temp, 0, swz(1, 0, 2, 3)),
         reg(RegFile::Temp, 0));
  p.emit(Op::Mov, dst(RegFile::Output, 0), reg(RegFile::Temp, 0));
  Batch r(p, {1, 2, 3, 4});
  for (int l : {0, 5, 15}) EXPECT_EQ(r.out(l), Vec4(3 + 2 * l, 3 + 2 * l, 3 + l, 4 + l)) << l;
}

TEST(InterpreterAliasing, DirectWriteAppliesSaturateAndShift) {
  Program p;
  // o0 = saturate(v0 * v0 * 2): lane 0 v0 = (-1, 0.25, 0.5, 2) -> 2*(1, 1/16, 1/4, 4)
  // = (2, 0.125, 0.5, 8) -> (1, 0.125, 0.5, 1)
  Instr& i = p.emit(Op::Mul, dst(RegFile::Output, 0), reg(RegFile::Input, 0), reg(RegFile::Input, 0));
  i.shift = 1;
  i.saturate = true;
  Batch r(p, {-1, 0.25f, 0.5f, 2});
  EXPECT_EQ(r.out(0), Vec4(1, 0.125f, 0.5f, 1));
}

TEST(InterpreterAliasing, SelfDotProductUsesOldComponents) {
  Program p;
  p.emit(Op::Mov, dst(RegFile::Temp, 0), reg(RegFile::Input, 0));
  // r0.xw = dp3(r0, r0): lane 0 r0 = (1,2,3,4): 1 + 4 + 9 = 14 in x and w; y, z unchanged
  p.emit(Op::Dp3, dst(RegFile::Temp, 0, 0x9), reg(RegFile::Temp, 0), reg(RegFile::Temp, 0));
  p.emit(Op::Mov, dst(RegFile::Output, 0), reg(RegFile::Temp, 0));
  Batch r(p, {1, 2, 3, 4});
  EXPECT_EQ(r.out(0), Vec4(14, 2, 3, 14));
}

}  // namespace
