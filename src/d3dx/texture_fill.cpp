// Texture fills, the normalization cube map and the normal map generator.
#include "refx/d3dx/texture_fill.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "refx/core/diagnostics.h"

namespace refx::d3dx {

namespace {

const FormatInfo& fillableFormat(const Texture& t, const char* fn) {
  const FormatInfo* info = formatInfo(t.format());
  if (!info) fail("{}: unknown texture format {}", fn, uint32_t(t.format()));
  if (info->compressed) fail("{}: cannot fill texels of compressed format {}", fn, info->name);
  return *info;
}

void requireType(const Texture& t, TextureType type, const char* fn, const char* what) {
  if (t.type() != type) fail("{}: needs a {} texture", fn, what);
}

Color4 toColor(Vec4 v) { return {v.x, v.y, v.z, v.w}; }

// Per-face texel direction: (s, t) in [-1, 1] across the face -> (x, y, z).
// Table of fixed-function.md §10: each axis is +-1 (major), +-s or +-t.
struct FaceAxes {
  float major[3];  // the constant component
  float sCoef[3];  // multiplies s
  float tCoef[3];  // multiplies t
};
constexpr FaceAxes kFaces[6] = {
    {{1, 0, 0}, {0, 0, -1}, {0, -1, 0}},   // +X (1, -t, -s)
    {{-1, 0, 0}, {0, 0, 1}, {0, -1, 0}},   // -X (-1, -t, s)
    {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}},     // +Y (s, 1, t)
    {{0, -1, 0}, {1, 0, 0}, {0, 0, -1}},   // -Y (s, -1, -t)
    {{0, 0, 1}, {1, 0, 0}, {0, -1, 0}},    // +Z (s, -t, 1)
    {{0, 0, -1}, {-1, 0, 0}, {0, -1, 0}},  // -Z (-s, -t, -1)
};

}  // namespace

Vec3 cubeTexelDirection(int face, float x, float y, int size) {
  if (face < 0 || face > 5) fail("cube texture: face {} does not exist (0 to 5)", face);
  const FaceAxes& f = kFaces[face];
  float s = 2.0f * (x + 0.5f) / float(size) - 1.0f;
  float t = 2.0f * (y + 0.5f) / float(size) - 1.0f;
  return {f.major[0] + s * f.sCoef[0] + t * f.tCoef[0], f.major[1] + s * f.sCoef[1] + t * f.tCoef[1],
          f.major[2] + s * f.sCoef[2] + t * f.tCoef[2]};
}

void fillTexture(Texture& texture, const Fill2D& fill) {
  requireType(texture, TextureType::Texture2D, "fillTexture", "2D");
  fillableFormat(texture, "fillTexture");
  std::vector<Color4> row;
  for (int level = 0; level < texture.levelCount(); ++level) {
    int w = texture.width(level), h = texture.height(level);
    Vec2 size{1.0f / float(w), 1.0f / float(h)};
    row.resize(size_t(w));
    uint8_t* base = texture.data(0, level);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x)
        row[size_t(x)] = toColor(fill({(float(x) + 0.5f) / float(w), (float(y) + 0.5f) / float(h)}, size));
      encodeRow(texture.format(), row.data(), w, base + size_t(y) * texture.rowPitch(level));
    }
  }
  texture.markDirty();
}

void fillCubeTexture(Texture& texture, const Fill3D& fill) {
  requireType(texture, TextureType::Cube, "fillCubeTexture", "cube");
  fillableFormat(texture, "fillCubeTexture");
  std::vector<Color4> row;
  for (int face = 0; face < 6; ++face) {
    const FaceAxes& f = kFaces[face];
    for (int level = 0; level < texture.levelCount(); ++level) {
      int n = texture.width(level);
      float step = 2.0f / float(n);
      // 0 on the major axis, 2/S on the two axes the face spans.
      Vec3 size{f.major[0] != 0 ? 0.0f : step, f.major[1] != 0 ? 0.0f : step,
                f.major[2] != 0 ? 0.0f : step};
      row.resize(size_t(n));
      uint8_t* base = texture.data(face, level);
      for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x)
          row[size_t(x)] = toColor(fill(cubeTexelDirection(face, float(x), float(y), n), size));
        encodeRow(texture.format(), row.data(), n, base + size_t(y) * texture.rowPitch(level));
      }
    }
  }
  texture.markDirty();
}

void fillVolumeTexture(Texture& texture, const Fill3D& fill) {
  requireType(texture, TextureType::Volume, "fillVolumeTexture", "volume");
  fillableFormat(texture, "fillVolumeTexture");
  std::vector<Color4> row;
  for (int level = 0; level < texture.levelCount(); ++level) {
    int w = texture.width(level), h = texture.height(level), d = texture.depth(level);
    Vec3 size{1.0f / float(w), 1.0f / float(h), 1.0f / float(d)};
    row.resize(size_t(w));
    uint8_t* base = texture.data(0, level);
    for (int z = 0; z < d; ++z)
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x)
          row[size_t(x)] = toColor(fill({(float(x) + 0.5f) / float(w), (float(y) + 0.5f) / float(h),
                                         (float(z) + 0.5f) / float(d)},
                                        size));
        encodeRow(texture.format(), row.data(), w,
                  base + size_t(z) * texture.slicePitch(level) + size_t(y) * texture.rowPitch(level));
      }
  }
  texture.markDirty();
}

TexturePtr createNormalizationCubeMap(int size, Format format, int levels) {
  TexturePtr cube = Texture::createCube(format, size, levels);
  bool isSigned = fillableFormat(*cube, "createNormalizationCubeMap").isSigned;
  fillCubeTexture(*cube, [isSigned](Vec3 dir, Vec3) {
    Vec3 n = normalize(dir);
    return isSigned ? Vec4(n, 1.0f) : Vec4(n * 0.5f + Vec3{0.5f, 0.5f, 0.5f}, 1.0f);
  });
  return cube;
}

namespace {

// Height field with wrap or mirror addressing for out-of-range texels.
struct HeightField {
  int w = 0, h = 0;
  bool mirrorU = false, mirrorV = false;
  std::vector<float> v;

  static int address(int i, int n, bool mirror) {
    if (mirror) {
      // Mirror addressing: texel -1 -> 0, n -> n-1 (period 2n).
      int p = ((i % (2 * n)) + 2 * n) % (2 * n);
      return p < n ? p : 2 * n - 1 - p;
    }
    return ((i % n) + n) % n;
  }
  float at(int x, int y) const {
    return v[size_t(address(y, h, mirrorV)) * w + size_t(address(x, w, mirrorU))];
  }
};

// D3DX luminance weights for CHANNEL_LUMINANCE (Rec. 709).
constexpr float kLumR = 0.2125f, kLumG = 0.7154f, kLumB = 0.0721f;

float channelValue(Color4 c, uint32_t channel) {
  switch (channel) {
    case CHANNEL_RED: return c.r;
    case CHANNEL_GREEN: return c.g;
    case CHANNEL_BLUE: return c.b;
    case CHANNEL_ALPHA: return c.a;
    default: return kLumR * c.r + kLumG * c.g + kLumB * c.b;
  }
}

// Horizon-based sky visibility: along 8 directions, the steepest rise of the terrain
// (heights in texel units, h * amplitude) within kOcclusionRadius texels gives the
// horizon elevation angle e; that direction keeps 1 - sin(e) of its sky.
constexpr int kOcclusionRadius = 16;

float occlusion(const HeightField& f, int x, int y, float amplitude) {
  static const int kDirs[8][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
  float h0 = f.at(x, y) * amplitude, open = 0;
  int radius = std::min(kOcclusionRadius, std::max(f.w, f.h));
  for (const auto& d : kDirs) {
    float step = std::sqrt(float(d[0] * d[0] + d[1] * d[1])), maxTan = 0;
    for (int k = 1; k <= radius; ++k) {
      float rise = f.at(x + k * d[0], y + k * d[1]) * amplitude - h0;
      maxTan = std::max(maxTan, rise / (float(k) * step));
    }
    open += 1.0f - maxTan / std::sqrt(1.0f + maxTan * maxTan);
  }
  return open / 8.0f;
}

}  // namespace

TexturePtr computeNormalMap(const Texture& height, uint32_t channel, float amplitude,
                            uint32_t flags, Format format) {
  requireType(height, TextureType::Texture2D, "computeNormalMap", "2D height");
  static constexpr uint32_t kChannels[] = {CHANNEL_RED, CHANNEL_BLUE, CHANNEL_GREEN, CHANNEL_ALPHA,
                                           CHANNEL_LUMINANCE};
  if (std::find(std::begin(kChannels), std::end(kChannels), channel) == std::end(kChannels))
    fail("computeNormalMap: channel 0x{:x} is not one D3DX_CHANNEL value (RED 0x1, BLUE 0x2, "
         "GREEN 0x4, ALPHA 0x8, LUMINANCE 0x10)",
         channel);
  constexpr uint32_t kKnownFlags = NORMALMAP_MIRROR | NORMALMAP_INVERTSIGN | NORMALMAP_COMPUTE_OCCLUSION;
  if (flags & ~kKnownFlags)
    fail("computeNormalMap: unknown D3DX_NORMALMAP flags 0x{:x}", flags & ~kKnownFlags);
  if (!std::isfinite(amplitude)) fail("computeNormalMap: amplitude must be finite");

  TexturePtr out = Texture::create2D(format, height.width(0), height.height(0), 1);
  const FormatInfo& info = fillableFormat(*out, "computeNormalMap");

  HeightField f;
  f.w = height.width(0), f.h = height.height(0);
  f.mirrorU = flags & NORMALMAP_MIRROR_U;
  f.mirrorV = flags & NORMALMAP_MIRROR_V;
  f.v.resize(size_t(f.w) * f.h);
  const SampleLevel& src = height.sampleLevel(0, 0);
  for (size_t i = 0; i < f.v.size(); ++i) {
    Color4 c;
    if (src.unorm8) {
      uint32_t p = src.rgba8[i];
      c = {float(p & 0xff) / 255.0f, float((p >> 8) & 0xff) / 255.0f,
           float((p >> 16) & 0xff) / 255.0f, float(p >> 24) / 255.0f};
    } else {
      c = src.rgbaf[i];
    }
    f.v[i] = channelValue(c, channel);
  }

  float sign = (flags & NORMALMAP_INVERTSIGN) ? 1.0f : -1.0f;
  bool occ = flags & NORMALMAP_COMPUTE_OCCLUSION;
  std::vector<Color4> row(size_t(f.w));
  uint8_t* base = out->data(0, 0);
  for (int y = 0; y < f.h; ++y) {
    for (int x = 0; x < f.w; ++x) {
      float dx = (f.at(x + 1, y) - f.at(x - 1, y)) * 0.5f * amplitude;
      float dy = (f.at(x, y + 1) - f.at(x, y - 1)) * 0.5f * amplitude;
      Vec3 n = normalize({sign * dx, sign * dy, 1.0f});
      float a = occ ? occlusion(f, x, y, amplitude) : 1.0f;
      row[size_t(x)] = info.isSigned ? Color4{n.x, n.y, n.z, a}
                                     : Color4{0.5f * n.x + 0.5f, 0.5f * n.y + 0.5f, 0.5f * n.z + 0.5f, a};
    }
    encodeRow(format, row.data(), f.w, base + size_t(y) * out->rowPitch(0));
  }
  out->markDirty();
  return out;
}

}  // namespace refx::d3dx
