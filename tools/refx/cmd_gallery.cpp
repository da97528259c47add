// `refx gallery`: renders every built-in sample to PNG and writes index.html.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "commands.h"
#include "refx/core/diagnostics.h"
#include "refx/resource/image_io.h"
#include "samples.h"

namespace refx::cli {

namespace {

struct GalleryOptions {
  std::string out = "gallery";
  std::string size = "256x256";
  std::string caps = "ref";
  int threads = 0;
  std::string precision = "exact";
};

std::string htmlEscape(const std::string& s) {
  std::string r;
  for (char c : s) {
    switch (c) {
      case '<': r += "&lt;"; break;
      case '>': r += "&gt;"; break;
      case '&': r += "&amp;"; break;
      case '"': r += "&quot;"; break;
      default: r += c;
    }
  }
  return r;
}

int runGallery(const GalleryOptions& o) {
  int w = 0, h = 0;
  parseSize(o.size, w, h);
  const CapsProfile caps = loadCapsProfile(o.caps);
  std::filesystem::create_directories(o.out);
  const auto& samples = samples::allSamples();
  const bool tty = stderrIsTerminal();
  std::string cards;
  int index = 0;
  for (const auto& s : samples) {
    ++index;
    if (tty) std::fprintf(stderr, "\r[%d/%zu] %-40s", index, samples.size(), s.name.c_str());
    auto devPtr = makeTargetDevice(caps, o.threads, o.precision, w, h);
    Device& dev = *devPtr;
    dev.clear(d3d::CLEAR_TARGET | d3d::CLEAR_ZBUFFER | d3d::CLEAR_STENCIL, 0xff000000, 1.0f, 0);
    const auto t0 = std::chrono::steady_clock::now();
    samples::SampleResult r = s.render(dev);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    const std::string png = s.name + ".png";
    savePNG(*dev.renderTarget(), (std::filesystem::path(o.out) / png).string());
    std::string notes;
    for (const auto& n : r.notes) notes += "<li>" + htmlEscape(n) + "</li>";
    cards += fmt::format(
        "<figure><img src=\"{}\" width=\"{}\" height=\"{}\" alt=\"{}\">"
        "<figcaption><b>{}</b><br>{}<br><i>source:</i> {}<br><i>profile:</i> {}<br>"
        "<i>precision:</i> {}<br><i>technique:</i> {}<br><i>validation:</i> {}<br><i>render:</i> {:.1f} ms<ul>{}</ul>"
        "</figcaption></figure>\n",
        png, w, h, htmlEscape(s.name), htmlEscape(s.name), htmlEscape(s.title), htmlEscape(s.source),
        htmlEscape(caps.name), o.precision, htmlEscape(r.technique), htmlEscape(r.validation), ms, notes);
    if (!tty) std::printf("%s: %s (%s)\n", png.c_str(), r.technique.c_str(), r.validation.c_str());
  }
  if (tty) std::fprintf(stderr, "\r%-60s\r", "");
  std::ofstream html(std::filesystem::path(o.out) / "index.html");
  html << "<!doctype html><html><head><meta charset=\"utf-8\"><title>refx gallery — " << htmlEscape(caps.name)
       << "</title><style>body{font-family:sans-serif;background:#222;color:#ddd}"
          "figure{display:inline-block;vertical-align:top;width:"
       << std::max(w, 256) + 20
       << "px;margin:8px;background:#333;padding:8px}figcaption{font-size:12px}"
          "img{image-rendering:pixelated;background:#000}</style></head><body>\n"
       << "<h1>refx gallery</h1><p>caps profile <b>" << htmlEscape(caps.name) << "</b>: "
       << htmlEscape(caps.description) << "</p>\n"
       << cards << "</body></html>\n";
  if (!html) fail("{}: cannot write index.html", o.out);
  std::printf("wrote %zu samples and index.html to %s\n", samples.size(), o.out.c_str());
  return 0;
}

}  // namespace

Action addGalleryCommand(CLI::App& app) {
  auto o = std::make_shared<GalleryOptions>();
  CLI::App* cmd = app.add_subcommand("gallery", "render every built-in sample to PNG and write index.html");
  cmd->add_option("--out", o->out, "output directory")->capture_default_str();
  cmd->add_option("--size", o->size, "image size WxH")->capture_default_str();
  cmd->add_option("--caps", o->caps, "caps profile (see `refx caps`)")->capture_default_str();
  cmd->add_option("--threads", o->threads, "render threads (0 = all cores)")->check(CLI::Range(0, 256));
  cmd->add_option("--precision", o->precision, "shader precision model: exact, or hardware (ps.1.x fixed point)")
      ->check(CLI::IsMember({"exact", "hardware"}))
      ->capture_default_str();
  return [o] { return runGallery(*o); };
}

}  // namespace refx::cli
