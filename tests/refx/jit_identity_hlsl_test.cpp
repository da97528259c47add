// Every HLSL sample (data/hlsl) compiled by refx's HLSL compiler for its profiles and
// the later ones, lowered, and run on native code against the interpreter, bit for bit.
#include "exec/jit_identity.h"

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "refx/exec/lower.h"
#include "refx/hlsl/compiler.h"

namespace {

using namespace jit_identity;
namespace fs = std::filesystem;

TEST(JitIdentityHlsl, EverySampleEntryPointAndProfile) {
  const auto isas = availableIsas();
  if (isas.empty()) GTEST_SKIP() << "no AVX2 on this CPU";
  const fs::path dir = fs::path(REFX_DATA_DIR) / "hlsl";
  int programs = 0, compiled = 0, interpreted = 0;
  CompileTimes times;
  uint32_t seed = 1;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() != ".hlsl") continue;
    std::ifstream f(e.path());
    std::stringstream text;
    text << f.rdbuf();
    // "// Compile: refx fxc /T vs_1_1 /E VS file.hlsl; refx fxc /T ps_2_0 /E PS file.hlsl"
    const std::string source = text.str();
    const std::regex command(R"(/T (vs|ps)_\S+ /E (\w+))");
    for (auto m = std::sregex_iterator(source.begin(), source.end(), command); m != std::sregex_iterator(); ++m) {
      const bool vertex = (*m)[1] == "vs";
      const std::vector<std::string> profiles =
          vertex ? std::vector<std::string>{"vs_1_1", "vs_2_0", "vs_3_0"}
                 : std::vector<std::string>{"ps_2_0", "ps_2_x", "ps_3_0"};
      for (const std::string& profile : profiles)
        for (bool optimize : {true, false}) {
          hlsl::CompileOptions options;
          options.profile = profile;
          options.entry = (*m)[2];
          options.optimize = optimize;
          const hlsl::CompileResult r = hlsl::compile(source, e.path().filename().string(), options);
          SCOPED_TRACE(e.path().filename().string() + " " + options.entry + " " + profile +
                       (optimize ? "" : " /Od"));
          ASSERT_TRUE(r.ok()) << r.messages();
          const exec::LoweredShader low = exec::lowerShader(r.shader);
          ++programs;
          for (auto isa : isas) {
            const Outcome o = compare(low.program, isa, seed++, {-1.5f, 1.5f}, exec::kPixelInputRegisters);
            EXPECT_EQ(o.mismatch, "") << isaName(isa) << "\n" << exec::listProgram(low.program);
            (o.backend == "interpreter" ? interpreted : compiled)++;
            times.add(o);
          }
        }
    }
  }
  std::printf("HLSL samples: %d programs; %d compiled, %d left to the interpreter\n", programs, compiled,
              interpreted);
  std::printf("HLSL samples: %s\n", times.summary().c_str());
  EXPECT_GE(programs, 60);
}

}  // namespace
