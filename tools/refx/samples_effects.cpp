// The effect samples: each seed example written as an effect file (data/effects),
// drawn through the effect framework. The technique is the first one valid on the
// device's caps profile (FindNextValidTechnique), and the notes say why each better
// technique was rejected. A sample that shows one of an effect's lesser techniques
// (RacorX11 inside the point light effect, the multiply-based specular ...) prefers it:
// it runs where it is valid, and elsewhere the effect falls back as it always does.
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
  std::string technique = {};  // tried first when valid on the profile; "" = the effect's order
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
  effect::SelectionPolicy policy;
  if (!s.technique.empty()) policy.preferred = {s.technique};
  const cli::TechniqueChoice choice = cli::chooseTechnique(*fx, dev.caps(), "", policy);
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
    // RacorX10: two ps.1.1 passes; RacorX11-14: one effect, the samples prefer each
    // article's technique (each falls back to the lower versions where it cannot run).
    v.push_back({"racorx10.fx", "fx-racorx10",
                 "RacorX10: point light, attenuation pass then illumination map (ZERO / SRCCOLOR)",
                 "seeds/002 Advanced Shader Programming, RacorX10", {}});
    const char* const kPointLight = "racorx_point_light.fx";
    v.push_back({kPointLight, "fx-racorx11", "RacorX11: three ps.1.1 passes with the normalization cube map",
                 "seeds/002, RacorX11", {}, "PS11"});
    v.push_back({kPointLight, "fx-racorx12", "RacorX12: ps.1.2 texdp3tex with the 2048x1 table, two passes",
                 "seeds/002, RacorX12", {}, "PS12"});
    v.push_back({kPointLight, "fx-racorx13", "RacorX13: ps.1.4, one pass, six stages", "seeds/002, RacorX13", {},
                 "PS14_13"});
    v.push_back({kPointLight, "fx-racorx14a", "RacorX14: the point light texture fetched twice (five stages)",
                 "seeds/002, RacorX14, first shader", {}, "PS14_14a"});
    v.push_back({kPointLight, "fx-racorx14b", "RacorX14: the half vector normalized by a cube map",
                 "seeds/002, RacorX14, second shader", {}, "PS14_14b"});
    v.push_back({kPointLight, "fx-racorx14",
                 "RacorX14: one cube map stage fetched twice (the point light effect's best)",
                 "seeds/002, RacorX14, final shader", {}});
    v.push_back({"paper_diffuse.fx", "fx-paper-diffuse",
                 "Per-pixel diffuse as an effect: ps.1.1, DOT3 (DirectX 7), emboss (DirectX 6)",
                 "seeds/000 per-pixel lighting column and its fallbacks", {}});
    v.push_back({"paper_diffuse.fx", "fx-paper-emboss", "Emboss vertex shader with the fixed-function emboss stages",
                 "seeds/000 per-pixel lighting column: emboss vertex shader", {}, "Emboss_VS"});
    v.push_back({"paper_specular.fx", "fx-paper-specular",
                 "Per-pixel specular: texdp3tex into a 1D power-100 table (ps.1.2)",
                 "seeds/000 per-pixel lighting column: table-based specular, with seeds/002's texdp3tex", {}});
    v.push_back({"paper_specular.fx", "fx-paper-specular-table",
                 "Per-pixel specular from a 3x2 table lookup (power 100)",
                 "seeds/000 per-pixel lighting column: table-based specular", {}, "PS11"});
    v.push_back({"paper_specular.fx", "fx-paper-specular-mul", "Per-pixel specular, exponent by multiplies (N.H^16)",
                 "seeds/000 per-pixel lighting column: multiply-based specular", {}, "PS11Mul"});
    // Hemisphere lighting: per pixel on the globe, per vertex on the teapot whose vertices
    // carry their occlusion.
    const char* const kHemisphere = "seeds/000 custom per-pixel lighting: hemisphere lighting";
    v.push_back({"hemisphere.fx", "fx-hemisphere",
                 "Hemisphere lighting per pixel: sky/ground x open sky + a directional light (3-term + sun)",
                 kHemisphere, {}});
    v.push_back({"hemisphere.fx", "fx-hemisphere-pixel", "Hemisphere lighting per pixel: the ps.1.1 fragment (2-term)",
                 kHemisphere, {}, "Pixel"});
    cli::EffectSceneOptions teapot;
    teapot.mesh = "teapot-occlusion";
    v.push_back({"hemisphere.fx", "fx-hemisphere-vertex",
                 "Hemisphere lighting per vertex: sky/ground lerp with occlusion (3-term)", kHemisphere, teapot,
                 "Vertex"});
    v.push_back({"hemisphere.fx", "fx-hemisphere-vertex-2term",
                 "Hemisphere lighting per vertex without occlusion (2-term)", kHemisphere, teapot, "Vertex2Term"});
    v.push_back({"hemisphere.fx", "fx-hemisphere-vertex-sun",
                 "Hemisphere lighting per vertex with occlusion and a directional light", kHemisphere, teapot,
                 "VertexSun"});
    v.push_back({"hemisphere.fx", "fx-hemisphere-integral",
                 "Hemisphere lighting on DirectX 7: the integral in a cube map looked up with the normal", kHemisphere,
                 {}, "Integral"});
    v.push_back({"bump_earth.fx", "fx-bump-earth", "Bump-environment-mapped earth as an effect, with a fallback",
                 "seeds/000 \"DirectX 6 Multi-Texture\" listing", {}});
    // "Implementing Lighting Models With HLSL": the six programs, compiled by refx from
    // data/hlsl, on a lit sphere (the bump-mapped ones on the earth with its normal map).
    const char* const kArticle = "seeds/001 \"Implementing Lighting Models With HLSL\"";
    v.push_back({"hlsl_ambient.fx", "fx-hlsl-ambient", "HLSL ambient lighting (vs_1_1, ps_2_0)", kArticle, {}});
    v.push_back({"hlsl_diffuse.fx", "fx-hlsl-diffuse", "HLSL diffuse lighting: ambient + N.L", kArticle, {}});
    v.push_back({"hlsl_specular.fx", "fx-hlsl-specular", "HLSL Phong specular: (R.V)^8 per pixel", kArticle, {}});
    v.push_back({"hlsl_self_shadow.fx", "fx-hlsl-self-shadow", "HLSL specular with the self-shadowing term",
                 kArticle, {}});
    cli::EffectSceneOptions earth;
    earth.textures = {{"ColorMapSampler", "earth-color"}, {"BumpMapSampler", "earth-normal"}};
    v.push_back({"hlsl_bump.fx", "fx-hlsl-bump", "HLSL bump mapping with a gloss map on the earth", kArticle, earth});
    v.push_back({"hlsl_point_light.fx", "fx-hlsl-point-light",
                 "HLSL bump-mapped point light with attenuation, the light just off the surface", kArticle, earth});
    // The wood shader on a box: the noise volume, world-space L and I, white light, and
    // the turbulence down to 0.1 so the rings show through the noise.
    cli::EffectSceneOptions wood;
    wood.mesh = "box";
    wood.textures = {{"noise", "wood-volume"}};
    wood.sets = {{"L", "-0.57,0.48,-0.67"}, {"I", "0,0,1"}, {"ambient_color", "1,1,1"},
                 {"diffuse_color", "1,1,1"}, {"specular_color", "1,1,1"}, {"turbulence", "0.1"}};
    v.push_back({"wood.fx", "fx-wood", "Renderman wood (the effect paper's HLSL, pre-release dialect) on a box",
                 "seeds/000 DirectX 9 effect white paper, wood shader", wood});
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
