// D3D9 token encoding and decoding. Expected DWORDs are worked out from the field
// tables of bytecode.md (register type bits 30:28 + 12:11, write mask 19:16, result
// modifier 23:20, shift 27:24, swizzle 23:16, source modifier 27:24, bit 31 on every
// parameter token, length in 27:24 of the opcode token for SM2+).
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <optional>

#include "refx/core/diagnostics.h"
#include "refx/shader/bytecode.h"

using namespace refx::shader;

namespace {

const Version vs11{ShaderType::Vertex, 1, 1};
const Version vs20{ShaderType::Vertex, 2, 0};
const Version vs2x{ShaderType::Vertex, 2, 1};
const Version vs30{ShaderType::Vertex, 3, 0};
const Version ps11{ShaderType::Pixel, 1, 1};
const Version ps12{ShaderType::Pixel, 1, 2};
const Version ps13{ShaderType::Pixel, 1, 3};
const Version ps14{ShaderType::Pixel, 1, 4};
const Version ps20{ShaderType::Pixel, 2, 0};
const Version ps2x{ShaderType::Pixel, 2, 1};
const Version ps30{ShaderType::Pixel, 3, 0};

DstParam D(RegType t, uint16_t i, uint8_t mask = 0xF, uint8_t rmod = 0, int8_t shift = 0) {
  DstParam d;
  d.type = t;
  d.index = i;
  d.writeMask = mask;
  d.resultMod = rmod;
  d.shift = shift;
  return d;
}

SrcParam S(RegType t, uint16_t i, uint8_t swz = 0xE4, SrcMod mod = SrcMod::None) {
  SrcParam s;
  s.type = t;
  s.index = i;
  s.swizzle = swz;
  s.mod = mod;
  return s;
}

SrcParam Rel(SrcParam s, RegType at = RegType::Addr, uint8_t comp = 0) {
  s.relative = true;
  s.rel.type = at;
  s.rel.component = comp;
  return s;
}

Instruction I(Opcode op, std::optional<DstParam> d, std::initializer_list<SrcParam> srcs = {}) {
  Instruction ins;
  ins.opcode = op;
  if (d) {
    ins.hasDst = true;
    ins.dst = *d;
  }
  for (const SrcParam& s : srcs) ins.src[ins.srcCount++] = s;
  return ins;
}

// The tokens of one instruction: encode a shader holding only it and strip the
// version and end tokens.
std::vector<uint32_t> enc(Version v, const Instruction& ins) {
  Shader s;
  s.version = v;
  s.instructions.push_back(ins);
  std::vector<uint32_t> t = encode(s);
  EXPECT_EQ(t.front(), v.token());
  EXPECT_EQ(t.back(), 0x0000FFFFu);
  return std::vector<uint32_t>(t.begin() + 1, t.end() - 1);
}

using W = std::vector<uint32_t>;

uint32_t fbits(float f) { return std::bit_cast<uint32_t>(f); }

std::string decodeError(std::vector<uint32_t> tokens) {
  try {
    decode(tokens);
  } catch (const refx::Error& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(Bytecode, VersionTokensAndNames) {
  EXPECT_EQ(vs11.token(), 0xFFFE0101u);
  EXPECT_EQ(vs20.token(), 0xFFFE0200u);
  EXPECT_EQ(vs2x.token(), 0xFFFE0201u);  // 2_x = minor 1
  EXPECT_EQ(ps14.token(), 0xFFFF0104u);
  EXPECT_EQ(ps30.token(), 0xFFFF0300u);
  EXPECT_EQ(vs11.name(), "vs_1_1");
  EXPECT_EQ(vs2x.name(), "vs_2_x");
  EXPECT_EQ(ps2x.name(), "ps_2_x");
  EXPECT_EQ(ps14.name(), "ps_1_4");
  EXPECT_EQ(ps30.name(), "ps_3_0");
  EXPECT_EQ((Version{ShaderType::Vertex, 3, 0xFF}.name()), "vs_3_sw");
}

// bytecode.md §11, each row.
TEST(Bytecode, WorkedEncodings) {
  Shader empty;
  empty.version = vs20;
  EXPECT_EQ(encode(empty), (W{0xFFFE0200, 0x0000FFFF}));

  Instruction dcl = I(Opcode::Dcl, D(RegType::Input, 0));
  dcl.usage = DeclUsage::Position;
  EXPECT_EQ(enc(vs20, dcl), (W{0x0200001F, 0x80000000, 0x900F0000}));

  dcl.usage = DeclUsage::TexCoord;  // usage 5, index 1 at bits 19:16
  dcl.usageIndex = 1;
  dcl.dst.index = 2;
  EXPECT_EQ(enc(vs20, dcl), (W{0x0200001F, 0x80010005, 0x900F0002}));

  EXPECT_EQ(enc(vs20, I(Opcode::Mov, D(RegType::RastOut, 0), {S(RegType::Input, 0)})),
            (W{0x02000001, 0xC00F0000, 0x90E40000}));

  // vs_1_1: no length field.
  EXPECT_EQ(enc(vs11, I(Opcode::M4x4, D(RegType::RastOut, 0), {S(RegType::Input, 0), S(RegType::Const, 0)})),
            (W{0x00000014, 0xC00F0000, 0x90E40000, 0xA0E40000}));

  // mov r0.xy, -c[a0.x+3].yzzz: yzzz = 1|2<<2|2<<4|2<<6 = 0xA9; vs_1_1 has no address token.
  EXPECT_EQ(enc(vs11, I(Opcode::Mov, D(RegType::Temp, 0, 0x3),
                        {Rel(S(RegType::Const, 3, 0xA9, SrcMod::Neg))})),
            (W{0x00000001, 0x80030000, 0xA1A92003}));

  Instruction def = I(Opcode::Def, D(RegType::Const, 0));
  def.literal = {fbits(1.0f), fbits(0.0f), fbits(0.0f), fbits(1.0f)};
  EXPECT_EQ(enc(ps20, def), (W{0x05000051, 0xA00F0000, 0x3F800000, 0, 0, 0x3F800000}));

  // texld r0, t0, s0: sampler type 10 = 0b01010 -> 0x20000000 | 0x800.
  EXPECT_EQ(enc(ps20, I(Opcode::Tex, D(RegType::Temp, 0), {S(RegType::Texture, 0), S(RegType::Sampler, 0)})),
            (W{0x03000042, 0x800F0000, 0xB0E40000, 0xA0E40800}));

  Instruction dcl2d = I(Opcode::Dcl, D(RegType::Sampler, 0));
  dcl2d.textureType = TextureType::Tex2D;  // 2 << 27 = 0x10000000
  EXPECT_EQ(enc(ps20, dcl2d), (W{0x0200001F, 0x90000000, 0xA00F0800}));

  EXPECT_EQ(enc(ps20, I(Opcode::Add, D(RegType::Temp, 0, 0xF, ResultSaturate),
                        {S(RegType::Temp, 1), S(RegType::Const, 0)})),
            (W{0x03000002, 0x801F0000, 0x80E40001, 0xA0E40000}));

  EXPECT_EQ(enc(ps11, I(Opcode::Tex, D(RegType::Texture, 0))), (W{0x00000042, 0xB00F0000}));

  EXPECT_EQ(enc(ps11, I(Opcode::Mul, D(RegType::Temp, 0, 0x7, 0, 1),
                        {S(RegType::Texture, 0), S(RegType::Input, 0)})),
            (W{0x00000005, 0x81070000, 0xB0E40000, 0x90E40000}));

  Instruction co = I(Opcode::Mov, D(RegType::Temp, 0, 0x8), {S(RegType::Texture, 0)});
  co.coissue = true;
  EXPECT_EQ(enc(ps11, co), (W{0x40000001, 0x80080000, 0xB0E40000}));
}

TEST(Bytecode, MalformedStreams) {
  EXPECT_NE(decodeError({}).find("token 0: expected a version token"), std::string::npos);
  EXPECT_NE(decodeError({0x12345678}).find("token 0: expected a version token"), std::string::npos);
  EXPECT_NE(decodeError({0xFFFF0105, 0xFFFF}).find("token 0: expected a shader version"), std::string::npos);
  // No end token.
  EXPECT_NE(decodeError({0xFFFE0200}).find("token 1: expected an instruction or the end token"),
            std::string::npos);
}
