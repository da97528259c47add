// The compiler as one readable pipeline: preprocess, parse, build the IR (types,
// inlining, unrolling, flattening), optimise, generate code, check with the
// validator.
#include "refx/hlsl/compiler.h"

#include <fstream>
#include <sstream>

#include "hlsl/codegen_ps1x.h"
#include "hlsl/ir.h"
#include "hlsl/constant_table.h"
#include "hlsl/parser.h"
#include "hlsl/preprocessor.h"
#include "hlsl/preshader.h"
#include "refx/shader/validator.h"

namespace refx::hlsl {

using namespace detail;

namespace {

const char* kCreator = "refx HLSL compiler 0.1";

bool parseProfile(const std::string& p, shader::Version& v) {
  static const std::pair<const char*, shader::Version> profiles[] = {
      {"vs_1_1", {shader::ShaderType::Vertex, 1, 1}}, {"vs_2_0", {shader::ShaderType::Vertex, 2, 0}},
      {"vs_2_x", {shader::ShaderType::Vertex, 2, 1}}, {"vs_2_a", {shader::ShaderType::Vertex, 2, 1}},
      {"vs_3_0", {shader::ShaderType::Vertex, 3, 0}}, {"ps_1_1", {shader::ShaderType::Pixel, 1, 1}},
      {"ps_1_2", {shader::ShaderType::Pixel, 1, 2}}, {"ps_1_3", {shader::ShaderType::Pixel, 1, 3}},
      {"ps_1_4", {shader::ShaderType::Pixel, 1, 4}}, {"ps_2_0", {shader::ShaderType::Pixel, 2, 0}},
      {"ps_2_x", {shader::ShaderType::Pixel, 2, 1}}, {"ps_2_a", {shader::ShaderType::Pixel, 2, 1}},
      {"ps_2_b", {shader::ShaderType::Pixel, 2, 1}}, {"ps_3_0", {shader::ShaderType::Pixel, 3, 0}}};
  for (const auto& [name, ver] : profiles)
    if (p == name) { v = ver; return true; }
  return false;
}

// The preshader as the effect runs it: its inputs as a constant table of their own
// (the layout fxc gives a preshader), its outputs at the registers code generation chose.
Preshader finishPreshader(const IrProgram& ir, const PreshaderExtraction& pre, const shader::Version& version) {
  Preshader p;
  p.program = pre.program;
  ConstantTable table;
  table.creator = kCreator;
  table.target = version.name();
  table.versionToken = version.token();
  int next = 0;
  for (int u : pre.inputUniforms) {
    const IrUniform& uniform = ir.uniforms[size_t(u)];
    ConstantTable::Constant c;
    c.name = uniform.name;
    c.registerSet = ConstantTable::RegisterSet::Float4;
    c.registerIndex = next;
    c.registerCount = uniform.registerCount;
    c.type = uniform.type;
    c.defaultValue = uniform.defaults;
    next += uniform.registerCount;
    table.constants.push_back(std::move(c));
  }
  const std::vector<uint32_t> words = table.encode();
  if (auto decoded = shader::readConstantTable(std::span<const uint32_t>(words))) p.inputs = std::move(*decoded);
  for (int u : pre.outputUniforms) p.outputRegisters.push_back(ir.uniforms[size_t(u)].firstRegister);
  return p;
}

}  // namespace

std::string CompileResult::messages() const {
  std::string s;
  for (const Diagnostic& d : diagnostics) s += d.fxcStyle() + "\n";
  return s;
}

CompileResult compile(std::string_view source, std::string_view fileName, const CompileOptions& options) {
  CompileResult result;
  DiagnosticSink sink;
  const std::string file(fileName);
  shader::Version version;
  if (!parseProfile(options.profile, version)) {
    sink.error({file, 0, 0}, "X3501", "unknown profile '{}' (expected vs_1_1, vs_2_0, vs_2_x, vs_3_0, ps_1_1 … ps_1_4, "
               "ps_2_0, ps_2_x or ps_3_0)", options.profile);
    result.diagnostics = sink.all();
    return result;
  }
  PreprocessOptions pp;
  // The target, as dxc documents its predefined macros (__SHADER_TARGET_STAGE is one
  // of __SHADER_STAGE_PIXEL = 0 / __SHADER_STAGE_VERTEX = 1), then the user's /D.
  pp.defines = {{"__SHADER_STAGE_PIXEL", "0"},
                {"__SHADER_STAGE_VERTEX", "1"},
                {"__SHADER_TARGET_STAGE", version.isVertex() ? "1" : "0"},
                {"__SHADER_TARGET_MAJOR", std::to_string(version.major)},
                {"__SHADER_TARGET_MINOR", std::to_string(version.minor)}};
  pp.defines.insert(pp.defines.end(), options.defines.begin(), options.defines.end());
  pp.includeDirs = options.includeDirs;
  std::vector<Token> tokens = preprocess(source, fileName, pp, sink);

  ParseOptions po;
  po.compatibility = options.compatibility;
  po.rowMajorDefault = options.rowMajorDefault;
  Program program = parse(tokens, po, sink);

  std::vector<ExprPtr> argExprs;
  BuildOptions bo;
  bo.version = version;
  bo.entry = options.entry;
  bo.fileName = file;
  bo.rowMajorDefault = options.rowMajorDefault;
  bo.compatibility = options.compatibility;
  for (const std::string& a : options.entryArguments) {
    std::vector<Token> at = preprocess(a, "<argument>", pp, sink);
    argExprs.push_back(parseExpression(at, sink));
    if (argExprs.back()) bo.entryArguments.push_back(argExprs.back().get());
  }
  {
    // Type checking runs after syntax errors too, so one run reports every problem;
    // code is generated only for an error-free program.
    IrProgram ir = buildIr(program, bo, sink);
    if (!sink.hasErrors()) {
      // Optimisation passes, in order.
      propagateCopies(ir);
      foldConstants(ir);
      mergeDuplicates(ir);
      if (options.optimize) {
        fuseMultiplyAdd(ir);
        vectorizeScalars(ir);
      }
      removeDeadCode(ir);
      PreshaderExtraction pre;
      if (options.preshaders) {
        pre = extractPreshader(ir);
        removeDeadCode(ir);
      }
      SourceLocation entryWhere{file, 0, 0};
      for (const auto& f : program.functions)
        if (f->name == options.entry) entryWhere = f->where;
      shader::Shader sh = version.ps1x() ? generateCodePs1x(ir, kCreator, sink, entryWhere)
                                         : generateCode(ir, kCreator, sink, entryWhere);
      if (!sink.hasErrors()) {
        // Everything refx emits must pass refx's own validator for the profile.
        shader::SlotCount slots = shader::countSlots(sh);
        for (const Diagnostic& d : shader::validate(sh)) {
          if (shader::isLimitViolation(d.code))
            sink.error({file, d.where.line, d.where.column}, "X4532", "cannot map expression to {} instruction set: {}",
                       options.profile, d.message);
          else
            sink.error({file, d.where.line, d.where.column}, "X9000",
                       "internal error: generated code fails validation: {}", d.message);
        }
        if (!sink.hasErrors()) {
          result.shader = sh;
          result.tokens = shader::encode(sh);
          result.instructionSlots = slots.total();
          if (pre.program) result.preshader = finishPreshader(ir, pre, version);
        }
      }
    }
  }
  result.diagnostics = sink.all();
  return result;
}

CompileResult compileFile(const std::string& path, const CompileOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    CompileResult result;
    Diagnostic missing;
    missing.where = SourceLocation{path, 0, 0};
    missing.severity = Severity::Error;
    missing.code = "X1507";
    missing.message = "failed to open source file: " + path;
    result.diagnostics.push_back(std::move(missing));
    return result;
  }
  std::stringstream ss;
  ss << in.rdbuf();
  return compile(ss.str(), path, options);
}

}  // namespace refx::hlsl
