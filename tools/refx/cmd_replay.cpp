// `refx replay SCENE -o OUT`: runs a scene script (reference/scene-script.md) on a
// device with the chosen caps profile and writes the render target.
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "refx/core/diagnostics.h"
#include "refx/pipeline/device.h"
#include "refx/scene/scene_script.h"
#include "refx/resource/image_io.h"

namespace refx::cli {

namespace {

struct ReplayOptions {
  std::string scene;
  std::string output;
  bool rgba = false;
  std::vector<std::string> prints;
  std::string caps = "ref";
  bool info = false;
  int threads = 0;
  bool check = false;
  std::string precision = "exact";
  int target = 0;  // render target written by -o and read by --print
};

struct Pixel {
  int x = 0, y = 0;
};

bool parsePixel(const std::string& s, Pixel& p) {
  size_t comma = s.find(',');
  if (comma == std::string::npos) return false;
  auto num = [](std::string_view t, int& out) {
    auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), out);
    return ec == std::errc() && end == t.data() + t.size() && out >= 0;
  };
  std::string_view v(s);
  return num(v.substr(0, comma), p.x) && num(v.substr(comma + 1), p.y);
}

int usageError(const std::string& msg) {
  std::fprintf(stderr, "refx replay: %s\n", msg.c_str());
  return 2;
}

int replay(const ReplayOptions& o) {
  // Check the command line before doing any work.
  std::string ext = std::filesystem::path(o.output).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (!o.output.empty() && ext != ".png" && ext != ".ppm" && ext != ".pam")
    return usageError("-o " + o.output + ": unknown output type (expected .png, .ppm or .pam)");
  std::vector<Pixel> prints;
  for (const std::string& s : o.prints) {
    Pixel p;
    if (!parsePixel(s, p)) return usageError("--print " + s + ": expected X,Y");
    prints.push_back(p);
  }

  try {
    scene::SceneScript script = scene::loadSceneScript(o.scene);
    for (size_t i = 0; i < prints.size(); ++i)
      if (prints[i].x >= script.width || prints[i].y >= script.height)
        return usageError(fmt::format("--print {}: outside the {}x{} render target",
                                      o.prints[i], script.width, script.height));
    CapsProfile caps = loadCapsProfile(o.caps);
    if (o.info) std::printf("caps profile %s: %s\n", caps.name.c_str(), caps.description.c_str());
    DeviceOptions options;
    options.threads = o.threads;
    options.precision = o.precision == "hardware" ? Precision::Hardware : Precision::Exact;
    Device device(caps, options);
    scene::SceneOutput out = scene::runSceneScript(script, device);
    const Texture* image = out.targets[size_t(o.target)].get();
    if (!image)
      return usageError(fmt::format("--target {}: the scene creates no render target {} (expected "
                                    "`rendertarget {} W H FORMAT`)", o.target, o.target, o.target));
    if (!o.output.empty()) saveImage(*image, o.output, ext == ".pam" || (o.rgba && ext == ".png"));
    for (const Pixel& p : prints) {
      if (p.x >= image->width() || p.y >= image->height())
        return usageError(fmt::format("--print {},{}: outside the {}x{} render target {}", p.x, p.y,
                                      image->width(), image->height(), o.target));
      int c[4];
      scene::readTargetPixel(*image, p.x, p.y, c);
      std::printf("%d,%d: %d %d %d %d\n", p.x, p.y, c[0], c[1], c[2], c[3]);
    }
    if (o.check) {
      std::vector<std::string> mismatches = scene::checkSceneExpectations(script, out);
      for (const std::string& m : mismatches) std::printf("%s\n", m.c_str());
      std::fflush(stdout);
      if (!mismatches.empty()) return 1;
    }
  } catch (const Error& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace

Action addReplayCommand(CLI::App& app) {
  auto o = std::make_shared<ReplayOptions>();
  CLI::App* cmd = app.add_subcommand("replay", "Run a scene script and write the frame");
  cmd->add_option("scene", o->scene, "Scene script (reference/scene-script.md)")->required();
  cmd->add_option("-o,--output", o->output, "Output image: .png, .ppm (P6) or .pam (P7 RGBA)");
  cmd->add_flag("--rgba", o->rgba, "Write PNG with alpha");
  cmd->add_option("--print", o->prints, "Print pixel X,Y as r g b a (0-255); repeatable")
      ->allow_extra_args(false);
  cmd->add_option("--caps", o->caps, "Caps profile name or .caps file (default ref)");
  cmd->add_flag("--info", o->info, "Print the active caps profile");
  cmd->add_option("--threads", o->threads, "Rendering threads (0: all cores)")
      ->check(CLI::Range(0, 1024));
  cmd->add_option("--precision", o->precision,
                  "Shader precision: exact (fp32, version ranges) or hardware (ps_1_x fixed "
                  "point of the era's parts); default exact")
      ->check(CLI::IsMember({"exact", "hardware"}));
  cmd->add_option("--target", o->target,
                  "Render target that -o writes and --print reads: 0 (default) or the N of a "
                  "`rendertarget N W H FORMAT` command")
      ->check(CLI::Range(0, 3));
  cmd->add_flag("--check", o->check,
                "Compare the `# expect` pixels of the script; exit 1 on any mismatch");
  return [o] { return replay(*o); };
}

}  // namespace refx::cli
