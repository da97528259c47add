// Texture and surface formats, numbered as D3DFORMAT.
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "refx/core/color.h"

namespace refx {

constexpr uint32_t makeFourCC(char a, char b, char c, char d) {
  return uint32_t(uint8_t(a)) | (uint32_t(uint8_t(b)) << 8) | (uint32_t(uint8_t(c)) << 16) |
         (uint32_t(uint8_t(d)) << 24);
}

enum class Format : uint32_t {
  Unknown = 0,
  R8G8B8 = 20,
  A8R8G8B8 = 21,
  X8R8G8B8 = 22,
  R5G6B5 = 23,
  X1R5G5B5 = 24,
  A1R5G5B5 = 25,
  A4R4G4B4 = 26,
  A8 = 28,
  A8B8G8R8 = 32,
  X8B8G8R8 = 33,
  G16R16 = 34,
  A16B16G16R16 = 36,
  L8 = 50,
  A8L8 = 51,
  A4L4 = 52,
  V8U8 = 60,
  L6V5U5 = 61,
  X8L8V8U8 = 62,
  Q8W8V8U8 = 63,
  V16U16 = 64,
  D16 = 80,
  L16 = 81,
  D24S8 = 75,
  R16F = 111,
  G16R16F = 112,
  A16B16G16R16F = 113,
  R32F = 114,
  G32R32F = 115,
  A32B32G32R32F = 116,
  CxV8U8 = 117,
  DXT1 = makeFourCC('D', 'X', 'T', '1'),
  DXT2 = makeFourCC('D', 'X', 'T', '2'),
  DXT3 = makeFourCC('D', 'X', 'T', '3'),
  DXT4 = makeFourCC('D', 'X', 'T', '4'),
  DXT5 = makeFourCC('D', 'X', 'T', '5'),
};

struct FormatInfo {
  Format format;
  std::string_view name;     // "A8R8G8B8"
  uint32_t blockBytes;       // bytes per texel, or per 4x4 block when compressed
  bool compressed;           // DXTn: 4x4 blocks
  bool isSigned;             // V8U8, Q8W8V8U8, ... (some channels signed)
  bool isFloat;              // R16F ... A32B32G32R32F
  bool fitsUnorm8;           // every channel decodes exactly or nearly to 8-bit unorm
  bool isDepth = false;      // D16, D24S8: depth-stencil surfaces (G = depth when read)
};

// nullptr for unknown formats.
const FormatInfo* formatInfo(Format f);
// Case-insensitive, accepts an optional "D3DFMT_" prefix.
std::optional<Format> parseFormat(std::string_view name);
std::string_view formatName(Format f);

// Bytes for one row of blocks/texels of the given width (whole 4x4 block rows for DXT).
size_t formatRowPitch(Format f, int width);
// Bytes for a whole w×h×d image.
size_t formatImageSize(Format f, int width, int height, int depth = 1);

// Decodes `count` consecutive texels of one row of a non-compressed format to the
// values a shader sees (missing channels filled as the texld table says).
void decodeRow(Format f, const uint8_t* src, int count, Color4* out);
// Encodes values (as a shader would read them back) into a row of a non-compressed format.
void encodeRow(Format f, const Color4* src, int count, uint8_t* out);
// encodeRow with exact rounding: an n-bit unsigned field stores floor(v·(2ⁿ−1) + 0.5),
// a signed one round(v·(2ⁿ⁻¹−1)) with ties away from zero, both computed in double
// (encodeRow's 8-bit formats form v·255 in float first, which can round a value just
// below a tie up onto it). The scene-script texture generators store texels this way.
void encodeRowExact(Format f, const Color4* src, int count, uint8_t* out);
// unorm8() that maps NaN to 0 (float textures may hold NaN).
inline uint8_t unorm8Safe(float v) { return v == v ? unorm8(v) : uint8_t(0); }

// IEEE half <-> float (round to nearest even; overflow gives infinity).
float halfToFloat(uint16_t h);
uint16_t floatToHalf(float f);

// Decodes one 4x4 DXTn block into 16 texels (row-major).
void decodeBlock(Format f, const uint8_t* block, Color4 out[16]);

}  // namespace refx
