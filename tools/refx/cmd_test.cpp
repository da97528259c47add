// `refx test FILE.shader_test…`: runs files of vkd3d's shader test format on a D3D9
// device (docs/shader_test_format.md). One line per file, a summary line last; exit
// status 1 when any file failed.
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "refx/core/diagnostics.h"
#include "refx/scene/shader_test.h"

namespace refx::cli {

namespace {

struct TestOptions {
  std::vector<std::string> files;
  int threads = 0;
  bool verbose = false;
};

int runTests(const TestOptions& o) {
  int passed = 0, failed = 0, skipped = 0;
  for (const std::string& path : o.files) {
    scene::ShaderTestFile file;
    try {
      file = scene::loadShaderTest(path);
    } catch (const Error& e) {
      std::printf("%s\n", e.what());  // "path:line: error: …"
      ++failed;
      continue;
    }
    scene::ShaderTestOptions options;
    options.threads = o.threads;
    const scene::ShaderTestResult r = scene::runShaderTest(file, options);
    switch (r.status) {
      case scene::ShaderTestResult::Status::Passed:
        std::printf("%s: passed\n", path.c_str());
        ++passed;
        break;
      case scene::ShaderTestResult::Status::Skipped:
        std::printf("%s: skipped (%s)\n", path.c_str(), r.skipReason.c_str());
        ++skipped;
        break;
      case scene::ShaderTestResult::Status::Failed: {
        const scene::ShaderTestFailure& first = r.failures.front();
        std::string more;
        if (r.failures.size() > 1 && !o.verbose) more = fmt::format(" (and {} more)", r.failures.size() - 1);
        std::printf("%s: failed at line %d: %s%s\n", path.c_str(), first.line, first.message.c_str(), more.c_str());
        if (o.verbose)
          for (size_t i = 1; i < r.failures.size(); ++i)
            std::printf("  line %d: %s\n", r.failures[i].line, r.failures[i].message.c_str());
        ++failed;
        break;
      }
    }
    std::fflush(stdout);
  }
  std::printf("%d passed, %d failed, %d skipped\n", passed, failed, skipped);
  return failed ? 1 : 0;
}

}  // namespace

Action addTestCommand(CLI::App& app) {
  auto o = std::make_shared<TestOptions>();
  CLI::App* cmd = app.add_subcommand("test", "Run .shader_test files (vkd3d's test format) on a D3D9 device");
  cmd->add_option("files", o->files, "Files to run")->required()->check(CLI::ExistingFile);
  cmd->add_option("--threads", o->threads, "Rendering threads (0: all cores)")->check(CLI::Range(0, 1024));
  cmd->add_flag("-v,--verbose", o->verbose, "List every failure of a file, not only the first");
  return [o] { return runTests(*o); };
}

}  // namespace refx::cli
