// Disassembly round trip over every shader source in the tree: assemble → encode →
// disassemble → assemble → encode must give the same tokens (issue: "bytecode → text
// that reassembles to the same bytes"). Sources that do not assemble in the first
// place (misprints kept verbatim from the articles) are counted and left to the
// assembler's own tests.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "refx/core/diagnostics.h"
#include "refx/shader/assembler.h"
#include "refx/shader/disassembler.h"

using namespace refx::shader;
namespace fs = std::filesystem;

namespace {

// Shader sources under data/shaders and tests/shader/asm that assemble today.
constexpr int kShaderSourcesThatAssemble = 64;

std::vector<fs::path> shaderSources() {
  std::vector<fs::path> files;
  for (const fs::path& dir : {fs::path(REFX_DATA_DIR) / "shaders", fs::path(REFX_TEST_DIR) / "shader" / "asm"}) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) continue;
    for (const auto& e : fs::recursive_directory_iterator(dir, ec)) {
      const std::string ext = e.path().extension().string();
      if (e.is_regular_file() && (ext == ".vsh" || ext == ".psh")) files.push_back(e.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string readText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(RoundTrip, EveryShaderSourceReassemblesToTheSameTokens) {
  int roundTripped = 0, notAssembled = 0;
  for (const fs::path& file : shaderSources()) {
    SCOPED_TRACE(file.string());
    std::vector<uint32_t> tokens;
    try {
      tokens = encode(assemble(readText(file), file.string()));
    } catch (const refx::Error& e) {
      ++notAssembled;
      std::cout << "  not assembled (first pass): " << e.what() << "\n";
      continue;
    }
    std::string text;
    try {
      text = disassemble(tokens);
    } catch (const refx::Error& e) {
      ADD_FAILURE() << "the assembler's tokens do not decode: " << e.what();
      continue;
    }
    std::vector<uint32_t> again;
    try {
      again = encode(assemble(text, file.filename().string() + " (disassembly)"));
    } catch (const refx::Error& e) {
      ADD_FAILURE() << "the disassembly does not assemble: " << e.what() << "\n" << text;
      continue;
    }
    EXPECT_EQ(again, tokens) << "disassembly:\n" << text;
    ++roundTripped;
  }
  std::cout << "round trip: " << roundTripped << " shader files reassembled, " << notAssembled
            << " did not assemble in the first place\n";
  // The tree holds this many shader sources that assemble; fewer means the search
  // above lost files (an empty glob must not pass).
  EXPECT_GE(roundTripped, kShaderSourcesThatAssemble);
  RecordProperty("roundTripped", roundTripped);
  RecordProperty("notAssembled", notAssembled);
}

// Token streams written by hand from bytecode.md (every source modifier, shift,
// result modifier, relative form, predicate, comparison, texld variant and dcl form)
// → disassembly → assembly gives the same tokens.
TEST(RoundTrip, HandWrittenTokenStreams) {
  const std::vector<std::vector<uint32_t>> streams = {
      // vs_1_1: dcl_position v0; m4x4 oPos, v0, c0; mov r0.xy, -c[a0.x+3].yzzz; def; expp; oFog; oD1; oT7.
      {0xFFFE0101, 0x0000001F, 0x80000000, 0x900F0000, 0x00000014, 0xC00F0000, 0x90E40000, 0xA0E40000, 0x00000001,
       0x80030000, 0xA1A92003, 0x00000051, 0xA00F005F, 0x3DCCCCCD, 0x3EAAAAAB, 0x80000000, 0x2EDBE6FF, 0x0000004E,
       0xE0050007, 0x80FF0000, 0x00000001, 0xC0010001, 0x80AA0001, 0x00000001, 0xD00F0001, 0x80550002, 0x0000FFFF},
      // ps_1_1: def, tex, texm3x2pad/tex with _bx2, mul_x2 .rgb, co-issued 1-t1.a, cnd, texkill, texcoord.
      {0xFFFF0101, 0x00000051, 0xA00F0000, 0x3F800000, 0x3F000000, 0x00000000, 0xBF800000, 0x00000042, 0xB00F0000,
       0x00000047, 0xB00F0001, 0xB4E40000, 0x00000048, 0xB00F0002, 0xB4E40000, 0x00000040, 0xB00F0003,
       0x00000005, 0x81070000, 0xB0E40000, 0x90E40000, 0x40000001, 0x80080000, 0xB6FF0001, 0x00000050, 0x800F0000,
       0x80FF0000, 0x83E40001, 0xA1E40000, 0x00000041, 0xB00F0000, 0x0000FFFF},
      // ps_1_3: texm3x3pad x2, texm3x3spec; dp3_sat r0, t0_bx2, v0_bias; -t0_bx2.
      {0xFFFF0103, 0x00000042, 0xB00F0000, 0x00000049, 0xB00F0001, 0xB0E40000, 0x00000049, 0xB00F0002, 0xB0E40000,
       0x0000004C, 0xB00F0003, 0xB0E40000, 0xA0E40000, 0x00000008, 0x801F0000, 0xB4E40000, 0x92E40000,
       0x00000001, 0x800F0001, 0xB5E40000, 0x0000FFFF},
      // ps_1_4: texld r0, t0_dz.xyz; texcrd r1.xyz, t1_dw.xyw; every shift; _x2 / -_x2 sources; phase; bem.
      {0xFFFF0104, 0x00000042, 0x800F0000, 0xB9A40000, 0x00000040, 0x80070001, 0xBAF40001, 0x00000059, 0x80030001,
       0x80E40001, 0x80E40000, 0x0000FFFD, 0x00000042, 0x800F0001, 0x80E40001, 0x00000001, 0x820F0000, 0x87E40001,
       0x00000001, 0x8F0F0000, 0x88E40001, 0x00000001, 0x8D0F0000, 0x80E40001, 0x00000001, 0x8E0F0000, 0x80E40001,
       0x00000001, 0x831F0000, 0x80E40001, 0x00000057, 0x800F0005, 0x0000FFFF},
      // ps_2_0: dcl_centroid t0, dcl_pp t1.xy, dcl v0, dcl_2d/cube/volume, texld/texldp/texldb, add_sat, mov_pp oC0,
      // sincos (SM2 form), dp2add, texkill r0, oDepth.
      {0xFFFF0200, 0x0200001F, 0x80000000, 0xB04F0000, 0x0200001F, 0x80000000, 0xB0230001, 0x0200001F, 0x80000000,
       0x900F0000, 0x0200001F, 0x90000000, 0xA00F0800, 0x0200001F, 0x98000000, 0xA00F0801, 0x0200001F, 0xA0000000,
       0xA00F0802, 0x03000042, 0x800F0000, 0xB0E40000, 0xA0E40800, 0x03010042, 0x800F0000, 0xB0E40000, 0xA0E40801,
       0x03020042, 0x800F0000, 0xB0E40000, 0xA0E40802, 0x03000002, 0x801F0000, 0x80E40001, 0xA0E40000,
       0x04000025, 0x80030001, 0x80000000, 0xA0E40000, 0xA0E40001, 0x0400005A, 0x80110002, 0x80E40000, 0x81E40001,
       0xA0000002, 0x01000041, 0x800F0000, 0x02000001, 0x802F0800, 0x80E40000, 0x02000001, 0x90010800,
       0x80000002, 0x0000FFFF},
      // vs_2_0: dcl_texcoord1 v2, dcl_normal v1, relative a0.y / aL, defi, loop, rep, if !b0, call, callnz, label, mova.
      {0xFFFE0200, 0x0200001F, 0x80010005, 0x900F0002, 0x0200001F, 0x80000003, 0x900F0001, 0x05000030, 0xF00F0000, 4,
       0, 1, 0, 0x0200002E, 0xB0020000, 0x80550000, 0x03000001, 0x800F0000, 0xA0E42005, 0xB0550000, 0x0200001B,
       0xF0E40800, 0xF0E40000, 0x03000001, 0x800F0000, 0xA0E42002, 0xF0E40800, 0x0000001D, 0x01000028, 0xEDE40800,
       0x01000019, 0xA0E41000, 0x0000002B, 0x0200001A, 0xA0E41001, 0xE0E40802, 0x02000001, 0xC00F0000, 0x80E40000,
       0x0000001C, 0x0100001E, 0xA0E41000, 0x0000001C, 0x0100001E, 0xA0E41001, 0x0000001C, 0x0000FFFF},
      // vs_3_0: dcl_texcoord3 o4.xy, dcl_position o0, dcl_2d s0, defb, o[aL+1], setp_ge, predicated texldl,
      // sincos (SM3 form) with -r0_abs.z, c2049.
      {0xFFFE0300, 0x0200001F, 0x80030005, 0xE0030004, 0x0200001F, 0x80000000, 0xE00F0000, 0x0200001F, 0x90000000,
       0xA00F0800, 0x0200002F, 0xE00F0801, 1, 0x05000030, 0xF00F0000, 2, 0, 1, 0, 0x0200001B, 0xF0E40800, 0xF0E40000,
       0x03000001, 0xE00F2001, 0xF0E40800, 0x80E40000, 0x0000001D, 0x0303005E, 0xB0031000, 0x80E40000, 0xB0E40801,
       0x1400005F, 0x800F0001, 0xBD001000, 0x80E40000, 0xA0E40800, 0x02000025, 0x80030002, 0x8CAA0000,
       0x02000001, 0xE00F0000, 0x80E40001, 0x0000FFFF},
      // ps_3_0: dcl vPos.xy, vFace, dcl_texcoord2_centroid v1.xy, dcl_color1 v0, if_lt, rep, break_ne, breakp !p0.w,
      // (p0) add, dsx, texldd, v[aL].
      {0xFFFF0300, 0x0200001F, 0x80000000, 0x90031000, 0x0200001F, 0x80000000, 0x900F1001, 0x0200001F, 0x80020005,
       0x90430001, 0x0200001F, 0x8001000A, 0x900F0000, 0x0200001F, 0x90000000, 0xA00F0800, 0x02040029, 0x80000000,
       0x80550001, 0x01000026, 0xF0E40001, 0x0205002D, 0x90001001, 0x8BAA0001, 0x01000060, 0xBDFF1000, 0x00000027,
       0x0000002B, 0x0303005E, 0xB00F1000, 0x80E40000, 0x80E40001, 0x14000002, 0x800F0000, 0xB0E41000, 0x90E40001,
       0x90E40000, 0x0200005B, 0x800F0003, 0x90E40001, 0x0500005D, 0x800F0000, 0x90E40001, 0xA0E40800, 0x80E40003,
       0x80E40003, 0x0200001B, 0xF0E40800, 0xF0E40000, 0x03000001, 0x800F0004, 0x90E42000, 0xF0E40800, 0x0000001D,
       0x02000001, 0x800F0800, 0x80E40000, 0x0000FFFF},
  };
  for (size_t i = 0; i < streams.size(); ++i) {
    SCOPED_TRACE(i);
    const std::vector<uint32_t>& tokens = streams[i];
    ASSERT_EQ(encode(decode(tokens)), tokens) << "stream " << i << " is not in canonical form";
    std::string text = disassemble(tokens);
    try {
      EXPECT_EQ(encode(assemble(text, "stream" + std::to_string(i))), tokens) << text;
    } catch (const refx::Error& e) {
      ADD_FAILURE() << e.what() << "\n" << text;
    }
  }
}
