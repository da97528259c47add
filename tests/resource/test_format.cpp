// Texel decoding as the shader sees it (fixed-function.md §11), encoding, DXTn blocks.
// Every expected value is worked out by hand from the bit layout; the formula is beside it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "refx/resource/format.h"

using namespace refx;

namespace {

constexpr float kEps = 1e-6f;

Color4 decode1(Format f, std::vector<uint8_t> bytes) {
  Color4 c;
  decodeRow(f, bytes.data(), 1, &c);
  return c;
}

std::vector<uint8_t> le16(uint16_t v) { return {uint8_t(v), uint8_t(v >> 8)}; }

void expectColor(Color4 c, float r, float g, float b, float a, float eps = kEps) {
  EXPECT_NEAR(c.r, r, eps);
  EXPECT_NEAR(c.g, g, eps);
  EXPECT_NEAR(c.b, b, eps);
  EXPECT_NEAR(c.a, a, eps);
}

std::vector<uint8_t> floats(std::initializer_list<float> v) {
  std::vector<uint8_t> b(v.size() * 4);
  std::memcpy(b.data(), v.begin(), b.size());
  return b;
}

}  // namespace

TEST(Format, Info) {
  EXPECT_EQ(formatInfo(Format::A8R8G8B8)->blockBytes, 4u);
  EXPECT_EQ(formatInfo(Format::R8G8B8)->blockBytes, 3u);
  EXPECT_EQ(formatInfo(Format::A16B16G16R16F)->blockBytes, 8u);
  EXPECT_EQ(formatInfo(Format::A32B32G32R32F)->blockBytes, 16u);
  EXPECT_EQ(formatInfo(Format::DXT1)->blockBytes, 8u);
  EXPECT_EQ(formatInfo(Format::DXT5)->blockBytes, 16u);
  EXPECT_TRUE(formatInfo(Format::DXT3)->compressed);
  EXPECT_TRUE(formatInfo(Format::V8U8)->isSigned);
  EXPECT_TRUE(formatInfo(Format::R16F)->isFloat);
  EXPECT_TRUE(formatInfo(Format::D24S8)->isDepth);
  EXPECT_EQ(formatInfo(Format::Unknown), nullptr);
  for (Format f : {Format::A8R8G8B8, Format::X8R8G8B8, Format::A8B8G8R8, Format::X8B8G8R8,
                   Format::R8G8B8, Format::A8, Format::L8, Format::A8L8, Format::R5G6B5,
                   Format::A1R5G5B5, Format::A4R4G4B4, Format::DXT1, Format::DXT5})
    EXPECT_TRUE(formatInfo(f)->fitsUnorm8) << formatName(f);
  for (Format f : {Format::V8U8, Format::Q8W8V8U8, Format::R16F, Format::A32B32G32R32F,
                   Format::G16R16, Format::A16B16G16R16, Format::L16})
    EXPECT_FALSE(formatInfo(f)->fitsUnorm8) << formatName(f);
}

TEST(Format, Parse) {
  EXPECT_EQ(parseFormat("A8R8G8B8"), Format::A8R8G8B8);
  EXPECT_EQ(parseFormat("d3dfmt_x8r8g8b8"), Format::X8R8G8B8);
  EXPECT_EQ(parseFormat("D3DFMT_DXT5"), Format::DXT5);
  EXPECT_EQ(parseFormat("a16b16g16r16f"), Format::A16B16G16R16F);
  EXPECT_EQ(parseFormat("A8R8G8B"), std::nullopt);
  EXPECT_EQ(parseFormat("D3DFMT_"), std::nullopt);
  EXPECT_EQ(formatName(Format::Q8W8V8U8), "Q8W8V8U8");
}

TEST(Format, Pitch) {
  EXPECT_EQ(formatRowPitch(Format::A8R8G8B8, 3), 12u);
  EXPECT_EQ(formatRowPitch(Format::DXT1, 5), 16u);  // ceil(5/4) = 2 blocks * 8
  EXPECT_EQ(formatRowPitch(Format::DXT5, 1), 16u);
  EXPECT_EQ(formatImageSize(Format::DXT5, 5, 5), 64u);            // 2*2 blocks * 16
  EXPECT_EQ(formatImageSize(Format::A8R8G8B8, 3, 2, 2), 48u);     // 3*2*2 * 4
  EXPECT_EQ(formatImageSize(Format::R5G6B5, 0, 2), 0u);
}

TEST(Format, Decode8BitRgb) {
  // Memory bytes B, G, R, A (little-endian A8R8G8B8).
  expectColor(decode1(Format::A8R8G8B8, {0x10, 0x20, 0x30, 0x40}), 0x30 / 255.f, 0x20 / 255.f,
              0x10 / 255.f, 0x40 / 255.f);
  expectColor(decode1(Format::X8R8G8B8, {0x10, 0x20, 0x30, 0x40}), 0x30 / 255.f, 0x20 / 255.f,
              0x10 / 255.f, 1);
  expectColor(decode1(Format::R8G8B8, {0x10, 0x20, 0x30}), 0x30 / 255.f, 0x20 / 255.f,
              0x10 / 255.f, 1);
  // A8B8G8R8: R in the low byte.
  expectColor(decode1(Format::A8B8G8R8, {0x10, 0x20, 0x30, 0x40}), 0x10 / 255.f, 0x20 / 255.f,
              0x30 / 255.f, 0x40 / 255.f);
  expectColor(decode1(Format::X8B8G8R8, {0x10, 0x20, 0x30, 0x40}), 0x10 / 255.f, 0x20 / 255.f,
              0x30 / 255.f, 1);
}

TEST(Format, Decode16BitPacked) {
  expectColor(decode1(Format::R5G6B5, le16(0xF800)), 1, 0, 0, 1);
  expectColor(decode1(Format::R5G6B5, le16(0x07E0)), 0, 1, 0, 1);
  expectColor(decode1(Format::R5G6B5, le16(0x001F)), 0, 0, 1, 1);
  // 0x8410: R = 16, G = (0x8410 >> 5) & 63 = 32, B = 16
  expectColor(decode1(Format::R5G6B5, le16(0x8410)), 16 / 31.f, 32 / 63.f, 16 / 31.f, 1);
  expectColor(decode1(Format::X1R5G5B5, le16(0x7C00)), 1, 0, 0, 1);
  expectColor(decode1(Format::X1R5G5B5, le16(0x0000)), 0, 0, 0, 1);  // no alpha -> 1
  expectColor(decode1(Format::A1R5G5B5, le16(0x8000)), 0, 0, 0, 1);
  expectColor(decode1(Format::A1R5G5B5, le16(0x7FFF)), 1, 1, 1, 0);
  // 0x03E0: G = 31
  expectColor(decode1(Format::A1R5G5B5, le16(0x03E0)), 0, 1, 0, 0);
  // A4R4G4B4 0xF840: A = 15, R = 8, G = 4, B = 0
  expectColor(decode1(Format::A4R4G4B4, le16(0xF840)), 8 / 15.f, 4 / 15.f, 0, 1);
}

TEST(Format, DecodeLuminanceAlpha) {
  expectColor(decode1(Format::A8, {0x80}), 0, 0, 0, 128 / 255.f);
  expectColor(decode1(Format::L8, {0x80}), 128 / 255.f, 128 / 255.f, 128 / 255.f, 1);
  // A8L8: L in bits 7:0 (first byte), A in 15:8
  expectColor(decode1(Format::A8L8, {0xC0, 0x40}), 0xC0 / 255.f, 0xC0 / 255.f, 0xC0 / 255.f,
              0x40 / 255.f);
  // A4L4 0x3C: A = 3/15, L = 12/15
  expectColor(decode1(Format::A4L4, {0x3C}), 0.8f, 0.8f, 0.8f, 0.2f);
  expectColor(decode1(Format::L16, le16(0x8000)), 32768 / 65535.f, 32768 / 65535.f,
              32768 / 65535.f, 1);
}

TEST(Format, Decode16BitChannels) {
  // G16R16: R = 0xFFFF (first WORD), G = 0x8000 -> (1, 32768/65535, 1, 1)
  expectColor(decode1(Format::G16R16, {0xFF, 0xFF, 0x00, 0x80}), 1, 32768 / 65535.f, 1, 1);
  // A16B16G16R16: R, G, B, A WORDs in memory order.
  expectColor(decode1(Format::A16B16G16R16, {0, 0, 0xFF, 0xFF, 0x00, 0x80, 0x00, 0x40}), 0, 1,
              32768 / 65535.f, 16384 / 65535.f);
}

TEST(Format, DecodeSigned) {
  // V8U8 {0x81, 0x7F}: U = -127/127 = -1, V = 127/127 = 1; B = A = 1.
  expectColor(decode1(Format::V8U8, {0x81, 0x7F}), -1, 1, 1, 1);
  // Most negative code -128 clamps to -1; V = 64/127.
  expectColor(decode1(Format::V8U8, {0x80, 0x40}), -1, 64 / 127.f, 1, 1);
  // L6V5U5 (non-negative only): U = 15 -> 15/15, V = 7 -> 7/15, L = 63 -> 1.
  // 63<<10 | 7<<5 | 15 = 0xFCEF
  expectColor(decode1(Format::L6V5U5, le16(0xFCEF)), 1, 7 / 15.f, 1, 1);
  // L = 21 -> 21/63, U = V = 0: 21<<10 = 0x5400
  expectColor(decode1(Format::L6V5U5, le16(0x5400)), 0, 0, 21 / 63.f, 1);
  // X8L8V8U8 {U=0x40, V=0xC0 (-64), L=0xFF, X}: (64/127, -64/127, 1, 1)
  expectColor(decode1(Format::X8L8V8U8, {0x40, 0xC0, 0xFF, 0x00}), 64 / 127.f, -64 / 127.f, 1, 1);
  // Q8W8V8U8 {U=127, V=-127, W=0, Q=-128 (clamped)}: (1, -1, 0, -1)
  expectColor(decode1(Format::Q8W8V8U8, {0x7F, 0x81, 0x00, 0x80}), 1, -1, 0, -1);
  // V16U16: U = 0x7FFF -> 1, V = 0xC000 = -16384 -> -16384/32767
  expectColor(decode1(Format::V16U16, {0xFF, 0x7F, 0x00, 0xC0}), 1, -16384 / 32767.f, 1, 1);
  // CxV8U8: U = 76/127, V = 0, B = sqrt(1 - U^2)
  float u = 76 / 127.f;
  expectColor(decode1(Format::CxV8U8, {76, 0}), u, 0, std::sqrt(1 - u * u), 1, 1e-5f);
}

TEST(Format, DecodeFloat) {
  EXPECT_EQ(halfToFloat(0x3C00), 1.0f);
  EXPECT_EQ(halfToFloat(0xC000), -2.0f);
  EXPECT_EQ(halfToFloat(0x7BFF), 65504.0f);          // largest half
  EXPECT_EQ(halfToFloat(0x0001), std::ldexp(1.0f, -24));  // smallest subnormal
  EXPECT_TRUE(std::isinf(halfToFloat(0x7C00)));
  // 0x3555: exponent 13 -> 2^-2, mantissa 0x155 = 341 -> 0.25 * (1 + 341/1024)
  EXPECT_EQ(halfToFloat(0x3555), 0.25f * (1 + 341 / 1024.f));
  expectColor(decode1(Format::R16F, le16(0xC000)), -2, 1, 1, 1);
  expectColor(decode1(Format::G16R16F, {0x00, 0x38, 0xFF, 0x7B}), 0.5f, 65504, 1, 1);
  expectColor(decode1(Format::A16B16G16R16F, {0x00, 0x3C, 0x00, 0xBC, 0x00, 0x00, 0x00, 0x40}), 1,
              -1, 0, 2);
  expectColor(decode1(Format::R32F, floats({1.5f})), 1.5f, 1, 1, 1);
  expectColor(decode1(Format::G32R32F, floats({-3.0f, 7.0f})), -3, 7, 1, 1);
  expectColor(decode1(Format::A32B32G32R32F, floats({1, 2, 3, 4})), 1, 2, 3, 4);
}

TEST(Format, DecodeDepth) {
  // Depth read as a texture: R = B = 0, G = depth, A = 1.
  expectColor(decode1(Format::D16, le16(0xFFFF)), 0, 1, 0, 1);
  // D24S8: depth in bits 31:8 -> 0x800000 / 0xFFFFFF
  expectColor(decode1(Format::D24S8, {0x12, 0x00, 0x00, 0x80}), 0, 8388608 / 16777215.f, 0, 1);
}

TEST(Format, HalfEncode) {
  EXPECT_EQ(floatToHalf(1.0f), 0x3C00);
  EXPECT_EQ(floatToHalf(-2.0f), 0xC000);
  EXPECT_EQ(floatToHalf(65504.0f), 0x7BFF);
  EXPECT_EQ(floatToHalf(65520.0f), 0x7C00);  // halfway past the largest rounds to inf
  EXPECT_EQ(floatToHalf(std::ldexp(1.0f, -24)), 0x0001);
  // 1 + 2^-11 is halfway between 0x3C00 and 0x3C01 -> even 0x3C00
  EXPECT_EQ(floatToHalf(1.0f + std::ldexp(1.0f, -11)), 0x3C00);
  EXPECT_EQ(floatToHalf(1.0f + 3 * std::ldexp(1.0f, -11)), 0x3C02);  // halfway -> even
}

TEST(Format, EncodeSigned) {
  uint8_t b[4];
  Color4 c{-1.0f, 0.5f, 0, 0};
  encodeRow(Format::V8U8, &c, 1, b);
  EXPECT_EQ(b[0], 0x81);  // round(-1 * 127) = -127
  EXPECT_EQ(b[1], 0x40);  // round(0.5 * 127) = round(63.5) = 64
  Color4 q{0.25f, -0.25f, 1.0f, -1.0f};
  encodeRow(Format::Q8W8V8U8, &q, 1, b);
  EXPECT_EQ(b[0], 32);    // round(31.75)
  EXPECT_EQ(b[1], 0xE0);  // round(-31.75) = -32
  EXPECT_EQ(b[2], 0x7F);
  EXPECT_EQ(b[3], 0x81);
  // L6V5U5 takes L from b (unsigned 6 bit), U/V 5-bit signed: round(0.2*15) = 3,
  // round(-1*15) = -15 = 0b10001, round(0.5*63) = 32
  Color4 l{0.2f, -1.0f, 0.5f, 1};
  encodeRow(Format::L6V5U5, &l, 1, b);
  EXPECT_EQ(b[0] | (b[1] << 8), (32 << 10) | (0x11 << 5) | 3);
}

TEST(Format, EncodeUnorm) {
  uint8_t b[8];
  Color4 c{1.0f, 0.5f, 0.0f, 1.0f};
  encodeRow(Format::R5G6B5, &c, 1, b);
  // R = 31, G = round(0.5 * 63) = 32, B = 0 -> 31<<11 | 32<<5
  EXPECT_EQ(b[0] | (b[1] << 8), (31 << 11) | (32 << 5));
  encodeRow(Format::A8L8, &c, 1, b);  // L from r
  EXPECT_EQ(b[0], 255);
  EXPECT_EQ(b[1], 255);
  Color4 a{0, 0, 0, 0.5f};
  encodeRow(Format::A8, &a, 1, b);
  EXPECT_EQ(b[0], 128);  // 0.5*255 + 0.5
  encodeRow(Format::X8R8G8B8, &a, 1, b);
  EXPECT_EQ(b[3], 0xFF);  // X written as ones
}

TEST(Format, RoundTripEveryFormat) {
  // Values on each format's grid come back exactly (within float rounding).
  struct Case { Format f; Color4 v; };
  const Case cases[] = {
      {Format::R8G8B8, {0.2f, 0.4f, 0.6f, 1}},        {Format::A8R8G8B8, {0.2f, 0.4f, 0.6f, 0.8f}},
      {Format::X8R8G8B8, {0.2f, 0.4f, 0.6f, 1}},      {Format::R5G6B5, {1, 21 / 63.f, 6 / 31.f, 1}},
      {Format::X1R5G5B5, {6 / 31.f, 12 / 31.f, 19 / 31.f, 1}}, {Format::A1R5G5B5, {6 / 31.f, 1, 0, 0}},
      {Format::A4R4G4B4, {0.2f, 0.4f, 0.6f, 0.8f}},   {Format::A8, {0, 0, 0, 0.4f}},
      {Format::A8B8G8R8, {0.2f, 0.4f, 0.6f, 0.8f}},   {Format::X8B8G8R8, {0.2f, 0.4f, 0.6f, 1}},
      {Format::G16R16, {0.2f, 0.4f, 1, 1}},           {Format::A16B16G16R16, {0.2f, 0.4f, 0.6f, 0.8f}},
      {Format::L8, {0.2f, 0.2f, 0.2f, 1}},            {Format::A8L8, {0.2f, 0.2f, 0.2f, 0.6f}},
      {Format::A4L4, {0.2f, 0.2f, 0.2f, 0.4f}},       {Format::V8U8, {-0.5f, 1, 1, 1}},
      {Format::L6V5U5, {1 / 15.f, -1, 1 / 63.f, 1}},  {Format::X8L8V8U8, {0.5f, -0.5f, 0.2f, 1}},
      {Format::Q8W8V8U8, {0.5f, -0.5f, 1, -1}},       {Format::V16U16, {0.5f, -0.25f, 1, 1}},
      {Format::L16, {0.2f, 0.2f, 0.2f, 1}},           {Format::R16F, {-0.75f, 1, 1, 1}},
      {Format::G16R16F, {0.5f, 1024, 1, 1}},          {Format::A16B16G16R16F, {1, -2, 0.25f, 8}},
      {Format::R32F, {3.25f, 1, 1, 1}},               {Format::G32R32F, {3.25f, -1e6f, 1, 1}},
      {Format::A32B32G32R32F, {1e-3f, -5, 7, 9}},     {Format::D16, {0, 0.2f, 0, 1}},
  };
  for (const Case& k : cases) {
    const FormatInfo* info = formatInfo(k.f);
    std::vector<uint8_t> buf(info->blockBytes);
    encodeRow(k.f, &k.v, 1, buf.data());
    Color4 back;
    decodeRow(k.f, buf.data(), 1, &back);
    // 8-bit signed: the grid is 1/127, so 0.5 is off by up to 0.5/127.
    float eps = info->isSigned ? 0.5f / 127 + 1e-6f : 1e-5f;
    SCOPED_TRACE(std::string(info->name));
    expectColor(back, k.v.r, k.v.g, k.v.b, k.v.a, eps);
  }
}

TEST(Format, Dxt1FourColor) {
  // c0 = 0xF800 (red) > c1 = 0x001F (blue): palette red, blue, (2c0+c1)/3, (c0+2c1)/3.
  // Indices: texel 0..3 = 0, 1, 2, 3 -> byte 0b11100100 = 0xE4; the rest 0.
  uint8_t block[8] = {0x00, 0xF8, 0x1F, 0x00, 0xE4, 0, 0, 0};
  Color4 t[16];
  decodeBlock(Format::DXT1, block, t);
  expectColor(t[0], 1, 0, 0, 1);
  expectColor(t[1], 0, 0, 1, 1);
  expectColor(t[2], 2 / 3.f, 0, 1 / 3.f, 1, 1e-6f);
  expectColor(t[3], 1 / 3.f, 0, 2 / 3.f, 1, 1e-6f);
  expectColor(t[15], 1, 0, 0, 1);
}

TEST(Format, Dxt1ThreeColorTransparent) {
  // c0 = 0x001F <= c1 = 0xF800: palette blue, red, (c0+c1)/2, transparent black.
  // Texel 5 (x=1, y=1) index 3: bits 2*5 = 10 -> byte 5 bits 2..3 = 0x0C.
  uint8_t block[8] = {0x1F, 0x00, 0x00, 0xF8, 0xE4, 0x0C, 0, 0};
  Color4 t[16];
  decodeBlock(Format::DXT1, block, t);
  expectColor(t[0], 0, 0, 1, 1);
  expectColor(t[1], 1, 0, 0, 1);
  expectColor(t[2], 0.5f, 0, 0.5f, 1);
  expectColor(t[3], 0, 0, 0, 0);
  expectColor(t[5], 0, 0, 0, 0);
  expectColor(t[4], 0, 0, 1, 1);
}

TEST(Format, Dxt3ExplicitAlpha) {
  // Alpha nibbles: texel 0 = 0, texel 1 = 15, texel 2 = 5, texel 3 = 0.
  // Color block in 4-color mode even with c0 <= c1 (c0 = c1 = 0x07E0 green, index 3
  // would be transparent in DXT1; here it is (c0 + 2c1)/3 = green).
  uint8_t block[16] = {0xF0, 0x05, 0, 0, 0, 0, 0, 0, 0xE0, 0x07, 0xE0, 0x07, 0xFF, 0xFF, 0xFF, 0xFF};
  Color4 t[16];
  decodeBlock(Format::DXT3, block, t);
  expectColor(t[0], 0, 1, 0, 0);
  expectColor(t[1], 0, 1, 0, 1);
  expectColor(t[2], 0, 1, 0, 5 / 15.f);
  expectColor(t[3], 0, 1, 0, 0);
}

TEST(Format, Dxt5AlphaEightValues) {
  // a0 = 255 > a1 = 0; texels 0..7 use indices 0..7: sum i << 3i = 0xFAC688.
  uint8_t block[16] = {255, 0, 0x88, 0xC6, 0xFA, 0, 0, 0, 0xFF, 0xFF, 0xFF, 0xFF, 0, 0, 0, 0};
  Color4 t[16];
  decodeBlock(Format::DXT5, block, t);
  // a0, a1, (6a0+a1)/7, (5a0+2a1)/7, ... (a0+6a1)/7
  const float expect[8] = {1, 0, 6 / 7.f, 5 / 7.f, 4 / 7.f, 3 / 7.f, 2 / 7.f, 1 / 7.f};
  for (int i = 0; i < 8; ++i) EXPECT_NEAR(t[i].a, expect[i], 1e-6f) << i;
  EXPECT_NEAR(t[8].a, 1, 1e-6f);
  expectColor(t[0], 1, 1, 1, 1);  // c0 = c1 = white
}

TEST(Format, Dxt5AlphaSixValues) {
  // a0 = 50 <= a1 = 100: a0, a1, (4a0+a1)/5 = 60, 70, 80, 90, then 0 and 255.
  uint8_t block[16] = {50, 100, 0x88, 0xC6, 0xFA, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  Color4 t[16];
  decodeBlock(Format::DXT4, block, t);
  const float expect[8] = {50, 100, 60, 70, 80, 90, 0, 255};
  for (int i = 0; i < 8; ++i) EXPECT_NEAR(t[i].a, expect[i] / 255.f, 1e-6f) << i;
  expectColor(t[0], 0, 0, 0, 50 / 255.f);
}

// encodeRowExact: unsigned n-bit fields store floor(v·(2ⁿ−1) + 0.5) of the float v exactly,
// signed 8-bit ones round(v·127) with ties away from zero.
TEST(Format, EncodeRowExactRounding) {
  auto encode = [](Format f, Color4 c) {
    uint8_t out[4] = {};
    encodeRowExact(f, &c, 1, out);
    return std::vector<uint8_t>(out, out + 4);
  };
  // A4R4G4B4 (bits: A 12-15, R 8-11, G 4-7, B 0-3): 0.3f·15 = 4.5000002 -> 5;
  // 0.5·15 = 7.5, a tie -> 8; 0.6f·15 = 9.0000004 -> 9.
  auto a4 = encode(Format::A4R4G4B4, {0.3f, 0.5f, 0.3f, 0.6f});
  EXPECT_EQ(a4[0], 0x85);  // G = 8, B = 5
  EXPECT_EQ(a4[1], 0x95);  // A = 9, R = 5
  // A8R8G8B8 (bytes B G R A): 0.5·255 = 127.5, a tie -> 128. The float 0x1.0101p-9 is just
  // below the tie 0.5/255: v·255 = 0.49999997 -> 0 (float arithmetic v·255.0f rounds it up
  // onto 0.5 and gives 1). 0x1.0102p-9 is just above it: 0.50000003 -> 1.
  const float below = std::ldexp(1.0f + 1.0f / 256 + 1.0f / 65536, -9);
  const float above = std::ldexp(1.0f + 1.0f / 256 + 2.0f / 65536, -9);
  ASSERT_LT(double(below) * 255.0, 0.5);
  ASSERT_GT(double(above) * 255.0, 0.5);
  auto a8 = encode(Format::A8R8G8B8, {0.5f, below, above, 1.0f});
  EXPECT_EQ(a8, (std::vector<uint8_t>{1, 0, 128, 255}));
  auto l8 = encode(Format::L8, {below, 0, 0, 0});
  EXPECT_EQ(l8[0], 0);
  // V8U8 (U byte 0, V byte 1): round(0.5·127 = 63.5) = 64 (away from zero),
  // round(-0.5·127 = -63.5) = -64 = 0xc0.
  auto v8 = encode(Format::V8U8, {0.5f, -0.5f, 0, 0});
  EXPECT_EQ(v8[0], 64);
  EXPECT_EQ(v8[1], 0xc0);
}
