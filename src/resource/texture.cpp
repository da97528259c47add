// Texture storage in the texture's own format, plus lazily decoded copies for sampling.
#include "refx/resource/texture.h"

#include <algorithm>

#include "refx/core/diagnostics.h"

namespace refx {

namespace {

constexpr int kMaxDimension = 16384;
// Refuse textures whose storage would exceed this many bytes (all faces and levels).
constexpr uint64_t kMaxTextureBytes = uint64_t(1) << 32;

const char* typeName(TextureType t) {
  return t == TextureType::Cube ? "cube" : t == TextureType::Volume ? "volume" : "2D";
}

int fullChain(int w, int h, int d) {
  int m = std::max({w, h, d}), n = 1;
  while (m > 1) m >>= 1, ++n;
  return n;
}

}  // namespace

Texture::Texture(TextureType type, Format format, int width, int height, int depth, int levels)
    : type_(type), format_(format), width_(width), height_(height), depth_(depth), levels_(levels) {
  const FormatInfo* info = formatInfo(format);
  if (!info) fail("texture: unknown format {}", uint32_t(format));
  auto checkDim = [&](const char* what, int v) {
    if (v <= 0 || v > kMaxDimension)
      fail("{} texture: {} {} is out of range (1 to {})", typeName(type), what, v, kMaxDimension);
  };
  checkDim("width", width);
  checkDim("height", height);
  if (type == TextureType::Volume) {
    checkDim("depth", depth);
  } else if (depth != 1) {
    fail("{} texture: depth must be 1, not {}", typeName(type), depth);
  }
  if (type == TextureType::Cube && width != height)
    fail("cube texture: faces must be square, not {}x{}", width, height);
  if (type == TextureType::Volume && info->compressed)
    fail("volume texture: compressed format {} is not supported for volumes", info->name);
  int full = fullChain(width, height, depth);
  if (levels < 0 || levels > full)
    fail("{} texture {}x{}x{}: {} mip levels requested, the full chain has {}", typeName(type),
         width, height, depth, levels, full);
  if (levels == 0) levels_ = full;

  uint64_t total = 0;
  for (int l = 0; l < levels_; ++l)
    total += formatImageSize(format, this->width(l), this->height(l), this->depth(l));
  total *= uint64_t(faceCount());
  if (total > kMaxTextureBytes)
    fail("{} texture {}x{}x{} {}: {} bytes of storage exceeds the limit of {} bytes",
         typeName(type), width, height, depth, info->name, total, kMaxTextureBytes);

  size_t n = size_t(faceCount()) * size_t(levels_);
  storage_.resize(n);
  for (int f = 0; f < faceCount(); ++f)
    for (int l = 0; l < levels_; ++l)
      storage_[index(f, l)].assign(
          formatImageSize(format, this->width(l), this->height(l), this->depth(l)), 0);
  decoded_ = std::vector<std::atomic<const SampleLevel*>>(n);
  decodedOwned_.resize(n);
}

std::shared_ptr<Texture> Texture::create2D(Format f, int w, int h, int levels) {
  return std::make_shared<Texture>(TextureType::Texture2D, f, w, h, 1, levels);
}
std::shared_ptr<Texture> Texture::createCube(Format f, int size, int levels) {
  return std::make_shared<Texture>(TextureType::Cube, f, size, size, 1, levels);
}
std::shared_ptr<Texture> Texture::createVolume(Format f, int w, int h, int d, int levels) {
  return std::make_shared<Texture>(TextureType::Volume, f, w, h, d, levels);
}

int Texture::width(int level) const { return std::max(1, width_ >> level); }
int Texture::height(int level) const { return std::max(1, height_ >> level); }
int Texture::depth(int level) const {
  return type_ == TextureType::Volume ? std::max(1, depth_ >> level) : 1;
}

uint8_t* Texture::data(int face, int level) {
  if (face < 0 || face >= faceCount() || level < 0 || level >= levels_)
    fail("texture: face {} level {} does not exist", face, level);
  return storage_[index(face, level)].data();
}
const uint8_t* Texture::data(int face, int level) const {
  return const_cast<Texture*>(this)->data(face, level);
}
size_t Texture::dataSize(int face, int level) const {
  if (face < 0 || face >= faceCount() || level < 0 || level >= levels_) return 0;
  return storage_[index(face, level)].size();
}
size_t Texture::rowPitch(int level) const { return formatRowPitch(format_, width(level)); }
size_t Texture::slicePitch(int level) const {
  return formatImageSize(format_, width(level), height(level), 1);
}

Color4 Texture::texel(int face, int level, int x, int y, int z) const {
  const uint8_t* base = data(face, level);
  if (x < 0 || y < 0 || z < 0 || x >= width(level) || y >= height(level) || z >= depth(level))
    fail("texture: texel ({}, {}, {}) is outside level {} ({}x{}x{})", x, y, z, level,
         width(level), height(level), depth(level));
  const FormatInfo* info = formatInfo(format_);
  const uint8_t* slice = base + size_t(z) * slicePitch(level);
  if (info->compressed) {
    Color4 block[16];
    decodeBlock(format_, slice + size_t(y / 4) * rowPitch(level) + size_t(x / 4) * info->blockBytes,
                block);
    return block[(y % 4) * 4 + x % 4];
  }
  Color4 c;
  decodeRow(format_, slice + size_t(y) * rowPitch(level) + size_t(x) * info->blockBytes, 1, &c);
  return c;
}

void Texture::setTexel(int face, int level, int x, int y, int z, Color4 c) {
  uint8_t* base = data(face, level);
  const FormatInfo* info = formatInfo(format_);
  if (info->compressed) fail("texture: cannot set single texels of compressed format {}", info->name);
  if (x < 0 || y < 0 || z < 0 || x >= width(level) || y >= height(level) || z >= depth(level))
    fail("texture: texel ({}, {}, {}) is outside level {} ({}x{}x{})", x, y, z, level,
         width(level), height(level), depth(level));
  encodeRow(format_, &c,  1,
            base + size_t(z) * slicePitch(level) + size_t(y) * rowPitch(level) +
                size_t(x) * info->blockBytes);
  markDirty();
}

void Texture::generateMips() {
  const FormatInfo* info = formatInfo(format_);
  if (levels_ <= 1) return;
  if (info->compressed) fail("cannot generate mips for compressed format {}", info->name);
  for (int f = 0; f < faceCount(); ++f) {
    // Filter each level from the float values of the one above it, so quantisation
    // does not accumulate down the chain.
    int w = width(0), h = height(0), d = depth(0);
    std::vector<Color4> src(size_t(w) * h * d), dst;
    const uint8_t* p = data(f, 0);
    for (size_t row = 0; row < size_t(h) * d; ++row)
      decodeRow(format_, p + row * rowPitch(0), w, &src[row * w]);
    for (int l = 1; l < levels_; ++l) {
      int nw = width(l), nh = height(l), nd = depth(l);
      dst.assign(size_t(nw) * nh * nd, Color4{});
      // 2x2(x2) box; a dimension that is already 1 is not halved.
      for (int z = 0; z < nd; ++z)
        for (int y = 0; y < nh; ++y)
          for (int x = 0; x < nw; ++x) {
            int x0 = std::min(2 * x, w - 1), x1 = std::min(2 * x + 1, w - 1);
            int y0 = std::min(2 * y, h - 1), y1 = std::min(2 * y + 1, h - 1);
            int z0 = std::min(2 * z, d - 1), z1 = std::min(2 * z + 1, d - 1);
            if (w == 1) x1 = x0;
            if (h == 1) y1 = y0;
            if (d == 1) z1 = z0;
            Color4 s{};
            int n = 0;
            for (int zz : {z0, z1}) {
              for (int yy : {y0, y1}) {
                for (int xx : {x0, x1}) {
                  const Color4& c = src[(size_t(zz) * h + yy) * w + xx];
                  s.r += c.r, s.g += c.g, s.b += c.b, s.a += c.a;
                  ++n;
                }
              }
            }
            float inv = 1.0f / float(n);
            dst[(size_t(z) * nh + y) * nw + x] = {s.r * inv, s.g * inv, s.b * inv, s.a * inv};
          }
      uint8_t* q = data(f, l);
      for (size_t row = 0; row < size_t(nh) * nd; ++row)
        encodeRow(format_, &dst[row * nw], nw, q + row * rowPitch(l));
      src.swap(dst);
      w = nw, h = nh, d = nd;
    }
  }
  markDirty();
}

void Texture::markDirty() {
  std::lock_guard lock(decodeMutex_);
  for (size_t i = 0; i < decoded_.size(); ++i) {
    decoded_[i].store(nullptr, std::memory_order_release);
    decodedOwned_[i].reset();
  }
}

const SampleLevel& Texture::sampleLevel(int face, int level) const {
  if (face < 0 || face >= faceCount() || level < 0 || level >= levels_)
    fail("texture: face {} level {} does not exist", face, level);
  size_t i = index(face, level);
  if (const SampleLevel* s = decoded_[i].load(std::memory_order_acquire)) return *s;

  std::lock_guard lock(decodeMutex_);
  if (const SampleLevel* s = decoded_[i].load(std::memory_order_relaxed)) return *s;
  auto s = std::make_unique<SampleLevel>();
  const FormatInfo* info = formatInfo(format_);
  int w = width(level), h = height(level), d = depth(level);
  s->width = w, s->height = h, s->depth = d;
  s->unorm8 = info->fitsUnorm8;
  size_t n = size_t(w) * h * d;
  const uint8_t* p = storage_[i].data();
  std::vector<Color4> tmp;
  Color4* dst;
  if (s->unorm8) {
    s->rgba8.resize(n);
    tmp.resize(info->compressed ? 0 : size_t(w));
    dst = tmp.data();
  } else {
    s->rgbaf.resize(n);
    dst = s->rgbaf.data();
  }
  auto pack = [](const Color4& c) {
    return uint32_t(unorm8Safe(c.r)) | (uint32_t(unorm8Safe(c.g)) << 8) | (uint32_t(unorm8Safe(c.b)) << 16) |
           (uint32_t(unorm8Safe(c.a)) << 24);
  };
  if (info->compressed) {
    size_t pitch = rowPitch(level);
    Color4 block[16];
    for (int by = 0; by < (h + 3) / 4; ++by)
      for (int bx = 0; bx < (w + 3) / 4; ++bx) {
        decodeBlock(format_, p + by * pitch + size_t(bx) * info->blockBytes, block);
        for (int k = 0; k < 16; ++k) {
          int x = bx * 4 + k % 4, y = by * 4 + k / 4;
          if (x < w && y < h) s->rgba8[size_t(y) * w + x] = pack(block[k]);
        }
      }
  } else if (s->unorm8 && (format_ == Format::A8R8G8B8 || format_ == Format::X8R8G8B8)) {
    // Byte shuffle: memory B, G, R, A -> r | g<<8 | b<<16 | a<<24.
    uint32_t amask = format_ == Format::X8R8G8B8 ? 0xff000000u : 0;
    for (size_t k = 0; k < n; ++k, p += 4)
      s->rgba8[k] = (uint32_t(p[2]) | (uint32_t(p[1]) << 8) | (uint32_t(p[0]) << 16) |
                     (uint32_t(p[3]) << 24)) | amask;
  } else {
    size_t pitch = rowPitch(level);
    for (size_t row = 0; row < size_t(h) * d; ++row) {
      if (s->unorm8) {
        decodeRow(format_, p + row * pitch, w, dst);
        for (int x = 0; x < w; ++x) s->rgba8[row * w + x] = pack(dst[x]);
      } else {
        decodeRow(format_, p + row * pitch, w, dst + row * w);
      }
    }
  }
  const SampleLevel* published = s.get();
  decodedOwned_[i] = std::move(s);
  decoded_[i].store(published, std::memory_order_release);
  return *published;
}

}  // namespace refx
