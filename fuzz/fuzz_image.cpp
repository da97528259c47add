// Image file reader fuzz target: any bytes either load or give refx::Error.
#include <cstddef>
#include <cstdint>

#include "refx/core/diagnostics.h"
#include "refx/resource/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    refx::TexturePtr tex = refx::loadTextureFromMemory({data, size}, "fuzz");
    // Decode what was loaded: every face's first and last level.
    for (int f = 0; f < tex->faceCount(); ++f) {
      tex->sampleLevel(f, 0);
      tex->sampleLevel(f, tex->levelCount() - 1);
    }
  } catch (const refx::Error&) {
  }
  return 0;
}
