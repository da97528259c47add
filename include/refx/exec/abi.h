// The register layout of lowered programs: where a vertex program writes its
// outputs, where a pixel program finds its inputs and writes its colors, and where
// pixel programs read the bump environment. Shader lowering, the fixed-function
// program builders and the rasterizer all use these numbers.
//
//   vertex inputs   Input  v# of the shader as written (dcl says which element feeds it)
//   vertex outputs  Output kVertexOut*; vs_3_0 o# are mapped here by their dcl semantic
//   pixel inputs    Input  kPixelIn*; ps_3_0 v# are mapped here by their dcl semantic
//   pixel outputs   Output oC0..oC3 at kPixelOutColor + n, oDepth (.x) at kPixelOutDepth
//   constants       Const  0..N-1 the float constants c# set through the API (local
//                          `def` constants are resolved by the lowering itself);
//                          pixel shaders additionally read the texture stages' bump
//                          environment at kConstBumpEnv (see below), so their
//                          constant array needs kConstBumpEnv + kConstBumpEnvCount
//                          entries when bumpEnvStages is set
//                   ConstInt / ConstBool: i# / b# through ExecContext::intConstants /
//                          boolConstants (defi / defb resolved by the lowering)
//   samplers        Instr::sampler = the stage: ps_1_x stage m (t#/r# number), ps_2_0+
//                          s#; vertex shaders (vs_3_0 texldl) use s0..s3, which the
//                          device binds to D3DVERTEXTEXTURESAMPLER0..3
#pragma once

namespace refx::exec {

// Vertex program outputs (vertex shaders and fixed-function T&L alike).
enum VertexOutput : int {
  kVertexOutPosition = 0,  // clip space (x,y,z,w); pretransformed: (sx, sy, sz, rhw) passed through
  kVertexOutDiffuse = 1,   // oD0
  kVertexOutSpecular = 2,  // oD1
  kVertexOutTex0 = 3,      // ..10: oT0..oT7, coordinates for texture stage 0..7
  kVertexOutFog = 11,      // .x (replicated)
  kVertexOutPSize = 12,    // .x (replicated)
  kVertexOutputCount = 13,
};

// Pixel program inputs.
enum PixelInput : int {
  kPixelInDiffuse = 0,   // v0
  kPixelInSpecular = 1,  // v1
  // 2..9 = t0..t7, coordinates for stage/texture register 0..7 (4 components; when
  // TEXTURETRANSFORMFLAGS has PROJECTED the divisor is already in .w)
  kPixelInTex0 = 2,
  kPixelInFog = 10,       // .x = vertex fog factor f (1 = no fog)
  kPixelInPosition = 11,  // vPos: (screen x, screen y, z in [0,1], eye-space w)
  // The inputs above are interpolated for every pixel program; vFace is not
  // interpolated and is present only in programs that read it.
  kPixelInterpolatedInputCount = 12,
  kPixelInFace = 12,  // vFace .x: +1 clockwise, -1 counter-clockwise
  kPixelInputRegisters = 13,  // every pixel input a program may address
};

// Pixel program outputs.
enum PixelOutput : int {
  kPixelOutColor = 0,  // ..3: oC0..oC3 (fixed function and ps_1_x write oC0 alone)
  kPixelOutDepth = 4,  // oDepth .x
  kPixelOutputRegisters = 5,
};

constexpr int kTextureCoordinateSets = 8;  // t0..t7, oT0..oT7, TEXCOORD0..7
constexpr int kSamplerCount = 16;          // s0..s15

// Pixel shaders read BUMPENVMAT00/01/10/11 of texture stage n at
// Const[kConstBumpEnv + 2n] = (m00, m01, m10, m11) and BUMPENVLSCALE/LOFFSET at
// Const[kConstBumpEnv + 2n + 1] = (lscale, loffset, 0, 0).
constexpr int kConstBumpEnv = 256;
constexpr int kBumpEnvStages = 8;
constexpr int kConstBumpEnvCount = 2 * kBumpEnvStages;

// Fixed-function pixel programs, and the fog appended to ps_1_x/ps_2_x shaders, read
// the draw's values from constants after the bump environment, so a program built for
// a state serves every value of them:
//   Const[kConstTextureFactor]        D3DRS_TEXTUREFACTOR as (r, g, b, a)
//   Const[kConstStageConstant + n]    D3DTSS_CONSTANT of stage n as (r, g, b, a)
//   Const[kConstBumpEnvRows + 2n]     (BUMPENVMAT00, BUMPENVMAT01, 0, 0) of stage n
//   Const[kConstBumpEnvRows + 2n + 1] (BUMPENVMAT10, BUMPENVMAT11, 0, 0) of stage n
//   Const[kConstPixelFog + i]         pixel fog, each value in all four components:
//                                     i = 0: -1/(end - start), 1: end/(end - start),
//                                     2: end, 3: -density*log2(e), 4: density*sqrt(log2(e));
//                                     i = 5: D3DRS_FOGCOLOR as (r, g, b, a)
// (BUMPENVLSCALE/LOFFSET are read at kConstBumpEnv + 2n + 1 as for pixel shaders.)
constexpr int kConstTextureFactor = kConstBumpEnv + kConstBumpEnvCount;
constexpr int kConstStageConstant = kConstTextureFactor + 1;
constexpr int kConstBumpEnvRows = kConstStageConstant + kBumpEnvStages;
constexpr int kConstPixelFog = kConstBumpEnvRows + 2 * kBumpEnvStages;
constexpr int kConstPixelFogCount = 6;
constexpr int kConstFixedPixelEnd = kConstPixelFog + kConstPixelFogCount;

// Fixed-function vertex programs read the draw's transforms, material, lights, fog and
// point size from their own constant array (they read no API constants), filled for
// every draw. Matrices are stored as columns (dp4(v, column j) = component j of v * M);
// single values in all four components.
constexpr int kConstVertexWorldView = 0;            // 4 columns of World * View
constexpr int kConstVertexWorldViewProjection = 4;  // 4 columns of World * View * Projection
constexpr int kConstVertexNormalMatrix = 8;         // 3 columns: inverse transpose of World * View
constexpr int kConstVertexProjection = 11;          // 4 columns
// Vertex blending without indices: matrix i (0-3) at kConstVertexBlendMatrices + 7i,
// 4 columns of WorldMatrix(i) * View, then 3 columns of its normal matrix.
constexpr int kConstVertexBlendMatrices = 15;
constexpr int kConstVertexBlendStride = 7;
constexpr int kConstVertexTextureTransform = 43;  // stage n: 4 columns at + 4n
constexpr int kConstVertexMaterial = 75;  // diffuse, ambient, specular, emissive, power
constexpr int kConstVertexAmbient = 80;   // D3DRS_AMBIENT + the directional lights' ambient, .w 0
// Vertex fog: -1/(end - start) (or -1e30 when end = start), end/(end - start),
// -density*log2(e), density.
constexpr int kConstVertexFog = 81;
// D3DRS_POINTSIZE, POINTSCALE_A, _B, _C, the viewport height, POINTSIZE_MIN, _MAX.
constexpr int kConstVertexPointSize = 85;
constexpr int kConstVertexTweenFactor = 92;
// Light n at kConstVertexLights + kConstVertexLightStride * n: direction towards the
// light and position (camera space, .w 0), attenuation 0/1/2, range, cos(phi/2), spot
// scale 1/(cos(theta/2) - cos(phi/2)), -cos(phi/2) * spot scale, falloff, ambient,
// diffuse and specular colour, and the half vector of a directional light with a
// non-local viewer.
constexpr int kConstVertexLights = 93;
constexpr int kConstVertexLightStride = 14;
// Indexed vertex blending: World(m) * View and its normal matrix for all 256 matrices,
// 7 columns each, addressed relative to the vertex's blend indices.
constexpr int kConstVertexBlendTable = kConstVertexLights + 8 * kConstVertexLightStride;
constexpr int kConstVertexBlendTableEnd = kConstVertexBlendTable + 256 * kConstVertexBlendStride;

}  // namespace refx::exec
