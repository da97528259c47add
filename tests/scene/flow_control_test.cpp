// [loop] and [branch] as real flow control: which instructions each profile gets
// (rep/defi, rep i#, if_comp, if b#, break_comp), what happens on profiles without
// them (a warning, then unrolled or flattened; an error naming the profile when that
// is impossible), and a vs_2_0 program run on the interpreter.
#include <gtest/gtest.h>

#include <regex>

#include "exec/shader_probe.h"
#include "refx/hlsl/compiler.h"
#include "refx/shader/disassembler.h"

namespace refx {
namespace {

using shader::Opcode;

hlsl::CompileResult compile(const std::string& source, const char* profile) {
  hlsl::CompileOptions o;
  o.profile = profile;
  o.entry = "main";
  return hlsl::compile(source, "flow.hlsl", o);
}

int count(const hlsl::CompileResult& r, Opcode op) {
  int n = 0;
  for (const shader::Instruction& in : r.shader.instructions) n += in.opcode == op;
  return n;
}

const shader::Instruction* find(const hlsl::CompileResult& r, Opcode op) {
  for (const shader::Instruction& in : r.shader.instructions)
    if (in.opcode == op) return &in;
  return nullptr;
}

std::string listing(const hlsl::CompileResult& r) {
  shader::DisassemblyOptions o;
  o.listing = true;
  return shader::disassemble(r.shader, o);
}

const Diagnostic* diagnostic(const hlsl::CompileResult& r, const char* code) {
  for (const Diagnostic& d : r.diagnostics)
    if (d.code == code) return &d;
  return nullptr;
}

// The accumulation runs once per iteration in a rep body: one add, not four.
const char* kLoop = R"(
float4 k;
float4 main(float4 t : TEXCOORD0) : COLOR
{
    float4 sum = 0;
    [loop] for (int i = 0; i < 4; ++i)
        sum += t * k;
    return sum;
}
)";

TEST(HlslFlowControl, LoopWithLiteralTripCountIsRep) {
  for (const char* profile : {"ps_2_x", "ps_3_0"}) {
    hlsl::CompileResult r = compile(kLoop, profile);
    ASSERT_TRUE(r.ok()) << profile << "\n" << r.messages();
    EXPECT_EQ(count(r, Opcode::Rep), 1) << profile;
    EXPECT_EQ(count(r, Opcode::EndRep), 1) << profile;
    EXPECT_EQ(count(r, Opcode::Mad), 1) << profile << "\n" << listing(r);
    const shader::Instruction* defi = find(r, Opcode::DefI);
    ASSERT_NE(defi, nullptr) << profile;
    EXPECT_EQ(defi->literal[0], 4u);  // rep reads the count from i#.x
    const shader::Instruction* rep = find(r, Opcode::Rep);
    EXPECT_EQ(rep->src[0].type, shader::RegType::ConstInt);
    EXPECT_EQ(rep->src[0].index, defi->dst.index);
    // as the disassembler lists it: defi i0, 4, … then rep i0 … endrep
    std::string text = shader::disassemble(r.shader);
    EXPECT_TRUE(std::regex_search(text, std::regex(R"(defi i0, 4, 0, 0, 0\n(.*\n)*rep i0\n(.*\n)*endrep)"))) << text;
  }
  // Without the attribute the loop unrolls: four mads, no rep.
  std::string unrolled = std::regex_replace(kLoop, std::regex(R"(\[loop\] )"), "");
  hlsl::CompileResult u = compile(unrolled, "ps_3_0");
  ASSERT_TRUE(u.ok()) << u.messages();
  EXPECT_EQ(count(u, Opcode::Rep), 0);
  EXPECT_EQ(count(u, Opcode::Mad) + count(u, Opcode::Add) + count(u, Opcode::Mul), 4) << listing(u);
}

TEST(HlslFlowControl, UniformIntTripCountIsAnIntRegister) {
  const char* src = R"(
int n;
float4 main() : COLOR
{
    float4 r = 0;
    [loop] for (int i = 0; i < n; i++)
        r += 0.25;
    return r;
}
)";
  hlsl::CompileResult r = compile(src, "ps_3_0");
  ASSERT_TRUE(r.ok()) << r.messages();
  const shader::Instruction* rep = find(r, Opcode::Rep);
  ASSERT_NE(rep, nullptr) << listing(r);
  EXPECT_EQ(rep->src[0].type, shader::RegType::ConstInt);
  EXPECT_EQ(rep->src[0].index, 0);
  EXPECT_EQ(count(r, Opcode::DefI), 0);  // i0 comes from the application
  // the constant table lists n in the int register set: "n    i0       1"
  EXPECT_TRUE(std::regex_search(listing(r), std::regex(R"(//   n +i0 +1\n)"))) << listing(r);
}

TEST(HlslFlowControl, BranchIsIfCompElseEndif) {
  const char* src = R"(
float4 main(float4 t : TEXCOORD0) : COLOR
{
    float4 r = 0;
    [branch] if (t.x > 0.5)
        r.x = 1;
    else
        r.y = 1;
    return r;
}
)";
  for (const char* profile : {"ps_2_x", "ps_3_0"}) {
    hlsl::CompileResult r = compile(src, profile);
    ASSERT_TRUE(r.ok()) << profile << "\n" << r.messages();
    const shader::Instruction* ifc = find(r, Opcode::IfC);
    ASSERT_NE(ifc, nullptr) << profile << "\n" << listing(r);
    EXPECT_EQ(ifc->comparison(), shader::Comparison::Gt);
    EXPECT_EQ(count(r, Opcode::Else), 1);
    EXPECT_EQ(count(r, Opcode::EndIf), 1);
    EXPECT_EQ(count(r, Opcode::Cmp), 0) << "flattened:\n" << listing(r);
    std::string text = shader::disassemble(r.shader);
    EXPECT_TRUE(std::regex_search(text, std::regex(R"(if_gt [rtv]0\.x, c0\.\w\n(.*\n)*else\n(.*\n)*endif)"))) << text;
  }
}

TEST(HlslFlowControl, BoolUniformBranchIsIfB) {
  const char* src = R"(
bool b;
float4 main(float4 t : TEXCOORD0) : COLOR
{
    float4 r = t;
    [branch] if (b) r.x = 1;
    [branch] if (!b) r.y = 0;
    return r;
}
)";
  for (const char* profile : {"ps_2_x", "ps_3_0"}) {
    hlsl::CompileResult r = compile(src, profile);
    ASSERT_TRUE(r.ok()) << profile << "\n" << r.messages();
    EXPECT_EQ(count(r, Opcode::If), 2) << listing(r);
    EXPECT_EQ(count(r, Opcode::IfC), 0);
    int negated = 0;
    for (const shader::Instruction& in : r.shader.instructions)
      if (in.opcode == Opcode::If) {
        EXPECT_EQ(in.src[0].type, shader::RegType::ConstBool);
        EXPECT_EQ(in.src[0].index, 0);
        negated += in.src[0].mod == shader::SrcMod::Not;
      }
    EXPECT_EQ(negated, 1);
    std::string text = shader::disassemble(r.shader);
    EXPECT_NE(text.find("if b0\n"), std::string::npos) << text;
    EXPECT_NE(text.find("if !b0\n"), std::string::npos) << text;
    EXPECT_TRUE(std::regex_search(listing(r), std::regex(R"(//   b +b0 +1\n)"))) << listing(r);
  }
  // vs_2_0 has if b# (static flow control) but no if_comp
  const char* vs = R"(
bool b;
void main(float4 p : POSITION, out float4 o : POSITION)
{
    o = p;
    [branch] if (b) o.x = 0;
}
)";
  hlsl::CompileResult r = compile(vs, "vs_2_0");
  ASSERT_TRUE(r.ok()) << r.messages();
  EXPECT_EQ(count(r, Opcode::If), 1) << listing(r);
}

TEST(HlslFlowControl, BreakIsBreakComp) {
  const char* src = R"(
float t;
float4 main() : COLOR
{
    float s = 0;
    [loop] for (int i = 0; i < 8; i++)
    {
        if (s >= t) break;
        s += 0.125;
    }
    return s;
}
)";
  hlsl::CompileResult r = compile(src, "ps_3_0");
  ASSERT_TRUE(r.ok()) << r.messages();
  const shader::Instruction* br = find(r, Opcode::BreakC);
  ASSERT_NE(br, nullptr) << listing(r);
  EXPECT_EQ(br->comparison(), shader::Comparison::Ge);
  EXPECT_EQ(count(r, Opcode::Rep), 1);
  EXPECT_TRUE(std::regex_search(shader::disassemble(r.shader), std::regex(R"(rep i\d\n(.*\n)*break_ge r\d\.x, c0\.x\n)")))
      << shader::disassemble(r.shader);
}

// Profiles without the instructions: a warning (X3554) at the statement that names
// the profile, and the code is unrolled or flattened as without the attribute.
TEST(HlslFlowControl, ProfilesWithoutFlowControlWarnAndUnroll) {
  const char* ps = R"(
float4 main(float4 t : TEXCOORD0) : COLOR
{
    float4 r = 0;
    [loop] for (int i = 0; i < 2; i++) r += t;
    [branch] if (t.x > 0.5) r.y = 1;
    return r;
}
)";
  hlsl::CompileResult r = compile(ps, "ps_2_0");
  ASSERT_TRUE(r.ok()) << r.messages();
  EXPECT_EQ(count(r, Opcode::Rep) + count(r, Opcode::IfC), 0);
  int warnings = 0;
  for (const Diagnostic& d : r.diagnostics) {
    if (d.code != "X3554") continue;
    ++warnings;
    EXPECT_EQ(d.severity, Severity::Warning);
    EXPECT_NE(d.message.find("ps_2_0"), std::string::npos) << d.message;
  }
  EXPECT_EQ(warnings, 2) << r.messages();
  const Diagnostic* loop = diagnostic(r, "X3554");
  ASSERT_NE(loop, nullptr);
  EXPECT_EQ(loop->where.line, 5);
  EXPECT_EQ(loop->where.column, 12);

  const char* vs = R"(
void main(float4 p : POSITION, out float4 o : POSITION)
{
    o = p;
    [loop] for (int i = 0; i < 2; i++) o.x += 1;
    [branch] if (p.y > 0) o.y = 0;
}
)";
  hlsl::CompileResult v11 = compile(vs, "vs_1_1");
  ASSERT_TRUE(v11.ok()) << v11.messages();
  EXPECT_NE(diagnostic(v11, "X3554"), nullptr);
  // vs_2_0: rep, but no if_comp (the branch is flattened)
  hlsl::CompileResult v20 = compile(vs, "vs_2_0");
  ASSERT_TRUE(v20.ok()) << v20.messages();
  EXPECT_EQ(count(v20, Opcode::Rep), 1);
  EXPECT_EQ(count(v20, Opcode::IfC), 0);
  const Diagnostic* w = diagnostic(v20, "X3554");
  ASSERT_NE(w, nullptr) << v20.messages();
  EXPECT_NE(w->message.find("vs_2_0 has no if_comp"), std::string::npos) << w->message;
  EXPECT_EQ(w->where.line, 6);
}

// A [loop] that neither the profile can run nor the compiler can unroll: X3531 at the
// loop, naming the profile.
TEST(HlslFlowControl, LoopThatCannotUnrollIsAnErrorNamingTheProfile) {
  const char* src = R"(
float t;
float4 main() : COLOR
{
    float s = 0;
    [loop] while (s < t) s += 0.125;
    return s;
}
)";
  hlsl::CompileResult r = compile(src, "ps_2_0");
  EXPECT_FALSE(r.ok());
  const Diagnostic* d = diagnostic(r, "X3531");
  ASSERT_NE(d, nullptr) << r.messages();
  EXPECT_EQ(d->where.line, 6);
  EXPECT_EQ(d->where.column, 12);
  EXPECT_NE(d->message.find("ps_2_0"), std::string::npos) << d->message;
  // ps_3_0 runs it: rep 255 with a break_comp on the condition
  hlsl::CompileResult ok = compile(src, "ps_3_0");
  ASSERT_TRUE(ok.ok()) << ok.messages();
  EXPECT_EQ(count(ok, Opcode::BreakC), 1) << listing(ok);
  // vs_2_0 has rep but no break_comp
  hlsl::CompileResult vs = compile(R"(
float t;
void main(float4 p : POSITION, out float4 o : POSITION)
{
    o = p;
    [loop] while (o.x < t) o.x += 1;
}
)",
                                   "vs_2_0");
  const Diagnostic* e = diagnostic(vs, "X3531");
  ASSERT_NE(e, nullptr) << vs.messages();
  EXPECT_NE(e->message.find("vs_2_0"), std::string::npos) << e->message;
}

TEST(HlslFlowControl, RepCountsAtMost255) {
  hlsl::CompileResult r = compile(R"(
float4 main() : COLOR
{
    float s = 0;
    [loop] for (int i = 0; i < 300; i++) s += 0.001;
    return s;
}
)",
                                  "ps_3_0");
  const Diagnostic* d = diagnostic(r, "X3531");
  ASSERT_NE(d, nullptr) << r.messages();
  EXPECT_NE(d->message.find("255"), std::string::npos) << d->message;
}

TEST(HlslFlowControl, FlowUniformReadAsAValueIsAnError) {
  hlsl::CompileResult r = compile(R"(
int n;
float4 main() : COLOR
{
    float s = n * 0.5;
    [loop] for (int i = 0; i < n; i++) s += 0.1;
    return s;
}
)",
                                  "ps_3_0");
  const Diagnostic* d = diagnostic(r, "X4551");
  ASSERT_NE(d, nullptr) << r.messages();
  EXPECT_EQ(d->where.line, 2);
}

// vs_2_0 on the interpreter: rep i# from the application (n), rep with defi, if b#.
// k = (0.5, 0.25, 0.125, 0) in c0, n = 3 in i0, b = true in b0:
// acc = n * k = (1.5, 0.75, 0.375, 0); then w += 1 three times -> 3; b sets x = -1.
// t = (-1, 0.75, 0.375, 3). With b false and n = 0: (0, 0, 0, 3).
TEST(HlslFlowControl, Vs20RunsRepAndIfB) {
  const char* src = R"(
int n;
bool b;
float4 k;
void main(float4 p : POSITION, out float4 o : POSITION, out float4 t : TEXCOORD0)
{
    o = p;
    float4 acc = 0;
    [loop] for (int i = 0; i < n; i++) acc += k;
    [loop] for (int j = 0; j < 3; j++) acc.w += 1;
    [branch] if (b) acc.x = -1;
    t = acc;
}
)";
  hlsl::CompileResult r = compile(src, "vs_2_0");
  ASSERT_TRUE(r.ok()) << r.messages();
  EXPECT_EQ(count(r, Opcode::Rep), 2) << listing(r);
  EXPECT_EQ(count(r, Opcode::If), 1) << listing(r);
  // the listing places n in i0, b in b0, k in c0
  std::string text = listing(r);
  ASSERT_TRUE(std::regex_search(text, std::regex(R"(//   n +i0 +1\n)"))) << text;
  ASSERT_TRUE(std::regex_search(text, std::regex(R"(//   b +b0 +1\n)"))) << text;
  ASSERT_TRUE(std::regex_search(text, std::regex(R"(//   k +c0 +1\n)"))) << text;
  {
    probe::ShaderRun run(r.shader);
    run.constant(0, {0.5f, 0.25f, 0.125f, 0});
    run.ints[0] = {3, 0, 0, 0};
    run.bools[0] = true;
    run.execute();
    probe::expectNear(run.output(3), {-1, 0.75f, 0.375f, 3});
  }
  {
    probe::ShaderRun run(r.shader);
    run.constant(0, {0.5f, 0.25f, 0.125f, 0});
    run.ints[0] = {0, 0, 0, 0};
    run.bools[0] = false;
    run.execute();
    probe::expectNear(run.output(3), {0, 0, 0, 3});
  }
}

}  // namespace
}  // namespace refx
