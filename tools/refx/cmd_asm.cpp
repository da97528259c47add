// `refx asm FILE [-o OUT] [--listing] [--no-validate]`: shader assembly text
// (.vsh/.psh/.asm) → D3D9 tokens written as little-endian DWORDs (default OUT: FILE
// with the extension .vso for vertex and .pso for pixel shaders). The version rules
// are checked unless --no-validate; any error exits 1, printing every diagnostic of the
// file as `file:line:col: error A2001: …`.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "refx/core/diagnostics.h"
#include "refx/shader/assembler.h"
#include "refx/shader/disassembler.h"
#include "refx/shader/validator.h"

namespace refx::cli {

namespace {

struct AsmOptions {
  std::string input, output;
  bool listing = false;
  bool noValidate = false;
};

std::vector<uint8_t> littleEndianBytes(const std::vector<uint32_t>& tokens) {
  std::vector<uint8_t> bytes;
  bytes.reserve(tokens.size() * 4);
  for (uint32_t t : tokens)
    for (int i = 0; i < 4; ++i) bytes.push_back(uint8_t(t >> (8 * i)));
  return bytes;
}

int runAsm(const AsmOptions& o) {
  std::string text;
  {
    std::ifstream in(o.input, std::ios::binary);
    if (!in) {
      std::fprintf(stderr, "%s: error: cannot open the file for reading\n", o.input.c_str());
      return 1;
    }
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    if (in.bad()) {
      std::fprintf(stderr, "%s: error: read error\n", o.input.c_str());
      return 1;
    }
  }

  // Every error of the file, each with its code.
  DiagnosticSink diagnostics;
  shader::Shader sh = shader::assemble(text, o.input, diagnostics);
  for (const Diagnostic& d : diagnostics.all()) std::fprintf(stderr, "%s\n", d.str().c_str());
  if (diagnostics.hasErrors()) return 1;
  std::vector<uint32_t> tokens;
  try {
    tokens = shader::encode(sh);
  } catch (const Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }

  if (!o.noValidate) {
    DiagnosticSink diags;
    shader::validate(sh, diags, o.input);
    for (const Diagnostic& d : diags.all()) std::fprintf(stderr, "%s\n", d.str().c_str());
    if (diags.hasErrors()) return 1;
  }

  if (o.listing) {
    shader::DisassemblyOptions d;
    d.listing = true;
    std::fputs(shader::disassemble(tokens, d).c_str(), stdout);
  }

  std::string outPath = o.output;
  if (outPath.empty())
    outPath = std::filesystem::path(o.input).replace_extension(sh.version.isVertex() ? ".vso" : ".pso").string();
  const std::vector<uint8_t> bytes = littleEndianBytes(tokens);
  if (outPath == "-") {
    std::fwrite(bytes.data(), 1, bytes.size(), stdout);
    return 0;
  }
  std::ofstream out(outPath, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  out.close();
  if (!out) {
    std::fprintf(stderr, "%s: error: cannot write the file\n", outPath.c_str());
    return 1;
  }
  return 0;
}

}  // namespace

Action addAsmCommand(CLI::App& app) {
  auto o = std::make_shared<AsmOptions>();
  CLI::App* cmd = app.add_subcommand("asm", "Assemble shader text (.vsh/.psh) to D3D9 tokens (.vso/.pso)");
  cmd->add_option("file", o->input, "Shader assembly text (vs_1_1 … ps_3_0, vs.1.1/ps.1.4 spellings)")->required();
  cmd->add_option("-o,--output", o->output,
                  "Token file to write (default: FILE with extension .vso/.pso; '-' = standard output)");
  cmd->add_flag("--listing", o->listing, "Print the disassembly listing with instruction slots to standard output");
  cmd->add_flag("--no-validate", o->noValidate, "Skip the version rules (slot limits, register use, order)");
  return [o] { return runAsm(*o); };
}

}  // namespace refx::cli
