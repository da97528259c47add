// DirectX 8 vertex shader declarations: the D3DVSD token stream that D3D8's
// CreateVertexShader took beside the shader tokens, binding vertex stream data to the
// v# input registers of a vs_1_1 shader that has no dcl instructions.
//
// Token layout (d3d8types.h): token type in bits 31:29 (D3DVSD_TOKENTYPESHIFT 29).
//   NOP         0x00000000
//   STREAM      1<<29 | stream (bits 3:0); STREAM_TESS = 1<<29 | 1<<28
//   STREAMDATA  2<<29 | type<<16 | reg (bits 4:0)           D3DVSD_REG(reg, type)
//               2<<29 | 1<<28 | dwords<<16                  D3DVSD_SKIP(dwords)
//   TESSELLATOR 3<<29 | regIn<<20 | 2<<16 | regOut          D3DVSD_TESSNORMAL(in, out)
//               3<<29 | 1<<28 | 1<<16 | reg                 D3DVSD_TESSUV(reg)
//   CONSTMEM    4<<29 | count<<25 | address (bits 6:0), then count*4 DWORDs of data
//   EXT         5<<29 | count<<24 | info (bits 23:0), then count DWORDs
//   END         0xFFFFFFFF
#pragma once
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace refx::shader {

// D3DVSDT_*: the data type of one element, as stored in the vertex buffer. The shader
// reads it as 4 floats with missing components (0, 0, 0, 1); D3DCOLOR 0xAARRGGBB
// arrives as (R, G, B, A) / 255, UBYTE4 as (x, y, z, w) unnormalised, SHORTn signed.
enum class VsdType : uint8_t { Float1 = 0, Float2, Float3, Float4, D3DColor, UByte4, Short2, Short4 };

int vsdTypeSize(VsdType type);        // bytes in the vertex: 4, 8, 12, 16, 4, 4, 4, 8
int vsdTypeComponents(VsdType type);  // 1, 2, 3, 4, 4, 4, 2, 4
const char* vsdTypeName(VsdType type);  // "D3DVSDT_FLOAT3" …

// D3DVSD_TOKENTYPE.
enum class VsdTokenType : uint8_t {
  Nop = 0, Stream = 1, StreamData = 2, Tessellator = 3, ConstMem = 4, Ext = 5, End = 7,
};

// One declaration entry (one token, plus its data for CONST/EXT).
struct VsdEntry {
  enum class Kind : uint8_t {
    Nop, Stream, StreamTess, Reg, Skip, TessNormal, TessUV, Const, Ext,
  };
  Kind kind = Kind::Nop;
  uint8_t stream = 0;          // Stream
  uint8_t reg = 0;             // Reg, TessUV, TessNormal (output register)
  uint8_t regIn = 0;           // TessNormal input register
  VsdType type = VsdType::Float1;  // Reg
  uint8_t count = 0;           // Skip: DWORDs; Const: registers (0..15); Ext: DWORDs (0..31)
  uint16_t address = 0;        // Const: first constant register (0..127)
  uint32_t info = 0;           // Ext: bits 23:0
  std::vector<uint32_t> data;  // Const: count*4 DWORDs (float bits); Ext: count DWORDs
};

struct VsDeclaration {
  std::vector<VsdEntry> entries;  // in declaration order, without the END token
};

// An element of a vertex stream bound to an input register.
struct VsdElement {
  uint8_t stream = 0;
  uint16_t offset = 0;  // bytes from the start of the vertex in that stream
  uint8_t reg = 0;      // v#
  VsdType type = VsdType::Float1;
};

// The stream elements in declaration order, offsets accumulated per stream
// (D3DVSD_SKIP advances the offset by 4 bytes per DWORD).
std::vector<VsdElement> vsdElements(const VsDeclaration& decl);
// Bytes per vertex the declaration consumes from `stream` (elements and skips).
uint32_t vsdStreamSize(const VsDeclaration& decl, uint8_t stream);

// Parses either text form; throws refx::Error "file:line:col: error: …".
//  * token macros as in D3D8 C++ code:
//      DWORD dwDecl[] = { D3DVSD_STREAM(0), D3DVSD_REG(0, D3DVSDT_FLOAT3),
//                         D3DVSD_REG(D3DVSDE_NORMAL, D3DVSDT_FLOAT3), D3DVSD_SKIP(2),
//                         D3DVSD_CONST(4, 1), 1.0f, 0.0f, 0.0f, 1.0f, D3DVSD_END() };
//    register arguments may be numbers or D3DVSDE_* names, types D3DVSDT_* names;
//  * the DirectX 8 effect `decl` block:
//      decl { stream 0; float v0[3]; float v3[3]; d3dcolor v5; skip 2; }
//    with element types float (1..4), d3dcolor, ubyte (4), short (2 or 4).
VsDeclaration parseVsDeclaration(std::string_view text, std::string_view fileName = "<input>");

// The D3DVSD DWORD stream including the END token.
std::vector<uint32_t> encodeVsDeclaration(const VsDeclaration& decl);
// Tokens (up to and including END) → declaration; throws refx::Error naming the
// token offset for unknown token types, bad fields or a missing END.
VsDeclaration decodeVsDeclaration(std::span<const uint32_t> tokens);

}  // namespace refx::shader
