// Parsing of .shader_test files: sections, qualifiers, uniform offsets, probe forms
// and line prefixes. Expected values are read off the text by hand.
#include <gtest/gtest.h>

#include <bit>
#include <string>

#include "refx/core/diagnostics.h"
#include "refx/scene/shader_test.h"

using namespace refx;
using namespace refx::scene;

namespace {

// A copy, so that `const auto& x = body<T>(parseTestCommand(...))` stays valid.
template <typename T>
T body(const TestCommand& c) {
  const T* b = std::get_if<T>(&c.body);
  if (!b) {
    ADD_FAILURE() << "line '" << c.text << "' parsed to variant index " << c.body.index();
    return T{};
  }
  return *b;
}

std::string errorOf(const std::string& text) {
  try {
    parseShaderTest(text, "t.shader_test");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(ShaderTestParse, SectionsInOrderWithTheirLines) {
  const ShaderTestFile f = parseShaderTest(
      "% comment\n"
      "[require]\n"            // 2
      "shader model >= 3.0\n"
      "\n"
      "[pixel shader]\n"       // 5
      "float4 main() : sv_target { return 1; }\n"
      "[test]\n"               // 7
      "draw quad\n",
      "t.shader_test");
  ASSERT_EQ(f.sections.size(), 3u);
  EXPECT_EQ(f.sections[0].line, 2);
  EXPECT_EQ(std::get<RequireSection>(f.sections[0].section).minModel, 30);
  const auto& ps = std::get<ShaderSection>(f.sections[1].section);
  EXPECT_EQ(f.sections[1].line, 5);
  EXPECT_EQ(ps.stage, ShaderStage::Pixel);
  EXPECT_EQ(ps.source, ShaderSource::Hlsl);
  EXPECT_EQ(ps.bodyLine, 6);
  EXPECT_EQ(ps.text, "float4 main() : sv_target { return 1; }\n");
  const auto& t = std::get<TestSection>(f.sections[2].section);
  ASSERT_EQ(t.commands.size(), 1u);
  EXPECT_EQ(t.commands[0].line, 8);
  EXPECT_TRUE(body<DrawCommand>(t.commands[0]).quad);
}

TEST(ShaderTestParse, ShaderSectionQualifiers) {
  const ShaderTestFile f = parseShaderTest(
      "[pixel shader fail(sm<3)]\n"
      "[vertex shader notimpl todo(sm>=4)]\n"
      "[pixel shader d3dbc-hex]\n"
      "[effect fail]\n"
      "[compute shader]\n",
      "t.shader_test");
  ASSERT_EQ(f.sections.size(), 5u);
  const auto& a = std::get<ShaderSection>(f.sections[0].section);
  ASSERT_TRUE(a.fail.has_value());
  EXPECT_TRUE(a.fail->holds(20));   // 2.0 < 3
  EXPECT_FALSE(a.fail->holds(30));
  EXPECT_FALSE(a.notimpl.has_value());
  const auto& b = std::get<ShaderSection>(f.sections[1].section);
  EXPECT_EQ(b.stage, ShaderStage::Vertex);
  ASSERT_TRUE(b.notimpl && b.todo);
  EXPECT_TRUE(b.notimpl->holds(20));  // no parentheses: always
  EXPECT_FALSE(b.todo->holds(30));
  EXPECT_TRUE(b.todo->holds(41));
  EXPECT_EQ(std::get<ShaderSection>(f.sections[2].section).source, ShaderSource::D3dbcHex);
  EXPECT_EQ(std::get<ShaderSection>(f.sections[3].section).stage, ShaderStage::Effect);
  EXPECT_EQ(std::get<ShaderSection>(f.sections[4].section).stage, ShaderStage::Unsupported);
}

TEST(ShaderTestParse, Conditions) {
  // (sm>=3 & !glsl) | msl: at 2.0 neither side holds; at 3.0 the left one does.
  const Condition c = parseCondition("sm>=3 & !glsl | msl");
  EXPECT_FALSE(c.holds(20));
  EXPECT_TRUE(c.holds(30));
  EXPECT_TRUE(parseCondition("d3d9").holds(20));
  EXPECT_FALSE(parseCondition("glsl").holds(20));
  EXPECT_FALSE(parseCondition("mesa<23.3").holds(20));  // a versioned tag that is absent
  EXPECT_TRUE(parseCondition("sm<4.1").holds(40));
  EXPECT_FALSE(parseCondition("sm<4.1").holds(41));
  EXPECT_TRUE(parseCondition("!sm>=4").holds(30));
  EXPECT_THROW(parseCondition("sm>=three"), Error);
  EXPECT_THROW(parseCondition("nosuchtag"), Error);
}

TEST(ShaderTestParse, UniformOffsetsCountWords) {
  // `uniform 6 float4` starts at c1.z: word 6 = 4 * 1 + 2.
  const TestCommand c = parseTestCommand("uniform 6 float4 1.0 2.5 -3 0x1p2", 3);
  const auto& u = body<UniformCommand>(c);
  EXPECT_EQ(u.offset, 6);
  EXPECT_EQ(u.type, UniformCommand::Type::Float4);
  EXPECT_EQ(u.floats, (std::vector<float>{1.0f, 2.5f, -3.0f, 4.0f}));
  const auto& i = body<UniformCommand>(parseTestCommand("uniform 8 int4 -1 2 0x10 4"));
  EXPECT_EQ(i.ints, (std::vector<int64_t>{-1, 2, 16, 4}));
  const auto& s = body<UniformCommand>(parseTestCommand("uniform 1 uint 4294967295"));
  EXPECT_EQ(s.type, UniformCommand::Type::Uint);
  EXPECT_EQ(s.ints, (std::vector<int64_t>{4294967295}));
  // `float` must not swallow the 4 of float4 and vice versa.
  EXPECT_EQ(body<UniformCommand>(parseTestCommand("uniform 0 float 0.5")).floats.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<MalformedCommand>(parseTestCommand("uniform 0 float4 1 2 3").body));
  EXPECT_TRUE(std::holds_alternative<UnknownCommand>(parseTestCommand("uniform 0 double2 1 2").body));
}

TEST(ShaderTestParse, ProbeForms) {
  const auto& a = body<ProbeCommand>(parseTestCommand("probe (3, 4) rgba(0.1, 0.2, 0.3, 0.4)"));
  EXPECT_EQ(a.left, 3);
  EXPECT_EQ(a.top, 4);
  EXPECT_EQ(a.right, 4);
  EXPECT_EQ(a.bottom, 5);
  EXPECT_EQ(a.count, 4);
  EXPECT_FLOAT_EQ(a.floats[3], 0.4f);
  EXPECT_EQ(a.ulps, 0u);

  const auto& b = body<ProbeCommand>(parseTestCommand("probe (10, 20, 30, 40) rgba (1, 0, 0, 1) 4"));
  EXPECT_EQ(b.right, 30);  // right/bottom, exclusive
  EXPECT_EQ(b.bottom, 40);
  EXPECT_EQ(b.ulps, 4u);

  // Older form: rect is x, y, width, height.
  const auto& c = body<ProbeCommand>(parseTestCommand("probe rect rgba (10, 20, 5, 6) (0.5, 0.5, 0.5, 0.5)"));
  EXPECT_EQ(c.left, 10);
  EXPECT_EQ(c.right, 15);
  EXPECT_EQ(c.bottom, 26);

  EXPECT_TRUE(body<ProbeCommand>(parseTestCommand("probe all rgba (0, 0, 0, 0)")).all);
  const auto& d = body<ProbeCommand>(parseTestCommand("probe rgba (7, 9) (1, 2, 3, 4)"));
  EXPECT_EQ(d.left, 7);
  EXPECT_EQ(d.top, 9);
  EXPECT_FLOAT_EQ(d.floats[2], 3.0f);

  const auto& e = body<ProbeCommand>(parseTestCommand("probe (5) r(0.25) 2"));
  EXPECT_EQ(e.left, 5);
  EXPECT_EQ(e.top, 0);
  EXPECT_EQ(e.count, 1);
  EXPECT_EQ(e.ulps, 2u);

  const auto& f = body<ProbeCommand>(parseTestCommand("probe rtv-0 (1, 2) f32(0.5, 1.5)"));
  EXPECT_EQ(f.count, 2);
  const auto& g = body<ProbeCommand>(parseTestCommand("probe (0, 0) u32(0x3f800000, 0, 0, 1)"));
  EXPECT_EQ(g.kind, ProbeCommand::Kind::Uint);
  EXPECT_EQ(g.ints[0], 0x3f800000);
  EXPECT_EQ(body<ProbeCommand>(parseTestCommand("probe (0, 0) rgbai(-1, 0, 0, 1)")).kind, ProbeCommand::Kind::Int);

  EXPECT_TRUE(std::holds_alternative<MalformedCommand>(parseTestCommand("probe (1, 2) rgba(1, 2, 3)").body));
  EXPECT_TRUE(std::holds_alternative<MalformedCommand>(parseTestCommand("probe (1, 2)").body));
  EXPECT_TRUE(std::holds_alternative<MalformedCommand>(parseTestCommand("probe (5, 5, 2, 2) r(0)").body));
  EXPECT_TRUE(std::holds_alternative<UnknownCommand>(parseTestCommand("probe uav 1 (0, 0) r(0)").body));
}

TEST(ShaderTestParse, LinePrefixes) {
  const TestCommand a = parseTestCommand("todo(sm<4) if(sm>=3) probe (0, 0) rgba(1, 1, 1, 1)", 12);
  EXPECT_EQ(a.line, 12);
  EXPECT_TRUE(a.todo);
  EXPECT_FALSE(a.bug);
  ASSERT_EQ(a.onlyIf.size(), 1u);
  EXPECT_FALSE(a.onlyIf[0].holds(20));
  EXPECT_TRUE(a.onlyIf[0].holds(30));
  EXPECT_TRUE(std::holds_alternative<ProbeCommand>(a.body));

  const TestCommand b = parseTestCommand("bug(glsl) draw quad");
  EXPECT_TRUE(b.bug);
  EXPECT_TRUE(b.onlyIf.empty());
  EXPECT_TRUE(std::holds_alternative<DrawCommand>(b.body));

  EXPECT_TRUE(std::holds_alternative<MalformedCommand>(parseTestCommand("if draw quad").body));
  EXPECT_TRUE(std::holds_alternative<MalformedCommand>(parseTestCommand("if(sm>=) draw quad").body));
}

TEST(ShaderTestParse, OtherTestLines) {
  const auto& d = body<DrawCommand>(parseTestCommand("draw triangle strip 4"));
  EXPECT_FALSE(d.quad);
  EXPECT_EQ(d.topology, Topology::TriangleStrip);
  EXPECT_EQ(d.vertexCount, 4);
  const auto& c = body<ClearCommand>(parseTestCommand("clear rtv 0 0.25 0.5 0.75 1"));
  EXPECT_FLOAT_EQ(c.color[1], 0.5f);
  EXPECT_FLOAT_EQ(body<ClearCommand>(parseTestCommand("clear rtv-0 f32(1, 0, 0, 0.5)")).color[3], 0.5f);
  const auto& a = body<AlphaTestCommand>(parseTestCommand("alpha test greater equal 0.5"));
  EXPECT_EQ(a.func, 7u);  // D3DCMP_GREATEREQUAL
  EXPECT_FLOAT_EQ(a.reference, 0.5f);
  EXPECT_TRUE(body<ShadeModeCommand>(parseTestCommand("shade mode flat")).flat);
  const auto& fog = body<FogCommand>(parseTestCommand("fog linear ortho 0.25 0.75"));
  EXPECT_EQ(fog.mode, FogCommand::Mode::Linear);
  EXPECT_FLOAT_EQ(fog.end, 0.75f);
  EXPECT_FLOAT_EQ(body<FogColorCommand>(parseTestCommand("fog-colour 0 1 0 1")).color[1], 1.0f);
  const TestCommand u = parseTestCommand("dispatch 1 1 1");
  EXPECT_EQ(body<UnknownCommand>(u).text, "dispatch 1 1 1");
}

TEST(ShaderTestParse, ResourcesSamplersAndLayout) {
  const ShaderTestFile f = parseShaderTest(
      "[srv 1]\n"
      "size (2d, 2, 1)\n"
      "levels 1\n"
      "1.0 0.5 0 0x3f800000\n"
      "[texture 0]\n"
      "size (1, 1)\n"
      "1 2 3 4\n"
      "[sampler 2]\n"
      "filter linear point linear\n"
      "address wrap mirror border\n"
      "[input layout]\n"
      "0 r32g32-float position\n"
      "1 r32g32b32a32-float texcoord 2\n"
      "[rtv 0]\n"
      "format r32g32b32a32-uint\n"
      "size (2d, 64, 32)\n",
      "t.shader_test");
  ASSERT_EQ(f.sections.size(), 5u);
  const auto& srv = std::get<ResourceSection>(f.sections[0].section);
  EXPECT_EQ(srv.kind, ResourceSection::Kind::Texture);
  EXPECT_EQ(srv.slot, 1);
  EXPECT_EQ(srv.width, 2);
  // Floats need a '.', other numbers are raw words: 0 and 0x3f800000 (= 1.0f).
  EXPECT_EQ(srv.data, (std::vector<uint32_t>{0x3f800000u, 0x3f000000u, 0u, 0x3f800000u}));
  const auto& tex = std::get<ResourceSection>(f.sections[1].section);
  // The older [texture] sections read every number as a float.
  EXPECT_EQ(tex.data[1], std::bit_cast<uint32_t>(2.0f));
  const auto& s = std::get<SamplerSection>(f.sections[2].section);
  EXPECT_EQ(s.slot, 2);
  EXPECT_EQ(s.minFilter, FilterMode::Linear);
  EXPECT_EQ(s.magFilter, FilterMode::Point);
  EXPECT_EQ(s.address[1], AddressMode::Mirror);
  EXPECT_EQ(s.address[2], AddressMode::Border);
  const auto& l = std::get<InputLayoutSection>(f.sections[3].section);
  ASSERT_EQ(l.elements.size(), 2u);
  EXPECT_EQ(l.elements[0].format, ElementFormat::Float2);
  EXPECT_EQ(l.elements[1].semantic, "texcoord");
  EXPECT_EQ(l.elements[1].semanticIndex, 2);
  const auto& rtv = std::get<ResourceSection>(f.sections[4].section);
  EXPECT_EQ(rtv.kind, ResourceSection::Kind::RenderTarget);
  EXPECT_EQ(rtv.format, ElementFormat::Unsupported);
  EXPECT_EQ(rtv.height, 32);
}

TEST(ShaderTestParse, RequireAndModelChoice) {
  auto model = [](const char* text) { return chooseShaderModel(parseShaderTest(text, "t")); };
  EXPECT_EQ(model("[test]\ndraw quad\n"), 20);
  EXPECT_EQ(model("[require]\nshader model >= 3.0\n"), 30);
  EXPECT_EQ(model("[require]\nshader model >= 4.0\n"), std::nullopt);
  EXPECT_EQ(model("[require]\nshader model < 3.0\n"), 20);
  // Two sections: the lowest model either allows.
  EXPECT_EQ(model("[require]\nshader model >= 4.0\n[require]\nshader model >= 3.0\n"), 30);

  const ShaderTestFile f = parseShaderTest(
      "[require]\nshader model >= 2.0\nshader model < 6.0\noptions: row-major backcompat\nfloat64\nfog\n", "t");
  const auto& r = std::get<RequireSection>(f.sections[0].section);
  EXPECT_EQ(r.minModel, 20);
  EXPECT_EQ(r.belowModel, 60);
  EXPECT_TRUE(r.rowMajor);
  EXPECT_TRUE(r.backCompat);
  EXPECT_EQ(r.missingCaps, (std::vector<std::string>{"float64"}));  // fog is supported
}

TEST(ShaderTestParse, ErrorsNameFileAndLine) {
  EXPECT_EQ(errorOf("[test]\ndraw quad\n[nonsense]\n"), "t.shader_test:3: error: unknown section '[nonsense]'");
  EXPECT_EQ(errorOf("draw quad\n"), "t.shader_test:1: error: 'draw quad' before the first [section]");
  EXPECT_EQ(errorOf("[require]\nshader model >= x\n"),
            "t.shader_test:2: error: expected a shader model such as 3.0 in 'shader model >= x'");
  EXPECT_EQ(errorOf("[sampler 0]\nfilter bilinear\n"),
            "t.shader_test:2: error: expected 'filter MIN MAG MIP' with point or linear");
  EXPECT_EQ(errorOf("[srv 0]\nsize (2d, 0, 1)\n"),
            "t.shader_test:2: error: malformed size 'size (2d, 0, 1)' (1 to 8192 each)");
  EXPECT_EQ(errorOf("[pixel shader fail(sm<<3)]\n").substr(0, 20), "t.shader_test:1: err");
  EXPECT_EQ(errorOf("[test\n"), "t.shader_test:1: error: expected ']' to close '[test'");
}

TEST(ShaderTestRun, SkipsFilesOutsideShaderModel2And3) {
  const ShaderTestResult r = runShaderTest(parseShaderTest("[require]\nshader model >= 4.0\n[test]\ndraw quad\n", "t"));
  EXPECT_EQ(r.status, ShaderTestResult::Status::Skipped);
  EXPECT_EQ(r.skipReason, "requires shader model >= 4.0");
}

TEST(ShaderTestRun, UnknownLinesFailNamingTheLine) {
  const ShaderTestResult r = runShaderTest(parseShaderTest("[test]\nclear rtv 0 0 0 0 0\nfrobnicate 3\n", "t"));
  ASSERT_EQ(r.status, ShaderTestResult::Status::Failed);
  ASSERT_EQ(r.failures.size(), 1u);
  EXPECT_EQ(r.failures[0].line, 3);
  EXPECT_EQ(r.failures[0].message, "unsupported test line: frobnicate 3");
}

// The compilations the runner makes: HLSL shader sections switched on by the [require]
// sections before them, up to the first section a D3D9 device cannot run.
TEST(ShaderTestRun, ListsTheShadersItCompiles) {
  const ShaderTestFile f = parseShaderTest(
      "[vertex shader]\n"                           // 1: vs_2_0
      "float4 main(float4 p : POSITION) : POSITION { return p; }\n"
      "[pixel shader fail(sm<3)]\n"                 // 3: must fail at 2.0
      "float4 main() : COLOR { return 1; }\n"
      "[require]\n"                                 // 5
      "shader model >= 4.0\n"
      "[pixel shader]\n"                            // 7: off (4.0)
      "float4 main() : SV_Target { return 2; }\n"
      "[require]\n"                                 // 9
      "shader model >= 2.0\n"
      "options: row-major\n"
      "[pixel shader d3dbc-hex]\n"                  // 12: not HLSL
      "ffff0200 0000ffff\n"
      "[pixel shader notimpl]\n"                    // 14: row-major, not implemented
      "float4 main() : COLOR { return 3; }\n"
      "[compute shader]\n"                          // 16: ends the file
      "void main() {}\n"
      "[pixel shader]\n"                            // 18: never reached
      "float4 main() : COLOR { return 4; }\n",
      "t.shader_test");
  const std::vector<ShaderCompilation> c = listShaderCompilations(f);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0].line, 1);
  EXPECT_EQ(c[0].options.profile, "vs_2_0");
  EXPECT_FALSE(c[0].mustFail);
  EXPECT_EQ(c[0].source, "\nfloat4 main(float4 p : POSITION) : POSITION { return p; }\n");
  EXPECT_EQ(c[1].line, 3);
  EXPECT_EQ(c[1].options.profile, "ps_2_0");
  EXPECT_TRUE(c[1].mustFail);
  EXPECT_FALSE(c[1].options.rowMajorDefault);
  EXPECT_EQ(c[2].line, 14);
  EXPECT_TRUE(c[2].notImplemented);
  EXPECT_TRUE(c[2].options.rowMajorDefault);
  EXPECT_EQ(c[2].section, &std::get<ShaderSection>(f.sections[6].section));

  // A file only shader model 3.0 runs compiles for vs_3_0 / ps_3_0.
  const ShaderTestFile sm3 = parseShaderTest(
      "[require]\nshader model >= 3.0\n[pixel shader]\nfloat4 main() : COLOR { return 1; }\n", "t");
  const std::vector<ShaderCompilation> c3 = listShaderCompilations(sm3);
  ASSERT_EQ(c3.size(), 1u);
  EXPECT_EQ(c3[0].options.profile, "ps_3_0");
  EXPECT_TRUE(listShaderCompilations(parseShaderTest("[require]\nshader model >= 4.0\n[pixel shader]\nx\n", "t")).empty());
}
