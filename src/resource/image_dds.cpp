// DDS (DirectDraw Surface): DDS_HEADER with a DDS_PIXELFORMAT given by FourCC
// (DXTn or a numeric D3DFORMAT) or by bit masks. 2D, cube (all six faces) and volume
// textures with their mip chains; data tightly packed, faces one after another.
#include <cstring>

#include "resource/image_io_internal.h"

namespace refx::resource::image {

namespace {

// DDS_HEADER.dwFlags
constexpr uint32_t DDSD_CAPS = 0x1, DDSD_HEIGHT = 0x2, DDSD_WIDTH = 0x4, DDSD_PITCH = 0x8,
                   DDSD_PIXELFORMAT = 0x1000, DDSD_MIPMAPCOUNT = 0x20000,
                   DDSD_LINEARSIZE = 0x80000, DDSD_DEPTH = 0x800000;
// DDS_PIXELFORMAT.dwFlags
constexpr uint32_t DDPF_ALPHAPIXELS = 0x1, DDPF_ALPHA = 0x2, DDPF_FOURCC = 0x4, DDPF_RGB = 0x40,
                   DDPF_LUMINANCE = 0x20000, DDPF_BUMPLUMINANCE = 0x40000,
                   DDPF_BUMPDUDV = 0x80000;
// dwCaps / dwCaps2
constexpr uint32_t DDSCAPS_COMPLEX = 0x8, DDSCAPS_TEXTURE = 0x1000, DDSCAPS_MIPMAP = 0x400000;
constexpr uint32_t DDSCAPS2_CUBEMAP = 0x200, DDSCAPS2_CUBEMAP_ALLFACES = 0xFC00,
                   DDSCAPS2_VOLUME = 0x200000;

constexpr uint32_t kHeaderSize = 124, kPixelFormatSize = 32;

// Pixel formats described by masks. `flags` is the kind bit that must be set
// (RGB, LUMINANCE, ALPHA, BUMPDUDV or BUMPLUMINANCE); alpha mask 0 = none.
struct MaskFormat {
  Format format;
  uint32_t flags, bits, r, g, b, a;
};
const MaskFormat kMaskFormats[] = {
    {Format::A8R8G8B8, DDPF_RGB, 32, 0xff0000, 0xff00, 0xff, 0xff000000},
    {Format::X8R8G8B8, DDPF_RGB, 32, 0xff0000, 0xff00, 0xff, 0},
    {Format::A8B8G8R8, DDPF_RGB, 32, 0xff, 0xff00, 0xff0000, 0xff000000},
    {Format::X8B8G8R8, DDPF_RGB, 32, 0xff, 0xff00, 0xff0000, 0},
    {Format::G16R16, DDPF_RGB, 32, 0xffff, 0xffff0000, 0, 0},
    {Format::R8G8B8, DDPF_RGB, 24, 0xff0000, 0xff00, 0xff, 0},
    {Format::R5G6B5, DDPF_RGB, 16, 0xf800, 0x7e0, 0x1f, 0},
    {Format::A1R5G5B5, DDPF_RGB, 16, 0x7c00, 0x3e0, 0x1f, 0x8000},
    {Format::X1R5G5B5, DDPF_RGB, 16, 0x7c00, 0x3e0, 0x1f, 0},
    {Format::A4R4G4B4, DDPF_RGB, 16, 0xf00, 0xf0, 0xf, 0xf000},
    {Format::L8, DDPF_LUMINANCE, 8, 0xff, 0, 0, 0},
    {Format::A8L8, DDPF_LUMINANCE, 16, 0xff, 0, 0, 0xff00},
    {Format::A4L4, DDPF_LUMINANCE, 8, 0xf, 0, 0, 0xf0},
    {Format::L16, DDPF_LUMINANCE, 16, 0xffff, 0, 0, 0},
    {Format::A8, DDPF_ALPHA, 8, 0, 0, 0, 0xff},
    {Format::V8U8, DDPF_BUMPDUDV, 16, 0xff, 0xff00, 0, 0},
    {Format::Q8W8V8U8, DDPF_BUMPDUDV, 32, 0xff, 0xff00, 0xff0000, 0xff000000},
    {Format::V16U16, DDPF_BUMPDUDV, 32, 0xffff, 0xffff0000, 0, 0},
    {Format::L6V5U5, DDPF_BUMPLUMINANCE, 16, 0x1f, 0x3e0, 0xfc00, 0},
    {Format::X8L8V8U8, DDPF_BUMPLUMINANCE, 32, 0xff, 0xff00, 0xff0000, 0},
};

constexpr uint32_t kKindFlags =
    DDPF_RGB | DDPF_LUMINANCE | DDPF_ALPHA | DDPF_BUMPDUDV | DDPF_BUMPLUMINANCE;

struct PixelFormat {
  uint32_t size, flags, fourCC, bits, r, g, b, a;
};

std::string fourCCText(uint32_t f) {
  std::string s;
  for (int i = 0; i < 4; ++i) {
    char c = char((f >> (8 * i)) & 0xff);
    s += (c >= 32 && c < 127) ? c : '?';
  }
  return s;
}

Format pixelFormatToFormat(const PixelFormat& pf, const std::string& name) {
  if (pf.flags & DDPF_FOURCC) {
    if (pf.fourCC == makeFourCC('D', 'X', '1', '0'))
      failFile(name, "DX10 extended header (DXGI formats) is not supported; "
                     "save the file with a D3D9 format");
    const FormatInfo* info = formatInfo(Format(pf.fourCC));
    if (!info) {
      if (pf.fourCC < 256) failFile(name, "unsupported D3DFORMAT {} in the FourCC", pf.fourCC);
      failFile(name, "unsupported FourCC '{}' (0x{:08x})", fourCCText(pf.fourCC), pf.fourCC);
    }
    return info->format;
  }
  uint32_t kind = pf.flags & kKindFlags;
  // DDPF_LUMINANCE | DDPF_ALPHAPIXELS is how A8L8 is written; BUMPDUDV files may also
  // carry DDPF_ALPHAPIXELS (Q8W8V8U8).
  for (const MaskFormat& m : kMaskFormats) {
    if (!(kind & m.flags) || pf.bits != m.bits) continue;
    uint32_t alpha = (pf.flags & (DDPF_ALPHAPIXELS | DDPF_ALPHA | DDPF_BUMPDUDV)) ? pf.a : 0;
    if (pf.r == m.r && pf.g == m.g && pf.b == m.b && alpha == m.a) return m.format;
  }
  failFile(name,
           "unsupported pixel format: flags 0x{:x}, {} bits, masks R 0x{:x} G 0x{:x} B 0x{:x} "
           "A 0x{:x}",
           pf.flags, pf.bits, pf.r, pf.g, pf.b, pf.a);
}

void put32(std::vector<uint8_t>& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
}

int fullChain(int w, int h, int d) {
  int m = std::max({w, h, d}), n = 1;
  while (m > 1) m >>= 1, ++n;
  return n;
}

}  // namespace

TexturePtr loadDDS(std::span<const uint8_t> bytes, const std::string& name) {
  Reader r(bytes, name);
  r.skip(4, "magic");
  r.need(kHeaderSize, "DDS header");
  uint32_t size = r.u32("header");
  if (size != kHeaderSize) failFile(name, "invalid DDS header size {} (expected 124)", size);
  uint32_t flags = r.u32("header");
  uint32_t height = r.u32("header"), width = r.u32("header");
  r.u32("header");  // pitch or linear size: data is read tightly packed
  uint32_t depth = r.u32("header");
  uint32_t mipCount = r.u32("header");
  r.skip(11 * 4, "header");
  PixelFormat pf;
  pf.size = r.u32("header");
  pf.flags = r.u32("header");
  pf.fourCC = r.u32("header");
  pf.bits = r.u32("header");
  pf.r = r.u32("header");
  pf.g = r.u32("header");
  pf.b = r.u32("header");
  pf.a = r.u32("header");
  uint32_t caps = r.u32("header"), caps2 = r.u32("header");
  r.skip(3 * 4, "header");
  (void)flags;
  (void)caps;
  if (pf.size != kPixelFormatSize)
    failFile(name, "invalid DDS pixel format size {} (expected 32)", pf.size);
  Format format = pixelFormatToFormat(pf, name);
  const FormatInfo* info = formatInfo(format);

  TextureType type = TextureType::Texture2D;
  if (caps2 & DDSCAPS2_CUBEMAP) {
    if ((caps2 & DDSCAPS2_CUBEMAP_ALLFACES) != DDSCAPS2_CUBEMAP_ALLFACES)
      failFile(name, "cube map without all six faces (caps2 0x{:x}) is not supported", caps2);
    type = TextureType::Cube;
  } else if (caps2 & DDSCAPS2_VOLUME) {
    type = TextureType::Volume;
  }
  if (type != TextureType::Volume) depth = 1;
  if (depth == 0) depth = 1;
  const char* kind = type == TextureType::Cube ? "cube" : type == TextureType::Volume ? "volume" : "2D";
  if (width == 0 || height == 0) failFile(name, "invalid size {}x{}", width, height);
  if (width > uint32_t(kMaxImageDimension) || height > uint32_t(kMaxImageDimension) ||
      depth > uint32_t(kMaxImageDimension))
    failFile(name, "{} texture size {}x{}x{} exceeds the limit of {}", kind, width, height, depth,
             kMaxImageDimension);
  if (type == TextureType::Cube && width != height)
    failFile(name, "cube map faces must be square, not {}x{}", width, height);
  if (type == TextureType::Volume && info->compressed)
    failFile(name, "compressed volume textures ({}) are not supported", info->name);
  int w = int(width), h = int(height), d = int(depth);
  if (mipCount == 0) mipCount = 1;
  if (mipCount > uint32_t(fullChain(w, h, d)))
    failFile(name, "{} mip levels, but a {}x{}x{} texture has at most {}", mipCount, w, h, d,
             fullChain(w, h, d));
  int levels = int(mipCount);
  int faces = type == TextureType::Cube ? 6 : 1;

  // Check that every level is present before allocating anything.
  size_t offset = r.pos();
  for (int f = 0; f < faces; ++f)
    for (int l = 0; l < levels; ++l) {
      size_t n = formatImageSize(format, std::max(1, w >> l), std::max(1, h >> l),
                                 std::max(1, d >> l));
      if (n > bytes.size() - offset) {
        std::string where = faces > 1 ? fmt::format("face {} mip level {}", f, l)
                                      : fmt::format("mip level {}", l);
        failFile(name, "truncated: {} needs {} bytes, {} remain", where, n, bytes.size() - offset);
      }
      offset += n;
    }

  auto tex = std::make_shared<Texture>(type, format, w, h, d, levels);
  for (int f = 0; f < faces; ++f)
    for (int l = 0; l < levels; ++l) {
      size_t n = tex->dataSize(f, l);
      std::memcpy(tex->data(f, l), r.take(n, "texture data"), n);
    }
  tex->markDirty();
  return tex;
}

std::vector<uint8_t> encodeDDS(const Texture& tex, const std::string& name) {
  const FormatInfo* info = formatInfo(tex.format());
  PixelFormat pf{kPixelFormatSize, 0, 0, 0, 0, 0, 0, 0};
  bool masked = false;
  for (const MaskFormat& m : kMaskFormats)
    if (m.format == tex.format()) {
      pf.flags = m.flags | (m.a && m.flags != DDPF_ALPHA && m.flags != DDPF_BUMPDUDV
                                ? DDPF_ALPHAPIXELS : 0);
      pf.bits = m.bits, pf.r = m.r, pf.g = m.g, pf.b = m.b, pf.a = m.a;
      masked = true;
      break;
    }
  if (!masked) {  // DXTn FourCC, or the numeric D3DFORMAT for float and other formats
    pf.flags = DDPF_FOURCC;
    pf.fourCC = uint32_t(tex.format());
  }
  int levels = tex.levelCount();
  uint32_t flags = DDSD_CAPS | DDSD_HEIGHT | DDSD_WIDTH | DDSD_PIXELFORMAT;
  flags |= info->compressed ? DDSD_LINEARSIZE : DDSD_PITCH;
  if (levels > 1) flags |= DDSD_MIPMAPCOUNT;
  if (tex.type() == TextureType::Volume) flags |= DDSD_DEPTH;
  uint32_t caps = DDSCAPS_TEXTURE;
  if (levels > 1) caps |= DDSCAPS_COMPLEX | DDSCAPS_MIPMAP;
  if (tex.type() != TextureType::Texture2D) caps |= DDSCAPS_COMPLEX;
  uint32_t caps2 = tex.type() == TextureType::Cube ? DDSCAPS2_CUBEMAP | DDSCAPS2_CUBEMAP_ALLFACES
                   : tex.type() == TextureType::Volume ? DDSCAPS2_VOLUME
                                                       : 0;
  uint32_t pitch = uint32_t(info->compressed ? tex.slicePitch(0) : tex.rowPitch(0));

  std::vector<uint8_t> out;
  put32(out, makeFourCC('D', 'D', 'S', ' '));
  put32(out, kHeaderSize);
  put32(out, flags);
  put32(out, uint32_t(tex.height()));
  put32(out, uint32_t(tex.width()));
  put32(out, pitch);
  put32(out, tex.type() == TextureType::Volume ? uint32_t(tex.depth()) : 0);
  put32(out, uint32_t(levels));
  for (int i = 0; i < 11; ++i) put32(out, 0);
  for (uint32_t v : {pf.size, pf.flags, pf.fourCC, pf.bits, pf.r, pf.g, pf.b, pf.a}) put32(out, v);
  put32(out, caps);
  put32(out, caps2);
  for (int i = 0; i < 3; ++i) put32(out, 0);
  for (int f = 0; f < tex.faceCount(); ++f)
    for (int l = 0; l < levels; ++l)
      out.insert(out.end(), tex.data(f, l), tex.data(f, l) + tex.dataSize(f, l));
  (void)name;
  return out;
}

}  // namespace refx::resource::image
