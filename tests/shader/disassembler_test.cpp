// Disassembly text of hand-written token streams (bytecode.md §11 and the field
// tables): the expected text is the D3D assembler syntax for those tokens.
#include <gtest/gtest.h>

#include <cstring>

#include "refx/core/diagnostics.h"
#include "refx/shader/disassembler.h"

using namespace refx::shader;

namespace {

std::string dis(std::vector<uint32_t> tokens, bool listing = false) {
  DisassemblyOptions o;
  o.listing = listing;
  return disassemble(tokens, o);
}

}  // namespace

TEST(Disassembler, Vs11) {
  // bytecode.md §11: dcl_position v0, m4x4 oPos, v0, c0, mov r0.xy, -c[a0.x+3].yzzz.
  EXPECT_EQ(dis({0xFFFE0101, 0x0000001F, 0x80000000, 0x900F0000, 0x00000014, 0xC00F0000, 0x90E40000, 0xA0E40000,
                 0x00000001, 0x80030000, 0xA1A92003, 0x0000FFFF}),
            "vs_1_1\n"
            "dcl_position v0\n"
            "m4x4 oPos, v0, c0\n"
            "mov r0.xy, -c[a0.x+3].yz\n");  // .yzzz: the repeated last letter is implied
}

TEST(Disassembler, FullMaskOfMatrixMacrosIsWrittenOut) {
  // m3x3 r0, v3, c0 with mask .xyzw (0x800F0000) and m3x2 r1.xy: without a mask the
  // assembler writes .xyz / .xy for these macros, so only the full mask is spelled out.
  EXPECT_EQ(dis({0xFFFE0101, 0x00000017, 0x800F0000, 0x90E40003, 0xA0E40000, 0x00000018,
                 0x80030001, 0x90E40003, 0xA0E40000, 0x0000FFFF}),
            "vs_1_1\n"
            "m3x3 r0.xyzw, v3, c0\n"
            "m3x2 r1.xy, v3, c0\n");
}

TEST(Disassembler, Ps11) {
  // def c0, 1, 0.5, 0, -1; tex t0; mul_x2 r0.rgb, t0, v0; +mov r0.a, t0 (co-issue).
  EXPECT_EQ(dis({0xFFFF0101, 0x00000051, 0xA00F0000, 0x3F800000, 0x3F000000, 0x00000000, 0xBF800000,
                 0x00000042, 0xB00F0000, 0x00000005, 0x81070000, 0xB0E40000, 0x90E40000, 0x40000001, 0x80080000,
                 0xB0E40000, 0x0000FFFF}),
            "ps_1_1\n"
            "def c0, 1, 0.5, 0, -1\n"
            "tex t0\n"
            "mul_x2 r0.xyz, t0, v0\n"
            "+mov r0.w, t0\n");
}

TEST(Disassembler, SourceModifiers) {
  // mov r0, <r1 with modifier code m> in ps_1_4 (swizzle .w = 0xFF for a selector).
  const std::pair<uint32_t, const char*> mods[] = {
      {0x80E40001, "r1"},        {0x81E40001, "-r1"},       {0x82E40001, "r1_bias"}, {0x83E40001, "-r1_bias"},
      {0x84E40001, "r1_bx2"},    {0x85E40001, "-r1_bx2"},   {0x86E40001, "1-r1"},    {0x87E40001, "r1_x2"},
      {0x88E40001, "-r1_x2"},    {0x89E40001, "r1_dz"},     {0x8AE40001, "r1_dw"},   {0x8BE40001, "r1_abs"},
      {0x8CE40001, "-r1_abs"},   {0x86FF0001, "1-r1.w"},    {0x84FF0001, "r1_bx2.w"},
  };
  for (auto [tok, text] : mods)
    EXPECT_EQ(dis({0xFFFF0104, 0x00000001, 0x800F0000, tok, 0x0000FFFF}), std::string("ps_1_4\nmov r0, ") + text + "\n");
  // !b0 on if (vs_2_0): NOT = 13.
  EXPECT_EQ(dis({0xFFFE0200, 0x01000028, 0xEDE40800, 0x0000002B, 0x0000FFFF}), "vs_2_0\nif !b0\nendif\n");
}

TEST(Disassembler, InstructionModifiers) {
  // _x4 (2), _d2 (0xF), _d8 (0xD), _x8 (3) with _sat (ps_1_4).
  const std::pair<uint32_t, const char*> shifts[] = {
      {0x820F0000, "mov_x4 r0"}, {0x8F0F0000, "mov_d2 r0"}, {0x8D0F0000, "mov_d8 r0"},
      {0x8E0F0000, "mov_d4 r0"}, {0x831F0000, "mov_x8_sat r0"}, {0x81170000, "mov_x2_sat r0.xyz"}};
  for (auto [tok, text] : shifts)
    EXPECT_EQ(dis({0xFFFF0104, 0x00000001, tok, 0x80E40001, 0x0000FFFF}), std::string("ps_1_4\n") + text + ", r1\n");
  // ps_2_0: add_sat, _pp, dcl_centroid t0, dcl_pp t1.xy.
  EXPECT_EQ(dis({0xFFFF0200, 0x0200001F, 0x80000000, 0xB04F0000, 0x0200001F, 0x80000000, 0xB0230001,
                 0x03000002, 0x801F0000, 0x80E40001, 0xA0E40000, 0x02000001, 0x802F0800, 0x80E40000, 0x0000FFFF}),
            "ps_2_0\n"
            "dcl_centroid t0\n"
            "dcl_pp t1.xy\n"
            "add_sat r0, r1, c0\n"
            "mov_pp oC0, r0\n");
}

TEST(Disassembler, Swizzles) {
  // Shortest text that re-expands to the same swizzle: xxxx .x, xyyy .xy, xyzz .xyz,
  // wzyx .wzyx, xyzw (none), yyyy .y, xxxy .xxxy.
  const std::pair<uint32_t, const char*> swz[] = {{0x00, ".x"},   {0x54, ".xy"},   {0xA4, ".xyz"}, {0x1B, ".wzyx"},
                                                 {0xE4, ""},      {0x55, ".y"},     {0x40, ".xxxy"}, {0xFF, ".w"}};
  for (auto [s, text] : swz)
    EXPECT_EQ(dis({0xFFFE0101, 0x00000001, 0x800F0000, 0x80000001u | s << 16, 0x0000FFFF}),
              std::string("vs_1_1\nmov r0, r1") + text + "\n");
}

TEST(Disassembler, Sm2Sm3Forms) {
  EXPECT_EQ(dis({0xFFFF0200, 0x0200001F, 0x90000000, 0xA00F0800, 0x0200001F, 0x98000000, 0xA00F0801,
                 0x0200001F, 0xA0000000, 0xA00F0802, 0x03000042, 0x800F0000, 0xB0E40000, 0xA0E40800, 0x03010042,
                 0x800F0000, 0xB0E40000, 0xA0E40801, 0x03020042, 0x800F0000, 0xB0E40000, 0xA0E40802, 0x0000FFFF}),
            "ps_2_0\n"
            "dcl_2d s0\n"
            "dcl_cube s1\n"
            "dcl_volume s2\n"
            "texld r0, t0, s0\n"
            "texldp r0, t0, s1\n"
            "texldb r0, t0, s2\n");
  // vs_2_0: dcl_texcoord1 v2, mov r0, c[a0.y+5], mov r0, c[aL+2], mov r0, c[aL].
  EXPECT_EQ(dis({0xFFFE0200, 0x0200001F, 0x80010005, 0x900F0002, 0x03000001, 0x800F0000, 0xA0E42005, 0xB0550000,
                 0x03000001, 0x800F0000, 0xA0E42002, 0xF0E40800, 0x03000001, 0x800F0000, 0xA0E42000, 0xF0E40800,
                 0x0000FFFF}),
            "vs_2_0\n"
            "dcl_texcoord1 v2\n"
            "mov r0, c[a0.y+5]\n"
            "mov r0, c[aL+2]\n"
            "mov r0, c[aL]\n");
  // vs_3_0: dcl_texcoord3 o4.xy, mov o[aL+1], r0, defi, defb, loop, setp_ge, predicated texldl.
  EXPECT_EQ(dis({0xFFFE0300, 0x0200001F, 0x80030005, 0xE0030004, 0x05000030, 0xF00F0000, 1, 0xFFFFFFFE, 3, 255,
                 0x0200002F, 0xE00F0801, 1, 0x0200002F, 0xE00F0802, 0, 0x0200001B, 0xF0E40800, 0xF0E40000,
                 0x03000001, 0xE00F2001, 0xF0E40800, 0x80E40000, 0x0000001D, 0x0303005E, 0xB00F1000, 0x80E40000,
                 0x80E40001, 0x13000001, 0x800F0000, 0xBD001000, 0x80E40001, 0x0000FFFF}),
            "vs_3_0\n"
            "dcl_texcoord3 o4.xy\n"
            "defi i0, 1, -2, 3, 255\n"
            "defb b1, true\n"
            "defb b2, false\n"
            "loop aL, i0\n"
            "mov o[aL+1], r0\n"
            "endloop\n"
            "setp_ge p0, r0, r1\n"
            "(!p0.x) mov r0, r1\n");
  // ps_3_0: dcl vPos.xy, dcl vFace, dcl_texcoord2_centroid v1.xy, dcl_color v0, if_lt, break_ne, breakp.
  EXPECT_EQ(dis({0xFFFF0300, 0x0200001F, 0x80000000, 0x90031000, 0x0200001F, 0x80000000, 0x900F1001,
                 0x0200001F, 0x80020005, 0x90430001, 0x0200001F, 0x8000000A, 0x900F0000, 0x02040029, 0x80000000,
                 0x80550001, 0x01000026, 0xF0E40001, 0x0205002D, 0x90001001, 0x8BAA0001, 0x01000060, 0xBDFF1000,
                 0x00000027, 0x0000002B, 0x14000002, 0x800F0000, 0xB0E41000, 0x90E40001, 0x90E40000, 0x0000FFFF}),
            "ps_3_0\n"
            "dcl vPos.xy\n"
            "dcl vFace\n"
            "dcl_texcoord2_centroid v1.xy\n"
            "dcl_color v0\n"
            "if_lt r0.x, r1.y\n"
            "rep i1\n"
            "break_ne vFace.x, r1_abs.z\n"
            "breakp !p0.w\n"
            "endrep\n"
            "endif\n"
            "(p0) add r0, v1, v0\n");
  // Constants above c2047 (CONST2 bank).
  EXPECT_EQ(dis({0xFFFE0300, 0x02000001, 0x800F0000, 0xB0E40801, 0x0000FFFF}), "vs_3_0\nmov r0, c2049\n");
}

TEST(Disassembler, Ps1xTextureForms) {
  // ps_1_4: texld r0, t0_dz.xyz; texcrd r1.xyz, t1; phase; texld r1, r1; ps_1_1 texcoord/texkill.
  EXPECT_EQ(dis({0xFFFF0104, 0x00000042, 0x800F0000, 0xB9A40000, 0x00000040, 0x80070001, 0xB0E40001, 0x0000FFFD,
                 0x00000042, 0x800F0001, 0x80E40001, 0x0000FFFF}),
            "ps_1_4\n"
            "texld r0, t0_dz.xyz\n"
            "texcrd r1.xyz, t1\n"
            "phase\n"
            "texld r1, r1\n");
  EXPECT_EQ(dis({0xFFFF0101, 0x00000040, 0xB00F0001, 0x00000041, 0xB00F0000, 0x0000004C, 0xB00F0003, 0xB0E40000,
                 0xA0E40000, 0x0000FFFF}),
            "ps_1_1\n"
            "texcoord t1\n"
            "texkill t0\n"
            "texm3x3spec t3, t0, c0\n");
}

TEST(Disassembler, FloatLiteralsRoundTrip) {
  // Fewest digits that read back to the same float: 0.1f = 0x3DCCCCCD prints "0.1";
  // 1/3 = 0x3EAAAAAB needs 8 (0.3333333 reads back as 0x3EAAAAAA); -0 keeps its sign; 1e-10 uses an exponent.
  EXPECT_EQ(dis({0xFFFE0101, 0x00000051, 0xA00F0005, 0x3DCCCCCD, 0x3EAAAAAB, 0x80000000, 0x2EDBE6FF, 0x0000FFFF}),
            "vs_1_1\ndef c5, 0.1, 0.33333334, -0, 1e-10\n");
}

TEST(Disassembler, CommentsAreDroppedFromText) {
  EXPECT_EQ(dis({0xFFFE0101, 0x0002FFFE, 0x47554244, 0x12345678, 0x00000000, 0x0000FFFF}), "vs_1_1\nnop\n");
}

namespace {

// A CTAB comment for: float4x4 WorldViewProj (c0, 4 registers, column-major) and
// sampler2D Base (s0, 1). Offsets are relative to the header (after 'CTAB').
std::vector<uint32_t> ctabComment() {
  std::vector<uint8_t> b(28 + 2 * 20 + 2 * 16, 0);
  auto put32 = [&](size_t off, uint32_t v) { std::memcpy(&b[off], &v, 4); };
  auto put16 = [&](size_t off, uint16_t v) { std::memcpy(&b[off], &v, 2); };
  auto str = [&](const char* s) {
    size_t off = b.size();
    b.insert(b.end(), s, s + std::strlen(s) + 1);
    return uint32_t(off);
  };
  const uint32_t info = 28, type0 = 28 + 40, type1 = type0 + 16;
  put32(0, 28);
  put32(12, 2);
  put32(16, info);
  put32(8, 0xFFFE0200);
  uint32_t name0 = str("WorldViewProj"), name1 = str("Base"), creator = str("refx test"), target = str("vs_2_0");
  put32(4, creator);
  put32(24, target);
  put32(info + 0, name0);
  put16(info + 4, 2);  // FLOAT4
  put16(info + 6, 0);
  put16(info + 8, 4);
  put32(info + 12, type0);
  put32(info + 20, name1);
  put16(info + 24, 3);  // SAMPLER
  put16(info + 26, 0);
  put16(info + 28, 1);
  put32(info + 32, type1);
  put16(type0 + 0, 3);  // MATRIX_COLUMNS
  put16(type0 + 2, 3);  // FLOAT
  put16(type0 + 4, 4);
  put16(type0 + 6, 4);
  put16(type0 + 8, 1);
  put16(type1 + 0, 4);   // OBJECT
  put16(type1 + 2, 12);  // SAMPLER2D
  put16(type1 + 4, 1);
  put16(type1 + 6, 1);
  put16(type1 + 8, 1);
  while (b.size() % 4) b.push_back(0);
  std::vector<uint32_t> words(b.size() / 4);
  std::memcpy(words.data(), b.data(), b.size());
  std::vector<uint32_t> out = {uint32_t(0xFFFE | (words.size() + 1) << 16), 0x42415443};
  out.insert(out.end(), words.begin(), words.end());
  return out;
}

}  // namespace

TEST(Disassembler, ListingShowsConstantTable) {
  std::vector<uint32_t> t = {0xFFFE0200};
  std::vector<uint32_t> c = ctabComment();
  t.insert(t.end(), c.begin(), c.end());
  for (uint32_t w : std::initializer_list<uint32_t>{0x0200001F, 0x80000000, 0x900F0000, 0x03000014, 0xC00F0000, 0x90E40000, 0xA0E40000, 0x0000FFFF})
    t.push_back(w);
  std::string text = dis(t, true);
  EXPECT_NE(text.find("// Generated by refx test\n"), std::string::npos) << text;
  EXPECT_NE(text.find("//   float4x4 WorldViewProj;\n"), std::string::npos) << text;
  EXPECT_NE(text.find("//   sampler2D Base;\n"), std::string::npos) << text;
  EXPECT_NE(text.find("//   WorldViewProj c0       4\n"), std::string::npos) << text;
  EXPECT_NE(text.find("//   Base          s0       1\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\n    vs_2_0\n    dcl_position v0\n    m4x4 oPos, v0, c0\n"), std::string::npos) << text;
  // Without the listing the CTAB comment leaves no trace.
  EXPECT_EQ(dis(t), "vs_2_0\ndcl_position v0\nm4x4 oPos, v0, c0\n");
  // A truncated CTAB (offsets past the end) is not an error.
  t[1] = 0xFFFE | 3u << 16;
  std::vector<uint32_t> cut = {t[0], 0x0003FFFE, 0x42415443, 28, 0xFFFFFF00, 0x0000FFFF};
  EXPECT_NO_THROW(dis(cut, true));
}

TEST(Disassembler, BadTokensAreErrors) {
  EXPECT_THROW(dis({0xFFFE0101, 0x00000001, 0x800F0000}), refx::Error);
}

TEST(Disassembler, ListingSlotLine) {
  // ps_1_1: tex t0 (1 texture slot), mul r0, t0, v0 and mad (1 arithmetic slot each).
  std::string ps = dis({0xFFFF0101, 0x00000042, 0xB00F0000, 0x00000005, 0x800F0000, 0xB0E40000, 0x90E40000,
                        0x00000004, 0x800F0000, 0x80E40000, 0x90E40000, 0xB0E40000, 0x0000FFFF},
                       true);
  EXPECT_NE(ps.find("\n// approximately 3 instruction slots used (1 texture, 2 arithmetic)\n"), std::string::npos) << ps;
  // vs_1_1: m4x4 is a 4-slot macro, dcl costs nothing, mov 1 slot: 5.
  std::string vs = dis({0xFFFE0101, 0x0000001F, 0x80000000, 0x900F0000, 0x00000014, 0xC00F0000, 0x90E40000,
                        0xA0E40000, 0x00000001, 0xD00F0000, 0x90E40000, 0x0000FFFF},
                       true);
  EXPECT_NE(vs.find("\n// approximately 5 instruction slots used\n"), std::string::npos) << vs;
}
