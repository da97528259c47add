// Every shader of the samples (data/shaders) that assembles also lowers.
#include <filesystem>
#include <fstream>
#include <sstream>

#include "shader_probe.h"

using namespace probe;

namespace {

TEST(LowerSeeds, EveryAssembledSampleShaderLowers) {
  const std::filesystem::path dir = std::filesystem::path(REFX_DATA_DIR) / "shaders";
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << "no " << dir;
  int count = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const auto ext = e.path().extension();
    if (ext != ".vsh" && ext != ".psh") continue;
    std::ifstream f(e.path());
    std::stringstream text;
    text << f.rdbuf();
    sh::Shader s;
    try {
      s = sh::assemble(text.str(), e.path().filename().string());
    } catch (const refx::Error&) {
      continue;  // the misprinted originals are the assembler's and validator's business
    }
    SCOPED_TRACE(e.path().filename().string());
    try {
      ShaderRun r(s);
      r.execute();
      ++count;
    } catch (const refx::Error& err) {
      ADD_FAILURE() << err.what();
    }
  }
  EXPECT_GT(count, 20);
}

}  // namespace
