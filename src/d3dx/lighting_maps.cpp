// Specular power tables, attenuation maps and the wood noise volume.
#include "refx/d3dx/lighting_maps.h"

#include <algorithm>
#include <cmath>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/texture_fill.h"

namespace refx::d3dx {

namespace {

void requireSize(const char* fn, const char* what, int v, int min, int max) {
  if (v < min || v > max) fail("{}: {} must be between {} and {}, not {}", fn, what, min, max, v);
}

void requirePower(const char* fn, float power) {
  if (!std::isfinite(power) || power < 0) fail("{}: power must be a finite value >= 0, not {}", fn, power);
}

// The callbacks compute in double and store a float, as the samples' `(float) pow(...)`.
float powf64(float x, float power) { return float(std::pow(double(x), double(power))); }

// ---------------------------------------------------------------- gradient noise

// 32-bit integer hash (a variant of the "lowbias32" mixer): lattice point -> bits.
uint32_t hash(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

uint32_t latticeHash(int x, int y, int z, uint32_t salt) {
  return hash(uint32_t(x) * 0x8da6b343U ^ hash(uint32_t(y) * 0xd8163841U ^ hash(uint32_t(z) * 0xcb1ab31fU ^ salt)));
}

// Improved Perlin noise's twelve gradients (the cube's edge midpoints).
constexpr float kGradients[12][3] = {{1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0},
                                     {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
                                     {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}};

float fade(float t) { return t * t * t * (t * (t * 6 - 15) + 10); }

// One octave of periodic gradient noise: the lattice repeats every `period` cells,
// its gradient indices hashed once per lattice point.
class PeriodicNoise {
 public:
  PeriodicNoise(int period, uint32_t salt) : period_(period), grad_(size_t(period) * period * period) {
    for (int z = 0; z < period; ++z)
      for (int y = 0; y < period; ++y)
        for (int x = 0; x < period; ++x)
          grad_[(size_t(z) * period + y) * period + x] = uint8_t(latticeHash(x, y, z, salt) % 12);
  }

  // About [-1, 1] at p (in lattice cells).
  float operator()(Vec3 p) const {
    int ix = int(std::floor(p.x)), iy = int(std::floor(p.y)), iz = int(std::floor(p.z));
    float fx = p.x - float(ix), fy = p.y - float(iy), fz = p.z - float(iz);
    float corner[8];
    for (int c = 0; c < 8; ++c) {
      int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
      const float* g = kGradients[grad_[(size_t(wrap(iz + dz)) * period_ + wrap(iy + dy)) * period_ + wrap(ix + dx)]];
      corner[c] = g[0] * (fx - float(dx)) + g[1] * (fy - float(dy)) + g[2] * (fz - float(dz));
    }
    float u = fade(fx), v = fade(fy), w = fade(fz);
    auto lerp = [](float a, float b, float t) { return a + (b - a) * t; };
    float x00 = lerp(corner[0], corner[1], u), x10 = lerp(corner[2], corner[3], u);
    float x01 = lerp(corner[4], corner[5], u), x11 = lerp(corner[6], corner[7], u);
    return lerp(lerp(x00, x10, v), lerp(x01, x11, v), w);
  }

 private:
  int wrap(int i) const { return ((i % period_) + period_) % period_; }
  int period_;
  std::vector<uint8_t> grad_;
};

// Four octaves from 4 lattice cells across the volume; t in [0,1)³ is one period.
class WoodFbm {
 public:
  explicit WoodFbm(uint32_t salt) {
    for (int octave = 0, cells = 4; octave < 4; ++octave, cells *= 2)
      octaves_.emplace_back(cells, salt + uint32_t(octave) * 0x9e3779b9U);
  }
  float operator()(Vec3 t) const {
    float sum = 0, amplitude = 1, cells = 4;
    for (const PeriodicNoise& n : octaves_) {
      sum += amplitude * n(t * cells);
      amplitude *= 0.5f;
      cells *= 2;
    }
    return sum / 1.875f;  // the amplitudes' sum: about [-1, 1] again
  }

 private:
  std::vector<PeriodicNoise> octaves_;
};

}  // namespace

TexturePtr specularPowerMap(int width, int height, float power, SpecularAlpha alpha, int levels) {
  requireSize("specularPowerMap", "width", width, 1, 8192);
  requireSize("specularPowerMap", "height", height, 1, 8192);
  requirePower("specularPowerMap", power);
  TexturePtr t = Texture::create2D(Format::A8R8G8B8, width, height, levels);
  fillTexture(*t, [&](Vec2 uv, Vec2) {
    float p = powf64(uv.y, power);
    return Vec4(p, p, p, alpha == SpecularAlpha::U ? uv.x : 1.0f);
  });
  return t;
}

TexturePtr specularPowerTable(int width, float power, int levels) {
  requireSize("specularPowerTable", "width", width, 1, 8192);
  requirePower("specularPowerTable", power);
  TexturePtr t = Texture::create2D(Format::A8R8G8B8, width, 1, levels);
  fillTexture(*t, [&](Vec2 uv, Vec2) { return Vec4(0, 0, 0, powf64(uv.x, power)); });
  return t;
}

TexturePtr attenuationMap2D(int size, int levels) {
  requireSize("attenuationMap2D", "size", size, 1, 8192);
  TexturePtr t = Texture::create2D(Format::A8R8G8B8, size, size, levels);
  fillTexture(*t, [](Vec2 uv, Vec2) {
    float x = 2 * uv.x - 1, y = 2 * uv.y - 1;
    float r2 = std::min(1.0f, x * x + y * y);
    return Vec4(r2, r2, r2, x * x);
  });
  return t;
}

TexturePtr attenuationMap1D(int width, int levels) {
  requireSize("attenuationMap1D", "width", width, 1, 8192);
  TexturePtr t = Texture::create2D(Format::A8R8G8B8, width, 1, levels);
  fillTexture(*t, [](Vec2 uv, Vec2) {
    float z = 2 * uv.x - 1;
    return Vec4(z * z, z * z, z * z, z * z);
  });
  return t;
}

TexturePtr woodNoiseVolume(int size, int levels, uint32_t seed) {
  requireSize("woodNoiseVolume", "size", size, 4, 256);
  TexturePtr t = Texture::createVolume(Format::A8R8G8B8, size, size, size, levels);
  const uint32_t salt = hash(seed);
  const WoodFbm fields[4] = {WoodFbm(salt), WoodFbm(salt + 0x632be5abU), WoodFbm(salt + 2 * 0x632be5abU),
                             WoodFbm(salt + 3 * 0x632be5abU)};
  // Level 0 from the noise; smaller levels box-filtered, as noise point-sampled at
  // fewer texels would alias.
  const int count = t->levelCount();
  std::vector<Color4> row(static_cast<size_t>(size));
  uint8_t* base = t->data(0, 0);
  for (int z = 0; z < size; ++z)
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        Vec3 p{(float(x) + 0.5f) / float(size), (float(y) + 0.5f) / float(size), (float(z) + 0.5f) / float(size)};
        float c[4];
        for (int ch = 0; ch < 4; ++ch)
          c[ch] = std::clamp(0.5f + 0.5f * fields[ch](p), 0.0f, 1.0f);
        row[size_t(x)] = {c[0], c[1], c[2], c[3]};
      }
      encodeRow(Format::A8R8G8B8, row.data(), size,
                base + size_t(z) * t->slicePitch(0) + size_t(y) * t->rowPitch(0));
    }
  if (count > 1) t->generateMips();
  t->markDirty();
  return t;
}

}  // namespace refx::d3dx
