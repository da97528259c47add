// Texture lookups run on whole 2x2 quads: the lanes of a quad outside the primitive
// (helper pixels) are sampled too, so a dependent read's derivatives are those of
// the surface and not of zeroed lanes.
#include "shader_probe.h"

namespace {

using namespace probe;

void expectQuadsSampled(bool usePrepare) {
  ShaderRun run = asmRun(R"(ps_2_0
dcl t0
dcl_2d s0
texld r0, t0, s0
mov oC0, r0
)");
  run.usePrepare = usePrepare;
  // Live lanes: lane 0 of quad 0 and lane 5 (quad 1, lane 1); quads 2 and 3 empty.
  run.regs.laneMask = 0x0021;
  run.execute();
  // Quads with a live lane are sampled whole: 0x000F | 0x00F0.
  EXPECT_EQ(run.fakes[0].lastMask, 0x00FF);
}

TEST(ShaderHelperLanes, TexldSamplesWholeQuads) { expectQuadsSampled(true); }
TEST(ShaderHelperLanes, TexldSamplesWholeQuadsUnprepared) { expectQuadsSampled(false); }

TEST(ShaderHelperLanes, Ps11TexSamplesWholeQuads) {
  ShaderRun run = asmRun("ps.1.1\ntex t0\nmov r0, t0\n");
  run.regs.laneMask = 0x8000;  // lane 15 only: quad 3
  run.execute();
  EXPECT_EQ(run.fakes[0].lastMask, 0xF000);
}

}  // namespace
