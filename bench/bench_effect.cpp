// Effect load time: Effect::fromFile for each effect of data/effects, which parses the
// file, evaluates the parameters' initialisers, assembles the asm shaders and compiles
// the HLSL ones (the part of an edit-to-image reload that is not drawing).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "refx/effect/effect.h"

namespace {

void BM_LoadEffect(benchmark::State& state, const std::string& file) {
  const std::string path = std::string(REFX_DATA_DIR) + "/effects/" + file;
  for (auto _ : state) benchmark::DoNotOptimize(refx::effect::Effect::fromFile(path));
}

// One benchmark per effect file, named after it.
const bool kRegistered = [] {
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(std::string(REFX_DATA_DIR) + "/effects"))
    if (e.path().extension() == ".fx") files.push_back(e.path().filename().string());
  std::sort(files.begin(), files.end());
  for (const std::string& f : files)
    benchmark::RegisterBenchmark(("BM_LoadEffect/" + f).c_str(), BM_LoadEffect, f)->Unit(benchmark::kMillisecond);
  return true;
}();

}  // namespace
