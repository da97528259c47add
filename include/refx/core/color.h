// Colors: float RGBA (what shaders see) and D3DCOLOR (0xAARRGGBB).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace refx {

struct Color4 {
  float r = 0, g = 0, b = 0, a = 0;
  constexpr bool operator==(const Color4&) const = default;
};

using D3DColor = uint32_t;

constexpr Color4 colorFromD3D(D3DColor c) {
  return {((c >> 16) & 0xff) / 255.0f, ((c >> 8) & 0xff) / 255.0f, (c & 0xff) / 255.0f,
          ((c >> 24) & 0xff) / 255.0f};
}

// Round-to-nearest conversion of a [0,1] value to 8 bits (clamped).
// NaN and negative values give 0.
inline uint8_t unorm8(float v) {
  v = v > 0.0f ? v : 0.0f;
  v = v < 1.0f ? v : 1.0f;
  return static_cast<uint8_t>(v * 255.0f + 0.5f);
}

inline D3DColor colorToD3D(Color4 c) {
  return (D3DColor(unorm8(c.a)) << 24) | (D3DColor(unorm8(c.r)) << 16) |
         (D3DColor(unorm8(c.g)) << 8) | D3DColor(unorm8(c.b));
}

}  // namespace refx
