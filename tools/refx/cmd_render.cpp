// `refx render FILE.fx`: loads an effect, chooses its technique for a caps profile
// (the first valid one, best first, or --technique), draws a mesh with it and writes
// a PNG. Says which technique ran and why each better one was rejected. Errors in
// the effect are printed as file:line:col; a good technique still renders, and the
// exit status is 1 when the file had errors.
#include <cstdio>
#include <filesystem>
#include <optional>

#include <fmt/format.h>

#include "commands.h"
#include "effect_scene.h"
#include "refx/core/text.h"
#include "refx/effect/effect.h"
#include "refx/resource/image_io.h"

namespace refx::cli {

namespace {

struct RenderOptions {
  std::string input, output = "render.png", technique, caps = "ref", mesh = "sphere", size = "256x256";
  std::string precision = "exact", outDir;
  std::vector<std::string> sets, textures, vsConsts, psConsts;
  float time = 0;
  std::vector<std::string> prefer;
  std::optional<float> maxCost, distance;
  int frames = 0;
  int threads = 0;
  bool autoTechnique = false;
};

std::pair<std::string, std::string> splitAssignment(const std::string& s, const char* option) {
  const size_t eq = s.find('=');
  if (eq == std::string::npos || eq == 0) fail("{}: expected NAME=VALUE, got '{}'", option, s);
  return {s.substr(0, eq), s.substr(eq + 1)};
}

// "10=0,0,-3,1": register and up to four numbers (the rest 0).
std::pair<int, Vec4> constantAssignment(const std::string& s, const char* option, int maxRegister) {
  auto [reg, value] = splitAssignment(s, option);
  char* end = nullptr;
  const long r = std::strtol(reg.c_str(), &end, 10);
  if (*end || r < 0 || r > maxRegister) fail("{}: '{}' is not a register number 0 to {}", option, reg, maxRegister);
  float v[4] = {0, 0, 0, 0};
  int n = 0;
  std::string_view rest = value;
  while (!rest.empty()) {
    const size_t comma = rest.find(',');
    const std::string part(trim(rest.substr(0, comma)));
    const float f = std::strtof(part.c_str(), &end);
    if (part.empty() || *end || n == 4) fail("{} {}: expected up to four comma-separated numbers", option, s);
    v[n++] = f;
    if (comma == std::string_view::npos) break;
    rest.remove_prefix(comma + 1);
  }
  return {int(r), Vec4(v[0], v[1], v[2], v[3])};
}

int runRender(const RenderOptions& o) {
  int w = 0, h = 0;
  parseSize(o.size, w, h);
  const CapsProfile caps = loadCapsProfile(o.caps);
  EffectSceneOptions so;
  so.mesh = o.mesh;
  so.time = o.time;
  for (const std::string& s : o.sets) so.sets.push_back(splitAssignment(s, "--set"));
  for (const std::string& s : o.textures) so.textures.insert(splitAssignment(s, "--texture"));
  for (const std::string& s : o.vsConsts) so.vsConstants.push_back(constantAssignment(s, "--vs-const", 255));
  for (const std::string& s : o.psConsts) so.psConstants.push_back(constantAssignment(s, "--ps-const", 223));

  auto fx = effect::Effect::fromFile(o.input);
  bool hadErrors = false;
  for (const effect::EffectDiagnostic& d : fx->diagnostics()) {
    std::fprintf(stderr, "%s\n", d.str().c_str());
    hadErrors |= d.error;
  }
  EffectScene scene(so);
  for (const std::string& warning : scene.prepare(*fx))
    std::fprintf(stderr, "%s: warning: %s\n", o.input.c_str(), warning.c_str());

  effect::SelectionPolicy policy;
  policy.preferred = o.prefer;
  policy.maxCost = o.maxCost;
  policy.distance = o.distance;
  const TechniqueChoice choice = chooseTechnique(*fx, caps, o.technique, policy);
  for (const std::string& r : choice.rejected)
    std::printf("rejected on %s: %s\n", caps.name.c_str(), r.c_str());
  if (choice.technique < 0) {
    std::fprintf(stderr, "%s: error: no technique of the effect is valid on %s\n", o.input.c_str(), caps.name.c_str());
    return 1;
  }
  if (!fx->techniqueDesc(choice.technique).brokenReason.empty()) return 1;
  fx->setTechnique(choice.technique);
  std::printf("technique %s (%d pass%s) on %s\n", fx->techniqueDesc(choice.technique).name.c_str(),
              int(fx->techniqueDesc(choice.technique).passes.size()),
              fx->techniqueDesc(choice.technique).passes.size() == 1 ? "" : "es", caps.name.c_str());

  auto devicePtr = makeTargetDevice(caps, o.threads, o.precision, w, h);
  Device& device = *devicePtr;

  if (o.frames <= 0) {
    scene.draw(*fx, device);
    savePNG(*device.renderTarget(), o.output);
    std::printf("wrote %s\n", o.output.c_str());
    return hadErrors ? 1 : 0;
  }
  // An animation: TIME advances by 1/30 s a frame.
  const std::string dir = o.outDir.empty() ? "." : o.outDir;
  std::filesystem::create_directories(dir);
  const bool tty = stderrIsTerminal();
  for (int f = 0; f < o.frames; ++f) {
    scene.setTime(o.time + float(f) / 30.0f);
    scene.draw(*fx, device);
    const std::string path = fmt::format("{}/frame{:04d}.png", dir, f);
    savePNG(*device.renderTarget(), path);
    if (tty) std::fprintf(stderr, "\r[%d/%d] %s", f + 1, o.frames, path.c_str());
  }
  if (tty) std::fprintf(stderr, "\n");
  std::printf("wrote %d frames to %s\n", o.frames, dir.c_str());
  return hadErrors ? 1 : 0;
}

}  // namespace

Action addRenderCommand(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand("render", "Render a mesh with an effect (.fx) file");
  cmd->add_option("file", o->input, "effect file (.fx)")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", o->output, "PNG to write (default render.png)");
  cmd->add_option("--technique", o->technique, "technique name (default: the first valid one)");
  cmd->add_option("--prefer", o->prefer, "techniques to try first, in order (user preference)");
  cmd->add_option("--max-cost", o->maxCost, "skip techniques whose `float Cost` annotation is above this");
  cmd->add_option("--distance", o->distance,
                  "camera distance for level of detail: skip techniques whose MinDistance/MaxDistance exclude it");
  cmd->add_flag("--auto", o->autoTechnique, "choose the first technique valid on --caps (the default)");
  cmd->add_option("--caps", o->caps, "device generation: a caps profile name or file (default ref)");
  cmd->add_option("--mesh", o->mesh, "sphere, teapot, torus, box, a built-in mesh, or a .x/.obj file");
  cmd->add_option("--size", o->size, "render target WxH (default 256x256)");
  cmd->add_option("--set", o->sets, "NAME=VALUE: a parameter's value (numbers comma-separated, or text)");
  cmd->add_option("--texture", o->textures, "NAME=ASSET|FILE: a texture parameter's image or built-in texture");
  cmd->add_option("--vs-const", o->vsConsts, "R=x,y,z,w: a vertex shader constant the application sets after each BeginPass");
  cmd->add_option("--ps-const", o->psConsts, "R=x,y,z,w: a pixel shader constant set after each BeginPass");
  cmd->add_option("--time", o->time, "value of the TIME semantic in seconds (default 0)");
  cmd->add_option("--frames", o->frames, "render N frames (TIME += 1/30 s each) into --out-dir")->check(CLI::Range(1, 100000));
  cmd->add_option("--out-dir", o->outDir, "directory for --frames");
  cmd->add_option("--threads", o->threads, "rendering threads (0: all cores)")->check(CLI::Range(0, 256));
  cmd->add_option("--precision", o->precision, "shader precision model")->check(CLI::IsMember({"exact", "hardware"}));
  return [o] {
    if (o->autoTechnique && !o->technique.empty()) fail("--auto and --technique exclude each other");
    return runRender(*o);
  };
}

}  // namespace refx::cli
