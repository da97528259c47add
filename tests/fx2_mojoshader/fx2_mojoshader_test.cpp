// MojoShader's effect parser (Debian libmojoshader-dev, MOJOSHADER_compileEffect) loads
// the fx_2_0 binaries refx writes for the sample effects: parameters, annotations,
// techniques, passes, states and shaders come out as the .fx text says.
//
// MojoShader asserts on input it does not expect, so each binary is parsed in a child
// process that prints what MojoShader saw, one line per item; the test reads that.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <cmath>
#include <string>
#include <vector>

#include "effect/effect_internal.h"
#include "effect/fx2_preshader.h"
#include "effect/fxlc.h"
#include "refx/effect/effect.h"
#include "refx/effect/fx2_binary.h"

extern "C" {
#include <mojoshader.h>
#include <mojoshader_effects.h>
// Exported by libmojoshader (hg-1314) but not declared in its headers: runs a parsed
// preshader with its inputs in preshader->registers; outputs by component offset.
void MOJOSHADER_runPreshader(const MOJOSHADER_preshader* preshader, float* outregs);
}

namespace refx::effect {
namespace {

// ---------------------------------------------------------------- the child's side
std::vector<const MOJOSHADER_parseData*> g_parsed;

void* compileShader(const char* mainfn, const unsigned char* tokens, const unsigned int size,
                    const MOJOSHADER_swizzle* swiz, const unsigned int swizcount, const MOJOSHADER_samplerMap* smap,
                    const unsigned int smapcount) {
  const MOJOSHADER_parseData* pd = MOJOSHADER_parse(MOJOSHADER_PROFILE_BYTECODE, mainfn, tokens, size, swiz,
                                                    swizcount, smap, smapcount, nullptr, nullptr, nullptr);
  g_parsed.push_back(pd);
  return const_cast<MOJOSHADER_parseData*>(pd);
}
void addRef(void*) {}
void deleteShader(void*) {}
MOJOSHADER_parseData* parseData(void* shader) { return static_cast<MOJOSHADER_parseData*>(shader); }
void bindShaders(void*, void*) {}
void boundShaders(void** v, void** p) { *v = *p = nullptr; }
void mapUniforms(float**, int**, unsigned char**, float**, int**, unsigned char**) {}
void unmapUniforms() {}
const char* lastError() { return "shader parse failed"; }

std::string valueText(const MOJOSHADER_effectValue& v, const MOJOSHADER_effect* e) {
  std::string s;
  const auto type = v.type.parameter_type;
  if (v.type.parameter_class == MOJOSHADER_SYMCLASS_OBJECT) {
    if (type >= MOJOSHADER_SYMTYPE_SAMPLER && type <= MOJOSHADER_SYMTYPE_SAMPLERCUBE) {
      for (unsigned i = 0; i < v.value_count; ++i) {
        const MOJOSHADER_effectSamplerState& st = v.valuesSS[i];
        s += "{" + std::to_string(int(st.type)) + ":" + valueText(st.value, e) + "}";
      }
      return s;
    }
    for (unsigned i = 0; i < v.value_count; ++i) {
      const int id = v.valuesI[i];
      s += "#" + std::to_string(id);
      if (id > 0 && id < e->object_count && type == MOJOSHADER_SYMTYPE_STRING && e->objects[id].string.string)
        s += "\"" + std::string(e->objects[id].string.string) + "\"";
      if (id > 0 && id < e->object_count && type >= MOJOSHADER_SYMTYPE_TEXTURE &&
          type <= MOJOSHADER_SYMTYPE_TEXTURECUBE && e->objects[id].mapping.name)
        s += "<" + std::string(e->objects[id].mapping.name) + ">";
      s += " ";
    }
    return s;
  }
  // Numbers: MojoShader keeps them in float4 slots; print the components it filled.
  const unsigned per = v.type.columns;
  for (unsigned i = 0; i < v.value_count; ++i) {
    if (per && i % 4 >= per && v.type.parameter_class != MOJOSHADER_SYMCLASS_STRUCT) continue;
    char buf[32];
    if (type == MOJOSHADER_SYMTYPE_FLOAT) std::snprintf(buf, sizeof buf, "%g ", double(v.valuesF[i]));
    else std::snprintf(buf, sizeof buf, "%d ", v.valuesI[i]);
    s += buf;
  }
  return s;
}

std::string describe(const MOJOSHADER_effectValue& v) {
  return std::string(v.name ? v.name : "") + "|" + std::to_string(int(v.type.parameter_type)) + "|" +
         std::to_string(int(v.type.parameter_class)) + "|" + std::to_string(v.type.rows) + "|" +
         std::to_string(v.type.columns) + "|" + std::to_string(v.type.elements) + "|" +
         (v.semantic ? v.semantic : "");
}

std::string mojoDump(const std::vector<uint8_t>& bytes) {
  MOJOSHADER_effectShaderContext ctx{};
  ctx.compileShader = compileShader;
  ctx.shaderAddRef = addRef;
  ctx.deleteShader = deleteShader;
  ctx.getParseData = parseData;
  ctx.bindShaders = bindShaders;
  ctx.getBoundShaders = boundShaders;
  ctx.mapUniformBufferMemory = mapUniforms;
  ctx.unmapUniformBufferMemory = unmapUniforms;
  ctx.getError = lastError;
  const MOJOSHADER_effect* e =
      MOJOSHADER_compileEffect(bytes.data(), unsigned(bytes.size()), nullptr, 0, nullptr, 0, &ctx);
  std::string out;
  for (int i = 0; i < e->error_count; ++i) out += std::string("E ") + e->errors[i].error + "\n";
  for (int i = 0; i < e->param_count; ++i) {
    const MOJOSHADER_effectParam& p = e->params[i];
    out += "P " + describe(p.value) + " = " + valueText(p.value, e) + "\n";
    for (unsigned a = 0; a < p.annotation_count; ++a)
      out += "A " + describe(p.annotations[a]) + " = " + valueText(p.annotations[a], e) + "\n";
  }
  for (int t = 0; t < e->technique_count; ++t) {
    const MOJOSHADER_effectTechnique& tech = e->techniques[t];
    out += std::string("T ") + (tech.name ? tech.name : "") + "\n";
    for (unsigned a = 0; a < tech.annotation_count; ++a)
      out += "A " + describe(tech.annotations[a]) + " = " + valueText(tech.annotations[a], e) + "\n";
    for (unsigned p = 0; p < tech.pass_count; ++p) {
      const MOJOSHADER_effectPass& pass = tech.passes[p];
      out += std::string("p ") + (pass.name ? pass.name : "") + "\n";
      for (unsigned s = 0; s < pass.state_count; ++s)
        out += "S " + std::to_string(int(pass.states[s].type)) + " = " + valueText(pass.states[s].value, e) + "\n";
    }
  }
  int shaders = 0, shaderErrors = 0;
  for (const MOJOSHADER_parseData* pd : g_parsed) {
    ++shaders;
    for (int i = 0; i < pd->error_count; ++i) {
      ++shaderErrors;
      out += std::string("X ") + pd->errors[i].error + "\n";  // a shader error
    }
  }
  out += "shaders " + std::to_string(shaders) + " errors " + std::to_string(shaderErrors) + "\n";
  return out;
}

// ---------------------------------------------------------------- the test's side
// What `f` printed in a child process, or "MojoShader crashed …" when it aborted (an
// assert).
std::string inChild(const std::function<std::string()>& f) {
  int fds[2];
  if (pipe(fds) != 0) return "pipe failed";
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    std::string dump;
    try {
      dump = f();
    } catch (const std::exception& e) {
      dump = std::string("exception in the child: ") + e.what() + "\n";
    }
    size_t done = 0;
    while (done < dump.size()) {
      const ssize_t n = write(fds[1], dump.data() + done, dump.size() - done);
      if (n <= 0) break;
      done += size_t(n);
    }
    _exit(0);
  }
  close(fds[1]);
  std::string out;
  char buf[4096];
  for (ssize_t n; (n = read(fds[0], buf, sizeof buf)) > 0;) out.append(buf, size_t(n));
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    return "MojoShader crashed (signal " + std::to_string(WIFSIGNALED(status) ? WTERMSIG(status) : 0) + ")\n" + out;
  return out;
}

std::string parseInChild(const std::vector<uint8_t>& bytes) {
  return inChild([&] { return mojoDump(bytes); });
}

std::vector<std::string> lines(const std::string& text, char kind) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    if (text[start] == kind) out.push_back(text.substr(start + 2, end - start - 2));
    start = end + 1;
  }
  return out;
}

std::unique_ptr<Effect> load(const std::string& name) {
  return Effect::fromFile(std::string(REFX_DATA_DIR) + "/effects/" + name);
}

// Every sample effect: MojoShader reads the parameters (name, type, class, rows,
// columns, elements, semantic) and annotations the effect framework loaded from the
// text, the techniques and passes by name, and parses every shader without error.
class SampleEffect : public testing::TestWithParam<const char*> {};

TEST_P(SampleEffect, MojoShaderLoadsTheBinary) {
  auto fx = load(GetParam());
  Fx2WriteOptions opts;
  opts.inlineShaderReferences = true;  // MojoShader cannot load usage-1 shader references
  Fx2Binary bin;
  ASSERT_NO_THROW(bin = writeFx2(*fx, opts));
  const std::string dump = parseInChild(bin.bytes);
  ASSERT_EQ(dump.find("MojoShader crashed"), std::string::npos) << dump;
  // Every shader of the effect parses without an error (MojoShader stops at the first
  // one that has one, and the effect's errors are that shader's).
  for (char kind : {'E', 'X'})
    for (const std::string& l : lines(dump, kind)) ADD_FAILURE() << "MojoShader error: " << l;
  EXPECT_NE(dump.find(" errors 0\n"), std::string::npos) << dump;

  std::vector<std::string> params;
  for (const std::string& l : lines(dump, 'P')) params.push_back(l.substr(0, l.find(" = ")));
  ASSERT_EQ(params.size(), size_t(fx->parameterCount())) << dump;
  for (int i = 0; i < fx->parameterCount(); ++i) {
    const ParameterDesc& d = fx->parameterDesc(i);
    const bool matrix = d.cls == ParameterClass::MatrixRows || d.cls == ParameterClass::MatrixColumns;
    // MojoShader names the first tail DWORD "columns": a vector's columns, a matrix's rows.
    const int cols = d.isNumeric() ? (matrix ? d.rows : d.columns) : 0;
    const int rows = d.isNumeric() ? (matrix ? d.columns : d.rows) : 0;
    const std::string want = d.name + "|" + std::to_string(int(d.type)) + "|" +
                             std::to_string(matrix ? 2 : int(d.cls)) + "|" + std::to_string(rows) + "|" +
                             std::to_string(cols) + "|" + std::to_string(d.elements) + "|" + d.semantic;
    EXPECT_EQ(params[size_t(i)], want) << dump;
  }
  std::vector<std::string> techniques = lines(dump, 'T');
  ASSERT_EQ(techniques.size(), size_t(fx->techniqueCount())) << dump;
  std::vector<std::string> passes = lines(dump, 'p');
  size_t pass = 0;
  for (int t = 0; t < fx->techniqueCount(); ++t) {
    EXPECT_EQ(techniques[size_t(t)], fx->techniqueDesc(t).name);
    for (const PassDesc& p : fx->techniqueDesc(t).passes) {
      ASSERT_LT(pass, passes.size()) << dump;
      EXPECT_EQ(passes[pass++], p.name);
    }
  }
  EXPECT_EQ(pass, passes.size());
}

INSTANTIATE_TEST_SUITE_P(Fx2, SampleEffect,
                         testing::Values("brdf.fx", "brdf_fixed.fx", "bump_earth.fx", "hemisphere.fx", "hlsl_ambient.fx",
                                         "hlsl_bump.fx", "hlsl_diffuse.fx", "hlsl_point_light.fx",
                                         "hlsl_self_shadow.fx", "hlsl_specular.fx", "paper_diffuse.fx",
                                         "paper_specular.fx", "racorx10.fx", "racorx6.fx", "racorx7.fx", "racorx8.fx",
                                         "racorx9.fx", "racorx_point_light.fx", "wood.fx"),
                         [](const testing::TestParamInfo<const char*>& i) {
                           std::string n = i.param;
                           return n.substr(0, n.find('.'));
                         });

// bump_earth.fx, written out by hand from its text: the parameters with their
// defaults and annotations, and the first pass's 49 states in source order with the
// operation numbers of the state table and the D3D values of the keywords.
TEST(Fx2MojoShader, BumpEarthStatesAsTheTextSays) {
  auto fx = load("bump_earth.fx");
  const std::string dump = parseInChild(writeFx2(*fx).bytes);
  ASSERT_EQ(dump.find("MojoShader crashed"), std::string::npos) << dump;
  const std::vector<std::string> p = lines(dump, 'P');
  ASSERT_EQ(p.size(), 6u) << dump;
  EXPECT_EQ(p[0], "vLightDir|3|1|1|4|0|LIGHTDIRECTION = 0 0 0 0 ");
  EXPECT_EQ(p[1], "dwAmbient|2|0|1|1|0| = " + std::to_string(int32_t(0xff202020u)) + " ");
  EXPECT_EQ(p[2].substr(0, p[2].find(" = ")), "EarthTexture|5|4|0|0|0|");
  EXPECT_EQ(p[5], "mEnvMap|3|2|4|4|0| = 0.5 0 0 0 0 -0.5 0 0 0 0 0 0 0.5 0.5 0 1 ");
  const std::vector<std::string> a = lines(dump, 'A');
  ASSERT_GE(a.size(), 3u);
  EXPECT_NE(a[0].find("ResourceName|4|4|"), std::string::npos) << a[0];
  EXPECT_NE(a[0].find("\"earth-color\""), std::string::npos) << a[0];

  // (operation, value as MojoShader prints it); "" = a parameter reference (zero
  // placeholder) or an object.
  const std::pair<int, std::string> pass0[] = {
      {146, "#"}, {147, "#"},  // VertexShader = NULL, PixelShader = NULL
      {0, "1 "},               // ZEnable = True
      {48, "1 "}, {53, "1 "},  // Lighting, NormalizeNormals
      {49, "0 "},              // Ambient = <dwAmbient>
      {132, "3 "},             // LightType[0] = Directional (D3DLIGHT_DIRECTIONAL)
      {137, "0 0 0 0 "},       // LightDirection[0] = <vLightDir>
      {133, "1 1 1 1 "}, {134, "0 0 0 0 "}, {135, "0 0 0 0 "},
      {145, "1 "},                                  // LightEnable[0] = True
      {127, "1 1 1 1 "}, {128, "1 1 1 1 "},         // MaterialDiffuse, MaterialAmbient
      {31, "3 "},                                   // Wrap0 = U | V
      {164, "#"}, {116, "0 "}, {103, "4 "},         // Texture[0], TexCoordIndex, ColorOp = Modulate
      {105, "2 "}, {106, "0 "},                     // ColorArg1 = Texture, ColorArg2 = Diffuse
      {170, "2 "}, {169, "2 "}, {171, "2 "},        // Min/Mag/MipFilter = Linear
      {164, "#"}, {116, "0 "}, {103, "22 "},        // ColorOp[1] = BumpEnvMap
      {105, "2 "}, {106, "1 "},                     // Texture, Current
      {112, "0.5 "}, {113, "0 "}, {114, "0 "}, {115, "0.5 "}, {117, "4 "}, {118, "0 "},
      {170, "2 "}, {169, "2 "}, {171, "0 "},        // MipFilter = None
      {164, "#"}, {116, "65536 "}, {119, "2 "},     // CameraSpaceNormal, Count2
      {126, "0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 "},    // TextureTransform[2] = <mEnvMap>
      {103, "7 "}, {105, "2 "}, {106, "1 "},        // Add, Texture, Current
      {170, "2 "}, {169, "2 "}, {171, "0 "},
      {103, "1 "}, {107, "1 "}};                    // ColorOp[3], AlphaOp[3] = Disable
  const std::vector<std::string> s = lines(dump, 'S');
  ASSERT_GE(s.size(), std::size(pass0)) << dump;
  for (size_t i = 0; i < std::size(pass0); ++i) {
    const auto& [op, value] = pass0[i];
    const std::string got = s[i];
    EXPECT_EQ(got.substr(0, got.find(" = ")), std::to_string(op)) << "state " << i << ": " << got;
    const std::string v = got.substr(got.find(" = ") + 3);
    if (value == "#") EXPECT_EQ(v.substr(0, 1), "#") << "state " << i << ": " << got;
    else EXPECT_EQ(v, value) << "state " << i << ": " << got;
  }
  // The pass's Texture[0] names its texture parameter (a usage-1 large object).
  EXPECT_NE(s[15].find("<EarthTexture>"), std::string::npos) << s[15];
  EXPECT_EQ(lines(dump, 'T'), (std::vector<std::string>{"BumpEnvMap", "NoBump"}));
}

// hlsl_diffuse.fx: three techniques of one pass, each a compiled vs_1_1 and a ps_2_0 /
// ps_1_4 / ps_1_1 pixel shader; MojoShader parses all six with their constant tables.
TEST(Fx2MojoShader, HlslDiffuseShaders) {
  auto fx = load("hlsl_diffuse.fx");
  const std::string dump = parseInChild(writeFx2(*fx).bytes);
  ASSERT_EQ(dump.find("MojoShader crashed"), std::string::npos) << dump;
  EXPECT_EQ(lines(dump, 'T'), (std::vector<std::string>{"Diffuse", "Diffuse_ps_1_4", "Diffuse_ps_1_1"}));
  EXPECT_EQ(lines(dump, 'p'), (std::vector<std::string>{"P0", "P0", "P0"}));
  const std::vector<std::string> s = lines(dump, 'S');
  ASSERT_EQ(s.size(), 6u) << dump;
  for (size_t i = 0; i < 6; ++i) EXPECT_EQ(s[i].substr(0, 3), i % 2 ? "147" : "146") << s[i];
  EXPECT_NE(dump.find("shaders 6 errors 0\n"), std::string::npos) << dump;
}

// MojoShader's preshader parser and VM run the FXLC blob of every state expression in
// the samples (its effect loader itself skips FXLC states, reference §7.2): inputs
// filled at the registers MojoShader read from the blob's CTAB, the outputs it
// computes equal refx's evaluation of the same blob.
std::string runWithMojoShader(const std::vector<uint32_t>& blob, const std::map<std::string, std::vector<float>>& values,
                              size_t components) {
  return inChild([&]() -> std::string {
    const MOJOSHADER_preshader* p = MOJOSHADER_parsePreshader(reinterpret_cast<const unsigned char*>(blob.data()),
                                                              unsigned(blob.size() * 4), nullptr, nullptr, nullptr);
    if (!p) return "parse failed\n";
    for (unsigned i = 0; i < p->symbol_count; ++i) {
      const MOJOSHADER_symbol& sym = p->symbols[i];
      const std::vector<float>& v = values.at(sym.name);
      for (size_t k = 0; k < v.size() && k < size_t(sym.register_count) * 4; ++k)
        p->registers[size_t(sym.register_index) * 4 + k] = v[k];
    }
    std::vector<float> out(4096, -12345.0f);
    MOJOSHADER_runPreshader(p, out.data());
    std::string s;
    for (size_t i = 0; i < components; ++i) s += std::to_string(out[i]) + " ";
    return s + "\n";
  });
}

class ExpressionEffect : public testing::TestWithParam<const char*> {};

TEST_P(ExpressionEffect, MojoShaderRunsTheFxlcStates) {
  auto fx = load(GetParam());
  const detail::EffectContents contents = detail::EffectAccess::contents(*fx);
  int expressions = 0;
  for (const auto& t : contents.techniques)
    for (const auto& pass : t.passes)
      for (const detail::StateContents& s : pass.states) {
        if (s.kind != detail::StateContents::Kind::Expression) continue;
        ++expressions;
        ASSERT_TRUE(s.fxlc) << s.name << ": " << s.fxlcError;
        // Input values: each parameter's current value in the register layout its
        // CTAB entry gives (rows of MATRIX_ROWS matrices in consecutive registers).
        std::map<std::string, std::vector<float>> values;
        std::vector<float> inputs;
        for (const shader::ShaderConstant& c : s.fxlc->inputs.constants) {
          const std::vector<float> v = fx->getFloatArray(fx->parameterByName(c.name));
          std::vector<float> regs(size_t(c.registerCount) * 4, 0.0f);
          for (size_t i = 0; i < v.size(); ++i) regs[(i / size_t(c.columns)) * 4 + i % size_t(c.columns)] = v[i];
          values[c.name] = regs;
          inputs.resize(size_t(c.registerIndex + c.registerCount) * 4, 0.0f);
          std::copy(regs.begin(), regs.end(), inputs.begin() + c.registerIndex * 4);
        }
        const std::vector<uint32_t> blob = detail::encodeFxlc(*s.fxlc, detail::kFxlcStandaloneVersion, false);
        const std::vector<float> ours = s.fxlc->run(inputs);
        std::string want;
        for (int i = 0; i < s.fxlcComponents; ++i) want += std::to_string(ours[size_t(i)]) + " ";
        EXPECT_EQ(runWithMojoShader(blob, values, size_t(s.fxlcComponents)), want + "\n")
            << s.name << "[" << s.index << "]\n" << s.fxlc->listing();
      }
  EXPECT_GT(expressions, 0);
}

INSTANTIATE_TEST_SUITE_P(Fx2, ExpressionEffect,
                         testing::Values("hemisphere.fx", "paper_diffuse.fx", "racorx10.fx", "racorx_point_light.fx"),
                         [](const testing::TestParamInfo<const char*>& i) {
                           std::string n = i.param;
                           return n.substr(0, n.find('.'));
                         });

// -vLightPos with vLightPos = (0.9, 0.8, -1.6, 1) (racorx10.fx): MojoShader computes
// (-0.9, -0.8, 1.6, -1).
TEST(Fx2MojoShader, NegatedLightPositionByHand) {
  auto fx = load("racorx10.fx");
  const detail::EffectContents contents = detail::EffectAccess::contents(*fx);
  const detail::StateContents* found = nullptr;
  for (const auto& t : contents.techniques)
    for (const auto& pass : t.passes)
      for (const auto& s : pass.states)
        if (s.kind == detail::StateContents::Kind::Expression && s.index == 12) found = &s;
  ASSERT_TRUE(found && found->fxlc);
  const std::vector<uint32_t> blob = detail::encodeFxlc(*found->fxlc, detail::kFxlcStandaloneVersion, false);
  EXPECT_EQ(runWithMojoShader(blob, {{"vLightPos", {0.9f, 0.8f, -1.6f, 1}}}, 4),
            std::to_string(-0.9f) + " " + std::to_string(-0.8f) + " " + std::to_string(1.6f) + " " +
                std::to_string(-1.0f) + " \n");
}

// Compiled shaders' preshaders (PRES comments): MojoShader's shader parser reads the
// preshader of every sample shader that has one, and its VM computes the same output
// registers as refx's preshader (hlsl::Preshader::run) from the same inputs.
int checkPreshaders(const Effect& effect) {
  const Effect* fx = &effect;
  const detail::EffectContents contents = detail::EffectAccess::contents(*fx);
  std::set<const detail::ShaderContents*> seen;
  int checked = 0;
  for (const auto& t : contents.techniques)
    for (const auto& pass : t.passes)
      for (const detail::StateContents& s : pass.states) {
        if (s.kind != detail::StateContents::Kind::Shader || !s.shader->preshader || !seen.insert(s.shader.get()).second)
          continue;
        const hlsl::Preshader& pre = *s.shader->preshader;
        const std::vector<uint32_t> tokens = detail::withPresComment(s.shader->tokens, detail::fxlcFromPreshader(pre));
        // Inputs: component k of input register r is 0.37 * (4r + k + 1) - 1.5.
        std::vector<float> inputs;
        for (const shader::ShaderConstant& c : pre.inputs.constants)
          inputs.resize(std::max(inputs.size(), size_t(c.registerIndex + c.registerCount) * 4), 0.0f);
        for (size_t i = 0; i < inputs.size(); ++i) inputs[i] = 0.37f * float(i + 1) - 1.5f;
        const std::vector<float> ours = pre.run(inputs);
        std::string want;
        for (size_t i = 0; i < pre.outputRegisters.size(); ++i) {
          want += "c" + std::to_string(pre.outputRegisters[i]);
          for (int k = 0; k < 4; ++k) want += " " + std::to_string(ours[4 * i + size_t(k)]);
          want += "\n";
        }
        const std::string got = inChild([&]() -> std::string {
          const MOJOSHADER_parseData* pd =
              MOJOSHADER_parse(MOJOSHADER_PROFILE_BYTECODE, "main", reinterpret_cast<const unsigned char*>(tokens.data()),
                               unsigned(tokens.size() * 4), nullptr, 0, nullptr, 0, nullptr, nullptr, nullptr);
          if (pd->error_count) return std::string("parse error: ") + pd->errors[0].error + "\n";
          if (!pd->preshader) return "no preshader\n";
          const MOJOSHADER_preshader* p = pd->preshader;
          for (unsigned i = 0; i < p->symbol_count; ++i) {
            const MOJOSHADER_symbol& sym = p->symbols[i];
            for (unsigned k = 0; k < sym.register_count * 4; ++k) {
              const size_t at = size_t(sym.register_index) * 4 + k;
              if (at < size_t(p->register_count) * 4 && at < inputs.size()) p->registers[at] = inputs[at];
            }
          }
          std::vector<float> out(4 * 8192, 0.0f);
          MOJOSHADER_runPreshader(p, out.data());
          std::string text;
          for (int reg : pre.outputRegisters) {
            text += "c" + std::to_string(reg);
            for (int k = 0; k < 4; ++k) text += " " + std::to_string(out[size_t(reg) * 4 + size_t(k)]);
            text += "\n";
          }
          return text;
        });
        // The same registers, values within float rounding (refx's preshader computes in
        // float, MojoShader's VM in double).
        std::istringstream g(got), w(want);
        std::string a, b;
        size_t values = 0;
        while (w >> b) {
          if (!(g >> a)) {
            ADD_FAILURE() << got;
            break;
          }
          if (b[0] == 'c') {
            EXPECT_EQ(a, b) << got;
            continue;
          }
          const double x = std::stod(a), y = std::stod(b);
          EXPECT_NEAR(x, y, 1e-5 * std::max(1.0, std::fabs(y))) << s.name << " " << s.shader->profile << " " << s.shader->entry << "\n" << got;
          ++values;
        }
        EXPECT_EQ(values, pre.outputRegisters.size() * 4);
        ++checked;
      }
  (void)fx;
  return checked;
}

// wood.fx: the one sample whose shaders have a preshader.
TEST(Fx2MojoShader, WoodPreshaderRunsInMojoShader) { EXPECT_GT(checkPreshaders(*load("wood.fx")), 0); }

// Preshaders with the operations the FXLC translation uses (mul, add, rcp for
// division, min/max for saturate, lt/ge, cmp, frc, rsq for normalize, sin/cos, dot as
// mul + add, cross). exp/log (pow) are left out: MojoShader computes e^x and ln x
// where D3DX computes 2^x and log2 x (reference §5.6).
TEST(Fx2MojoShader, PreshaderOperationsRunInMojoShader) {
  const char* text =
      "float4 a = {0.5, -0.25, 2, 1};\n"
      "float4 b = {1, 3, -2, 0.5};\n"
      "float3 n = {1, 2, 2};\n"
      "float k = 0.3;\n"
      "float4 PS(float4 t : TEXCOORD0) : COLOR {\n"
      "  float4 x = saturate(a * b + k) + a / b.y + lerp(a, b, k) + frac(b * 1.7);\n"
      "  float3 m = normalize(n) + cross(a.xyz, b.xyz) + dot(a, b);\n"
      "  float s = sin(k) + cos(k) + (k < 0.5 ? 1 : 0) + max(a.x, b.x) + min(a.y, b.y);\n"
      "  return t * x + float4(m, s);\n"
      "}\n"
      "technique T { pass P { PixelShader = compile ps_2_0 PS(); } }\n";
  auto fx = Effect::fromText(text, "ops.fx");
  EXPECT_GT(checkPreshaders(*fx), 0);
}

}  // namespace
}  // namespace refx::effect
