// Flow control (rep, loop/aL, if/else, ifc, break/breakc/breakp, call/callnz/ret),
// predicates and relative addressing with aL: per-lane execution masks, one dispatch
// per instruction per batch, and the bound on executed instructions.
#include "shader_probe.h"

using namespace probe;

namespace {

constexpr int kPos = kVertexOutPosition, kD0 = kVertexOutDiffuse, kT0 = kVertexOutTex0;

TEST(ShaderFlow, RepWithLocalAndApiCounts) {
  auto r = asmRun(R"(vs_2_0
    defi i0, 3, 0, 0, 0
    mov r0, c1
    rep i0
      add r0, r0, c0
    endrep
    rep i1
      add r0.y, r0.y, c0.y
    endrep
    mov oPos, r0
  )");
  r.ints[1] = {5, 0, 0, 0};  // API i1
  r.constant(0, {1, 1, 1, 1}).execute();
  // x: 3 passes; y: 3 + 5 passes
  expectNear(r.output(kPos), {3, 8, 3, 3});
  EXPECT_TRUE(r.lowered.program.flowControl);
}

TEST(ShaderFlow, RepZeroSkipsTheBody) {
  auto r = asmRun("vs_2_0\nmov r0, c1\nrep i0\nadd r0, r0, c0\nendrep\nmov oPos, r0\n");
  r.ints[0] = {0, 0, 0, 0};
  r.constant(0, {1, 1, 1, 1}).constant(1, {7, 7, 7, 7}).execute();
  expectNear(r.output(kPos), {7, 7, 7, 7});
}

TEST(ShaderFlow, LoopCounterIndexesConstants) {
  // defi i0, 3, 10, 2, 0: aL = 10, 12, 14
  auto r = asmRun(R"(vs_2_0
    defi i0, 3, 10, 2, 0
    mov r0, c0
    loop aL, i0
      add r0, r0, c[aL]
    endloop
    mov oPos, r0
  )");
  for (int c = 10; c <= 15; ++c) r.constant(c, {float(c), float(c), float(c), float(c)});
  r.execute();
  expectNear(r.output(kPos), {36, 36, 36, 36});  // 10 + 12 + 14
}

TEST(ShaderFlow, NestedLoopsRestoreTheOuterCounter) {
  auto r = asmRun(R"(vs_3_0
    dcl_position o0
    defi i0, 2, 1, 1, 0
    defi i1, 3, 0, 0, 0
    mov r0, c0
    loop aL, i0
      rep i1
        add r0.x, r0.x, c[aL].x
      endrep
      add r0.y, r0.y, c[aL].y
    endloop
    mov o0, r0
  )");
  r.constant(1, {1, 10, 0, 0}).constant(2, {100, 1000, 0, 0}).execute();
  // outer aL = 1, 2: x += 3*c[aL].x = 3 + 300; y += c1.y + c2.y = 1010
  expectNear(r.output(kPos), {303, 1010, 0, 0});
}

TEST(ShaderFlow, BreakcPerLane) {
  auto r = asmRun(R"(vs_2_x
    dcl_position v0
    defi i0, 10, 0, 0, 0
    mov r0, c1
    rep i0
      add r0, r0, c0
      break_ge r0.x, v0.x
    endrep
    mov oPos, r0
  )");
  r.constant(0, {1, 1, 1, 1});
  r.setInput(0, 0, {3, 0, 0, 0}).setInput(0, 1, {5, 0, 0, 0}).setInput(0, 2, {100, 0, 0, 0});
  r.execute();
  // each lane stops when r0.x >= its threshold; lane 2 runs all 10 passes
  EXPECT_FLOAT_EQ(r.output(kPos, 0).x, 3);
  EXPECT_FLOAT_EQ(r.output(kPos, 1).x, 5);
  EXPECT_FLOAT_EQ(r.output(kPos, 2).x, 10);
}

TEST(ShaderFlow, BreakInsideIfAndUnconditionalBreak) {
  auto r = asmRun(R"(vs_2_x
    dcl_position v0
    defi i0, 10, 0, 0, 0
    defi i1, 4, 0, 0, 0
    mov r0, c1
    rep i0
      add r0.x, r0.x, c0.x
      if_ge r0.x, v0.x
        add r0.y, r0.y, c0.y
        break
      endif
      add r0.z, r0.z, c0.z
    endrep
    rep i1
      add r0.w, r0.w, c0.w
      break
    endrep
    mov oPos, r0
  )");
  r.constant(0, {1, 1, 1, 1});
  r.setInput(0, 0, {2, 0, 0, 0}).setInput(0, 1, {4, 0, 0, 0});
  r.execute();
  // lane 0: x reaches 2 in pass 2 (z counted once); lane 1: x = 4, z = 3; w: one pass
  expectNear(r.output(kPos, 0), {2, 1, 1, 1});
  expectNear(r.output(kPos, 1), {4, 1, 3, 1});
}

TEST(ShaderFlow, IfElsePerLaneAndOnBools) {
  auto r = asmRun(R"(vs_2_x
    dcl_position v0
    if_lt v0.x, c0.x
      mov r0, c1
    else
      mov r0, c2
    endif
    if b0
      add r0.y, r0.y, c3.y
    endif
    if !b1
      add r0.z, r0.z, c3.z
    else
      add r0.w, r0.w, c3.w
    endif
    mov oPos, r0
  )");
  r.bools[0] = true;
  r.bools[1] = true;
  r.constant(0, {0.5f, 0, 0, 0}).constant(1, {1, 1, 1, 1}).constant(2, {2, 2, 2, 2}).constant(3, {0, 10, 100, 1000});
  r.setInput(0, 0, {0, 0, 0, 0}).setInput(0, 1, {1, 0, 0, 0});
  r.execute();
  // lane 0: x < 0.5 → c1; b0 → y += 10; b1 true → else: w += 1000
  expectNear(r.output(kPos, 0), {1, 11, 1, 1001});
  expectNear(r.output(kPos, 1), {2, 12, 2, 1002});
}

TEST(ShaderFlow, PredicatesSetpPredicatedWritesIfpAndBreakp) {
  auto r = asmRun(R"(vs_2_x
    dcl_position v0
    defi i0, 8, 0, 0, 0
    setp_gt p0, v0, c0
    mov r0, c1
    (p0) mov r0, c2
    (!p0.x) add r0.x, r0.x, c3.x
    mov r1, c1
    if p0.y
      mov r1.y, c2.y
    endif
    mov r2, c1
    rep i0
      add r2.x, r2.x, c3.x
      setp_ge p0.z, r2.x, v0.z
      breakp p0.z
    endrep
    mov oPos, r0
    mov oD0, r1
    mov oT0, r2
  )");
  r.constant(0, {0, 0, 0, 0}).constant(1, {0, 0, 0, 0}).constant(2, {5, 5, 5, 5}).constant(3, {1, 1, 1, 1});
  r.input(0, {1, -1, 3, -1}).execute();
  // p0 = v0 > 0 = (T, F, T, F): r0 = (5, 0, 5, 0); x true so no add
  expectNear(r.output(kPos), {5, 0, 5, 0});
  // p0.y false: r1.y stays 0
  expectNear(r.output(kD0), {0, 0, 0, 0});
  // loop runs until r2.x >= v0.z = 3
  EXPECT_FLOAT_EQ(r.output(kT0).x, 3);
}

TEST(ShaderFlow, CallCallnzRet) {
  auto r = asmRun(R"(vs_2_x
    dcl_position v0
    mov r0, c1
    call l0
    call l0
    callnz l1, b0
    callnz l1, !b0
    setp_gt p0.x, v0.x, c1.x
    callnz l2, p0.x
    mov oPos, r0
    ret
    label l0
      add r0.x, r0.x, c0.x
      ret
    label l1
      add r0.y, r0.y, c0.y
      ret
    label l2
      add r0.z, r0.z, c0.z
      ret
  )");
  r.bools[0] = false;
  r.constant(0, {1, 10, 100, 0}).constant(1, {0, 0, 0, 0});
  r.setInput(0, 0, {1, 0, 0, 0}).setInput(0, 1, {-1, 0, 0, 0});
  r.execute();
  // l0 twice; l1 once (!b0); l2 only where v0.x > 0
  expectNear(r.output(kPos, 0), {2, 10, 100, 0});
  expectNear(r.output(kPos, 1), {2, 10, 0, 0});
}

TEST(ShaderFlow, RunawayLoopsAreBounded) {
  // 255^4 passes would never finish; execution stops after kMaxExecutedInstructions.
  auto r = asmRun(R"(vs_3_0
    dcl_position o0
    defi i0, 255, 0, 0, 0
    mov r0, c1
    rep i0
      rep i0
        rep i0
          rep i0
            add r0, r0, c0
          endrep
        endrep
      endrep
    endrep
    mov o0, r0
  )");
  r.constant(0, {1, 1, 1, 1});
  r.execute();
  // The run stops exactly when the budget is spent, not after all 255^4 passes.
  EXPECT_EQ(r.regs.executedInstructions, kMaxExecutedInstructions);
  // Fewer passes than the instruction budget; the final mov is never reached.
  EXPECT_LT(r.temp(0).x, float(kMaxExecutedInstructions));
  EXPECT_GT(r.temp(0).x, 1000.0f);
}

TEST(ShaderFlow, ALoopThatEndsStaysUnderTheInstructionBound) {
  // 255 passes of a one-instruction body: a few instructions a pass, well under the bound.
  auto r = asmRun("vs_2_0\ndefi i0, 255, 0, 0, 0\nmov r0, c1\nrep i0\nadd r0, r0, c0\nendrep\nmov oPos, r0\n");
  r.constant(0, {1, 1, 1, 1}).execute();
  expectNear(r.output(kPos), {255, 255, 255, 255});
  EXPECT_GE(r.regs.executedInstructions, 2 * 255);  // at least the add and the endrep a pass
  EXPECT_LT(r.regs.executedInstructions, 8 * 255);
}

TEST(ShaderFlow, LoopCountsAreLimitedTo255) {
  auto r = asmRun("vs_2_0\nmov r0, c1\nrep i0\nadd r0, r0, c0\nendrep\nmov oPos, r0\n");
  r.ints[0] = {100000, 0, 0, 0};
  r.constant(0, {1, 1, 1, 1}).execute();
  expectNear(r.output(kPos), {255, 255, 255, 255});
}

TEST(ShaderFlow, RelativeOutputsAndInputsWithAL) {
  auto r = asmRun(R"(vs_3_0
    dcl_position v0
    dcl_texcoord0 v1
    dcl_texcoord1 v2
    dcl_position o0
    dcl_texcoord0 o1
    dcl_texcoord1 o2
    defi i0, 2, 1, 1, 0
    mov o0, v0
    loop aL, i0
      mov o[aL], v[aL]
    endloop
  )");
  r.input(1, {1, 1, 1, 1}).input(2, {2, 2, 2, 2}).execute();
  expectNear(r.output(kT0), {1, 1, 1, 1});
  expectNear(r.output(kT0 + 1), {2, 2, 2, 2});
}

TEST(ShaderFlow, MalformedBlocksAreErrors) {
  EXPECT_THROW(asmRun("vs_2_0\nendrep\n"), refx::Error);
  EXPECT_THROW(asmRun("vs_2_0\nrep i0\nmov r0, c0\n"), refx::Error);
  EXPECT_THROW(asmRun("vs_2_0\nif b0\nendloop\n"), refx::Error);
  EXPECT_THROW(asmRun("vs_2_0\ncall l3\nret\n"), refx::Error);
  EXPECT_THROW(asmRun("vs_2_x\nbreak\n"), refx::Error);
}

}  // namespace
