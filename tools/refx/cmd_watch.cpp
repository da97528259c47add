// `refx watch FILE.fx -o out.png`: renders the effect, then re-renders whenever the
// file or one of its includes changes. Meshes and built-in textures stay loaded; an
// edit that breaks the effect prints its errors and keeps the last good image.
// `--measure N` is the edit-to-image benchmark: it edits the file N times itself and
// reports how long each new image took (stat, reload, validation, render, PNG).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <thread>

#include <fmt/format.h>

#include "commands.h"
#include "effect_scene.h"
#include "refx/effect/effect.h"
#include "refx/resource/image_io.h"

namespace refx::cli {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
constexpr auto kPollInterval = std::chrono::milliseconds(5);

struct WatchOptions {
  std::string input, output = "watch.png", technique, caps = "ref", mesh = "sphere", size = "512x512";
  int maxRenders = 0;  // stop after this many renders (0: run until interrupted)
  int measure = 0;
  int threads = 0;
};

struct Stamp {
  std::string path;
  fs::file_time_type time;
  uintmax_t size;
  bool operator==(const Stamp&) const = default;
};

Stamp stampOf(const std::string& path) {
  std::error_code ec;
  Stamp s{path, fs::last_write_time(path, ec), 0};
  s.size = fs::file_size(path, ec);
  if (ec) s.size = uintmax_t(-1);
  return s;
}

class Watcher {
 public:
  Watcher(const WatchOptions& o, const CapsProfile& caps, int w, int h)
      : o_(o), caps_(caps), scene_([&] {
          EffectSceneOptions so;
          so.mesh = o.mesh;
          return so;
        }()) {
    device_ = makeTargetDevice(caps, o.threads, "exact", w, h);
  }

  // Loads and draws; returns false when the edit is broken (the last image stays).
  bool render() {
    files_ = {o_.input};
    try {
      auto fx = effect::Effect::fromFile(o_.input);
      files_ = fx->sourceFiles();
      stamps_ = stamps();
      for (const effect::EffectDiagnostic& d : fx->diagnostics()) std::fprintf(stderr, "%s\n", d.str().c_str());
      for (const std::string& w : scene_.prepare(*fx)) std::fprintf(stderr, "%s: warning: %s\n", o_.input.c_str(), w.c_str());
      const TechniqueChoice choice = chooseTechnique(*fx, caps_, o_.technique);
      if (choice.technique < 0 || !fx->techniqueDesc(choice.technique).brokenReason.empty()) {
        for (const std::string& r : choice.rejected) std::fprintf(stderr, "rejected: %s\n", r.c_str());
        std::fprintf(stderr, "%s: error: no technique to draw; keeping the last image\n", o_.input.c_str());
        return false;
      }
      fx->setTechnique(choice.technique);
      scene_.draw(*fx, *device_);
      savePNG(*device_->renderTarget(), o_.output);
      technique_ = fx->techniqueDesc(choice.technique).name;
      return true;
    } catch (const Error& e) {
      stamps_ = stamps();
      std::fprintf(stderr, "%s\n", e.what());
      std::fprintf(stderr, "%s: keeping the last image\n", o_.input.c_str());
      return false;
    }
  }

  bool changed() const { return stamps() != stamps_; }
  const std::string& technique() const { return technique_; }

 private:
  std::vector<Stamp> stamps() const {
    std::vector<Stamp> s;
    for (const std::string& f : files_) s.push_back(stampOf(f));
    return s;
  }

  const WatchOptions& o_;
  const CapsProfile& caps_;
  EffectScene scene_;
  std::unique_ptr<Device> device_;
  std::vector<std::string> files_;
  std::vector<Stamp> stamps_;
  std::string technique_;
};

double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

int runMeasure(Watcher& watcher, const WatchOptions& o) {
  std::string original;
  {
    std::ifstream in(o.input, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    original = s.str();
  }
  std::vector<double> latencies;
  const bool tty = stderrIsTerminal();
  for (int i = 0; i < o.measure; ++i) {
    // An edit a person makes: a changed comment line at the end of the file.
    {
      std::ofstream out(o.input, std::ios::binary | std::ios::trunc);
      out << original << fmt::format("\n// edit {}\n", i);
    }
    const auto t0 = Clock::now();
    while (!watcher.changed()) std::this_thread::sleep_for(std::chrono::microseconds(200));
    watcher.render();
    latencies.push_back(msSince(t0));
    if (tty) std::fprintf(stderr, "\r[%d/%d] %.1f ms", i + 1, o.measure, latencies.back());
  }
  if (tty) std::fprintf(stderr, "\n");
  std::sort(latencies.begin(), latencies.end());
  const double median = latencies[latencies.size() / 2];
  std::printf("%s: edit -> new image at %s on %s, %d edits: median %.1f ms, min %.1f ms, max %.1f ms "
              "(plus up to %lld ms polling)\n",
              o.input.c_str(), o.size.c_str(), o.caps.c_str(), o.measure, median, latencies.front(), latencies.back(),
              static_cast<long long>(kPollInterval.count()));
  return 0;
}

int runWatch(const WatchOptions& options) {
  WatchOptions o = options;
  // The benchmark edits a copy beside the file (its includes and textures resolve the same).
  std::optional<fs::path> copy;
  if (o.measure > 0) {
    const fs::path src(o.input);
    copy = src.parent_path() / (".refx-measure-" + src.filename().string());
    fs::copy_file(src, *copy, fs::copy_options::overwrite_existing);
    o.input = copy->string();
  }
  struct RemoveCopy {
    std::optional<fs::path>& p;
    ~RemoveCopy() {
      std::error_code ec;
      if (p) fs::remove(*p, ec);
    }
  } removeCopy{copy};
  int w = 0, h = 0;
  parseSize(o.size, w, h);
  const CapsProfile caps = loadCapsProfile(o.caps);
  Watcher watcher(o, caps, w, h);
  auto t0 = Clock::now();
  bool ok = watcher.render();
  if (o.measure > 0) {
    if (!ok) return 1;
    return runMeasure(watcher, o);
  }
  int renders = 1;
  if (ok) std::printf("technique %s: wrote %s (%.1f ms)\n", watcher.technique().c_str(), o.output.c_str(), msSince(t0));
  std::fflush(stdout);
  while (o.maxRenders == 0 || renders < o.maxRenders) {
    std::this_thread::sleep_for(kPollInterval);
    if (!watcher.changed()) continue;
    t0 = Clock::now();
    ++renders;
    if (watcher.render())
      std::printf("technique %s: wrote %s (%.1f ms)\n", watcher.technique().c_str(), o.output.c_str(), msSince(t0));
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace

Action addWatchCommand(CLI::App& app) {
  auto o = std::make_shared<WatchOptions>();
  CLI::App* cmd = app.add_subcommand("watch", "Re-render an effect whenever it (or an included file) changes");
  cmd->add_option("file", o->input, "effect file (.fx)")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o->output, "PNG to write (default watch.png)");
  cmd->add_option("--technique", o->technique, "technique name (default: the first valid one)");
  cmd->add_option("--caps", o->caps, "caps profile (default ref)");
  cmd->add_option("--mesh", o->mesh, "sphere, teapot, torus, box, a built-in mesh, or a .x/.obj file");
  cmd->add_option("--size", o->size, "render target WxH (default 512x512)");
  cmd->add_option("--renders", o->maxRenders, "stop after N renders (default: run until interrupted)")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--measure", o->measure, "benchmark: edit the file N times and report edit -> image latency")
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--threads", o->threads, "rendering threads (0: all cores)")->check(CLI::Range(0, 256));
  return [o] { return runWatch(*o); };
}

}  // namespace refx::cli
