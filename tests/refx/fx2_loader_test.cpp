// Loading fx_2_0 binaries (Effect::fromFx2, Effect::fromFile on a binary): the sample
// effects written by refx's writer load back with the same parameters, annotations,
// techniques and passes, and draw the same pixels as the text they came from; the
// reference's hand-built example (§6.1) loads; damaged binaries are errors with the
// offset, never crashes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>

#include "pipeline/device_helpers.h"
#include "refx/core/diagnostics.h"
#include "refx/d3dx/lighting_maps.h"
#include "refx/d3dx/texture_fill.h"
#include "refx/effect/effect.h"
#include "refx/effect/fx2_binary.h"

namespace refx::effect {
namespace {

const std::string kEffects = std::string(REFX_DATA_DIR) + "/effects/";

std::unique_ptr<Effect> roundTrip(const Effect& fx, const std::string& name) {
  const Fx2Binary bin = writeFx2(fx);
  return Effect::fromFx2(bin.bytes, name);
}

std::string annotationText(const std::vector<Annotation>& list) {
  std::string s;
  for (const Annotation& a : list) {
    s += fmt::format("{} {} {}x{}[{}] \"{}\"", a.desc.name, int(a.desc.type), a.desc.rows, a.desc.columns,
                     a.desc.elements, a.text);
    for (double x : a.numbers) s += fmt::format(" {}", float(x));
    s += ";";
  }
  return s;
}

// A 4x4 texture whose texels differ (so that sampling positions show).
TexturePtr gradient(uint32_t seed) {
  auto t = Texture::create2D(Format::A8R8G8B8, 4, 4, 1);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const uint32_t v = 0xff000000u | ((seed * 37 + uint32_t(x) * 60) & 0xff) << 16 |
                         ((seed * 11 + uint32_t(y) * 60) & 0xff) << 8 | ((seed * 5 + uint32_t(x + y) * 30) & 0xff);
      std::memcpy(t->data(0, 0) + y * t->rowPitch(0) + x * 4, &v, 4);
    }
  t->markDirty();
  return t;
}

// The same inputs for both: textures for every texture parameter, identity matrices.
void prepare(Effect& fx) {
  for (Handle p = 0; p < fx.parameterCount(); ++p) {
    const ParameterDesc& d = fx.parameterDesc(p);
    if (d.type == ParameterType::TextureCube) fx.setTexture(p, d3dx::createNormalizationCubeMap(8));
    else if (d.type == ParameterType::Texture || d.type == ParameterType::Texture2D) fx.setTexture(p, gradient(uint32_t(p)));
    else if (d.isNumeric() && d.rows == 4 && d.columns == 4 && d.elements == 0) fx.setMatrix(p, Matrix::identity());
  }
}

struct QuadVertex {
  float x, y, z, nx, ny, nz, u, v, w, tx, ty, tz;
};

// Every pass of technique `t` over a quad facing the camera on a 16x16 target; the
// target's pixels.
std::vector<uint32_t> draw(Effect& fx, Handle t) {
  fx.setTechnique(t);
  auto dev = test::makeDevice(16, 16, 0xff204060);
  const int passes = fx.begin(*dev, 0);
  const QuadVertex quad[4] = {{-0.8f, 0.7f, 0.5f, 0.3f, 0.2f, -1, 0, 0, 0.25f, 1, 0, 0},
                              {0.9f, 0.8f, 0.5f, -0.2f, 0.3f, -1, 1, 0, 0.25f, 1, 0, 0},
                              {-0.7f, -0.9f, 0.5f, 0.1f, -0.4f, -1, 0, 1, 0.25f, 1, 0, 0},
                              {0.8f, -0.8f, 0.5f, 0, 0, -1, 1, 1, 0.25f, 1, 0, 0}};
  for (int i = 0; i < passes; ++i) {
    fx.beginPass(i);
    dev->setFVF(d3d::FVF_XYZ | d3d::FVF_NORMAL | (2u << d3d::FVF_TEXCOUNT_SHIFT) | d3d::fvfTexCoordSize(3, 0) |
                d3d::fvfTexCoordSize(3, 1));
    dev->drawPrimitiveUP(d3d::PT_TRIANGLESTRIP, 2, quad, sizeof(QuadVertex));
    fx.endPass();
  }
  fx.end();
  std::vector<uint32_t> px;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) px.push_back(test::pixel(*dev, x, y));
  return px;
}

class SampleRoundTrip : public testing::TestWithParam<const char*> {};

TEST_P(SampleRoundTrip, TextAndBinaryAreTheSameEffect) {
  auto text = Effect::fromFile(kEffects + GetParam());
  std::unique_ptr<Effect> bin;
  ASSERT_NO_THROW(bin = roundTrip(*text, GetParam()));
  for (const auto& d : bin->diagnostics()) ADD_FAILURE() << d.str();

  ASSERT_EQ(bin->parameterCount(), text->parameterCount());
  for (Handle p = 0; p < text->parameterCount(); ++p) {
    const ParameterDesc& a = text->parameterDesc(p);
    const ParameterDesc& b = bin->parameterDesc(p);
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.semantic, a.semantic) << a.name;
    EXPECT_EQ(int(b.type), int(a.type)) << a.name;
    const bool matrix = a.cls == ParameterClass::MatrixRows || a.cls == ParameterClass::MatrixColumns;
    if (matrix) EXPECT_EQ(b.cls, ParameterClass::MatrixColumns) << a.name;  // the binary does not keep the packing
    else EXPECT_EQ(int(b.cls), int(a.cls)) << a.name;
    EXPECT_EQ(b.rows, a.rows) << a.name;
    EXPECT_EQ(b.columns, a.columns) << a.name;
    EXPECT_EQ(b.elements, a.elements) << a.name;
    EXPECT_EQ(b.flags, a.flags) << a.name;
    if (a.isNumeric()) {
      EXPECT_EQ(bin->getFloatArray(p), text->getFloatArray(p)) << a.name;
    }
    if (a.type == ParameterType::String) {
      EXPECT_EQ(bin->getString(p), text->getString(p)) << a.name;
    }
    EXPECT_EQ(annotationText(bin->parameterAnnotations(p)), annotationText(text->parameterAnnotations(p))) << a.name;
  }
  ASSERT_EQ(bin->techniqueCount(), text->techniqueCount());
  prepare(*text);
  prepare(*bin);
  const CapsProfile caps = loadCapsProfile("ref");
  int drawn = 0;
  for (Handle t = 0; t < text->techniqueCount(); ++t) {
    const TechniqueDesc& a = text->techniqueDesc(t);
    const TechniqueDesc& b = bin->techniqueDesc(t);
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(annotationText(b.annotations), annotationText(a.annotations)) << a.name;
    ASSERT_EQ(b.passes.size(), a.passes.size()) << a.name;
    for (size_t p = 0; p < a.passes.size(); ++p) {
      EXPECT_EQ(b.passes[p].name, a.passes[p].name);
      EXPECT_EQ(annotationText(b.passes[p].annotations), annotationText(a.passes[p].annotations));
    }
    const TechniqueValidation va = text->validateTechnique(t, caps);
    const TechniqueValidation vb = bin->validateTechnique(t, caps);
    EXPECT_EQ(vb.ok, va.ok) << a.name << ": " << va.reason << " / " << vb.reason;
    if (!va.ok || !vb.ok) continue;
    const std::vector<uint32_t> pa = draw(*text, t);
    const std::vector<uint32_t> pb = draw(*bin, t);
    int differ = 0;
    for (size_t i = 0; i < pa.size(); ++i) differ += pa[i] != pb[i];
    EXPECT_EQ(differ, 0) << a.name << ": " << differ << " pixels differ; middle " << std::hex << pa[8 * 16 + 8] << " / "
                         << pb[8 * 16 + 8];
    for (uint32_t px : pa) {
      if (px != 0xff204060) {
        ++drawn;
        break;
      }
    }
  }
  // At least one technique draws something: the comparison is of pictures.
  EXPECT_GT(drawn, 0);
}

INSTANTIATE_TEST_SUITE_P(Fx2, SampleRoundTrip,
                         testing::Values("brdf.fx", "brdf_fixed.fx", "bump_earth.fx", "hemisphere.fx", "hlsl_ambient.fx",
                                         "hlsl_bump.fx", "hlsl_diffuse.fx", "hlsl_point_light.fx",
                                         "hlsl_self_shadow.fx", "hlsl_specular.fx", "paper_diffuse.fx",
                                         "paper_specular.fx", "racorx10.fx", "racorx6.fx", "racorx7.fx", "racorx8.fx",
                                         "racorx9.fx", "racorx_point_light.fx", "wood.fx"),
                         [](const testing::TestParamInfo<const char*>& i) {
                           std::string n = i.param;
                           return n.substr(0, n.find('.'));
                         });

// Reference §6.1, the 280 bytes built by hand: g_Color = (1, 0.5, 0.25, 1); technique T,
// pass P: ColorOp[0] = MODULATE (4), PixelShader = ps_1_1 `mov r0, v0`.
const uint32_t kWorkedExample[] = {
    0xFEFF0901, 0x84, 0, 3, 1, 0x30, 0, 0, 4, 1, 0x3F800000, 0x3F000000, 0x3E800000, 0x3F800000, 8, 0x6F435F67,
    0x00726F6C, 4, 2, 2, 0, 0, 0, 1, 1, 1, 15, 4, 0, 0, 0, 2, 0x50, 2, 0x54, 1, 1, 2, 2, 0x04, 0x20, 0, 0, 0x7C, 0, 1,
    0x74, 0, 2, 0x67, 0, 0x40, 0x3C, 0x93, 0, 0x60, 0x5C, 0, 1, 0, 0, 0xFFFFFFFF, 1, 0, 20, 0xFFFF0101, 0x00000001,
    0x800F0000, 0x90E40000, 0x0000FFFF};

std::vector<uint8_t> bytesOf(std::span<const uint32_t> w) {
  std::vector<uint8_t> b(w.size() * 4);
  std::memcpy(b.data(), w.data(), b.size());
  return b;
}

TEST(Fx2Loader, TheReferencesWorkedExampleLoads) {
  static_assert(sizeof(kWorkedExample) == 280);
  auto fx = Effect::fromFx2(bytesOf(kWorkedExample), "example.fxo");
  EXPECT_TRUE(fx->diagnostics().empty());
  ASSERT_EQ(fx->parameterCount(), 1);
  EXPECT_EQ(fx->parameterDesc(0).name, "g_Color");
  EXPECT_EQ(fx->parameterDesc(0).cls, ParameterClass::Vector);
  EXPECT_EQ(fx->parameterDesc(0).columns, 4);
  EXPECT_EQ(fx->getFloatArray(0), (std::vector<float>{1, 0.5f, 0.25f, 1}));
  ASSERT_EQ(fx->techniqueCount(), 1);
  EXPECT_EQ(fx->techniqueDesc(0).name, "T");
  ASSERT_EQ(fx->techniqueDesc(0).passes.size(), 1u);
  EXPECT_EQ(fx->techniqueDesc(0).passes[0].name, "P");
  // The pass sets ColorOp[0] = MODULATE and the ps_1_1 shader that outputs v0: a
  // triangle's diffuse color (0xff336699) comes out as it is.
  auto dev = test::makeDevice(8, 8);
  fx->begin(*dev, kDoNotSaveState);
  fx->beginPass(0);
  EXPECT_EQ(dev->state().stageStates[0][d3d::TSS_COLOROP], uint32_t(d3d::TOP_MODULATE));
  const uint32_t c = 0xff336699;
  test::drawTL(*dev, d3d::PT_TRIANGLESTRIP, {{0, 0, 0.5f, 1, c, 0, 0}, {8, 0, 0.5f, 1, c, 0, 0},
                                              {0, 8, 0.5f, 1, c, 0, 0}, {8, 8, 0.5f, 1, c, 0, 0}});
  fx->endPass();
  fx->end();
  EXPECT_EQ(test::pixel(*dev, 4, 4), c);
}

TEST(Fx2Loader, DamagedBinariesAreErrorsWithTheOffset) {
  const std::vector<uint8_t> good = bytesOf(kWorkedExample);
  // Every truncation: an error naming an offset (never a crash).
  for (size_t n = 0; n < good.size(); n += 4) {
    std::vector<uint8_t> cut(good.begin(), good.begin() + std::ptrdiff_t(n));
    try {
      Effect::fromFx2(cut, "cut.fxo");
      ADD_FAILURE() << "a binary cut to " << n << " bytes loaded";
    } catch (const Error& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("cut.fxo: error:"), std::string::npos) << msg;
      if (n >= 8) {
        EXPECT_NE(msg.find("offset 0x"), std::string::npos) << msg;
      }
    }
  }
  // The parameter's type offset (file byte 0x9C) pointing outside the unstructured area.
  std::vector<uint8_t> bad = good;
  const uint32_t outside = 0x1000;
  std::memcpy(&bad[0x9C], &outside, 4);
  try {
    Effect::fromFx2(bad, "bad.fxo");
    ADD_FAILURE() << "a type offset outside the file loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.fxo: error: fx_2_0 offset 0x9c: offset 0x1000"), std::string::npos)
        << e.what();
  }
  // State operation 200 (the table ends at 178), in the pass's first state record (0xC4).
  bad = good;
  const uint32_t op = 200;
  std::memcpy(&bad[0xC4], &op, 4);
  try {
    Effect::fromFx2(bad, "bad.fxo");
    ADD_FAILURE() << "operation 200 loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("offset 0xc4: state operation 200"), std::string::npos) << e.what();
  }
}

// fromFile tells a binary from text by its first DWORD.
TEST(Fx2Loader, FromFileReadsBinaries) {
  const std::string path = testing::TempDir() + "/example.fxo";
  {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(kWorkedExample), sizeof kWorkedExample);
  }
  auto fx = Effect::fromFile(path);
  EXPECT_EQ(fx->parameterDesc(0).name, "g_Color");
  EXPECT_EQ(fx->techniqueDesc(0).name, "T");
}

// A state expression and a compiled shader's preshader survive the trip and compute
// the same values: -v (v = (1, 2, 3, 4)) into c3 = (-1, -2, -3, -4); the pixel shader's
// uniform-only k * 0.5 (k = 0.8) is a preshader: 0.4 * 255 = 102.
TEST(Fx2Loader, ExpressionsAndPreshadersRunAfterLoading) {
  const char* text =
      "float4 v = {1, 2, 3, 4};\n"
      "float k = 0.8;\n"
      "float4 PS() : COLOR { return float4(k * 0.5, k * 0.5, k * 0.5, 1); }\n"
      "technique T { pass P {\n"
      "  VertexShaderConstant4[3] = -v;\n"
      "  PixelShader = compile ps_2_0 PS();\n"
      "} }\n";
  auto src = Effect::fromText(text, "pre.fx");
  const Fx2Binary bin = writeFx2(*src);
  EXPECT_NE(bin.listing.find("PRES"), std::string::npos) << bin.listing;
  auto fx = Effect::fromFx2(bin.bytes, "pre.fxo");
  for (const auto& d : fx->diagnostics()) ADD_FAILURE() << d.str();
  auto dev = test::makeDevice(8, 8);
  fx->begin(*dev, kDoNotSaveState);
  fx->beginPass(0);
  const Vec4 c3 = dev->state().vsConstF[3];
  EXPECT_EQ((std::vector<float>{c3.x, c3.y, c3.z, c3.w}), (std::vector<float>{-1, -2, -3, -4}));
  const uint32_t c = 0xff000000;
  test::drawTL(*dev, d3d::PT_TRIANGLESTRIP, {{0, 0, 0.5f, 1, c, 0, 0}, {8, 0, 0.5f, 1, c, 0, 0},
                                              {0, 8, 0.5f, 1, c, 0, 0}, {8, 8, 0.5f, 1, c, 0, 0}});
  fx->endPass();
  fx->end();
  EXPECT_EQ(test::pixel(*dev, 4, 4), 0xff666666u);
  // A new value reaches both after CommitChanges: k = 0.2 → 0.1 → 26 (25.5 rounds up).
  fx->setFloat(fx->parameterByName("k"), 0.2f);
  fx->setVector(fx->parameterByName("v"), Vec4(0.5f, 0, 0, 0));
  fx->begin(*dev, kDoNotSaveState);
  fx->beginPass(0);
  EXPECT_EQ(dev->state().vsConstF[3].x, -0.5f);
  test::drawTL(*dev, d3d::PT_TRIANGLESTRIP, {{0, 0, 0.5f, 1, c, 0, 0}, {8, 0, 0.5f, 1, c, 0, 0},
                                              {0, 8, 0.5f, 1, c, 0, 0}, {8, 8, 0.5f, 1, c, 0, 0}});
  fx->endPass();
  fx->end();
  const uint32_t p = test::pixel(*dev, 4, 4);
  EXPECT_NEAR(int(p & 0xff), 26, 1) << std::hex << p;
}

}  // namespace
}  // namespace refx::effect
