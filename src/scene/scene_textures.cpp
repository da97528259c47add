// Texture generators of scene scripts (`texture NAME ... GEN`): level 0 of every face is
// computed texel by texel as float colors, encoded in the texture's format (rounded as
// scene-script.md states: floor(v·(2ⁿ−1) + 0.5), signed round(v·127) ties away from
// zero), and the smaller levels are box-filtered from it (mipcolors fills each level itself).
#include <cmath>
#include <functional>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/texture_fill.h"
#include "refx/scene/scene_script.h"

namespace refx::scene {

namespace {

const char* typeName(TextureType t) {
  return t == TextureType::Cube ? "cube" : t == TextureType::Volume ? "volume" : "2d";
}

// splitmix64: small, fast and the same on every platform.
uint64_t nextRandom(uint64_t& state) {
  uint64_t z = (state += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

using TexelFn = std::function<Color4(int face, int x, int y, int z)>;

void fillLevel(Texture& tex, int face, int level, const TexelFn& fn) {
  int w = tex.width(level), h = tex.height(level), d = tex.depth(level);
  std::vector<Color4> row(static_cast<size_t>(w));
  uint8_t* base = tex.data(face, level);
  for (int z = 0; z < d; ++z)
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) row[size_t(x)] = fn(face, x, y, z);
      encodeRowExact(tex.format(), row.data(), w,
                base + size_t(z) * tex.slicePitch(level) + size_t(y) * tex.rowPitch(level));
    }
}

Color4 lerp(Color4 a, Color4 b, float t) {
  // a*(1-t) + b*t gives a and b exactly at t = 0 and t = 1.
  float u = 1.0f - t;
  return {a.r * u + b.r * t, a.g * u + b.g * t, a.b * u + b.b * t, a.a * u + b.a * t};
}

}  // namespace

TexturePtr createSceneTexture(const TextureDef& def, const Texture* image) {
  auto tex = std::make_shared<Texture>(def.type, def.format, def.width, def.height, def.depth,
                                       def.levels);
  const FormatInfo* info = formatInfo(def.format);
  if (!info || info->compressed) fail("texture: format {} cannot be generated", formatName(def.format));
  const bool isSigned = info->isSigned;
  const int W = def.width, H = def.height, D = def.depth;
  // Unit vectors are stored biased (0.5 + 0.5n) in unsigned formats, raw in signed ones.
  auto vectorColor = [isSigned](Vec3 n) {
    if (isSigned) return Color4{n.x, n.y, n.z, 1};
    return Color4{0.5f + 0.5f * n.x, 0.5f + 0.5f * n.y, 0.5f + 0.5f * n.z, 1};
  };
  auto needColors = [&](size_t n) {
    if (def.colors.size() < n) fail("texture: the generator needs {} colors, got {}", n, def.colors.size());
  };

  TexelFn fn;
  uint64_t noiseState = def.seed;
  switch (def.generator) {
    case Generator::Solid:
      needColors(1);
      fn = [&](int, int, int, int) { return def.colors[0]; };
      break;
    case Generator::Checker: {
      needColors(2);
      int cell = std::max(1, def.cell);
      fn = [&, cell](int, int x, int y, int z) {
        return ((x / cell + y / cell + z / cell) & 1) ? def.colors[1] : def.colors[0];
      };
      break;
    }
    case Generator::Gradient:
      needColors(4);
      fn = [&](int, int x, int y, int) {
        float u = W > 1 ? float(x) / float(W - 1) : 0.0f;
        float v = H > 1 ? float(y) / float(H - 1) : 0.0f;
        return lerp(lerp(def.colors[0], def.colors[1], u), lerp(def.colors[2], def.colors[3], u), v);
      };
      break;
    case Generator::Coords:
      fn = [&](int, int x, int y, int z) {
        float b = def.type == TextureType::Volume ? (float(z) + 0.5f) / float(D) : 0.0f;
        return Color4{(float(x) + 0.5f) / float(W), (float(y) + 0.5f) / float(H), b, 1};
      };
      break;
    case Generator::Pixels:
      needColors(size_t(W) * H * D * size_t(tex->faceCount()));
      fn = [&](int face, int x, int y, int z) {
        return def.colors[((size_t(face) * D + z) * H + y) * W + x];
      };
      break;
    case Generator::Noise:
      fn = [&](int, int, int, int) {
        uint64_t r = nextRandom(noiseState);
        float c[4];
        for (int k = 0; k < 4; ++k) {
          uint8_t byte = uint8_t(r >> (8 * k));
          // Signed formats: the byte as a two's complement snorm8 value, -128 -> -1.
          c[k] = isSigned ? std::max(float(int8_t(byte)) / 127.0f, -1.0f) : float(byte) / 255.0f;
        }
        return Color4{c[0], c[1], c[2], c[3]};
      };
      break;
    case Generator::Dome:
      fn = [&](int, int x, int y, int) {
        // Texel centre in [-1, 1], x right, y down; the hemisphere fills the inscribed circle.
        float nx = 2.0f * (float(x) + 0.5f) / float(W) - 1.0f;
        float ny = 2.0f * (float(y) + 0.5f) / float(H) - 1.0f;
        float r2 = nx * nx + ny * ny;
        Vec3 n = r2 < 1.0f ? Vec3{nx, ny, std::sqrt(1.0f - r2)} : Vec3{0, 0, 1};
        return vectorColor(n);
      };
      break;
    case Generator::Normalize:
      if (def.type != TextureType::Cube) fail("texture: normalize needs a cube texture");
      fn = [&](int face, int x, int y, int) {
        return vectorColor(normalize(d3dx::cubeTexelDirection(face, float(x), float(y), W)));
      };
      break;
    case Generator::Faces:
      if (def.type != TextureType::Cube) fail("texture: faces needs a cube texture");
      needColors(6);
      fn = [&](int face, int, int, int) { return def.colors[size_t(face)]; };
      break;
    case Generator::MipColors:
      needColors(size_t(tex->levelCount()));
      for (int f = 0; f < tex->faceCount(); ++f)
        for (int l = 0; l < tex->levelCount(); ++l)
          fillLevel(*tex, f, l, [&](int, int, int, int) { return def.colors[size_t(l)]; });
      tex->markDirty();
      return tex;
    case Generator::File: {
      if (!image) fail("texture: file {}: no image was loaded", def.path);
      if (image->type() != def.type)
        fail("texture: file {} holds a {} texture, expected {}", def.path, typeName(image->type()),
             typeName(def.type));
      if (image->width() != W || image->height() != H || image->depth() != D) {
        if (def.type == TextureType::Volume)
          fail("texture: file {} is {}x{}x{}, the texture is {}x{}x{}", def.path, image->width(),
               image->height(), image->depth(), W, H, D);
        fail("texture: file {} is {}x{}, the texture is {}x{}", def.path, image->width(),
             image->height(), W, H);
      }
      fn = [image](int face, int x, int y, int z) { return image->texel(face, 0, x, y, z); };
      break;
    }
  }
  for (int f = 0; f < tex->faceCount(); ++f) fillLevel(*tex, f, 0, fn);
  if (tex->levelCount() > 1) tex->generateMips();
  tex->markDirty();
  return tex;
}

}  // namespace refx::scene
