// D3DX mesh and texture helpers on production-sized inputs: tangent frames and
// normals of a ~100k-triangle sphere, adjacency and welding of it, and a normal map
// of a 2048x1024 height map. items_per_second counts triangles or texels.
#include <benchmark/benchmark.h>

#include "refx/d3dx/mesh.h"
#include "refx/d3dx/mesh_ops.h"
#include "refx/d3dx/sample_assets.h"
#include "refx/d3dx/texture_fill.h"

namespace {

using namespace refx;
using namespace refx::d3dx;

// createTexturedSphere(1, 317, 158): 2 * 317 * 157 = 99538 triangles, 50880 vertices.
const Mesh& sphere() {
  static const Mesh mesh = createTexturedSphere(1, 317, 158);
  return mesh;
}

void BM_ComputeTangentFrame(benchmark::State& state) {
  TangentFrameOptions options;
  options.flags = uint32_t(state.range(0));
  options.tangentOut = 1;
  options.binormalOut = 2;
  for (auto _ : state) {
    Mesh mesh = sphere();
    benchmark::DoNotOptimize(computeTangentFrame(mesh, options));
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * sphere().faceCount());
}
BENCHMARK(BM_ComputeTangentFrame)->Arg(0)->Arg(TANGENT_CALCULATE_NORMALS)->Unit(benchmark::kMillisecond);

void BM_ComputeNormals(benchmark::State& state) {
  Mesh mesh = sphere();
  std::vector<uint32_t> adjacency;
  if (state.range(0)) adjacency = generateAdjacency(mesh, 0.0f);
  for (auto _ : state) computeNormals(mesh, adjacency);
  state.SetItemsProcessed(int64_t(state.iterations()) * mesh.faceCount());
}
BENCHMARK(BM_ComputeNormals)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_GenerateAdjacency(benchmark::State& state) {
  float epsilon = state.range(0) ? 1e-5f : 0.0f;
  for (auto _ : state) benchmark::DoNotOptimize(generateAdjacency(sphere(), epsilon));
  state.SetItemsProcessed(int64_t(state.iterations()) * sphere().faceCount());
}
BENCHMARK(BM_GenerateAdjacency)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_WeldVertices(benchmark::State& state) {
  for (auto _ : state) {
    Mesh mesh = sphere();
    benchmark::DoNotOptimize(weldVertices(mesh, 1e-6f, WELD_ALL));
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * sphere().faceCount());
}
BENCHMARK(BM_WeldVertices)->Unit(benchmark::kMillisecond);

void BM_ComputeNormalMap(benchmark::State& state) {
  static const TexturePtr height = earthHeightMap(2048, 1024);
  uint32_t flags = uint32_t(state.range(0));
  for (auto _ : state)
    benchmark::DoNotOptimize(computeNormalMap(*height, CHANNEL_LUMINANCE, 10.0f, flags));
  state.SetItemsProcessed(int64_t(state.iterations()) * 2048 * 1024);
}
BENCHMARK(BM_ComputeNormalMap)->Arg(0)->Arg(NORMALMAP_MIRROR_V)->Unit(benchmark::kMillisecond);

}  // namespace
