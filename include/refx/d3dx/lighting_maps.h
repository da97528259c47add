// Lookup textures and baked terms of the per-pixel lighting samples: the specular
// power tables filled by the samples' LightEval callbacks, RacorX10's point-light
// attenuation maps, per-vertex hemisphere occlusion for the "DIY" hemisphere lighting
// model, and the noise volume of the RenderMan wood shader.
// Every generator is deterministic: the same arguments give the same bytes.
#pragma once
#include <cstdint>
#include <vector>

#include "refx/core/math.h"
#include "refx/d3dx/mesh.h"
#include "refx/resource/texture.h"

namespace refx::d3dx {

// What LightEval writes into alpha.
enum class SpecularAlpha {
  One,  // RacorX8: col->w = 1
  U,    // RacorX9 and the effect paper's power-100 map: col->w = input->x
};

// The LightEval callback of RacorX8/RacorX9 and of the effect paper, run by
// fillTexture over every texel of every level (texel centre (u, v)):
//   RGB = (float) pow(v, power),  A = 1 or u.
// RacorX8: specularPowerMap(256, 256, 16) (A = 1); the effect paper's table:
// specularPowerMap(256, 256, 100, SpecularAlpha::U). A8R8G8B8; levels as
// Texture::create2D (0 = the full chain, as D3DXCreateTexture(..., 0, ...) gives).
TexturePtr specularPowerMap(int width, int height, float power,
                            SpecularAlpha alpha = SpecularAlpha::One, int levels = 0);

// RacorX12's 2048x1 table for texdp3tex: its LightEval writes RGB = 0 and
// A = (float) pow(u, power) with u = (x + 0.5) / width. A8R8G8B8.
TexturePtr specularPowerTable(int width = 2048, float power = 16, int levels = 0);

// RacorX10's point-light texture (pointlight.dds). The vertex shader puts
// 0.5 * L / range + 0.5 into the texture coordinates, so texel centre (u, v) stands
// for x = 2u - 1, y = 2v - 1:
//   RGB = x² + y² (clamped to 1)   read with (x, y) in t0
//   A   = x²                       read with z in the u coordinate of t1
// and the pixel shader's `add r0, 1-t0, -t1.a` gives 1 - (x² + y² + z²). A8R8G8B8.
TexturePtr attenuationMap2D(int size = 256, int levels = 1);
// The z² function alone as a width x 1 texture: RGB = A = (2u - 1)². A8R8G8B8.
TexturePtr attenuationMap1D(int width = 256, int levels = 1);

// Noise volume for the wood shader (`PP += sample3d(noise, PP) * turbulence`):
// four independent fractal gradient-noise fields (4 octaves, 4 lattice cells across
// the volume at the lowest) in R, G, B and A, each 0.5 + 0.5 * noise so values centre
// on 0.5 like RenderMan's noise(). The fields are periodic over the volume, so the
// texture tiles seamlessly under WRAP addressing. A8R8G8B8, size³ texels
// (size a power of two >= 4); `seed` picks the gradients.
inline constexpr uint32_t kWoodNoiseSeed = 0x57d00d;
TexturePtr woodNoiseVolume(int size = 64, int levels = 1, uint32_t seed = kWoodNoiseSeed);

// Per-vertex hemisphere visibility for the DIY hemisphere lighting model: rays from
// each vertex (lifted off the surface by `bias` times the mean length of the edges
// at the vertex) over the hemisphere around its normal are cast against the mesh's own
// triangles (both sides block); the result is the fraction of rays that escape, 1 =
// the whole sky is open, 0 = fully enclosed. The seed's vertex shader scales the
// light by (1 - v7.z), so it stores the occluded fraction 1 - visibility there.
struct OcclusionOptions {
  int rays = 128;               // per vertex; the same deterministic set everywhere
  bool cosineWeighted = false;  // directions distributed by cos θ (irradiance) instead of
                                // uniformly over the hemisphere (solid angle)
  float maxDistance = 0;        // > 0: hits farther than this (in mesh units) do not count
  float bias = 1e-3f;           // ray origin offset along the normal, x mean edge length
};
// Uses the mesh's NORMAL element, or area-weighted face normals when it has none.
// A bounding-volume hierarchy over the triangles keeps this fast: the teapot at
// 13 x 13 quads per patch (10816 triangles, 6272 vertices, 128 rays each) takes about
// half a second on one core.
std::vector<float> computeHemisphereVisibility(const Mesh& mesh, const OcclusionOptions& options = {});

// The unit directions used for `rays` rays in a frame whose z axis is the normal:
// a Fibonacci spiral, uniform in z (or in z² when cosine weighted).
std::vector<Vec3> hemisphereRayDirections(int rays, bool cosineWeighted);

}  // namespace refx::d3dx
