// HLSL compiler fuzz target: the whole compile() (preprocessor, parser, type checking,
// IR passes, code generation, validation) on any text. The first byte picks the
// options, the rest is the source:
//   bits 0-1  vertex profile   vs_1_1 vs_2_0 vs_2_x vs_3_0
//   bits 2-3  pixel profile    ps_2_0 ps_2_x ps_3_0 ps_1_4 (refused: no ps_1_x back end)
//   bit 4     compatibility (the white paper's dialect, /Gec)
//   bit 5     row_major by default (/Zpr)
//   bit 6     optimisations off (/Od)
//   bit 7     entry point "PS"/"VS" instead of "main"
// The source is compiled for both profiles. Never a crash, a hang or a sanitizer report;
// a shader that compiles has tokens, passes the validator, and its disassembly
// assembles back to the same tokens (comments aside).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/hlsl/compiler.h"
#include "refx/shader/assembler.h"
#include "refx/shader/disassembler.h"
#include "refx/shader/validator.h"

namespace {

std::vector<uint32_t> withoutComments(const refx::shader::Shader& s) {
  refx::shader::Shader copy = s;
  std::erase_if(copy.instructions,
                [](const refx::shader::Instruction& i) { return i.opcode == refx::shader::Opcode::Comment; });
  return refx::shader::encode(copy);
}

void check(const refx::hlsl::CompileResult& r) {
  using namespace refx;
  bool error = false;
  for (const Diagnostic& d : r.diagnostics) error = error || d.severity == Severity::Error;
  if (r.ok() == error) std::abort();  // code exactly when there is no error
  if (!r.ok()) return;
  if (!shader::validate(r.shader).empty()) std::abort();
  if (shader::encode(shader::decode(r.tokens)) != r.tokens) std::abort();
  const std::string text = shader::disassemble(r.tokens);
  std::vector<uint32_t> again;
  try {
    again = shader::assembleTokens(text, "disassembly");
  } catch (const Error&) {
    std::abort();
  }
  if (again != withoutComments(r.shader)) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace refx;
  if (size == 0) return 0;
  static const char* vertex[] = {"vs_1_1", "vs_2_0", "vs_2_x", "vs_3_0"};
  static const char* pixel[] = {"ps_2_0", "ps_2_x", "ps_3_0", "ps_1_4"};
  const uint8_t select = data[0];
  const std::string_view source(reinterpret_cast<const char*>(data + 1), size - 1);
  hlsl::CompileOptions options;
  options.compatibility = select & 0x10;
  options.rowMajorDefault = select & 0x20;
  options.optimize = !(select & 0x40);
  options.defines = {{"FUZZ", "1"}};
  const bool namedEntries = select & 0x80;
  options.profile = vertex[select & 3];
  options.entry = namedEntries ? "VS" : "main";
  check(hlsl::compile(source, "fuzz.hlsl", options));
  options.profile = pixel[(select >> 2) & 3];
  options.entry = namedEntries ? "PS" : "main";
  check(hlsl::compile(source, "fuzz.hlsl", options));
  return 0;
}
