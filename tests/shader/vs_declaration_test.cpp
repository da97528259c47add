// DirectX 8 vertex shader declarations. Token values are worked out by hand from the
// d3d8types.h layout (token type << 29; STREAMDATA type << 16 | reg; SKIP 1<<28 |
// count << 16; CONSTMEM count << 25 | address; TESSELLATOR …).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/shader/vs_declaration.h"

using namespace refx::shader;

namespace {

std::string errorOf(const std::string& text) {
  try {
    parseVsDeclaration(text, "decl.h");
  } catch (const refx::Error& e) {
    return e.what();
  }
  return "(no error)";
}

bool sameElement(const VsdElement& a, const VsdElement& b) {
  return a.stream == b.stream && a.offset == b.offset && a.reg == b.reg && a.type == b.type;
}

}  // namespace

TEST(VsDeclaration, TokenMacros) {
  const char* text = R"(
    // The D3D8 C++ form.
    DWORD dwDecl[] =
    {
        D3DVSD_STREAM(0),
        D3DVSD_REG(0, D3DVSDT_FLOAT3),                 // position
        D3DVSD_REG(D3DVSDE_NORMAL, D3DVSDT_FLOAT3),
        D3DVSD_SKIP(2),
        D3DVSD_REG( 7, D3DVSDT_FLOAT2 ),
        D3DVSD_STREAM(1),
        D3DVSD_REG(D3DVSDE_DIFFUSE, D3DVSDT_D3DCOLOR),
        D3DVSD_CONST(4, 1), 1.0f, 0.5f, 0.0f, -2.0f,
        D3DVSD_END()
    };)";
  VsDeclaration d = parseVsDeclaration(text);
  const std::vector<uint32_t> expected = {
      0x20000000,  // STREAM(0): 1 << 29
      0x40020000,  // REG(0, FLOAT3): 2 << 29 | 2 << 16 | 0
      0x40020003,  // REG(NORMAL = 3, FLOAT3)
      0x50020000,  // SKIP(2): 2 << 29 | 1 << 28 | 2 << 16
      0x40010007,  // REG(7, FLOAT2 = 1)
      0x20000001,  // STREAM(1)
      0x40040005,  // REG(DIFFUSE = 5, D3DCOLOR = 4)
      0x82000004,  // CONST(4, 1): 4 << 29 | 1 << 25 | 4
      0x3F800000, 0x3F000000, 0x00000000, 0xC0000000,  // 1.0, 0.5, 0.0, -2.0
      0xFFFFFFFF,  // END
  };
  EXPECT_EQ(encodeVsDeclaration(d), expected);

  // Offsets: v0 at 0, v3 at 12 (after 3 floats), skip 2 DWORDs → v7 at 24 + 8 = 32.
  const std::vector<VsdElement> want = {
      {0, 0, 0, VsdType::Float3}, {0, 12, 3, VsdType::Float3}, {0, 32, 7, VsdType::Float2}, {1, 0, 5, VsdType::D3DColor}};
  std::vector<VsdElement> got = vsdElements(d);
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) EXPECT_TRUE(sameElement(got[i], want[i])) << i;
  EXPECT_EQ(vsdStreamSize(d, 0), 40u);  // 12 + 12 + 8 + 8
  EXPECT_EQ(vsdStreamSize(d, 1), 4u);

  // Decoding the tokens gives the same declaration back.
  EXPECT_EQ(encodeVsDeclaration(decodeVsDeclaration(expected)), expected);
}

TEST(VsDeclaration, TessellatorAndNop) {
  VsDeclaration d = parseVsDeclaration(
      "D3DVSD_STREAM_TESS(), D3DVSD_TESSNORMAL(0, 3), D3DVSD_TESSUV(7), D3DVSD_NOP(), D3DVSD_END()");
  EXPECT_EQ(encodeVsDeclaration(d), (std::vector<uint32_t>{
                                        0x30000000,  // STREAM_TESS: 1 << 29 | 1 << 28
                                        0x60020003,  // TESSNORMAL(0, 3): 3 << 29 | 0 << 20 | 2 << 16 | 3
                                        0x70010007,  // TESSUV(7): 3 << 29 | 1 << 28 | 1 << 16 | 7
                                        0x00000000,  // NOP
                                        0xFFFFFFFF}));
}

TEST(VsDeclaration, EffectDeclBlockFromTheSeeds) {
  // The BRDF effect's vertex shader declaration, verbatim.
  const char* text = R"(decl 
        { 
            stream 0; 
            float v0[3];        // Position 
            float v3[3];        // Normal 
            float v7[3];        // Texture Coord1 
            float v8[3];        // Tangent  
        })";
  VsDeclaration d = parseVsDeclaration(text);
  EXPECT_EQ(encodeVsDeclaration(d),
            (std::vector<uint32_t>{0x20000000, 0x40020000, 0x40020003, 0x40020007, 0x40020008, 0xFFFFFFFF}));
  std::vector<VsdElement> e = vsdElements(d);
  ASSERT_EQ(e.size(), 4u);
  EXPECT_EQ(e[1].offset, 12);
  EXPECT_EQ(e[2].offset, 24);
  EXPECT_EQ(e[3].offset, 36);
  EXPECT_EQ(vsdStreamSize(d, 0), 48u);
}

TEST(VsDeclaration, DeclBlockTypes) {
  VsDeclaration d = parseVsDeclaration("stream 1; float v0; float v1[4]; d3dcolor v5; ubyte v2[4]; short v3[2]; "
                                       "short v4[4]; skip 3;");
  EXPECT_EQ(encodeVsDeclaration(d), (std::vector<uint32_t>{
                                        0x20000001,  // stream 1
                                        0x40000000,  // float v0 → FLOAT1 (0)
                                        0x40030001,  // float v1[4] → FLOAT4 (3)
                                        0x40040005,  // d3dcolor → 4
                                        0x40050002,  // ubyte[4] → UBYTE4 (5)
                                        0x40060003,  // short[2] → SHORT2 (6)
                                        0x40070004,  // short[4] → SHORT4 (7)
                                        0x50030000,  // skip 3
                                        0xFFFFFFFF}));
  // 4 + 16 + 4 + 4 + 4 + 8 + 12 bytes.
  EXPECT_EQ(vsdStreamSize(d, 1), 52u);
  EXPECT_EQ(vsdStreamSize(d, 0), 0u);
}

TEST(VsDeclaration, Errors) {
  EXPECT_EQ(errorOf("D3DVSD_STREAM(0), D3DVSD_REG(0, D3DVSDT_FLOAT3)"),
            "decl.h:1:48: error: the declaration has no D3DVSD_END()");
  EXPECT_EQ(errorOf("D3DVSD_STREAM(0),\n  D3DVSD_REGG(0, D3DVSDT_FLOAT3), D3DVSD_END()"),
            "decl.h:2:3: error: unknown declaration macro 'D3DVSD_REGG' (expected D3DVSD_STREAM, D3DVSD_REG, "
            "D3DVSD_SKIP, D3DVSD_CONST, D3DVSD_TESSNORMAL, D3DVSD_TESSUV, D3DVSD_NOP or D3DVSD_END)");
  EXPECT_EQ(errorOf("D3DVSD_REG(0, D3DVSDT_FLOAT5), D3DVSD_END()"),
            "decl.h:1:15: error: unknown data type 'D3DVSDT_FLOAT5' (expected D3DVSDT_FLOAT1..4, D3DVSDT_D3DCOLOR, "
            "D3DVSDT_UBYTE4, D3DVSDT_SHORT2 or D3DVSDT_SHORT4)");
  EXPECT_EQ(errorOf("D3DVSD_STREAM(16), D3DVSD_END()"), "decl.h:1:15: error: stream number 16 is out of range (0 to 15)");
  EXPECT_EQ(errorOf("D3DVSD_CONST(0, 1), 1.0, 2.0, D3DVSD_END()"),
            "decl.h:1:31: error: D3DVSD_CONST(0, 1) needs 4 data values after it, found 2");
  EXPECT_EQ(errorOf("decl { stream 0; float q0[3]; }"), "decl.h:1:24: error: expected an input register v0..v15, found 'q0'");
  EXPECT_EQ(errorOf("decl { stream 0; float v0[3] }"),
            "decl.h:1:30: error: expected ';' after the declaration statement, found '}'");
  EXPECT_EQ(errorOf("decl { stream 0; double v0[3]; }"),
            "decl.h:1:18: error: unknown declaration statement 'double' (expected stream, float, d3dcolor, ubyte, short "
            "or skip)");
}

TEST(VsDeclaration, DecodeErrors) {
  auto message = [](std::vector<uint32_t> t) -> std::string {
    try {
      decodeVsDeclaration(t);
    } catch (const refx::Error& e) {
      return e.what();
    }
    return "(no error)";
  };
  EXPECT_EQ(message({0x20000000}), "declaration token 1: missing D3DVSD_END (0xFFFFFFFF)");
  // Token type 6 does not exist.
  EXPECT_EQ(message({0xC0000000, 0xFFFFFFFF}), "declaration token 0: unknown token type 6 in 0xC0000000");
  // CONST(0, 2) needs 8 DWORDs.
  EXPECT_EQ(message({0x84000000, 1, 2, 3}), "declaration token 0: D3DVSD_CONST needs 8 data DWORDs, 3 remain");
  EXPECT_EQ(message({0x40080000, 0xFFFFFFFF}), "declaration token 0: unknown data type 8 (D3DVSDT_* is 0..7)");
}
