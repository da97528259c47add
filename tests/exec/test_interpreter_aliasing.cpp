// Results written straight to the destination register versus staged when the
// destination is also a source (swizzled self-reads see the old values), and
// prepared programs against per-instruction decoding.
#include <gtest/gtest.h>

#include <cstring>
#include <iterator>
#include <random>

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

// Random programs give bit-identical registers whether run decoded per instruction
// or prepared (resolved operands, specialised routines).
TEST(InterpreterPrepared, MatchesPerInstructionDecoding) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<float> val(-3.0f, 3.0f);
  const Op ops[] = {Op::Mov, Op::Add, Op::Sub, Op::Mul, Op::Mad, Op::Min, Op::Max, Op::Lrp,
                    Op::Cmp, Op::Dp3, Op::Dp4, Op::Rcp, Op::Frc, Op::Slt, Op::Abs, Op::Kill};
  const RegFile files[] = {RegFile::Temp, RegFile::Input, RegFile::Const, RegFile::Imm};
  std::vector<Vec4> constants(4);
  for (auto& c : constants) c = {val(rng), val(rng), val(rng), val(rng)};
  for (int iter = 0; iter < 500; ++iter) {
    Program p;
    p.tempCount = 3, p.inputCount = 2, p.outputCount = 2;
    for (int i = 0; i < 4; ++i) p.imm({val(rng), val(rng), val(rng), val(rng)});
    const int count = 1 + int(rng() % 8);
    for (int k = 0; k < count; ++k) {
      auto src = [&] {
        Src s;
        s.file = files[rng() % 4];
        s.index = uint16_t(rng() % (s.file == RegFile::Input ? 2 : s.file == RegFile::Temp ? 3 : 4));
        s.swizzle = uint8_t(rng());
        s.mod = rng() % 3 == 0 ? SrcMod(rng() % 11) : SrcMod::None;
        return s;
      };
      const bool toOutput = rng() % 3 == 0;
      Instr& in = p.emit(ops[rng() % std::size(ops)],
                         dst(toOutput ? RegFile::Output : RegFile::Temp, int(rng() % (toOutput ? 2 : 3)),
                             uint8_t(1 + rng() % 15)),
                         src(), src(), src());
      in.saturate = rng() % 3 == 0;
      in.shift = int8_t(rng() % 4 == 0 ? int(rng() % 5) - 2 : 0);
      in.clamp = !in.saturate && rng() % 5 == 0;
      in.clampLo = -1, in.clampHi = 1;
    }
    BatchRegisters a;
    a.resize(p);
    for (auto* file : {&a.temps, &a.inputs, &a.outputs})
      for (auto& r : *file)
        for (int c = 0; c < 4; ++c)
          for (int l = 0; l < kBatchLanes; ++l) r.c[c][l] = val(rng);
    BatchRegisters b = a;
    ExecContext ctx;
    ctx.constants = constants.data();
    ctx.constantCount = int(constants.size());
    execute(p, ctx, a);
    prepare(p, ctx, b);
    execute(p, ctx, b);
    ASSERT_EQ(a.laneMask, b.laneMask) << iter;
    auto same = [](const std::vector<LaneVec4>& x, const std::vector<LaneVec4>& y) {
      return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(LaneVec4)) == 0;
    };
    ASSERT_TRUE(same(a.temps, b.temps)) << iter << "\n" << listProgram(p);
    ASSERT_TRUE(same(a.outputs, b.outputs)) << iter << "\n" << listProgram(p);
  }
}

}  // namespace
