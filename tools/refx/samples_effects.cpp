// The effect samples: each seed example written as an effect file (data/effects),
// drawn through the effect framework. The technique is the first one valid on the
// device's caps profile (FindNextValidTechnique), and the notes say why each better
// technique was rejected.
#include <fmt/format.h>

#include "effect_scene.h"
#include "refx/core/diagnostics.h"
#include "refx/effect/effect.h"
#include "samples.h"

namespace refx::samples {

namespace {

struct EffectSample {
  std::string file;  // under data/effects
  std::string name, title, source;
  cli::EffectSceneOptions scene;
};

SampleResult renderEffect(Device& dev, const EffectSample& s) {
  SampleResult r;
  std::unique_ptr<effect::Effect> fx;
  try {
    fx = effect::Effect::fromFile(std::string(REFX_DATA_DIR) + "/effects/" + s.file);
  } catch (const Error& e) {
    r.technique = "nothing drawn";
    r.validation = fmt::format("(error: {})", e.what());
    return r;
  }
  for (const effect::EffectDiagnostic& d : fx->diagnostics())
    r.notes.push_back(fmt::format("(error: {})", d.str()));
  cli::EffectScene scene(s.scene);
  for (const std::string& w : scene.prepare(*fx)) r.notes.push_back(w);
  const cli::TechniqueChoice choice = cli::chooseTechnique(*fx, dev.caps(), "");
  for (const std::string& rej : choice.rejected) r.notes.push_back("rejected " + rej);
  if (choice.technique < 0) {
    r.technique = fmt::format("{}: nothing drawn", s.file);
    r.validation = fmt::format("no technique is valid on {}", dev.caps().name);
    return r;
  }
  fx->setTechnique(choice.technique);
  const effect::TechniqueDesc& t = fx->techniqueDesc(choice.technique);
  r.technique = fmt::format("{}: technique {}", s.file, t.name);
  r.validation = fmt::format("valid ({} pass{})", t.passes.size(), t.passes.size() == 1 ? "" : "es");
  scene.draw(*fx, dev);
  return r;
}

const std::vector<EffectSample>& effectList() {
  static const std::vector<EffectSample> list = [] {
    std::vector<EffectSample> v;
    EffectSample brdf{"brdf.fx", "fx-brdf",
                      "BRDF effect file as printed (fx_1_0): its oT2.z misprint leaves the light lookup at the horizon",
                      "seeds/000 \"DirectX 8 Pixel Shaders\" BRDF effect file, verbatim", {}};
    // What the sample application bound: the factor cube maps, a detail texture and
    // the eye position in c10, which the effect reads but does not set.
    brdf.scene.textures = {{"BRDFTexture1", "brdf-p"}, {"BRDFTexture2", "brdf-p-cos"},
                           {"BRDFTexture3", "brdf-q"}, {"ObjectTexture", "brick"}};
    brdf.scene.vsConstants = {{10, Vec4(0, 0, -3, 1)}};
    v.push_back(brdf);
    v.push_back({"brdf_fixed.fx", "fx-brdf-fixed", "BRDF effect with oT1.z and the eye position set by the effect",
                 "seeds/000 BRDF effect file, corrected", {}});
    v.push_back({"racorx6.fx", "fx-racorx6", "RacorX6 as an effect: ps.1.4, then ps.1.1",
                 "seeds/003 Programming Pixel Shaders, RacorX6", {}});
    v.push_back({"racorx7.fx", "fx-racorx7", "RacorX7 as an effect: N.H^16 by multiplies, ps.1.4 then ps.1.1",
                 "seeds/003, RacorX7", {}});
    v.push_back({"racorx8.fx", "fx-racorx8", "RacorX8 as an effect: specular table lookup, ps.1.4 then ps.1.1",
                 "seeds/003, RacorX8", {}});
    v.push_back({"racorx9.fx", "fx-racorx9", "RacorX9 as an effect: diffuse + specular, ps.1.4 then ps.1.1",
                 "seeds/003, RacorX9", {}});
    v.push_back({"paper_diffuse.fx", "fx-paper-diffuse",
                 "Per-pixel diffuse as an effect: ps.1.1, DOT3 (DirectX 7), emboss (DirectX 6)",
                 "seeds/000 per-pixel lighting column and its fallbacks", {}});
    v.push_back({"bump_earth.fx", "fx-bump-earth", "Bump-environment-mapped earth as an effect, with a fallback",
                 "seeds/000 \"DirectX 6 Multi-Texture\" listing", {}});
    return v;
  }();
  return list;
}

}  // namespace

const std::vector<Sample>& effectSamples() {
  static const std::vector<Sample> samples = [] {
    std::vector<Sample> v;
    for (const EffectSample& e : effectList())
      v.push_back({e.name, e.title, e.source, [&e](Device& d) { return renderEffect(d, e); }});
    return v;
  }();
  return samples;
}

}  // namespace refx::samples
