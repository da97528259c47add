// Shader assembler fuzz target: any text either assembles or gives refx::Error; what
// assembles encodes, decodes, and the decoded model encodes to the same tokens.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/shader/assembler.h"
#include "refx/shader/bytecode.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace refx::shader;
  Shader shader;
  try {
    shader = assemble(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.asm");
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
