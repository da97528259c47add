// Primitive setup and the tiled rasterizer. A draw is turned into screen-space
// primitives, binned into 64x64 tiles, and each tile is shaded by one thread in
// submission order, so the output does not depend on the thread count.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "refx/core/batch.h"
#include "refx/core/thread_pool.h"
#include "refx/exec/abi.h"
#include "refx/exec/interpreter.h"
#include "refx/pipeline/device.h"
#include "refx/resource/sampler.h"
#include "raster_store.h"

namespace refx::pipeline {

constexpr int kTileSize = 64;
constexpr int kSubPixelBits = 8;  // edge functions in 1/256 pixel units

// A vertex after the vertex stage: clip-space position and all vertex outputs.
constexpr int kVaryingCount = exec::kVertexOutputCount;  // every vertex output (exec/abi.h)
struct ShadedVertex {
  Vec4 out[kVaryingCount];  // out[0] = clip position (or screen position when pretransformed)
};

// One input component of the pixel program and where it comes from.
struct InterpolatedInput {
  uint8_t input;      // pixel input register
  uint8_t component;  // 0..3
  uint8_t varying;    // vertex output index
  bool flat;          // flat shading: first vertex value
  bool wrap = false;  // D3DRS_WRAPn: interpolate the shorter way around the unit cylinder
};

enum class PrimKind : uint8_t { Triangle, Line, Point };

struct Primitive {
  PrimKind kind;
  bool counterClockwise;  // screen-space winding (two-sided stencil)
  int minX, minY, maxX, maxY;  // inclusive pixel bounds, clipped to the scissor/viewport
  // Triangles: edge functions E = A*X + B*Y + C in subpixel units, inside when E + bias > 0.
  int64_t edgeA[3], edgeB[3], edgeC[3], edgeBias[3];
  // Lines: major axis and the line y = m*x + q (or x = m*y + q) in pixels.
  bool xMajor;
  float lineM, lineQ;
  // Interpolation planes: value(x,y) = base + dx*(x - originX) + dy*(y - originY).
  float originX, originY;
  uint32_t planeOffset;
  float wDepthOffset;  // w-buffering: the depth bias added to w / w_far  // into RasterDraw::planes: [invW, z, then inputs' attr/w (or attr when flat)]
};

// Direct3D 9 binds up to four render targets (SetRenderTarget 0-3).
constexpr int kMaxRenderTargets = 4;

// One colour render target as the output merger and Clear write it.
struct ColorTarget {
  uint8_t* data = nullptr;  // A8R8G8B8/X8R8G8B8 rows, or A32B32G32R32F rows; null: none
  int pitch = 0;
  bool hasAlpha = true;      // X8R8G8B8 stores 255 as alpha
  bool isFloat = false;      // four floats (r, g, b, a) a pixel, unclamped
  uint32_t writeMask = 0xf;  // D3DRS_COLORWRITEENABLE (target 0) or COLORWRITEENABLE1-3
};

struct RasterDraw;
// Alpha test, depth/stencil, blend and write of one batch (output_merger.h mergeBatch or
// a version of it specialised for the draw's state).
using MergeBatchFn = void (*)(const RasterDraw& d, int bx, int by, uint16_t mask,
                              const exec::LaneVec4* colors, const float* z, bool depthAlreadyTested,
                              bool counterClockwise);
// The early depth test of a batch, returning the lanes that pass (output_merger.h
// earlyDepthTest or a version of it specialised for the draw's depth state).
using EarlyDepthFn = uint16_t (*)(const RasterDraw& d, int bx, int by, uint16_t mask, const float* z,
                                  bool writeDepth);

// Everything the tile workers need for one draw.
struct RasterDraw {
  const DeviceState* state = nullptr;
  const exec::Program* pixelProgram = nullptr;
  exec::ExecContext execContext;
  std::vector<InterpolatedInput> inputs;
  // The opaque store of whole blocks inside target 0 for the active instruction set
  // (rasterize); null: merge_kernels.h's.
  OpaqueBlockStoreFn opaqueBlockStore = nullptr;
  // Per input: an earlier one whose planes are its own in every primitive (the same
  // values at every vertex, the same flags), or -1 (setupPrimitives).
  std::vector<int> inputCopies;
  bool usesPosition = false;  // pixel input exec::kPixelInPosition read
  bool usesFace = false;      // pixel input exec::kPixelInFace read (vFace: +1 clockwise, -1 not)
  bool shaderDepth = false;   // the program writes the depth (output exec::kPixelOutDepth .x)
  std::vector<Primitive> prims;
  std::vector<float> planes;  // 3 floats per plane
  // Targets: [i] is written from the pixel program's output i (oCi); a target that is
  // not bound, or whose oCi the program does not write, has no data and stays as it was.
  std::array<ColorTarget, kMaxRenderTargets> targets;
  DepthStencilSurface* depth = nullptr;
  int width = 0, height = 0;
  bool earlyDepth = false;
  // Precomputed output-merger state.
  struct Blend {
    bool enable;
    uint32_t src, dst, op, srcA, dstA, opA;
    Color4 factor;
  } blend{};
  bool srgbWrite = false;  // D3DRS_SRGBWRITEENABLE: linear -> sRGB on write
  bool dither = false;     // D3DRS_DITHERENABLE: ordered dithering into 8-bit targets
  bool alphaTest = false;
  uint32_t alphaFunc = 8;
  bool depthTest = false, depthWrite = false;
  uint32_t depthFunc = 4;
  bool stencil = false;
  // The reference values and stencil operations (D3DRS_ALPHAREF, STENCIL*, CCW_STENCIL*)
  // of the draw; ops[0] clockwise, ops[1] counter-clockwise (the CCW_ states with
  // TWOSIDEDSTENCILMODE): func, fail, zfail, pass.
  uint8_t alphaRef = 0, stencilRef = 0, stencilMask = 0xff, stencilWriteMask = 0xff;
  std::array<std::array<uint32_t, 4>, 2> stencilOps{};
  // The merge for the draw's state; null: mergeBatch.
  MergeBatchFn merge = nullptr;
  // The early depth test for the draw's state; null: earlyDepthTest.
  EarlyDepthFn earlyDepthTestFn = nullptr;
  // D3DZB_USEW: the depth tested and written is w / w_far (projectionFarW), from the
  // interpolated 1/w, plus Primitive::wDepthOffset, instead of z.
  bool wBuffer = false;
  float invFarW = 1.0f;
  // D3DRS_DEPTHBIAS and SLOPESCALEDEPTHBIAS, added to triangles' depth at setup (their z
  // planes, or wDepthOffset).
  float depthBias = 0, slopeScaleDepthBias = 0;
  // The plan's samplePassthrough with a prepared 2D texture bound: the pixel stage
  // samples it at input `passthroughInput` of `inputs` (u; v is the next one) and stores
  // the bytes, instead of running the program and the merge. Null: the program runs.
  const PreparedSampler* passthroughSampler = nullptr;
  int passthroughInput = -1;
  // The plan's texturePrologue where every lookup's texture is a prepared 2D one: the
  // pixel stage makes the lookups for groups of batches (PreparedSampler::
  // sampleImplicitGroup), then runs pixelRest (the program without them) on each batch.
  // Empty: the whole program runs batch by batch.
  struct PrologueLookup {
    const PreparedSampler* sampler = nullptr;
    int input = 0;                             // the coordinates' input register
    exec::RegFile file = exec::RegFile::Temp;  // the result's register
    int index = 0;
    uint8_t channels = 0xF;  // the result's components the rest of the program reads
    // The input register the lookup reads its coordinates from: `input`, or an earlier
    // lookup's whose interpolated values are the same in every component
    // (RasterDraw::inputCopies; set by rasterize), so both read one array.
    int coordinates = 0;
  };
  std::vector<PrologueLookup> prologue;
  const exec::Program* pixelRest = nullptr;
  exec::ProgramBuildInfo* pixelRestBuild = nullptr;  // gets what ran pixelRest (null: not wanted)
  bool groupedLookups = false;  // set by rasterize: the lookups were made for groups of blocks
  uint64_t* pixelsShaded = nullptr;  // per-thread counters (array of threadCount)
  exec::PrepareOptions prepareOptions;     // how the pixel program may run
  exec::ProgramBuildInfo* pixelBuild = nullptr;  // gets what ran it (null: not wanted)
  // A Clear deferred to this draw, written tile by tile as the tiles are shaded (tiles
  // without primitives too); where the draw overwrites target 0 or the depth, block by
  // block together with its batches (raster_fill.h), so those are written once.
  struct Fill {
    bool color = false, depth = false, stencil = false;  // surfaces (depth: the z values)
    Rect rect;                                             // inside the target
    uint32_t colorValue = 0;
    std::array<ColorTarget, kMaxRenderTargets> colorTargets;  // every bound render target
    float z = 1.0f;
    uint8_t stencilValue = 0;
  } fill;
};

// Writes the clear colour `argb` (a D3DCOLOR) to pixels [x0, x1) of one target row:
// as is for A8R8G8B8/X8R8G8B8, as four floats c/255 for A32B32G32R32F.
void fillColorRow(uint8_t* row, int x0, int x1, uint32_t argb, bool isFloat);

// Applies `fill` to the part of the targets (and depth/stencil) inside [x0,x1)x[y0,y1).
void applyFill(const RasterDraw::Fill& fill, DepthStencilSurface* depth, int x0, int y0, int x1,
               int y1);

// Bins the draw's primitives and shades all tiles on the pool.
void rasterize(RasterDraw& draw, ThreadPool& pool);

// A triangle's edge functions from its subpixel vertices (X, Y) and winding (the sign of
// its area: y points down, counter-clockwise on screen is negative): E = (P.y - a.y)*dx -
// (P.x - a.x)*dy of each edge a->b in clockwise order, positive inside, with the top-left
// rule's bias (a pixel centre on a top or left edge is inside).
void setTriangleEdges(const int64_t (&X)[3], const int64_t (&Y)[3], bool counterClockwise, Primitive& p);

}  // namespace refx::pipeline
