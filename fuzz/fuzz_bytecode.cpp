// Shader bytecode fuzz target: any bytes either decode or give refx::Error; a decoded
// shader re-encodes to tokens that decode to the same tokens, and the validator and
// the disassembler (plain and listing, which parses CTAB comments) accept it without
// crashing.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "refx/core/diagnostics.h"
#include "refx/shader/bytecode.h"
#include "refx/shader/disassembler.h"
#include "refx/shader/validator.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace refx::shader;
  std::vector<uint32_t> tokens = tokensFromBytes({data, size - size % 4});
  Shader shader;
  try {
    shader = decode(tokens);
  } catch (const refx::Error&) {
    return 0;
  }
  // Re-encoding is canonical: decode → encode is a fixed point after one pass.
  std::vector<uint32_t> once = encode(shader);
  if (encode(decode(once)) != once) __builtin_trap();
  (void)validate(shader);
  (void)countSlots(shader);
  (void)disassemble(shader);
  DisassemblyOptions listing;
  listing.listing = true;
  (void)disassemble(shader, listing);
  return 0;
}
