// Procedural sample textures: a fictional earth (colour, gloss, height, bump and
// normal maps, clouds), a sky environment map, a checkerboard and bricks.
#include "refx/d3dx/sample_assets.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/d3dx/texture_fill.h"

namespace refx::d3dx {

namespace {

constexpr float kPi = 3.14159265358979323846f;

// Fixed seeds: one per independent noise field.
constexpr uint32_t kSeedContinents = 0x5eed0001u, kSeedMountains = 0x5eed0002u,
                   kSeedDryness = 0x5eed0003u, kSeedIce = 0x5eed0004u, kSeedClouds = 0x5eed0005u,
                   kSeedBricks = 0x5eed0006u, kSeedWarp = 0x5eed0007u,
                   kSeedRanges = 0x5eed0008u;

uint32_t hash3(int x, int y, int z, uint32_t seed) {
  uint32_t h = seed ^ (uint32_t(x) * 0x8da6b343u) ^ (uint32_t(y) * 0xd8163841u) ^
               (uint32_t(z) * 0xcb1ab31fu);
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return h;
}

// Lattice value in [-1, 1].
float latticeValue(int x, int y, int z, uint32_t seed) {
  return float(hash3(x, y, z, seed) >> 8) * (2.0f / 16777215.0f) - 1.0f;
}

float lerp(float a, float b, float t) { return a + (b - a) * t; }
float smoothstep(float e0, float e1, float x) {
  float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// Trilinear value noise with a smooth fade, in [-1, 1].
float valueNoise(Vec3 p, uint32_t seed) {
  float fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
  int x = int(fx), y = int(fy), z = int(fz);
  float tx = p.x - fx, ty = p.y - fy, tz = p.z - fz;
  tx = tx * tx * (3 - 2 * tx), ty = ty * ty * (3 - 2 * ty), tz = tz * tz * (3 - 2 * tz);
  float c[2][2];
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy)
      c[dz][dy] = lerp(latticeValue(x, y + dy, z + dz, seed), latticeValue(x + 1, y + dy, z + dz, seed), tx);
  return lerp(lerp(c[0][0], c[0][1], ty), lerp(c[1][0], c[1][1], ty), tz);
}

// Fractal sum of `octaves` noise layers (frequency x2, amplitude x gain), normalised
// back to [-1, 1]. Each octave is shifted so lattice points do not line up.
float fbm(Vec3 p, int octaves, uint32_t seed, float gain = 0.5f) {
  float sum = 0, amp = 1, total = 0;
  for (int i = 0; i < octaves; ++i) {
    sum += amp * valueNoise(p, seed + uint32_t(i) * 0x9e3779b9u);
    total += amp;
    amp *= gain;
    p = p * 2.0f + Vec3{17.13f, -9.71f, 5.37f};
  }
  return sum / total;
}

// fbm with its typical (small) values doubled, still within [-1, 1].
float fbmContrast(Vec3 p, int octaves, uint32_t seed, float gain = 0.5f) {
  return std::clamp(2.0f * fbm(p, octaves, seed, gain), -1.0f, 1.0f);
}

// Perlin gradient noise (the 12 cube-edge gradients), about [-1, 1]. Its zero set
// curves freely, unlike value noise whose creases follow the lattice.
float gradientNoise(Vec3 p, uint32_t seed) {
  static const float kGrad[12][3] = {{1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0},
                                     {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
                                     {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}};
  float fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
  int x = int(fx), y = int(fy), z = int(fz);
  float rx = p.x - fx, ry = p.y - fy, rz = p.z - fz;
  auto corner = [&](int dx, int dy, int dz) {
    const float* g = kGrad[hash3(x + dx, y + dy, z + dz, seed) % 12];
    return g[0] * (rx - float(dx)) + g[1] * (ry - float(dy)) + g[2] * (rz - float(dz));
  };
  auto fade = [](float t) { return t * t * t * (t * (t * 6 - 15) + 10); };
  float u = fade(rx), v = fade(ry), w = fade(rz);
  float c00 = lerp(corner(0, 0, 0), corner(1, 0, 0), u), c10 = lerp(corner(0, 1, 0), corner(1, 1, 0), u);
  float c01 = lerp(corner(0, 0, 1), corner(1, 0, 1), u), c11 = lerp(corner(0, 1, 1), corner(1, 1, 1), u);
  return lerp(lerp(c00, c10, v), lerp(c01, c11, v), w);
}

// Ridges (1 at the crest, 0 in the valleys) for mountain ranges.
float ridged(Vec3 p, int octaves, uint32_t seed) {
  float sum = 0, amp = 1, total = 0;
  for (int i = 0; i < octaves; ++i) {
    float r = std::clamp(1.0f - std::fabs(gradientNoise(p, seed + uint32_t(i) * 0x9e3779b9u)), 0.0f, 1.0f);
    sum += amp * r * r;
    total += amp;
    amp *= 0.5f;
    p = p * 2.0f + Vec3{-3.17f, 11.3f, 7.9f};
  }
  return sum / total;
}

struct EarthSample {
  float elevation;  // > 0 land
  float height;     // L8 height: 0 water, land (0, 1]
  bool ice;
};

// Low plains rising inland, with ranges of ridged mountains in some regions.
float landHeight(Vec3 p, float e) {
  float ranges = smoothstep(-0.1f, 0.4f, fbm(p * 2.0f, 2, kSeedRanges));
  float mountains = 0;
  if (ranges > 0) {
    float r = ridged(p * 4.5f, 3, kSeedMountains);
    mountains = r * r * ranges * smoothstep(0.03f, 0.3f, e);
  }
  return std::clamp(0.04f + 0.3f * std::min(e, 1.0f) + 0.6f * mountains, 0.0f, 1.0f);
}

bool polarIce(Vec3 p) {
  float ay = std::fabs(p.y);
  if (ay < 0.90f) return false;  // more than 25.8 deg (acos 0.9) from a pole: never ice
  return ay > 0.945f + 0.025f * fbm(p * 9.0f, 2, kSeedIce);
}

EarthSample earthAt(Vec3 p) {
  EarthSample s;
  s.elevation = earthElevation(p);
  s.height = s.elevation > 0 ? landHeight(p, s.elevation) : 0.0f;
  s.ice = polarIce(p);
  return s;
}

void requireSize(const char* fn, int w, int h) {
  if (w < 1 || h < 1 || w > 16384 || h > 16384)
    fail("{}: size {}x{} is out of range (1 to 16384)", fn, w, h);
}

// Writes level 0 from per-texel colours (row by row) and box-filters the rest.
template <class F>
TexturePtr makeMap(const char* fn, Format format, int w, int h, int levels, F texelColor) {
  requireSize(fn, w, h);
  TexturePtr t = Texture::create2D(format, w, h, levels);
  std::vector<Color4> row(static_cast<size_t>(w));
  uint8_t* base = t->data(0, 0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) row[size_t(x)] = texelColor(x, y);
    encodeRow(format, row.data(), w, base + size_t(y) * t->rowPitch(0));
  }
  t->generateMips();
  t->markDirty();
  return t;
}

// Unit-sphere points of every texel centre of a w x h equirectangular map.
struct SphereGrid {
  std::vector<float> sinTheta, cosTheta, sinPhi, cosPhi;
  SphereGrid(int w, int h) : sinTheta(size_t(h)), cosTheta(size_t(h)), sinPhi(size_t(w)), cosPhi(size_t(w)) {
    for (int y = 0; y < h; ++y) {
      float theta = kPi * (float(y) + 0.5f) / float(h);
      sinTheta[size_t(y)] = std::sin(theta), cosTheta[size_t(y)] = std::cos(theta);
    }
    for (int x = 0; x < w; ++x) {
      float phi = 2.0f * kPi * (float(x) + 0.5f) / float(w);
      sinPhi[size_t(x)] = std::sin(phi), cosPhi[size_t(x)] = std::cos(phi);
    }
  }
  Vec3 at(int x, int y) const {
    float st = sinTheta[size_t(y)];
    return {-st * sinPhi[size_t(x)], cosTheta[size_t(y)], st * cosPhi[size_t(x)]};
  }
};

// 8-bit L8 heights of the earth, row-major.
std::vector<uint8_t> earthHeights(int w, int h) {
  SphereGrid grid(w, h);
  std::vector<uint8_t> out(size_t(w) * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      Vec3 p = grid.at(x, y);
      float e = earthElevation(p);
      out[size_t(y) * w + x] = e > 0 ? unorm8(landHeight(p, e)) : 0;
    }
  return out;
}

// BumpEarth's differences in 8-bit height steps: left - right, above - below.
TexturePtr earthBump(const char* fn, Format format, int w, int h, int levels) {
  requireSize(fn, w, h);
  std::vector<uint8_t> hm = earthHeights(w, h);
  auto H = [&](int x, int y) {
    x = (x % w + w) % w;             // wraps around the globe
    y = std::clamp(y, 0, h - 1);     // stops at the poles
    return int(hm[size_t(y) * w + x]);
  };
  return makeMap(fn, format, w, h, levels, [&](int x, int y) {
    float du = float(H(x - 1, y) - H(x + 1, y)) / 127.0f;
    float dv = float(H(x, y - 1) - H(x, y + 1)) / 127.0f;
    float lum = H(x, y) > 0 ? 63.0f / 255.0f : 127.0f / 255.0f;
    return Color4{du, dv, lum, 1.0f};
  });
}

}  // namespace

Vec3 earthDirection(float u, float v) {
  float theta = kPi * v, phi = 2.0f * kPi * u;
  float st = std::sin(theta);
  return {-st * std::sin(phi), std::cos(theta), st * std::cos(phi)};
}

float earthElevation(Vec3 p) {
  // Centres of the continents, computed once.
  static const std::vector<Vec3> centres = [] {
    std::vector<Vec3> c;
    for (const EarthContinent& k : kEarthContinents) c.push_back(earthDirection(k.u, k.v));
    return c;
  }();
  float e = -0.45f + 0.4f * fbmContrast(p * 2.2f, 5, kSeedContinents, 0.55f);
  // Only points within radius + kEarthWarp of a centre can reach a continent.
  bool nearLand = false;
  for (size_t i = 0; i < centres.size(); ++i) {
    float reach = kEarthContinents[i].radius + kEarthWarp;
    Vec3 d = p - centres[i];
    nearLand = nearLand || dot(d, d) < reach * reach;
  }
  if (!nearLand) return e;
  // Warp: each component in [-1, 1] * kEarthWarp / sqrt(3), so its length <= kEarthWarp.
  constexpr float kComponent = kEarthWarp * 0.57735f;
  Vec3 q = p + Vec3{fbmContrast(p * 1.7f, 1, kSeedWarp), fbmContrast(p * 1.7f, 1, kSeedWarp + 101),
                    fbmContrast(p * 1.7f, 1, kSeedWarp + 202)} * kComponent;
  for (size_t i = 0; i < centres.size(); ++i) {
    float r = kEarthContinents[i].radius;
    Vec3 d = q - centres[i];
    float d2 = dot(d, d);
    if (d2 < r * r) e += smoothstep(r, 0.5f * r, std::sqrt(d2));
  }
  return e;
}

TexturePtr earthColorMap(int w, int h, int levels) {
  requireSize("earthColorMap", w, h);
  SphereGrid grid(w, h);
  return makeMap("earthColorMap", Format::A8R8G8B8, w, h, levels, [&](int x, int y) {
    Vec3 p = grid.at(x, y);
    EarthSample s = earthAt(p);
    if (s.ice) return Color4{0.92f, 0.95f, 0.98f, 0.0f};
    if (s.elevation <= 0) {
      // Lighter shelves near the coast, deep blue in the open ocean; fully glossy.
      float deep = smoothstep(0.0f, 0.25f, -s.elevation);
      return Color4{lerp(0.13f, 0.02f, deep), lerp(0.38f, 0.08f, deep), lerp(0.62f, 0.32f, deep), 1.0f};
    }
    // Green lowlands or dry tan plains, brown-grey highlands, snow on the peaks.
    float dry = smoothstep(-0.3f, 0.5f, fbm(p * 3.0f, 3, kSeedDryness));
    Color4 c{lerp(0.18f, 0.60f, dry), lerp(0.42f, 0.52f, dry), lerp(0.14f, 0.30f, dry), 0.0f};
    float high = smoothstep(0.3f, 0.6f, s.height);
    c = {lerp(c.r, 0.42f, high), lerp(c.g, 0.36f, high), lerp(c.b, 0.30f, high), 0.0f};
    float snow = smoothstep(0.78f, 0.9f, s.height);
    return Color4{lerp(c.r, 0.95f, snow), lerp(c.g, 0.95f, snow), lerp(c.b, 0.97f, snow), 0.0f};
  });
}

TexturePtr earthHeightMap(int w, int h, int levels) {
  requireSize("earthHeightMap", w, h);
  std::vector<uint8_t> hm = earthHeights(w, h);
  return makeMap("earthHeightMap", Format::L8, w, h, levels, [&](int x, int y) {
    float v = float(hm[size_t(y) * w + x]) / 255.0f;
    return Color4{v, v, v, 1.0f};
  });
}

TexturePtr earthBumpMap(int w, int h, int levels) {
  return earthBump("earthBumpMap", Format::V8U8, w, h, levels);
}

TexturePtr earthBumpMapLuminance(int w, int h, int levels) {
  return earthBump("earthBumpMapLuminance", Format::X8L8V8U8, w, h, levels);
}

TexturePtr earthNormalMap(int w, int h, int levels) {
  TexturePtr height = earthHeightMap(w, h, 1);
  TexturePtr n = computeNormalMap(*height, CHANNEL_RED, 10.0f, NORMALMAP_MIRROR_V);
  if (levels == 1) return n;
  TexturePtr out = Texture::create2D(Format::A8R8G8B8, w, h, levels);
  std::copy_n(n->data(0, 0), n->dataSize(0, 0), out->data(0, 0));
  out->generateMips();
  out->markDirty();
  return out;
}

TexturePtr earthNormalMapSpecularAlpha(int w, int h, float power, int levels) {
  TexturePtr normal = earthNormalMap(w, h, 1);
  TexturePtr out = Texture::create2D(Format::A8R8G8B8, w, h, levels);
  for (int y = 0; y < h; ++y) {
    const float a = std::pow((float(y) + 0.5f) / float(h), power);
    for (int x = 0; x < w; ++x) {
      Color4 c = normal->texel(0, 0, x, y);
      c.a = a;
      out->setTexel(0, 0, x, y, 0, c);
    }
  }
  out->generateMips();
  out->markDirty();
  return out;
}

TexturePtr cloudMap(int w, int h, int levels) {
  requireSize("cloudMap", w, h);
  SphereGrid grid(w, h);
  return makeMap("cloudMap", Format::A8R8G8B8, w, h, levels, [&](int x, int y) {
    Vec3 p = grid.at(x, y);
    // Bands: more cloud in the mid latitudes than at the equator.
    float band = 0.15f * std::cos(6.0f * std::acos(std::clamp(p.y, -1.0f, 1.0f)));
    float cover = smoothstep(0.05f, 0.55f, fbm(p * 3.5f, 6, kSeedClouds) + band);
    return Color4{1.0f, 1.0f, 1.0f, cover};
  });
}

TexturePtr environmentMap(int size, int levels) {
  requireSize("environmentMap", size, size);
  return makeMap("environmentMap", Format::A8R8G8B8, size, size, levels, [&](int x, int y) {
    float dx = (float(x) + 0.5f) / float(size) - 0.5f, dy = (float(y) + 0.5f) / float(size) - 0.5f;
    float r = std::sqrt(dx * dx + dy * dy) * 2.0f;  // 0 at the centre, 1 at the edge midpoints
    float sky = std::clamp(1.0f - r, 0.0f, 1.0f);
    float sun = std::exp(-(r * r) / (0.18f * 0.18f));
    Color4 c{0.02f + 0.35f * sky * sky, 0.05f + 0.5f * sky * sky, 0.20f + 0.6f * sky, 1.0f};
    return Color4{std::min(1.0f, c.r + sun), std::min(1.0f, c.g + 0.95f * sun),
                  std::min(1.0f, c.b + 0.8f * sun), 1.0f};
  });
}

TexturePtr checker(int size, int cells, int levels) {
  requireSize("checker", size, size);
  if (cells < 1 || cells > size) fail("checker: {} cells do not fit a {}-texel texture", cells, size);
  return makeMap("checker", Format::A8R8G8B8, size, size, levels, [&](int x, int y) {
    int cx = int(int64_t(x) * cells / size), cy = int(int64_t(y) * cells / size);
    float v = (cx + cy) % 2 == 0 ? 1.0f : 0.0f;
    return Color4{v, v, v, 1.0f};
  });
}

TexturePtr brick(int size, int levels) {
  requireSize("brick", size, size);
  constexpr int kCourses = 8, kBricksPerCourse = 4;
  const float mortar = 0.06f;  // fraction of a brick's height
  return makeMap("brick", Format::A8R8G8B8, size, size, levels, [&](int x, int y) {
    float v = (float(y) + 0.5f) / float(size) * kCourses;
    int course = int(v);
    float u = (float(x) + 0.5f) / float(size) * kBricksPerCourse + (course % 2 ? 0.5f : 0.0f);
    int column = int(std::floor(u)) % kBricksPerCourse;
    float fu = u - std::floor(u), fv = v - float(course);
    float edgeU = mortar * 0.5f;  // bricks are twice as wide as tall (4 across, 8 down)
    if (fv < mortar || fv > 1 - mortar || fu < edgeU || fu > 1 - edgeU)
      return Color4{0.78f, 0.76f, 0.72f, 1.0f};
    // Each brick its own shade, plus a fine grain.
    float shade = float(hash3(column, course, 0, kSeedBricks) >> 8) / 16777215.0f;
    float grain = 0.05f * valueNoise({float(x) * 0.35f, float(y) * 0.35f, 0.5f}, kSeedBricks + 1);
    return Color4{0.55f + 0.15f * shade + grain, 0.22f + 0.08f * shade + grain,
                  0.15f + 0.05f * shade + grain, 1.0f};
  });
}

}  // namespace refx::d3dx
