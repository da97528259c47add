// The shader samples of the seeds: RacorX6-RacorX14 (seeds/003, seeds/002), the
// per-pixel lighting column, the hemisphere lighting model and the BRDF effect
// (seeds/000). The shader text is data/shaders/ (the seeds' listings); this file sets
// the constants, textures and states the texts describe, and picks the pixel shader
// version the way the articles' ConfirmDevice does: the best version the caps
// profile's PixelShaderVersion allows, falling back to the lower versions the texts
// give (RacorX13/14 -> RacorX12's ps.1.2 passes -> RacorX11's ps.1.1 passes).
#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "racorx_scene.h"
#include "refx/d3dx/brdf.h"
#include "refx/d3dx/lighting_maps.h"
#include "refx/d3dx/sample_assets.h"
#include "refx/d3dx/teapot.h"
#include "refx/d3dx/texture_fill.h"
#include "samples.h"

namespace refx::samples {

namespace {

using namespace d3d;
using namespace racorx;
namespace fvf = d3dx::fvf;
using SampleFn = std::function<SampleResult(Device&)>;

constexpr float kPi = 3.14159265358979f;

// Direction toward the light (world space) of the directional-light samples.
const Vec3 kTowardLight = normalize(Vec3{-0.6f, 0.5f, -0.7f});
// The globe's orientation: the same view of the earth as the fixed-function samples.
Matrix globeWorld() { return matrixRotationY(2.2f) * matrixRotationX(0.35f); }

// RacorX10's illumination map (diffspec.dds), indexed by u = N.L and v = N.H:
// RGB = the diffuse value u, A = the specular value v^16.
TexturePtr illuminationMap(int size) {
  auto t = Texture::create2D(Format::A8R8G8B8, size, size, 1);
  d3dx::fillTexture(*t, [](Vec2 p, Vec2) { return Vec4(p.x, p.x, p.x, std::pow(p.y, 16.0f)); });
  return t;
}

struct Assets {
  TexturePtr color = d3dx::earthColorMap(512, 256, 0);   // alpha = gloss (water)
  TexturePtr height = d3dx::earthHeightMap(512, 256, 0);
  TexturePtr normal = d3dx::earthNormalMap(512, 256, 0);
  TexturePtr normalSpecular = d3dx::earthNormalMapSpecularAlpha(normal->width(), normal->height(), 16.0f, 0);
  TexturePtr table16 = racorx8Table();                                       // RacorX8
  TexturePtr table100 = d3dx::specularPowerMap(256, 256, 100, d3dx::SpecularAlpha::U);  // the column's
  TexturePtr table2048 = d3dx::specularPowerTable(2048, 16, 1);              // RacorX12
  TexturePtr illum = illuminationMap(256);
  TexturePtr cube = d3dx::createNormalizationCubeMap(64);
  TexturePtr atten2D = d3dx::attenuationMap2D(256);
  TexturePtr atten1D = d3dx::attenuationMap1D(256);
  TexturePtr brick = d3dx::brick(256, 0);
  d3dx::Mesh sphere = globe();
};

const Assets& assets() {
  static const Assets a;
  return a;
}

// The color map in stage 0 and a normal map in stage 1, both filtered with mips: the
// texture set most of the bump-mapping samples share.
void bindColorAndNormal(Device& dev, const Assets& a, const TexturePtr& normal) {
  dev.setTexture(0, a.color);
  dev.setTexture(1, normal);
  linearSampling(dev, 0, true);
  linearSampling(dev, 1, true);
}

// bindColorAndNormal with the plain normal map, then the globe drawn once.
void drawColorNormalGlobe(Device& dev, const Assets& a) {
  bindColorAndNormal(dev, a, a.normal);
  bindMesh(dev, a.sphere);
  drawGlobe(dev, a.sphere);
}

std::string describe(const ValidationResult& v) {
  return v.ok ? fmt::format("valid ({} pass{})", v.passes, v.passes == 1 ? "" : "es") : v.reason;
}

std::string versionName(const CapsProfile& caps) {
  if (caps.psMajor() == 0) return fmt::format("none ({})", caps.name);
  return fmt::format("{}.{} ({})", caps.psMajor(), caps.psMinor(), caps.name);
}

// One version of a sample: its pixel shader version and what it is.
struct Version {
  int major, minor;
  std::string label;  // "ps.1.4: racorx6_ps14.psh"
};

// ConfirmDevice: the first of `versions` (best first) the profile supports; the
// rejected ones are listed in the notes as the articles report them.
std::optional<size_t> confirmDevice(const CapsProfile& caps, const std::vector<Version>& versions,
                                    SampleResult& r) {
  for (size_t i = 0; i < versions.size(); ++i) {
    const Version& v = versions[i];
    if (supportsPixelShader(caps, v.major, v.minor)) {
      r.technique = v.label;
      r.notes.push_back(fmt::format("ConfirmDevice: PixelShaderVersion {} >= {}.{}: {}", versionName(caps), v.major,
                                    v.minor, v.label));
      for (size_t j = i + 1; j < versions.size(); ++j)
        r.notes.push_back(fmt::format("also supported: {}", versions[j].label));
      return i;
    }
    r.notes.push_back(fmt::format("rejected {}: PixelShaderVersion {} < {}.{} (\"ps.{}.{} Not Supported\")", v.label,
                                  versionName(caps), v.major, v.minor, v.major, v.minor));
  }
  r.technique = "nothing drawn: no pixel shader version of this sample runs on " + caps.name;
  r.validation = fmt::format("ConfirmDevice: PixelShaderVersion {} < {}.{}", versionName(caps), versions.back().major,
                             versions.back().minor);
  return std::nullopt;
}

// A sample body runs inside this: assembly or creation errors become the validation
// line instead of ending the gallery.
SampleResult guarded(Device& dev, const std::function<void(Device&, SampleResult&)>& body) {
  SampleResult r;
  try {
    body(dev, r);
    if (r.validation.empty()) r.validation = "ValidateDevice: " + describe(dev.validate());
  } catch (const Error& e) {
    r.validation = std::string("error: ") + e.what();
  }
  return r;
}

// Loads `file`, and when it does not assemble or validate as printed, `fixed` in its
// place with the error in the notes (the misprinted listings of the seeds).
PixelShaderPtr loadPixelShaderOrFixed(const Device& dev, const std::string& file, const std::string& fixed,
                                      SampleResult& r) {
  try {
    return loadPixelShader(dev, file);
  } catch (const Error& e) {
    r.notes.push_back(fmt::format("{} as printed: {}; using {}", file, e.what(), fixed));
    return loadPixelShader(dev, fixed);
  }
}

void setVec(Device& dev, uint32_t reg, Vec4 v) { setVector(dev, reg, v); }
void setPSVec(Device& dev, uint32_t reg, Vec4 v) { dev.setPixelShaderConstantF(reg, &v.x, 1); }

View globeScene(const Device& dev) {
  View v = globeView(dev, globeWorld());
  v.lightDirection = -kTowardLight;
  return v;
}

// ---------------------------------------------------------------- RacorX6-9
void racorx6(Device& dev, SampleResult& r) {
  const Assets& a = assets();
  const auto pick = confirmDevice(dev.caps(),
                                  {{1, 4, "ps.1.4: racorx6_ps14.psh (diffDot314.psh), vs racorx6.vsh"},
                                   {1, 1, "ps.1.1: racorx6_ps11.psh (diffDot3.psh), vs racorx6.vsh"}},
                                  r);
  if (!pick) return;
  dev.setRenderState(RS_ZENABLE, ZB_TRUE);
  dev.setVertexShader(loadVertexShader(dev, "racorx6.vsh"));
  dev.setPixelShader(loadPixelShader(dev, *pick == 0 ? "racorx6_ps14.psh" : "racorx6_ps11.psh"));
  setConstants(dev, globeScene(dev));
  drawColorNormalGlobe(dev, a);
}

SpecularTextures earthSpecular() {
  const Assets& a = assets();
  return {a.color, a.normal, a.table16};
}

void racorx7(Device& dev, SampleResult& r) {
  const auto pick = confirmDevice(dev.caps(),
                                  {{1, 4, "ps.1.4: racorx7_ps14.psh (N.H^16 by 4 muls), vs racorx7.vsh"},
                                   {1, 1, "ps.1.1: racorx7_ps11.psh (N.H^16 by 4 muls), vs racorx7.vsh"}},
                                  r);
  if (!pick) return;
  setupRacorX7(dev, globeScene(dev), earthSpecular(), *pick == 0 ? PSVersion::PS14 : PSVersion::PS11);
  bindMesh(dev, assets().sphere);
  drawGlobe(dev, assets().sphere);
}

void racorx8(Device& dev, SampleResult& r) {
  const auto pick = confirmDevice(
      dev.caps(),
      {{1, 4, "ps.1.4: racorx8_ps14.psh (TableSpecps14: texcrd, dp3, texld from the 256x256 table), vs racorx8.vsh"},
       {1, 1, "ps.1.1: racorx8_ps11.psh (TableSpec: texm3x2pad/texm3x2tex into the 256x256 table), vs racorx8.vsh"}},
      r);
  if (!pick) return;
  setupRacorX8(dev, globeScene(dev), earthSpecular(), *pick == 0 ? PSVersion::PS14 : PSVersion::PS11);
  bindMesh(dev, assets().sphere);
  drawGlobe(dev, assets().sphere);
}

void racorx9(Device& dev, SampleResult& r) {
  const Assets& a = assets();
  const auto pick = confirmDevice(
      dev.caps(),
      {{1, 4, "ps.1.4: racorx9_ps14.psh (specular power from the normal map's alpha), vs racorx9_ps14.vsh (SpecDot314)"},
       {1, 1, "ps.1.1: racorx9_ps11.psh (diffuse + N.H^16 by 4 muls), vs racorx9.vsh (SpecDot3Pix)"}},
      r);
  if (!pick) return;
  const bool ps14 = *pick == 0;
  dev.setRenderState(RS_ZENABLE, ZB_TRUE);
  dev.setVertexShader(loadVertexShader(dev, ps14 ? "racorx9_ps14.vsh" : "racorx9.vsh"));
  dev.setPixelShader(loadPixelShader(dev, ps14 ? "racorx9_ps14.psh" : "racorx9_ps11.psh"));
  setConstants(dev, globeScene(dev));
  bindColorAndNormal(dev, a, ps14 ? a.normalSpecular : a.normal);
  // ps.1.4 reads the table in the normal map's alpha at (N.H, N.H): clamped like
  // RacorX8's table, or N.H at 1 would wrap onto the table's dark first row.
  if (ps14) clampAddressing(dev, 1);
  bindMesh(dev, a.sphere);
  drawGlobe(dev, a.sphere);
}

// ---------------------------------------------------------------- RacorX10-14
// A point light near the globe's lit side (world space) and its range.
const Vec3 kPointLight{-1.1f, 0.9f, -1.5f};
constexpr float kPointRange = 2.6f;

// The constants of the point-light vertex shaders: c0-c3 world, c8-c11 world*view*proj
// (transposed), c12 = -(light position) (PerPixelPointLight.vsh adds it to the
// position), c24 eye, c33 = (1/range, 0.5, 0.5, 0.5).
void setPointLightConstants(Device& dev) {
  const View v = globeView(dev, globeWorld());
  setMatrix(dev, 0, v.world);
  setMatrix(dev, 8, v.world * v.view * v.projection);
  setVec(dev, 12, Vec4(-kPointLight, 0));
  setVec(dev, 24, Vec4(v.eye, 1));
  setVec(dev, 33, Vec4(1.0f / kPointRange, 0.5f, 0.5f, 0.5f));
}

// The attenuation pass of RacorX10/11/12: PerPixelPointLight.vsh / PointLight.psh with
// the point light texture in stages 0 and 1.
void attenuationPass(Device& dev, SampleResult& r, const std::string& label) {
  const Assets& a = assets();
  dev.setVertexShader(loadVertexShader(dev, "racorx10_pointlight.vsh"));
  dev.setPixelShader(loadPixelShader(dev, "racorx10_pointlight.psh"));
  for (int s = 0; s < 4; ++s) dev.setTexture(s, nullptr);
  dev.setTexture(0, a.atten2D);
  dev.setTexture(1, a.atten2D);
  for (int s = 0; s < 2; ++s) {
    linearSampling(dev, s, false);
    clampAddressing(dev, s);
  }
  r.notes.push_back(label + ": " + describe(dev.validate()));
  drawGlobe(dev, assets().sphere);
}

void setBlend(Device& dev, bool enable, uint32_t src = BLEND_ONE, uint32_t dest = BLEND_ZERO) {
  dev.setRenderState(RS_ALPHABLENDENABLE, enable ? 1 : 0);
  dev.setRenderState(RS_SRCBLEND, src);
  dev.setRenderState(RS_DESTBLEND, dest);
}

void beginPointLight(Device& dev) {
  dev.setRenderState(RS_ZENABLE, ZB_TRUE);
  dev.setRenderState(RS_ZFUNC, CMP_LESSEQUAL);
  setPointLightConstants(dev);
  bindMesh(dev, assets().sphere);
}

void racorx10Passes(Device& dev, SampleResult& r) {
  const Assets& a = assets();
  beginPointLight(dev);
  setBlend(dev, false);
  attenuationPass(dev, r, "pass 1 (attenuation: racorx10_pointlight.vsh/.psh)");
  // SrcColor * 0 + DestColor * SrcColor
  setBlend(dev, true, BLEND_ZERO, BLEND_SRCCOLOR);
  dev.setTexture(0, a.color);
  dev.setTexture(1, a.normal);
  dev.setTexture(3, a.illum);
  for (int s : {0, 1}) {
    linearSampling(dev, s, true);
    dev.setSamplerState(s, SAMP_ADDRESSU, 1);
    dev.setSamplerState(s, SAMP_ADDRESSV, 1);
  }
  linearSampling(dev, 3, false);
  clampAddressing(dev, 3);
  dev.setPixelShader(loadPixelShader(dev, "racorx10_ps11.psh"));
  dev.setVertexShader(loadVertexShader(dev, "racorx10_specular.vsh"));
  r.notes.push_back("pass 2 (illumination map, SRCBLEND ZERO / DESTBLEND SRCCOLOR): " + describe(dev.validate()));
  drawGlobe(dev, a.sphere);
  setBlend(dev, false);
}

void racorx11Passes(Device& dev, SampleResult& r) {
  const Assets& a = assets();
  beginPointLight(dev);
  // first pass: diffuse(cubemap) * color, SrcColor * 1 + DestColor * 1
  setBlend(dev, true, BLEND_ONE, BLEND_ONE);
  bindColorAndNormal(dev, a, a.normal);
  dev.setTexture(2, a.cube);
  linearSampling(dev, 2, false);
  clampAddressing(dev, 2);
  dev.setPixelShader(loadPixelShader(dev, "racorx11_diffuse.psh"));
  dev.setVertexShader(loadVertexShader(dev, "racorx10_specular.vsh"));
  r.notes.push_back("pass 1 (diffuse with the normalization cube map, ONE/ONE): " + describe(dev.validate()));
  drawGlobe(dev, a.sphere);
  // second pass: specular (the same vertex shader)
  dev.setTexture(3, a.illum);
  linearSampling(dev, 3, false);
  clampAddressing(dev, 3);
  dev.setPixelShader(loadPixelShader(dev, "racorx11_specular.psh"));
  r.notes.push_back("pass 2 (specular from the illumination map, ONE/ONE): " + describe(dev.validate()));
  drawGlobe(dev, a.sphere);
  // third pass: attenuation, SrcColor * 0 + DestColor * SrcColor
  setBlend(dev, true, BLEND_ZERO, BLEND_SRCCOLOR);
  attenuationPass(dev, r, "pass 3 (attenuation, ZERO/SRCCOLOR)");
  setBlend(dev, false);
}

void racorx12Passes(Device& dev, SampleResult& r) {
  const Assets& a = assets();
  beginPointLight(dev);
  setBlend(dev, false);
  bindColorAndNormal(dev, a, a.normal);
  dev.setTexture(2, a.cube);
  dev.setTexture(3, a.table2048);
  for (int s : {2, 3}) {
    linearSampling(dev, s, false);
    clampAddressing(dev, s);
  }
  dev.setPixelShader(loadPixelShader(dev, "racorx12_ps12.psh"));
  dev.setVertexShader(loadVertexShader(dev, "racorx10_specular.vsh"));
  r.notes.push_back("pass 1 (diffuse + texdp3tex specular from the 2048x1 table): " + describe(dev.validate()));
  drawGlobe(dev, a.sphere);
  setBlend(dev, true, BLEND_ZERO, BLEND_SRCCOLOR);
  attenuationPass(dev, r, "pass 2 (attenuation, ZERO/SRCCOLOR)");
  setBlend(dev, false);
}

// RacorX13 and the three RacorX14 shaders: one ps.1.4 pass. `stages` lists the
// texture of each stage 0-5 (nullptr = unused).
void racorx13Pass(Device& dev, SampleResult& r, const std::string& psFile, const std::array<TexturePtr, 6>& stages) {
  beginPointLight(dev);
  setBlend(dev, false);
  for (int s = 0; s < 6; ++s) {
    dev.setTexture(s, stages[s]);
    const bool map = stages[s] == assets().color || stages[s] == assets().normal;
    linearSampling(dev, s, map);
    if (!map) clampAddressing(dev, s);
  }
  dev.setVertexShader(loadVertexShader(dev, "racorx13.vsh"));
  dev.setPixelShader(loadPixelShader(dev, psFile));
  r.notes.push_back("one pass: " + describe(dev.validate()));
  drawGlobe(dev, assets().sphere);
}

// The passes of the best version the profile runs, RacorX13/14 falling back to
// RacorX12 and RacorX11 ("how to divide a ps.1.4 shader into several ps.1.1 pixel
// shaders").
void pointLightSample(Device& dev, SampleResult& r, std::vector<Version> versions,
                      const std::function<void(Device&, SampleResult&)>& ps14) {
  if (versions.front().major == 1 && versions.front().minor == 4) {
    versions.push_back({1, 2, "fallback ps.1.2: RacorX12, 2 passes (racorx12_ps12.psh + attenuation)"});
    versions.push_back({1, 1, "fallback ps.1.1: RacorX11, 3 passes (diffuse, specular, attenuation)"});
  } else if (versions.front().minor == 2) {
    versions.push_back({1, 1, "fallback ps.1.1: RacorX11, 3 passes (diffuse, specular, attenuation)"});
  }
  const auto pick = confirmDevice(dev.caps(), versions, r);
  if (!pick) return;
  const Version& v = versions[*pick];
  if (v.minor == 4) {
    ps14(dev, r);
  } else if (v.minor == 2) {
    racorx12Passes(dev, r);
  } else if (v.label.find("RacorX10") != std::string::npos) {
    racorx10Passes(dev, r);
  } else {
    racorx11Passes(dev, r);
  }
}

void racorx10(Device& dev, SampleResult& r) {
  pointLightSample(dev, r, {{1, 1, "ps.1.1: RacorX10, 2 passes: attenuation, then racorx10_ps11.psh (SpecDot3)"}}, {});
}
void racorx11(Device& dev, SampleResult& r) {
  pointLightSample(dev, r, {{1, 1, "ps.1.1: RacorX11, 3 passes (diffuse with cube map, specular, attenuation)"}}, {});
}
void racorx12(Device& dev, SampleResult& r) {
  pointLightSample(dev, r, {{1, 2, "ps.1.2: RacorX12, 2 passes: racorx12_ps12.psh (texdp3tex), attenuation"}}, {});
}

void racorx13(Device& dev, SampleResult& r) {
  const Assets& a = assets();
  pointLightSample(dev, r, {{1, 4, "ps.1.4: RacorX13, one pass, six stages (racorx13_ps14.psh)"}},
                   [&](Device& d, SampleResult& rr) {
                     racorx13Pass(d, rr, "racorx13_ps14.psh",
                                  {a.normal, a.cube, a.color, a.table2048, a.atten2D, a.atten1D});
                   });
}

void racorx14(Device& dev, SampleResult& r, char variant) {
  const Assets& a = assets();
  const std::string file = fmt::format("racorx14{}_ps14.psh", variant);
  const char* what = variant == 'a'   ? "attenuation map fetched twice, five stages"
                     : variant == 'b' ? "half vector normalized by a second cube map stage"
                                      : "one cube map stage fetched twice";
  std::array<TexturePtr, 6> stages = {a.normal, a.cube, a.color, a.table2048, a.atten2D, nullptr};
  if (variant == 'b') stages[5] = a.cube;
  if (variant == 'c') stages = {a.normal, nullptr, a.color, a.table2048, a.atten2D, a.cube};
  pointLightSample(dev, r, {{1, 4, fmt::format("ps.1.4: RacorX14 ({}), {}", file, what)}},
                   [&](Device& d, SampleResult& rr) { racorx13Pass(d, rr, file, stages); });
}

// ---------------------------------------------------------------- the per-pixel lighting column
// Its shaders read c0-c3 world, c4-c7 total matrix, c16 light direction, c20 = 0.5,
// c24 camera position (see data/shaders/README.md for the text's differing list).
void setColumnConstants(Device& dev, const View& v) {
  setMatrix(dev, 0, v.world);
  setMatrix(dev, 4, v.world * v.view * v.projection);
  setVec(dev, 16, Vec4(normalize(v.lightDirection), 0));
  setVec(dev, 20, Vec4(0.5f, 0.5f, 0.5f, 0.5f));
  setVec(dev, 24, Vec4(v.eye, 1));
}

// The column's pixel shaders are ps.1.1: they run on every pixel shader part.
bool columnConfirm(Device& dev, SampleResult& r, const std::string& label) {
  return confirmDevice(dev.caps(), {{1, 1, label}}, r).has_value();
}

void paperDiffuse(Device& dev, SampleResult& r) {
  const Assets& a = assets();
  if (!columnConfirm(dev, r, "ps.1.1: paper_diffuse.vsh / .psh (dp3_sat N.L, modulate)")) return;
  dev.setRenderState(RS_ZENABLE, ZB_TRUE);
  dev.setVertexShader(loadVertexShader(dev, "paper_diffuse.vsh"));
  dev.setPixelShader(loadPixelShaderOrFixed(dev, "paper_diffuse.psh", "paper_diffuse_fixed.psh", r));
  setColumnConstants(dev, globeScene(dev));
  // The shader samples the color map in t0 and the normal map in t1 (the text's
  // Texture[] list names them the other way round).
  drawColorNormalGlobe(dev, a);
}

void paperSpecularMul(Device& dev, SampleResult& r) {
  const Assets& a = assets();
  if (!columnConfirm(dev, r, "ps.1.1: paper_specular_mul.vsh / .psh (pow2 by multiplies)")) return;
  dev.setRenderState(RS_ZENABLE, ZB_TRUE);
  dev.setVertexShader(loadVertexShader(dev, "paper_specular_mul.vsh"));
  dev.setPixelShader(loadPixelShader(dev, "paper_specular_mul.psh"));
  setColumnConstants(dev, globeScene(dev));
  drawColorNormalGlobe(dev, a);
}

void paperSpecularTable(Device& dev, SampleResult& r) {
  const Assets& a = assets();
  if (!columnConfirm(dev, r, "ps.1.1: paper_specular_table.vsh / .psh (3x2 table lookup, power 100)")) return;
  dev.setRenderState(RS_ZENABLE, ZB_TRUE);
  dev.setVertexShader(loadVertexShader(dev, "paper_specular_table.vsh"));
  dev.setPixelShader(loadPixelShaderOrFixed(dev, "paper_specular_table.psh", "paper_specular_table_fixed.psh", r));
  setColumnConstants(dev, globeScene(dev));
  dev.setTexture(0, a.normal);
  dev.setTexture(2, a.table100);
  dev.setTexture(3, a.color);
  linearSampling(dev, 0, true);
  linearSampling(dev, 2, false);
  clampAddressing(dev, 2);
  linearSampling(dev, 3, true);
  bindMesh(dev, a.sphere);
  drawGlobe(dev, a.sphere);
}

// The emboss vertex shader with the column's fixed-function stages
// (SelectArg1(height) / AddSigned(height | Complement, current)), then the color map
// lit by its oD0 multiplied in (2 x src x dst), as the emboss fixed-function sample.
void paperEmboss(Device& dev, SampleResult& r) {
  const Assets& a = assets();
  r.technique = "vs.1.1 paper_emboss.vsh + fixed-function SELECTARG1 / ADDSIGNED(height | COMPLEMENT), 2 passes";
  dev.setRenderState(RS_ZENABLE, ZB_TRUE);
  dev.setVertexShader(loadVertexShader(dev, "paper_emboss.vsh"));
  // The shader dots the light with the untransformed normal (dp3 oD0.xyz, v3, c12)
  // and with the world-space tangent frame: it assumes world = identity. The camera
  // moves around the globe instead (the same picture as the other samples).
  Matrix inv;
  if (!inverse(globeWorld(), inv)) inv = Matrix::identity();
  View v = globeScene(dev);
  v.world = Matrix::identity();
  v.view = matrixLookAtLH(transformCoord(v.eye, inv), {0, 0, 0}, transformNormal({0, 1, 0}, inv));
  setMatrix(dev, 0, v.world);
  setMatrix(dev, 8, v.world * v.view * v.projection);
  setVec(dev, 12, Vec4(normalize(transformNormal(kTowardLight, inv)), 0));  // c12: toward the light
  setVec(dev, 24, Vec4(1.5f / 512.0f, 1.5f / 256.0f, 0, 0));  // offset: 1.5 texels of the height map
  bindMesh(dev, a.sphere);
  dev.setTexture(0, a.height);
  dev.setTextureStageState(0, TSS_COLOROP, TOP_SELECTARG1);
  dev.setTextureStageState(0, TSS_COLORARG1, TA_TEXTURE);
  dev.setTexture(1, a.height);
  dev.setTextureStageState(1, TSS_COLOROP, TOP_ADDSIGNED);
  dev.setTextureStageState(1, TSS_COLORARG1, TA_TEXTURE | TA_COMPLEMENT);
  dev.setTextureStageState(1, TSS_COLORARG2, TA_CURRENT);
  dev.setTextureStageState(2, TSS_COLOROP, TOP_DISABLE);
  linearSampling(dev, 0, true);
  linearSampling(dev, 1, true);
  r.notes.push_back("pass 1 (emboss): " + describe(dev.validate()));
  drawGlobe(dev, a.sphere);
  dev.setTexture(0, a.color);
  dev.setTextureStageState(0, TSS_COLOROP, TOP_MODULATE);
  dev.setTextureStageState(0, TSS_COLORARG1, TA_TEXTURE);
  dev.setTextureStageState(0, TSS_COLORARG2, TA_DIFFUSE);
  dev.setTextureStageState(1, TSS_COLOROP, TOP_DISABLE);
  dev.setTexture(1, nullptr);
  setBlend(dev, true, BLEND_DESTCOLOR, BLEND_SRCCOLOR);
  dev.setRenderState(RS_ZFUNC, CMP_EQUAL);
  r.notes.push_back("pass 2 (color x oD0, DESTCOLOR/SRCCOLOR): " + describe(dev.validate()));
  drawGlobe(dev, a.sphere);
  setBlend(dev, false);
}

// ---------------------------------------------------------------- hemisphere lighting
const Vec4 kSkyColor{0.55f, 0.7f, 1.0f, 1.0f};
const Vec4 kGroundColor{0.35f, 0.25f, 0.15f, 1.0f};

// The vertex hemisphere shader on the teapot, with the occluded fraction of each
// vertex's hemisphere in v7.z.
void hemisphereVertex(Device& dev, SampleResult& r) {
  r.technique = "vs.1.1 hemisphere.vsh (sky/ground lerp x (1 - occlusion)), fixed-function SELECTARG1(diffuse)";
  static const d3dx::Mesh teapot = [] {
    const d3dx::Mesh t = d3dx::createTeapot(6);
    d3dx::Mesh m = d3dx::cloneMeshFVF(t, fvf::XYZ | fvf::NORMAL | fvf::tex(1) | fvf::texCoordSize(3, 0));
    const std::vector<float> visible = d3dx::computeHemisphereVisibility(t);
    for (uint32_t i = 0; i < m.vertexCount(); ++i) m.setTexCoord(i, 0, Vec4(0, 0, 1.0f - visible[i], 0));
    return m;
  }();
  const Texture& rt = *dev.renderTarget();
  const Matrix world = matrixScaling(0.55f, 0.55f, 0.55f) * matrixRotationY(0.6f) * matrixRotationX(-0.35f);
  const Matrix view = matrixLookAtLH({0, 0.5f, -4.2f}, {0, 0, 0}, {0, 1, 0});
  const Matrix proj = matrixPerspectiveFovLH(kPi / 4, float(rt.width()) / float(rt.height()), 0.1f, 100.0f);
  dev.setRenderState(RS_ZENABLE, ZB_TRUE);
  dev.setVertexShader(loadVertexShader(dev, "hemisphere.vsh"));
  setMatrix(dev, 0, world);
  setMatrix(dev, 8, world * view * proj);
  setVec(dev, 33, Vec4(0.5f, 0.5f, 0.5f, 0.5f));
  setVec(dev, 40, Vec4(0, 1, 0, 0));  // sky vector: up
  setVec(dev, 41, kSkyColor);
  setVec(dev, 42, kGroundColor);
  setVec(dev, 43, Vec4(1, 1, 1, 1));  // the light's intensity
  setVec(dev, 44, Vec4(1, 1, 1, 1));
  dev.setTextureStageState(0, TSS_COLOROP, TOP_SELECTARG1);
  dev.setTextureStageState(0, TSS_COLORARG1, TA_DIFFUSE);
  dev.setTextureStageState(0, TSS_ALPHAOP, TOP_SELECTARG1);
  dev.setTextureStageState(0, TSS_ALPHAARG1, TA_DIFFUSE);
  bindMesh(dev, teapot);
  drawGlobe(dev, teapot);
}

// The per-pixel fragment: "pass the hemisphere axis in as a light direction and use
// the standard tangent space basis vertex shader" (paper_diffuse.vsh, c16 = -axis).
void hemispherePixel(Device& dev, SampleResult& r) {
  const Assets& a = assets();
  if (!columnConfirm(dev, r, "ps.1.1: hemisphere.psh with paper_diffuse.vsh carrying the sky axis")) return;
  dev.setRenderState(RS_ZENABLE, ZB_TRUE);
  dev.setVertexShader(loadVertexShader(dev, "paper_diffuse.vsh"));
  dev.setPixelShader(loadPixelShaderOrFixed(dev, "hemisphere.psh", "hemisphere_fixed.psh", r));
  View v = globeScene(dev);
  v.lightDirection = {0, -1, 0};  // -c16 = the sky axis, up
  setColumnConstants(dev, v);
  setPSVec(dev, 1, kSkyColor);
  setPSVec(dev, 2, kGroundColor);
  setPSVec(dev, 5, Vec4(0.5f, 0.5f, 0.5f, 0.5f));
  dev.setTexture(0, a.normal);
  dev.setTexture(1, a.color);
  linearSampling(dev, 0, true);
  linearSampling(dev, 1, true);
  bindMesh(dev, a.sphere);
  drawGlobe(dev, a.sphere);
}

// ---------------------------------------------------------------- BRDF
void brdf(Device& dev, SampleResult& r) {
  const Assets& a = assets();
  if (!columnConfirm(dev, r, "ps.1.1: brdf_fixed.vsh / brdf.psh (homomorphic factorization, 3 cube maps)")) return;
  static const d3dx::BrdfFactorization f = [] {
    d3dx::BrdfFactorizationOptions o;
    o.cubeSize = 16;
    o.samples = 1 << 15;
    o.iterations = 100;
    return d3dx::computeBrdfFactorization(d3dx::WardBrdf{}, o);
  }();
  // The listing as printed assembles but leaves oT1.z unwritten; the sample runs the
  // corrected copy.
  loadVertexShader(dev, "brdf.vsh");
  r.notes.push_back("brdf.vsh as printed writes oT2.z for the light vector; running brdf_fixed.vsh");
  dev.setRenderState(RS_ZENABLE, ZB_TRUE);
  dev.setVertexShader(loadVertexShader(dev, "brdf_fixed.vsh"));
  dev.setPixelShader(loadPixelShader(dev, "brdf.psh"));
  View v = globeScene(dev);
  setMatrix(dev, 0, v.world);
  setMatrix(dev, 4, v.world * v.view * v.projection);
  // MaterialColor: white; the factors are each normalized to a largest texel of 1, so
  // the product shows the BRDF's shape (f.scale would rescale it to radiance).
  setVec(dev, 9, Vec4(1, 1, 1, 1));
  setVec(dev, 10, Vec4(v.eye, 1));
  setVec(dev, 16, Vec4(normalize(v.lightDirection), 0));
  dev.setTexture(0, f.p);
  dev.setTexture(1, f.pCos);
  dev.setTexture(2, f.q);
  dev.setTexture(3, a.brick);  // the object's own texture
  for (int st = 0; st < 3; ++st) {
    linearSampling(dev, st, false);
    clampAddressing(dev, st);
  }
  linearSampling(dev, 3, true);
  bindMesh(dev, a.sphere);
  drawGlobe(dev, a.sphere);
}

SampleFn wrap(void (*fn)(Device&, SampleResult&)) {
  return [fn](Device& d) { return guarded(d, fn); };
}

}  // namespace

const std::vector<Sample>& shaderSamples() {
  static const std::vector<Sample> samples = {
      {"racorx6", "RacorX6: per-pixel diffuse bump mapping (ps.1.1 / ps.1.4)",
       "seeds/003 Programming Pixel Shaders, RacorX6", wrap(racorx6)},
      {"racorx7", "RacorX7: specular N.H^16 by four multiplies (banding)", "seeds/003, RacorX7", wrap(racorx7)},
      {"racorx8", "RacorX8: specular power from a 256x256 lookup table (texm3x2pad/texm3x2tex, ps.1.4 texcrd)",
       "seeds/003, RacorX8", wrap(racorx8)},
      {"racorx9", "RacorX9: diffuse + specular; ps.1.4 reads the power from the normal map's alpha",
       "seeds/003, RacorX9", wrap(racorx9)},
      {"racorx10", "RacorX10: point light, attenuation pass then illumination map (ZERO / SRCCOLOR)",
       "seeds/002 Advanced Shader Programming, RacorX10", wrap(racorx10)},
      {"racorx11", "RacorX11: three passes with the normalization cube map", "seeds/002, RacorX11", wrap(racorx11)},
      {"racorx12", "RacorX12: ps.1.2 texdp3tex with the 2048x1 table, two passes", "seeds/002, RacorX12",
       wrap(racorx12)},
      {"racorx13", "RacorX13: ps.1.4, one pass, six stages", "seeds/002, RacorX13", wrap(racorx13)},
      {"racorx14a", "RacorX14: attenuation map fetched twice (five stages)", "seeds/002, RacorX14, first shader",
       [](Device& d) { return guarded(d, [](Device& dd, SampleResult& r) { racorx14(dd, r, 'a'); }); }},
      {"racorx14b", "RacorX14: half vector normalized by a cube map", "seeds/002, RacorX14, second shader",
       [](Device& d) { return guarded(d, [](Device& dd, SampleResult& r) { racorx14(dd, r, 'b'); }); }},
      {"racorx14c", "RacorX14: one cube map stage fetched twice", "seeds/002, RacorX14, final shader",
       [](Device& d) { return guarded(d, [](Device& dd, SampleResult& r) { racorx14(dd, r, 'c'); }); }},
      {"paper-diffuse", "Per-pixel diffuse: dp3_sat N.L in a ps.1.1 shader",
       "seeds/000 per-pixel lighting column: diffuse", wrap(paperDiffuse)},
      {"paper-specular-mul", "Per-pixel specular, exponent by multiplies (N.H^16)",
       "seeds/000 per-pixel lighting column: multiply-based specular", wrap(paperSpecularMul)},
      {"paper-specular-table", "Per-pixel specular from a 3x2 table lookup (power 100)",
       "seeds/000 per-pixel lighting column: table-based specular", wrap(paperSpecularTable)},
      {"paper-emboss", "Emboss vertex shader with the fixed-function emboss stages",
       "seeds/000 per-pixel lighting column: emboss vertex shader", wrap(paperEmboss)},
      {"hemisphere-vertex", "Hemisphere lighting per vertex: sky/ground lerp with occlusion",
       "seeds/000 custom per-pixel lighting: vertex hemisphere shader", wrap(hemisphereVertex)},
      {"hemisphere-pixel", "Hemisphere lighting per pixel: the ps.1.1 fragment",
       "seeds/000 custom per-pixel lighting: per-pixel fragment", wrap(hemispherePixel)},
      {"brdf", "BRDF by homomorphic factorization: three cube maps multiplied (vs.1.1/ps.1.1 pair)",
       "seeds/000 \"DirectX 8 Pixel Shaders\" BRDF effect", wrap(brdf)},
  };
  return samples;
}

}  // namespace refx::samples
