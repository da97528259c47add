// Shared pieces of the image file readers and writers.
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/resource/texture.h"

namespace refx::resource::image {

// Largest width/height of a 2D image file (the texture limit).
constexpr int kMaxImageDimension = 16384;

// Bounds-checked little-endian reader over a file held in memory. Every failure
// throws refx::Error naming the file.
class Reader {
 public:
  Reader(std::span<const uint8_t> bytes, const std::string& name) : bytes_(bytes), name_(name) {}
  size_t pos() const { return pos_; }
  size_t size() const { return bytes_.size(); }
  size_t remaining() const { return bytes_.size() - pos_; }
  const std::string& name() const { return name_; }
  const uint8_t* here() const { return bytes_.data() + pos_; }

  // Throws "<name>: truncated: <what> needs N bytes, M remain".
  void need(size_t n, const std::string& what) const;
  void seek(size_t pos, const std::string& what);
  void skip(size_t n, const std::string& what);
  uint8_t u8(const char* what);
  uint16_t u16(const char* what);
  uint32_t u32(const char* what);
  const uint8_t* take(size_t n, const std::string& what);

 private:
  std::span<const uint8_t> bytes_;
  const std::string& name_;
  size_t pos_ = 0;
};

template <typename... Args>
[[noreturn]] void failFile(const std::string& name, fmt::format_string<Args...> f, Args&&... args) {
  throw Error(name + ": " + fmt::format(f, std::forward<Args>(args)...));
}

// Checks a 2D image size from a file header.
void checkImageSize(const std::string& name, int64_t width, int64_t height);

// A one-level 2D texture: A8R8G8B8, or L8 when `grey`.
TexturePtr makeImageTexture(int width, int height, bool grey);
// Stores 8-bit r, g, b, a at texel (x, y) of an A8R8G8B8 texture's level 0.
inline void putRGBA(uint8_t* base, int width, int x, int y, uint8_t r, uint8_t g, uint8_t b,
                    uint8_t a) {
  uint8_t* p = base + (size_t(y) * size_t(width) + size_t(x)) * 4;
  p[0] = b, p[1] = g, p[2] = r, p[3] = a;
}

// Decodes one face/level of any texture to 8-bit RGBA rows (r, g, b, a bytes).
std::vector<uint8_t> toRGBA8(const Texture& tex, int face, int level);
void writeFile(const std::string& path, std::span<const uint8_t> bytes);

TexturePtr loadPNG(std::span<const uint8_t> bytes, const std::string& name);
TexturePtr loadDDS(std::span<const uint8_t> bytes, const std::string& name);
TexturePtr loadTGA(std::span<const uint8_t> bytes, const std::string& name);
TexturePtr loadBMP(std::span<const uint8_t> bytes, const std::string& name);
TexturePtr loadPNM(std::span<const uint8_t> bytes, const std::string& name);
// True when the first bytes look like a TGA header (TGA has no magic number).
bool looksLikeTGA(std::span<const uint8_t> bytes);

std::vector<uint8_t> encodePNG(const Texture& tex, bool alpha, int face, int level,
                               const std::string& name);
std::vector<uint8_t> encodeDDS(const Texture& tex, const std::string& name);

}  // namespace refx::resource::image
