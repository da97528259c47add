// Textures: 2D, cube and volume, with mip chains, stored in their D3D format.
#pragma once
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "refx/core/color.h"
#include "refx/core/large_buffer.h"
#include "refx/resource/format.h"

namespace refx {

enum class TextureType { Texture2D, Cube, Volume };

// A decoded mip level ready for sampling: 8-bit RGBA (r in the low byte) when the
// format fits 8-bit unorm exactly, float RGBA otherwise.
struct SampleLevel {
  int width = 0, height = 0, depth = 1;
  bool unorm8 = false;
  LargeBuffer<uint32_t> rgba8;  // width*height*depth, when unorm8
  std::vector<Color4> rgbaf;    // width*height*depth, otherwise
};

class Texture {
 public:
  // levels == 0: full chain down to 1x1(x1).
  Texture(TextureType type, Format format, int width, int height, int depth, int levels);
  static std::shared_ptr<Texture> create2D(Format f, int w, int h, int levels = 1);
  static std::shared_ptr<Texture> createCube(Format f, int size, int levels = 1);
  static std::shared_ptr<Texture> createVolume(Format f, int w, int h, int d, int levels = 1);

  TextureType type() const { return type_; }
  Format format() const { return format_; }
  int width(int level = 0) const;
  int height(int level = 0) const;
  int depth(int level = 0) const;
  int levelCount() const { return levels_; }
  int faceCount() const { return type_ == TextureType::Cube ? 6 : 1; }

  // Raw storage of one face/level (rows of texels or 4x4 blocks, tightly packed,
  // volume slices one after another).
  uint8_t* data(int face, int level);
  const uint8_t* data(int face, int level) const;
  size_t dataSize(int face, int level) const;
  size_t rowPitch(int level) const;
  size_t slicePitch(int level) const;

  Color4 texel(int face, int level, int x, int y, int z = 0) const;
  void setTexel(int face, int level, int x, int y, int z, Color4 c);  // not for DXT
  // Box-filters level 0 of every face into the smaller levels.
  void generateMips();

  // Call after writing data() directly so sampling sees the change. Drops the decoded
  // levels: no sampling may run on this texture at the same time.
  void markDirty();
  // Decoded level for the sampler (built on first use, thread-safe; after the first
  // use a lookup is one atomic load).
  const SampleLevel& sampleLevel(int face, int level) const;

 private:
  size_t index(int face, int level) const { return size_t(face) * levels_ + level; }
  TextureType type_;
  Format format_;
  int width_, height_, depth_, levels_;
  std::vector<LargeBuffer<uint8_t>> storage_;  // [face*levels + level]
  mutable std::vector<std::atomic<const SampleLevel*>> decoded_;  // published levels
  mutable std::vector<std::unique_ptr<SampleLevel>> decodedOwned_;  // guarded by decodeMutex_
  mutable std::mutex decodeMutex_;
};

using TexturePtr = std::shared_ptr<Texture>;

}  // namespace refx
