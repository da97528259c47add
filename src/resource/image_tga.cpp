// Truevision TGA: colour-mapped (1, 9), true-colour (2, 10) and grey (3, 11) images,
// uncompressed or RLE, 8/15/16/24/32 bits per pixel, either vertical origin.
#include <cstring>

#include "resource/image_io_internal.h"

namespace refx::resource::image {

namespace {

struct TgaHeader {
  uint8_t idLength, colorMapType, imageType;
  uint16_t cmFirst, cmLength;
  uint8_t cmEntryBits;
  uint16_t width, height;
  uint8_t pixelBits, descriptor;
};

TgaHeader parseHeader(std::span<const uint8_t> b) {
  auto u16 = [&](int o) { return uint16_t(b[o] | (b[o + 1] << 8)); };
  return {b[0], b[1], b[2], u16(3), u16(5), b[7], u16(12), u16(14), b[16], b[17]};
}

bool validPixelBits(int type, int bits) {
  int base = type & 7;
  if (base == 1) return bits == 8 || bits == 16;
  if (base == 2) return bits == 15 || bits == 16 || bits == 24 || bits == 32;
  if (base == 3) return bits == 8 || bits == 16;
  return false;
}

struct Rgba { uint8_t r, g, b, a; };

// Expands a 15/16/24/32-bit little-endian BGR(A) value (pixel or colour-map entry).
Rgba decodeTrueColor(const uint8_t* p, int bits, bool useAlpha16) {
  if (bits == 15 || bits == 16) {
    uint16_t v = uint16_t(p[0] | (p[1] << 8));
    auto x5 = [](int c) { return uint8_t((c * 255 + 15) / 31); };  // round(c*255/31)
    uint8_t a = (bits == 16 && useAlpha16) ? ((v & 0x8000) ? 255 : 0) : 255;
    return {x5((v >> 10) & 31), x5((v >> 5) & 31), x5(v & 31), a};
  }
  return {p[2], p[1], p[0], bits == 32 ? p[3] : uint8_t(255)};
}

}  // namespace

bool looksLikeTGA(std::span<const uint8_t> bytes) {
  if (bytes.size() < 18) return false;
  TgaHeader h = parseHeader(bytes);
  int base = h.imageType & 7;
  if ((h.imageType & ~8) < 1 || (h.imageType & ~8) > 3) return false;
  if (h.colorMapType > 1 || (base == 1) != (h.colorMapType == 1)) return false;
  if (h.width == 0 || h.height == 0) return false;
  return validPixelBits(h.imageType, h.pixelBits);
}

TexturePtr loadTGA(std::span<const uint8_t> bytes, const std::string& name) {
  Reader r(bytes, name);
  r.need(18, "TGA header");
  if (!looksLikeTGA(bytes)) failFile(name, "invalid TGA header");
  TgaHeader h = parseHeader(bytes);
  r.skip(18, "TGA header");
  r.skip(h.idLength, "TGA image ID");
  int base = h.imageType & 7;
  bool rle = (h.imageType & 8) != 0;
  int alphaBits = h.descriptor & 15;
  bool useAlpha16 = alphaBits >= 1;  // 16-bit: the top bit is alpha only when declared

  // Colour map: present for type 1/9; may be present (and is skipped) for others.
  std::vector<Rgba> palette;
  if (h.colorMapType == 1) {
    int eb = h.cmEntryBits;
    if (eb != 15 && eb != 16 && eb != 24 && eb != 32)
      failFile(name, "unsupported TGA colour-map entry size {} bits", eb);
    size_t entryBytes = size_t((eb + 7) / 8);
    const uint8_t* cm = r.take(entryBytes * h.cmLength, "TGA colour map");
    if (base == 1) {
      palette.resize(h.cmLength);
      for (size_t i = 0; i < h.cmLength; ++i)
        palette[i] = decodeTrueColor(cm + i * entryBytes, eb, useAlpha16);
    }
  }

  int w = h.width, ht = h.height;
  checkImageSize(name, w, ht);
  int bpp = (h.pixelBits + 7) / 8;
  size_t npix = size_t(w) * size_t(ht);
  // A run packet of 1 + bpp bytes yields at most 128 pixels: refuse before allocating
  // when the remaining data cannot hold the image.
  if (!rle) {
    r.need(npix * bpp, fmt::format("{}x{} pixel data", w, ht));
  } else if ((npix + 127) / 128 * size_t(1 + bpp) > r.remaining()) {
    failFile(name, "truncated: RLE data for {}x{} pixels needs at least {} bytes, {} remain", w,
             ht, (npix + 127) / 128 * size_t(1 + bpp), r.remaining());
  }

  bool grey = base == 3 && h.pixelBits == 8;
  TexturePtr tex = makeImageTexture(w, ht, grey);
  uint8_t* dst = tex->data(0, 0);
  bool topDown = (h.descriptor & 0x20) != 0, rightToLeft = (h.descriptor & 0x10) != 0;

  auto store = [&](size_t i, const uint8_t* p) {
    int x = int(i % size_t(w)), y = int(i / size_t(w));
    if (!topDown) y = ht - 1 - y;
    if (rightToLeft) x = w - 1 - x;
    if (grey) {
      dst[size_t(y) * w + x] = p[0];
      return;
    }
    Rgba c;
    if (base == 1) {
      uint32_t index = bpp == 1 ? p[0] : uint32_t(p[0] | (p[1] << 8));
      if (index < h.cmFirst || index - h.cmFirst >= palette.size())
        failFile(name, "colour index {} is outside the colour map (first {}, {} entries)", index,
                 h.cmFirst, palette.size());
      c = palette[index - h.cmFirst];
    } else if (base == 3) {  // 16-bit grey + alpha
      c = {p[0], p[0], p[0], p[1]};
    } else {
      c = decodeTrueColor(p, h.pixelBits, useAlpha16);
    }
    putRGBA(dst, w, x, y, c.r, c.g, c.b, c.a);
  };

  if (!rle) {
    const uint8_t* p = r.take(npix * bpp, "pixel data");
    for (size_t i = 0; i < npix; ++i) store(i, p + i * bpp);
  } else {
    size_t i = 0;
    while (i < npix) {
      uint8_t packet = r.u8("RLE packet header");
      size_t count = size_t(packet & 0x7f) + 1;
      if (count > npix - i)
        failFile(name, "RLE packet of {} pixels runs past the end of the image", count);
      if (packet & 0x80) {
        const uint8_t* p = r.take(size_t(bpp), "RLE run pixel");
        for (size_t k = 0; k < count; ++k) store(i++, p);
      } else {
        const uint8_t* p = r.take(count * bpp, "RLE raw pixels");
        for (size_t k = 0; k < count; ++k) store(i++, p + k * bpp);
      }
    }
  }
  tex->markDirty();
  return tex;
}

}  // namespace refx::resource::image
