#include <cstdio>
#include <exception>
#include <unistd.h>

#include "commands.h"
#include "refx/core/diagnostics.h"

namespace refx::cli {
bool stderrIsTerminal() { return isatty(2) != 0; }

std::unique_ptr<Device> makeTargetDevice(const CapsProfile& caps, int threads, const std::string& precision,
                                         int w, int h) {
  DeviceOptions opt;
  opt.threads = threads;
  opt.precision = precision == "hardware" ? Precision::Hardware : Precision::Exact;
  auto dev = std::make_unique<Device>(caps, opt);
  dev->setRenderTarget(Texture::create2D(Format::A8R8G8B8, w, h));
  dev->setDepthStencilSurface(std::make_shared<DepthStencilSurface>(w, h));
  return dev;
}

void parseSize(const std::string& s, int& w, int& h) {
  if (std::sscanf(s.c_str(), "%dx%d", &w, &h) != 2 || w < 1 || h < 1 || w > 8192 || h > 8192)
    refx::fail("--size: expected WxH with 1 <= W,H <= 8192, got '{}'", s);
}
}  // namespace refx::cli

int main(int argc, char** argv) {
  using namespace refx::cli;
  CLI::App app{"refx: a software Direct3D 8/9 shading system"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "refx 0.1");
  std::vector<std::pair<CLI::App*, Action>> commands;
  for (Register reg : {addCapsCommand, addReplayCommand, addGalleryCommand, addBenchCommand,
                       addAssetCommand, addDisasmCommand, addAsmCommand,
                       addValidateCommand, addRenderCommand, addWatchCommand, addFxcCommand,
                       addTestCommand}) {
    size_t before = app.get_subcommands({}).size();
    Action action = reg(app);
    auto subs = app.get_subcommands({});
    if (subs.size() > before) commands.emplace_back(subs.back(), std::move(action));
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? 0 : 2;  // usage errors exit 2
  }
  try {
    for (auto& [sub, action] : commands)
      if (sub->parsed()) return action();
  } catch (const refx::Error& e) {
    // Located errors already read "file:line: error: ..." or "file:line: error A2001: ...";
    // others get the prefix here.
    const std::string what = e.what();
    const size_t coded = what.find(" error ");
    const bool located = what.find("error: ") != std::string::npos ||
                         (coded != std::string::npos && what.compare(coded + 12, 2, ": ") == 0);
    std::fprintf(stderr, "refx: %s%s\n", located ? "" : "error: ", what.c_str());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "refx: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
