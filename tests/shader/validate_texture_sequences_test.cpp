// Texture-sequence check (ps_1_1 – ps_1_3): texture instructions write t
// registers in increasing order, each once, from lower t registers a texture
// instruction wrote; texm3x2pad is followed by texm3x2tex (or texm3x2depth, ps_1_3) and
// texm3x3pad by a second pad and texm3x3tex/spec/vspec (texm3x3, ps_1_2) on the next
// registers with the same source; pad destinations hold no color; a register
// texbem/texbeml read is read afterwards only by them; _bx2 is the only source
// modifier, and not on texbem/texreg2ar/texreg2gb sources (ps_1_1: only on the matrix
// instructions).
#include "shader/validator_test_util.h"

namespace refx::shader {
namespace {

using namespace validator_test;

TEST(ValidatorPs11, TextureRegisterOrder) {
  EXPECT_TRUE(hasError("ps_1_1\ntex t1\ntex t0\nmul r0, t0, t1",
                       "texture instructions must use t registers in increasing order: t0 comes after t1"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntex t0\nmov r0, t0", "t0 is already the destination of a texture instruction"));
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\ntexbem t1, t0\nmov r0, t1"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t1\ntexbem t2, t0\nmov r0, t2", "t0 is read by texbem before a texture instruction writes it"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntex t1\ntexbem t1, t1\nmov r0, t1",
                       "texbem t1, t1: the source must be a lower t register than the destination"));
}

TEST(ValidatorPs11, MatrixSequences) {
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\ntexm3x3pad t1, t0_bx2\ntexm3x3pad t2, t0_bx2\ntexm3x3tex t3, t0_bx2\nmov r0, t3"));
  EXPECT_TRUE(isValid("ps_1_1\ndef c0, 0, 0, 1, 0\ntex t0\ntexm3x3pad t1, t0_bx2\ntexm3x3pad t2, t0_bx2\n"
                      "texm3x3spec t3, t0_bx2, c0\nmov r0, t3"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexm3x2pad t1, t0\nmov r0, t0",
                       "texm3x2pad t1, t0 must be followed by texm3x2tex t2, t0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexm3x2tex t1, t0\nmov r0, t1", "texm3x2tex must follow texm3x2pad"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntex t1\ntexm3x2pad t2, t0\ntexm3x2tex t3, t1\nmov r0, t3",
                       "texm3x2pad t2, t0 must be followed by texm3x2tex t3, t0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexm3x3pad t1, t0\ntexm3x3tex t2, t0\nmov r0, t2",
                       "texm3x3pad t1, t0 must be followed by a second texm3x3pad t2, t0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexm3x3pad t1, t0\ntexm3x3pad t2, t0\nmov r0, t0",
                       "texm3x3pad t2, t0 must be followed by texm3x3tex, texm3x3spec, texm3x3vspec t3, t0"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexm3x3tex t1, t0\nmov r0, t1", "texm3x3tex must follow two texm3x3pad instructions"));
  // The pad destination holds no data.
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexm3x2pad t1, t0\ntexm3x2tex t2, t0\nmul r0, t2, t1",
                       "t1 holds no data after texm3x2pad/texm3x3pad/texm3x2depth and cannot be read"));
  // texm3x2depth exists from ps_1_3 on.
  std::string depth = "tex t0\ntexm3x2pad t1, t0\ntexm3x2depth t2, t0\nmov r0, t0";
  EXPECT_TRUE(isValid("ps_1_3\n" + depth));
  EXPECT_TRUE(hasError("ps_1_2\n" + depth, "texm3x2depth is not a ps_1_2 instruction"));
}

TEST(ValidatorPs11, TexbemSourceIsReservedForTexbem) {
  EXPECT_TRUE(isValid("ps_1_1\ntex t0\ntexbem t1, t0\ntexbem t2, t0\nadd r0, t1, t2"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexbem t1, t0\nadd r0, t1, t0",
                       "t0 was read by texbem/texbeml and can afterwards be read only by texbem/texbeml"));
}

TEST(ValidatorPs11, TextureSourceModifiers) {
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexbem t1, t0_bx2\nmov r0, t1", "_bx2 is not allowed on the source of texbem in ps_1_1"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexreg2ar t1, t0_bx2\nmov r0, t1", "_bx2 is not allowed on the source of texreg2ar"));
  EXPECT_TRUE(isValid("ps_1_2\ntex t0\ntexdp3 t1, t0_bx2\nmov r0, t1"));
  EXPECT_TRUE(hasError("ps_1_1\ntex t0\ntexm3x2pad t1, t0_bias\ntexm3x2tex t2, t0\nmov r0, t2",
                       "texm3x2pad sources take no modifier other than _bx2"));
  EXPECT_TRUE(hasError("ps_1_1\ntex_sat t0\nmov r0, t0", "tex cannot take _sat"));
}

}  // namespace
}  // namespace refx::shader
