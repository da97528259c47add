// Shader assembler fuzz target: any text either assembles or gives refx::Error; what
// assembles encodes, decodes, and the decoded model encodes to the same tokens. The
// same text is also read as a DirectX 8 vertex shader declaration.
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
  Shader shader;
  try {
    shader = assemble(text, "fuzz.asm");
  } catch (const refx::Error&) {
    return 0;
  }
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
