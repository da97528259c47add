// D3DXFillTexture / FillCubeTexture / FillVolumeTexture, the normalization cube
// map, and D3DXComputeNormalMap.
#pragma once
#include <cstdint>
#include <functional>

#include "refx/core/math.h"
#include "refx/resource/texture.h"

namespace refx::d3dx {

// LPD3DXFILL2D / LPD3DXFILL3D: returns (x, y, z, w) written as (R, G, B, A), converted
// to the texture's format (clamped to its range).
using Fill2D = std::function<Vec4(Vec2 texCoord, Vec2 texelSize)>;
using Fill3D = std::function<Vec4(Vec3 texCoord, Vec3 texelSize)>;

// Every texel of every mip level: texCoord = ((x + 0.5) / W, (y + 0.5) / H) of the
// level, texelSize = (1/W, 1/H). Throws refx::Error for compressed formats and for
// textures that are not 2D.
void fillTexture(Texture& texture, const Fill2D& fill);
// Every face and level: texCoord = the direction of the texel centre (not
// normalized; see cubeTexelDirection), texelSize = 2/S on the two axes of the face
// and 0 on its major axis.
void fillCubeTexture(Texture& texture, const Fill3D& fill);
// texCoord = ((x+0.5)/W, (y+0.5)/H, (z+0.5)/D), texelSize = (1/W, 1/H, 1/D).
void fillVolumeTexture(Texture& texture, const Fill3D& fill);

// Direction of texel (x, y) of cube face `face` (D3DCUBEMAP_FACES: +X 0, -X 1, +Y 2,
// -Y 3, +Z 4, -Z 5) of size S, with s = 2(x+0.5)/S - 1, t = 2(y+0.5)/S - 1:
// +X (1,-t,-s), -X (-1,-t,s), +Y (s,1,t), -Y (s,-1,-t), +Z (s,-t,1), -Z (-s,-t,-1).
Vec3 cubeTexelDirection(int face, float x, float y, int size);

// Cube map whose texels hold their own normalized direction n: 0.5 + 0.5*n in
// unsigned formats, n itself in signed ones (Q8W8V8U8 ...); alpha 1.
TexturePtr createNormalizationCubeMap(int size, Format format = Format::A8R8G8B8, int levels = 1);

// D3DX_CHANNEL_*: where ComputeNormalMap reads the height.
enum Channel : uint32_t {
  CHANNEL_RED = 0x01,
  CHANNEL_BLUE = 0x02,
  CHANNEL_GREEN = 0x04,
  CHANNEL_ALPHA = 0x08,
  CHANNEL_LUMINANCE = 0x10,
};

// D3DX_NORMALMAP_*.
enum NormalMapFlags : uint32_t {
  NORMALMAP_MIRROR_U = 0x00010000,
  NORMALMAP_MIRROR_V = 0x00020000,
  NORMALMAP_MIRROR = 0x00030000,
  NORMALMAP_INVERTSIGN = 0x00080000,
  NORMALMAP_COMPUTE_OCCLUSION = 0x00100000,
};

// D3DXComputeNormalMap from level 0 of a 2D height texture (h in [0,1] from
// `channel`; samples past an edge wrap, or mirror with MIRROR_U/V):
//   dx = (h(x+1,y) - h(x-1,y)) / 2 * amplitude,  dy = (h(x,y+1) - h(x,y-1)) / 2 * amplitude
//   n  = normalize(-dx, -dy, 1)        (INVERTSIGN: normalize(dx, dy, 1))
// stored as (R, G, B) = 0.5*n + 0.5 in unsigned formats, n in signed formats
// (V8U8, Q8W8V8U8 ...). Alpha is 1, or with COMPUTE_OCCLUSION the fraction of the
// sky above the texel that the height field leaves open (1 = unoccluded).
// The result has one level of the height map's size.
TexturePtr computeNormalMap(const Texture& height, uint32_t channel, float amplitude,
                            uint32_t flags = 0, Format format = Format::A8R8G8B8);

}  // namespace refx::d3dx
