// `refx disasm FILE [-o OUT] [--listing]`: D3D9 shader tokens (.vso/.pso or any
// binary file of little-endian DWORDs) → assembly text that reassembles to the
// same tokens; --listing adds the fxc /Fc header (constant table) and slot count.
#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "refx/core/diagnostics.h"
#include "refx/shader/disassembler.h"

namespace refx::cli {

namespace {

struct DisasmOptions {
  std::string input, output;
  bool listing = false;
};

int runDisasm(const DisasmOptions& o) {
  std::string text;
  try {
    std::ifstream in(o.input, std::ios::binary);
    if (!in) fail("cannot open the file for reading");
    std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) fail("read error");
    shader::DisassemblyOptions d;
    d.listing = o.listing;
    text = shader::disassemble(shader::decode(shader::tokensFromBytes(bytes)), d);
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: error: %s\n", o.input.c_str(), e.what());
    return 1;
  }
  if (o.output.empty() || o.output == "-") {
    std::fputs(text.c_str(), stdout);
    return 0;
  }
  std::ofstream out(o.output, std::ios::binary);
  out << text;
  out.close();
  if (!out) {
    std::fprintf(stderr, "%s: error: cannot write the file\n", o.output.c_str());
    return 1;
  }
  return 0;
}

}  // namespace

Action addDisasmCommand(CLI::App& app) {
  auto o = std::make_shared<DisasmOptions>();
  CLI::App* cmd = app.add_subcommand("disasm", "Disassemble D3D9 shader tokens (.vso/.pso) to assembly text");
  cmd->add_option("file", o->input, "Binary shader token file")->required();
  cmd->add_option("-o,--output", o->output, "Write the text here instead of standard output");
  cmd->add_flag("--listing", o->listing, "fxc /Fc style listing: constant table and instruction slots");
  return [o] { return runDisasm(*o); };
}

}  // namespace refx::cli
