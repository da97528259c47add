// Procedural textures for the built-in samples, so they need no downloaded media.
// Every generator is deterministic (fixed seeds): the same arguments give the same
// bytes on every run and machine.
//
// The earth maps are equirectangular and match createTexturedSphere: texel centre
// (u, v) = ((x+0.5)/W, (y+0.5)/H) lies at earthDirection(u, v) on the unit sphere,
// and the noise is sampled there, so the u = 0 / u = 1 seam is invisible.
// `levels` is as for Texture::create2D (0 = full chain); the smaller levels are box
// filtered from level 0.
#pragma once
#include <cstdint>

#include "refx/core/math.h"
#include "refx/resource/texture.h"

namespace refx::d3dx {

// Continents: each is a plateau around a centre (u, v) of the map, adding
// smoothstep(radius, radius/2, d) to the elevation (1 within chord distance d <
// radius/2 on the unit sphere, 0 beyond radius). d is measured from a point displaced
// by a smooth warp field of length <= kEarthWarp, which makes the coasts irregular.
// Elevation = -0.45 + the continents + 0.4 * noise (|noise| <= 1); land where > 0.
// So by construction a continent centre is always land (radius/2 >= kEarthWarp:
// elevation >= -0.45 + 1 - 0.4), and a point farther than radius + kEarthWarp from
// every centre is always ocean (elevation <= -0.45 + 0.4).
struct EarthContinent {
  float u, v, radius;
};
inline constexpr float kEarthWarp = 0.18f;
inline constexpr EarthContinent kEarthContinents[] = {
    {0.20f, 0.27f, 0.55f},  // north-west
    {0.27f, 0.42f, 0.36f},  // its isthmus
    {0.32f, 0.63f, 0.48f},  // south-west
    {0.55f, 0.24f, 0.55f},  // the large northern mass
    {0.72f, 0.27f, 0.60f},
    {0.85f, 0.22f, 0.45f},
    {0.53f, 0.53f, 0.50f},  // south of it
    {0.68f, 0.45f, 0.36f},  // a peninsula
    {0.86f, 0.68f, 0.40f},  // the southern island continent
    {0.95f, 0.40f, 0.36f},  // an island
    {0.50f, 0.97f, 0.50f},  // the south polar land
};

// Unit-sphere point of map position (u, v): north pole +y at v = 0, u = 0 toward +z,
// east toward -x there (createTexturedSphere's mapping).
Vec3 earthDirection(float u, float v);
// Elevation of the procedural earth at a unit-sphere point: > 0 land, <= 0 sea.
float earthElevation(Vec3 p);

// A8R8G8B8 colour map: blue oceans (lighter near the coasts), green to brown land,
// white polar ice. Alpha = gloss: 255 over open water, 0 on land and ice.
TexturePtr earthColorMap(int width, int height, int levels = 1);
// L8 heights: water 0, land from a low coast rising to mountain ranges.
TexturePtr earthHeightMap(int width, int height, int levels = 1);
// V8U8 bump map for D3DTOP_BUMPENVMAP (as the DirectX 6 BumpEarth sample builds it):
// du = h(x-1, y) - h(x+1, y), dv = h(x, y-1) - h(x, y+1) in 8-bit height steps,
// stored as signed bytes (value = steps / 127); wraps in u, clamps at the poles.
TexturePtr earthBumpMap(int width, int height, int levels = 1);
// X8L8V8U8: the same du, dv, and L = brightness for BUMPENVMAPLUMINANCE: 127/255 over
// water, 63/255 on land (land reflects less of the environment).
TexturePtr earthBumpMapLuminance(int width, int height, int levels = 1);
// A8R8G8B8 normal map: computeNormalMap of the height map (amplitude 10, mirrored
// at the poles, wrapped in u).
TexturePtr earthNormalMap(int width, int height, int levels = 1);
// earthNormalMap with a specular power table in alpha: A = v^power at texel row v
// (RacorX9's ps.1.4 reads the power from the normal map's alpha).
TexturePtr earthNormalMapSpecularAlpha(int width, int height, float power, int levels = 1);
// A8R8G8B8 white clouds over the same sphere; alpha = cloud cover.
TexturePtr cloudMap(int width, int height, int levels = 1);

// A8R8G8B8 sky for bump environment mapping: a bright soft sun in the middle falling
// off through sky blue to dark blue at the corners.
TexturePtr environmentMap(int size, int levels = 1);
// A8R8G8B8 checkerboard of cells x cells squares, white where (cx + cy) is even
// (the top-left cell is white), black elsewhere.
TexturePtr checker(int size, int cells, int levels = 1);
// A8R8G8B8 brick wall: 8 courses of running bond, light grey mortar.
TexturePtr brick(int size, int levels = 1);

}  // namespace refx::d3dx
