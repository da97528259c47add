// Windows BMP: BITMAPINFOHEADER (and the V4/V5 extensions, and the OS/2 core header),
// 1/4/8-bit palettes, 16/24/32-bit BI_RGB and BI_BITFIELDS, bottom-up or top-down rows.
#include <array>
#include <bit>
#include <climits>

#include "resource/image_io_internal.h"

namespace refx::resource::image {

namespace {

constexpr uint32_t BI_RGB = 0, BI_RLE8 = 1, BI_RLE4 = 2, BI_BITFIELDS = 3, BI_ALPHABITFIELDS = 6;

// One colour channel given by a bit mask, expanded to 8 bits: round(v * 255 / (2^n - 1)).
struct MaskChannel {
  uint32_t mask = 0;
  int shift = 0;
  uint32_t maxv = 0;
  explicit MaskChannel(uint32_t m = 0) : mask(m) {
    if (!m) return;
    shift = std::countr_zero(m);
    int bits = std::popcount(m);
    maxv = bits >= 32 ? 0xffffffffu : (1u << bits) - 1;
  }
  uint8_t get(uint32_t v, uint8_t absent) const {
    if (!mask) return absent;
    uint64_t c = (v & mask) >> shift;
    if (c > maxv) c = maxv;  // non-contiguous mask
    return uint8_t((c * 255 + maxv / 2) / maxv);
  }
};

}  // namespace

TexturePtr loadBMP(std::span<const uint8_t> bytes, const std::string& name) {
  Reader r(bytes, name);
  r.need(14, "BMP file header");
  r.skip(2, "magic");
  r.u32("file header");
  r.u32("file header");
  uint32_t dataOffset = r.u32("file header");
  uint32_t headerSize = r.u32("BMP info header");
  int64_t width, height;
  uint32_t bits, compression = BI_RGB, colorsUsed = 0;
  uint32_t masks[4] = {0, 0, 0, 0};
  bool haveMasks = false;
  size_t paletteEntryBytes = 4;
  if (headerSize == 12) {  // BITMAPCOREHEADER
    width = r.u16("core header");
    height = r.u16("core header");
    r.u16("core header");
    bits = r.u16("core header");
    paletteEntryBytes = 3;
  } else if (headerSize >= 40 && headerSize <= 124) {
    r.need(headerSize - 4, "BMP info header");
    width = int32_t(r.u32("info header"));
    height = int32_t(r.u32("info header"));
    r.u16("info header");  // planes
    bits = r.u16("info header");
    compression = r.u32("info header");
    r.skip(12, "info header");  // image size, resolution
    colorsUsed = r.u32("info header");
    r.u32("info header");
    if (headerSize >= 52) {  // V2+ carry the masks inside the header
      for (int i = 0; i < (headerSize >= 56 ? 4 : 3); ++i) masks[i] = r.u32("colour masks");
      haveMasks = true;
    }
    r.seek(14 + size_t(headerSize), "end of info header");
    if (!haveMasks && (compression == BI_BITFIELDS || compression == BI_ALPHABITFIELDS)) {
      int n = compression == BI_ALPHABITFIELDS ? 4 : 3;
      for (int i = 0; i < n; ++i) masks[i] = r.u32("colour masks");
      haveMasks = true;
    }
  } else {
    failFile(name, "unsupported BMP header size {}", headerSize);
  }

  if (compression == BI_RLE8 || compression == BI_RLE4)
    failFile(name, "RLE-compressed BMP is not supported");
  if (compression != BI_RGB && compression != BI_BITFIELDS && compression != BI_ALPHABITFIELDS)
    failFile(name, "unsupported BMP compression {}", compression);
  if (bits != 1 && bits != 4 && bits != 8 && bits != 16 && bits != 24 && bits != 32)
    failFile(name, "unsupported BMP bit count {}", bits);
  if (compression != BI_RGB && bits != 16 && bits != 32)
    failFile(name, "BI_BITFIELDS needs 16 or 32 bits per pixel, not {}", bits);
  bool topDown = height < 0;
  if (height == INT32_MIN) failFile(name, "invalid image height");
  if (topDown) height = -height;
  checkImageSize(name, width, height);

  std::vector<std::array<uint8_t, 4>> palette;  // r, g, b, a
  if (bits <= 8) {
    size_t n = colorsUsed ? colorsUsed : size_t(1) << bits;
    if (n > 256) failFile(name, "palette of {} colours (at most 256)", n);
    const uint8_t* p = r.take(n * paletteEntryBytes, "BMP palette");
    palette.resize(n);
    for (size_t i = 0; i < n; ++i, p += paletteEntryBytes) palette[i] = {p[2], p[1], p[0], 255};
  }
  if (compression == BI_RGB && bits == 16) {
    masks[0] = 0x7c00, masks[1] = 0x3e0, masks[2] = 0x1f, masks[3] = 0;  // X1R5G5B5
  } else if (compression == BI_RGB && bits == 32) {
    masks[0] = 0xff0000, masks[1] = 0xff00, masks[2] = 0xff, masks[3] = 0;  // X8R8G8B8
  } else if (compression == BI_BITFIELDS && masks[3] && headerSize < 56) {
    masks[3] = 0;
  }
  MaskChannel mr(masks[0]), mg(masks[1]), mb(masks[2]), ma(masks[3]);

  size_t rowBytes = (size_t(width) * bits + 31) / 32 * 4;  // rows padded to 4 bytes
  size_t total = rowBytes * size_t(height);
  r.seek(dataOffset, "pixel data");
  // The last row need not carry its padding.
  size_t needed = total - rowBytes + (size_t(width) * bits + 7) / 8;
  r.need(needed, fmt::format("{}x{} pixel data", width, height));
  const uint8_t* data = r.here();

  int w = int(width), h = int(height);
  TexturePtr tex = makeImageTexture(w, h, false);
  uint8_t* dst = tex->data(0, 0);
  for (int row = 0; row < h; ++row) {
    const uint8_t* p = data + size_t(row) * rowBytes;
    int y = topDown ? row : h - 1 - row;
    for (int x = 0; x < w; ++x) {
      if (bits <= 8) {
        int perByte = 8 / int(bits);
        uint8_t byte = p[x / perByte];
        int shift = 8 - int(bits) * (x % perByte + 1);
        uint32_t index = (byte >> shift) & ((1u << bits) - 1);
        if (index >= palette.size())
          failFile(name, "colour index {} is outside the palette ({} entries)", index,
                   palette.size());
        const auto& c = palette[index];
        putRGBA(dst, w, x, y, c[0], c[1], c[2], c[3]);
      } else if (bits == 24) {
        const uint8_t* q = p + size_t(x) * 3;
        putRGBA(dst, w, x, y, q[2], q[1], q[0], 255);
      } else {
        const uint8_t* q = p + size_t(x) * (bits / 8);
        uint32_t v = bits == 16 ? uint32_t(q[0] | (q[1] << 8))
                                : uint32_t(q[0]) | (uint32_t(q[1]) << 8) |
                                      (uint32_t(q[2]) << 16) | (uint32_t(q[3]) << 24);
        putRGBA(dst, w, x, y, mr.get(v, 0), mg.get(v, 0), mb.get(v, 0), ma.get(v, 255));
      }
    }
  }
  tex->markDirty();
  return tex;
}

}  // namespace refx::resource::image
