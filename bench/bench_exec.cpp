// The execution engine on its own: every sample shader (data/shaders) that lowers,
// one 16-lane batch per iteration, on the interpreter and on native code (AVX2, and
// AVX-512 where the CPU has it); and the time AsmJit takes to compile each program.
//   bench_exec --benchmark_filter=run/        batches
//   bench_exec --benchmark_filter=compile/    compile time per program
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "exec/jit/jit.h"
#include "refx/exec/abi.h"
#include "refx/exec/interpreter.h"
#include "refx/exec/lower.h"
#include "refx/shader/assembler.h"

namespace {

using namespace refx;
using namespace refx::exec;

struct Sample {
  std::string name;
  Program program;
};

std::vector<Sample> samples() {
  std::vector<Sample> out;
  std::vector<std::filesystem::path> files;
  const std::filesystem::path dir = std::filesystem::path(REFX_DATA_DIR) / "shaders";
  if (!std::filesystem::is_directory(dir)) return out;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".psh" || e.path().extension() == ".vsh") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const auto& path : files) {
    std::ifstream f(path);
    std::stringstream text;
    text << f.rdbuf();
    try {
      out.push_back({path.filename().string(), lowerShader(shader::assemble(text.str(), path.string())).program});
    } catch (const Error&) {
    }
  }
  return out;
}

void fakeSample(const void*, SampleMode, const float (*co)[kBatchLanes], uint16_t, float (*out)[kBatchLanes]) {
  for (int c = 0; c < 4; ++c)
    for (int l = 0; l < kBatchLanes; ++l) out[c][l] = co[c][l] * 0.5f + 0.25f;
}

struct Backend {
  const char* name;
  bool jit;
  PrepareOptions::Isa isa;
};

void run(benchmark::State& state, const Program* program, Backend backend) {
  std::vector<Vec4> constants(kConstBumpEnv + kConstBumpEnvCount, Vec4(0.5f, 0.25f, -0.5f, 1));
  std::vector<SamplerBinding> samplers(kSamplerCount, SamplerBinding{nullptr, fakeSample});
  ExecContext ctx;
  ctx.constants = constants.data();
  ctx.constantCount = int(constants.size());
  ctx.samplers = samplers.data();
  ctx.samplerCount = kSamplerCount;
  BatchRegisters regs;
  regs.resize(*program);
  if (regs.inputs.size() < size_t(kPixelInputRegisters)) regs.inputs.resize(kPixelInputRegisters);
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> value(0.0f, 1.0f);
  for (auto& r : regs.inputs)
    for (auto& c : r.c)
      for (float& x : c) x = value(rng);
  PrepareOptions options;
  options.jit = backend.jit;
  options.isa = backend.isa;
  const ProgramBuildInfo info = prepare(*program, ctx, regs, options);
  if (backend.jit && std::string(info.backend) == "interpreter") {
    state.SkipWithError("not compiled for this instruction set");
    return;
  }
  for (auto _ : state) {
    regs.laneMask = 0xffff;
    execute(*program, ctx, regs);
    benchmark::ClobberMemory();
  }
  state.counters["instructions"] = double(program->code.size());
  state.SetItemsProcessed(int64_t(state.iterations()) * kBatchLanes);
}

void compile(benchmark::State& state, const Program* program, detail::JitIsa isa) {
  for (auto _ : state) {
    auto jit = detail::compileProgram(*program, isa);
    benchmark::DoNotOptimize(jit.get());
  }
  state.counters["instructions"] = double(program->code.size());
}

const bool registered = [] {
  static const std::vector<Sample> all = samples();
  const Backend backends[] = {{"interpreter", false, PrepareOptions::Isa::Auto},
                              {"jit-avx2", true, PrepareOptions::Isa::Avx2},
                              {"jit-avx512", true, PrepareOptions::Isa::Avx512}};
  for (const Sample& s : all)
    for (const Backend& b : backends)
      benchmark::RegisterBenchmark(("run/" + s.name + "/" + b.name).c_str(), run, &s.program, b);
  for (const Sample& s : all)
    benchmark::RegisterBenchmark(("compile/" + s.name + "/avx512").c_str(), compile, &s.program,
                                 detail::JitIsa::Avx512)
        ->Unit(benchmark::kMicrosecond);
  return true;
}();

}  // namespace
