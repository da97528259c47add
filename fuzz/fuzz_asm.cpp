// Shader assembler fuzz target: any text either assembles or gives refx::Error; what
// assembles encodes, decodes, and the decoded model encodes to the same tokens. The
// diagnostics form agrees with the throwing one: errors exactly when it throws, each
// with an assembler code and a line, at most 100 and the stop notice. The same text is
// also read as a DirectX 8 vertex shader declaration.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/shader/assembler.h"
#include "refx/shader/bytecode.h"
#include "refx/shader/vs_declaration.h"

namespace {

void declaration(std::string_view text) {
  using namespace refx::shader;
  VsDeclaration decl;
  try {
    decl = parseVsDeclaration(text, "fuzz.decl");
  } catch (const refx::Error&) {
    return;
  }
  std::vector<uint32_t> tokens = encodeVsDeclaration(decl);
  if (encodeVsDeclaration(decodeVsDeclaration(tokens)) != tokens) std::abort();
  (void)vsdElements(decl);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace refx::shader;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  declaration(text);
  refx::DiagnosticSink diagnostics;
  (void)assemble(text, "fuzz.asm", diagnostics);
  if (diagnostics.all().size() > 101) std::abort();
  for (const refx::Diagnostic& d : diagnostics.all())
    if (d.code.size() != 5 || d.code[0] != 'A' || d.where.line < 1 || d.severity != refx::Severity::Error)
      std::abort();
  Shader shader;
  try {
    shader = assemble(text, "fuzz.asm");
  } catch (const refx::Error&) {
    if (!diagnostics.hasErrors()) std::abort();
    return 0;
  }
  if (diagnostics.hasErrors()) std::abort();
  std::vector<uint32_t> tokens;
  try {
    tokens = encode(shader);
  } catch (const refx::Error&) {
    std::abort();  // everything the assembler accepts must be encodable
  }
  // Tokens the encoder wrote must decode, and re-encode unchanged.
  Shader back;
  try {
    back = decode(tokens);
  } catch (const refx::Error&) {
    std::abort();
  }
  if (encode(back) != tokens) std::abort();
  return 0;
}
