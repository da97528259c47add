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
#include "refx/shader/opcode_table.h"

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

namespace {

Instruction withControl(Instruction ins, uint8_t control) {
  ins.control = control;
  return ins;
}

Instruction predicated(Instruction ins, uint8_t swizzle = 0xE4, bool negate = false) {
  ins.predicated = true;
  ins.predicateSwizzle = swizzle;
  ins.predicateNot = negate;
  return ins;
}

Instruction literals(Opcode op, DstParam d, std::array<uint32_t, 4> values) {
  Instruction ins = I(op, d);
  ins.literal = values;
  return ins;
}

Instruction dclUsage(DstParam d, DeclUsage usage, uint8_t index) {
  Instruction ins = I(Opcode::Dcl, d);
  ins.usage = usage;
  ins.usageIndex = index;
  return ins;
}

Instruction dclSampler(uint16_t s, TextureType type) {
  Instruction ins = I(Opcode::Dcl, D(RegType::Sampler, s));
  ins.textureType = type;
  return ins;
}

}  // namespace

// Source modifier codes 0..13 sit in bits 27:24 of the source token: mov r0, r1 with
// each code gives 0x80E40001 | code << 24.
TEST(Bytecode, EverySourceModifier) {
  for (int mod = 0; mod <= int(SrcMod::Not); ++mod) {
    SCOPED_TRACE(mod);
    EXPECT_EQ(enc(ps14, I(Opcode::Mov, D(RegType::Temp, 0), {S(RegType::Temp, 1, 0xE4, SrcMod(mod))})),
              (W{0x00000001, 0x800F0000, 0x80E40001u | uint32_t(mod) << 24}));
  }
  // -r1_bx2 (SIGNNEG 5) on ps_1_1 t0.a: swizzle wwww = 0xFF.
  EXPECT_EQ(enc(ps11, I(Opcode::Mov, D(RegType::Temp, 0), {S(RegType::Texture, 0, 0xFF, SrcMod::SignNeg)})),
            (W{0x00000001, 0x800F0000, 0xB5FF0000}));
  // ps_1_4 texld r0, t0_dz.xyz: DZ = 9, swizzle xyzz = 0 | 1<<2 | 2<<4 | 2<<6 = 0xA4.
  EXPECT_EQ(enc(ps14, I(Opcode::Tex, D(RegType::Temp, 0), {S(RegType::Texture, 0, 0xA4, SrcMod::Dz)})),
            (W{0x00000042, 0x800F0000, 0xB9A40000}));
}

// Result modifiers in bits 23:20 and the shift nibble in bits 27:24.
TEST(Bytecode, ResultModifiersAndShifts) {
  auto mov = [](uint8_t rmod, int8_t shift) {
    return I(Opcode::Mov, D(RegType::Temp, 0, 0xF, rmod, shift), {S(RegType::Temp, 1)});
  };
  EXPECT_EQ(enc(ps20, mov(ResultSaturate, 0))[1], 0x801F0000u);
  EXPECT_EQ(enc(ps20, mov(ResultPartialPrecision, 0))[1], 0x802F0000u);
  EXPECT_EQ(enc(ps20, mov(ResultSaturate | ResultPartialPrecision, 0))[1], 0x803F0000u);
  // Shifts are 4-bit two's complement: _x2 1, _x4 2, _x8 3, _d2 -1 = 0xF, _d4 0xE, _d8 0xD.
  const std::pair<int8_t, uint32_t> shifts[] = {{1, 0x810F0000}, {2, 0x820F0000}, {3, 0x830F0000},
                                                {-1, 0x8F0F0000}, {-2, 0x8E0F0000}, {-3, 0x8D0F0000}};
  for (auto [shift, tok] : shifts) EXPECT_EQ(enc(ps14, mov(0, shift))[1], tok) << int(shift);
  // mul_x2_sat r0, ...: shift and saturate together.
  EXPECT_EQ(enc(ps11, mov(ResultSaturate, 1))[1], 0x811F0000u);
  // _centroid (4) on a ps_2_0 dcl t0: usage token is just bit 31.
  Instruction dcl = I(Opcode::Dcl, D(RegType::Texture, 0, 0xF, ResultCentroid));
  EXPECT_EQ(enc(ps20, dcl), (W{0x0200001F, 0x80000000, 0xB04F0000}));
}

TEST(Bytecode, WriteMasksAndSwizzles) {
  // .w mask = bit 19; swizzle wzyx = 3 | 2<<2 | 1<<4 | 0<<6 = 0x1B.
  EXPECT_EQ(enc(vs11, I(Opcode::Mov, D(RegType::Temp, 2, 0x8), {S(RegType::Temp, 3, 0x1B)})),
            (W{0x00000001, 0x80080002, 0x801B0003}));
  // dp3 r0.rgb, t0_bx2, v0_bx2 (ps_1_1): .rgb = 0x7.
  EXPECT_EQ(enc(ps11, I(Opcode::Dp3, D(RegType::Temp, 0, 0x7),
                        {S(RegType::Texture, 0, 0xE4, SrcMod::Sign), S(RegType::Input, 0, 0xE4, SrcMod::Sign)})),
            (W{0x00000008, 0x80070000, 0xB4E40000, 0x94E40000}));
}

// Register types split over bits 30:28 and 12:11.
TEST(Bytecode, RegisterTypeBits) {
  auto movDst = [](Version v, RegType t, uint16_t i, uint8_t mask = 0xF) {
    return enc(v, I(Opcode::Mov, D(t, i, mask), {S(RegType::Temp, 0)}))[1];
  };
  EXPECT_EQ(movDst(vs11, RegType::AttrOut, 1), 0xD00F0001u);     // 5 = 101
  EXPECT_EQ(movDst(vs11, RegType::TexCrdOut, 3), 0xE00F0003u);   // 6 = 110
  EXPECT_EQ(movDst(vs11, RegType::RastOut, 1, 0x1), 0xC0010001u); // oFog.x
  EXPECT_EQ(movDst(ps20, RegType::ColorOut, 2), 0x800F0802u);    // 8 = 01 000
  EXPECT_EQ(movDst(ps20, RegType::DepthOut, 0, 0x1), 0x90010800u); // 9 = 01 001
  // c2048.. are written as CONST2 (11), CONST3 (12), CONST4 (13) with the bank offset removed.
  auto movSrc = [](RegType t, uint16_t i) { return enc(vs30, I(Opcode::Mov, D(RegType::Temp, 0), {S(t, i)}))[2]; };
  EXPECT_EQ(movSrc(RegType::Const, 2047), 0xA0E407FFu);
  EXPECT_EQ(movSrc(RegType::Const, 2049), 0xB0E40801u);  // 11 = 01 011
  EXPECT_EQ(movSrc(RegType::Const, 4096), 0xC0E40800u);  // 12 = 01 100
  EXPECT_EQ(movSrc(RegType::Const, 6149), 0xD0E40805u);  // 13 = 01 101
  EXPECT_EQ(movSrc(RegType::ConstInt, 1), 0xF0E40001u);  // 7 = 00 111
  EXPECT_EQ(movSrc(RegType::ConstBool, 2), 0xE0E40802u); // 14 = 01 110
  EXPECT_EQ(movSrc(RegType::MiscType, 1), 0x90E41001u);  // 17 = 10 001 (vFace)
}

TEST(Bytecode, RelativeAddressing) {
  // vs_2_0 mov r0, c[a0.y+5]: address token = a0 (type 3 -> 0xB0000000) with replicate .y (0x55).
  EXPECT_EQ(enc(vs20, I(Opcode::Mov, D(RegType::Temp, 0), {Rel(S(RegType::Const, 5), RegType::Addr, 1)})),
            (W{0x03000001, 0x800F0000, 0xA0E42005, 0xB0550000}));
  // c[a0.x]: replicate .x = 0x00.
  EXPECT_EQ(enc(vs2x, I(Opcode::Mov, D(RegType::Temp, 0), {Rel(S(RegType::Const, 0), RegType::Addr, 0)})),
            (W{0x03000001, 0x800F0000, 0xA0E42000, 0xB0000000}));
  // c[aL+2]: aL = 15 = 01 111 -> 0xF0000800, swizzle .xyzw.
  EXPECT_EQ(enc(vs20, I(Opcode::Mov, D(RegType::Temp, 0), {Rel(S(RegType::Const, 2), RegType::Loop)})),
            (W{0x03000001, 0x800F0000, 0xA0E42002, 0xF0E40800}));
  // vs_3_0 mov o[aL+1], r0: destination bit 13 and its address token right after it.
  Instruction out = I(Opcode::Mov, D(RegType::Output, 1), {S(RegType::Temp, 0)});
  out.dst.relative = true;
  out.dst.rel.type = RegType::Loop;
  EXPECT_EQ(enc(vs30, out), (W{0x03000001, 0xE00F2001, 0xF0E40800, 0x80E40000}));
  // ps_3_0 v[aL+0].
  EXPECT_EQ(enc(ps30, I(Opcode::Mov, D(RegType::Temp, 0), {Rel(S(RegType::Input, 0), RegType::Loop)})),
            (W{0x03000001, 0x800F0000, 0x90E42000, 0xF0E40800}));
}

TEST(Bytecode, Predicates) {
  // (p0) add r0, r1, r2: bit 28, predicate token (type 19 = 10 011 -> 0xB0001000) after the dst.
  EXPECT_EQ(enc(ps2x, predicated(I(Opcode::Add, D(RegType::Temp, 0), {S(RegType::Temp, 1), S(RegType::Temp, 2)}))),
            (W{0x14000002, 0x800F0000, 0xB0E41000, 0x80E40001, 0x80E40002}));
  // (!p0.x) mov r0, r1: NOT = 13 -> 0x0D000000, swizzle .x = 0.
  EXPECT_EQ(enc(vs2x, predicated(I(Opcode::Mov, D(RegType::Temp, 0), {S(RegType::Temp, 1)}), 0x00, true)),
            (W{0x13000001, 0x800F0000, 0xBD001000, 0x80E40001}));
  // if !p0.x / breakp p0.y / callnz l1, !b2 take the condition as an ordinary source.
  EXPECT_EQ(enc(vs2x, I(Opcode::If, std::nullopt, {S(RegType::Predicate, 0, 0x00, SrcMod::Not)})),
            (W{0x01000028, 0xBD001000}));
  EXPECT_EQ(enc(ps30, I(Opcode::BreakP, std::nullopt, {S(RegType::Predicate, 0, 0x55)})),
            (W{0x01000060, 0xB0551000}));
  EXPECT_EQ(enc(vs20, I(Opcode::CallNZ, std::nullopt, {S(RegType::Label, 1), S(RegType::ConstBool, 2, 0xE4, SrcMod::Not)})),
            (W{0x0200001A, 0xA0E41001, 0xEDE40802}));
}

// Comparison codes in bits 18:16; texld project/bias in bits 16/17.
TEST(Bytecode, SpecificControls) {
  SrcParam r0x = S(RegType::Temp, 0, 0x00), r1x = S(RegType::Temp, 1, 0x00);
  EXPECT_EQ(enc(vs2x, withControl(I(Opcode::IfC, std::nullopt, {r0x, r1x}), uint8_t(Comparison::Lt))),
            (W{0x02040029, 0x80000000, 0x80000001}));
  EXPECT_EQ(enc(ps30, withControl(I(Opcode::BreakC, std::nullopt, {r0x, r1x}), uint8_t(Comparison::Ne))),
            (W{0x0205002D, 0x80000000, 0x80000001}));
  EXPECT_EQ(enc(ps30, withControl(I(Opcode::SetP, D(RegType::Predicate, 0), {S(RegType::Temp, 0), S(RegType::Temp, 1)}),
                                  uint8_t(Comparison::Ge))),
            (W{0x0303005E, 0xB00F1000, 0x80E40000, 0x80E40001}));
  const std::pair<Comparison, uint32_t> cmps[] = {{Comparison::Gt, 0x02010029}, {Comparison::Eq, 0x02020029},
                                                  {Comparison::Ge, 0x02030029}, {Comparison::Le, 0x02060029}};
  for (auto [c, tok] : cmps)
    EXPECT_EQ(enc(ps2x, withControl(I(Opcode::IfC, std::nullopt, {r0x, r1x}), uint8_t(c)))[0], tok);

  Instruction texld = I(Opcode::Tex, D(RegType::Temp, 0), {S(RegType::Texture, 0), S(RegType::Sampler, 0)});
  EXPECT_EQ(enc(ps20, withControl(texld, 1))[0], 0x03010042u);  // texldp
  EXPECT_EQ(enc(ps20, withControl(texld, 2))[0], 0x03020042u);  // texldb
  // texldl r0, r1, s1 (vs_3_0) and texldd r0, r1, s0, r2, r3 (ps_3_0: 5 parameters).
  EXPECT_EQ(enc(vs30, I(Opcode::TexLdl, D(RegType::Temp, 0), {S(RegType::Temp, 1), S(RegType::Sampler, 1)})),
            (W{0x0300005F, 0x800F0000, 0x80E40001, 0xA0E40801}));
  EXPECT_EQ(enc(ps30, I(Opcode::TexLdd, D(RegType::Temp, 0),
                        {S(RegType::Temp, 1), S(RegType::Sampler, 0), S(RegType::Temp, 2), S(RegType::Temp, 3)})),
            (W{0x0500005D, 0x800F0000, 0x80E40001, 0xA0E40800, 0x80E40002, 0x80E40003}));
}

TEST(Bytecode, Declarations) {
  // dcl_normal v1: usage 3.  dcl_color1 v5: usage 10, index 1.  dcl_blendindices v2: usage 2.
  EXPECT_EQ(enc(vs20, dclUsage(D(RegType::Input, 1), DeclUsage::Normal, 0)), (W{0x0200001F, 0x80000003, 0x900F0001}));
  EXPECT_EQ(enc(vs20, dclUsage(D(RegType::Input, 5), DeclUsage::Color, 1)), (W{0x0200001F, 0x8001000A, 0x900F0005}));
  EXPECT_EQ(enc(vs11, dclUsage(D(RegType::Input, 2), DeclUsage::BlendIndices, 0)), (W{0x0000001F, 0x80000002, 0x900F0002}));
  // vs_3_0 dcl_texcoord3 o4.xy: usage 5, index 3, output type 6, mask .xy.
  EXPECT_EQ(enc(vs30, dclUsage(D(RegType::Output, 4, 0x3), DeclUsage::TexCoord, 3)), (W{0x0200001F, 0x80030005, 0xE0030004}));
  // dcl_fog o5.x: usage 11.
  EXPECT_EQ(enc(vs30, dclUsage(D(RegType::Output, 5, 0x1), DeclUsage::Fog, 0)), (W{0x0200001F, 0x8000000B, 0xE0010005}));
  // Samplers: texture type at bits 30:27 (cube 3 -> 0x18000000, volume 4 -> 0x20000000).
  EXPECT_EQ(enc(ps20, dclSampler(1, TextureType::Cube)), (W{0x0200001F, 0x98000000, 0xA00F0801}));
  EXPECT_EQ(enc(ps20, dclSampler(2, TextureType::Volume)), (W{0x0200001F, 0xA0000000, 0xA00F0802}));
  EXPECT_EQ(enc(vs30, dclSampler(3, TextureType::Tex2D)), (W{0x0200001F, 0x90000000, 0xA00F0803}));
  // ps_3_0 dcl vPos.xy: misc type 17 (10 001), usage token 0x80000000.
  EXPECT_EQ(enc(ps30, I(Opcode::Dcl, D(RegType::MiscType, 0, 0x3))), (W{0x0200001F, 0x80000000, 0x90031000}));
  // ps_3_0 dcl_texcoord2_centroid v1.xy.
  Instruction tc = dclUsage(D(RegType::Input, 1, 0x3, ResultCentroid), DeclUsage::TexCoord, 2);
  EXPECT_EQ(enc(ps30, tc), (W{0x0200001F, 0x80020005, 0x90430001}));
}

TEST(Bytecode, Definitions) {
  // def c3, -0.5, 0.25, 2, -1: IEEE bits written as they are (bit 31 not forced).
  EXPECT_EQ(enc(vs11, literals(Opcode::Def, D(RegType::Const, 3),
                               {fbits(-0.5f), fbits(0.25f), fbits(2.0f), fbits(-1.0f)})),
            (W{0x00000051, 0xA00F0003, 0xBF000000, 0x3E800000, 0x40000000, 0xBF800000}));
  // defi i0, 1, -2, 3, 255: type 7 -> 0xF0000000, two's complement ints, length 5.
  EXPECT_EQ(enc(vs20, literals(Opcode::DefI, D(RegType::ConstInt, 0), {1, uint32_t(-2), 3, 255})),
            (W{0x05000030, 0xF00F0000, 1, 0xFFFFFFFE, 3, 255}));
  // defb b1, true: type 14 -> 0xE0000800, one literal, length 2.
  EXPECT_EQ(enc(ps30, literals(Opcode::DefB, D(RegType::ConstBool, 1), {1, 0, 0, 0})),
            (W{0x0200002F, 0xE00F0801, 1}));
}

TEST(Bytecode, CommentsPhaseAndFlowControl) {
  Instruction comment;
  comment.opcode = Opcode::Comment;
  comment.comment = {0x42415443, 0x0000001C};
  EXPECT_EQ(enc(vs20, comment), (W{0x0002FFFE, 0x42415443, 0x0000001C}));
  Instruction phase;
  phase.opcode = Opcode::Phase;
  EXPECT_EQ(enc(ps14, phase), (W{0x0000FFFD}));
  // Empty flow-control instructions: length 0.
  for (Opcode op : {Opcode::Ret, Opcode::Else, Opcode::EndIf, Opcode::EndLoop, Opcode::EndRep, Opcode::Break,
                    Opcode::Nop})
    EXPECT_EQ(enc(vs30, I(op, std::nullopt)), (W{uint32_t(op)}));
  // label l0 (type 18 = 10 010 -> 0xA0001000), call l0, loop aL, i0, rep i1, if b0.
  EXPECT_EQ(enc(vs20, I(Opcode::Label, std::nullopt, {S(RegType::Label, 0)})), (W{0x0100001E, 0xA0E41000}));
  EXPECT_EQ(enc(vs20, I(Opcode::Call, std::nullopt, {S(RegType::Label, 0)})), (W{0x01000019, 0xA0E41000}));
  EXPECT_EQ(enc(vs20, I(Opcode::Loop, std::nullopt, {S(RegType::Loop, 0), S(RegType::ConstInt, 0)})),
            (W{0x0200001B, 0xF0E40800, 0xF0E40000}));
  EXPECT_EQ(enc(ps2x, I(Opcode::Rep, std::nullopt, {S(RegType::ConstInt, 1)})), (W{0x01000026, 0xF0E40001}));
  EXPECT_EQ(enc(vs20, I(Opcode::If, std::nullopt, {S(RegType::ConstBool, 0)})), (W{0x01000028, 0xE0E40800}));
  // mova a0.x, r0.x (vs_2_0).
  EXPECT_EQ(enc(vs20, I(Opcode::MovA, D(RegType::Addr, 0, 0x1), {S(RegType::Temp, 0, 0x00)})),
            (W{0x0200002E, 0xB0010000, 0x80000000}));
}

// Operand forms that change with the version.
TEST(Bytecode, VersionDependentForms) {
  EXPECT_EQ(enc(ps11, I(Opcode::TexCoord, D(RegType::Texture, 1))), (W{0x00000040, 0xB00F0001}));
  EXPECT_EQ(enc(ps14, I(Opcode::TexCoord, D(RegType::Temp, 0, 0x7), {S(RegType::Texture, 1)})),
            (W{0x00000040, 0x80070000, 0xB0E40001}));
  EXPECT_EQ(enc(ps14, I(Opcode::Tex, D(RegType::Temp, 1), {S(RegType::Texture, 1)})),
            (W{0x00000042, 0x800F0001, 0xB0E40001}));
  EXPECT_EQ(enc(ps11, I(Opcode::TexKill, D(RegType::Texture, 0))), (W{0x00000041, 0xB00F0000}));
  EXPECT_EQ(enc(ps20, I(Opcode::TexKill, D(RegType::Temp, 0))), (W{0x01000041, 0x800F0000}));
  // sincos: SM2 D S S S (two scratch constants), SM3 D S.
  EXPECT_EQ(enc(vs20, I(Opcode::SinCos, D(RegType::Temp, 0, 0x3),
                        {S(RegType::Temp, 1, 0x00), S(RegType::Const, 0), S(RegType::Const, 1)})),
            (W{0x04000025, 0x80030000, 0x80000001, 0xA0E40000, 0xA0E40001}));
  EXPECT_EQ(enc(vs30, I(Opcode::SinCos, D(RegType::Temp, 0, 0x3), {S(RegType::Temp, 1, 0x00)})),
            (W{0x02000025, 0x80030000, 0x80000001}));
  EXPECT_EQ(operandCounts(Opcode::Sgn, vs2x).src, 3);
  EXPECT_EQ(operandCounts(Opcode::Sgn, vs30).src, 1);
  EXPECT_EQ(operandCounts(Opcode::Tex, ps13).src, 0);
  EXPECT_EQ(operandCounts(Opcode::Tex, ps14).src, 1);
  EXPECT_EQ(operandCounts(Opcode::Tex, ps30).src, 2);
  EXPECT_EQ(operandCounts(Opcode::TexCoord, ps12).src, 0);
  EXPECT_TRUE(operandCounts(Opcode::TexKill, ps20).dst);
  EXPECT_EQ(operandCounts(Opcode::TexM3x3Spec, ps13).src, 2);
  // ps_1_x texture-address ops: D S, texm3x3spec D S S, texdepth D.
  EXPECT_EQ(enc(ps11, I(Opcode::TexM3x3Spec, D(RegType::Texture, 3), {S(RegType::Texture, 0), S(RegType::Const, 0)})),
            (W{0x0000004C, 0xB00F0003, 0xB0E40000, 0xA0E40000}));
  EXPECT_EQ(enc(ps14, I(Opcode::TexDepth, D(RegType::Temp, 5))), (W{0x00000057, 0x800F0005}));
  EXPECT_EQ(enc(ps14, I(Opcode::Bem, D(RegType::Temp, 1, 0x3), {S(RegType::Texture, 0), S(RegType::Temp, 0)})),
            (W{0x00000059, 0x80030001, 0xB0E40000, 0x80E40000}));
  EXPECT_EQ(findOpcode(Opcode::TexM3x3Diff), nullptr);  // reserved
  EXPECT_STREQ(findOpcode(Opcode::Tex)->name, "texld");
}

// ---------------------------------------------------------------------------------
// decode(encode(x)) == x

namespace {

bool sameRel(const RelativeAddress& a, const RelativeAddress& b) {
  return a.type == b.type && a.component == b.component;
}

void expectSameInstruction(const Instruction& a, const Instruction& b, size_t n) {
  SCOPED_TRACE(::testing::Message() << "instruction " << n << " opcode " << int(a.opcode));
  EXPECT_EQ(int(a.opcode), int(b.opcode));
  EXPECT_EQ(a.control, b.control);
  EXPECT_EQ(a.coissue, b.coissue);
  EXPECT_EQ(a.predicated, b.predicated);
  if (a.predicated) {
    EXPECT_EQ(a.predicateNot, b.predicateNot);
    EXPECT_EQ(a.predicateSwizzle, b.predicateSwizzle);
  }
  EXPECT_EQ(a.hasDst, b.hasDst);
  if (a.hasDst) {
    EXPECT_EQ(int(a.dst.type), int(b.dst.type));
    EXPECT_EQ(a.dst.index, b.dst.index);
    EXPECT_EQ(a.dst.writeMask, b.dst.writeMask);
    EXPECT_EQ(a.dst.resultMod, b.dst.resultMod);
    EXPECT_EQ(a.dst.shift, b.dst.shift);
    EXPECT_EQ(a.dst.relative, b.dst.relative);
    if (a.dst.relative) {
      EXPECT_TRUE(sameRel(a.dst.rel, b.dst.rel));
    }
  }
  EXPECT_EQ(a.srcCount, b.srcCount);
  for (int i = 0; i < std::min<int>(a.srcCount, b.srcCount); ++i) {
    EXPECT_EQ(int(a.src[i].type), int(b.src[i].type)) << "src " << i;
    EXPECT_EQ(a.src[i].index, b.src[i].index) << "src " << i;
    EXPECT_EQ(a.src[i].swizzle, b.src[i].swizzle) << "src " << i;
    EXPECT_EQ(int(a.src[i].mod), int(b.src[i].mod)) << "src " << i;
    EXPECT_EQ(a.src[i].relative, b.src[i].relative) << "src " << i;
    if (a.src[i].relative) {
      EXPECT_TRUE(sameRel(a.src[i].rel, b.src[i].rel)) << "src " << i;
    }
  }
  EXPECT_EQ(a.literal, b.literal);
  if (a.opcode == Opcode::Dcl) {
    EXPECT_EQ(int(a.usage), int(b.usage));
    EXPECT_EQ(a.usageIndex, b.usageIndex);
    EXPECT_EQ(int(a.textureType), int(b.textureType));
  }
  EXPECT_EQ(a.comment, b.comment);
}

void expectRoundTrip(const Shader& s) {
  SCOPED_TRACE(s.version.name());
  std::vector<uint32_t> tokens = encode(s);
  Shader back = decode(tokens);
  EXPECT_EQ(back.version, s.version);
  ASSERT_EQ(back.instructions.size(), s.instructions.size());
  for (size_t i = 0; i < s.instructions.size(); ++i) expectSameInstruction(s.instructions[i], back.instructions[i], i);
  EXPECT_EQ(encode(back), tokens);
}

Shader shaderOf(Version v, std::vector<Instruction> ins) {
  Shader s;
  s.version = v;
  s.instructions = std::move(ins);
  return s;
}

Shader sampleVs11() {
  Instruction relSrc = I(Opcode::Mov, D(RegType::Temp, 0, 0x3), {Rel(S(RegType::Const, 3, 0xA9, SrcMod::Neg))});
  return shaderOf(vs11, {
      dclUsage(D(RegType::Input, 0), DeclUsage::Position, 0),
      dclUsage(D(RegType::Input, 3), DeclUsage::Normal, 0),
      literals(Opcode::Def, D(RegType::Const, 95), {fbits(0.5f), fbits(-1.0f), fbits(3.0e-8f), fbits(-0.0f)}),
      I(Opcode::M4x4, D(RegType::RastOut, 0), {S(RegType::Input, 0), S(RegType::Const, 4)}),
      I(Opcode::Dp3, D(RegType::Temp, 1, 0x1), {S(RegType::Input, 3), S(RegType::Const, 12)}),
      I(Opcode::Lit, D(RegType::Temp, 2), {S(RegType::Temp, 1)}),
      I(Opcode::MovA, D(RegType::Addr, 0, 0x1), {S(RegType::Temp, 1, 0x00)}),
      relSrc,
      I(Opcode::Mov, D(RegType::AttrOut, 0), {S(RegType::Temp, 2, 0x55)}),
      I(Opcode::Mov, D(RegType::RastOut, 1, 0x1), {S(RegType::Temp, 1, 0xAA)}),
      I(Opcode::ExpP, D(RegType::TexCrdOut, 7, 0x5), {S(RegType::Temp, 0, 0xFF)}),
  });
}

}  // namespace

TEST(Bytecode, RoundTripVs11) { expectRoundTrip(sampleVs11()); }

TEST(Bytecode, RoundTripPs1x) {
  Instruction co = I(Opcode::Mov, D(RegType::Temp, 0, 0x8), {S(RegType::Texture, 1, 0xFF, SrcMod::Comp)});
  co.coissue = true;
  expectRoundTrip(shaderOf(ps11, {
      literals(Opcode::Def, D(RegType::Const, 0), {fbits(1.0f), fbits(0.5f), 0, fbits(-1.0f)}),
      I(Opcode::Tex, D(RegType::Texture, 0)),
      I(Opcode::TexM3x2Pad, D(RegType::Texture, 1), {S(RegType::Texture, 0, 0xE4, SrcMod::Sign)}),
      I(Opcode::TexM3x2Tex, D(RegType::Texture, 2), {S(RegType::Texture, 0, 0xE4, SrcMod::Sign)}),
      I(Opcode::Dp3, D(RegType::Temp, 0, 0x7, ResultSaturate, 1),
        {S(RegType::Texture, 0, 0xE4, SrcMod::Sign), S(RegType::Input, 0, 0xE4, SrcMod::Bias)}),
      co,
      I(Opcode::Cnd, D(RegType::Temp, 0), {S(RegType::Temp, 0, 0xFF), S(RegType::Temp, 1), S(RegType::Const, 0, 0xE4, SrcMod::Neg)}),
  }));
  Instruction phase;
  phase.opcode = Opcode::Phase;
  expectRoundTrip(shaderOf(ps14, {
      I(Opcode::Tex, D(RegType::Temp, 0), {S(RegType::Texture, 0)}),
      I(Opcode::TexCoord, D(RegType::Temp, 1, 0x7), {S(RegType::Texture, 1, 0xA4, SrcMod::Dw)}),
      I(Opcode::Bem, D(RegType::Temp, 1, 0x3), {S(RegType::Temp, 1), S(RegType::Temp, 0)}),
      phase,
      I(Opcode::Tex, D(RegType::Temp, 1), {S(RegType::Temp, 1)}),
      I(Opcode::Mul, D(RegType::Temp, 0, 0xF, 0, -3), {S(RegType::Temp, 0, 0xE4, SrcMod::X2Neg), S(RegType::Temp, 1)}),
      I(Opcode::TexDepth, D(RegType::Temp, 5)),
  }));
  expectRoundTrip(shaderOf(ps13, {
      I(Opcode::Tex, D(RegType::Texture, 0)),
      I(Opcode::TexM3x3Pad, D(RegType::Texture, 1), {S(RegType::Texture, 0)}),
      I(Opcode::TexM3x3Pad, D(RegType::Texture, 2), {S(RegType::Texture, 0)}),
      I(Opcode::TexM3x3Spec, D(RegType::Texture, 3), {S(RegType::Texture, 0), S(RegType::Const, 0)}),
      I(Opcode::TexKill, D(RegType::Texture, 0)),
      I(Opcode::TexCoord, D(RegType::Texture, 1)),
  }));
}

TEST(Bytecode, RoundTripSm2Sm3) {
  Instruction out = I(Opcode::Mov, D(RegType::Output, 1, 0x3), {Rel(S(RegType::Input, 2), RegType::Loop)});
  out.dst.relative = true;
  out.dst.rel.type = RegType::Loop;
  expectRoundTrip(shaderOf(vs30, {
      dclUsage(D(RegType::Input, 0), DeclUsage::Position, 0),
      dclUsage(D(RegType::Output, 0), DeclUsage::Position, 0),
      dclUsage(D(RegType::Output, 1, 0x3), DeclUsage::TexCoord, 4),
      dclSampler(0, TextureType::Tex2D),
      literals(Opcode::DefI, D(RegType::ConstInt, 0), {4, 0, 1, 0}),
      literals(Opcode::DefB, D(RegType::ConstBool, 3), {1, 0, 0, 0}),
      I(Opcode::Loop, std::nullopt, {S(RegType::Loop, 0), S(RegType::ConstInt, 0)}),
      out,
      I(Opcode::Add, D(RegType::Temp, 0), {Rel(S(RegType::Const, 10), RegType::Loop), Rel(S(RegType::Const, 4000), RegType::Addr, 2)}),
      I(Opcode::EndLoop, std::nullopt),
      withControl(I(Opcode::SetP, D(RegType::Predicate, 0, 0x3), {S(RegType::Temp, 0), S(RegType::Const, 8000)}), 5),
      predicated(I(Opcode::TexLdl, D(RegType::Temp, 1), {S(RegType::Temp, 0), S(RegType::Sampler, 0)}), 0x00, true),
      I(Opcode::SinCos, D(RegType::Temp, 2, 0x3), {S(RegType::Temp, 0, 0xAA, SrcMod::AbsNeg)}),
      I(Opcode::If, std::nullopt, {S(RegType::ConstBool, 3, 0xE4, SrcMod::Not)}),
      I(Opcode::Call, std::nullopt, {S(RegType::Label, 1)}),
      I(Opcode::Else, std::nullopt),
      I(Opcode::CallNZ, std::nullopt, {S(RegType::Label, 1), S(RegType::Predicate, 0, 0x55)}),
      I(Opcode::EndIf, std::nullopt),
      I(Opcode::Mov, D(RegType::Output, 0), {S(RegType::Temp, 1)}),
      I(Opcode::Ret, std::nullopt),
      I(Opcode::Label, std::nullopt, {S(RegType::Label, 1)}),
      I(Opcode::Ret, std::nullopt),
  }));
  Instruction comment;
  comment.opcode = Opcode::Comment;
  comment.comment = {0x42415443, 0xFFFFFFFF, 0};
  expectRoundTrip(shaderOf(ps20, {
      comment,
      I(Opcode::Dcl, D(RegType::Texture, 0, 0x3, ResultCentroid | ResultPartialPrecision)),
      I(Opcode::Dcl, D(RegType::Input, 0)),
      dclSampler(0, TextureType::Cube),
      withControl(I(Opcode::Tex, D(RegType::Temp, 0, 0xF, ResultPartialPrecision), {S(RegType::Texture, 0), S(RegType::Sampler, 0)}), 1),
      I(Opcode::SinCos, D(RegType::Temp, 1, 0x3), {S(RegType::Temp, 0, 0x00), S(RegType::Const, 0), S(RegType::Const, 1)}),
      I(Opcode::Dp2Add, D(RegType::Temp, 2, 0x1, ResultSaturate), {S(RegType::Temp, 0), S(RegType::Temp, 1, 0xE4, SrcMod::Neg), S(RegType::Const, 2, 0x00)}),
      I(Opcode::TexKill, D(RegType::Temp, 0)),
      I(Opcode::Mov, D(RegType::ColorOut, 0), {S(RegType::Temp, 0)}),
      I(Opcode::Mov, D(RegType::DepthOut, 0, 0x1), {S(RegType::Temp, 2, 0x00)}),
  }));
  expectRoundTrip(shaderOf(ps30, {
      I(Opcode::Dcl, D(RegType::MiscType, 1)),
      dclUsage(D(RegType::Input, 3, 0xF, ResultCentroid), DeclUsage::Color, 1),
      withControl(I(Opcode::IfC, std::nullopt, {S(RegType::MiscType, 1, 0x00), S(RegType::Const, 0, 0x00)}), 3),
      I(Opcode::Rep, std::nullopt, {S(RegType::ConstInt, 1)}),
      withControl(I(Opcode::BreakC, std::nullopt, {S(RegType::Temp, 0, 0x00), S(RegType::Temp, 1, 0x55, SrcMod::Abs)}), 6),
      I(Opcode::Break, std::nullopt),
      I(Opcode::EndRep, std::nullopt),
      I(Opcode::EndIf, std::nullopt),
      I(Opcode::Dsx, D(RegType::Temp, 0), {S(RegType::Input, 3)}),
      I(Opcode::TexLdd, D(RegType::Temp, 0), {S(RegType::Input, 3), S(RegType::Sampler, 2), S(RegType::Temp, 0), S(RegType::Temp, 0)}),
      I(Opcode::BreakP, std::nullopt, {S(RegType::Predicate, 0, 0xFF, SrcMod::Not)}),
  }));
}

// ---------------------------------------------------------------------------------
// Malformed token streams: every one is a refx::Error naming the token.

namespace {
void expectDecodeError(std::vector<uint32_t> tokens, const std::string& expected) {
  std::string what = decodeError(std::move(tokens));
  EXPECT_NE(what.find(expected), std::string::npos) << "message: " << what << "\nexpected: " << expected;
}
}  // namespace

TEST(Bytecode, MalformedStreams) {
  expectDecodeError({}, "token 0: expected a version token");
  expectDecodeError({0x12345678}, "token 0: expected a version token");
  expectDecodeError({0xFFFF0105, 0xFFFF}, "token 0: expected a shader version");
  expectDecodeError({0xFFFE0400, 0xFFFF}, "token 0: expected a shader version");
  // No end token.
  expectDecodeError({0xFFFE0200}, "token 1: expected an instruction or the end token");
  expectDecodeError({0xFFFE0200, 0x02000001, 0x800F0000, 0x90E40000},
                    "token 4: expected an instruction or the end token");
  // Unknown opcodes: 49 (gap), 75 (reserved texm3x3diff), 0x1234.
  expectDecodeError({0xFFFF0101, 0x00000031, 0xFFFF}, "token 1: expected a known opcode, found 49");
  expectDecodeError({0xFFFF0101, 0x0000004B, 0x800F0000, 0xB0E40000, 0xFFFF}, "token 1: expected a known opcode, found 75");
  expectDecodeError({0xFFFF0101, 0x00001234, 0xFFFF}, "expected a known opcode, found 4660");
  // A parameter token where an instruction belongs.
  expectDecodeError({0xFFFF0101, 0x800F0000, 0xFFFF}, "token 1: expected an instruction token (bit 31 clear)");
  // Register type 31 (bits 30:28 = 111, 12:11 = 11) in a source, 20 in a destination.
  expectDecodeError({0xFFFE0101, 0x00000001, 0x800F0000, 0xF0E41800, 0xFFFF},
                    "token 3: expected a register type 0..19 in a source, found 31");
  expectDecodeError({0xFFFE0101, 0x00000001, 0xC00F1000, 0x80E40000, 0xFFFF},
                    "token 2: expected a register type 0..19 in the destination, found 20");
  // Length field larger than the operands: mov with length 3.
  expectDecodeError({0xFFFE0200, 0x03000001, 0x800F0000, 0x90E40000, 0x90E40000, 0xFFFF},
                    "token 1: expected 3 parameter tokens for mov (length field), found 2");
  // Length field smaller than the operands: add with length 2.
  expectDecodeError({0xFFFE0200, 0x02000002, 0x800F0000, 0x90E40000, 0x90E40001, 0xFFFF},
                    "token 4: expected a source token of the instruction at token 1, found the end of the instruction (length field)");
  // Length field past the end of the data.
  expectDecodeError({0xFFFE0200, 0x05000001, 0x800F0000}, "token 1: expected 5 parameter tokens (length field), found only 1");
  // SM1 instruction truncated.
  expectDecodeError({0xFFFF0101, 0x00000004, 0x800F0000, 0xB0E40000},
                    "token 4: expected a source token of the instruction at token 1, found the end of the data");
  // Source token without bit 31 (the end token read as an operand).
  expectDecodeError({0xFFFF0101, 0x00000002, 0x800F0000, 0xB0E40000, 0x0000FFFF},
                    "token 4: expected a source token (bit 31 set), found 0x0000FFFF");
  // Comment overrunning the buffer.
  expectDecodeError({0xFFFE0200, 0x0005FFFE, 1, 2}, "token 1: expected a comment of 5 DWORDs, found only 2");
  // def truncated inside its literals.
  expectDecodeError({0xFFFF0101, 0x00000051, 0xA00F0000, 0x3F800000}, "expected a literal value of the instruction at token 1");
  // Source modifier 14 (reserved).
  expectDecodeError({0xFFFE0101, 0x00000001, 0x800F0000, 0x8EE40000, 0xFFFF}, "token 3: expected a source modifier 0..13, found 14");
  // Predicate bit in a shader model 1 instruction.
  expectDecodeError({0xFFFE0101, 0x10000001, 0x800F0000, 0x90E40000, 0xFFFF}, "token 1: expected no predicate bit");
  // Predicate token of the wrong type (r0 instead of p0).
  expectDecodeError({0xFFFE0201, 0x13000001, 0x800F0000, 0x80E40000, 0x90E40000, 0xFFFF},
                    "token 3: expected a predicate token of type p0 (19), found type 0");
  // Relative-address token of the wrong type (c0 instead of a0/aL).
  expectDecodeError({0xFFFE0200, 0x03000001, 0x800F0000, 0xA0E42000, 0xA0000000, 0xFFFF},
                    "token 4: expected a relative-address token of type a0 (3) or aL (15), found type 2");
  // Relative source whose address token is missing (length says 2).
  expectDecodeError({0xFFFE0200, 0x02000001, 0x800F0000, 0xA0E42000, 0xFFFF},
                    "token 4: expected a relative-address token of the instruction at token 1");
  // A phase token carrying other bits, an end token with other bits.
  expectDecodeError({0xFFFF0104, 0x4000FFFD, 0xFFFF}, "token 1: expected a phase token");
  expectDecodeError({0xFFFF0104, 0x0100FFFF, 0xFFFF}, "token 1: expected the end token");
  // Data that is not whole DWORDs.
  std::vector<uint8_t> bytes = {0x00, 0x02, 0xFE, 0xFF, 0xFF, 0xFF};
  try {
    tokensFromBytes(bytes);
    ADD_FAILURE() << "no error";
  } catch (const refx::Error& e) {
    EXPECT_NE(std::string(e.what()).find("not a multiple of 4"), std::string::npos) << e.what();
  }
}

TEST(Bytecode, TokensFromBytesLittleEndian) {
  std::vector<uint8_t> bytes = {0x01, 0x01, 0xFF, 0xFF, 0xFF, 0xFF, 0x00, 0x00};
  EXPECT_EQ(tokensFromBytes(bytes), (W{0xFFFF0101, 0x0000FFFF}));
}

// Every prefix of a valid stream is an error (no end token), and every single-bit
// change either decodes or is a refx::Error, never anything else.
TEST(Bytecode, TruncationsAndBitFlipsAreSafe) {
  for (const Shader& s : {sampleVs11()}) {
    std::vector<uint32_t> tokens = encode(s);
    for (size_t n = 0; n < tokens.size(); ++n)
      EXPECT_THROW(decode(std::span(tokens).first(n)), refx::Error) << n;
    for (size_t i = 0; i < tokens.size(); ++i)
      for (int bit = 0; bit < 32; ++bit) {
        std::vector<uint32_t> t = tokens;
        t[i] ^= 1u << bit;
        try {
          Shader d = decode(t);
          (void)encode(d);
        } catch (const refx::Error&) {
        }
      }
  }
}
