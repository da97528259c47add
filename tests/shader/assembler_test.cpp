// Assembly text → D3D9 tokens. Every expected DWORD below is worked out by hand from the
// field tables of the bytecode reference, never taken from refx's own output.
//
// Parameter tokens (bit 31 set), register type in bits 30:28 (low 3 bits) and 12:11
// (high 2 bits):
//   r 0 → 80000000   v 1 → 90000000   c 2 → A0000000   a0/t 3 → B0000000
//   RastOut 4 → C0000000   oD 5 → D0000000   oT/o 6 → E0000000   i 7 → F0000000
//   oC 8 → 80000800   oDepth 9 → 90000800   s 10 → A0000800   b 14 → E0000800
//   aL 15 → F0000800   vPos/vFace 17 → 90001000   l 18 → A0001000   p0 19 → B0001000
// Destination: | writeMask << 16 | resultMod << 20 (sat 1, pp 2, centroid 4) | shift << 24.
// Source: | swizzle << 16 (xyzw = E4, xxxx = 00, yyyy = 55, zzzz = AA, wwww = FF) | mod << 24.
// Opcode token: opcode | control << 16 | length << 24 (SM2+) | predicated 1<<28 | co-issue 1<<30.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/shader/assembler.h"

using namespace refx::shader;

namespace {

// Tokens of `line` assembled under `version`, without the version and end tokens.
std::vector<uint32_t> body(const std::string& version, const std::string& line) {
  std::vector<uint32_t> t = assembleTokens(version + "\n" + line + "\n");
  EXPECT_GE(t.size(), 2u);
  EXPECT_EQ(t.back(), 0x0000FFFFu);
  if (t.size() < 2) return {};
  return std::vector<uint32_t>(t.begin() + 1, t.end() - 1);
}

struct Case {
  const char* version;
  const char* text;
  std::vector<uint32_t> tokens;
};

void check(const std::vector<Case>& cases) {
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string(c.version) + ": " + c.text);
    try {
      EXPECT_EQ(body(c.version, c.text), c.tokens);
    } catch (const refx::Error& e) {
      ADD_FAILURE() << e.what();
    }
  }
}

// The first error's code and position, "A2001@3:1".
std::string codeOf(const std::string& source) {
  refx::DiagnosticSink sink;
  assemble(source, "t.psh", sink);
  if (sink.all().empty()) return "(no error)";
  const refx::Diagnostic& d = sink.all().front();
  return d.code + "@" + std::to_string(d.where.line) + ":" + std::to_string(d.where.column);
}

// The first error's position and message text, as "file:line:col: error: message": these
// tests are about what the messages say; the other errors are checked by code (codeOf).
std::string errorOf(const std::string& source, const char* file = "t.psh") {
  refx::DiagnosticSink sink;
  assemble(source, file, sink);
  if (sink.all().empty()) return "(no error)";
  const refx::Diagnostic& d = sink.all().front();
  return refx::Error(d.where, d.message).what();
}

}  // namespace

TEST(Assembler, VersionTokens) {
  // D3DVS_VERSION(M,m) = 0xFFFE0000 | M<<8 | m; D3DPS_VERSION = 0xFFFF0000 | M<<8 | m.
  struct V {
    const char* text;
    uint32_t token;
  };
  const V versions[] = {
      {"vs_1_1", 0xFFFE0101}, {"vs.1.1", 0xFFFE0101}, {"vs.1.0", 0xFFFE0100}, {"vs_2_0", 0xFFFE0200},
      {"vs_2_x", 0xFFFE0201}, {"vs_3_0", 0xFFFE0300}, {"ps_1_1", 0xFFFF0101}, {"ps.1.1", 0xFFFF0101},
      {"ps.1.2", 0xFFFF0102}, {"ps_1_3", 0xFFFF0103}, {"ps.1.4", 0xFFFF0104}, {"ps_1_4", 0xFFFF0104},
      {"ps_2_0", 0xFFFF0200}, {"ps_2_x", 0xFFFF0201}, {"ps_2_a", 0xFFFF0201}, {"ps_2_b", 0xFFFF0201},
      {"ps_3_0", 0xFFFF0300}, {"PS.1.1", 0xFFFF0101}, {"Vs_2_0", 0xFFFE0200}, {"ps_1_0", 0xFFFF0100},
  };
  for (const V& v : versions) {
    SCOPED_TRACE(v.text);
    // An empty shader is the version token and the end token 0x0000FFFF.
    EXPECT_EQ(assembleTokens(v.text), (std::vector<uint32_t>{v.token, 0x0000FFFF}));
  }
}

TEST(Assembler, Vs11Arithmetic) {
  // SM1: no length field, the opcode token is the bare opcode number.
  check({
      {"vs_1_1", "nop", {0x00000000}},
      // mov r0, v0: dst r0 full mask 800F0000, src v0 .xyzw 90E40000.
      {"vs_1_1", "mov r0, v0", {0x00000001, 0x800F0000, 0x90E40000}},
      {"vs_1_1", "add r0, r1, r2", {0x00000002, 0x800F0000, 0x80E40001, 0x80E40002}},
      {"vs_1_1", "sub r0, r1, r2", {0x00000003, 0x800F0000, 0x80E40001, 0x80E40002}},
      {"vs_1_1", "mad r0, r1, r2, c0", {0x00000004, 0x800F0000, 0x80E40001, 0x80E40002, 0xA0E40000}},
      {"vs_1_1", "mul r0, r1, r2", {0x00000005, 0x800F0000, 0x80E40001, 0x80E40002}},
      // rcp r0.x, r1.w: mask x = 1 → 80010000; .w replicated = FF → 80FF0001.
      {"vs_1_1", "rcp r0.x, r1.w", {0x00000006, 0x80010000, 0x80FF0001}},
      {"vs_1_1", "rsq r0.x, r1.x", {0x00000007, 0x80010000, 0x80000001}},
      {"vs_1_1", "dp3 r0, r1, r2", {0x00000008, 0x800F0000, 0x80E40001, 0x80E40002}},
      {"vs_1_1", "dp4 r0, r1, c0", {0x00000009, 0x800F0000, 0x80E40001, 0xA0E40000}},
      {"vs_1_1", "min r0, r1, r2", {0x0000000A, 0x800F0000, 0x80E40001, 0x80E40002}},
      {"vs_1_1", "max r0, r1, r2", {0x0000000B, 0x800F0000, 0x80E40001, 0x80E40002}},
      {"vs_1_1", "slt r0, r1, r2", {0x0000000C, 0x800F0000, 0x80E40001, 0x80E40002}},
      {"vs_1_1", "sge r0, r1, r2", {0x0000000D, 0x800F0000, 0x80E40001, 0x80E40002}},
      {"vs_1_1", "exp r0, r1.x", {0x0000000E, 0x800F0000, 0x80000001}},
      {"vs_1_1", "log r0, r1.x", {0x0000000F, 0x800F0000, 0x80000001}},
      {"vs_1_1", "lit r0, r1", {0x00000010, 0x800F0000, 0x80E40001}},
      {"vs_1_1", "dst r0, r1, r2", {0x00000011, 0x800F0000, 0x80E40001, 0x80E40002}},
      // frc r0.xy: mask x|y = 3 → 80030000.
      {"vs_1_1", "frc r0.xy, r1", {0x00000013, 0x80030000, 0x80E40001}},
      // Macros are one opcode each (20..24), as D3D encodes them.
      {"vs_1_1", "m4x4 oPos, v0, c0", {0x00000014, 0xC00F0000, 0x90E40000, 0xA0E40000}},
      {"vs_1_1", "m4x3 r0.xyz, v0, c4", {0x00000015, 0x80070000, 0x90E40000, 0xA0E40004}},
      {"vs_1_1", "m3x4 r0, v0, c4", {0x00000016, 0x800F0000, 0x90E40000, 0xA0E40004}},
      {"vs_1_1", "m3x3 r0.xyz, v3, c0", {0x00000017, 0x80070000, 0x90E40003, 0xA0E40000}},
      {"vs_1_1", "m3x2 r0.xy, v3, c0", {0x00000018, 0x80030000, 0x90E40003, 0xA0E40000}},
      // No mask: the components the matrix macro computes (.xyz = 0x7, .xy = 0x3 in
      // bits 16-19 of the destination token), as D3D9 requires.
      {"vs_1_1", "m3x3 r5, v8, c0", {0x00000017, 0x80070005, 0x90E40008, 0xA0E40000}},
      {"vs_1_1", "m4x3 r0, v0, c4", {0x00000015, 0x80070000, 0x90E40000, 0xA0E40004}},
      {"vs_1_1", "m3x2 r0, v3, c0", {0x00000018, 0x80030000, 0x90E40003, 0xA0E40000}},
      {"vs_1_1", "expp r0, r1.x", {0x0000004E, 0x800F0000, 0x80000001}},
      {"vs_1_1", "logp r0, r1.x", {0x0000004F, 0x800F0000, 0x80000001}},
      // def: dst c0 (A00F0000) + four IEEE floats: 1.0 = 3F800000, 0.0 = 0.
      {"vs_1_1", "def c0, 1.0, 0.0, 0.0, 1.0", {0x00000051, 0xA00F0000, 0x3F800000, 0, 0, 0x3F800000}},
      // dcl in SM1: opcode 31, usage token (bit 31 | usage), dst v0 full mask.
      {"vs_1_1", "dcl_position v0", {0x0000001F, 0x80000000, 0x900F0000}},
  });
}

TEST(Assembler, Vs11Registers) {
  check({
      // a0 is type 3 (B0000000), mask x; c0.x → A0000000.
      {"vs_1_1", "mov a0.x, c0.x", {0x00000001, 0xB0010000, 0xA0000000}},
      // oFog/oPts: RastOut numbers 1 and 2; the mask is kept as written (none = F).
      {"vs_1_1", "mov oFog, r0.x", {0x00000001, 0xC00F0001, 0x80000000}},
      {"vs_1_1", "mov oPts.x, r0.x", {0x00000001, 0xC0010002, 0x80000000}},
      {"vs_1_1", "mov oD1, r0", {0x00000001, 0xD00F0001, 0x80E40000}},
      {"vs_1_1", "mov oT7.xy, r0", {0x00000001, 0xE0030007, 0x80E40000}},
      // V7.xy as a source is .xyyy = 0|1<<2|1<<4|1<<6 = 54.
      {"vs_1_1", "mov OT3.XY, V7.xy", {0x00000001, 0xE0030003, 0x90540007}},
      // c08 reads as c8 (leading zero in the seeds' emboss shader).
      {"vs_1_1", "m4x4 oPos, v0,c08", {0x00000014, 0xC00F0000, 0x90E40000, 0xA0E40008}},
  });
}

TEST(Assembler, Vs11RelativeAddressing) {
  // vs_1_1: bit 13 (0x2000) on the source, no extra token (a0.x implied).
  check({
      // -c[a0.x+3].yzzz: NEG 01000000 | yzzz = 1|2<<2|2<<4|2<<6 = A9 | 2000 | c → A1A92003.
      {"vs_1_1", "mov r0.xy, -c[a0.x+3].yzzz", {0x00000001, 0x80030000, 0xA1A92003}},
      {"vs_1_1", "mov r0, c[3+a0.x]", {0x00000001, 0x800F0000, 0xA0E42003}},
      {"vs_1_1", "mov r0, c[ a0.x + 12 ]", {0x00000001, 0x800F0000, 0xA0E4200C}},
      {"vs_1_1", "mov r0, c[a0.x]", {0x00000001, 0x800F0000, 0xA0E42000}},
      // fxc's listing form: c5[a0.x] = c[a0.x + 5].
      {"vs_1_1", "mov r0, c5[a0.x]", {0x00000001, 0x800F0000, 0xA0E42005}},
  });
}

TEST(Assembler, Vs20LengthAndFlowControl) {
  // SM2+: length (parameter tokens after the opcode) in bits 27:24.
  check({
      {"vs_2_0", "dcl_position v0", {0x0200001F, 0x80000000, 0x900F0000}},
      // dcl_texcoord1: usage 5, index 1 at bit 16 → 80010005.
      {"vs_2_0", "dcl_texcoord1 v2", {0x0200001F, 0x80010005, 0x900F0002}},
      {"vs_2_0", "dcl_normal v3", {0x0200001F, 0x80000003, 0x900F0003}},
      {"vs_2_0", "dcl_blendindices1 v4", {0x0200001F, 0x80010002, 0x900F0004}},
      {"vs_2_0", "mov oPos, v0", {0x02000001, 0xC00F0000, 0x90E40000}},
      {"vs_2_0", "lrp r0, r1, r2, c0", {0x04000012, 0x800F0000, 0x80E40001, 0x80E40002, 0xA0E40000}},
      // call l0: label type 18 → A0001000 with .xyzw.
      {"vs_2_0", "call l0", {0x01000019, 0xA0E41000}},
      {"vs_2_0", "callnz l1, b2", {0x0200001A, 0xA0E41001, 0xE0E40802}},
      // loop aL, i0: aL F0000800, i0 F0000000, both .xyzw.
      {"vs_2_0", "loop aL, i0", {0x0200001B, 0xF0E40800, 0xF0E40000}},
      {"vs_2_0", "ret", {0x0000001C}},
      {"vs_2_0", "endloop", {0x0000001D}},
      {"vs_2_0", "label l0", {0x0100001E, 0xA0E41000}},
      // pow r0, r1.x, r2.y: .y = 55.
      {"vs_2_0", "pow r0, r1.x, r2.y", {0x03000020, 0x800F0000, 0x80000001, 0x80550002}},
      {"vs_2_0", "crs r0.xyz, r1, r2", {0x03000021, 0x80070000, 0x80E40001, 0x80E40002}},
      // sgn in SM2 carries two scratch temps.
      {"vs_2_0", "sgn r0, r1, r2, r3", {0x04000022, 0x800F0000, 0x80E40001, 0x80E40002, 0x80E40003}},
      {"vs_2_0", "abs r0, r1", {0x02000023, 0x800F0000, 0x80E40001}},
      {"vs_2_0", "nrm r0, r1", {0x02000024, 0x800F0000, 0x80E40001}},
      // sincos SM2: dst .xy, src .x, two constants.
      {"vs_2_0", "sincos r0.xy, r1.x, c0, c1", {0x04000025, 0x80030000, 0x80000001, 0xA0E40000, 0xA0E40001}},
      {"vs_2_0", "rep i0", {0x01000026, 0xF0E40000}},
      {"vs_2_0", "endrep", {0x00000027}},
      // if b0: b is type 14 → E0000800.
      {"vs_2_0", "if b0", {0x01000028, 0xE0E40800}},
      // if !b1: NOT = 13 → 0D000000.
      {"vs_2_0", "if !b1", {0x01000028, 0xEDE40801}},
      {"vs_2_0", "else", {0x0000002A}},
      {"vs_2_0", "endif", {0x0000002B}},
      {"vs_2_0", "mova a0.x, r0.x", {0x0200002E, 0xB0010000, 0x80000000}},
      // defb: dst b0 (E00F0800) + one DWORD; defi: dst i0 (F00F0000) + four int32.
      {"vs_2_0", "defb b0, true", {0x0200002F, 0xE00F0800, 0x00000001}},
      {"vs_2_0", "defb b3, FALSE", {0x0200002F, 0xE00F0803, 0x00000000}},
      {"vs_2_0", "defi i0, 3, 0, 1, 0", {0x05000030, 0xF00F0000, 3, 0, 1, 0}},
      {"vs_2_0", "defi i1, -1, 255, +2, 0", {0x05000030, 0xF00F0001, 0xFFFFFFFF, 255, 2, 0}},
      // m4x4 in SM2: length 3.
      {"vs_2_0", "m4x4 oPos, v0, c0", {0x03000014, 0xC00F0000, 0x90E40000, 0xA0E40000}},
      {"vs_2_0", "expp r0, r1.x", {0x0200004E, 0x800F0000, 0x80000001}},
  });
}

TEST(Assembler, Vs20RelativeAddressing) {
  // SM2+: bit 13 on the source and a relative-address token after it: a0 with a
  // replicate swizzle of the component (x → B0000000, y → B0550000), aL F0E40800.
  check({
      {"vs_2_0", "mov r0, c[a0.x + 3]", {0x03000001, 0x800F0000, 0xA0E42003, 0xB0000000}},
      {"vs_2_0", "mov r0, c[a0.y+2]", {0x03000001, 0x800F0000, 0xA0E42002, 0xB0550000}},
      {"vs_2_0", "mov r0, c[aL + 1]", {0x03000001, 0x800F0000, 0xA0E42001, 0xF0E40800}},
      {"vs_2_0", "mov r0, c10[aL]", {0x03000001, 0x800F0000, 0xA0E4200A, 0xF0E40800}},
      {"vs_2_0", "add r0, -c[a0.w+1].x, r1",
       {0x04000002, 0x800F0000, 0xA1002001, 0xB0FF0000, 0x80E40001}},
  });
}

TEST(Assembler, Vs2xComparisonsAndPredicates) {
  check({
      // if_lt: ifc (41 = 0x29) with comparison lt = 4 in bits 18:16.
      {"vs_2_x", "if_lt r0.x, r1.x", {0x02040029, 0x80000000, 0x80000001}},
      {"vs_2_x", "ifc_ge r0.x, c0.y", {0x02030029, 0x80000000, 0xA0550000}},
      {"vs_2_x", "break", {0x0000002C}},
      // break_ne: breakc (45 = 0x2D), ne = 5.
      {"vs_2_x", "break_ne r0.x, r1.x", {0x0205002D, 0x80000000, 0x80000001}},
      {"vs_2_x", "breakc_gt r0.x, r1.x", {0x0201002D, 0x80000000, 0x80000001}},
      {"vs_2_x", "break_le r0.x, r1.x", {0x0206002D, 0x80000000, 0x80000001}},
      // setp_eq p0: setp 94 = 0x5E, eq = 2; p0 dst B00F1000.
      {"vs_2_x", "setp_eq p0, r0, r1", {0x0302005E, 0xB00F1000, 0x80E40000, 0x80E40001}},
      // (p0) add: bit 28; predicate token B0E41000 right after the destination; length 4.
      {"vs_2_x", "(p0) add r0, r1, r2", {0x14000002, 0x800F0000, 0xB0E41000, 0x80E40001, 0x80E40002}},
      // (!p0.x): NOT 0D000000 | swizzle 00 → BD001000.
      {"vs_2_x", "(!p0.x) mov r0, r1", {0x13000001, 0x800F0000, 0xBD001000, 0x80E40001}},
      {"vs_2_x", "breakp p0.x", {0x01000060, 0xB0001000}},
      {"vs_2_x", "if p0.y", {0x01000028, 0xB0551000}},
      // callnz l0, !p0.z: zzzz = AA, NOT.
      {"vs_2_x", "callnz l0, !p0.z", {0x0200001A, 0xA0E41000, 0xBDAA1000}},
  });
}

TEST(Assembler, Vs30) {
  check({
      // vs_3_0 outputs o# are type 6 (E0000000); dcl_texcoord0 → usage 5.
      {"vs_3_0", "dcl_texcoord0 o3.xy", {0x0200001F, 0x80000005, 0xE0030003}},
      {"vs_3_0", "dcl_fog o1.x", {0x0200001F, 0x8000000B, 0xE0010001}},
      {"vs_3_0", "dcl_psize o2.x", {0x0200001F, 0x80000004, 0xE0010002}},
      {"vs_3_0", "dcl_color1 v1", {0x0200001F, 0x8001000A, 0x900F0001}},
      // dcl_2d s0: texture type 2 << 27 = 10000000 | bit 31 → 90000000; s0 A00F0800.
      {"vs_3_0", "dcl_2d s0", {0x0200001F, 0x90000000, 0xA00F0800}},
      {"vs_3_0", "texldl r0, r1, s0", {0x0300005F, 0x800F0000, 0x80E40001, 0xA0E40800}},
      // SM3 sincos and sgn take one source.
      {"vs_3_0", "sincos r0.xy, r1.x", {0x02000025, 0x80030000, 0x80000001}},
      {"vs_3_0", "sgn r0, r1", {0x02000022, 0x800F0000, 0x80E40001}},
      // o[aL + 1]: relative destination, address token after the destination.
      {"vs_3_0", "mov o[aL+1], r0", {0x03000001, 0xE00F2001, 0xF0E40800, 0x80E40000}},
      {"vs_3_0", "mov r0, v0[aL]", {0x03000001, 0x800F0000, 0x90E42000, 0xF0E40800}},
      // _sat → 00100000; _abs = 11 → 0B000000; -_abs = 12 → 0C000000.
      {"vs_3_0", "mov_sat r0, r1", {0x02000001, 0x801F0000, 0x80E40001}},
      {"vs_3_0", "mov r0, r1_abs", {0x02000001, 0x800F0000, 0x8BE40001}},
      {"vs_3_0", "mov r0, -r1_abs", {0x02000001, 0x800F0000, 0x8CE40001}},
  });
}

TEST(Assembler, DclUsages) {
  // D3DDECLUSAGE 0..13 in bits 3:0, index in 19:16.
  const char* names[] = {"position", "blendweight", "blendindices", "normal", "psize", "texcoord", "tangent",
                         "binormal", "tessfactor", "positiont", "color", "fog", "depth", "sample"};
  for (uint32_t u = 0; u < 14; ++u) {
    for (uint32_t index : {0u, 7u, 15u}) {
      std::string line = std::string("dcl_") + names[u] + std::to_string(index) + " v1";
      SCOPED_TRACE(line);
      EXPECT_EQ(body("vs_3_0", line), (std::vector<uint32_t>{0x0200001F, 0x80000000u | index << 16 | u, 0x900F0001}));
    }
  }
}

TEST(Assembler, Ps11TextureAndArithmetic) {
  check({
      // tex t0: opcode 66 = 0x42, dst t0 (B0000000) full mask, no source in ps_1_1.
      {"ps_1_1", "tex t0", {0x00000042, 0xB00F0000}},
      {"ps_1_1", "texcoord t1", {0x00000040, 0xB00F0001}},
      {"ps_1_1", "texkill t2", {0x00000041, 0xB00F0002}},
      {"ps_1_1", "texbem t1, t0", {0x00000043, 0xB00F0001, 0xB0E40000}},
      {"ps_1_1", "texbeml t1, t0", {0x00000044, 0xB00F0001, 0xB0E40000}},
      {"ps_1_1", "texreg2ar t1, t0", {0x00000045, 0xB00F0001, 0xB0E40000}},
      {"ps_1_1", "texreg2gb t1, t0", {0x00000046, 0xB00F0001, 0xB0E40000}},
      // texm3x2pad t1, t0_bx2: SIGN = 4 → 04000000.
      {"ps_1_1", "texm3x2pad t1, t0_bx2", {0x00000047, 0xB00F0001, 0xB4E40000}},
      {"ps_1_1", "texm3x2tex t2, t0_bx2", {0x00000048, 0xB00F0002, 0xB4E40000}},
      {"ps_1_1", "texm3x3pad t1, t0", {0x00000049, 0xB00F0001, 0xB0E40000}},
      {"ps_1_1", "texm3x3tex t3, t0", {0x0000004A, 0xB00F0003, 0xB0E40000}},
      {"ps_1_1", "texm3x3spec t3, t0, c0", {0x0000004C, 0xB00F0003, 0xB0E40000, 0xA0E40000}},
      {"ps_1_1", "texm3x3vspec t3, t0", {0x0000004D, 0xB00F0003, 0xB0E40000}},
      // cnd r0, r0.a, r1, r2: .a = FF.
      {"ps_1_1", "cnd r0, r0.a, r1, r2", {0x00000050, 0x800F0000, 0x80FF0000, 0x80E40001, 0x80E40002}},
      {"ps_1_1", "lrp r0, t0, t1, t2", {0x00000012, 0x800F0000, 0xB0E40000, 0xB0E40001, 0xB0E40002}},
      // def with the seeds' number forms: 1.0 = 3F800000, -0.5 = BF000000, .5 = 3F000000, 1.f.
      {"ps_1_1", "def c0, 1.0, -0.5, .5, 1.f", {0x00000051, 0xA00F0000, 0x3F800000, 0xBF000000, 0x3F000000, 0x3F800000}},
      // 2.5e-1 = 0.25 = 3E800000; -1 = BF800000; 1e0 = 3F800000; 0.125f = 3E000000.
      {"ps_1_1", "def c7, 2.5e-1, -1, 1e0, 0.125f", {0x00000051, 0xA00F0007, 0x3E800000, 0xBF800000, 0x3F800000, 0x3E000000}},
  });
}

TEST(Assembler, Ps11Modifiers) {
  check({
      // mul_x2 r0.rgb: shift 1 → 01000000, mask rgb = 7 → 81070000.
      {"ps_1_1", "mul_x2 r0.rgb, t0, v0", {0x00000005, 0x81070000, 0xB0E40000, 0x90E40000}},
      {"ps_1_1", "mul_x4 r0, r1, r0", {0x00000005, 0x820F0000, 0x80E40001, 0x80E40000}},
      // _d2 = −1 → nibble F.
      {"ps_1_1", "mul_d2 r0, r1, r0", {0x00000005, 0x8F0F0000, 0x80E40001, 0x80E40000}},
      // mul_x2_sat: shift 1 | sat 1 → 811F0000; the other order reads the same.
      {"ps_1_1", "mul_x2_sat r0, r1, r0", {0x00000005, 0x811F0000, 0x80E40001, 0x80E40000}},
      {"ps_1_1", "mul_sat_x2 r0, r1, r0", {0x00000005, 0x811F0000, 0x80E40001, 0x80E40000}},
      // dp3_sat r1, t1_bx2, v0_bx2.
      {"ps_1_1", "dp3_sat r1, t1_bx2, v0_bx2", {0x00000008, 0x801F0001, 0xB4E40001, 0x94E40000}},
      // Source modifiers: NEG 1, BIAS 2, BIASNEG 3, SIGN 4, SIGNNEG 5, COMP 6.
      {"ps_1_1", "mov r0, -r1", {0x00000001, 0x800F0000, 0x81E40001}},
      {"ps_1_1", "mov r0, r1_bias", {0x00000001, 0x800F0000, 0x82E40001}},
      {"ps_1_1", "add r0, -r1_bias, 1-r0", {0x00000002, 0x800F0000, 0x83E40001, 0x86E40000}},
      {"ps_1_1", "mov r0, r1_bx2", {0x00000001, 0x800F0000, 0x84E40001}},
      {"ps_1_1", "mov r0, -t1_bx2", {0x00000001, 0x800F0000, 0xB5E40001}},
      {"ps_1_1", "mov r0, 1 - v0", {0x00000001, 0x800F0000, 0x96E40000}},
      // add r0, 1-t0, -t1.a (RacorX10): COMP on t0; NEG with .a = FF on t1.
      {"ps_1_1", "add r0, 1-t0, -t1.a", {0x00000002, 0x800F0000, 0xB6E40000, 0xB1FF0001}},
      // Selectors .b (zzzz = AA) and .a (FF); modifier and selector in either order.
      {"ps_1_1", "mov r0.a, r1.b", {0x00000001, 0x80080000, 0x80AA0001}},
      {"ps_1_1", "mov r0.a, -r1_bias.a", {0x00000001, 0x80080000, 0x83FF0001}},
      {"ps_1_1", "mov r0.a, -r1.a_bias", {0x00000001, 0x80080000, 0x83FF0001}},
  });
}

TEST(Assembler, Ps11CoIssue) {
  // The second instruction of a pair carries bit 30 (40000000).
  std::vector<uint32_t> t = assembleTokens(
      "ps.1.1\n"
      "mul r1.rgb, t3, t0 ; (N dot L) * base texture\n"
      "+mul r1.a, t0.a, t3.a\n"
      "+ mov r0.a, t0\n");
  EXPECT_EQ(t, (std::vector<uint32_t>{
                   0xFFFF0101,
                   0x00000005, 0x80070001, 0xB0E40003, 0xB0E40000,  // mul r1.rgb
                   0x40000005, 0x80080001, 0xB0FF0000, 0xB0FF0003,  // +mul r1.a, t0.a, t3.a
                   0x40000001, 0x80080000, 0xB0E40000,              // + mov r0.a, t0
                   0x0000FFFF}));
}

TEST(Assembler, Ps12Ps13) {
  check({
      {"ps_1_2", "texreg2rgb t1, t0", {0x00000052, 0xB00F0001, 0xB0E40000}},
      {"ps_1_2", "texdp3tex t3, t1_bx2", {0x00000053, 0xB00F0003, 0xB4E40001}},
      {"ps_1_2", "texdp3 t1, t0", {0x00000055, 0xB00F0001, 0xB0E40000}},
      {"ps_1_2", "texm3x3 t3, t0", {0x00000056, 0xB00F0003, 0xB0E40000}},
      {"ps_1_2", "dp4 r0, r1, c0", {0x00000009, 0x800F0000, 0x80E40001, 0xA0E40000}},
      {"ps_1_2", "cmp r0, r1, r2, c0", {0x00000058, 0x800F0000, 0x80E40001, 0x80E40002, 0xA0E40000}},
      {"ps_1_3", "texm3x2depth t2, t0", {0x00000054, 0xB00F0002, 0xB0E40000}},
  });
}

TEST(Assembler, Ps14) {
  check({
      // texld r0, t0 in ps_1_4: dst r + one source.
      {"ps_1_4", "texld r0, t0", {0x00000042, 0x800F0000, 0xB0E40000}},
      {"ps_1_4", "texcrd r1.rgb, t1", {0x00000040, 0x80070001, 0xB0E40001}},
      // .xyz = xyzz = 0|1<<2|2<<4|2<<6 = A4.
      {"ps_1_4", "texcrd r1.rgb, t0.xyz", {0x00000040, 0x80070001, 0xB0A40000}},
      // _dz = 9, _dw = 10; .xyw = xyww = 0|1<<2|3<<4|3<<6 = F4.
      {"ps_1_4", "texld r2, r1_dz", {0x00000042, 0x800F0002, 0x89E40001}},
      {"ps_1_4", "texld r2, r1_db", {0x00000042, 0x800F0002, 0x89E40001}},
      {"ps_1_4", "texld r3, t2_dw.xyw", {0x00000042, 0x800F0003, 0xBAF40002}},
      {"ps_1_4", "texcrd r3.rgb, t2_da.xyw", {0x00000040, 0x80070003, 0xBAF40002}},
      {"ps_1_4", "texdepth r5", {0x00000057, 0x800F0005}},
      {"ps_1_4", "texkill t0", {0x00000041, 0xB00F0000}},
      // bem r0.rg: mask 3.
      {"ps_1_4", "bem r0.rg, r1, r2", {0x00000059, 0x80030000, 0x80E40001, 0x80E40002}},
      {"ps_1_4", "phase", {0x0000FFFD}},
      // _x8 = 3, _d4 = −2 = E, _d8 = −3 = D.
      {"ps_1_4", "mul_x8 r0, r1, r2", {0x00000005, 0x830F0000, 0x80E40001, 0x80E40002}},
      {"ps_1_4", "mul_d4 r0, r1, r2", {0x00000005, 0x8E0F0000, 0x80E40001, 0x80E40002}},
      {"ps_1_4", "mul_d8_sat r0, r1, r2", {0x00000005, 0x8D1F0000, 0x80E40001, 0x80E40002}},
      // X2 = 7, X2NEG = 8.
      {"ps_1_4", "add r0, r1_x2, -r2_x2", {0x00000002, 0x800F0000, 0x87E40001, 0x88E40002}},
      {"ps_1_4", "mov r0.r, r1.g", {0x00000001, 0x80010000, 0x80550001}},
      {"ps_1_4", "dp3 r1.rg, r1, r0_bx2", {0x00000008, 0x80030001, 0x80E40001, 0x84E40000}},
      {"ps_1_4", "cnd r0, r1, r2, r3", {0x00000050, 0x800F0000, 0x80E40001, 0x80E40002, 0x80E40003}},
  });
}

TEST(Assembler, Ps20) {
  check({
      // ps_2_0 dcl of t#/v#: the usage token is bit 31 alone.
      {"ps_2_0", "dcl t0", {0x0200001F, 0x80000000, 0xB00F0000}},
      {"ps_2_0", "dcl t1.xy", {0x0200001F, 0x80000000, 0xB0030001}},
      {"ps_2_0", "dcl v0", {0x0200001F, 0x80000000, 0x900F0000}},
      {"ps_2_0", "dcl_2d s0", {0x0200001F, 0x90000000, 0xA00F0800}},
      // dcl_cube: 3 << 27 = 18000000 → 98000000; dcl_volume: 4 << 27 = 20000000 → A0000000.
      {"ps_2_0", "dcl_cube s1", {0x0200001F, 0x98000000, 0xA00F0801}},
      {"ps_2_0", "dcl_volume s2", {0x0200001F, 0xA0000000, 0xA00F0802}},
      // _centroid = 4 → 00400000; _pp = 2 → 00200000.
      {"ps_2_0", "dcl_centroid t0", {0x0200001F, 0x80000000, 0xB04F0000}},
      {"ps_2_0", "dcl_pp t0.xy", {0x0200001F, 0x80000000, 0xB0230000}},
      {"ps_2_0", "texld r0, t0, s0", {0x03000042, 0x800F0000, 0xB0E40000, 0xA0E40800}},
      // texldp: control bit 16; texldb: bit 17.
      {"ps_2_0", "texldp r0, t0, s0", {0x03010042, 0x800F0000, 0xB0E40000, 0xA0E40800}},
      {"ps_2_0", "texldb r0, t0, s0", {0x03020042, 0x800F0000, 0xB0E40000, 0xA0E40800}},
      {"ps_2_0", "texld_pp r0, t0, s0", {0x03000042, 0x802F0000, 0xB0E40000, 0xA0E40800}},
      {"ps_2_0", "texkill t0", {0x01000041, 0xB00F0000}},
      {"ps_2_0", "dp2add r0, r1, r2, c0.x", {0x0400005A, 0x800F0000, 0x80E40001, 0x80E40002, 0xA0000000}},
      // oC0: type 8 → 80000800; oDepth: type 9 → 90000800.
      {"ps_2_0", "mov oC0, r0", {0x02000001, 0x800F0800, 0x80E40000}},
      {"ps_2_0", "mov oDepth, r0.x", {0x02000001, 0x900F0800, 0x80000000}},
      {"ps_2_0", "def c0, 1.0, 0.0, 0.0, 1.0", {0x05000051, 0xA00F0000, 0x3F800000, 0, 0, 0x3F800000}},
      {"ps_2_0", "add_sat r0, r1, c0", {0x03000002, 0x801F0000, 0x80E40001, 0xA0E40000}},
      {"ps_2_0", "mov_sat_pp r0, r1", {0x02000001, 0x803F0000, 0x80E40001}},
      {"ps_2_0", "sincos r0.xy, r1.x, c0, c1", {0x04000025, 0x80030000, 0x80000001, 0xA0E40000, 0xA0E40001}},
      {"ps_2_0", "m3x3 r0.xyz, t0, c0", {0x03000017, 0x80070000, 0xB0E40000, 0xA0E40000}},
      {"ps_2_0", "cmp r0, r1, r2, r3", {0x04000058, 0x800F0000, 0x80E40001, 0x80E40002, 0x80E40003}},
      {"ps_2_0", "rcp r0, r1.w", {0x02000006, 0x800F0000, 0x80FF0001}},
      {"ps_2_0", "exp r0, r1.x", {0x0200000E, 0x800F0000, 0x80000001}},
      {"ps_2_0", "log r0, r1.x", {0x0200000F, 0x800F0000, 0x80000001}},
      {"ps_2_0", "frc r0, r1", {0x02000013, 0x800F0000, 0x80E40001}},
      {"ps_2_0", "nop", {0x00000000}},
  });
}

TEST(Assembler, Ps2x) {
  check({
      {"ps_2_x", "dsx r0, r1", {0x0200005B, 0x800F0000, 0x80E40001}},
      {"ps_2_x", "dsy r0, r1", {0x0200005C, 0x800F0000, 0x80E40001}},
      // texldd: dst + 4 sources, length 5.
      {"ps_2_x", "texldd r0, r1, s0, r2, r3",
       {0x0500005D, 0x800F0000, 0x80E40001, 0xA0E40800, 0x80E40002, 0x80E40003}},
      {"ps_2_x", "rep i0", {0x01000026, 0xF0E40000}},
      {"ps_2_x", "break_gt r0.x, c0.x", {0x0201002D, 0x80000000, 0xA0000000}},
      {"ps_2_x", "setp_lt p0.x, r0.x, c0.x", {0x0304005E, 0xB0011000, 0x80000000, 0xA0000000}},
  });
}

TEST(Assembler, Ps30) {
  check({
      // dcl_texcoord2 v1.xy: usage 5 index 2 → 80020005; v1 mask xy → 90030001.
      {"ps_3_0", "dcl_texcoord2 v1.xy", {0x0200001F, 0x80020005, 0x90030001}},
      {"ps_3_0", "dcl_color0 v0", {0x0200001F, 0x8000000A, 0x900F0000}},
      // vPos / vFace: type 17 → 90001000; usage token bit 31 alone.
      {"ps_3_0", "dcl vPos.xy", {0x0200001F, 0x80000000, 0x90031000}},
      {"ps_3_0", "dcl vFace", {0x0200001F, 0x80000000, 0x900F1001}},
      // dcl_texcoord0_centroid v0: centroid 00400000 on the destination.
      {"ps_3_0", "dcl_texcoord0_centroid v0", {0x0200001F, 0x80000005, 0x904F0000}},
      {"ps_3_0", "mov r0, v0[aL]", {0x03000001, 0x800F0000, 0x90E42000, 0xF0E40800}},
      {"ps_3_0", "loop aL, i1", {0x0200001B, 0xF0E40800, 0xF0E40001}},
      {"ps_3_0", "texldl r0, r1, s2", {0x0300005F, 0x800F0000, 0x80E40001, 0xA0E40802}},
      {"ps_3_0", "sincos_pp r0.y, r1.w", {0x02000025, 0x80220000, 0x80FF0001}},
      {"ps_3_0", "mul r0, r1_abs, -c0_abs", {0x03000005, 0x800F0000, 0x8BE40001, 0xACE40000}},
      {"ps_3_0", "if_ne vFace, c0.x", {0x02050029, 0x90E41001, 0xA0000000}},
      {"ps_3_0", "mov oC1, r0", {0x02000001, 0x800F0801, 0x80E40000}},
  });
}

TEST(Assembler, SwizzlesAndMasks) {
  check({
      // .xy repeats the last letter: xyyy = 0|1<<2|1<<4|1<<6 = 54.
      {"vs_2_0", "mov r0, r1.xy", {0x02000001, 0x800F0000, 0x80540001}},
      // .zxyw = 2|0<<2|1<<4|3<<6 = D2; .yzxw = 1|2<<2|0<<4|3<<6 = C9.
      {"vs_2_0", "mul r2, -r1.zxyw, r0.yzxw", {0x03000005, 0x800F0002, 0x81D20001, 0x80C90000}},
      // .wzyx = 3|2<<2|1<<4|0<<6 = 1B; .bgra = 2|1<<2|0<<4|3<<6 = C6.
      {"vs_2_0", "add r0, r1.wzyx, r2.bgra", {0x03000002, 0x800F0000, 0x801B0001, 0x80C60002}},
      // Write masks: .xz = 5, .yw = A, .xyw = B, .rgba = F, .rgb = 7, .a = 8.
      {"vs_2_0", "mov r0.xz, r1", {0x02000001, 0x80050000, 0x80E40001}},
      {"vs_2_0", "mov r0.yw, r1", {0x02000001, 0x800A0000, 0x80E40001}},
      {"vs_2_0", "mov r0.xyw, r1", {0x02000001, 0x800B0000, 0x80E40001}},
      {"ps_2_0", "mov r0.rgba, r1", {0x02000001, 0x800F0000, 0x80E40001}},
      {"ps_1_1", "mov r0.rgb, r1", {0x00000001, 0x80070000, 0x80E40001}},
      {"ps_1_1", "mov r0.a, r1", {0x00000001, 0x80080000, 0x80E40001}},
  });
}

TEST(Assembler, LargeConstantNumbers) {
  // c2048+ use CONST2..CONST4 (types 11..13) with the number within the bank:
  // c2050 → type 11 (B0000800) | 2; c6144 → type 13 = 01101 → D0000800 | 0.
  check({
      {"vs_3_0", "mov r0, c2050", {0x02000001, 0x800F0000, 0xB0E40802}},
      {"vs_3_0", "mov r0, c6144", {0x02000001, 0x800F0000, 0xD0E40800}},
  });
}

TEST(Assembler, CommentsAndLayout) {
  // ; // /* */ comments, #line, blank lines, several instructions per line, tabs.
  std::vector<uint32_t> t = assembleTokens(
      "// leading comment\n"
      "/* block\n comment */ ps.1.1 ; version\n"
      "#line 40 \"shader.psh\"\n"
      "\ttex t0 // sample\n"
      "mov r0, /* inline */ t0 ; done\n"
      "\n");
  EXPECT_EQ(t, (std::vector<uint32_t>{0xFFFF0101, 0x00000042, 0xB00F0000, 0x00000001, 0x800F0000, 0xB0E40000,
                                      0x0000FFFF}));
  // The D3DX grammar does not need newlines between instructions.
  EXPECT_EQ(assembleTokens("ps.1.1 tex t0 mov r0, t0"), t);
  // Trailing `;` as in the seeds' `mul r1,r0,r0;`.
  EXPECT_EQ(assembleTokens("ps.1.1\ntex t0;\nmov r0,t0;; comment\n"), t);
  // CRLF line ends.
  EXPECT_EQ(assembleTokens("ps.1.1\r\ntex t0\r\nmov r0, t0\r\n"), t);
}

TEST(Assembler, CaseInsensitive) {
  EXPECT_EQ(assembleTokens("VS.1.1\nM4X4 OPOS, V0, C0\nMOV OD0, C4.XYZW\n"),
            assembleTokens("vs.1.1\nm4x4 oPos, v0, c0\nmov oD0, c4\n"));
  EXPECT_EQ(assembleTokens("PS_2_0\nDCL_2D S0\nTEXLD R0, T0, S0\nMOV OC0, R0\n"),
            assembleTokens("ps_2_0\ndcl_2d s0\ntexld r0, t0, s0\nmov oC0, r0\n"));
  EXPECT_EQ(assembleTokens("ps_1_1\nMUL_X2_SAT R0.RGB, T0_BX2, 1-V0.A\n"),
            assembleTokens("ps_1_1\nmul_x2_sat r0.rgb, t0_bx2, 1-v0.a\n"));
}

TEST(Assembler, InstructionsCarryPositions) {
  Shader s = assemble("vs.1.1\n\n  mov r0, v0\n\tadd r0, r0, c1\n");
  ASSERT_EQ(s.instructions.size(), 2u);
  EXPECT_EQ(s.instructions[0].pos.line, 3);
  EXPECT_EQ(s.instructions[0].pos.column, 3);
  EXPECT_EQ(s.instructions[1].pos.line, 4);
  EXPECT_EQ(s.instructions[1].pos.column, 2);
  EXPECT_EQ(s.version.token(), 0xFFFE0101u);
}

// ---- the test shaders and the seeds' shaders -------------------------------------------------

namespace {
std::string readFile(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
std::string testShader(const char* name) {
  return readFile(std::filesystem::path(REFX_TEST_DIR) / "shader" / "asm" / name);
}
}  // namespace

TEST(AssemblerSeeds, RacorX6DiffuseBumpPs11) {
  EXPECT_EQ(assembleTokens(testShader("seed_racorx6_ps11.psh")),
            (std::vector<uint32_t>{
                0xFFFF0101,                                      // ps.1.1
                0x00000042, 0xB00F0000,                          // tex t0
                0x00000042, 0xB00F0001,                          // tex t1
                0x00000008, 0x800F0001, 0xB4E40001, 0x94E40000,  // dp3 r1, t1_bx2, v0_bx2 (SIGN = 4)
                0x00000005, 0x800F0000, 0xB0E40000, 0x80E40001,  // mul r0,t0, r1
                0x0000FFFF}));
}

TEST(AssemblerSeeds, RacorX8TableSpecularPs14) {
  EXPECT_EQ(assembleTokens(testShader("seed_racorx8_ps14.psh")),
            (std::vector<uint32_t>{
                0xFFFF0104,                                      // ps.1.4
                0x00000042, 0x800F0000, 0xB0E40000,              // texld r0, t0
                0x00000040, 0x80070001, 0xB0E40001,              // texcrd r1.rgb, t1
                0x00000008, 0x80030001, 0x80E40001, 0x84E40000,  // dp3 r1.rg, r1, r0_bx2
                0x0000FFFD,                                      // phase
                0x00000042, 0x800F0003, 0xB0E40000,              // texld r3, t0
                0x00000042, 0x800F0002, 0x80E40001,              // texld r2, r1
                0x00000005, 0x800F0000, 0x80E40002, 0x80E40003,  // mul r0, r2, r3
                0x0000FFFF}));
}

TEST(AssemblerSeeds, RacorX10PointLightVs11) {
  std::vector<uint32_t> t = assembleTokens(testShader("seed_racorx10_pointlight.vsh"));
  EXPECT_EQ(t, (std::vector<uint32_t>{
                   0xFFFE0101,                                      // vs.1.1
                   0x00000014, 0xC00F0000, 0x90E40000, 0xA0E40008,  // m4x4 oPos, v0, c8
                   0x00000014, 0x800F0002, 0x90E40000, 0xA0E40000,  // m4x4 r2, v0, c0
                   0x00000002, 0x800F000A, 0x80E40002, 0xA0E4000C,  // add r10, r2, c12
                   0x00000005, 0x800F000A, 0x80E4000A, 0xA0000021,  // mul r10, r10, c33.x
                   0x00000004, 0x800F000A, 0x80E4000A, 0xA0550021, 0xA0550021,  // mad … c33.yyyy
                   0x00000001, 0xE0030000, 0x8054000A,              // mov oT0.xy, r10.xy (.xyyy = 54)
                   0x00000001, 0xE0010001, 0x80AA000A,              // mov oT1.x, r10.z
                   0x0000FFFF}));
}

TEST(AssemblerSeeds, EveryTestShaderAssemblesAndSurvivesDecode) {
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(fs::path(REFX_TEST_DIR) / "shader" / "asm"))
    if (e.path().extension() == ".vsh" || e.path().extension() == ".psh") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  EXPECT_GE(files.size(), 20u);
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.filename().string());
    try {
      Shader s = assemble(readFile(f), f.filename().string());
      const bool vertex = f.extension() == ".vsh";
      EXPECT_EQ(s.version.isVertex(), vertex);
      std::vector<uint32_t> t = encode(s);
      // The decoded model encodes to the same tokens.
      EXPECT_EQ(encode(decode(t)), t);
    } catch (const refx::Error& e) {
      ADD_FAILURE() << e.what();
    }
  }
}

// ---- errors ---------------------------------------------------------------------------------

TEST(AssemblerErrors, UnknownInstruction) {
  EXPECT_EQ(errorOf("ps.1.1\ntex t0\nmull r0, t0, t0\n"),
            "t.psh:3:1: error: unknown instruction 'mull' (did you mean 'mul'?)");
  EXPECT_EQ(errorOf("ps.1.1\n  frobnicate r0\n"),
            "t.psh:2:3: error: unknown instruction 'frobnicate' (expected an instruction such as mov, add, mul, mad, "
            "dp3, tex, texld, def, dcl_*)");
}

TEST(AssemblerErrors, OperandCount) {
  EXPECT_EQ(errorOf("ps.1.1\ndp3 r0, t0\n"),
            "t.psh:2:1: error: 'dp3' takes 3 operands (dst, src0, src1) in ps_1_1, found 2");
  // A missing operand before the next line's instruction.
  EXPECT_EQ(errorOf("vs.1.1\nmov r0,\nadd r0, r1, r2\n"),
            "t.psh:2:1: error: 'mov' takes 2 operands (dst, src0) in vs_1_1, found 1");
  EXPECT_EQ(errorOf("vs.1.1\nmov\n"), "t.psh:2:1: error: 'mov' takes 2 operands (dst, src0) in vs_1_1, found 0");
  EXPECT_EQ(errorOf("vs_2_0\nadd r0, r1, r2, r3\n"),
            "t.psh:2:17: error: 'add' takes 3 operands (dst, src0, src1) in vs_2_0, found more");
  // sincos: 3 sources in SM2, 1 in SM3.
  EXPECT_EQ(errorOf("vs_2_0\nsincos r0.xy, r1.x\n"),
            "t.psh:2:1: error: 'sincos' takes 4 operands (dst, src0, src1, src2) in vs_2_0, found 2");
  EXPECT_EQ(errorOf("ps_1_1\ntex t0, t1\n"), "t.psh:2:9: error: 'tex' takes 1 operand (dst) in ps_1_1, found more");
  EXPECT_EQ(errorOf("ps_1_1\ndef c0, 1.0, 2.0\n"), "t.psh:2:1: error: 'def' takes a register and 4 values, found 2");
}

TEST(AssemblerErrors, Registers) {
  EXPECT_EQ(errorOf("ps.1.1\nmov r0, q3\n"),
            "t.psh:2:9: error: 'mov' src0: unknown register 'q3' (registers of ps_1_1: r#, v#, c#, t#, s#, b#, i#, "
            "p0, oC#, oDepth)");
  EXPECT_EQ(errorOf("ps_2_0\nmov oPos, r0\n"),
            "t.psh:2:5: error: 'mov' dst: unknown register 'oPos' (registers of ps_2_0: r#, v#, c#, t#, s#, b#, i#, "
            "p0, oC#, oDepth)");
  EXPECT_EQ(errorOf("vs_3_0\nmov oT0, r0\n"),
            "t.psh:2:5: error: 'mov' dst: unknown register 'oT0' (registers of vs_3_0: r#, v#, c#, a0, aL, b#, i#, "
            "p0, s#, o#)");
  EXPECT_EQ(errorOf("vs_1_1\nmov r, v0\n"), "t.psh:2:5: error: 'mov' dst: register 'r' needs a number (e.g. r0)");
  EXPECT_EQ(errorOf("vs_1_1\nmov r0, a1\n"),
            "t.psh:2:9: error: 'mov' src0: register 'a1' is out of range (a0 is the highest encodable)");
}

TEST(AssemblerErrors, SwizzlesMasksModifiers) {
  EXPECT_EQ(codeOf("vs.1.1\nmov r0, r1.xq\n"), "A2008@2:12");  // 'mov' src0: bad swizzle '.xq'
  EXPECT_EQ(codeOf("vs.1.1\nmov r0, r1.xyzwx\n"), "A2008@2:12");  // 'mov' src0: bad swizzle '.xyzwx'
  EXPECT_EQ(codeOf("vs.1.1\nmov r0, r1.xg\n"), "A2008@2:12");  // 'mov' src0: bad swizzle '.xg'
  EXPECT_EQ(codeOf("vs.1.1\nmov r0.yx, r1\n"), "A2008@2:8");  // 'mov' dst: bad write mask '.yx'
  EXPECT_EQ(codeOf("ps.1.1\nmov r0, t0_bx3\n"), "A2009@2:9");  // 'mov' src0: unknown source modifier '_bx3'
  // 'mov' src0: the invert modifier '1-' cannot be combined with '_bx2'
  EXPECT_EQ(codeOf("ps.1.1\nmov r0, 1-t0_bx2\n"), "A2009@2:9");
  EXPECT_EQ(codeOf("ps.1.1\nmul_x3 r0, t0, t0\n"), "A2010@2:1");  // 'mul_x3': unknown instruction modifier '_x3'
  // 'mul_x2': instruction modifier '_x2' is only available in ps_1_x, not in vs_2_0
  EXPECT_EQ(codeOf("vs_2_0\nmul_x2 r0, r1, r2\n"), "A2003@2:1");
  EXPECT_EQ(codeOf("ps.1.1\nmov r0_bx2, t0\n"), "A2009@2:5");  // 'mov' dst: a destination register takes no modifier
}

TEST(AssemblerErrors, VersionLine) {
  EXPECT_EQ(errorOf("mov r0, v0\n"),
            "t.psh:1:1: error: expected the shader version (vs_1_1 … ps_3_0) before the first instruction, found 'mov'");
  EXPECT_EQ(errorOf("; only a comment\n"),
            "t.psh:2:1: error: empty shader: expected a version (vs_1_1, vs_2_0, vs_3_0, ps_1_1 … ps_3_0) first");
  EXPECT_EQ(errorOf("\n ps.1.5\n"),
            "t.psh:2:2: error: unknown shader version 'ps.1.5' (expected vs_1_1, vs_2_0, vs_2_x, vs_3_0, ps_1_1, "
            "ps_1_2, ps_1_3, ps_1_4, ps_2_0, ps_2_x, ps_3_0; `vs.1.1` spelling also accepted)");
  EXPECT_EQ(errorOf("ps.1.1\nps.1.1\n"),
            "t.psh:2:1: error: a second shader version 'ps.1.1' (the version must appear once, first)");
}

TEST(AssemblerErrors, VersionSpecificForms) {
  EXPECT_EQ(codeOf("ps.1.4\ntex t0\n"), "A2003@2:1");  // 'tex' is the ps_1_1–ps_1_3 instruction; ps_1_4 uses 'texld'
  EXPECT_EQ(codeOf("ps.1.1\ntexld r0, t0\n"), "A2003@2:1");  // 'texld' needs ps_1_4 or later; ps_1_1 uses 'tex'
  EXPECT_EQ(codeOf("vs_3_0\ntexld r0, r1, s0\n"), "A2003@2:1");  // 'texld' is a pixel shader instruction
  // 'texcrd' is a ps_1_4 instruction; ps_1_1 uses 'texcoord'
  EXPECT_EQ(codeOf("ps.1.1\ntexcrd r0, t0\n"), "A2003@2:1");
  // 'texm3x3diff' is a reserved opcode that no shader version accepts
  EXPECT_EQ(codeOf("ps.1.1\ntexm3x3diff t3, t0\n"), "A2003@2:1");
  EXPECT_EQ(codeOf("vs_2_0\n+mov r0, r1\n"), "A2003@2:1");  // co-issue '+' is only available in ps_1_x, not in vs_2_0
  // predicated instructions need shader model 2.0 or later, not vs_1_1
  EXPECT_EQ(codeOf("vs_1_1\n(p0) mov r0, r1\n"), "A2003@2:1");
  EXPECT_EQ(codeOf("ps_1_4\n+phase\n"), "A2010@2:1");  // 'phase' cannot be co-issued
  EXPECT_EQ(codeOf("ps_2_x\n(p0) def c0, 1, 1, 1, 1\n"), "A2010@2:1");  // 'def' cannot be predicated
  EXPECT_EQ(codeOf("vs_2_x\nsetp p0, r0, r1\n"), "A2010@2:1");  // 'setp' needs a comparison suffix
  // 'mov' src0: relative addressing is not available in ps_2_0
  EXPECT_EQ(codeOf("ps_2_0\nmov r0, c[a0.x]\n"), "A2007@2:9");
  // 'mov' src0: vs_1_1 relative addressing reads a0.x only
  EXPECT_EQ(codeOf("vs_1_1\nmov r0, c[aL+1]\n"), "A2007@2:9");
}

TEST(AssemblerErrors, DefAndDcl) {
  EXPECT_EQ(codeOf("ps.1.1\ndef c0, 1.0, abc, 0, 0\n"), "A2012@2:14");  // 'def' value 2: expected a number, found 'abc'
  EXPECT_EQ(codeOf("ps.1.1\ndef r0, 1, 0, 0, 0\n"), "A2011@2:5");  // 'def' dst: expected a c# register, found 'r0'
  EXPECT_EQ(codeOf("vs_2_0\ndefi i0, 1.5, 0, 0, 0\n"), "A2012@2:10");  // 'defi' value 1: expected an integer
  EXPECT_EQ(codeOf("vs_2_0\ndefb b0, maybe\n"), "A2012@2:10");  // 'defb' value 1: expected true or false, found 'maybe'
  EXPECT_EQ(codeOf("vs_2_0\ndcl_bogus v0\n"), "A2013@2:1");  // unknown declaration 'dcl_bogus'
  EXPECT_EQ(codeOf("vs_2_0\ndcl_texcoord16 v0\n"), "A2013@2:1");  // usage index in 'dcl_texcoord16' must be 0 to 15
  // 'dcl_2d' dst: expected a sampler register s# for a dcl_2d declaration, found t0
  EXPECT_EQ(codeOf("ps_2_0\ndcl_2d t0\n"), "A2013@2:1");
  // 'def' value 1: number '1e99' is out of the float range
  EXPECT_EQ(codeOf("ps_2_0\ndef c0, 1e99, 0, 0, 0\n"), "A2012@2:9");
}

TEST(AssemblerErrors, CommentsAndDirectives) {
  EXPECT_EQ(errorOf("ps.1.1\n/* never closed\ntex t0\n"), "t.psh:2:1: error: unterminated comment '/*' (expected '*/')");
  EXPECT_EQ(errorOf("ps.1.1\n#define X 1\n"),
            "t.psh:2:1: error: preprocessor directive '#define' is not supported (assembly text is not preprocessed; "
            "only #line is accepted)");
  // #line renames the file and renumbers the following lines.
  EXPECT_EQ(errorOf("ps.1.1\n#line 100 \"orig.fx\"\nmull r0, t0, t0\n"),
            "orig.fx:100:1: error: unknown instruction 'mull' (did you mean 'mul'?)");
}

TEST(AssemblerErrors, ArbitraryBytesNeverCrash) {
  // Every prefix of a valid shader and a few hostile inputs either assemble or throw refx::Error.
  const std::string good =
      "vs_3_0\ndcl_position v0\ndcl_texcoord0 o1.xy\ndefi i0, 3, 0, 1, 0\nloop aL, i0\n"
      "(!p0.y) mov r0, c[aL + 2].yzxw\nendloop\nif_lt r0.x, c0.x\nmov o[aL+1], -r1_abs\nendif\n";
  for (size_t n = 0; n <= good.size(); ++n) {
    try {
      assemble(good.substr(0, n));
    } catch (const refx::Error&) {
    }
  }
  const std::string hostile[] = {
      std::string("ps.1.1\n\0\xff\xfe mov", 14),
      "vs_1_1\nmov r0, c[",
      "vs_1_1\nmov r0, c[a0.x+99999999999999999999]",
      "vs_2_0\ndefi i0, 99999999999999999999, 0, 0, 0",
      "ps_1_1\n+",
      "ps_1_1\n(",
      "vs_2_0\n(p0",
      "#line 99999999999999999999\nvs_1_1",
      "ps.1.1\nmov r0, 1",
      "ps.1.1\nmov r0, t0.",
      "ps.1.1\nmov r0., t0",
      "vs_3_0\nmov o[",
      "ps_2_0\ndcl_",
      "ps_2_0\ndcl",
      "ps_2_0\nmov_ r0, r1",
      std::string(100000, '+'),
  };
  for (const std::string& h : hostile) {
    SCOPED_TRACE(h.substr(0, 40));
    try {
      assemble(h);
    } catch (const refx::Error& e) {
      EXPECT_NE(std::string(e.what()).find(" error A2"), std::string::npos) << e.what();
    }
  }
}
