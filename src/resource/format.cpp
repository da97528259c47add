// Format table and texel codecs. Every non-compressed format is described as a list of
// bit fields of its little-endian texel plus a mapping to the (r, g, b, a) a shader sees;
// one generic decoder/encoder reads those descriptions, with fast paths for the formats
// that are sampled most.
#include "refx/resource/format.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstring>
#include <limits>

namespace refx {

namespace {

enum class Kind : uint8_t { Unorm, Snorm, Half, Float, Pad };

struct Channel {
  uint8_t offset = 0;  // bit offset in the texel (little-endian)
  uint8_t bits = 0;    // 0 = channel unused
  Kind kind = Kind::Unorm;
};

// Output component source: channel 0..3, or a constant.
constexpr int8_t kZero = -1, kOne = -2;

struct Layout {
  Format format;
  std::array<Channel, 4> ch;  // fields of the texel
  std::array<int8_t, 4> out;  // (r, g, b, a) <- channel index or constant
  bool cxv8u8 = false;        // b = sqrt(1 - u^2 - v^2)
};

constexpr Channel U(int off, int bits) { return {uint8_t(off), uint8_t(bits), Kind::Unorm}; }
constexpr Channel S(int off, int bits) { return {uint8_t(off), uint8_t(bits), Kind::Snorm}; }
constexpr Channel H(int off) { return {uint8_t(off), 16, Kind::Half}; }
constexpr Channel F(int off) { return {uint8_t(off), 32, Kind::Float}; }
constexpr Channel X(int off, int bits) { return {uint8_t(off), uint8_t(bits), Kind::Pad}; }
constexpr Channel N{};

// Channel order in `ch` is free; `out` says what the shader sees (fixed-function.md §11).
// Pad channels (X) are written as all ones so the texel reads back opaque as its A-variant.
const Layout kLayouts[] = {
    {Format::R8G8B8, {U(16, 8), U(8, 8), U(0, 8), N}, {0, 1, 2, kOne}},
    {Format::A8R8G8B8, {U(16, 8), U(8, 8), U(0, 8), U(24, 8)}, {0, 1, 2, 3}},
    {Format::X8R8G8B8, {U(16, 8), U(8, 8), U(0, 8), X(24, 8)}, {0, 1, 2, kOne}},
    {Format::R5G6B5, {U(11, 5), U(5, 6), U(0, 5), N}, {0, 1, 2, kOne}},
    {Format::X1R5G5B5, {U(10, 5), U(5, 5), U(0, 5), X(15, 1)}, {0, 1, 2, kOne}},
    {Format::A1R5G5B5, {U(10, 5), U(5, 5), U(0, 5), U(15, 1)}, {0, 1, 2, 3}},
    {Format::A4R4G4B4, {U(8, 4), U(4, 4), U(0, 4), U(12, 4)}, {0, 1, 2, 3}},
    {Format::A8, {N, N, N, U(0, 8)}, {kZero, kZero, kZero, 3}},
    {Format::A8B8G8R8, {U(0, 8), U(8, 8), U(16, 8), U(24, 8)}, {0, 1, 2, 3}},
    {Format::X8B8G8R8, {U(0, 8), U(8, 8), U(16, 8), X(24, 8)}, {0, 1, 2, kOne}},
    {Format::G16R16, {U(0, 16), U(16, 16), N, N}, {0, 1, kOne, kOne}},
    {Format::A16B16G16R16, {U(0, 16), U(16, 16), U(32, 16), U(48, 16)}, {0, 1, 2, 3}},
    {Format::L8, {U(0, 8), N, N, N}, {0, 0, 0, kOne}},
    {Format::A8L8, {U(0, 8), N, N, U(8, 8)}, {0, 0, 0, 3}},
    {Format::A4L4, {U(0, 4), N, N, U(4, 4)}, {0, 0, 0, 3}},
    {Format::V8U8, {S(0, 8), S(8, 8), N, N}, {0, 1, kOne, kOne}},
    {Format::L6V5U5, {S(0, 5), S(5, 5), U(10, 6), N}, {0, 1, 2, kOne}},
    {Format::X8L8V8U8, {S(0, 8), S(8, 8), U(16, 8), X(24, 8)}, {0, 1, 2, kOne}},
    {Format::Q8W8V8U8, {S(0, 8), S(8, 8), S(16, 8), S(24, 8)}, {0, 1, 2, 3}},
    {Format::V16U16, {S(0, 16), S(16, 16), N, N}, {0, 1, kOne, kOne}},
    // Depth formats when read as textures: R = B = 0, G = depth, A = 1 (docs; the
    // shadow-map comparison some drivers do is not modelled).
    {Format::D16, {N, U(0, 16), N, N}, {kZero, 1, kZero, kOne}},
    {Format::D24S8, {N, U(8, 24), N, X(0, 8)}, {kZero, 1, kZero, kOne}},
    {Format::L16, {U(0, 16), N, N, N}, {0, 0, 0, kOne}},
    {Format::R16F, {H(0), N, N, N}, {0, kOne, kOne, kOne}},
    {Format::G16R16F, {H(0), H(16), N, N}, {0, 1, kOne, kOne}},
    {Format::A16B16G16R16F, {H(0), H(16), H(32), H(48)}, {0, 1, 2, 3}},
    {Format::R32F, {F(0), N, N, N}, {0, kOne, kOne, kOne}},
    {Format::G32R32F, {F(0), F(32), N, N}, {0, 1, kOne, kOne}},
    {Format::A32B32G32R32F, {F(0), F(32), F(64), F(96)}, {0, 1, 2, 3}},
    {Format::CxV8U8, {S(0, 8), S(8, 8), N, N}, {0, 1, kOne, kOne}, true},
};

//                 format                 name             bytes cmp    signed float  unorm8 depth
const FormatInfo kInfos[] = {
    {Format::R8G8B8, "R8G8B8", 3, false, false, false, true},
    {Format::A8R8G8B8, "A8R8G8B8", 4, false, false, false, true},
    {Format::X8R8G8B8, "X8R8G8B8", 4, false, false, false, true},
    {Format::R5G6B5, "R5G6B5", 2, false, false, false, true},
    {Format::X1R5G5B5, "X1R5G5B5", 2, false, false, false, true},
    {Format::A1R5G5B5, "A1R5G5B5", 2, false, false, false, true},
    {Format::A4R4G4B4, "A4R4G4B4", 2, false, false, false, true},
    {Format::A8, "A8", 1, false, false, false, true},
    {Format::A8B8G8R8, "A8B8G8R8", 4, false, false, false, true},
    {Format::X8B8G8R8, "X8B8G8R8", 4, false, false, false, true},
    {Format::G16R16, "G16R16", 4, false, false, false, false},
    {Format::A16B16G16R16, "A16B16G16R16", 8, false, false, false, false},
    {Format::L8, "L8", 1, false, false, false, true},
    {Format::A8L8, "A8L8", 2, false, false, false, true},
    {Format::A4L4, "A4L4", 1, false, false, false, true},
    {Format::V8U8, "V8U8", 2, false, true, false, false},
    {Format::L6V5U5, "L6V5U5", 2, false, true, false, false},
    {Format::X8L8V8U8, "X8L8V8U8", 4, false, true, false, false},
    {Format::Q8W8V8U8, "Q8W8V8U8", 4, false, true, false, false},
    {Format::V16U16, "V16U16", 4, false, true, false, false},
    {Format::D16, "D16", 2, false, false, false, false, true},
    {Format::L16, "L16", 2, false, false, false, false},
    {Format::D24S8, "D24S8", 4, false, false, false, false, true},
    {Format::R16F, "R16F", 2, false, false, true, false},
    {Format::G16R16F, "G16R16F", 4, false, false, true, false},
    {Format::A16B16G16R16F, "A16B16G16R16F", 8, false, false, true, false},
    {Format::R32F, "R32F", 4, false, false, true, false},
    {Format::G32R32F, "G32R32F", 8, false, false, true, false},
    {Format::A32B32G32R32F, "A32B32G32R32F", 16, false, false, true, false},
    {Format::CxV8U8, "CxV8U8", 2, false, true, false, false},
    {Format::DXT1, "DXT1", 8, true, false, false, true},
    {Format::DXT2, "DXT2", 16, true, false, false, true},
    {Format::DXT3, "DXT3", 16, true, false, false, true},
    {Format::DXT4, "DXT4", 16, true, false, false, true},
    {Format::DXT5, "DXT5", 16, true, false, false, true},
};

const Layout* layoutOf(Format f) {
  for (const Layout& l : kLayouts)
    if (l.format == f) return &l;
  return nullptr;
}

uint64_t readBits64(const uint8_t* p, int bytes) {
  uint64_t v = 0;
  std::memcpy(&v, p, size_t(std::min(bytes, 8)));  // little-endian host
  return v;
}

float snormValue(uint32_t code, int bits) {
  // Two's complement n-bit s -> s / (2^(n-1) - 1), most negative code clamped to -1.
  int32_t s = int32_t(code << (32 - bits)) >> (32 - bits);
  float v = float(s) / float((1u << (bits - 1)) - 1);
  return std::max(v, -1.0f);
}

uint32_t readField(const uint8_t* texel, int bytesPerTexel, const Channel& c) {
  int byte = c.offset / 8, shift = c.offset % 8;
  uint64_t v = readBits64(texel + byte, bytesPerTexel - byte);
  v >>= shift;
  return uint32_t(c.bits >= 32 ? v : v & ((uint64_t(1) << c.bits) - 1));
}

void writeField(uint8_t* texel, const Channel& c, uint32_t value) {
  // Fields never straddle more than 4 bytes in these formats; bit-by-byte write.
  uint64_t mask = c.bits >= 32 ? 0xffffffffull : ((uint64_t(1) << c.bits) - 1);
  uint64_t v = (uint64_t(value) & mask) << (c.offset % 8);
  uint64_t m = mask << (c.offset % 8);
  uint8_t* p = texel + c.offset / 8;
  for (int i = 0; m != 0; ++i, v >>= 8, m >>= 8) p[i] = uint8_t((p[i] & ~m) | (v & m));
}

float decodeField(uint32_t code, const Channel& c) {
  switch (c.kind) {
    case Kind::Unorm: return float(double(code) / double((uint64_t(1) << c.bits) - 1));
    case Kind::Snorm: return snormValue(code, c.bits);
    case Kind::Half: return halfToFloat(uint16_t(code));
    case Kind::Float: { float f; std::memcpy(&f, &code, 4); return f; }
    case Kind::Pad: return 1.0f;
  }
  return 0;
}

uint32_t encodeField(float v, const Channel& c) {
  switch (c.kind) {
    case Kind::Unorm: {
      double maxv = double((uint64_t(1) << c.bits) - 1);
      double x = std::isnan(v) ? 0.0 : std::clamp(double(v), 0.0, 1.0);
      return uint32_t(std::floor(x * maxv + 0.5));
    }
    case Kind::Snorm: {
      // round(v * (2^(n-1) - 1)), e.g. round(v * 127) for 8 bits.
      double maxv = double((1u << (c.bits - 1)) - 1);
      double x = std::isnan(v) ? 0.0 : std::clamp(double(v), -1.0, 1.0);
      return uint32_t(int32_t(std::lround(x * maxv)));
    }
    case Kind::Half: return floatToHalf(v);
    case Kind::Float: { uint32_t u; std::memcpy(&u, &v, 4); return u; }
    case Kind::Pad: return 0xffffffffu;
  }
  return 0;
}

float component(const Color4& c, int i) {
  return i == 0 ? c.r : i == 1 ? c.g : i == 2 ? c.b : c.a;
}

// R5G6B5 endpoint to float RGB.
Color4 rgb565(uint16_t c) {
  return {float((c >> 11) & 31) / 31.0f, float((c >> 5) & 63) / 63.0f, float(c & 31) / 31.0f,
          1.0f};
}

void decodeColorBlock(const uint8_t* b, bool allowTransparent, Color4 out[16]) {
  uint16_t c0 = uint16_t(b[0] | (b[1] << 8)), c1 = uint16_t(b[2] | (b[3] << 8));
  Color4 p[4];
  p[0] = rgb565(c0);
  p[1] = rgb565(c1);
  auto mix = [&](float w0, float w1, float d) {
    return Color4{(w0 * p[0].r + w1 * p[1].r) / d, (w0 * p[0].g + w1 * p[1].g) / d,
                  (w0 * p[0].b + w1 * p[1].b) / d, 1.0f};
  };
  if (c0 > c1 || !allowTransparent) {
    p[2] = mix(2, 1, 3);  // (2c0 + c1) / 3
    p[3] = mix(1, 2, 3);  // (c0 + 2c1) / 3
  } else {
    p[2] = mix(1, 1, 2);  // (c0 + c1) / 2
    p[3] = {0, 0, 0, 0};  // transparent black
  }
  uint32_t idx = uint32_t(b[4]) | (uint32_t(b[5]) << 8) | (uint32_t(b[6]) << 16) |
                 (uint32_t(b[7]) << 24);
  for (int i = 0; i < 16; ++i) out[i] = p[(idx >> (2 * i)) & 3];
}

}  // namespace

float halfToFloat(uint16_t h) {
  uint32_t sign = uint32_t(h & 0x8000) << 16;
  uint32_t exp = (h >> 10) & 0x1f, man = h & 0x3ff;
  uint32_t bits;
  if (exp == 0) {
    if (man == 0) {
      bits = sign;
    } else {  // subnormal: man * 2^-24
      float f = float(man) * (1.0f / 16777216.0f);
      return sign ? -f : f;
    }
  } else if (exp == 31) {
    bits = sign | 0x7f800000u | (man << 13);
  } else {
    bits = sign | ((exp + 112) << 23) | (man << 13);
  }
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

uint16_t floatToHalf(float f) {
  uint32_t x;
  std::memcpy(&x, &f, 4);
  uint16_t sign = uint16_t((x >> 16) & 0x8000);
  uint32_t absx = x & 0x7fffffffu;
  if (absx >= 0x7f800000u)  // inf or nan
    return uint16_t(sign | 0x7c00 | (absx > 0x7f800000u ? 0x200 : 0));
  if (absx >= 0x477ff000u) return uint16_t(sign | 0x7c00);  // rounds past 65504 -> inf
  if (absx < 0x38800000u) {                                   // below 2^-14: subnormal half
    // value / 2^-24, rounded to nearest even.
    float a;
    std::memcpy(&a, &absx, 4);
    float m = a * 16777216.0f;
    return uint16_t(sign | uint16_t(std::nearbyint(m)));
  }
  uint32_t mant = absx & 0x7fffff;
  uint32_t exp = (absx >> 23) - 112;
  uint32_t h = (exp << 10) | (mant >> 13);
  uint32_t rest = mant & 0x1fff;
  if (rest > 0x1000 || (rest == 0x1000 && (h & 1))) ++h;  // round to nearest even
  return uint16_t(sign | h);
}

const FormatInfo* formatInfo(Format f) {
  for (const FormatInfo& i : kInfos)
    if (i.format == f) return &i;
  return nullptr;
}

std::optional<Format> parseFormat(std::string_view name) {
  auto ieq = [](std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
      if (std::toupper(uint8_t(a[i])) != std::toupper(uint8_t(b[i]))) return false;
    return true;
  };
  if (name.size() > 7 && ieq(name.substr(0, 7), "D3DFMT_")) name.remove_prefix(7);
  for (const FormatInfo& i : kInfos)
    if (ieq(name, i.name)) return i.format;
  return std::nullopt;
}

std::string_view formatName(Format f) {
  const FormatInfo* i = formatInfo(f);
  return i ? i->name : std::string_view("UNKNOWN");
}

size_t formatRowPitch(Format f, int width) {
  const FormatInfo* i = formatInfo(f);
  if (!i || width <= 0) return 0;
  if (i->compressed) return size_t((width + 3) / 4) * i->blockBytes;
  return size_t(width) * i->blockBytes;
}

size_t formatImageSize(Format f, int width, int height, int depth) {
  const FormatInfo* i = formatInfo(f);
  if (!i || width <= 0 || height <= 0 || depth <= 0) return 0;
  size_t rows = i->compressed ? size_t((height + 3) / 4) : size_t(height);
  return formatRowPitch(f, width) * rows * size_t(depth);
}

void decodeRow(Format f, const uint8_t* src, int count, Color4* out) {
  switch (f) {  // fast paths for the formats sampled most
    case Format::A8R8G8B8:
    case Format::X8R8G8B8: {
      bool x = f == Format::X8R8G8B8;
      for (int i = 0; i < count; ++i, src += 4)
        out[i] = {src[2] / 255.0f, src[1] / 255.0f, src[0] / 255.0f, x ? 1.0f : src[3] / 255.0f};
      return;
    }
    case Format::L8:
      for (int i = 0; i < count; ++i) {
        float l = src[i] / 255.0f;
        out[i] = {l, l, l, 1.0f};
      }
      return;
    case Format::A8:
      for (int i = 0; i < count; ++i) out[i] = {0, 0, 0, src[i] / 255.0f};
      return;
    case Format::A32B32G32R32F:
      std::memcpy(out, src, size_t(count) * 16);
      return;
    default: break;
  }
  const Layout* l = layoutOf(f);
  const FormatInfo* info = formatInfo(f);
  if (!l || !info) {
    std::fill(out, out + count, Color4{0, 0, 0, 0});
    return;
  }
  int bpt = int(info->blockBytes);
  for (int i = 0; i < count; ++i, src += bpt) {
    float v[4] = {0, 0, 0, 0};
    for (int c = 0; c < 4; ++c)
      if (l->ch[c].bits) v[c] = decodeField(readField(src, bpt, l->ch[c]), l->ch[c]);
    float o[4];
    for (int k = 0; k < 4; ++k) o[k] = l->out[k] == kOne ? 1.0f : l->out[k] == kZero ? 0.0f : v[l->out[k]];
    if (l->cxv8u8) o[2] = std::sqrt(std::max(0.0f, 1.0f - o[0] * o[0] - o[1] * o[1]));
    out[i] = {o[0], o[1], o[2], o[3]};
  }
}

namespace {

// Every field through encodeField (exact rounding, any layout).
void encodeFields(Format f, const Color4* src, int count, uint8_t* out) {
  const Layout* l = layoutOf(f);
  const FormatInfo* info = formatInfo(f);
  if (!l || !info) return;
  int bpt = int(info->blockBytes);
  // Each field takes the first shader component that reads it (L8: r, A8L8: r and a).
  int source[4] = {-1, -1, -1, -1};
  for (int k = 3; k >= 0; --k)
    if (l->out[k] >= 0) source[l->out[k]] = k;
  for (int i = 0; i < count; ++i, out += bpt) {
    std::memset(out, 0, size_t(bpt));
    for (int c = 0; c < 4; ++c) {
      const Channel& ch = l->ch[c];
      if (!ch.bits) continue;
      float v = source[c] >= 0 ? component(src[i], source[c]) : 1.0f;
      writeField(out, ch, encodeField(v, ch));
    }
  }
}

}  // namespace

void encodeRowExact(Format f, const Color4* src, int count, uint8_t* out) {
  encodeFields(f, src, count, out);
}

void encodeRow(Format f, const Color4* src, int count, uint8_t* out) {
  switch (f) {
    case Format::A8R8G8B8:
    case Format::X8R8G8B8: {
      bool x = f == Format::X8R8G8B8;
      for (int i = 0; i < count; ++i, out += 4) {
        out[0] = unorm8Safe(src[i].b);
        out[1] = unorm8Safe(src[i].g);
        out[2] = unorm8Safe(src[i].r);
        out[3] = x ? 0xff : unorm8Safe(src[i].a);
      }
      return;
    }
    case Format::L8:
      for (int i = 0; i < count; ++i) out[i] = unorm8Safe(src[i].r);
      return;
    case Format::A8:
      for (int i = 0; i < count; ++i) out[i] = unorm8Safe(src[i].a);
      return;
    case Format::A32B32G32R32F:
      std::memcpy(out, src, size_t(count) * 16);
      return;
    default: break;
  }
  encodeFields(f, src, count, out);
}

void decodeBlock(Format f, const uint8_t* block, Color4 out[16]) {
  switch (f) {
    case Format::DXT1:
      decodeColorBlock(block, true, out);
      return;
    case Format::DXT2:
    case Format::DXT3:
      decodeColorBlock(block + 8, false, out);
      for (int i = 0; i < 16; ++i) {
        // 4 bits per texel at bits 4*(4y + x) of the 64-bit alpha block.
        int nib = (block[i / 2] >> ((i & 1) * 4)) & 15;
        out[i].a = float(nib) / 15.0f;
      }
      return;
    case Format::DXT4:
    case Format::DXT5: {
      decodeColorBlock(block + 8, false, out);
      float a0 = block[0], a1 = block[1], pal[8];
      pal[0] = a0;
      pal[1] = a1;
      if (block[0] > block[1]) {
        for (int k = 1; k <= 6; ++k) pal[k + 1] = ((7 - k) * a0 + k * a1) / 7.0f;
      } else {
        for (int k = 1; k <= 4; ++k) pal[k + 1] = ((5 - k) * a0 + k * a1) / 5.0f;
        pal[6] = 0;
        pal[7] = 255;
      }
      uint64_t bits = 0;
      for (int k = 0; k < 6; ++k) bits |= uint64_t(block[2 + k]) << (8 * k);
      for (int i = 0; i < 16; ++i) out[i].a = pal[(bits >> (3 * i)) & 7] / 255.0f;
      return;
    }
    default:
      for (int i = 0; i < 16; ++i) out[i] = {0, 0, 0, 0};
  }
}

}  // namespace refx
