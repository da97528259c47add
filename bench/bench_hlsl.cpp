// HLSL compile time: each seed program for the profiles its article names, the white
// paper's wood shader, and a generated 2,000-line vertex shader (many functions,
// uniform arrays, loops and feature switches, as an "uber-shader" of the era looks).
// One compile per iteration, on one core.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <fmt/format.h>

#include "refx/hlsl/compiler.h"

namespace {

std::string readSeed(const std::string& name) {
  std::ifstream in(std::string(REFX_DATA_DIR) + "/hlsl/" + name, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// ~2,000 lines: kFunctions helper functions of about 25 lines each, reading uniform
// arrays in loops and branching on their inputs, and a main that calls the ones its
// static feature switches enable (one in ten, so the result fits vs_3_0's slots).
constexpr int kFunctions = 64;
constexpr int kBanks = 8;

// allTerms switches every term on: the same code then needs about 3,000 slots, past
// vs_3_0's 512, and compiles up to that error (the most work the pipeline does on it).
std::string largeShader(bool allTerms = false) {
  std::string s = "// Generated: a vertex shader with many optional lighting terms.\n";
  s += "float4x4 gWorldViewProj;\nfloat4x4 gWorld;\nfloat3 gEye;\n";
  for (int b = 0; b < kBanks; ++b) s += fmt::format("float4 gBank{}[8];\n", b);
  s += "struct VS_OUTPUT {\n  float4 pos : POSITION;\n  float4 color : COLOR0;\n  float2 uv : TEXCOORD0;\n"
       "  float3 normal : TEXCOORD1;\n};\n\n";
  for (int f = 0; f < kFunctions; ++f) {
    s += fmt::format("static const bool kUseTerm{} = {};\n", f, allTerms || f % 10 == 0 ? "true" : "false");
    s += fmt::format("static const float kWeight{} = {:.3f};\n", f, 0.25 + 0.01 * f);
  }
  s += "\n";
  for (int f = 0; f < kFunctions; ++f) {
    const int bank = f % kBanks, first = f % 4;
    s += fmt::format("// Term {}: a light from bank {}.\n", f, bank);
    s += fmt::format("float3 term{}(float3 p, float3 n, float2 uv)\n{{\n", f);
    s += fmt::format("  float3 l = gBank{}[{}].xyz - p;\n", bank, first);
    s += "  float d2 = dot(l, l);\n";
    s += "  l = l * rsqrt(d2);\n";
    s += "  float3 v = normalize(gEye - p);\n";
    s += "  float3 h = normalize(l + v);\n";
    s += "  float ndl = saturate(dot(n, l));\n";
    s += "  float ndh = saturate(dot(n, h));\n";
    s += fmt::format("  float attenuation = 1.0 / (1.0 + gBank{}[{}].w * d2);\n", bank, first + 1);
    s += "  float3 acc = 0;\n";
    s += "  for (int i = 0; i < 3; i++) {\n";
    s += fmt::format("    float4 k = gBank{}[{} + i];\n", bank, first + 2);
    s += "    acc += k.rgb * (ndl * k.w + pow(ndh, 8.0 + i * 8.0));\n";
    s += "  }\n";
    s += "  float rim = 1 - saturate(dot(n, v));\n";
    s += "  if (rim > 0.5)\n";
    s += "    acc += rim * rim;\n";
    s += "  else\n";
    s += "    acc *= 0.75;\n";
    s += fmt::format("  float2 wave = sin(uv * {}.0 + p.xy);\n", f % 5 + 1);
    s += "  acc += wave.x * wave.y * 0.05;\n";
    s += fmt::format("  acc = lerp(acc, acc * attenuation, kWeight{});\n", f);
    s += "  return acc;\n";
    s += "}\n\n";
  }
  s += "VS_OUTPUT main(float4 pos : POSITION, float3 normal : NORMAL, float2 uv : TEXCOORD0)\n{\n";
  s += "  VS_OUTPUT o;\n";
  s += "  o.pos = mul(pos, gWorldViewProj);\n";
  s += "  float3 p = mul(pos, gWorld).xyz;\n";
  s += "  float3 n = normalize(mul(normal, (float3x3)gWorld));\n";
  s += "  float3 color = 0.1;\n";
  for (int f = 0; f < kFunctions; ++f) {
    s += fmt::format("  if (kUseTerm{})\n", f);
    s += fmt::format("    color += term{}(p, n, uv);\n", f);
  }
  s += "  o.color = float4(saturate(color), 1);\n";
  s += "  o.uv = uv;\n";
  s += "  o.normal = n;\n";
  s += "  return o;\n";
  s += "}\n";
  return s;
}

int lineCount(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

// expectedError: "" when the source must compile, else the one error code it must give.
void compileBenchmark(benchmark::State& state, const std::string& source, const std::string& name,
                      refx::hlsl::CompileOptions options, const std::string& expectedError = "") {
  const refx::hlsl::CompileResult check = refx::hlsl::compile(source, name, options);
  int errors = 0;
  bool expected = false;
  for (const refx::Diagnostic& d : check.diagnostics) {
    if (d.severity != refx::Severity::Error) continue;
    ++errors;
    expected = expected || d.code == expectedError;
  }
  if (expectedError.empty() ? !check.ok() : (errors != 1 || !expected)) {
    state.SkipWithError(("unexpected result:\n" + check.messages()).c_str());
    return;
  }
  for (auto _ : state) {
    refx::hlsl::CompileResult r = refx::hlsl::compile(source, name, options);
    benchmark::DoNotOptimize(r.tokens.data());
  }
  state.counters["lines"] = lineCount(source);
  state.counters["slots"] = check.instructionSlots;
}

void registerAll() {
  for (const char* program : {"ambient", "diffuse", "specular", "self_shadow", "bump", "point_light"}) {
    for (auto [profile, entry] : {std::pair{"vs_1_1", "VS"}, {"ps_2_0", "PS"}}) {
      refx::hlsl::CompileOptions o;
      o.profile = profile;
      o.entry = entry;
      const std::string file = std::string(program) + ".hlsl";
      benchmark::RegisterBenchmark(fmt::format("BM_CompileSeed/{}/{}", program, profile).c_str(),
                                   [source = readSeed(file), file, o](benchmark::State& st) {
                                     compileBenchmark(st, source, file, o);
                                   })
          ->Unit(benchmark::kMillisecond);
    }
  }
  refx::hlsl::CompileOptions wood;
  wood.profile = "ps_2_0";
  wood.entry = "Wood";
  wood.compatibility = true;
  benchmark::RegisterBenchmark("BM_CompileSeed/wood/ps_2_0", [source = readSeed("wood.fx"), wood](benchmark::State& st) {
    compileBenchmark(st, source, "wood.fx", wood);
  })->Unit(benchmark::kMillisecond);

  refx::hlsl::CompileOptions large;
  large.profile = "vs_3_0";
  benchmark::RegisterBenchmark("BM_CompileLarge/vs_3_0", [source = largeShader(), large](benchmark::State& st) {
    compileBenchmark(st, source, "large.hlsl", large);
  })->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("BM_CompileLarge/vs_3_0_all_terms_over_limit",
                               [source = largeShader(true), large](benchmark::State& st) {
                                 compileBenchmark(st, source, "large.hlsl", large, "X4532");
                               })->Unit(benchmark::kMillisecond);
}

}  // namespace

int main(int argc, char** argv) {
  // --dump-large writes the generated shader to stdout (to look at it or feed it to fxc).
  if (argc > 1 && std::string(argv[1]) == "--dump-large") {
    std::fputs(largeShader().c_str(), stdout);
    return 0;
  }
  registerAll();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
